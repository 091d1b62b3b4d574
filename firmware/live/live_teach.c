/* SPDX-License-Identifier: MIT */
/*
 * live_teach.c - teach, load and save (live.h). A teach edits the scene
 * file's text in place (yedit.h), loads and checks what it made, writes it
 * atomically with the previous version kept beside it (FILE.bak), and
 * swaps the new scene into the loop while the rig is at rest; anything
 * refused on the way leaves the file and the loop as they were.
 */
#define _GNU_SOURCE
#include "live_priv.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene/channel.h"
#include "yedit.h"

/* text into path's directory as path + suffix, synced: 0 or -errno */
static int write_tmp(const char *path, const char *suffix, const char *text, size_t len,
		     char *tmp, size_t tmpsize)
{
	size_t off = 0;
	int fd, rc = 0;

	snprintf(tmp, tmpsize, "%s%s", path, suffix);
	fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
	if (fd < 0)
		return -errno;
	while (off < len) {
		ssize_t n = write(fd, text + off, len - off);

		if (n < 0) {
			if (errno == EINTR)
				continue;
			rc = -errno;
			break;
		}
		off += (size_t)n;
	}
	if (!rc && fsync(fd))
		rc = -errno;
	if (close(fd) && !rc)
		rc = -errno;
	if (rc)
		unlink(tmp);
	return rc;
}

/* A name of the data folder: letters, digits, '_', '-', '.', not starting
 * with '.', ending in .yaml or .yml; never a path. */
static int data_path(struct live *lv, const char *name, char *path, size_t size, char *msg,
		     size_t msgsize)
{
	size_t n = name ? strlen(name) : 0, i;

	for (i = 0; i < n; i++)
		if (!((name[i] >= 'a' && name[i] <= 'z') || (name[i] >= 'A' && name[i] <= 'Z') ||
		      (name[i] >= '0' && name[i] <= '9') || name[i] == '_' || name[i] == '-' ||
		      name[i] == '.'))
			break;
	if (!n || n > 128 || i < n || name[0] == '.' ||
	    !((n > 5 && !strcmp(name + n - 5, ".yaml")) ||
	      (n > 4 && !strcmp(name + n - 4, ".yml")))) {
		snprintf(msg, msgsize, "'%.140s': a file name of the data folder (letters, digits, "
			 "'_', '-', '.', ending in .yaml), no path", name ? name : "");
		return -EINVAL;
	}
	if ((size_t)snprintf(path, size, "%s/%s", lv->data_dir, name) >= size) {
		snprintf(msg, msgsize, "the data folder's path is too long");
		return -ENAMETOOLONG;
	}
	return 0;
}

/*
 * The scene becomes text (written to path; NULL: its own file): loaded,
 * built and checked, written atomically, swapped in at rest.
 */
static int apply(struct live *lv, const char *text, size_t len, const char *path, char *msg,
		 size_t size)
{
	char tmp[PATH_MAX + 8], bak[PATH_MAX + 8];
	struct live_scene *ns;
	struct loop_cmd c = { .kind = LOOP_CMD_SOURCE };
	struct loop_ack a;
	struct lim_run run;
	const char *dst = path ? path : lv->sc->path;
	bool bak_made = false;
	int rc;

	if (lv->running && lv->state != LIVE_ENABLED && lv->snap.state != LIVE_ENABLED) {
		snprintf(msg, size, "the rig is not at rest: stop first");
		return -EBUSY;
	}
	rc = live_scene_parse(&ns, dst, text, len, msg, size);
	if (rc)
		return rc;
	if (ns->sf.desc.nnodes != lv->sc->sf.desc.nnodes) {
		snprintf(msg, size, "the new scene's nodes differ: load it instead");
		live_scene_free(ns);
		return -EINVAL;
	}
	run = (struct lim_run){ .from = ns->src.s.frame_first, .to = ns->src.s.frame_last };
	rc = live_scene_check(lv, ns, &run, msg, size);
	if (rc)
		goto fail;
	rc = live_scene_bind(ns, &lv->rig);
	if (rc) {
		snprintf(msg, size, "out of memory");
		goto fail;
	}
	rc = write_tmp(dst, ".tmp", text, len, tmp, sizeof(tmp));
	if (rc) {
		snprintf(msg, size, "%s.tmp: %s", dst, strerror(-rc));
		goto fail;
	}
	if (!path) {
		rc = write_tmp(dst, ".bak.tmp", lv->sc->text, lv->sc->len, bak, sizeof(bak));
		if (rc) {
			snprintf(msg, size, "%s.bak.tmp: %s", dst, strerror(-rc));
			unlink(tmp);
			goto fail;
		}
		bak_made = true;
	}
	if (!path && lv->running) {
		c.src = &ns->src.s;
		rc = live_send(lv, &c, &a, msg, size);
		if (rc) {
			unlink(tmp);
			unlink(bak);
			goto fail;
		}
	}
	if (bak_made) {
		char final[PATH_MAX + 8];

		snprintf(final, sizeof(final), "%s.bak", dst);
		rename(bak, final);
	}
	if (rename(tmp, dst)) {
		rc = -errno;
		snprintf(msg, size, "%s: %s", dst, strerror(errno));
		unlink(tmp);
		if (!path && lv->running) /* the loop has it: keep it as the scene */
			goto keep;
		goto fail;
	}
	if (path) { /* saved elsewhere: the session's scene is the same */
		live_scene_free(ns);
		return 0;
	}
keep:
	live_scene_swap(lv, ns);
	live_publish_scene(lv);
	return rc;
fail:
	live_scene_free(ns);
	return rc;
}

/* The rig's pose at output i, file units: where it is held. */
static double pose_at(struct live *lv, uint32_t i)
{
	double v;

	pthread_mutex_lock(&lv->snap_mu);
	v = lv->snap.out[i].sp;
	pthread_mutex_unlock(&lv->snap_mu);
	return v;
}

static bool wanted(const char *name, const char *const *nodes, uint32_t n)
{
	uint32_t i;

	if (!n)
		return true;
	for (i = 0; i < n; i++)
		if (!strcmp(nodes[i], name))
			return true;
	return false;
}

/* Output i follows one of the camera's channels. */
static bool drives_camera(struct live *lv, uint32_t i)
{
	return lv->sc->src.all.c[lv->rig.out[i].src].kind == CHAN_CAMERA;
}

/* y = x with a key set, *x freed (NULL: the session's text). */
static int set_key(struct live *lv, char **x, size_t *len, const char *node, const char *field,
		   double frame, const char *value, char *msg, size_t size)
{
	char *next;
	size_t nlen;
	int rc = yedit_key_set_text(*x ? *x : lv->sc->text, *x ? *len : lv->sc->len, node, field,
				    frame, value, &next, &nlen, msg, size);

	if (rc)
		return rc;
	free(*x);
	*x = next;
	*len = nlen;
	return 0;
}

/*
 * The camera's key where the rig holds it: the eye its slider's outputs
 * say, looking as its head's pan and tilt say (camera.h: from the eye down
 * (-sin pan cos tilt, sin tilt, -cos pan cos tilt)) at the distance the
 * scene's point looked at keeps at that frame, twist its roll. Channels no
 * output drives are the scene's there.
 */
static int teach_camera(struct live *lv, double frame, char **text, size_t *len, char *msg,
			size_t size)
{
	struct source_scene *ss = &lv->sc->twin;
	mot_q32 tmp[LOOP_LIVE_OUT_MAX];
	double q[6], look[3], f[3], d = 0, p, t;
	char eye_s[120], look_s[120], twist_s[40];
	uint32_t sat = 0, i;
	int rc;

	src_eval(&ss->s, (mot_q32)llround(frame * 4294967296.0), tmp, &sat);
	for (i = 0; i < 3; i++) {
		q[i] = (double)ss->pose.cam.eye[i] / 4294967296.0;
		look[i] = (double)ss->pose.cam.look[i] / 4294967296.0;
		d += (look[i] - q[i]) * (look[i] - q[i]);
	}
	q[3] = (double)ss->pose.cam.pan * (360.0 / 4294967296.0);
	q[4] = (double)ss->pose.cam.tilt * (360.0 / 4294967296.0);
	q[5] = (double)ss->pose.cam.roll * (360.0 / 4294967296.0);
	d = d > 0 ? sqrt(d) : 1;
	for (i = 0; i < lv->rig.nout; i++)
		if (drives_camera(lv, i))
			q[lv->sc->src.all.c[lv->rig.out[i].src].comp] = pose_at(lv, i);
	p = q[3] * M_PI / 180;
	t = q[4] * M_PI / 180;
	f[0] = -sin(p) * cos(t);
	f[1] = sin(t);
	f[2] = -cos(p) * cos(t);
	snprintf(eye_s, sizeof(eye_s), "[%.10g, %.10g, %.10g]", q[0], q[1], q[2]);
	snprintf(look_s, sizeof(look_s), "[%.10g, %.10g, %.10g]", q[0] + d * f[0],
		 q[1] + d * f[1], q[2] + d * f[2]);
	snprintf(twist_s, sizeof(twist_s), "%.10g", q[5]);
	rc = set_key(lv, text, len, "camera", "eye", frame, eye_s, msg, size);
	if (!rc)
		rc = set_key(lv, text, len, "camera", "look_at", frame, look_s, msg, size);
	if (!rc)
		rc = set_key(lv, text, len, "camera", "twist", frame, twist_s, msg, size);
	return rc;
}

static int teach(struct live *lv, double frame, const char *const *nodes, uint32_t n, char *msg,
		 size_t size)
{
	struct live_out_info info[LOOP_LIVE_OUT_MAX];
	uint32_t nout = live_outputs(lv, info, LOOP_LIVE_OUT_MAX), i, k, done = 0;
	char *text = NULL, *next;
	size_t len = lv->sc->len, nlen;
	int rc = 0;

	if (!(frame >= 0 && frame < 1073741824.0)) {
		snprintf(msg, size, "frame %g: 0 to 2^30", frame);
		return -ERANGE;
	}
	if (!lv->running) {
		snprintf(msg, size, "the drives are %s: teach keys the pose the loop holds; "
			 "enable first", live_state_name(lv->state));
		return -EPERM;
	}
	for (k = 0; k < n; k++) {
		for (i = 0; i < nout; i++)
			if ((info[i].node >= 0 &&
			     !strcmp(lv->sc->sf.desc.nodes[info[i].node].name, nodes[k])) ||
			    (!strcmp(nodes[k], "camera") && drives_camera(lv, i)))
				break;
		if (i == nout) {
			snprintf(msg, size, "'%s' is not a joint or the camera that drives an "
				 "output", nodes[k]);
			return -ENOENT;
		}
	}
	for (i = 0; i < nout && !rc; i++) {
		if (!drives_camera(lv, i) || !wanted("camera", nodes, n))
			continue;
		rc = teach_camera(lv, frame, &text, &len, msg, size);
		done++;
	}
	for (i = 0; i < nout; i++) {
		const struct sd_node *nd;

		if (info[i].node < 0)
			continue;
		nd = &lv->sc->sf.desc.nodes[info[i].node];
		if (!wanted(nd->name, nodes, n))
			continue;
		if (lv->sc->sf.strand[info[i].node].rpm) {
			snprintf(msg, size, "'%s' is keyed by speed (rpm): teach keys positions",
				 nd->name);
			rc = -EINVAL;
			break;
		}
		rc = yedit_key_set(text ? text : lv->sc->text, text ? len : lv->sc->len, nd->name,
				   nd->kind == MOT_NODE_REVOLUTE ? "angle" : "position", frame,
				   pose_at(lv, i), &next, &nlen, msg, size);
		if (rc)
			break;
		free(text);
		text = next;
		len = nlen;
		done++;
	}
	if (!rc && !done) {
		snprintf(msg, size, "no joint of the scene, nor its camera, drives an output: "
			 "nothing to teach");
		rc = -ENOENT;
	}
	if (!rc)
		rc = apply(lv, text, len, NULL, msg, size);
	if (!rc)
		snprintf(msg, size, "%u key%s at frame %.10g", done, done == 1 ? "" : "s", frame);
	free(text);
	return rc;
}

int live_teach(struct live *lv, double frame, const char *const *nodes, uint32_t n, char *msg,
	       size_t size)
{
	int rc;

	pthread_mutex_lock(&lv->mu);
	rc = lv->sc ? teach(lv, frame, nodes, n, msg, size) : live_no_scene(msg, size);
	pthread_mutex_unlock(&lv->mu);
	return rc;
}

/* A key deleted (del) or moved from `from` to `to`, then applied. */
static int key_edit(struct live *lv, const char *node, bool del, double from, double to,
		    char *msg, size_t size)
{
	char *text;
	size_t len;
	int rc;

	if (!lv->sc)
		return live_no_scene(msg, size);
	rc = del ? yedit_key_delete(lv->sc->text, lv->sc->len, node, from, &text, &len, msg,
				     size) :
		   yedit_key_move(lv->sc->text, lv->sc->len, node, from, to, &text, &len, msg,
				  size);
	if (rc)
		return rc;
	rc = apply(lv, text, len, NULL, msg, size);
	free(text);
	return rc;
}

int live_teach_delete(struct live *lv, const char *node, double frame, char *msg, size_t size)
{
	int rc;

	pthread_mutex_lock(&lv->mu);
	rc = key_edit(lv, node, true, frame, 0, msg, size);
	pthread_mutex_unlock(&lv->mu);
	return rc;
}

int live_teach_move(struct live *lv, const char *node, double from, double to, char *msg,
		    size_t size)
{
	int rc;

	pthread_mutex_lock(&lv->mu);
	rc = key_edit(lv, node, false, from, to, msg, size);
	pthread_mutex_unlock(&lv->mu);
	return rc;
}

int live_save(struct live *lv, const char *name, char *msg, size_t size)
{
	char path[PATH_MAX];
	int rc = 0;

	pthread_mutex_lock(&lv->mu);
	if (!lv->sc)
		rc = live_no_scene(msg, size);
	else if (name)
		rc = data_path(lv, name, path, sizeof(path), msg, size);
	if (!rc)
		rc = apply(lv, lv->sc->text, lv->sc->len, name ? path : NULL, msg, size);
	pthread_mutex_unlock(&lv->mu);
	return rc;
}

int live_load(struct live *lv, const char *name, char *msg, size_t size)
{
	char path[PATH_MAX];
	struct live_scene *ns, *old;
	int rc;

	pthread_mutex_lock(&lv->mu);
	rc = data_path(lv, name, path, sizeof(path), msg, size);
	if (rc)
		goto out;
	if (lv->running) {
		snprintf(msg, size, "the drives are enabled: disable them before loading a scene");
		rc = -EBUSY;
		goto out;
	}
	rc = live_scene_open(&ns, path, msg, size);
	if (rc)
		goto out;
	loop_free(lv->L);
	lv->L = NULL;
	live_rig_down(lv);
	lv->space.valid = false;
	old = lv->sc;
	lv->sc = ns;
	rc = live_rig_up(lv, msg, size);
	if (rc) {
		/* the old scene back, as it was */
		char err2[LIVE_MSG];

		live_rig_down(lv);
		lv->sc = old;
		live_scene_free(ns);
		if (old && live_rig_up(lv, err2, sizeof(err2))) {
			lv->state = LIVE_FAULTED;
			snprintf(lv->reason, sizeof(lv->reason), "%s", err2);
		}
		goto out;
	}
	live_scene_free(old);
	lv->at_frame = -1;
	lv->goto_frame = -1;
	live_publish_scene(lv);
out:
	pthread_mutex_unlock(&lv->mu);
	return rc;
}
