/* SPDX-License-Identifier: BSD-2-Clause */
/* A C-Motion 2.x (Navigator) host program written as public ones are (their constructs, none of
   their code; docs/sources.md): one handle per axis, set up on the parallel port and copied, the
   2.x names (PMDTrapezoidalProfile, PMDEventMotionCompleteMask ...), GetSampleTime into a 16-bit
   word, both axes started by MultiUpdate and polled on the activity status, results checked
   against PMD_ERR_OK with PMDGetErrorMessage, a refused parameter and a call given no handle.
   tests/test_cmotion_programs.py runs it against the twin and pins what it prints. */
#define PMD_CMOTION_GENERATION 2    /* this program's C-Motion: the Navigator's 2.x */
#include <stdio.h>
#include "c-motion.h"

#define AXES 2

static PMDAxisHandle hAxis[AXES];

static void check(PMDresult result, const char *call)
{
    if (result != PMD_ERR_OK)
        printf("%s: 0x%X %s\n", call, (unsigned)result, PMDGetErrorMessage(result));
}

int main(void)
{
    PMDresult result;
    PMDuint16 sample_time = 0, status = 0, polls = 0;
    PMDuint32 time = 0;
    PMDint32 position;
    int axis;

    result = PMDSetupAxisInterface_Parallel(&hAxis[0], PMDAxis1, 0x340);
    if (result != PMD_ERR_OK) {
        printf("PMDSetupAxisInterface_Parallel: %s\n", PMDGetErrorMessage(result));
        return 1;
    }
    check(PMDCopyAxisInterface(&hAxis[1], &hAxis[0], PMDAxis2), "PMDCopyAxisInterface");
    check(PMDGetHostIOError(&hAxis[0], &status), "PMDGetHostIOError");     /* the reset's, cleared */
    printf("host I/O error at start %u\n", status);
    check(PMDGetSampleTime(&hAxis[0], &sample_time), "PMDGetSampleTime");
    printf("sample time %u us\n", sample_time);

    for (axis = 0; axis < AXES; axis++) {
        check(PMDSetProfileMode(&hAxis[axis], PMDTrapezoidalProfile), "PMDSetProfileMode");
        check(PMDSetPosition(&hAxis[axis], 1000L * (axis + 1)), "PMDSetPosition");
        check(PMDSetVelocity(&hAxis[axis], 0x20000), "PMDSetVelocity");
        check(PMDSetAcceleration(&hAxis[axis], 0x400), "PMDSetAcceleration");
        check(PMDSetDeceleration(&hAxis[axis], 0x400), "PMDSetDeceleration");
        check(PMDResetEventStatus(&hAxis[axis], 0), "PMDResetEventStatus");
    }
    check(PMDMultiUpdate(&hAxis[0], PMDAxis1Mask | PMDAxis2Mask), "PMDMultiUpdate");
    for (axis = 0; axis < AXES; axis++) {
        do {
            check(PMDGetActivityStatus(&hAxis[axis], &status), "PMDGetActivityStatus");
            polls++;
        } while (status & PMDActivityInMotionMask);
        check(PMDGetEventStatus(&hAxis[axis], &status), "PMDGetEventStatus");
        check(PMDGetTime(&hAxis[axis], &time), "PMDGetTime");
        check(PMDGetCommandedPosition(&hAxis[axis], &position), "PMDGetCommandedPosition");
        printf("axis %d at %ld, cycle %lu, motion complete %d\n", axis + 1, position, time,
               (status & PMDEventMotionCompleteMask) != 0);
    }
    printf("%u polls\n", polls);

    /* a mode the chip does not have, and a call given an axis number for its handle */
    check(PMDSetProfileMode(&hAxis[0], 7), "PMDSetProfileMode");
    check(PMDUpdate(PMDAxis1), "PMDUpdate");
    result = PMDGetHostIOError(&hAxis[0], &status);
    printf("host I/O error %u\n", status);

    for (axis = AXES - 1; axis >= 0; axis--)
        check(PMDCloseAxisInterface(&hAxis[axis]), "PMDCloseAxisInterface");
    return result == PMD_ERR_OK ? 0 : 1;
}
