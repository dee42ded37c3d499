/* SPDX-License-Identifier: BSD-2-Clause */
/* Benchmark 2: one doStep of many cycles through the
 * FMU's real FMI 3 binary (dlopen), recorded (record.enabled, every cycle's
 * row in record.data) and not recorded (fast-forward where it pays), from the
 * same state (an FMU state taken after initialization), in turns run by run
 * (bench/engine.py makes min / median / max of the runs).
 *
 *   bench_dostep FMU.so TOKEN SCRIPT MEMORY_WORDS CYCLES RUNS
 *
 * instantiates with the script (its tables hold the profile) and
 * record.capacity CYCLES, and prints one line per run and path:
 * "unrecorded SECONDS" or "recorded SECONDS", the time of the doStep (and,
 * recorded, of fetching record.data). Each run checks that both paths end in
 * the same chip time and commanded positions. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "fmi3Functions.h"

/* the process's CPU time: on a shared machine a run descheduled for a while
 * would otherwise count the wait; the work is single-threaded */
static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void logger(fmi3InstanceEnvironment e, fmi3Status s, fmi3String category, fmi3String message)
{
    (void)e; (void)category;
    if (s >= fmi3Error)
        fprintf(stderr, "FMU error: %s\n", message);
}

static void *so;

static void *symbol(const char *name)
{
    void *f = dlsym(so, name);
    if (!f) {
        fprintf(stderr, "no %s in the FMU\n", name);
        exit(1);
    }
    return f;
}

#define CALL(f, ...) do { if (((f##TYPE *)symbol(#f))(__VA_ARGS__) > fmi3Warning) { \
    fprintf(stderr, "%s failed\n", #f); exit(1); } } while (0)

/* value references (modelDescription/variables.csv) */
enum { CYCLE_TIME = 1, MEMORY_SIZE = 2, SCRIPT = 4, CHIP_TIME = 10, RECORD_ENABLED = 20, RECORD_CAPACITY = 21,
       RECORD_DATA = 22, COMMANDED_POSITION = 100, AXIS_STRIDE = 100 };

/* chip time and the four commanded positions */
static void outputs(fmi3Instance c, fmi3Int32 out[5])
{
    const fmi3ValueReference chipTime = CHIP_TIME;
    fmi3ValueReference position[4];
    fmi3UInt32 time;
    int n;
    for (n = 0; n < 4; n++)
        position[n] = COMMANDED_POSITION + AXIS_STRIDE * n;
    CALL(fmi3GetUInt32, c, &chipTime, 1, &time, 1);
    CALL(fmi3GetInt32, c, position, 4, out + 1, 4);
    out[0] = (fmi3Int32)time;
}

int main(int argc, char **argv)
{
    fmi3Instance c;
    fmi3FMUState start = NULL;
    const fmi3ValueReference memorySize = MEMORY_SIZE, script = SCRIPT, enabled = RECORD_ENABLED,
                             capacity = RECORD_CAPACITY, data = RECORD_DATA, cycleTime = CYCLE_TIME;
    fmi3Int32 words, cycles, seen[2][5];
    fmi3Float64 dt;
    fmi3Boolean on = fmi3True, off = fmi3False, eventNeeded, terminate, early;
    fmi3Float64 last;
    int runs, run, path, n;

    if (argc != 7) {
        fprintf(stderr, "usage: bench_dostep FMU.so TOKEN SCRIPT MEMORY_WORDS CYCLES RUNS\n");
        return 2;
    }
    words = atoi(argv[4]);
    cycles = atoi(argv[5]);
    runs = atoi(argv[6]);
    if (!(so = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL))) {
        fprintf(stderr, "%s\n", dlerror());
        return 1;
    }
    c = ((fmi3InstantiateCoSimulationTYPE *)symbol("fmi3InstantiateCoSimulation"))(
        "bench", argv[2], "", fmi3False, fmi3False, fmi3False, fmi3False, NULL, 0, NULL, logger, NULL);
    if (!c)
        return 1;
    CALL(fmi3EnterInitializationMode, c, fmi3False, 0, 0, fmi3False, 0);
    CALL(fmi3SetInt32, c, &memorySize, 1, &words, 1);
    CALL(fmi3SetInt32, c, &capacity, 1, &cycles, 1);
    CALL(fmi3SetString, c, &script, 1, (const fmi3String *)&argv[3], 1);
    CALL(fmi3ExitInitializationMode, c);
    CALL(fmi3GetFloat64, c, &cycleTime, 1, &dt, 1);
    /* the script's cycle 0 calls run in the first doStep: one cycle, untimed, then the state to start from */
    CALL(fmi3DoStep, c, 0, dt, fmi3True, &eventNeeded, &terminate, &early, &last);
    CALL(fmi3GetFMUState, c, &start);

    for (run = -1; run < runs; run++) {          /* run -1: a warm-up (record.data's pages, caches), not printed */
        for (path = 0; path < 2; path++) {
            double t0, t1;
            CALL(fmi3SetFMUState, c, start);
            CALL(fmi3SetBoolean, c, &enabled, 1, path ? &on : &off, 1);
            t0 = now();
            CALL(fmi3DoStep, c, dt, cycles * dt, fmi3True, &eventNeeded, &terminate, &early, &last);
            if (path) {
                fmi3Binary row;
                size_t size;
                CALL(fmi3GetBinary, c, &data, 1, &size, &row, 1);
                if (size != (size_t)cycles * 13 * 4) {
                    fprintf(stderr, "record.data holds %zu bytes\n", size);
                    return 1;
                }
            }
            t1 = now();
            if (run >= 0)
                printf("%s %.9f\n", path ? "recorded" : "unrecorded", t1 - t0);
            outputs(c, seen[path]);
        }
        for (n = 0; n < 5; n++)
            if (seen[0][n] != seen[1][n]) {
                fprintf(stderr, "the recorded and the unrecorded doStep end differently\n");
                return 1;
            }
        fflush(stdout);
    }
    ((fmi3FreeFMUStateTYPE *)symbol("fmi3FreeFMUState"))(c, &start);
    ((fmi3FreeInstanceTYPE *)symbol("fmi3FreeInstance"))(c);
    return 0;
}
