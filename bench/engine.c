/* SPDX-License-Identifier: BSD-2-Clause */
/* Benchmark 1: the chip core running external profiles
 * on 4 axes, every cycle's commanded position, velocity and acceleration
 * stored (pmd_chip_run_every_cycle's record rows, as a recording doStep stores them),
 * against a bare C loop of the same exact recurrence storing the same rows,
 * measured in the same run.
 *
 * The profiles are random and never repeat within a run (a fixed-seed PRNG
 * fills tables longer than the run), so neither side gets help from a branch
 * predictor that has learnt the table: one family of 1-7-cycle segments (a
 * segment read every 4 cycles on average), one of 1000-2000-cycle segments
 * (the integration step alone). Velocities, accelerations and jerks have
 * random fraction bits: the position's carry is as random as in a real
 * profile's.
 *
 * The bare loop keeps the core's exact representation (chip_types.h) and
 * floors the position's fraction with each of several divisions, its loop
 * over the axes as written and unrolled (as the core's cycle() has it); the
 * fastest of them is the baseline (bench/engine.py takes it). Every one must
 * store the core's rows bit for bit, or the program fails. The contenders
 * take turns within each run (the engine, then every bare loop, run after
 * run), so that the shared machine's load falls on all alike; bench/engine.py
 * makes min / median / max of the runs.
 *
 *   bench_engine RUNS [FAMILY [NAME]]
 *
 * prints one line per family, run and contender: "FAMILY NAME SECONDS", the
 * time of CYCLES cycles of 4 axes. FAMILY (short, long) and NAME (engine, or
 * a bare loop's name: then the engine is not checked) narrow it down, for a
 * profiler. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "chip.h"

#define AXES 4
#ifndef CYCLES
#define CYCLES 1000000
#endif

/* the process's CPU time: on a shared machine a run descheduled for a while
 * would otherwise count the wait; the work is single-threaded */
static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- the profiles ---- */

/* The tables as the chip's buffers hold them (seed 000): per axis and
 * function (position, velocity and acceleration in 16.16, jerk in 0.32,
 * time in cycles) a column of `count` words, at table + (5 axis + function)
 * count. The chip's memory is a copy; the bare loop reads the same layout
 * (the chip's input, not a choice of either side). */
typedef struct {
    const char *name;
    uint32_t shortest, longest;      /* segment time, cycles */
    uint32_t count;                  /* segments per axis: more than the run reads */
    int32_t *table;
} Family;

static int32_t *column(const Family *fam, int axis, int function)
{
    return fam->table + (size_t)(PMD_FUNCTIONS * axis + function) * fam->count;
}

static uint64_t prng = 0x9E3779B97F4A7C15u;

/* splitmix64: a fixed seed, so every run and both sides see the same profile */
static uint64_t next_random(void)
{
    uint64_t z = (prng += 0x9E3779B97F4A7C15u);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    return z ^ (z >> 31);
}

/* a uniform value in -2^(bits-1) .. 2^(bits-1) - 1 */
static int32_t random_signed(int bits)
{
    return (int32_t)(next_random() >> (64 - bits)) - (int32_t)(1u << (bits - 1));
}

static void make_family(Family *fam)
{
    int a;
    /* enough segments for the run and one more: the table never wraps */
    fam->count = (uint32_t)(CYCLES / fam->shortest + 2);
    fam->table = malloc(sizeof(int32_t) * AXES * PMD_FUNCTIONS * fam->count);
    for (a = 0; a < AXES; a++) {
        uint64_t cycles = 0;
        uint32_t i;
        for (i = 0; i < fam->count; i++) {
            column(fam, a, PMDBufferFunctionPosition)[i] = (int32_t)(next_random() >> 32);
            column(fam, a, PMDBufferFunctionVelocity)[i] = random_signed(24);     /* +-128 counts/cycle */
            column(fam, a, PMDBufferFunctionAcceleration)[i] = random_signed(12); /* +-1/32 count/cycle^2 */
            column(fam, a, PMDBufferFunctionJerk)[i] = random_signed(20);         /* +-2^-13 count/cycle^3 */
            column(fam, a, PMDBufferFunctionTime)[i] =
                (int32_t)(fam->shortest + next_random() % (fam->longest - fam->shortest + 1));
            cycles += (uint64_t)column(fam, a, PMDBufferFunctionTime)[i];
        }
        if (cycles <= CYCLES) {
            fprintf(stderr, "table too short\n");
            exit(1);
        }
    }
}

/* ---- the baseline: the recurrence alone, in the core's exact representation ---- */

/* chip_types.h: position in whole counts + a fraction in U = 2^-32/6 count
 * (0 <= frac < 6 * 2^32); velocity and acceleration in whole counts + a
 * fraction in 2^-33 count (0 <= fraction < 2^33). */
typedef struct { int64_t frac, v, vf, a, af; const int32_t *next[PMD_FUNCTIONS]; int32_t pos, j; uint32_t left; } Plain;

#define U PMD_U_PER_COUNT
#define ONE ((int64_t)1 << 33)

/* The position's carry floor(f / U) for the f an integration step forms:
 * frac + 3 (vf + af/2) + j lies in [-2^31, 18 * 2^32 + 2^31), so the carry is
 * -1 .. 3. The contenders (GCC shifts negative values arithmetically): */

/* C's division, truncating, with the fix-up for negative values */
static inline int64_t floor_c(int64_t f)
{
    int64_t q = f / U;
    return q - (f % U < 0);
}

/* the core's own (chip_types.h): a floored shift and an unsigned division by 3 */
static inline int64_t floor_core(int64_t f)
{
    return pmd_floor_counts(f);
}

/* floor(f / 2^33) in -1 .. 9, then / 3 by a multiplication: (y + 3) * 11 >> 5 = floor((y + 3) / 3) for 0 <= y + 3 < 30 */
static inline int64_t floor_multiply(int64_t f)
{
    return (((f >> 33) + 3) * 11 >> 5) - 1;
}

/* comparisons against the carry's four thresholds, no division at all */
static inline int64_t floor_compare(int64_t f)
{
    return (int64_t)(f >= U) + (f >= 2 * U) + (f >= 3 * U) - (f < 0);
}

/* The loop over the axes as written, or unrolled (as chip.c's cycle() has it) */
#define ROLLED
#if defined(__clang__)
#define UNROLLED _Pragma("clang loop unroll(full)")
#elif defined(__GNUC__) && __GNUC__ >= 8
#define UNROLLED _Pragma("GCC unroll 4")
#else
#define UNROLLED
#endif

/* One run of the bare loop with floor division FLOOR: CYCLES cycles of 4
 * axes, a row per cycle in the layout of pmd_chip_record. */
#define BARE_LOOP(NAME, FLOOR, UNROLL)                                                                       \
    static void NAME(const Family *fam, int32_t *out)                                                        \
    {                                                                                                        \
        Plain p[AXES];                                                                                       \
        long k;                                                                                              \
        int a, f;                                                                                            \
        memset(p, 0, sizeof p);                                                                              \
        for (a = 0; a < AXES; a++)                                                                           \
            for (f = 0; f < PMD_FUNCTIONS; f++)                                                              \
                p[a].next[f] = column(fam, a, f);                                                            \
        for (k = 0; k < CYCLES; k++) {                                                                       \
            out[0] = (int32_t)k;                                                                             \
            UNROLL                                                                                           \
            for (a = 0; a < AXES; a++) {                                                                     \
                Plain *x = &p[a];                                                                            \
                if (x->left == 0) {                                                                          \
                    int64_t v = *x->next[PMDBufferFunctionVelocity]++;                                       \
                    int64_t acc = *x->next[PMDBufferFunctionAcceleration]++;                                 \
                    x->pos = *x->next[PMDBufferFunctionPosition]++;                                          \
                    x->frac = 0;                                                                             \
                    x->v = v >> 16; x->vf = (v & 0xFFFF) << 17;                                              \
                    x->a = acc >> 16; x->af = (acc & 0xFFFF) << 17;                                          \
                    x->j = *x->next[PMDBufferFunctionJerk]++;                                                \
                    x->left = (uint32_t)*x->next[PMDBufferFunctionTime]++;                                   \
                } else {                                                                                     \
                    /* P += V + A/2 + J/6: 2^-33 count is 3 U, J/6 is j U */                                 \
                    int64_t hc = x->a >> 1, hf = (x->af >> 1) | ((x->a & 1) << 32);                          \
                    int64_t f = x->frac + 3 * (x->vf + hf) + x->j, carry = FLOOR(f), s;                      \
                    x->frac = f - carry * U;                                                                 \
                    x->pos = (int32_t)((uint32_t)x->pos + (uint32_t)(x->v + hc + carry));                    \
                    /* V += A + J/2 (j in 2^-33 count), A += J (2 j) */                                      \
                    s = x->vf + x->af + x->j;                                                                \
                    x->v += x->a + (s >> 33); x->vf = s & (ONE - 1);                                         \
                    s = x->af + 2 * (int64_t)x->j;                                                           \
                    x->a += s >> 33; x->af = s & (ONE - 1);                                                  \
                }                                                                                            \
                x->left--;                                                                                   \
                out[1 + 3 * a] = x->pos;                                                                     \
                out[2 + 3 * a] = (int32_t)((uint32_t)((uint64_t)x->v << 16) | (uint32_t)(x->vf >> 17));                \
                out[3 + 3 * a] = (int32_t)((uint32_t)((uint64_t)x->a << 16) | (uint32_t)(x->af >> 17));                \
            }                                                                                                \
            out += PMD_RECORD_WORDS;                                                                         \
        }                                                                                                    \
    }

BARE_LOOP(bare_c, floor_c, ROLLED)
BARE_LOOP(bare_core, floor_core, ROLLED)
BARE_LOOP(bare_multiply, floor_multiply, ROLLED)
BARE_LOOP(bare_compare, floor_compare, ROLLED)
BARE_LOOP(bare_c_unrolled, floor_c, UNROLLED)
BARE_LOOP(bare_core_unrolled, floor_core, UNROLLED)
BARE_LOOP(bare_multiply_unrolled, floor_multiply, UNROLLED)
BARE_LOOP(bare_compare_unrolled, floor_compare, UNROLLED)

static const struct {
    const char *name;
    void (*run)(const Family *, int32_t *);
} contenders[] = {
    {"bare-c-division", bare_c},
    {"bare-core-division", bare_core},
    {"bare-multiply", bare_multiply},
    {"bare-compare", bare_compare},
    {"bare-c-division-unrolled", bare_c_unrolled},
    {"bare-core-division-unrolled", bare_core_unrolled},
    {"bare-multiply-unrolled", bare_multiply_unrolled},
    {"bare-compare-unrolled", bare_compare_unrolled},
};
#define CONTENDERS (int)(sizeof contenders / sizeof contenders[0])

/* ---- the chip core ---- */

/* The chip with the family's tables in its memory, one buffer per axis and
 * function (IDs 2..21), every axis started on its external profile. */
static void load_chip(PmdChip *chip, uint32_t *memory, const Family *fam)
{
    uint32_t words = AXES * PMD_FUNCTIONS * fam->count;
    int a, f;
    memset(chip, 0, sizeof *chip);
    pmd_chip_init(chip, memory, words);
    chip->s.loopback = 1;
    for (a = 0; a < AXES; a++)
        for (f = 0; f < PMD_FUNCTIONS; f++) {
            int id = PMD_FIRST_PROFILE_BUFFER + PMD_FUNCTIONS * a + f;
            PmdBuffer *b = &chip->s.buffer[id];
            b->start = (uint32_t)(PMD_FUNCTIONS * a + f) * fam->count;
            b->length = fam->count;
            memcpy(memory + b->start, column(fam, a, f), sizeof(int32_t) * fam->count);
            chip->s.axis[a].bufferOfFunction[f] = (int16_t)id;
        }
    for (a = 0; a < AXES; a++) {
        chip->s.axis[a].buffered.profileMode = PMDExternalProfile;
        if (pmd_update(chip, a) != 0) {
            fprintf(stderr, "Update refused\n");
            exit(1);
        }
    }
}

static double run_chip(const Family *fam, uint32_t *memory, int32_t *out)
{
    static PmdChip chip;
    double t0;
    load_chip(&chip, memory, fam);
    t0 = now();
    pmd_chip_run_every_cycle(&chip, CYCLES, out);
    return now() - t0;
}

int main(int argc, char **argv)
{
    static Family families[2] = {{"short", 1, 7, 0, NULL}, {"long", 1000, 2000, 0, NULL}};
    size_t bytes = sizeof(int32_t) * PMD_RECORD_WORDS * CYCLES;
    int32_t *core = malloc(bytes), *bare = malloc(bytes);
    int runs = argc > 1 ? atoi(argv[1]) : 5, run, i, c;
    const char *family = argc > 2 ? argv[2] : NULL, *only = argc > 3 ? argv[3] : NULL;
    if (!core || !bare || runs < 1) {
        fprintf(stderr, "usage: bench_engine RUNS\n");
        return 2;
    }
    memset(core, 0, bytes);             /* the pages exist before anything is timed */
    memset(bare, 0, bytes);
    for (i = 0; i < 2; i++) {
        Family *fam = &families[i];
        uint32_t *memory;
        if (family && strcmp(family, fam->name) != 0)
            continue;
        make_family(fam);
        memory = calloc((size_t)AXES * PMD_FUNCTIONS * fam->count, sizeof(uint32_t));
        if (!memory)
            return 1;
        run_chip(fam, memory, core);             /* a warm-up: caches, branch history of the code */
        for (run = 0; run < runs; run++) {
            if (!only || strcmp(only, "engine") == 0)
                printf("%s engine %.9f\n", fam->name, run_chip(fam, memory, core));
            for (c = 0; c < CONTENDERS; c++) {
                double t0;
                if (only && strcmp(only, contenders[c].name) != 0)
                    continue;
                t0 = now();
                contenders[c].run(fam, bare);
                printf("%s %s %.9f\n", fam->name, contenders[c].name, now() - t0);
                if (!only && memcmp(bare, core, bytes) != 0) {
                    fprintf(stderr, "%s segments: the core and %s disagree\n", fam->name, contenders[c].name);
                    return 1;
                }
            }
            fflush(stdout);
        }
        free(memory);
    }
    return 0;
}
