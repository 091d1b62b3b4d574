/* SPDX-License-Identifier: MIT */
/*
 * dfm_run.h - a DFMoco session on its port: lines in, the session's round
 * every few milliseconds, replies out, until asked to stop.
 */
#ifndef STRAND_DFM_RUN_H
#define STRAND_DFM_RUN_H

#include <signal.h>
#include <stdio.h>

#include "dfm_port.h"
#include "dfm_session.h"

/* [init] Serve s on p until *stop (a signal handler's flag, or another
 * thread's) or the live session is finished. A client that joins a TCP
 * port starts with no half line and no old replies. 0, or the port's
 * error (a negative errno), said on err. */
int dfm_run(struct dfm_session *s, struct dfm_port *p, const volatile sig_atomic_t *stop,
	    FILE *err);

#endif /* STRAND_DFM_RUN_H */
