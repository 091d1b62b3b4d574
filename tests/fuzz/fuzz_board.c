/* SPDX-License-Identifier: MIT */
/*
 * fuzz_board.c - libFuzzer on what a board of a lockstep run reads from
 * others (mk/boards.mk): the first byte picks the parser, the rest is its
 * input. 0: a datagram (lockstep/ls_msg.h), which must decode to a message
 * that encodes back to the same bytes, or be refused; 1: pmc's answer
 * (lockstep/ls_ptp.h), whose state must be a string within its field.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "lockstep/ls_msg.h"
#include "lockstep/ls_ptp.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	if (size < 1)
		return 0;
	if (data[0] == 0) {
		struct ls_msg m;
		uint8_t back[LS_MSG_MAX];
		size_t n;

		if (ls_msg_decode(&m, data + 1, size - 1, 3) == 0) {
			n = ls_msg_encode(&m, back, sizeof(back));
			if (n != size - 1 || memcmp(back, data + 1, n))
				abort(); /* what decodes, encodes back the same */
		}
	} else {
		struct ls_ptp st;
		char why[256];

		if (ls_ptp_parse(&st, (const char *)data + 1, size - 1) == 0) {
			if (strnlen(st.state, sizeof(st.state)) == sizeof(st.state))
				abort();
			ls_ptp_locked(&st, 100000, data[0] & 2, why, sizeof(why));
		}
	}
	return 0;
}
