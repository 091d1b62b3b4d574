/* SPDX-License-Identifier: MIT */
/*
 * test_load_errors.c - every kind of scene file error, with its exact
 * one-line message and position (golden strings), the parser's and what
 * only the build finds. The same cases seed the
 * loader's fuzz corpus: `test_load_errors --write-corpus DIR` writes them out.
 */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "load/load.h"
#include "testutil.h"

struct err_case {
	const char *name;
	const char *yaml;
	const char *expect; /* file:line:col: message */
};

static const struct err_case cases[] = {
	{ "unknown key suggested",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes:\n"
	  "  - name: a\n"
	  "    pivto: [0, 0, 0]\n",
	  "t.yaml:4:5: unknown key 'pivto' in node (did you mean 'pivot'?)" },
	{ "unknown key listed",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "lights: []\n",
	  "t.yaml:2:1: unknown key 'lights' in the scene (valid keys: scene, timing, nodes, strands, camera, cycles, attributes, surfaces, particles, flocks, aims, devices, outputs, triggers, inputs, boards, lockstep)" },
	{ "unknown key in a key",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands:\n"
	  "  - node: a\n"
	  "    keys: [{fram: 0, angle: 1}]\n",
	  "t.yaml:5:13: unknown key 'fram' in key (did you mean 'frame'?)" },
	{ "unknown interpolation",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands:\n"
	  "  - {node: a, interpolation: hermit, keys: [{frame: 0, angle: 1}]}\n",
	  "t.yaml:4:30: unknown interpolation 'hermit' (did you mean 'hermite'?)" },
	{ "unknown joint type",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: ball, axis: z}}]\n",
	  "t.yaml:2:33: unknown joint type 'ball' (one of: revolute, prismatic)" },
	{ "wrong type vector",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, pivot: 5}]\n",
	  "t.yaml:2:26: expected a sequence of 3 numbers, found '5'" },
	{ "wrong type vector length",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, pivot: [1, 2]}]\n",
	  "t.yaml:2:26: expected 3 numbers, found 2" },
	{ "wrong type number",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands: [{node: a, keys: [{frame: 0, angle: abc}]}]\n",
	  "t.yaml:3:46: expected a number, found 'abc'" },
	{ "wrong type quoted number",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands: [{node: a, keys: [{frame: 0, angle: \"10\"}]}]\n",
	  "t.yaml:3:46: expected a number, found '10'" },
	{ "wrong type sequence",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: {a: 1}\n",
	  "t.yaml:2:8: expected a sequence for nodes, found a mapping" },
	{ "wrong type mapping",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [a]\n",
	  "t.yaml:2:9: expected a mapping for node, found 'a'" },
	{ "wrong type frames",
	  "timing: {frame_rate: 24, frames: [0, 1.5]}\n",
	  "t.yaml:1:38: expected a whole number, found '1.5'" },
	{ "wrong type name",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: [a]}]\n",
	  "t.yaml:2:16: expected a name, found a sequence" },
	{ "bad name",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: arm.1}]\n",
	  "t.yaml:2:16: name 'arm.1': use letters, digits, '_' and '-', starting with a letter or '_'" },
	{ "missing timing",
	  "nodes: []\n",
	  "t.yaml:1:1: missing field 'timing' in the scene" },
	{ "missing frames",
	  "timing: {frame_rate: 24}\n",
	  "t.yaml:1:9: missing field 'frames' in timing" },
	{ "missing name",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes:\n"
	  "  - pivot: [0, 0, 0]\n",
	  "t.yaml:3:5: missing field 'name' in node" },
	{ "missing frame",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands: [{node: a, keys: [{angle: 3}]}]\n",
	  "t.yaml:3:28: missing field 'frame' in key" },
	{ "missing keys",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands: [{node: a}]\n",
	  "t.yaml:3:11: missing field 'keys' in strand" },
	{ "missing angle",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands: [{node: a, keys: [{frame: 0}]}]\n",
	  "t.yaml:3:28: missing field 'angle' (or 'rpm') in key" },
	{ "missing axis",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute}}]\n",
	  "t.yaml:2:26: missing field 'axis' in joint" },
	{ "keys equal",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands:\n"
	  "  - node: a\n"
	  "    keys:\n"
	  "      - {frame: 0, angle: 0}\n"
	  "      - {frame: 10, angle: 5}\n"
	  "      - {frame: 10, angle: 6}\n",
	  "t.yaml:8:17: key frame 10 is not after the previous key's frame 10 (keys must be strictly increasing)" },
	{ "keys decreasing",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a}]\n"
	  "strands:\n"
	  "  - node: a\n"
	  "    keys:\n"
	  "      - {frame: 5, translate: [0, 0, 0]}\n"
	  "      - {frame: 2.5, translate: [1, 0, 0]}\n",
	  "t.yaml:7:17: key frame 2.5 is not after the previous key's frame 5 (keys must be strictly increasing)" },
	{ "unknown parent suggested",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes:\n"
	  "  - {name: arm1}\n"
	  "  - {name: arm2, parent: arm}\n",
	  "t.yaml:4:26: unknown parent 'arm' (did you mean 'arm1'?)" },
	{ "unknown parent",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes:\n"
	  "  - {name: arm1}\n"
	  "  - {name: arm2, parent: wheel}\n",
	  "t.yaml:4:26: unknown parent 'wheel' (no node has that name)" },
	{ "later parent",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes:\n"
	  "  - {name: claw, parent: arm}\n"
	  "  - {name: arm}\n",
	  "t.yaml:3:26: parent 'arm' is defined after 'claw' (list parents before their children)" },
	{ "cycle",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes:\n"
	  "  - {name: a, parent: c}\n"
	  "  - {name: b, parent: a}\n"
	  "  - {name: c, parent: b}\n",
	  "t.yaml:3:23: cycle in the hierarchy: a -> c -> b -> a" },
	{ "own parent",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes:\n"
	  "  - {name: a, parent: a}\n",
	  "t.yaml:3:23: node 'a' is its own parent" },
	{ "duplicate node",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes:\n"
	  "  - {name: a}\n"
	  "  - {name: a}\n",
	  "t.yaml:4:12: duplicate node name 'a' (first at line 3)" },
	{ "duplicate key",
	  "timing: {frame_rate: 24, frames: [0, 10], frame_rate: 25}\n",
	  "t.yaml:1:43: duplicate key 'frame_rate' in timing (first at line 1)" },
	{ "joint keyed as free node",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: base, joint: {type: revolute, axis: y}}]\n"
	  "strands: [{node: base, keys: [{frame: 0, translate: [0, 1, 0]}]}]\n",
	  "t.yaml:3:53: 'translate' keys a free node, but 'base' is a revolute joint (key 'angle' or 'rpm')" },
	{ "prismatic keyed as free node",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: slide, joint: {type: prismatic, axis: x}}]\n"
	  "strands: [{node: slide, keys: [{frame: 0, matrix: [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}]}]\n",
	  "t.yaml:3:51: 'matrix' keys a free node, but 'slide' is a prismatic joint (key 'position')" },
	{ "free node keyed as joint",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: tool}]\n"
	  "strands: [{node: tool, keys: [{frame: 0, angle: 30}]}]\n",
	  "t.yaml:3:49: 'angle' keys a joint, but 'tool' is a free node (key translate, rotate, quat, scale, shear or matrix)" },
	{ "prismatic keyed by angle",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: slide, joint: {type: prismatic, axis: x}}]\n"
	  "strands: [{node: slide, keys: [{frame: 0, angle: 30}]}]\n",
	  "t.yaml:3:50: 'angle' keys a revolute joint, but 'slide' is a prismatic joint (key 'position')" },
	{ "revolute keyed by position",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: a, keys: [{frame: 0, position: 30}]}]\n",
	  "t.yaml:3:49: 'position' keys a prismatic joint, but 'a' is a revolute joint (key 'angle' or 'rpm')" },
	{ "rotation on a joint",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: a, rotation: squad, keys: [{frame: 0, angle: 30}]}]\n",
	  "t.yaml:3:31: 'rotation' interpolates a free node's rotation keys, but 'a' is a revolute joint" },
	{ "singular matrix",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: tool}]\n"
	  "strands:\n"
	  "  - node: tool\n"
	  "    keys:\n"
	  "      - {frame: 0, matrix: [[1,0,0,0],[0,1,0,0],[1,1,0,0],[0,0,0,1]]}\n",
	  "t.yaml:6:28: singular matrix key: its z scale is below 1e-9 of its largest row" },
	{ "non-affine matrix",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: tool}]\n"
	  "strands:\n"
	  "  - node: tool\n"
	  "    keys:\n"
	  "      - {frame: 0, matrix: [[1,0,0,0],[0,1,0,0],[0,0,1,0.5],[0,0,0,1]]}\n",
	  "t.yaml:6:28: a matrix key must be affine: its last column must be (0, 0, 0, 1)" },
	{ "matrix shape",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: tool}]\n"
	  "strands:\n"
	  "  - node: tool\n"
	  "    keys:\n"
	  "      - {frame: 0, matrix: [[1,0,0,0],[0,1,0,0],[0,0,1,0]]}\n",
	  "t.yaml:6:28: a matrix key has 4 rows of 4 numbers, found 3 rows" },
	{ "matrix with translate",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: tool}]\n"
	  "strands:\n"
	  "  - node: tool\n"
	  "    keys:\n"
	  "      - {frame: 0, translate: [1, 0, 0], matrix: [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}\n",
	  "t.yaml:6:31: 'matrix' sets the whole transform; a key with it cannot also set 'translate'" },
	{ "rotate and quat",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: tool}]\n"
	  "strands:\n"
	  "  - node: tool\n"
	  "    keys:\n"
	  "      - {frame: 0, rotate: [0, 0, 90], quat: [1, 0, 0, 0]}\n",
	  "t.yaml:6:46: 'rotate' and 'quat' both set the rotation; keep one" },
	{ "zero quaternion",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: tool}]\n"
	  "strands:\n"
	  "  - node: tool\n"
	  "    keys:\n"
	  "      - {frame: 0, quat: [0, 0, 0, 0]}\n",
	  "t.yaml:6:26: a rotation quaternion must not be zero" },
	{ "key sets nothing",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: tool}]\n"
	  "strands:\n"
	  "  - node: tool\n"
	  "    keys:\n"
	  "      - {frame: 0, ease_in: 0.5}\n",
	  "t.yaml:6:9: key sets nothing: give translate, rotate, quat, scale, shear or matrix" },
	{ "zero frame rate",
	  "timing: {frame_rate: 0, frames: [0, 10]}\n",
	  "t.yaml:1:22: frame rate '0' must be above zero" },
	{ "zero frame rate ratio",
	  "timing: {frame_rate: \"30000/0\", frames: [0, 10]}\n",
	  "t.yaml:1:22: frame rate '30000/0' must be above zero" },
	{ "bad frame rate",
	  "timing: {frame_rate: 29.97, frames: [0, 10]}\n",
	  "t.yaml:1:22: frame_rate must be a whole number or a ratio like \"30000/1001\", found '29.97'" },
	{ "frame rate above tick rate",
	  "timing: {tick_hz: 100, frame_rate: 120, frames: [0, 10]}\n",
	  "t.yaml:1:36: frame rate 120/1 is faster than tick_hz 100 (at most one frame per tick)" },
	{ "frame rate out of range",
	  "timing: {tick_hz: 1000, frame_rate: \"1/99999999\", frames: [0, 10]}\n",
	  "t.yaml:1:37: frame rate '1/99999999' is outside the core's range (numerator and denominator up to 16777216)" },
	{ "tick_hz zero",
	  "timing: {tick_hz: 0, frame_rate: 24, frames: [0, 10]}\n",
	  "t.yaml:1:19: '0' is out of range (1 to 1048576)" },
	{ "frames reversed",
	  "timing: {frame_rate: 24, frames: [10, 0]}\n",
	  "t.yaml:1:39: the last frame 0 is before the first frame 10" },
	{ "pivot out of range",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, pivot: [0, 2e9, 0]}]\n",
	  "t.yaml:2:30: 2000000000 is outside the core's range (|value| < 1073741824 scene units)" },
	{ "angle out of range",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands: [{node: a, keys: [{frame: 0, angle: 1e12}]}]\n",
	  "t.yaml:3:46: 1e+12 is outside the core's range (|value| < 3.865470566e+11 degrees)" },
	{ "frame out of range",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands: [{node: a, keys: [{frame: 1073741824, angle: 0}]}]\n",
	  "t.yaml:3:36: 1073741824 is outside the core's range (|value| < 1073741824 frames)" },
	{ "infinite number",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, pivot: [0, 1e999, 0]}]\n",
	  "t.yaml:2:30: '1e999' is outside the core's range" },
	{ "nan is not a number",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, pivot: [0, .nan, 0]}]\n",
	  "t.yaml:2:30: expected a number, found '.nan'" },
	{ "huge frame span",
	  "timing: {frame_rate: 24, frames: [0, 99999999999]}\n",
	  "t.yaml:1:38: '99999999999' is out of range (-1073741823 to 1073741823)" },
	{ "not yaml",
	  "timing: {frame_rate: 24, frames: [0, 10]\n"
	  "nodes: []\n",
	  "t.yaml:2:1: not valid YAML: did not find expected ',' or '}' while parsing a flow mapping" },
	{ "not yaml tab",
	  "timing:\n"
	  "\tframe_rate: 24\n",
	  "t.yaml:2:1: not valid YAML: found character that cannot start any token while scanning for the next token" },
	{ "truncated",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes:\n"
	  "  - name: a\n"
	  "    joint: {type: revolute, axis: \"z\n",
	  "t.yaml:5:1: not valid YAML: found unexpected end of stream while scanning a quoted scalar" },
	{ "truncated flow",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, pivot: [0, 0,\n",
	  "t.yaml:3:1: not valid YAML: did not find expected node content while parsing a flow node" },
	{ "not a scene",
	  "just a sentence\n",
	  "t.yaml:1:1: expected a mapping for the scene, found 'just a sentence'" },
	{ "top level sequence",
	  "- timing\n",
	  "t.yaml:1:1: expected a mapping for the scene, found a sequence" },
	{ "empty",
	  "",
	  "t.yaml:1:1: empty scene file (expected a mapping with timing, nodes, strands)" },
	{ "two documents",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "---\n"
	  "timing: {frame_rate: 24, frames: [0, 10]}\n",
	  "t.yaml:3:1: a scene file holds one YAML document" },
	{ "strand unknown node",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: base}]\n"
	  "strands: [{node: bsae, keys: [{frame: 0, translate: [0, 0, 0]}]}]\n",
	  "t.yaml:3:18: strand for unknown node 'bsae' (did you mean 'base'?)" },
	{ "second strand",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: base}]\n"
	  "strands:\n"
	  "  - {node: base, keys: [{frame: 0, translate: [0, 0, 0]}]}\n"
	  "  - {node: base, keys: [{frame: 0, translate: [0, 0, 0]}]}\n",
	  "t.yaml:5:12: node 'base' already has a strand (at line 4)" },
	{ "empty keys",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: base}]\n"
	  "strands: [{node: base, keys: []}]\n",
	  "t.yaml:3:30: a strand needs at least one key" },
	{ "rpm bezier",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: prop, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: prop, interpolation: bezier, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 100}]}]\n",
	  "t.yaml:3:39: an rpm strand is integrated in closed form: use step, linear or hermite" },
	{ "rpm ease",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: prop, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: prop, interpolation: linear, ease: {in: 2, out: 2}, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 100}]}]\n",
	  "t.yaml:3:53: an rpm strand takes no ease (slow-in/slow-out is in its rpm keys)" },
	{ "rpm key ease",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: prop, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: prop, interpolation: linear, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 100, ease_in: 0.5}]}]\n",
	  "t.yaml:3:74: an rpm strand takes no ease_in or ease_out (shape the speed with keys)" },
	{ "rpm and angle mixed",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: prop, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: prop, keys: [{frame: 0, rpm: 0}, {frame: 10, angle: 100}]}]\n",
	  "t.yaml:3:70: this strand keys 'rpm' from its first key; a key cannot switch to 'angle'" },
	{ "ease fraction",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands: [{node: a, keys: [{frame: 0, angle: 0, ease_out: 1.5}, {frame: 10, angle: 100}]}]\n",
	  "t.yaml:3:59: ease_out is a fraction of the interval: 0 to 1, found 1.5" },
	{ "ease fractions sum",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands:\n"
	  "  - node: a\n"
	  "    keys:\n"
	  "      - {frame: 0, angle: 0, ease_out: 0.6}\n"
	  "      - {frame: 10, angle: 100, ease_in: 0.5}\n",
	  "t.yaml:7:9: ease_out 0.6 leaving frame 0 and ease_in 0.5 arriving at frame 10 add up to more than the interval" },
	{ "strand ease too long",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands:\n"
	  "  - node: a\n"
	  "    ease: {in: 6, out: 6}\n"
	  "    keys: [{frame: 0, angle: 0}, {frame: 10, angle: 100}]\n",
	  "t.yaml:5:11: ease in 6 + out 6 frames is longer than the keys' span of 10 frames" },
	{ "negative ease",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands:\n"
	  "  - node: a\n"
	  "    ease: {in: -1}\n"
	  "    keys: [{frame: 0, angle: 0}, {frame: 10, angle: 100}]\n",
	  "t.yaml:5:11: ease in and out are frames, not below 0" },
	{ "beta on hermite",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands:\n"
	  "  - node: a\n"
	  "    beta: {bias: 1, tension: 2}\n"
	  "    keys: [{frame: 0, angle: 0}, {frame: 10, angle: 100}]\n",
	  "t.yaml:5:11: 'beta' shapes a Beta-spline, but the interpolation is 'hermite'" },
	{ "beta bias zero",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands:\n"
	  "  - node: a\n"
	  "    interpolation: beta\n"
	  "    beta: {bias: 0, tension: 2}\n"
	  "    keys: [{frame: 0, angle: 0}, {frame: 10, angle: 100}]\n",
	  "t.yaml:6:18: beta bias must be above 0" },
	{ "camera without eye",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "camera:\n"
	  "  keys: [{frame: 0, look_at: [0, 0, 0]}]\n",
	  "t.yaml:3:10: missing field 'eye' in camera key" },
	{ "camera looking at itself",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "camera:\n"
	  "  keys:\n"
	  "    - {frame: 0, eye: [0, 1, 5], look_at: [0, 0, 0]}\n"
	  "    - {frame: 5, eye: [1, 1, 1], look_at: [1, 1, 1]}\n",
	  "t.yaml:5:43: look_at is the eye itself: the camera has no direction" },
	{ "cycle reversed",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "cycles: [{name: slices, first: 10, last: 1}]\n",
	  "t.yaml:2:42: cycle last 1 is before first 10" },
	{ "cycle skip zero",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "cycles: [{name: slices, first: 1, last: 10, skip: 0}]\n",
	  "t.yaml:2:51: '0' is out of range (1 to 1073741823)" },
	{ "cycle mode",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "cycles: [{name: slices, first: 1, last: 10, mode: bouncing}]\n",
	  "t.yaml:2:51: unknown cycle mode 'bouncing' (did you mean 'bounce'?)" },
	{ "attribute named like a node",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: dye}]\n"
	  "attributes: [{name: dye, keys: [{frame: 0, value: 1}]}]\n",
	  "t.yaml:3:14: attribute name 'dye' is already the name of a node" },
	{ "node named camera",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: camera}]\n",
	  "t.yaml:2:9: 'camera' names the camera's channels; call the node something else" },
	{ "limits on a free node",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: tool, limits: {max: 10}}]\n",
	  "t.yaml:2:30: limits apply to joints, but 'tool' is a free node (it has no joint)" },
	{ "limits reversed",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {min: 10, max: -10}}]\n",
	  "t.yaml:2:76: limit max -10 is below min 10" },
	{ "zero velocity limit",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 0}}]\n",
	  "t.yaml:2:72: velocity limit must be above zero" },
	{ "zero axis",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: [0, 0, 0]}}]\n",
	  "t.yaml:2:49: the joint axis must not be zero" },
	{ "rest on a free node",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, rest: 10}]\n",
	  "t.yaml:2:25: 'rest' is a joint's value, but 'a' is a free node (it has no joint)" },
	{ "rig: unknown device",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "outputs: [{channel: a.angle, device: amr, counts_per_unit: 100}]\n",
	  "t.yaml:5:38: unknown device 'amr'; did you mean 'arm'?" },
	{ "rig: unknown channel",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "outputs: [{channel: a.angel, device: arm, counts_per_unit: 100}]\n",
	  "t.yaml:5:21: unknown channel 'a.angel'; did you mean 'a.angle'?" },
	{ "rig: output without limits",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "outputs: [{channel: b.position, device: arm, counts_per_unit: 100}]\n",
	  "t.yaml:5:11: output 'b.position' needs velocity and acceleration limits (here or on its node): the pre-roll, the moves and every stop are planned with them" },
	{ "rig: axis twice",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "outputs: [{channel: a.angle, device: arm, counts_per_unit: 100},\n"
	  "          {channel: b.position, device: arm, axis: 0, counts_per_unit: 1,\n"
	  "           limits: {velocity: 1, acceleration: 1}}]\n",
	  "t.yaml:6:52: axis 0 of device 'arm' already drives 'a.angle' (line 5)" },
	{ "rig: zero counts per unit",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "outputs: [{channel: a.angle, device: arm, counts_per_unit: 0}]\n",
	  "t.yaml:5:60: counts_per_unit must be non-zero and below 2^31 counts per turn" },
	{ "rig: min_ferror above ferror",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "outputs: [{channel: a.angle, device: arm, counts_per_unit: 10, ferror: 1, min_ferror: 2}]\n",
	  "t.yaml:5:87: min_ferror 2 is above ferror 1" },
	{ "rig: unknown driver",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "devices: [{name: arm, driver: serial}]\n",
	  "t.yaml:2:31: unknown driver 'serial' (one of: sim, modbus, gpio, canopen, dmx)" },
	{ "rig: device twice",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "devices: [{name: arm, driver: sim},\n"
	  "          {name: arm, driver: gpio}]\n",
	  "t.yaml:3:18: device 'arm' is already listed (line 2)" },
	{ "rig: no devices",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "triggers: [{name: cam, device: io, line: 0}]\n",
	  "t.yaml:2:11: a rig needs its devices: section first" },
	{ "rig: pulse too long",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "triggers: [{name: cam, device: io, line: 0, pulse_ms: 45}]\n",
	  "t.yaml:5:55: a 45 ms pulse does not end before the next frame's (frames are 41.6667 ms apart, ticks 1 ms)" },
	{ "rig: offset of a frame",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "triggers: [{name: cam, device: io, line: 0, offset_ms: -50}]\n",
	  "t.yaml:5:56: offset -50 ms is a frame (41.6667 ms) or more" },
	{ "rig: offset of a frame's ticks",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "triggers: [{name: cam, device: io, line: 0, offset_ms: 41.2}]\n",
	  "t.yaml:5:56: offset 41.2 ms is 41 ticks: frame ticks may be only 41 apart" },
	{ "rig: output limits crossing its node's",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z},\n"
	  "         limits: {max: 5, velocity: 90, acceleration: 360}}]\n"
	  "devices: [{name: arm, driver: sim}]\n"
	  "outputs: [{channel: a.angle, device: arm, counts_per_unit: 1, limits: {min: 10}}]\n",
	  "t.yaml:5:11: limit max 5 is below min 10" },
	{ "rig: line twice",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "triggers: [{name: cam, device: io, line: 3}]\n"
	  "inputs: [{name: estop, device: io, line: 3, role: estop}]\n",
	  "t.yaml:6:42: line 3 of 'io' is trigger 'cam' already" },
	{ "rig: unknown role",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "inputs: [{name: estop, device: io, line: 1, role: e-stop}]\n",
	  "t.yaml:5:51: unknown input role 'e-stop' (did you mean 'estop'?)" },
	{ "rig: polarity not a bool",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "inputs: [{name: estop, device: io, line: 1, role: estop, active_low: yes}]\n",
	  "t.yaml:5:70: expected true or false, found 'yes'" },
	{ "canopen: settings missing",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: s, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: s, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 5}]}]\n"
	  "devices: [{name: bus, driver: canopen}]\n",
	  "t.yaml:5:11: a device of driver canopen needs its canopen: section" },
	{ "canopen: settings on another driver",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: s, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: s, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 5}]}]\n"
	  "devices: [{name: bus, driver: sim, canopen: {interface: can0, bitrate: 500000}}]\n",
	  "t.yaml:5:45: a canopen: section belongs to a device of driver canopen" },
	{ "canopen: bitrate missing",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: s, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: s, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 5}]}]\n"
	  "devices: [{name: bus, driver: canopen, canopen: {interface: can0}}]\n",
	  "t.yaml:5:49: missing field 'bitrate' in canopen" },
	{ "canopen: bitrate too high",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: s, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: s, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 5}]}]\n"
	  "devices: [{name: bus, driver: canopen, canopen: {interface: can0, bitrate: 2000000}}]\n",
	  "t.yaml:5:76: '2000000' is out of range (10000 to 1000000)" },
	{ "canopen: SYNC COB-ID",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: s, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: s, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 5}]}]\n"
	  "devices: [{name: bus, driver: canopen, canopen: {interface: can0, bitrate: 500000, sync_id: 0x900}}]\n",
	  "t.yaml:5:93: '0x900' is not an 11-bit COB-ID (1 to 0x7ff)" },
	{ "canopen: interface name",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: s, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: s, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 5}]}]\n"
	  "devices: [{name: bus, driver: canopen, canopen: {interface: a-very-long-interface-name, bitrate: 500000}}]\n",
	  "t.yaml:5:61: interface 'a-very-long-interface-name': a network interface name (1 to 15 characters: can0, vcan0) or sim" },
	{ "canopen: axis on a bus",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: s, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: s, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 5}]}]\n"
	  "devices: [{name: bus, driver: canopen, canopen: {interface: can0, bitrate: 500000}}]\n"
	  "outputs: [{channel: a.angle, device: bus, axis: 1, counts_per_unit: 100}]\n",
	  "t.yaml:6:49: an output on canopen device 'bus' is placed by node:, not axis:" },
	{ "canopen: node missing",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: s, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: s, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 5}]}]\n"
	  "devices: [{name: bus, driver: canopen, canopen: {interface: can0, bitrate: 500000}}]\n"
	  "outputs: [{channel: a.angle, device: bus, counts_per_unit: 100}]\n",
	  "t.yaml:6:11: missing field 'node' in output on a canopen device" },
	{ "canopen: node range",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: s, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: s, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 5}]}]\n"
	  "devices: [{name: bus, driver: canopen, canopen: {interface: can0, bitrate: 500000}}]\n"
	  "outputs: [{channel: a.angle, device: bus, node: 128, counts_per_unit: 100}]\n",
	  "t.yaml:6:49: '128' is out of range (1 to 127)" },
	{ "canopen: node twice",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: s, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: s, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 5}]}]\n"
	  "devices: [{name: bus, driver: canopen, canopen: {interface: can0, bitrate: 500000}}]\n"
	  "outputs: [{channel: a.angle, device: bus, node: 3, counts_per_unit: 100},\n"
	  "          {channel: s.angle, device: bus, node: 3, counts_per_unit: 100,\n"
	  "           limits: {velocity: 10, acceleration: 10}}]\n",
	  "t.yaml:7:49: node 3 of device 'bus' already drives 'a.angle' (line 6)" },
	{ "canopen: mode of a position",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: s, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: s, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 5}]}]\n"
	  "devices: [{name: bus, driver: canopen, canopen: {interface: can0, bitrate: 500000}}]\n"
	  "outputs: [{channel: a.angle, device: bus, node: 3, mode: csv, counts_per_unit: 100}]\n",
	  "t.yaml:6:58: mode csv: 'a.angle' is not a spin speed; it needs mode csp" },
	{ "canopen: mode of a speed",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: s, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: s, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 5}]}]\n"
	  "devices: [{name: bus, driver: canopen, canopen: {interface: can0, bitrate: 500000}}]\n"
	  "outputs: [{channel: s.rpm, device: bus, node: 4, mode: csp, counts_per_unit: 100,\n"
	  "           limits: {velocity: 10, acceleration: 10}}]\n",
	  "t.yaml:6:56: mode csp: 's.rpm' is a spin speed; it needs mode csv" },
	{ "canopen: node on another driver",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: s, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: s, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 5}]}]\n"
	  "devices: [{name: arm, driver: sim}]\n"
	  "outputs: [{channel: a.angle, device: arm, node: 3, counts_per_unit: 100}]\n",
	  "t.yaml:6:49: node: and mode: place an output on a canopen device; 'arm' is not one" },
	{ "canopen: bus too slow",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: s, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: s, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 5}]}]\n"
	  "devices: [{name: bus, driver: canopen, canopen: {interface: can0, bitrate: 250000}}]\n"
	  "outputs: [{channel: a.angle, device: bus, node: 3, counts_per_unit: 100}]\n",
	  "t.yaml:5:49: canopen bus 'bus': the worst case of a tick is 350 bits (1 drive, bit stuffing) of the 250 a tick holds at 250000 bit/s and 1000 ticks/s: 140%, above 70%; lower tick_hz, drive fewer outputs on this bus or raise the bitrate" },
	{ "canopen: SYNC on a node",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: s, joint: {type: revolute, axis: x}}]\n"
	  "strands: [{node: s, keys: [{frame: 0, rpm: 0}, {frame: 10, rpm: 5}]}]\n"
	  "devices: [{name: bus, driver: canopen, canopen: {interface: can0, bitrate: 1000000, sync_id: 0x83}}]\n"
	  "outputs: [{channel: a.angle, device: bus, node: 3, counts_per_unit: 100}]\n",
	  "t.yaml:5:49: canopen bus 'bus': sync_id 0x83 is an identifier of node 3" },
	{ "rig: chip on a simulated device",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "devices: [{name: io, driver: sim, chip: gpiochip0}]\n",
	  "t.yaml:2:41: chip: and allow_sleeping_chip: are for a device with driver gpio" },
	{ "rig: a named line twice",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}}]\n"
	  "devices: [{name: io, driver: gpio}]\n"
	  "triggers: [{name: cam, device: io, line: SHUTTER}]\n"
	  "inputs: [{name: estop, device: io, line: SHUTTER, role: estop}]\n",
	  "t.yaml:5:42: line 'SHUTTER' of 'io' is trigger 'cam' already" },
	/* the edges where numbers come in (README, "Scene files" and "The rig"):
	 * each range, at the key that leaves it */
	{ "velocity limit below the least",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 1e-300}}]\n",
	  "t.yaml:2:72: velocity limit 1e-300 is below 1e-06 degrees a second (too slow to plan a move with)" },
	{ "acceleration limit below the least",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: prismatic, axis: z}, limits: {velocity: 1, acceleration: 1e-7}}]\n",
	  "t.yaml:2:90: acceleration limit 1e-07 is below 1e-06 scene units a second squared (too slow to plan a move with)" },
	{ "velocity limit beyond the core",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 1e300}}]\n",
	  "t.yaml:2:72: 1e+300 is outside the core's range (|value| < 3.865470566e+11 degrees)" },
	{ "rig: output velocity limit below the least",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}]\n"
	  "outputs: [{channel: b.position, device: arm, counts_per_unit: 1, limits: {velocity: 1e-9, acceleration: 1}}]\n",
	  "t.yaml:5:85: velocity limit 1e-09 is below 1e-06 scene units a second (too slow to plan a move with)" },
	{ "rig: counts per unit below the least",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}]\n"
	  "outputs: [{channel: a.angle, device: arm, counts_per_unit: 1e-9}]\n",
	  "t.yaml:5:60: counts_per_unit 1e-09 is 3.6e-07 counts per turn, below 0.0001" },
	{ "rig: ferror beyond the core",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}]\n"
	  "outputs: [{channel: a.angle, device: arm, counts_per_unit: 10, ferror: 1e300}]\n",
	  "t.yaml:5:72: 1e+300 is outside the core's range (|value| < 3.865470566e+11 degrees)" },
	{ "rig: in_position beyond the core",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}]\n"
	  "outputs: [{channel: b.position, device: arm, counts_per_unit: 1, in_position: 1e300, limits: {velocity: 1, acceleration: 1}}]\n",
	  "t.yaml:5:79: 1e+300 is outside the core's range (|value| < 1073741824 scene units)" },
	{ "rig: home beyond int64 counts",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}]\n"
	  "outputs: [{channel: a.angle, device: arm, counts_per_unit: 5000000, offset: 8000000000000000000, home: 300000000000}]\n",
	  "t.yaml:5:104: home 3e+11 is 9.5e+18 counts, beyond +-9e18" },
	{ "rig: sim bandwidth above the most",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim, sim: {bandwidth: 1e300}}]\n"
	  "outputs: [{channel: a.angle, device: arm, counts_per_unit: 100}]\n",
	  "t.yaml:4:53: bandwidth 1e+300 is above 10000 Hz" },
	{ "rig: sim damping below the least",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim, sim: {damping: 0.001}}]\n"
	  "outputs: [{channel: a.angle, device: arm, counts_per_unit: 100}]\n",
	  "t.yaml:4:51: damping 0.001 is below 0.01" },
	{ "rig: sim limit_factor above the most",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim, sim: {limit_factor: 1e6}}]\n"
	  "outputs: [{channel: a.angle, device: arm, counts_per_unit: 100}]\n",
	  "t.yaml:4:56: limit_factor 1e+06 is above 1000" },
	{ "rig: sim exposure above a day",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim, sim: {exposure_ms: 1e300}}]\n"
	  "outputs: [{channel: a.angle, device: arm, counts_per_unit: 100}]\n",
	  "t.yaml:4:55: exposure_ms 1e+300 is above 8.64e+07 ms" },
	{ "rig: sim readout above a day",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim, sim: {readout_ms: 1e9}}]\n"
	  "outputs: [{channel: a.angle, device: arm, counts_per_unit: 100}]\n",
	  "t.yaml:4:54: readout_ms 1e+09 is above 8.64e+07 ms" },
	{ "rig: pulse beyond a frame",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}]\n"
	  "outputs: [{channel: a.angle, device: arm, counts_per_unit: 100}]\n"
	  "triggers: [{name: cam, device: arm, line: 0, pulse_ms: 1e300}]\n",
	  "t.yaml:6:56: a 1e+300 ms pulse does not end before the next frame's (frames are 41.6667 ms apart, ticks 1 ms)" },
	{ "rig: trigger offset beyond a frame",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: arm, driver: sim}]\n"
	  "outputs: [{channel: a.angle, device: arm, counts_per_unit: 100}]\n"
	  "triggers: [{name: cam, device: arm, line: 0, offset_ms: -1e300}]\n",
	  "t.yaml:6:57: offset -1e+300 ms is a frame (41.6667 ms) or more" },
	{ "modbus: response timeout above a minute",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: d, driver: modbus, modbus: {tcp: {host: h}, unit: 1, response_timeout_ms: 1e300, axes: [{register: 0}]}}]\n"
	  "outputs: [{channel: a.angle, device: d, counts_per_unit: 100}]\n",
	  "t.yaml:4:92: response_timeout_ms 1e+300 is outside 0.001 to 60000 ms" },
	{ "modbus: byte timeout below a microsecond",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: d, driver: modbus, modbus: {tcp: {host: h}, unit: 1, byte_timeout_ms: 1e-9, axes: [{register: 0}]}}]\n"
	  "outputs: [{channel: a.angle, device: d, counts_per_unit: 100}]\n",
	  "t.yaml:4:88: byte_timeout_ms 1e-09 is outside 0.001 to 60000 ms" },
	{ "modbus: update rate below the least",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: d, driver: modbus, modbus: {tcp: {host: h}, unit: 1, update_hz: 1e-300, axes: [{register: 0}]}}]\n"
	  "outputs: [{channel: a.angle, device: d, counts_per_unit: 100}]\n",
	  "t.yaml:4:82: update_hz 1e-300 is outside 0.01 to 1048576 Hz" },
	{ "modbus: silence above an hour",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: d, driver: modbus, modbus: {tcp: {host: h}, unit: 1, max_silence_ms: 1e300, axes: [{register: 0}]}}]\n"
	  "outputs: [{channel: a.angle, device: d, counts_per_unit: 100}]\n",
	  "t.yaml:4:87: max_silence_ms 1e+300 is outside 0.001 to 3600000 ms" },
	{ "canopen: home beyond 32 bits",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}},\n"
	  "        {name: b, joint: {type: prismatic, axis: x}}]\n"
	  "devices: [{name: bus, driver: canopen, canopen: {interface: can0, bitrate: 1000000}}]\n"
	  "outputs: [{channel: a.angle, device: bus, node: 3, counts_per_unit: 100000, home: 30000}]\n",
	  "t.yaml:5:83: home 30000 is 3e+09 counts, beyond a CiA 402 drive's 32-bit position" },
	/* ---- systems, aims, channel patterns, DMX ---- */
	{ "surface: bezier net",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "surfaces: [{name: s, basis: bezier, control: [5, 4], samples: [2, 2],\n"
	  "            keys: [{frame: 0, heights: [[0]]}]}]\n",
	  "t.yaml:2:46: a net of Bezier patches has 3p + 1 points a side (4, 7, 10, ...), found [5, 4]" },
	{ "surface: heights rows",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "surfaces: [{name: s, control: [2, 2], samples: [2, 2],\n"
	  "            keys: [{frame: 0, heights: [[0, 0]]}]}]\n",
	  "t.yaml:3:40: expected 2 rows (control: [2, 2]), found 1" },
	{ "surface: heights and points",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "surfaces: [{name: s, control: [1, 1], samples: [2, 2],\n"
	  "            keys: [{frame: 0, heights: [[0]], points: [[[0, 0, 0]]]}]}]\n",
	  "t.yaml:3:20: a surface key gives heights (y above the rest net) or points (every control point), one of them" },
	{ "surface: limits by channel",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "surfaces: [{name: s, control: [1, 1], samples: [2, 2], keys: [{frame: 0, heights: [[0]]}],\n"
	  "            limits: {h: {min: 0}}}]\n",
	  "t.yaml:3:22: unknown key 'h' in limits (by channel: x, y, ...) (valid keys: x, y, z)" },
	{ "particles: emit or lattice",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "particles: [{name: p, pool: 4}]\n",
	  "t.yaml:2:13: particles are emitted (emit: and pool:) or a lattice (lattice:), one of them" },
	{ "particles: a force on scripted ones",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "particles: [{name: p, pool: 4, emit: {keys: [{frame: 0, rate: 1}]}, drag: 0.1}]\n",
	  "t.yaml:2:75: 'drag' is a force: it moves newtonian particles (motion: newtonian), not scripted ones" },
	{ "particles: lifetime zero",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "particles: [{name: p, pool: 4, emit: {keys: [{frame: 0, rate: 1, lifetime: [0, 1]}]}}]\n",
	  "t.yaml:2:38: lifetime 0 at frame 0: a lifetime is above 0 seconds" },
	{ "particles: age beyond a life",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "particles: [{name: p, pool: 4, emit: {keys: [{frame: 0, rate: 1}]},\n"
	  "             over_life: {keys: [{age: 1.5, alpha: 0}]}}]\n",
	  "t.yaml:3:39: age is a fraction of a life: 0 to 1" },
	{ "particles: pin off the lattice",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "particles: [{name: c, motion: newtonian, lattice: {size: [2, 2]}, springs: {stiffness: 1},\n"
	  "             pins: [{at: [3, 1]}]}]\n",
	  "t.yaml:3:26: pin at [3, 1] is off the 2 x 2 lattice (rows and columns count from 1)" },
	{ "particles: unstable lattice",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "particles: [{name: c, motion: newtonian, step_hz: 10, lattice: {size: [2, 2]},\n"
	  "             springs: {stiffness: 1000}}]\n",
	  "t.yaml:2:13: 'c': unstable at its step: the springs' stiffness (per mass) and step want w h < 1.8 for the highest frequency w = sqrt(2 k n) of a point with n springs, and h (drag + 2 n damping) < 1: raise step_hz or soften the springs" },
	{ "flock: speed required",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "flocks: [{name: f, members: 3, acceleration: 1}]\n",
	  "t.yaml:2:10: missing field 'speed' in flock" },
	{ "system name taken",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: f}]\n"
	  "flocks: [{name: f, members: 3, speed: 1, acceleration: 1}]\n",
	  "t.yaml:3:10: system name 'f' is already the name of a node" },
	{ "aim: unknown target",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "flocks: [{name: f, members: 3, speed: 1, acceleration: 1}]\n"
	  "aims: [{name: h, at: [0, 5, 0], target: f.7}]\n",
	  "t.yaml:3:41: 'f.7': 'f' has items 0 to 2" },
	{ "aim: count beyond the items",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "flocks: [{name: f, members: 3, speed: 1, acceleration: 1}]\n"
	  "aims: [{name: h, count: 4, at: [0, 5, 0], target: f}]\n",
	  "t.yaml:3:51: 'f' has 3 items, fewer than the aims" },
	{ "outputs: pattern matches nothing",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "flocks: [{name: f, members: 3, speed: 1, acceleration: 1}]\n"
	  "devices: [{name: d, driver: sim}]\n"
	  "outputs: [{channel: \"f.*.q\", device: d, counts_per_unit: 1}]\n",
	  "t.yaml:4:21: channel pattern 'f.*.q' matches no channel of the scene ('*' stands for a part between dots: skin.*.*.y)" },
	{ "outputs: stride without a pattern",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "flocks: [{name: f, members: 3, speed: 1, acceleration: 1, limits: {x: {velocity: 1, acceleration: 1}}}]\n"
	  "devices: [{name: d, driver: sim}]\n"
	  "outputs: [{channel: f.0.x, device: d, counts_per_unit: 1, stride: 2}]\n",
	  "t.yaml:4:67: stride spaces the outputs of a channel pattern (a channel with '*')" },
	{ "dmx: destination required",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "devices: [{name: l, driver: dmx, dmx: {universes: [1]}}]\n",
	  "t.yaml:2:39: missing field 'destination' in dmx" },
	{ "dmx: multicast is sACN's",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "devices: [{name: l, driver: dmx, dmx: {protocol: artnet, destination: multicast, universes: [1]}}]\n",
	  "t.yaml:2:71: 'multicast' is sACN's universe groups; Art-Net takes an address" },
	{ "dmx: slot beyond 512",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "attributes: [{name: a, keys: [{frame: 0, value: 0}]}]\n"
	  "devices: [{name: l, driver: dmx, dmx: {destination: 10.0.0.1, universes: [1]}}]\n"
	  "outputs: [{channel: a, device: l, address: 512, bits: 16, counts_per_unit: 1,\n"
	  "           limits: {velocity: 1, acceleration: 1}}]\n",
	  "t.yaml:4:44: 2 slots from address 512 go past slot 512" },
	{ "dmx: two on one slot",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "attributes: [{name: a, keys: [{frame: 0, value: 0}]}, {name: b, keys: [{frame: 0, value: 0}]}]\n"
	  "devices: [{name: l, driver: dmx, dmx: {destination: 10.0.0.1, universes: [1]}}]\n"
	  "outputs: [{channel: a, device: l, address: 1, bits: 16, counts_per_unit: 1,\n"
	  "           limits: {velocity: 1, acceleration: 1}},\n"
	  "          {channel: b, device: l, address: 2, counts_per_unit: 1,\n"
	  "           limits: {velocity: 1, acceleration: 1}}]\n",
	  "t.yaml:6:11: slot 2 of universe 1 is already taken by 'a'" },
	{ "dmx: unknown universe",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "attributes: [{name: a, keys: [{frame: 0, value: 0}]}]\n"
	  "devices: [{name: l, driver: dmx, dmx: {destination: 10.0.0.1, universes: [1]}}]\n"
	  "outputs: [{channel: a, device: l, universe: 2, address: 1, counts_per_unit: 1,\n"
	  "           limits: {velocity: 1, acceleration: 1}}]\n",
	  "t.yaml:4:45: universe 2 is not among the device's (dmx: universes:)" },
	{ "dmx: axis on a dmx device",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "attributes: [{name: a, keys: [{frame: 0, value: 0}]}]\n"
	  "devices: [{name: l, driver: dmx, dmx: {destination: 10.0.0.1, universes: [1]}}]\n"
	  "outputs: [{channel: a, device: l, axis: 1, counts_per_unit: 1,\n"
	  "           limits: {velocity: 1, acceleration: 1}}]\n",
	  "t.yaml:4:41: an output on dmx device 'l' is placed by universe: and address:, not axis:" },
	{ "tangent on a linear strand",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands:\n"
	  "  - {node: a, interpolation: linear, keys: [{frame: 0, angle: 1, out: 2}, {frame: 5, angle: 0}]}\n",
	  "t.yaml:4:45: 'in' or 'out' is a tangent, which only a hermite curve takes (this one is 'linear')" },
	{ "tangent without its value",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a}]\n"
	  "strands:\n"
	  "  - node: a\n"
	  "    keys: [{frame: 0, scale: [1, 1, 1], translate_in: [0, 0, 0]}]\n",
	  "t.yaml:5:55: 'translate_in' is the tangent of 'translate', which this key does not set" },
	{ "cubic rotation with ease",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a}]\n"
	  "strands:\n"
	  "  - node: a\n"
	  "    rotation: cubic\n"
	  "    keys: [{frame: 0, quat: [1, 0, 0, 0], ease_out: 0.5}, {frame: 5, quat: [0, 1, 0, 0]}]\n",
	  "t.yaml:6:12: a cubic or step rotation takes no ease_in or ease_out (shape it with quat_in and quat_out)" },
	{ "quat tangent on slerp",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a}]\n"
	  "strands:\n"
	  "  - node: a\n"
	  "    keys: [{frame: 0, quat: [1, 0, 0, 0], quat_out: [0, 0, 0, 0]}, {frame: 5, quat: [0, 1, 0, 0]}]\n",
	  "t.yaml:5:12: 'quat_in' and 'quat_out' are tangents of a cubic rotation; this strand's rotation is slerp or squad" },
	{ "unknown group interpolation",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a}]\n"
	  "strands:\n"
	  "  - node: a\n"
	  "    interpolation: {translate: linear, rotate: step}\n"
	  "    keys: [{frame: 0, translate: [0, 0, 0]}]\n",
	  "t.yaml:5:40: unknown key 'rotate' in interpolation (valid keys: translate, scale, shear)" },
	{ "tangent on a step group",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a}]\n"
	  "strands:\n"
	  "  - node: a\n"
	  "    interpolation: {translate: step}\n"
	  "    keys: [{frame: 0, translate: [0, 0, 0], translate_out: [1, 0, 0]}, {frame: 4, translate: [1, 0, 0]}]\n",
	  "t.yaml:6:12: 'translate_in' or 'translate_out' is a tangent, which only a hermite curve takes (this one is 'step')" },
	{ "tangent beyond the range",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
	  "strands:\n"
	  "  - {node: a, keys: [{frame: 0, angle: 1, out: 3e11}, {frame: 5, angle: 0}]}\n",
	  "t.yaml:4:22: a tangent of this key times its interval reaches beyond the core's range (below 2^31 turns)" },
	{ "mimic of an unknown joint",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes:\n"
	  "  - {name: a, joint: {type: revolute, axis: z}}\n"
	  "  - {name: b, joint: {type: revolute, axis: z}, mimic: {joint: c}}\n",
	  "t.yaml:4:64: mimic of unknown joint 'c'" },
	{ "mimic with a strand",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes:\n"
	  "  - {name: a, joint: {type: revolute, axis: z}}\n"
	  "  - {name: b, joint: {type: revolute, axis: z}, mimic: {joint: a, multiplier: -1}}\n"
	  "strands:\n"
	  "  - {node: b, keys: [{frame: 0, angle: 1}]}\n",
	  "t.yaml:6:5: 'b' mimics 'a': its motion is the master's, it takes no strand" },
	{ "mimic of a free node",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes:\n"
	  "  - {name: a}\n"
	  "  - {name: b, joint: {type: revolute, axis: z}, mimic: {joint: a}}\n",
	  "t.yaml:4:56: 'b' mimics 'a', which is not a joint of its own (a free node or a mimic)" },
	{ "mimic with a rest",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes:\n"
	  "  - {name: a, joint: {type: revolute, axis: z}}\n"
	  "  - {name: b, joint: {type: revolute, axis: z}, rest: 3, mimic: {joint: a}}\n",
	  "t.yaml:4:55: 'b' mimics a joint: its rest is the master's, mapped (give 'offset' instead)" },
	{ "boards: unknown device",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "boards:\n  - {name: l, address: 10.0.0.1, lead: true, devices: [amr]}\n  - {name: r, address: 10.0.0.2, devices: [io]}\n",
	  "t.yaml:5:56: unknown device 'amr'; did you mean 'arm'?" },
	{ "boards: a device twice",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "boards:\n  - {name: l, address: 10.0.0.1, lead: true, devices: [arm]}\n  - {name: r, address: 10.0.0.2, devices: [arm, io]}\n",
	  "t.yaml:6:44: device 'arm' is already on board 'l' (line 5): a device is driven by one board" },
	{ "boards: a device on none",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "boards:\n  - {name: l, address: 10.0.0.1, lead: true, devices: [arm]}\n  - {name: r, address: 10.0.0.2, devices: []}\n",
	  "t.yaml:5:3: device 'io' is on no board: every device is driven by one" },
	{ "boards: no leader",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "boards:\n  - {name: l, address: 10.0.0.1, devices: [arm]}\n  - {name: r, address: 10.0.0.2, devices: [io]}\n",
	  "t.yaml:5:3: no board leads: give one of them `lead: true`" },
	{ "boards: two leaders",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "boards:\n  - {name: l, address: 10.0.0.1, lead: true, devices: [arm]}\n  - {name: r, address: 10.0.0.2, lead: true, devices: [io]}\n",
	  "t.yaml:6:40: board 'r' leads too: one board leads (board 'l', line 5)" },
	{ "boards: one board",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "boards:\n  - {name: l, address: 10.0.0.1, lead: true, devices: [arm, io]}\n",
	  "t.yaml:5:3: boards: names at least two boards (one board plays the whole rig without it)" },
	{ "boards: same address",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "boards:\n  - {name: l, address: 10.0.0.1, lead: true, devices: [arm]}\n  - {name: r, address: 10.0.0.1, devices: [io]}\n",
	  "t.yaml:6:24: board 'r' has the address and port of board 'l' (line 5)" },
	{ "boards: same name",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "boards:\n  - {name: l, address: 10.0.0.1, lead: true, devices: [arm]}\n  - {name: l, address: 10.0.0.2, devices: [io]}\n",
	  "t.yaml:6:12: board 'l' is already listed (line 5)" },
	{ "boards: no address",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "boards:\n  - {name: l, lead: true, devices: [arm]}\n  - {name: r, address: 10.0.0.2, devices: [io]}\n",
	  "t.yaml:5:5: missing field 'address' in board" },
	{ "boards: port",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "boards:\n  - {name: l, address: 10.0.0.1, port: 70000, lead: true, devices: [arm]}\n  - {name: r, address: 10.0.0.2, devices: [io]}\n",
	  "t.yaml:5:40: '70000' is out of range (1 to 65535)" },
	{ "lockstep: lost within a heartbeat",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "boards:\n  - {name: l, address: 10.0.0.1, lead: true, devices: [arm]}\n  - {name: r, address: 10.0.0.2, devices: [io]}\nlockstep: {heartbeat_ms: 100, lost_ms: 150}\n",
	  "t.yaml:7:40: lost_ms 150: at least two heartbeats (heartbeat_ms 100), or one lost datagram loses a board" },
	{ "lockstep: unknown key",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "boards:\n  - {name: l, address: 10.0.0.1, lead: true, devices: [arm]}\n  - {name: r, address: 10.0.0.2, devices: [io]}\nlockstep: {heartbeat: 100}\n",
	  "t.yaml:7:12: unknown key 'heartbeat' in lockstep (did you mean 'heartbeat_ms'?)" },
	{ "lockstep without boards",
	  "timing: {frame_rate: 24, frames: [0, 10]}\n"
	  "nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, acceleration: 360}}]\n"
	  "devices: [{name: arm, driver: sim}, {name: io, driver: sim}]\n"
	  "lockstep: {heartbeat_ms: 100}\n",
	  "t.yaml:4:11: lockstep: goes with boards:" },
};

#define NCASES (sizeof(cases) / sizeof(cases[0]))

static void format_err(char *buf, size_t size, const char *path, const struct load_err *e)
{
	snprintf(buf, size, "%s:%u:%u: %s", path, e->line, e->col, e->msg);
}

static void test_golden(void **state)
{
	size_t i, failed = 0;

	for (i = 0; i < NCASES; i++) {
		struct scene_file sf;
		struct load_err e;
		char got[400];
		int rc = scene_file_parse(&sf, "t.yaml", cases[i].yaml, strlen(cases[i].yaml), &e);

		/* what only the build finds (a system the core refuses), at its place */
		if (rc == 0) {
			struct scene_built b;

			rc = scene_file_build(&sf, &b, &e);
			if (rc == 0)
				scene_built_free(&b);
		}
		format_err(got, sizeof(got), "t.yaml", &e);
		if (rc == 0 || strcmp(got, cases[i].expect) ||
		    (rc != -EINVAL && rc != -ERANGE && rc != -EBADMSG) || e.line == 0) {
			print_error("case '%s':\n  expected %s\n  got      %s (rc %d)\n",
				    cases[i].name, cases[i].expect, rc ? got : "success", rc);
			failed++;
		}
		scene_file_free(&sf);
	}
	assert_int_equal(failed, 0);
}

/* A Bezier strand is one curve through all its keys: at most 32. */
static void test_bezier_keys(void **state)
{
	char yaml[8192];
	size_t o = 0;
	struct scene_file sf;
	struct load_err e;
	int i;

	o += (size_t)snprintf(yaml + o, sizeof(yaml) - o,
			      "timing: {frame_rate: 24, frames: [0, 10]}\n"
			      "nodes: [{name: a, joint: {type: revolute, axis: z}}]\n"
			      "strands:\n  - node: a\n    interpolation: bezier\n    keys:\n");
	for (i = 0; i < 33; i++)
		o += (size_t)snprintf(yaml + o, sizeof(yaml) - o,
				      "      - {frame: %d, angle: %d}\n", i, i % 7);
	assert_int_equal(scene_file_parse(&sf, "t.yaml", yaml, o, &e), -EINVAL);
	assert_int_equal(e.line, 6 + 33);
	assert_int_equal(e.col, 9);
	assert_string_equal(e.msg, "a bezier strand takes at most 32 keys (it is one curve through all of them)");
}

/* The first error wins, and its code says what kind of failure it is. */
static void test_io(void **state)
{
	struct scene_file sf;
	struct load_err e;

	assert_int_equal(scene_file_load(&sf, "/nonexistent/scene.yaml", &e), -ENOENT);
	assert_int_equal(e.line, 0);
	assert_string_equal(e.msg, "cannot open: No such file or directory");
	scene_file_free(&sf);
	assert_int_equal(scene_file_load(&sf, "/", &e) < 0, 1);
	scene_file_free(&sf);
}

static int write_corpus(const char *dir)
{
	size_t i;

	mkdir(dir, 0777);
	for (i = 0; i < NCASES; i++) {
		char path[512];
		FILE *f;

		snprintf(path, sizeof(path), "%s/error-%02zu.yaml", dir, i);
		f = fopen(path, "w");
		if (!f || fputs(cases[i].yaml, f) < 0 || fclose(f)) {
			perror(path);
			return 1;
		}
	}
	return 0;
}

int main(int argc, char **argv)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_golden),
		cmocka_unit_test(test_bezier_keys),
		cmocka_unit_test(test_io),
	};

	if (argc == 3 && !strcmp(argv[1], "--write-corpus"))
		return write_corpus(argv[2]);
	return cmocka_run_group_tests(tests, NULL, NULL);
}
