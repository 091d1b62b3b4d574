# mk/modbus.mk - Modbus drives over libmodbus (hal/modbus_*.c), the simulated
# drive behind a real Modbus server (strand-simdrive, sim/simdrive/), their
# tests against it and their benchmark.
#
#   make build/strand-simdrive   the simulated drive as a Modbus server
#   make bench-modbus            Modbus update rate against a bare libmodbus loop

DEB_BUILD += libmodbus-dev
DEB_TEST  += mbpoll

MODBUS_CFLAGS = $(shell pkg-config --cflags libmodbus 2>/dev/null)
FW_CFLAGS   += $(MODBUS_CFLAGS)
TEST_CFLAGS += $(MODBUS_CFLAGS)
FW_LIBS     += $(shell pkg-config --libs libmodbus 2>/dev/null || echo -lmodbus)
# the fuzz build compiles hal/*.c too (mk/scene.mk)
$(BUILD)/fuzz/fuzz_load: FUZZ_CFLAGS += $(MODBUS_CFLAGS)

# ---- strand-simdrive ----------------------------------------------------------
# Its own sources and the program's objects (the scene loader, the rig, the
# simulated drive), at -O2 like the program.
SIMDRIVE_SRC := $(wildcard sim/simdrive/*.c)
SIMDRIVE_HDR := $(wildcard sim/simdrive/*.h)
SIMDRIVE_OBJ := $(SIMDRIVE_SRC:%.c=$(BUILD)/%.o)
# mk/play.mk's lists, which are not defined yet when this file is read
SIMDRIVE_LINK := $(patsubst %.c,$(BUILD)/%.o,$(filter-out firmware/main.c,$(wildcard \
                 firmware/*.c)) $(wildcard hal/*.c sim/*.c)) $(BUILD)/libmotion.a

$(BUILD)/sim/simdrive/%.o: sim/simdrive/%.c $(SIMDRIVE_HDR) $(MOTION_HDR) $(FW_HDR) \
		$(wildcard hal/*.h sim/*.h) | $(BUILD)/.deps-build
	@mkdir -p $(@D)
	$(Q)$(CC) $(FW_CFLAGS) -Isim/simdrive $(OPT) -g -c $< -o $@

$(BUILD)/strand-simdrive: $(SIMDRIVE_OBJ) $(SIMDRIVE_LINK)
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
                    $(BUILD)/hal/modbus_desc.o $(BUILD)/hal/modbus_map.o

$(BUILD)/bench/bench/modbus_bench.o $(BUILD)/bench/tests/mbpeer.o: \
	MB_CFLAGS += -Ihal $(MODBUS_CFLAGS)
$(BUILD)/bench/modbus_bench: $(MODBUS_BENCH_OBJ)
	$(Q)$(CC) $^ $(FW_LIBS) -o $@

bench-modbus: $(BUILD)/bench/modbus_bench $(BUILD)/strand $(BUILD)/strand-simdrive
	$(Q)STRAND_SIMDRIVE=$(BUILD)/strand-simdrive $(BUILD)/bench/modbus_bench $(BUILD)/strand

bench: bench-modbus
unit: export STRAND_SIMDRIVE = $(BUILD)/strand-simdrive
