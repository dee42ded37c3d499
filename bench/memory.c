/* SPDX-License-Identifier: BSD-2-Clause */
/* Benchmark 6: the heap one FMU instance holds, and what its doSteps
 * allocate. Drives the real FMI 2 binary (dlopen) and counts, from outside,
 * every malloc, calloc and realloc the FMU makes (this program's own
 * definitions take the FMU's calls: linked with -rdynamic; glibc's
 * __libc_* functions do the work) and the bytes in use (mallinfo2).
 *
 *   memory FMU.so GUID SCRIPT
 *
 * instantiates with memorySize 0x4000 and the script (its profile runs during
 * the steps), runs 200 doSteps of 1000 cycles, enables record.enabled, runs
 * 50 recorded doSteps of 1000 cycles, and prints
 *   instanceBytes doStepAllocations recordBytes recordedDoStepAllocations */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <malloc.h>
#include <stdio.h>
#include <stdlib.h>

#include "fmi2Functions.h"

extern void *__libc_malloc(size_t);
extern void *__libc_calloc(size_t, size_t);
extern void *__libc_realloc(void *, size_t);

static long allocations;

void *malloc(size_t n)
{
    allocations++;
    return __libc_malloc(n);
}

void *calloc(size_t n, size_t size)
{
    allocations++;
    return __libc_calloc(n, size);
}

void *realloc(void *p, size_t n)
{
    allocations++;
    return __libc_realloc(p, n);
}

static size_t in_use(void)
{
    struct mallinfo2 m = mallinfo2();
    return m.uordblks + m.hblkhd;
}

static void logger(fmi2ComponentEnvironment e, fmi2String n, fmi2Status s, fmi2String c, fmi2String m, ...)
{
    (void)e; (void)n; (void)c;
    if (s >= fmi2Error)
        fprintf(stderr, "FMU error: %s\n", m);
}

static const fmi2CallbackFunctions callbacks = {logger, NULL, NULL, NULL, NULL};

#define CALL(f, ...) do { if (((f##TYPE *)symbol(so, #f))(__VA_ARGS__) > fmi2Warning) { \
    fprintf(stderr, "%s failed\n", #f); return 1; } } while (0)

static void *symbol(void *so, const char *name)
{
    void *f = dlsym(so, name);
    if (!f) {
        fprintf(stderr, "no %s in the FMU\n", name);
        exit(1);
    }
    return f;
}

/* value references of the FMI 2 model description (modelDescription/variables.csv) */
enum { MEMORY_SIZE = 2, SCRIPT = 4, RECORD_ENABLED = 20 };

int main(int argc, char **argv)
{
    void *so;
    fmi2Component c;
    const fmi2ValueReference memorySize = MEMORY_SIZE, script = SCRIPT, recordEnabled = RECORD_ENABLED;
    const fmi2Integer words = 0x4000;
    const fmi2Boolean on = fmi2True;
    size_t before, instance, recording;
    long stepping, recorded;
    double t = 0, h = 1000 * 1e-4;
    int k;

    if (argc != 4) {
        fprintf(stderr, "usage: memory FMU.so GUID SCRIPT\n");
        return 2;
    }
    if (!(so = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL))) {
        fprintf(stderr, "%s\n", dlerror());
        return 1;
    }
    before = in_use();
    c = ((fmi2InstantiateTYPE *)symbol(so, "fmi2Instantiate"))("m", fmi2CoSimulation, argv[2], "", &callbacks,
                                                                fmi2False, fmi2False);
    if (!c)
        return 1;
    CALL(fmi2SetupExperiment, c, fmi2False, 0, 0, fmi2False, 0);
    CALL(fmi2EnterInitializationMode, c);
    CALL(fmi2SetInteger, c, &memorySize, 1, &words);
    CALL(fmi2SetString, c, &script, 1, (const fmi2String *)&argv[3]);
    CALL(fmi2ExitInitializationMode, c);
    instance = in_use() - before;

    stepping = allocations;
    for (k = 0; k < 200; k++, t += h)
        CALL(fmi2DoStep, c, t, h, fmi2True);
    stepping = allocations - stepping;

    before = in_use();
    CALL(fmi2SetBoolean, c, &recordEnabled, 1, &on);
    recording = in_use() - before;
    recorded = allocations;
    for (k = 0; k < 50; k++, t += h)
        CALL(fmi2DoStep, c, t, h, fmi2True);
    recorded = allocations - recorded;

    ((fmi2FreeInstanceTYPE *)symbol(so, "fmi2FreeInstance"))(c);
    printf("%zu %ld %zu %ld\n", instance, stepping, recording, recorded);
    return 0;
}
