/* SPDX-License-Identifier: MIT */
/* dfm_run.c - a DFMoco session on its port (see dfm_run.h). */
#include "dfm_run.h"

#include <errno.h>
#include <time.h>

/* The session's round at least this often (ms): moves waiting for rest,
 * positions while motors move, an e-stop said as it happens. */
#define DFM_ROUND_MS 5

static int64_t mono_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

int dfm_run(struct dfm_session *s, struct dfm_port *p, const volatile sig_atomic_t *stop,
	    FILE *err)
{
	char buf[4096];
	const char *out;
	size_t len;
	ssize_t n;
	bool joined;
	int rc;

	while (!*stop && !live_finished(s->lv)) {
		dfm_session_output(s, &len);
		rc = dfm_port_wait(p, DFM_ROUND_MS, len > 0, &joined);
		if (rc < 0)
			return rc;
		if (joined) {
			fprintf(err, "strand dfmoco: a client connected to %s\n", p->name);
			s->lines.len = 0;
			s->lines.overlong = false;
			dfm_session_consumed(s, len);
		}
		while ((n = dfm_port_read(p, buf, sizeof(buf))) > 0)
			dfm_session_input(s, buf, (size_t)n);
		if (n == -ENOTCONN)
			fprintf(err, "strand dfmoco: the client left %s\n", p->name);
		else if (n < 0)
			return (int)n;
		dfm_session_tick(s, mono_ns());
		out = dfm_session_output(s, &len);
		if (!dfm_port_up(p)) {
			dfm_session_consumed(s, len); /* no one to say it to */
			continue;
		}
		while (len && (n = dfm_port_write(p, out, len)) > 0) {
			dfm_session_consumed(s, (size_t)n);
			out = dfm_session_output(s, &len);
		}
		if (n < 0 && n != -ENOTCONN)
			return (int)n;
	}
	return 0;
}
