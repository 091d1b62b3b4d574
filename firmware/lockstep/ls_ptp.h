/* SPDX-License-Identifier: MIT */
/*
 * ls_ptp.h - is this board's clock locked to the others'? Asked of ptp4l
 * through its management socket with linuxptp's own client, pmc:
 *
 *     pmc -u -b 0 -s SOCKET 'GET PORT_DATA_SET' 'GET TIME_STATUS_NP'
 *
 * PORT_DATA_SET gives the port's state, TIME_STATUS_NP the offset from the
 * grandmaster and whether one is present. Locked means: the port is a
 * SLAVE whose offset is within the bound, or MASTER (or GRAND_MASTER):
 * this board's clock is the one the others follow. A port in any other
 * state (LISTENING: no master heard; UNCALIBRATED: the servo has not locked
 * yet; FAULTY, ...) is not locked. With free_running (ptp4l's own option,
 * for boards that share one clock, as in the namespace tests: ptp4l
 * measures but never steers, and its port stays UNCALIBRATED), an
 * UNCALIBRATED port whose offset is within the bound counts as locked.
 *
 * [init]: runs a program.
 */
#ifndef STRAND_LS_PTP_H
#define STRAND_LS_PTP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct ls_ptp {
	bool answered;          /* pmc's answer had a port state */
	char state[24];         /* SLAVE, MASTER, LISTENING, ... */
	bool has_offset;
	int64_t offset_ns;      /* master_offset */
	bool gm_present;
};

/* pmc's output (len bytes of text) into st: 0, or -EBADMSG when it holds
 * no port state. Fuzzed, as every parser. */
int ls_ptp_parse(struct ls_ptp *st, const char *text, size_t len);

/* Ask ptp4l at socket (its uds_address) through pmc: 0 and st, or a
 * negative errno with err (pmc missing, no answer). */
int ls_ptp_query(struct ls_ptp *st, const char *socket, char *err, size_t errsize);

/* Locked by the rules above (bound: the offset allowed, ns)? If not, why in
 * why. */
bool ls_ptp_locked(const struct ls_ptp *st, double bound_ns, bool free_running, char *why,
		   size_t size);

#endif /* STRAND_LS_PTP_H */
