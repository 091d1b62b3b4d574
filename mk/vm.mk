# mk/vm.mk - tests in a small virtual machine: Debian's own kernel under
# qemu, with vcan and an out-of-tree gpio-sim module, because the build
# machine's kernel has neither CAN nor GPIO (tests/vm/README.md).
#
#   make test-vm       build everything the VM needs, boot it once, run every
#                      tests/vm/t_*.sh in it and report each by name
#                      VM_ONLY='t_a t_b' runs only those; VM_VERBOSE=1 shows
#                      the console as it runs
#   make check-vm      the step of `make test`: test-vm when qemu can run here,
#                      else one line saying why it is skipped (never under CI)
#   make vm-shell      the same VM with a shell on the console instead of tests
#
# The kernel is pinned to one version: the one Debian's linux-image-amd64
# depended on when the pin was last moved. The mirror keeps only the current
# one, so when the pin has gone stale tests/vm/fetch-kernel.sh takes the
# current kernel instead and prints a NOTE naming it: a Debian point release
# must not turn `make test` red. The downloads (~220 MB) and the module
# build are cached under $(VM_CACHE) and reused by the next run; moving the
# pin fetches again.
VM_KERNEL_ABI     := 6.1.0-57
VM_KERNEL_VERSION := 6.1.192-3

VM_CACHE   ?= $(BUILD)/vm-cache
VM_DIR     := $(BUILD)/vm
VM_KDIR    := $(VM_CACHE)/kernel
VM_SIMDIR  := $(VM_CACHE)/gpio-sim
VM_TIMEOUT ?= 300

# The kernel's kbuild tools are unpacked, not installed: their libraries
# (libelf1, libssl3) and compiler (gcc-12) are listed here instead.
DEB_VM += qemu-system-x86 busybox-static cpio xz-utils patch gcc-12 make libelf1 libssl3 \
          can-utils gpiod libgpiod-dev

# Modules from the kernel package, loaded with insmod in this order (the
# initramfs has no modules.dep); gpio-sim.ko, built here, comes last.
# VM_MODULE_PARAMS: NAME.ko:PARAM=VALUE, given to insmod. gpio-sim wires
# output 0 to input 8 and output 1 to input 9 of every chip (the trigger
# and rig-ready lines of tests/vm/t_gpio_*.sh, watched by gpiomon).
VM_MODULES += kernel/drivers/net/can/dev/can-dev.ko kernel/drivers/net/can/vcan.ko \
              kernel/net/can/can.ko kernel/net/can/can-raw.ko kernel/fs/configfs/configfs.ko
VM_MODULE_PARAMS += gpio-sim.ko:loopback=0,8,1,9

# What goes into the guest. Other mk files add to these: VM_BINS are copied
# to /bin with the shared libraries ldd names for them, VM_FILES are
# DEST=SRC pairs copied as they are, VM_TESTS are the scripts run in order,
# VM_AGAIN NAME@VARIANT the tests run once more with /VARIANT/bin first on
# PATH (mk/gpiod2.mk).
VM_HOST_BINS += /usr/bin/gpiodetect /usr/bin/gpioinfo /usr/bin/gpioget /usr/bin/gpioset \
                /usr/bin/gpiomon /usr/bin/gpiofind /usr/bin/candump /usr/bin/cansend
VM_BINS      += $(BUILD)/strand
VM_FILES     += /tests/lib.sh=tests/vm/lib.sh /tests/edges.awk=tests/vm/edges.awk \
                $(foreach f,$(wildcard tests/vm/scenes/*.yaml),/scenes/$(notdir $(f))=$(f))
VM_TESTS     += $(sort $(wildcard tests/vm/t_*.sh))

.PHONY: test-vm check-vm vm-shell vm-kernel vm-initramfs FORCE

$(BUILD)/.deps-vm: mk/deps.sh $(BUILD)/.deps-build
	$(Q)sh mk/deps.sh $(DEB_VM) && touch $@
deps: $(BUILD)/.deps-vm

# The kernel, its modules, headers and the three gpio-sim sources; fetched
# again when the pin moves (kernel.pin changes only then).
$(VM_CACHE)/kernel.pin: FORCE
	@mkdir -p $(@D)
	$(Q)echo '$(VM_KERNEL_ABI) $(VM_KERNEL_VERSION)' | cmp -s - $@ || \
		echo '$(VM_KERNEL_ABI) $(VM_KERNEL_VERSION)' >$@
$(VM_KDIR)/.done: tests/vm/fetch-kernel.sh $(VM_CACHE)/kernel.pin | $(BUILD)/.deps-vm
	$(Q)sh tests/vm/fetch-kernel.sh $(VM_KERNEL_ABI) $(VM_KERNEL_VERSION) $(VM_KDIR)
vm-kernel: $(VM_KDIR)/.done

VM_SIM_SRC := tests/vm/gpio-sim.Kbuild tests/vm/gpio-sim-loopback.patch
$(VM_SIMDIR)/gpio-sim.ko: $(VM_KDIR)/.done tests/vm/build-gpio-sim.sh $(VM_SIM_SRC)
	$(Q)sh tests/vm/build-gpio-sim.sh $(VM_KDIR) $(VM_SIMDIR) $(VM_SIM_SRC)

# Rebuilt when any input or the lists change; cheap (a few MB of cpio).
VM_LISTS := $(VM_MODULES) $(VM_MODULE_PARAMS) | $(VM_HOST_BINS) $(VM_BINS) | $(VM_FILES) | \
            $(VM_TESTS) | $(VM_AGAIN)
$(VM_DIR)/initrd.lists: FORCE
	@mkdir -p $(@D)
	$(Q)echo '$(VM_LISTS)' | cmp -s - $@ || echo '$(VM_LISTS)' >$@
$(VM_DIR)/initrd.cpio.gz: $(VM_DIR)/initrd.lists $(VM_KDIR)/.done $(VM_SIMDIR)/gpio-sim.ko tests/vm/mkinitramfs.sh \
		tests/vm/init.sh $(VM_TESTS) $(VM_BINS) $(foreach f,$(VM_FILES),$(lastword $(subst =, ,$(f)))) \
		| $(BUILD)/.deps-vm
	$(Q)VM_MODULES="$(addprefix $(VM_KDIR)/modules/,$(VM_MODULES)) \
		$(VM_SIMDIR)/gpio-sim.ko" VM_MODULE_PARAMS="$(VM_MODULE_PARAMS)" \
		VM_BINS="$(VM_HOST_BINS) $(VM_BINS)" VM_FILES="$(VM_FILES)" VM_TESTS="$(VM_TESTS)" \
		VM_AGAIN="$(VM_AGAIN)" \
		sh tests/vm/mkinitramfs.sh tests/vm/init.sh $@
vm-initramfs: $(VM_DIR)/initrd.cpio.gz

test-vm: $(VM_DIR)/initrd.cpio.gz
	$(Q)VM_TIMEOUT=$(VM_TIMEOUT) VM_ONLY="$(VM_ONLY)" VM_VERBOSE="$(VM_VERBOSE)" \
		sh tests/vm/run.sh $(VM_KDIR)/vmlinux $< $(VM_DIR)

vm-shell: $(VM_DIR)/initrd.cpio.gz
	$(Q)VM_SHELL=1 sh tests/vm/run.sh $(VM_KDIR)/vmlinux $< $(VM_DIR)

check-vm:
	$(Q)if why=$$(sh tests/vm/can-run.sh $(DEB_VM)); then $(MAKE) --no-print-directory test-vm; \
	elif [ -n "$$CI" ]; then echo "FAIL test-vm cannot run under CI: $$why"; exit 1; \
	else echo "SKIP test-vm: $$why"; fi

EXTRA_TEST_STEPS += check-vm
