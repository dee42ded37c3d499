/* SPDX-License-Identifier: BSD-2-Clause */
/* A homing routine as C-Motion programs write one, run against the machine that
   PMDFMU_MACHINE names (examples/machine/stage.toml): nothing in it knows where
   the switches are. It hunts for the home switch with a velocity move and a
   capture on home, stops, moves back to the captured position and makes it the
   origin; captures the next index pulse; then runs into the positive limit and
   waits for its event. Every wait is a polling loop on the event status: the
   host time the commands take (the library's default, parallel16) moves the
   chip on.

   Prints "R <label> <values>" lines; with an argument "forever" it polls
   instead for a capture that never comes (capture never re-armed), which only
   PMDFMU_MAX_CYCLES ends. */
#include <stdio.h>
#include <string.h>
#include "c-motion.h"

static int failed;

static void check(PMDresult result, const char *call)
{
    if (result != PMD_ERR_OK) {
        printf("E %s 0x%X\n", call, (unsigned)result);
        failed = 1;
    }
}

/* Polls the event status until one of mask's bits is set; returns the status. */
static PMDuint16 wait_for(PMDAxisHandle *hAxis, PMDuint16 mask)
{
    PMDuint16 status = 0;
    do
        check(PMDGetEventStatus(hAxis, &status), "PMDGetEventStatus");
    while (!(status & mask) && !failed);
    return status;
}

int main(int argc, char **argv)
{
    PMDAxisHandle hAxis;
    PMDint32 captured = 0, actual = 0;
    PMDuint16 status = 0;
    PMDuint32 time = 0;

    check(PMDSetupAxisInterface_FMU(&hAxis, PMDAxis1, NULL), "PMDSetupAxisInterface_FMU");
    if (failed)
        return 1;

    /* 1. hunt for the home switch: velocity move, capture on home */
    check(PMDSetCaptureSource(&hAxis, PMDCaptureSourceHome), "PMDSetCaptureSource");
    check(PMDGetCaptureValue(&hAxis, &captured), "PMDGetCaptureValue");        /* arms the capture */
    check(PMDResetEventStatus(&hAxis, 0), "PMDResetEventStatus");
    check(PMDSetProfileMode(&hAxis, PMDVelocityContouringProfile), "PMDSetProfileMode");
    check(PMDSetAcceleration(&hAxis, 0x2000), "PMDSetAcceleration");            /* 0.125 counts/cycle^2 */
    check(PMDSetVelocity(&hAxis, 0x50000), "PMDSetVelocity");                   /* 5 counts/cycle */
    check(PMDUpdate(&hAxis), "PMDUpdate");
    wait_for(&hAxis, PMDEventCaptureReceivedMask);
    check(PMDGetCaptureValue(&hAxis, &captured), "PMDGetCaptureValue");
    check(PMDGetTime(&hAxis, &time), "PMDGetTime");
    printf("R home captured %ld\n", (long)captured);

    if (argc > 1 && strcmp(argv[1], "forever") == 0) {
        /* a capture is armed again only by reading the value: this one was, but the axis stops
           short of any other home edge, so the poll below never ends on its own */
        check(PMDSetStopMode(&hAxis, PMDAbruptStopMode), "PMDSetStopMode");
        check(PMDUpdate(&hAxis), "PMDUpdate");
        check(PMDResetEventStatus(&hAxis, (PMDuint16)~PMDEventCaptureReceivedMask), "PMDResetEventStatus");
        wait_for(&hAxis, PMDEventCaptureReceivedMask);
        printf("R never\n");
        return 0;
    }

    /* 2. stop, and move back to the captured position with a trapezoidal move */
    check(PMDSetStopMode(&hAxis, PMDSmoothStopMode), "PMDSetStopMode");
    check(PMDUpdate(&hAxis), "PMDUpdate");
    check(PMDResetEventStatus(&hAxis, (PMDuint16)~PMDEventMotionCompleteMask), "PMDResetEventStatus");
    wait_for(&hAxis, PMDEventMotionCompleteMask);
    check(PMDSetProfileMode(&hAxis, PMDTrapezoidalProfile), "PMDSetProfileMode");
    check(PMDSetPosition(&hAxis, captured), "PMDSetPosition");
    check(PMDSetVelocity(&hAxis, 0x50000), "PMDSetVelocity");
    check(PMDSetAcceleration(&hAxis, 0x2000), "PMDSetAcceleration");
    check(PMDSetDeceleration(&hAxis, 0x2000), "PMDSetDeceleration");
    check(PMDResetEventStatus(&hAxis, (PMDuint16)~PMDEventMotionCompleteMask), "PMDResetEventStatus");
    check(PMDUpdate(&hAxis), "PMDUpdate");
    wait_for(&hAxis, PMDEventMotionCompleteMask);
    check(PMDGetActualPosition(&hAxis, &actual), "PMDGetActualPosition");
    printf("R back at %ld\n", (long)actual);

    /* 3. the home position is the origin */
    check(PMDSetActualPosition(&hAxis, 0), "PMDSetActualPosition");
    check(PMDGetActualPosition(&hAxis, &actual), "PMDGetActualPosition");
    printf("R origin %ld\n", (long)actual);

    /* 4. the next index pulse: capture on index during a move up */
    check(PMDSetCaptureSource(&hAxis, PMDCaptureSourceIndex), "PMDSetCaptureSource");
    check(PMDGetCaptureValue(&hAxis, &captured), "PMDGetCaptureValue");        /* re-arms */
    check(PMDResetEventStatus(&hAxis, (PMDuint16)~PMDEventCaptureReceivedMask), "PMDResetEventStatus");
    check(PMDSetPosition(&hAxis, 5000), "PMDSetPosition");
    check(PMDUpdate(&hAxis), "PMDUpdate");
    wait_for(&hAxis, PMDEventCaptureReceivedMask);
    check(PMDGetCaptureValue(&hAxis, &captured), "PMDGetCaptureValue");
    printf("R index captured %ld\n", (long)captured);
    check(PMDResetEventStatus(&hAxis, (PMDuint16)~PMDEventMotionCompleteMask), "PMDResetEventStatus");
    wait_for(&hAxis, PMDEventMotionCompleteMask);

    /* 5. into the positive limit: the chip stops the axis and sets the event */
    check(PMDSetPosition(&hAxis, 100000), "PMDSetPosition");
    check(PMDSetVelocity(&hAxis, 0x140000), "PMDSetVelocity");                  /* 20 counts/cycle */
    check(PMDUpdate(&hAxis), "PMDUpdate");
    status = wait_for(&hAxis, PMDEventInPositiveLimitMask);
    check(PMDGetActualPosition(&hAxis, &actual), "PMDGetActualPosition");
    printf("R positive limit 0x%04X %ld\n", (unsigned)status, (long)actual);
    check(PMDCloseAxisInterface(&hAxis), "PMDCloseAxisInterface");
    return failed;
}
