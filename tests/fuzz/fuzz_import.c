/* SPDX-License-Identifier: MIT */
/*
 * fuzz_import.c - libFuzzer on one of strand import's readers and the scene
 * file it writes (mk/import.mk builds it once per reader: FUZZ_READER is
 * imp_gltf, imp_urdf or imp_csv): any input gives a model or one error, never a
 * crash, a leak or a read outside the input. Relative buffer files resolve
 * under a directory that does not exist.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "import/imp.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct imp_opts o = { 24, 1, 1008, NULL, IMP_LINEAR };
	struct imp_model m = { 0 };
	char err[512], *text = NULL;
	size_t len = 0;
	FILE *out;

	if (FUZZ_READER(&m, "/nonexistent-strand-fuzz/input", data, size, &o, NULL, err,
			sizeof(err)) == 0 && (out = open_memstream(&text, &len))) {
		imp_yaml_write(out, &m, IMP_YAML_ALL);
		fclose(out);
		free(text);
	}
	imp_model_free(&m);
	return 0;
}
