# mk/modbus.mk - Modbus drives over libmodbus (hal/modbus/), the simulated
# drive behind a real Modbus server (sim/mb_server.c, strand-simdrive's
# Modbus mode), their tests against it and their benchmark.
#
#   make build/strand-simdrive   the simulated drive as a Modbus server
#   make bench-modbus            Modbus update rate against a bare libmodbus loop

DEB_BUILD += libmodbus-dev
DEB_TEST  += mbpoll

MODBUS_CFLAGS = $(shell pkg-config --cflags libmodbus 2>/dev/null)
FW_CFLAGS   += $(MODBUS_CFLAGS)
TEST_CFLAGS += $(MODBUS_CFLAGS)
FW_LIBS     += $(shell pkg-config --libs libmodbus 2>/dev/null || echo -lmodbus)
# the fuzz build compiles every library folder too (mk/scene.mk)
$(FUZZ_DIR)/fuzz_load: FUZZ_CFLAGS += $(MODBUS_CFLAGS)

# ---- strand-simdrive ----------------------------------------------------------
# The program (firmware/simdrive/) on the library folders: the scene
# loader, the rig for the device's simulated twin, sim/'s Modbus server.
SIMDRIVE_SRC := $(wildcard firmware/simdrive/*.c)
SIMDRIVE_OBJ := $(SIMDRIVE_SRC:%.c=$(BUILD)/%.o)

# (and of cli/ the helpers: scene errors, option numbers)
SIMDRIVE_CLI := $(BUILD)/firmware/cli/cli.o $(BUILD)/firmware/cli/opt.o
$(BUILD)/strand-simdrive: $(SIMDRIVE_OBJ) $(SIMDRIVE_CLI) $(LIB_OBJ) $(BUILD)/libmotion.a
	$(Q)$(CC) $^ $(FW_LIBS) -o $@

all: $(BUILD)/strand-simdrive
# the Modbus tests run it as their peer
unit: $(BUILD)/strand-simdrive

# ---- the benchmark --------------------------------------------------------------
# Modbus over loopback TCP: strand's update rate against a bare libmodbus
# client loop, and an RTU update's time at 115200 baud (bench/modbus_bench.c).
# A prerequisite of `make bench`, so it runs before the others, never beside.
.PHONY: bench-modbus
MODBUS_BENCH_OBJ := $(BUILD)/bench/bench/modbus_bench.o $(BUILD)/bench/tests/mbpeer.o \
                    $(BUILD)/hal/modbus/modbus_desc.o $(BUILD)/hal/modbus/modbus_map.o

$(BUILD)/bench/bench/modbus_bench.o $(BUILD)/bench/tests/mbpeer.o: \
	MB_CFLAGS += $(MODBUS_CFLAGS)
$(BUILD)/bench/modbus_bench: $(MODBUS_BENCH_OBJ)
	$(Q)$(CC) $^ $(FW_LIBS) -o $@

bench-modbus: $(BUILD)/bench/modbus_bench $(BUILD)/strand $(BUILD)/strand-simdrive
	$(Q)STRAND_SIMDRIVE=$(BUILD)/strand-simdrive $(BUILD)/bench/modbus_bench $(BUILD)/strand

bench: bench-modbus
unit: export STRAND_SIMDRIVE = $(BUILD)/strand-simdrive
