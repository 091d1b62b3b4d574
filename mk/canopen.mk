# mk/canopen.mk - the CANopen master (hal/canopen/) builds with every other
# library folder (the Makefile finds it in mk/layers); what is its own here
# is the benchmark and what the VM tests need.

CO_SRC := $(wildcard hal/canopen/*.c)
CO_OBJ := $(CO_SRC:%.c=$(BUILD)/%.o)

# ---- the VM tests (mk/vm.mk) ------------------------------------------------------
# strand drives strand-simdrive processes on vcan0, candump records the bus.
VM_BINS  += $(BUILD)/strand-simdrive
VM_FILES += /tests/can.awk=tests/vm/can.awk /tests/can.sh=tests/vm/can.sh \
            /examples/canopen_turntable.yaml=examples/canopen_turntable.yaml

# ---- make bench-canopen (part of make bench) ---------------------------------------
# The master's CPU time per tick for 8 drives on this machine (bench/
# canopen_bench.c: the protocol and the HAL backend, the bus replayed), then
# the SYNC period in the test VM: tests/vm/t_can_play.sh over the scene five
# times, as candump and as a drive (strand-simdrive) see it. Under qemu's
# software emulation these bound what the harness sees, not what a board
# does (README "CANopen").
.PHONY: bench-canopen
bench: bench-canopen
CO_BENCH_LINK := $(BUILD)/sim/co_simbus.o $(BUILD)/sim/co_slave.o $(BUILD)/sim/co_slave_od.o \
                 $(BUILD)/sim/sim_drive.o $(BUILD)/hal/clock.o
$(BUILD)/bench/canopen_bench: bench/canopen_bench.c $(CO_OBJ) $(CO_BENCH_LINK)
	@mkdir -p $(@D)
	$(Q)$(CC) $(BENCH_CFLAGS) -iquote . $(DEPFLAGS) $< $(CO_OBJ) $(CO_BENCH_LINK) -lm -o $@
bench-canopen: $(BUILD)/bench/canopen_bench $(BUILD)/vm/initrd.cpio.gz
	$(Q)$(BUILD)/bench/canopen_bench
	$(Q)VM_ONLY=t_can_play VM_APPEND="strand.bench_passes=5" \
		sh tests/vm/run.sh $(VM_KDIR)/vmlinux \
		$(BUILD)/vm/initrd.cpio.gz $(BUILD)/bench-canopen >$(BUILD)/bench-canopen.log 2>&1 || \
		{ cat $(BUILD)/bench-canopen.log; exit 1; }
	$(Q)echo "bench-canopen: the SYNC on vcan0 in the VM ($$(sed -n \
		's/^vm: booting [^ ]* (\([A-Z]*\)).*/\1/p' $(BUILD)/bench-canopen.log)), 250 Hz," \
		"3 drives; jitter = |SYNC interval - 4 ms|"
	$(Q)grep -h '^BENCH can_' $(BUILD)/bench-canopen/console.log
