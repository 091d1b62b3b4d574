/* SPDX-License-Identifier: MIT */
/* ls_ptp.c - ptp4l's state through pmc (see ls_ptp.h). */
#define _GNU_SOURCE
#include "ls_ptp.h"

#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "hal/clock.h"
#include "hal/rt.h"

/* How long pmc may take to answer before it is given up. */
#define LS_PMC_TIMEOUT_MS 3000
/* The most of pmc's output read. */
#define LS_PMC_OUT 8192

/* The value after `key` on a line of its own ("\t\tportState   SLAVE"), up
 * to the end of the line, into v (size bytes): true if found. */
static bool field(const char *text, size_t len, const char *key, char *v, size_t size)
{
	size_t klen = strlen(key), i = 0;

	while (i < len) {
		size_t end = i, j, k = 0;

		while (end < len && text[end] != '\n')
			end++;
		j = i;
		while (j < end && (text[j] == ' ' || text[j] == '\t'))
			j++;
		if (end - j > klen && !memcmp(text + j, key, klen) &&
		    (text[j + klen] == ' ' || text[j + klen] == '\t')) {
			j += klen;
			while (j < end && (text[j] == ' ' || text[j] == '\t'))
				j++;
			while (j < end && text[j] != ' ' && text[j] != '\t' && text[j] != '\r' &&
			       k + 1 < size)
				v[k++] = text[j++];
			v[k] = '\0';
			return k > 0;
		}
		i = end + 1;
	}
	return false;
}

int ls_ptp_parse(struct ls_ptp *st, const char *text, size_t len)
{
	char v[32], *end;
	long long off;

	memset(st, 0, sizeof(*st));
	if (!field(text, len, "portState", st->state, sizeof(st->state)))
		return -EBADMSG;
	st->answered = true;
	if (field(text, len, "master_offset", v, sizeof(v))) {
		errno = 0;
		off = strtoll(v, &end, 10);
		st->has_offset = !*end && !errno;
		st->offset_ns = st->has_offset ? off : 0;
	}
	if (field(text, len, "gmPresent", v, sizeof(v)))
		st->gm_present = !strcmp(v, "true");
	return 0;
}

bool ls_ptp_locked(const struct ls_ptp *st, double bound_ns, bool free_running, char *why,
		   size_t size)
{
	bool master = !strcmp(st->state, "MASTER") || !strcmp(st->state, "GRAND_MASTER");
	bool slave = !strcmp(st->state, "SLAVE") ||
		     (free_running && !strcmp(st->state, "UNCALIBRATED"));

	if (master)
		return true;
	if (!slave) {
		snprintf(why, size, "PTP is not locked: ptp4l's port is %s%s", st->state,
			 !strcmp(st->state, "UNCALIBRATED") ? " (its servo has not locked yet)" :
			 !strcmp(st->state, "LISTENING") ? " (no master heard)" : "");
		return false;
	}
	if (!st->has_offset || !st->gm_present) {
		snprintf(why, size, "PTP is not locked: ptp4l is %s but reports %s", st->state,
			 st->has_offset ? "no grandmaster" : "no offset from its master");
		return false;
	}
	if ((double)llabs(st->offset_ns) > bound_ns) {
		snprintf(why, size, "PTP is not locked: ptp4l's offset from its master is %" PRId64
			 " ns (ptp_offset_ns %.0f)", st->offset_ns, bound_ns);
		return false;
	}
	return true;
}

int ls_ptp_query(struct ls_ptp *st, const char *socket, char *err, size_t errsize)
{
	char *out = malloc(LS_PMC_OUT), client[64];
	int fds[2], status = 0, rc;
	size_t len = 0;
	int64_t until;
	pid_t pid;

	STRAND_ASSERT_NOT_RT();
	memset(st, 0, sizeof(*st));
	if (!out)
		return -ENOMEM;
	if (pipe2(fds, O_CLOEXEC)) {
		rc = -errno;
		free(out);
		snprintf(err, errsize, "pmc: %s", strerror(-rc));
		return rc;
	}
	/* pmc's own end of the socket, private to this process */
	snprintf(client, sizeof(client), "/tmp/strand-pmc.%d", (int)getpid());
	pid = fork();
	if (pid == 0) {
		dup2(fds[1], 1);
		dup2(fds[1], 2);
		execlp("pmc", "pmc", "-u", "-b", "0", "-s", socket, "-i", client,
		       "GET PORT_DATA_SET", "GET TIME_STATUS_NP", (char *)NULL);
		_exit(127);
	}
	close(fds[1]);
	if (pid < 0) {
		rc = -errno;
		close(fds[0]);
		free(out);
		snprintf(err, errsize, "pmc: cannot start it: %s", strerror(-rc));
		return rc;
	}
	until = hal_mono_ns() + (int64_t)LS_PMC_TIMEOUT_MS * 1000000;
	for (;;) {
		struct pollfd p = { .fd = fds[0], .events = POLLIN };
		int64_t left = until - hal_mono_ns();
		ssize_t n;

		if (left <= 0 || poll(&p, 1, (int)(left / 1000000) + 1) <= 0) {
			kill(pid, SIGKILL);
			break;
		}
		n = read(fds[0], out + len, LS_PMC_OUT - 1 - len);
		if (n <= 0)
			break;
		len += (size_t)n;
		if (len == LS_PMC_OUT - 1)
			break;
	}
	close(fds[0]);
	waitpid(pid, &status, 0);
	unlink(client);
	out[len] = '\0';
	if (WIFEXITED(status) && WEXITSTATUS(status) == 127) {
		rc = -ENOENT;
		snprintf(err, errsize, "pmc (linuxptp) cannot be run: is linuxptp installed?");
	} else if (ls_ptp_parse(st, out, len)) {
		rc = -EHOSTUNREACH;
		snprintf(err, errsize, "PTP is not running: ptp4l does not answer at %s (pmc -s %s: "
			 "is ptp4l running, with that uds_address?)", socket, socket);
	} else {
		rc = 0;
	}
	free(out);
	return rc;
}
