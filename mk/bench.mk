# mk/bench.mk - `make bench`: build every benchmark program, then run them
# one after the other (never two at once, even under make -j: they time
# themselves). Each prints BENCH lines. Not part of `make test`.
#
#   make bench           all of them
#   make bench-fixmath   libfixmath's Q16.16 against double (fix.h's choice)
#   make bench-motion    the core against its double twin (bench/motion_bench.c)
#   make bench-systems   surfaces, particles and flocks against double twins
#                        (bench/sys_bench.c)
#   make bench-play      the play loop against cyclictest, CPU per tick (mk/bench-play.sh)
#   make bench-count     instructions per node per tick of every scene, core
#                        and twin, counted by callgrind (bench/scene_count.c)
#   make bench-time      the issue's scenes, core and twin, by the clock from
#                        fresh copies of scene_count, medians (mk/bench-time.sh)
#   make bench-ab AB_OTHER=DIR
#                        this build's core against another tree's build in DIR,
#                        pairs of plays in one process (bench/scene_ab.c)

.PHONY: bench-fixmath bench-motion bench-play bench-count bench-systems bench-time bench-ab

BENCH_PROGS := $(BUILD)/bench/fixmath_chain $(BUILD)/bench/motion_bench $(BUILD)/bench/sys_bench
# What the timed programs run under. On a shared machine
#   make bench-motion BENCH_PREFIX='chrt -f 50 taskset -c 1'
# keeps the other processes off their CPU while they time (root or rtprio):
# the README's figures, with run-to-run spreads of a few percent instead of
# tens.
BENCH_PREFIX ?=

bench: $(BENCH_PROGS) $(BUILD)/bench/scene_count $(BUILD)/strand $(BUILD)/bench/sleep_tick | \
		$(BUILD)/.deps-bench-play $(BUILD)/.deps-bench-count
	$(Q)for p in $(BENCH_PROGS); do $(BENCH_PREFIX) $$p || exit 1; done
	$(Q)sh mk/bench-count.sh $(BUILD)/bench/scene_count $(COUNT_SCENES)
	$(Q)BENCH_PREFIX='$(BENCH_PREFIX)' sh mk/bench-time.sh $(TIME_ROUNDS) 40 "$(TIME_SCENES)" \
		-- $(BUILD)/bench/scene_count
	$(Q)sh mk/bench-play.sh $(BUILD)/strand $(RUN_SCENE) $(BUILD)/bench-play \
		$(BUILD)/bench/sleep_tick

bench-fixmath: $(BUILD)/bench/fixmath_chain
	$(Q)$(BENCH_PREFIX) $<

bench-motion: $(BUILD)/bench/motion_bench
	$(Q)$(BENCH_PREFIX) $<

BENCH_CFLAGS := -std=c11 -O2 $(WARN) -Werror

# libfixmath's Q16.16 on a 5-joint chain, against double (the measurement
# behind fix.h's choice of Q32.32). Debian ships only a static library,
# /usr/lib/<triplet>/liblibfixmath.a, with its headers in
# /usr/include/libfixmath/.
$(BUILD)/bench/fixmath_chain: bench/fixmath_chain.c | $(BUILD)/.deps-bench
	@mkdir -p $(@D)
	$(Q)$(CC) $(BENCH_CFLAGS) $< -llibfixmath -lm -o $@

# ---- the motion benchmark ---------------------------------------------------------
# Its own sources and the double twin (bench/dbl_*.c), the scene generator
# and the tests' reference (tests/), all -O2 and without sanitizers (timing
# sanitized code would time the sanitizer); the core and the scene builder
# are the -O2 objects `make` builds. The tests' headers pull in cmocka's
# (testutil.h), hence its package and no -Wpedantic, as for the tests.
# No contraction into fused multiply-adds, as for firmware/: the double
# side rounds the same way on every target.
MB_SRC      := bench/motion_bench.c bench/scene_bench.c bench/pipe_bench.c \
               bench/prim_bench.c bench/dbl_scene.c bench/dbl_curve.c bench/dbl_mat.c \
               tests/synth.c tests/ref_scene.c tests/ref_curve.c tests/ref_mat.c
MB_OBJ      := $(MB_SRC:%.c=$(BUILD)/bench/%.o)
MB_CFLAGS    = -std=gnu11 -D_GNU_SOURCE -O2 $(filter-out -Wpedantic,$(WARN)) -Werror \
               -ffp-contract=off -iquote . -iquote firmware -iquote bench -iquote tests \
               $(shell pkg-config --cflags cmocka 2>/dev/null)
MB_LINK     := $(BUILD)/firmware/scene/scene_build.o $(BUILD)/firmware/scene/scene_build_sys.o \
               $(BUILD)/firmware/scene/scene_desc.o \
               $(BUILD)/libmotion.a

$(BUILD)/bench/%.o: %.c | $(BUILD)/.deps-test
	@mkdir -p $(@D)
	$(Q)$(CC) $(MB_CFLAGS) $(DEPFLAGS) -c $< -o $@

$(BUILD)/bench/motion_bench: $(MB_OBJ) $(MB_LINK)
	$(Q)$(CC) $^ -lm -o $@

# ---- the systems ---------------------------------------------------------------------
SB_OBJ := $(BUILD)/bench/bench/sys_bench.o $(BUILD)/bench/bench/dbl_curve.o

$(BUILD)/bench/sys_bench: $(SB_OBJ) $(MB_LINK)
	$(Q)$(CC) $^ -lm -o $@

bench-systems: $(BUILD)/bench/sys_bench
	$(Q)$<

# ---- the play loop ------------------------------------------------------------------
# Its wake-up latency on the wall clock against cyclictest (Debian's
# rt-tests), taking turns in 1 s rounds for 30 s each at 1 kHz and the same
# priority, and the CPU time per tick of the robot arm on the simulated rig
# beside that of a thread that only sleeps (bench/sleep_tick.c).
# BENCH_PLAY_STRESS=2 runs it all again under stress-ng (Debian's).
DEB_BENCH_PLAY := rt-tests stress-ng
$(BUILD)/.deps-bench-play: mk/deps.sh mk/bench.mk $(BUILD)/.deps-build
	$(Q)sh mk/deps.sh $(DEB_BENCH_PLAY) && touch $@
$(BUILD)/bench/sleep_tick: bench/sleep_tick.c | $(BUILD)/.deps-build
	@mkdir -p $(@D)
	$(Q)$(CC) -std=gnu11 -O2 $(WARN) -Werror $< -o $@
bench-play: $(BUILD)/strand $(BUILD)/bench/sleep_tick | $(BUILD)/.deps-bench-play
	$(Q)sh mk/bench-play.sh $(BUILD)/strand $(RUN_SCENE) $(BUILD)/bench-play \
		$(BUILD)/bench/sleep_tick

# ---- instruction counts ------------------------------------------------------------
# The scenes of scene_bench.c played once under callgrind, which counts only
# scene_count_play(): instructions per node per tick, steadier than any
# timing on a shared machine (mk/bench-count.sh). Needs Debian's valgrind,
# which mk/deps.sh installs for these targets only.
SC_SRC := bench/scene_count.c bench/scene_pick.c bench/dbl_scene.c bench/dbl_curve.c \
          bench/dbl_mat.c tests/synth.c
SC_OBJ := $(SC_SRC:%.c=$(BUILD)/bench/%.o)
COUNT_SCENES := arm joints1000 random1000 kind_step1000 kind_linear1000 kind_hermite1000 \
                kind_bspline1000 kind_beta1000 kind_bezier1000 rev_axis1000 rev_tilt1000 \
                pri_axis1000 pri_tilt1000

$(BUILD)/bench/scene_count: $(SC_OBJ) $(MB_LINK)
	$(Q)$(CC) $^ -lm -o $@

DEB_BENCH_COUNT := valgrind
$(BUILD)/.deps-bench-count: mk/deps.sh mk/bench.mk $(BUILD)/.deps-build
	$(Q)sh mk/deps.sh $(DEB_BENCH_COUNT) && touch $@

bench-count: $(BUILD)/bench/scene_count | $(BUILD)/.deps-bench-count
	$(Q)sh mk/bench-count.sh $< $(COUNT_SCENES)

# ---- the clock, from fresh copies ---------------------------------------------------
# The issue's scenes timed by scene_count itself (the fastest of 40 plays a
# run), core and twin from the same copy, TIME_ROUNDS rounds each from a
# fresh copy, medians (mk/bench-time.sh). TIME_OTHER: other builds'
# scene_count to run side by side, interleaved (an A/B of two commits:
# make BUILD=/tmp/a build of the one, then TIME_OTHER=/tmp/a/bench/scene_count).
TIME_SCENES ?= arm joints1000 random1000
TIME_ROUNDS ?= 9
TIME_OTHER ?=
bench-time: $(BUILD)/bench/scene_count
	$(Q)BENCH_PREFIX='$(BENCH_PREFIX)' sh mk/bench-time.sh $(TIME_ROUNDS) 40 "$(TIME_SCENES)" \
		-- $< $(TIME_OTHER)

# ---- the core against another build of it, in one process ---------------------------
# Pairs of plays side by side, the ratio of each pair (bench/scene_ab.c): the
# machine's drift cancels within a pair, where separate runs need many rounds.
# AB_OTHER: the other tree's build directory (in that tree: make BUILD=DIR
# DIR/libmotion.a); this build against itself (the default) is the control.
AB_OTHER ?= $(BUILD)
AB_SCENES ?= arm joints1000 random1000
AB_PAIRS ?= 150
AB_OBJ := $(BUILD)/bench/bench/scene_ab.o $(BUILD)/bench/bench/scene_pick.o \
          $(BUILD)/bench/tests/synth.o
bench-ab: $(AB_OBJ) $(MB_LINK)
	$(Q)BENCH_PREFIX='$(BENCH_PREFIX)' sh mk/bench-ab.sh '$(AB_OTHER)/libmotion.a' \
		'$(AB_SCENES)' $(AB_PAIRS) -- $(CC) $(AB_OBJ) $(MB_LINK) -lm
