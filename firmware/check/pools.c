/* SPDX-License-Identifier: MIT */
/* pools.c - particle pools against their emission (see pools.h). */
#include "pools.h"

#include "scene/channel.h"

uint32_t lim_pools(FILE *out, FILE *info, const struct scene_desc *d, const struct mot_scene *sc,
		   int64_t to, char *first, size_t size)
{
	uint32_t i, bad = 0, sat = 0;

	for (i = 0; i < sc->nsys; i++) {
		const struct mot_particles *p = sc->sys[i].particles;
		const char *name = sd_sys_name(&d->sys[i]);
		char line[256];
		mot_q32 f;

		if (sc->sys[i].kind != MOT_SYS_PARTICLES || !p->emit)
			continue;
		if (info)
			fprintf(info, "particles '%s': at most %lld of %u slots alive at once, %lld "
				"dropped; %lld steps at %g a second\n", name, (long long)p->peak,
				p->npool, (long long)p->dropped, (long long)p->steps.nsteps,
				(double)p->steps.rate_num / p->steps.rate_den);
		if (p->first_drop < 0)
			continue;
		f = mot_steps_frame(&p->steps, p->first_drop * MOT_Q32_ONE, &sat);
		if ((f >> 32) > to)
			continue;
		snprintf(line, sizeof(line), "%s: the pool of %u slots runs out at frame %.10g: %lld "
			 "particles dropped over the span (raise pool:)", name, p->npool, chan_q32(f),
			 (long long)p->dropped);
		if (out)
			fprintf(out, "%s\n", line);
		if (!bad && first)
			snprintf(first, size, "%s", line);
		bad++;
	}
	return bad;
}
