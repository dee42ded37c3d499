/* SPDX-License-Identifier: BSD-2-Clause */
/* A complete C-Motion host program against the PMDMotionProcessor FMU: two axes follow an
   external profile (a square, a leg per segment) that is longer than the chip's buffers, so the
   host streams it in, refilling behind the read index while the axes move; it starts both axes
   with MultiUpdate, polls the activity status until the profile segment number falls to 0 (the
   table's time-0 row), stops, and checks where the axes ended.

   Unchanged host code: chip time passes only as the host talks (each command takes its transfer
   time on the host interface, parallel16 by default), so the polling loops end.

   Build and run (docs/c-motion.md):
     cmake -S . -B build && cmake --build build
     build/cmotion/cmotion_example                  # the build tree's FMU; or PMDFMU_FMU=path.fmu */
#include <stdio.h>
#include "c-motion.h"

enum { AXES = 2, VARIABLES = 5, LENGTH = 8, LEGS = 24, LEG_CYCLES = 40, SIDE = 2000 };

/* Row `row` of axis `axis`'s table: position, velocity (16.16), acceleration, jerk, time. Axis 1
   and 2 trace a square of SIDE counts, a quarter turn apart; after the last leg a time-0 row. */
static PMDint32 table(int axis, int variable, int row)
{
    static const int corner[4][2] = {{0, 0}, {SIDE, 0}, {SIDE, SIDE}, {0, SIDE}};
    int from = corner[row % 4][axis], to = corner[(row + 1) % 4][axis];
    if (row >= LEGS)
        return variable == 0 ? corner[LEGS % 4][axis] : 0;
    switch (variable) {
    case 0: return from;
    case 1: return (to - from) * 65536 / LEG_CYCLES;
    case 4: return LEG_CYCLES;
    default: return 0;
    }
}

static PMDuint16 buffer_of(int axis, int variable)
{
    return (PMDuint16)(2 + axis * VARIABLES + variable);
}

#define CHECK(call) do { PMDresult r_ = (call); if (r_ != PMD_ERR_OK) { \
    printf("%s: error 0x%X\n", #call, (unsigned)r_); return 1; } } while (0)

int main(void)
{
    PMDAxisHandle hAxis[AXES];
    int axis, variable, written = 0;
    PMDuint16 status;
    PMDuint32 start = 0, now;

    CHECK(PMDSetupAxisInterface_FMU(&hAxis[0], PMDAxis1, NULL));
    CHECK(PMDCopyAxisInterface(&hAxis[1], &hAxis[0], PMDAxis2));

    /* one buffer of LENGTH entries per axis and trajectory variable, from 0x200 up */
    for (axis = 0; axis < AXES; axis++)
        for (variable = 0; variable < VARIABLES; variable++) {
            PMDuint16 id = buffer_of(axis, variable);
            CHECK(PMDSetBufferStart(&hAxis[axis], id, 0x200 + (PMDuint32)(id - 2) * LENGTH));
            CHECK(PMDSetBufferLength(&hAxis[axis], id, LENGTH));
            CHECK(PMDSetBufferFunction(&hAxis[axis], (PMDint16)variable, (PMDint16)id));
        }

    /* stream: keep every free entry filled. The entry under the read index is the row being run;
       an index equal to the write index means all is read, so one entry stays free. */
    do {
        PMDuint32 read, free;
        CHECK(PMDGetBufferReadIndex(&hAxis[0], buffer_of(0, 0), &read));
        free = (read + LENGTH - 1 - (PMDuint32)(written % LENGTH)) % LENGTH;
        if (written == 0)
            free = LENGTH - 1;
        for (; free > 0 && written <= LEGS; free--, written++)
            for (axis = 0; axis < AXES; axis++)
                for (variable = 0; variable < VARIABLES; variable++)
                    CHECK(PMDWriteBuffer(&hAxis[axis], buffer_of(axis, variable), table(axis, variable, written)));
        if (written == LENGTH - 1) {             /* the first fill: start both axes at once */
            for (axis = 0; axis < AXES; axis++)
                CHECK(PMDSetProfileMode(&hAxis[axis], PMDExternalProfile));
            CHECK(PMDMultiUpdate(&hAxis[0], PMDAxis1Mask | PMDAxis2Mask));
            CHECK(PMDGetTime(&hAxis[0], &start));
        }
    } while (written <= LEGS);

    /* poll until the profile segment number falls to 0: the time-0 row ended the profile */
    do
        CHECK(PMDGetActivityStatus(&hAxis[0], &status));
    while (status & PMDActivityProfileSegmentMask);
    CHECK(PMDGetTime(&hAxis[0], &now));

    /* stop: an abrupt stop of both axes holds them where they are */
    for (axis = 0; axis < AXES; axis++)
        CHECK(PMDSetStopMode(&hAxis[axis], PMDAbruptStop));
    CHECK(PMDMultiUpdate(&hAxis[0], PMDAxis1Mask | PMDAxis2Mask));

    for (axis = 0; axis < AXES; axis++) {
        PMDint32 position;
        CHECK(PMDGetCommandedPosition(&hAxis[axis], &position));
        printf("axis %d at %ld\n", axis + 1, (long)position);
        if (position != table(axis, 0, LEGS)) {
            printf("axis %d should be at %ld\n", axis + 1, (long)table(axis, 0, LEGS));
            return 1;
        }
    }
    printf("started after cycle %lu, profile complete at cycle %lu\n", (unsigned long)start, (unsigned long)now);
    for (axis = AXES - 1; axis >= 0; axis--)
        CHECK(PMDCloseAxisInterface(&hAxis[axis]));
    return 0;
}
