/* SPDX-License-Identifier: MIT */
/*
 * sha256.h - SHA-256 (FIPS 180-4), for the scene's digest: the boards of a
 * lockstep run (play/lockstep) refuse to start unless every one of them
 * loaded the same bytes. A digest, not a checksum: two scene files that
 * differ by one key must not pass for one another by accident.
 */
#ifndef STRAND_SHA256_H
#define STRAND_SHA256_H

#include <stddef.h>
#include <stdint.h>

#define SHA256_BYTES 32

/* out = SHA-256 of the n bytes at p. */
void sha256(uint8_t out[SHA256_BYTES], const void *p, size_t n);

/* The first `bytes` of d as lowercase hex into s (2 * bytes + 1 chars). */
void sha256_hex(char *s, const uint8_t *d, size_t bytes);

#endif /* STRAND_SHA256_H */
