# mk/layers.mk - the rooms' walls (mk/layers.txt, mk/layers.sh).
#
#   make check-layers   a step of `make test`: the self-test on the small
#                       tree of tests/layers/ (a good tree passes; each bad
#                       file is refused for its own reason, by the check
#                       and, for an include that points up, by the
#                       compiler in its view; a table with a cycle is
#                       refused), then every include of every folder
#                       against the table

.PHONY: check-layers


LT := tests/layers
# EXPECT FOLDER FILE [TABLE ROOTS]: the check refuses FILE as a file of
# FOLDER with a message containing EXPECT (by default in the small tree)
define layers_refuses
	$(Q)if out=$$(sh mk/layers.sh check $(or $(4),$(LT)/table $(LT)/rooms) $(2)=$(3) 2>&1); then \
		echo "check-layers: self-test: $(3) passed as $(2); it must not"; exit 1; \
	elif ! printf '%s\n' "$$out" | grep -q -- '$(1)'; then \
		echo "check-layers: self-test: $(3) refused, but not for '$(1)':"; \
		printf '%s\n' "$$out"; exit 1; \
	else echo "check-layers: self-test: $(3) as $(2): refused ($(1))"; fi
endef

check-layers: | $(BUILD)/.deps-build
	$(Q)sh mk/layers.sh check $(LT)/table $(LT)/rooms >/dev/null || \
		{ echo "check-layers: self-test: the good tree is refused"; exit 1; }
	$(call layers_refuses,low may not include \"high/high.h\",low,$(LT)/bad/up.c)
	$(call layers_refuses,high may not include \"low/low.h\",high,$(LT)/bad/skip.c)
	$(call layers_refuses,a bare name is a sibling,mid,$(LT)/bad/sibling.c)
	$(call layers_refuses,motion may not include <float.h>,motion,tests/freestanding/bad_include.c,\
		mk/layers.txt ". firmware")
	$(Q)if sh mk/layers.sh check $(LT)/cycle.table $(LT)/rooms >/dev/null 2>&1; then \
		echo "check-layers: self-test: a table with a cycle passed"; exit 1; fi
	$(Q)rm -rf $(BUILD)/layers-selftest && \
		sh mk/layers.sh views $(LT)/table $(LT)/rooms $(BUILD)/layers-selftest >/dev/null
	$(Q)$(CC) -c -iquote $(BUILD)/layers-selftest/mid $(LT)/rooms/mid/mid.c -o /dev/null || \
		{ echo "check-layers: self-test: a good file does not compile in its view"; exit 1; }
	$(Q)if $(CC) -c -iquote $(BUILD)/layers-selftest/low $(LT)/bad/up.c -o /dev/null 2>/dev/null; \
		then echo "check-layers: self-test: an upward include compiles in its view"; exit 1; fi
	@echo "check-layers: self-test: an upward include does not compile in its folder's view"
	$(Q)sh mk/layers.sh check mk/layers.txt ". firmware"
	@echo "LAYERS ok: $(words $(LAYERS)) folders, every include as mk/layers.txt allows, self-test passed"
