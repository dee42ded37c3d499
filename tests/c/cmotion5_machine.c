/* SPDX-License-Identifier: BSD-2-Clause */
/* A C-Motion 5.x host program against a machine (PMDFMU_MACHINE, examples/machine/stage.toml),
   written as ION and C-Motion Engine applications write their homing and test routines (their
   constructs, none of their code; docs/sources.md): the peripheral -> device -> axis opening,
   PMD_RESULT, and every wait a poll on the event status.
   1. Homing: a velocity move hunting the home switch with a capture on home, a smooth stop, a
      trapezoidal move back to the captured position made the origin, then a capture on the next
      index pulse.
   2. Limit switch: a move into the positive limit, its event read and cleared, a move out.
   3. Full range: 20 trapezoidal moves between -1000000 and +1000000 on axis 2 (no switches), the
      last one's target reached exactly, the cycles they took from GetTime.
   tests/test_cmotion_programs.py runs it and pins what it prints. */
#include "C-Motion.h"
#include "PMDperiph.h"
#include "PMDdevice.h"
#include "PMDdiag.h"
#include "PMDsys.h"

static PMDresult result;

/* Polls the event status until a bit of mask is set; returns the status word. */
static PMDuint16 WaitForEventBits(PMDAxisHandle *hAxis, PMDuint16 mask)
{
    PMDuint16 status = 0;
    do
        PMD_RESULT(PMDGetEventStatus(hAxis, &status))
    while (result == PMD_ERR_OK && !(status & mask));
    return status;
}

static void MoveTo(PMDAxisHandle *hAxis, PMDint32 position, PMDint32 velocity, PMDuint32 acceleration)
{
    PMD_RESULT(PMDSetProfileMode(hAxis, PMDProfileModeTrapezoidal))
    PMD_RESULT(PMDSetPosition(hAxis, position))
    PMD_RESULT(PMDSetVelocity(hAxis, velocity))
    PMD_RESULT(PMDSetAcceleration(hAxis, acceleration))
    PMD_RESULT(PMDSetDeceleration(hAxis, acceleration))
    PMD_RESULT(PMDResetEventStatus(hAxis, (PMDuint16)~PMDEventStatusMotionComplete))
    PMD_RESULT(PMDUpdate(hAxis))
    WaitForEventBits(hAxis, PMDEventStatusMotionComplete);
}

static void Home(PMDAxisHandle *hAxis)
{
    PMDint32 captured = 0, actual = 0;

    PMD_RESULT(PMDSetCaptureSource(hAxis, PMDCaptureSourceHome))
    PMD_RESULT(PMDGetCaptureValue(hAxis, &captured))       /* arms the capture */
    PMD_RESULT(PMDResetEventStatus(hAxis, 0))
    PMD_RESULT(PMDSetProfileMode(hAxis, PMDProfileModeVelocity))
    PMD_RESULT(PMDSetAcceleration(hAxis, 0x4000))
    PMD_RESULT(PMDSetVelocity(hAxis, 8L << 16))
    PMD_RESULT(PMDUpdate(hAxis))
    WaitForEventBits(hAxis, PMDEventStatusCaptureReceived);
    PMD_RESULT(PMDGetCaptureValue(hAxis, &captured))
    PMDprintf("Home captured at %ld\n", (long)captured);

    PMD_RESULT(PMDSetStopMode(hAxis, PMDStopModeSmooth))
    PMD_RESULT(PMDResetEventStatus(hAxis, (PMDuint16)~PMDEventStatusMotionComplete))
    PMD_RESULT(PMDUpdate(hAxis))
    WaitForEventBits(hAxis, PMDEventStatusMotionComplete);
    MoveTo(hAxis, captured, 8L << 16, 0x4000);
    PMD_RESULT(PMDGetActualPosition(hAxis, &actual))
    PMDprintf("Back at %ld, made the origin\n", (long)actual);
    PMD_RESULT(PMDSetActualPosition(hAxis, 0))

    PMD_RESULT(PMDSetCaptureSource(hAxis, PMDCaptureSourceIndex))
    PMD_RESULT(PMDGetCaptureValue(hAxis, &captured))       /* re-arms */
    PMD_RESULT(PMDResetEventStatus(hAxis, (PMDuint16)~PMDEventStatusCaptureReceived))
    MoveTo(hAxis, 4000, 8L << 16, 0x4000);
    PMD_RESULT(PMDGetCaptureValue(hAxis, &captured))
    PMDprintf("Index captured at %ld\n", (long)captured);
}

static void LimitSwitch(PMDAxisHandle *hAxis)
{
    PMDuint16 status, signals = 0;
    PMDint32 actual = 0;

    PMD_RESULT(PMDSetProfileMode(hAxis, PMDProfileModeTrapezoidal))
    PMD_RESULT(PMDSetPosition(hAxis, 100000))
    PMD_RESULT(PMDSetVelocity(hAxis, 20L << 16))
    PMD_RESULT(PMDResetEventStatus(hAxis, 0))
    PMD_RESULT(PMDUpdate(hAxis))
    status = WaitForEventBits(hAxis, PMDEventStatusInPositiveLimit);
    PMD_RESULT(PMDGetActualPosition(hAxis, &actual))
    PMD_RESULT(PMDGetSignalStatus(hAxis, &signals))
    PMDprintf("Positive limit: event 0x%04X signals 0x%04X at %ld\n", status, signals, (long)actual);

    PMD_RESULT(PMDResetEventStatus(hAxis, (PMDuint16)~PMDEventStatusInPositiveLimit))
    PMD_RESULT(PMDGetEventStatus(hAxis, &status))
    PMDprintf("Cleared: event 0x%04X\n", status);
    MoveTo(hAxis, 0, 20L << 16, 0x4000);
    PMD_RESULT(PMDGetActualPosition(hAxis, &actual))
    PMD_RESULT(PMDGetEventStatus(hAxis, &status))
    PMDprintf("Moved out to %ld: event 0x%04X\n", (long)actual, status);
}

static void FullRange(PMDAxisHandle *hAxis)
{
    PMDuint32 start = 0, end = 0;
    PMDint32 target = 0, actual = 0;
    int move;

    PMD_RESULT(PMDGetTime(hAxis, &start))
    for (move = 1; move <= 20; move++) {
        target = (move % 2 ? 1000000L : -1000000L) / move * (move % 4 < 2 ? 1 : -1);
        MoveTo(hAxis, target, 100L << 16, 0x10000);
    }
    PMD_RESULT(PMDGetTime(hAxis, &end))
    PMD_RESULT(PMDGetActualPosition(hAxis, &actual))
    PMDprintf("20 moves in %lu cycles, at %ld, target %ld\n", (unsigned long)(end - start), (long)actual,
              (long)target);
}

int main(void)
{
    PMDPeriphHandle hPeriph = {0};
    PMDDeviceHandle hDevice = {0};
    PMDAxisHandle hAxis1, hAxis2;

    PMD_ABORTONERROR(PMDPeriphOpenCOM(&hPeriph, NULL, PMDSerialPort1, PMDSerialBaud57600, PMDSerialParityNone,
                                      PMDSerialStopBits1))
    PMD_ABORTONERROR(PMDPeriphOpenDeviceMP(&hDevice, &hPeriph))
    PMD_ABORTONERROR(PMDAxisOpen(&hAxis1, &hDevice, PMDAxis1))
    PMD_ABORTONERROR(PMDAxisOpen(&hAxis2, &hDevice, PMDAxis2))

    Home(&hAxis1);
    LimitSwitch(&hAxis1);
    FullRange(&hAxis2);

    PMD_RESULT(PMDAxisClose(&hAxis2))
    PMD_RESULT(PMDAxisClose(&hAxis1))
    PMD_RESULT(PMDDeviceClose(&hDevice))
    PMD_RESULT(PMDPeriphClose(&hPeriph))
    PMDprintf("Done\n");
    return 0;
}
