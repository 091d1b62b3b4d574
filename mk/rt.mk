# mk/rt.mk - the real-time boundary (hal/rt.h, mk/check-rt.sh,
# mk/check-rt.list).
#
#   make check-rt   a step of `make test`: the self-test on tests/rt/ (a good
#                   file passes; each bad one is refused for its own
#                   reason; objects without an rt function are refused),
#                   then every library object of the build, as the
#                   program links them (-O2) and as the tests do
#                   (sanitized, -O1: less is inlined, so more of the
#                   tagged inlines of the headers are kept as copies)
#
# The objects are the build's own lists, LIB_OBJ and FW_SAN_OBJ, and the
# libgpiod archive: a file of a library folder that gets STRAND_RT
# functions is checked with nothing changed here. The motion core is
# trusted (make check-freestanding proves it libc-free).

.PHONY: check-rt
EXTRA_TEST_STEPS += check-rt

RT_SELFTEST := $(BUILD)/rt-selftest
# the core's header inlines, wherever the compiler keeps a copy of one
RT_TRUST    := $(foreach h,$(MOTION_HDR),-H $(h))
RT_BAD := allocator:bad_malloc \
          stdio:bad_printf \
          'a lock':bad_mutex \
          'may sleep':bad_sleep \
          'rt_test_untagged, a function of the project that is not STRAND_RT':bad_untagged+good \
          'untagged_helper, a function of the project that is not STRAND_RT':bad_static \
          'no function in .text.strand_rt':bad_none
# WHY:FILE[+OTHER]: the check refuses FILE.o (with OTHER.o: bad_untagged.c
# calls into good.c) with a message containing WHY.
RT_SELFTEST_SRC := $(wildcard tests/rt/*.c)
RT_SELFTEST_OBJ := $(RT_SELFTEST_SRC:tests/rt/%.c=$(RT_SELFTEST)/%.o)

# As a file of a library folder is built (the root as its include root,
# for "hal/rt.h" and "motion/fix.h").
$(RT_SELFTEST)/%.o: tests/rt/%.c hal/rt.h | $(BUILD)/.deps-build
	@mkdir -p $(@D)
	$(Q)$(CC) $(FW_CFLAGS) -iquote . $(OPT) -c $< -o $@

check-rt: $(RT_SELFTEST_OBJ) $(LIB_OBJ) $(FW_SAN_OBJ) $(GPIOD_LIB) $(BUILD)/libmotion.a \
		$(BUILD)/san/libmotion.a mk/check-rt.sh mk/check-rt.list $(MOTION_HDR)
	$(Q)sh mk/check-rt.sh $(RT_TRUST) objdump $(BUILD)/libmotion.a $(RT_SELFTEST)/good.o \
		>$(RT_SELFTEST)/good.log 2>&1 || \
		{ echo "check-rt: self-test: good.c is refused:"; cat $(RT_SELFTEST)/good.log; exit 1; }
	@echo "check-rt: self-test: good.c: accepted"
	$(Q)if sh mk/check-rt.sh objdump $(BUILD)/libmotion.a $(RT_SELFTEST)/good.o \
			>$(RT_SELFTEST)/good-nohdr.log 2>&1 || \
		! grep -q 'mot_add_sat, a function of the project that is not' $(RT_SELFTEST)/good-nohdr.log; then \
		echo "check-rt: self-test: good.c passed without the core's headers (-H); it must not"; \
		cat $(RT_SELFTEST)/good-nohdr.log; exit 1; fi
	@echo "check-rt: self-test: good.c without the core's headers: refused (mot_add_sat, its copy of an inline)"
	$(Q)for t in $(RT_BAD); do \
		why=$${t%%:*}; f=$${t#*:}; other=; \
		case $$f in *+*) other=$(RT_SELFTEST)/$${f#*+}.o; f=$${f%%+*};; esac; \
		log=$(RT_SELFTEST)/$$f.log; \
		if sh mk/check-rt.sh $(RT_TRUST) objdump $(BUILD)/libmotion.a $(RT_SELFTEST)/$$f.o $$other \
				>$$log 2>&1; then \
			echo "check-rt: self-test: $$f.c passed; it must not"; cat $$log; exit 1; \
		elif ! grep -q -- "$$why" $$log; then \
			echo "check-rt: self-test: $$f.c refused, but not for '$$why':"; cat $$log; exit 1; \
		fi; \
		echo "check-rt: self-test: $$f.c: refused ($$(grep -m1 -- "$$why" $$log | \
			sed 's/^check-rt: [^ :]*\.o: //'))"; \
	done
	@# both, whatever the first finds, so that one run reports everything
	$(Q)st=0; \
	sh mk/check-rt.sh $(RT_TRUST) objdump $(BUILD)/libmotion.a $(LIB_OBJ) $(GPIOD_LIB) \
		>$(RT_SELFTEST)/release.log 2>&1 || st=1; \
	sh mk/check-rt.sh $(RT_TRUST) objdump $(BUILD)/san/libmotion.a $(FW_SAN_OBJ) $(GPIOD_LIB) \
		>$(RT_SELFTEST)/san.log 2>&1 || st=1; \
	sed 's/^check-rt:/check-rt: release (-O2):/' $(RT_SELFTEST)/release.log; \
	sed 's/^check-rt:/check-rt: sanitized (-O1):/' $(RT_SELFTEST)/san.log; \
	exit $$st
	@echo "RT ok: $$(sed -n 's/^check-rt: \([0-9]*\) object(s), \([0-9]*\) rt function(s) in \([0-9]*\) .*/\2 rt functions (in \3 of \1 objects)/p' \
		$(RT_SELFTEST)/release.log) reach no allocator, stdio, lock or sleeping call," \
		"nor untagged code; the sanitized build's too; self-test passed"
