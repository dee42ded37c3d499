/* SPDX-License-Identifier: BSD-2-Clause */
/* What the seed's sample-code programs (tests/c/seed_1_*.c) share around the snippets: the
   chip, opened through the C-Motion library, printing its outputs after every cycle; the
   scenario's data; and the phases a program does not take from its own section, as plain
   library calls. tests/test_cmotion.py runs the same phases through the Python harness and
   compares the printed lines.

   Output lines:
     C <chipTime> then for axes 1..4: <commandedPosition> <commandedVelocity>
       <commandedAcceleration> <activityStatus> <eventStatus>; then <host.interrupt>
                                                     after every cycle
     R <label> <values...>                           a value a program reads back
     E <call> <result>                               a call that did not return PMD_ERR_OK */
#ifndef SEED_SUPPORT_H
#define SEED_SUPPORT_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "c-motion.h"
#include "PMDhosttime.h"

#define SEED_AXES 4
#define SEGMENT_CYCLES 64          /* cycles of each leg of the scenario's tables */
#define SEED_ENTRIES 5             /* rows of each axis's table: four legs and a time-0 row */

/* the seed's handle array: hAxis[PMDAxis1] .. hAxis[PMDAxis4] */
static PMDAxisHandle hAxis[SEED_AXES];

static void print_cycle(void *context, PMDAxisInterface chip)
{
    static const char *const quantities[] = {"commandedPosition", "commandedVelocity", "commandedAcceleration",
                                             "activityStatus", "eventStatus"};
    char name[64];
    PMDint32 value;
    int axis;
    size_t q;
    (void)context;
    PMDFMU_GetInteger(chip, "chipTime", &value);
    printf("C %lu", (unsigned long)(PMDuint32)value);
    for (axis = 1; axis <= SEED_AXES; axis++)
        for (q = 0; q < sizeof quantities / sizeof *quantities; q++) {
            snprintf(name, sizeof name, "axis%d.%s", axis, quantities[q]);
            PMDFMU_GetInteger(chip, name, &value);
            printf(" %ld", (long)value);
        }
    PMDFMU_GetInteger(chip, "host.interrupt", &value);
    printf(" %ld\n", (long)value);
}

static void check(PMDresult result, const char *call)
{
    if (result != PMD_ERR_OK)
        printf("E %s 0x%X\n", call, (unsigned)result);
}

/* Opens the chip the 2.x way, PMDSetupAxisInterface_Serial + PMDCopyAxisInterface (the twin
   in-process: the FMU of $PMDFMU_FMU or the build tree's), with hAxis[0..3] on its axes; the
   options give every opening the cycle printer and the host interface ($PMDFMU_HOST_INTERFACE,
   else the library's default, parallel16, whatever link the opening names). */
static void seed_open(void)
{
    PMDFMUOptions options;
    int axis;
    PMDresult r;
    PMDHostInterface host = PMDHostInterfaceDefault();
    const char *name = getenv("PMDFMU_HOST_INTERFACE");      /* a kind of host_interfaces.csv */
    PMDFMUOptionsInit(&options);
    options.cycle = print_cycle;
    if (name && *name) {
        if (PMDHostInterfaceKind(name) < 0) {
            fprintf(stderr, "PMDFMU_HOST_INTERFACE=%s: no such host interface\n", name);
            exit(2);
        }
        host = PMDHostInterfaceOf(PMDHostInterfaceKind(name));
    }
    options.hostInterface = &host;
    PMDFMU_SetOpenOptions(&options);
    r = PMDSetupAxisInterface_Serial(&hAxis[PMDAxis1], PMDAxis1, 1);
    if (r != PMD_ERR_OK) {
        fprintf(stderr, "PMDSetupAxisInterface_Serial: 0x%X %s\n", (unsigned)r, PMDGetErrorMessage(r));
        exit(1);
    }
    for (axis = 1; axis < SEED_AXES; axis++)
        check(PMDCopyAxisInterface(&hAxis[axis], &hAxis[PMDAxis1], (PMDAxis)axis), "PMDCopyAxisInterface");
}

static void seed_close(void)
{
    int axis;
    for (axis = SEED_AXES - 1; axis >= 0; axis--)
        check(PMDCloseAxisInterface(&hAxis[axis]), "PMDCloseAxisInterface");
    fflush(stdout);
}

/* The scenario's table entry of axis `axis`, variable `variable` (PMDBufferFunctionPosition ..
   Time), row `index`: constant-velocity legs between waypoints, back to 0, then a time-0 row
   that ends the profile (tests/test_sample_code.py's make_data, legs of SEGMENT_CYCLES). */
static PMDint32 seed_entry(int axis, int variable, int index)
{
    const PMDint32 waypoints[SEED_ENTRIES] = {400 * (axis + 1), 1200 + 100 * axis, 800, 1600 - 200 * axis, 0};
    if (index >= SEED_ENTRIES - 1)
        return 0;
    switch (variable) {
    case 0: return waypoints[index];
    case 1: return (waypoints[index + 1] - waypoints[index]) * 65536 / SEGMENT_CYCLES;
    case 4: return SEGMENT_CYCLES;
    default: return 0;
    }
}

/* ---- the phases as plain library calls ---- */

enum { seed_memory_start = 0x200, seed_memory_size = 0x4000, seed_variables = 5 };

/* 1.1's set-up for num_axes axes (the seed's own formula; its buffers overlap) */
static PMDuint32 setup_buffers(int num_axes)
{
    PMDuint32 length = (PMDuint32)(seed_memory_size - seed_memory_start) / (PMDuint32)(num_axes * seed_variables);
    int axis, variable, id = 2;
    for (axis = 0; axis < num_axes; axis++)
        for (variable = 0; variable < seed_variables; variable++, id++) {
            check(PMDSetBufferStart(&hAxis[axis], (PMDuint16)id,
                                    seed_memory_start + (PMDuint32)(axis * variable) * length), "PMDSetBufferStart");
            check(PMDSetBufferLength(&hAxis[axis], (PMDuint16)id, length), "PMDSetBufferLength");
            check(PMDSetBufferFunction(&hAxis[axis], (PMDint16)variable, (PMDint16)id), "PMDSetBufferFunction");
        }
    return length;
}

/* 1.3's WriteBuffer upload of the scenario's tables */
static void populate(int num_axes)
{
    int axis, variable, index;
    for (axis = 0; axis < num_axes; axis++)
        for (variable = 0; variable < seed_variables; variable++)
            for (index = 0; index < SEED_ENTRIES; index++)
                check(PMDWriteBuffer(&hAxis[axis], (PMDuint16)(2 + axis * seed_variables + variable),
                                     seed_entry(axis, variable, index)), "PMDWriteBuffer");
}

/* 1.4's initial moves, for every axis */
enum { max_vel = 0x20000, max_acc = 0x800 };     /* 2 counts/cycle, 1/32 count/cycle^2 */
static void initial_moves(int num_axes)
{
    int axis;
    for (axis = 0; axis < num_axes; axis++) {
        check(PMDSetProfileMode(&hAxis[axis], PMDTrapezoidal), "PMDSetProfileMode");
        check(PMDSetVelocity(&hAxis[axis], max_vel), "PMDSetVelocity");
        check(PMDSetAcceleration(&hAxis[axis], max_acc), "PMDSetAcceleration");
        check(PMDSetPosition(&hAxis[axis], seed_entry(axis, 0, 0)), "PMDSetPosition");
        check(PMDUpdate(&hAxis[axis]), "PMDUpdate");
    }
}

/* 64 cycles at a time until no axis is in motion */
static void wait_at_rest(int num_axes)
{
    for (;;) {
        int axis, moving = 0;
        for (axis = 0; axis < num_axes; axis++) {
            PMDuint16 status = 0;
            check(PMDGetActivityStatus(&hAxis[axis], &status), "PMDGetActivityStatus");
            moving |= (status & PMDActivityInMotionMask) != 0;
        }
        if (!moving)
            return;
        check(PMDFMU_RunCycles(&hAxis[PMDAxis1], 64), "PMDFMU_RunCycles");
    }
}

/* 1.4's synchronized start of num_axes axes */
static void start_external(int num_axes)
{
    int axis;
    PMDuint16 mask = 0;
    for (axis = 0; axis < num_axes; axis++) {
        check(PMDSetProfileMode(&hAxis[axis], PMDExternalProfile), "PMDSetProfileMode");
        mask |= (PMDuint16)(1u << axis);
    }
    check(PMDMultiUpdate(&hAxis[PMDAxis1], mask), "PMDMultiUpdate");
}

static void run_cycles(PMDuint32 cycles)
{
    check(PMDFMU_RunCycles(&hAxis[PMDAxis1], cycles), "PMDFMU_RunCycles");
}

#endif
