/* SPDX-License-Identifier: MIT */
/* exitcode.h - the exit codes of the strand program (README "Exit codes"). */
#ifndef STRAND_EXITCODE_H
#define STRAND_EXITCODE_H

enum strand_exit {
	STRAND_EXIT_OK = 0,        /* success */
	STRAND_EXIT_VIOLATION = 1, /* check: the timeline breaks a limit */
	STRAND_EXIT_SCENE = 2,     /* the scene file is invalid */
	STRAND_EXIT_USAGE = 3,     /* bad command line */
	STRAND_EXIT_IO = 4,        /* a file could not be read or written */
	STRAND_EXIT_STOPPED = 5,   /* play: stopped by SIGINT/SIGTERM (controlled stop) */
	STRAND_EXIT_ESTOP = 6,     /* play: e-stop input */
	STRAND_EXIT_FAULT = 7,     /* play: device fault or following error */
	STRAND_EXIT_INTERNAL = 8,  /* arithmetic saturated or another internal error */
};

#endif /* STRAND_EXITCODE_H */
