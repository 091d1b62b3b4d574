/* SPDX-License-Identifier: MIT */
/*
 * sim_camera.h - a simulated camera on a simulated trigger line.
 *
 * It exposes on each asserting edge of its trigger line, unless it is still
 * busy with the previous picture (exposure plus readout), in which case the
 * trigger is counted as missed, as a real camera ignores it. Every exposure
 * is recorded with its tick and clock time. Optionally every trigger edge
 * the camera receives, exposed or missed, is also logged into a file mapped
 * into memory, which the kernel keeps when the process is killed, so a test
 * can compare what reached the camera with strand's journal after
 * `kill -9`. When wired to an input line, the camera asserts it when ready
 * for the next picture and deasserts it while busy (step mode's
 * camera-ready).
 */
#ifndef SIM_CAMERA_H
#define SIM_CAMERA_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sim_gpio.h"

/* A simulated camera's exposure and readout where the scene gives none, as
 * fractions of a frame. */
#define SIM_CAMERA_DEFAULT_EXPOSURE_FRAC 0.4
#define SIM_CAMERA_DEFAULT_READOUT_FRAC 0.1

struct sim_camera_params {
	int64_t exposure_ns;
	int64_t readout_ns;
};

struct sim_exposure {
	int64_t tick;
	int64_t ts_ns;
	uint32_t exposed; /* log file: 0 for a trigger the camera missed */
	uint32_t pad;
};

/* The log file: this header, then count trigger edges. */
struct sim_camera_log {
	char magic[8]; /* "STRANDC2" */
	_Atomic uint64_t count;
	uint64_t capacity;
	struct sim_exposure e[];
};

struct sim_camera;

/*
 * [init] A camera keeping up to cap exposures in memory (all are counted),
 * into *out; log_path, when non-NULL, a file created to log up to cap
 * trigger edges. 0, or a negative errno with a message in err ("simulated
 * camera: ..."; the caller names the trigger it stands on).
 */
int sim_camera_new(struct sim_camera **out, const struct sim_camera_params *p, uint64_t cap,
		   const char *log_path, char *err, size_t errsize);
void sim_camera_free(struct sim_camera *c);

/* [init] Wire the trigger input to output line `line` of g. */
void sim_camera_trigger(struct sim_camera *c, struct sim_gpio *g, uint32_t line);
/* [init] Wire the ready output to input line `line` of g (asserted now). */
int sim_camera_ready(struct sim_camera *c, struct sim_gpio *g, uint32_t line);

/* [init] Call fn at each exposure (tests look at the rig then). */
void sim_camera_on_exposure(struct sim_camera *c,
			    void (*fn)(void *ctx, const struct sim_exposure *), void *ctx);

uint64_t sim_camera_count(const struct sim_camera *c);
uint64_t sim_camera_missed(const struct sim_camera *c);
/* The i-th exposure (i < min(count, cap)). */
const struct sim_exposure *sim_camera_exposure(const struct sim_camera *c, uint64_t i);

/* [init] Read a log file written by a camera (possibly killed): 0 and a
 * malloc'd array of its trigger edges in *e with *n entries, or a negative
 * errno. */
int sim_camera_log_read(const char *path, struct sim_exposure **e, uint64_t *n);

#endif /* SIM_CAMERA_H */
