# mk/canopen.mk - the CANopen master (hal/canopen/): built like hal/ (the
# pattern rules of mk/play.mk cover the sub-folder), into the program and
# the tests' archive.

CO_SRC := $(wildcard hal/canopen/*.c)
CO_HDR := $(wildcard hal/canopen/*.h)
CO_OBJ := $(CO_SRC:%.c=$(BUILD)/%.o)
CO_SAN_OBJ := $(CO_SRC:%.c=$(BUILD)/san/%.o)

$(BUILD)/san/libfw.a: $(CO_SAN_OBJ)
$(BUILD)/strand: $(CO_OBJ)
# strand-simdrive (mk/modbus.mk) links the program's objects, and plays a
# CiA 402 drive itself with --can
$(BUILD)/strand-simdrive: $(CO_OBJ)

# Everything that may include the master's headers: its own objects, the
# simulated drive in sim/, the rig and loader in firmware/, the tests.
CO_USERS := $(CO_OBJ) $(CO_SAN_OBJ) \
	$(patsubst %.c,$(BUILD)/%.o,$(wildcard sim/*.c sim/simdrive/*.c firmware/*.c)) \
	$(patsubst %.c,$(BUILD)/san/%.o,$(wildcard sim/*.c firmware/*.c tests/*.c))
$(CO_USERS): $(CO_HDR)

# ---- the VM tests (mk/vm.mk) ------------------------------------------------------
# strand drives strand-simdrive processes on vcan0, candump records the bus.
VM_BINS  += $(BUILD)/strand-simdrive
VM_FILES += /tests/can.awk=tests/vm/can.awk /tests/can.sh=tests/vm/can.sh
