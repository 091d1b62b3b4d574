# mk/import.mk - `strand import`'s own targets.
#
#   make blender-fixtures   regenerate tests/import/blender/ with Blender's own
#                           glTF exporter (tools/blender_fixtures.py): the glTF
#                           files, sampled and keyed, and Blender's own world
#                           positions at every frame. Not a step of `make
#                           test`: installing Blender (165 MB with numpy) and
#                           running it took 44 s here (more on a fresh machine), so
#                           the generated files are committed and test_import_gltf
#                           compares against them.
#   make fuzz-import        libFuzzer on the glTF, URDF and table readers for
#                           FUZZ_SECONDS (default 300) each; fuzz-import-short, a
#                           step of `make test`, 6 s each (the table's 3 s)

.PHONY: blender-fixtures fuzz-import fuzz-import-short

DEB_BLENDER := blender python3-numpy
DEB_IMPORT_TEST := liburdfdom-tools

EXTRA_TEST_STEPS += fuzz-import-short

$(BUILD)/.deps-blender: mk/deps.sh
	$(Q)mkdir -p $(BUILD) && sh mk/deps.sh $(DEB_BLENDER) && touch $@
$(BUILD)/.deps-import-test: mk/deps.sh $(BUILD)/.deps-test
	$(Q)sh mk/deps.sh $(DEB_IMPORT_TEST) && touch $@
deps: $(BUILD)/.deps-import-test

# check_urdf is the URDF tests' peer
$(BUILD)/san/tests/import/test_import_urdf.o: | $(BUILD)/.deps-import-test

blender-fixtures: $(BUILD)/.deps-blender
	$(Q)blender -b --factory-startup -P tools/blender_fixtures.py -- tests/import/blender \
		> $(BUILD)/blender-fixtures.log 2>&1 || \
		{ tail -n 30 $(BUILD)/blender-fixtures.log; exit 1; }
	@echo "BLENDER $$(blender --version | head -n 1): tests/import/blender/ written"

# ---- libFuzzer on the readers ---------------------------------------------------------
FUZZ_IMPORT_SECONDS ?= 6
FUZZ_IMPORT_CSV_SECONDS ?= 3
IMPORT_SRC := $(wildcard firmware/import/*.c)
FUZZ_IMPORT_CFLAGS = $(FUZZ_CFLAGS) $(shell pkg-config --cflags jansson expat)

# the readers compiled once for libFuzzer, then one program per reader from
# tests/fuzz/fuzz_import.c
IMPORT_FUZZ_OBJ := $(IMPORT_SRC:%.c=$(FUZZ_DIR)/obj/%.o)

$(FUZZ_DIR)/obj/%.o: %.c $(wildcard firmware/import/*.h) | $(BUILD)/.deps-fuzz
	@mkdir -p $(@D)
	$(Q)clang $(FUZZ_IMPORT_CFLAGS) -c $< -o $@

$(FUZZ_DIR)/fuzz_gltf $(FUZZ_DIR)/fuzz_urdf $(FUZZ_DIR)/fuzz_csv: \
		$(FUZZ_DIR)/fuzz_%: tests/fuzz/fuzz_import.c $(IMPORT_FUZZ_OBJ) | \
		$(BUILD)/.deps-fuzz
	$(Q)clang $(FUZZ_IMPORT_CFLAGS) -DFUZZ_READER=imp_$* $< $(IMPORT_FUZZ_OBJ) \
		$(shell pkg-config --libs jansson expat) -lm -o $@

# seeds: the Blender files and the URDF test robots
$(FUZZ_DIR)/seed-gltf: $(wildcard tests/import/blender/*.gl*)
	$(Q)rm -rf $@ && mkdir -p $@ && cp tests/import/blender/*.gl* $@/
$(FUZZ_DIR)/seed-urdf: $(wildcard tests/import/urdf/*.urdf)
	$(Q)rm -rf $@ && mkdir -p $@ && cp tests/import/urdf/*.urdf $@/
$(FUZZ_DIR)/seed-csv: $(wildcard tests/import/csv/*.csv)
	$(Q)rm -rf $@ && mkdir -p $@ && cp tests/import/csv/*.csv $@/

FUZZ_IMPORT_DEPS := $(FUZZ_DIR)/fuzz_gltf $(FUZZ_DIR)/fuzz_urdf \
                    $(FUZZ_DIR)/fuzz_csv $(FUZZ_DIR)/seed-gltf \
                    $(FUZZ_DIR)/seed-urdf $(FUZZ_DIR)/seed-csv

TEST_PREBUILD += $(FUZZ_DIR)/fuzz_gltf $(FUZZ_DIR)/fuzz_urdf $(FUZZ_DIR)/fuzz_csv

fuzz-import: $(FUZZ_IMPORT_DEPS)
	$(call fuzz_run,gltf,$(FUZZ_DIR)/seed-gltf,65536,$(FUZZ_SECONDS))
	$(call fuzz_run,urdf,$(FUZZ_DIR)/seed-urdf,65536,$(FUZZ_SECONDS))
	$(call fuzz_run,csv,$(FUZZ_DIR)/seed-csv,65536,$(FUZZ_SECONDS))

fuzz-import-short: $(FUZZ_IMPORT_DEPS)
	$(call fuzz_run,gltf,$(FUZZ_DIR)/seed-gltf,65536,$(FUZZ_IMPORT_SECONDS))
	$(call fuzz_run,urdf,$(FUZZ_DIR)/seed-urdf,65536,$(FUZZ_IMPORT_SECONDS))
	$(call fuzz_run,csv,$(FUZZ_DIR)/seed-csv,65536,$(FUZZ_IMPORT_CSV_SECONDS))

fuzz: fuzz-import
