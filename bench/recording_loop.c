/* SPDX-License-Identifier: BSD-2-Clause */
/* The recording benchmark's baseline (bench/recording.py): a bare C loop that
 * writes the rows Chip.run(cycles, record=names) returns - the same values in
 * the same packed layout - with nothing between the chip and the rows: no FMU,
 * no FMI call, no chunks, no copy.
 *
 * The values come from the chip core itself (fmu_src/chip, built as the FMUs
 * build it), run every cycle as bench/engine.c runs it: no other C loop
 * computes the chip's rows, so none is faster and still right. The chip is
 * set up as a fresh FMU instance is (its memory size, its sample time, the
 * loopback) with the profile the harness loads (pmdfmu.profile's
 * load_external_profile and start_external_profile: five buffers per axis from
 * ID 2 and address 0x200 up, all axes started at once), written into its
 * state directly: the chip's input, not part of the run.
 *
 * Rows (fmu_src/fmi/record.c's layout, the harness's numpy records):
 *   commanded  the chip time, then the commanded position, velocity and
 *              acceleration of the four axes: int32 each, 52 bytes - the
 *              engine's own row (pmd_chip_run_every_cycle's record)
 *   status     the chip time (int32), then per axis the commanded position,
 *              velocity and acceleration (int32), position, velocity and
 *              acceleration (float64, pmd_commanded_reals at the sample
 *              time's cycle) and the activity status (uint16), packed: 156
 *              bytes (pmdfmu.profile.record_outputs' order)
 *
 *   bench_recording_loop TABLE
 *
 * TABLE: the segment table, "ROWS" on the first line, then per axis 1..4
 * ROWS lines "position velocity acceleration jerk time" (raw words). Then
 * reads commands from stdin, one a line, and answers each with a line:
 *   run SET CYCLES reused   the rows into a buffer a former run wrote (its
 *                           pages mapped): prints the run's seconds
 *   run SET CYCLES fresh    malloc, the rows, free, as numpy's fresh result
 *                           (whose memory goes when the timed call drops it):
 *                           prints the seconds of all three
 *   dump SET CYCLES PATH    the rows written to PATH (the bench compares them
 *                           with Chip.run's bytes): prints "ok"
 * Times are wall-clock (CLOCK_MONOTONIC), as the bench's perf_counter. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "chip.h"
#include "profile.h"
#include "status.h"

#define AXES 4
#define MEMORY_WORDS 0x4000      /* a fresh instance's memorySize (fmu_src/fmi/instance.c) */
#define SAMPLE_TIME 100          /* us: a fresh instance's cycleTime 1e-4 s */
#define TABLE_ADDRESS 0x200      /* load_external_profile's memory_start */
#define STATUS_ROW (4 + AXES * (3 * 4 + 3 * 8 + 2))

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- the chip with the profile started ---- */

/* the most segments per axis whose five buffers of four axes fit the memory from TABLE_ADDRESS on */
#define MAX_ROWS ((MEMORY_WORDS - TABLE_ADDRESS) / (AXES * PMD_FUNCTIONS))

static uint32_t table[AXES][PMD_FUNCTIONS][MAX_ROWS];
static uint32_t rows;

static void read_table(const char *path)
{
    FILE *f = fopen(path, "r");
    uint32_t a, i;
    int function;
    if (!f || fscanf(f, "%u", &rows) != 1 || rows == 0 || rows > MAX_ROWS) {
        fprintf(stderr, "%s: no segment table of 1..%d rows\n", path, MAX_ROWS);
        exit(2);
    }
    for (a = 0; a < AXES; a++)
        for (i = 0; i < rows; i++)
            for (function = 0; function < PMD_FUNCTIONS; function++) {
                long long v;
                if (fscanf(f, "%lld", &v) != 1) {
                    fprintf(stderr, "%s: axis %u, row %u: not 5 numbers\n", path, a + 1, i);
                    exit(2);
                }
                table[a][function][i] = (uint32_t)v;
            }
    fclose(f);
}

static PmdChip chip;
static uint32_t memory[MEMORY_WORDS];

static void start_chip(void)
{
    uint32_t address = TABLE_ADDRESS;
    int a, f;
    memset(&chip, 0, sizeof chip);
    memset(memory, 0, sizeof memory);
    chip.s.loopback = 1;
    pmd_chip_init(&chip, memory, MEMORY_WORDS);
    chip.s.sampleTime = SAMPLE_TIME;
    for (a = 0; a < AXES; a++)
        for (f = 0; f < PMD_FUNCTIONS; f++) {
            int id = PMD_FIRST_PROFILE_BUFFER + PMD_FUNCTIONS * a + f;
            chip.s.buffer[id].start = address;
            chip.s.buffer[id].length = rows;
            memcpy(memory + address, table[a][f], sizeof(uint32_t) * rows);
            chip.s.axis[a].bufferOfFunction[f] = (int16_t)id;
            address += rows;
        }
    for (a = 0; a < AXES; a++) {
        chip.s.axis[a].buffered.profileMode = PMDExternalProfile;
        if (pmd_update(&chip, a) != 0) {
            fprintf(stderr, "Update refused\n");
            exit(1);
        }
    }
}

/* ---- the rows ---- */

/* A status + Reals row after each cycle (pmd_chip_run_every_cycle_with_rows: the
 * chip's own loop, deciding once what cannot happen in the run). */
static void status_row(void *context)
{
    unsigned char **at = (unsigned char **)context, *p = *at;
    PmdCommandedReals reals;
    int32_t time = pmd_int32(chip.s.time);
    int a;
    pmd_commanded_reals(&chip, SAMPLE_TIME / 1e6, &reals);
    memcpy(p, &time, 4);
    p += 4;
    for (a = 0; a < AXES; a++) {
        const PmdTrajectory *t = &chip.s.axis[a].trajectory;
        int32_t words[3];
        uint16_t activity = pmd_activity_status(&chip, a);
        words[0] = t->position;
        words[1] = pmd_commanded_velocity(t);
        words[2] = pmd_commanded_acceleration(t);
        memcpy(p, words, sizeof words);
        memcpy(p + 12, &reals.position[a], 8);
        memcpy(p + 20, &reals.velocity[a], 8);
        memcpy(p + 28, &reals.acceleration[a], 8);
        memcpy(p + 36, &activity, 2);
        p += 38;
    }
    *at = p;
}

static int status_set(const char *set)
{
    if (strcmp(set, "status") == 0)
        return 1;
    if (strcmp(set, "commanded") == 0)
        return 0;
    fprintf(stderr, "no column set %s (commanded, status)\n", set);
    exit(2);
}

static size_t row_bytes(int status)
{
    return status ? STATUS_ROW : sizeof(int32_t) * PMD_RECORD_WORDS;
}

static void record(int status, int64_t cycles, unsigned char *out)
{
    if (status)
        pmd_chip_run_every_cycle_with_rows(&chip, cycles, status_row, &out);
    else
        pmd_chip_run_every_cycle(&chip, cycles, (int32_t *)out);
}

/* Memory for a result, advised as numpy advises its arrays' (huge pages from
 * 4 MiB up, numpy/core/src/multiarray/alloc.c): a fresh result's pages cost
 * what numpy's cost. */
static unsigned char *allocate(size_t bytes)
{
    unsigned char *p = malloc(bytes);
    if (!p) {
        fprintf(stderr, "no memory for %zu bytes\n", bytes);
        exit(1);
    }
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (bytes >= ((size_t)1 << 22)) {
        size_t skip = 4096 - (size_t)p % 4096;       /* from the next page boundary on */
        madvise(p + skip, bytes - skip, MADV_HUGEPAGE);
    }
#endif
    return p;
}

int main(int argc, char **argv)
{
    char line[4096], set[32], mode[32], path[3000];
    unsigned char *reused = NULL;
    size_t reusedBytes = 0;
    long long cycles;
    if (argc != 2) {
        fprintf(stderr, "usage: bench_recording_loop TABLE\n");
        return 2;
    }
    read_table(argv[1]);
    while (fgets(line, sizeof line, stdin)) {
        int status;
        size_t bytes;
        if (sscanf(line, "run %31s %lld %31s", set, &cycles, mode) == 3 && cycles > 0) {
            double t0;
            status = status_set(set);
            bytes = (size_t)cycles * row_bytes(status);
            if (strcmp(mode, "reused") == 0) {
                if (reusedBytes != bytes) {         /* a buffer of the result's size: the same huge-page advice */
                    free(reused);
                    reused = allocate(bytes);
                    reusedBytes = bytes;
                    start_chip();
                    record(status, cycles, reused);      /* its pages mapped, as a result run() filled */
                }
                start_chip();
                t0 = now();
                record(status, cycles, reused);
                printf("%.9f\n", now() - t0);
            } else if (strcmp(mode, "fresh") == 0) {
                unsigned char *out;
                start_chip();
                t0 = now();
                out = allocate(bytes);
                record(status, cycles, out);
                free(out);
                printf("%.9f\n", now() - t0);
            } else {
                fprintf(stderr, "no mode %s (reused, fresh)\n", mode);
                return 2;
            }
        } else if (sscanf(line, "dump %31s %lld %2999s", set, &cycles, path) == 3 && cycles > 0) {
            unsigned char *out;
            FILE *f;
            status = status_set(set);
            bytes = (size_t)cycles * row_bytes(status);
            out = allocate(bytes);
            start_chip();
            record(status, cycles, out);
            f = fopen(path, "wb");
            if (!f || fwrite(out, 1, bytes, f) != bytes || fclose(f) != 0) {
                fprintf(stderr, "%s: cannot write the rows\n", path);
                return 1;
            }
            free(out);
            printf("ok\n");
        } else {
            fprintf(stderr, "not a command: %s", line);
            return 2;
        }
        fflush(stdout);
    }
    free(reused);
    return 0;
}
