/* SPDX-License-Identifier: BSD-2-Clause */
/* One chip per thread through the C-Motion library (PMDfmu.h): each worker opens its own chip,
   moves two axes and sleeps with PMDTaskWait between reads, then closes it, round after round.
   tests/test_cmotion_library.py runs the workers one after the other in one thread and all at
   once in their own threads, where every round's chips are all open while any worker waits
   (threads meet after opening and before closing); every worker must print the same lines both
   ways, since a chip's time passes only by its own thread's calls.

   Usage: cmotion_threads threads|sequential WORKERS ROUNDS
   Output, per worker after all are done:
     W <worker> <round> <wait> <chipTime> <hostNs> <commandedPosition axis 1> <axis 2>
     E <worker> <call> <result>        a call that did not return PMD_ERR_OK */
#define _XOPEN_SOURCE 700       /* pthread_barrier_t */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "c-motion.h"

#define MAX_WORKERS 16
#define WAITS 40               /* PMDTaskWait(1) calls per round: 10 cycles each at the default 100 us */
#define LINE 128

typedef struct {
    int worker, rounds;
    char (*lines)[LINE];        /* rounds * WAITS lines, then the errors */
    int count, capacity;
} Worker;

static pthread_barrier_t meeting;
static int threaded;

/* Threads meet: every worker has come this far in the round */
static void meet(void)
{
    if (threaded)
        pthread_barrier_wait(&meeting);
}

static void note(Worker *w, const char *format, long a, long b, long c, long d, long e, long f)
{
    if (w->count < w->capacity)
        snprintf(w->lines[w->count++], LINE, format, (long)w->worker, a, b, c, d, e, f);
}

static void check(Worker *w, PMDresult r, const char *call)
{
    if (r != PMD_ERR_OK && w->count < w->capacity)
        snprintf(w->lines[w->count++], LINE, "E %d %s 0x%X", w->worker, call, (unsigned)r);
}

/* Worker k's moves: their own targets, so a chip advanced by another thread shows */
static void run_round(Worker *w, int round)
{
    PMDAxisHandle axis1, axis2;
    PMDint32 p1 = 0, p2 = 0, chipTime = 0;
    uint64_t hostNs = 0;
    int i, k = w->worker;
    PMDresult r = PMDSetupAxisInterface_FMU(&axis1, PMDAxis1, NULL);
    check(w, r, "PMDSetupAxisInterface_FMU");
    meet();
    if (r != PMD_ERR_OK) {
        meet();
        return;
    }
    check(w, PMDCopyAxisInterface(&axis2, &axis1, PMDAxis2), "PMDCopyAxisInterface");
    check(w, PMDSetProfileMode(&axis1, PMDTrapezoidal), "PMDSetProfileMode");
    check(w, PMDSetPosition(&axis1, 4000 + 1000 * k + 100 * round), "PMDSetPosition");
    check(w, PMDSetVelocity(&axis1, 0x10000 * (k + 1)), "PMDSetVelocity");
    check(w, PMDSetAcceleration(&axis1, 0x400 * (PMDuint32)(k + 1)), "PMDSetAcceleration");
    check(w, PMDUpdate(&axis1), "PMDUpdate");
    check(w, PMDSetProfileMode(&axis2, PMDVelocityContouringProfile), "PMDSetProfileMode");
    check(w, PMDSetVelocity(&axis2, -0x8000 * (k + 1)), "PMDSetVelocity");
    check(w, PMDSetAcceleration(&axis2, 0x200), "PMDSetAcceleration");
    check(w, PMDUpdate(&axis2), "PMDUpdate");
    for (i = 0; i < WAITS; i++) {
        PMDTaskWait(1);
        check(w, PMDGetCommandedPosition(&axis1, &p1), "PMDGetCommandedPosition");
        check(w, PMDGetCommandedPosition(&axis2, &p2), "PMDGetCommandedPosition");
        check(w, PMDFMU_GetInteger(&axis1, "chipTime", &chipTime), "PMDFMU_GetInteger");
        check(w, PMDFMU_GetHostTime(&axis1, &hostNs), "PMDFMU_GetHostTime");
        note(w, "W %ld %ld %ld %ld %ld %ld %ld", round, i, chipTime, (long)hostNs, p1, p2);
    }
    meet();
    check(w, PMDCloseAxisInterface(&axis2), "PMDCloseAxisInterface");
    check(w, PMDCloseAxisInterface(&axis1), "PMDCloseAxisInterface");
}

static void *work(void *arg)
{
    Worker *w = arg;
    int round;
    for (round = 0; round < w->rounds; round++)
        run_round(w, round);
    return NULL;
}

int main(int argc, char **argv)
{
    Worker workers[MAX_WORKERS];
    pthread_t threads[MAX_WORKERS];
    int n, rounds, k, i;
    if (argc != 4 || (strcmp(argv[1], "threads") != 0 && strcmp(argv[1], "sequential") != 0) ||
        (n = atoi(argv[2])) < 1 || n > MAX_WORKERS || (rounds = atoi(argv[3])) < 1) {
        fprintf(stderr, "usage: cmotion_threads threads|sequential WORKERS ROUNDS\n");
        return 2;
    }
    threaded = strcmp(argv[1], "threads") == 0;
    for (k = 0; k < n; k++) {
        workers[k].worker = k, workers[k].rounds = rounds, workers[k].count = 0;
        workers[k].capacity = rounds * WAITS + 64;
        workers[k].lines = calloc((size_t)workers[k].capacity, LINE);
        if (!workers[k].lines)
            return 1;
    }
    if (threaded) {
        pthread_barrier_init(&meeting, NULL, (unsigned)n);
        for (k = 0; k < n; k++)
            if (pthread_create(&threads[k], NULL, work, &workers[k]) != 0)
                return 1;
        for (k = 0; k < n; k++)
            pthread_join(threads[k], NULL);
        pthread_barrier_destroy(&meeting);
    } else {
        for (k = 0; k < n; k++)
            work(&workers[k]);
    }
    for (k = 0; k < n; k++) {
        for (i = 0; i < workers[k].count; i++)
            puts(workers[k].lines[i]);
        free(workers[k].lines);
    }
    return 0;
}
