/* SPDX-License-Identifier: BSD-2-Clause */
/* A C-Motion 5.x host program written as public ION and Magellan host programs are (their
   constructs, none of their code; docs/sources.md): the peripheral -> device -> axis opening over
   a serial port, PMD_RESULT and PMD_ABORTONERROR, a trapezoidal move polled to completion on the
   event status, and the error path of a call the Navigator lacks. tests/test_cmotion_programs.py
   runs it against the twin and pins what it prints. */
#include "C-Motion.h"
#include "PMDperiph.h"
#include "PMDdevice.h"
#include "PMDdiag.h"
#include "PMDsys.h"

int main(void)
{
    PMDPeriphHandle hPeriph = {0};
    PMDDeviceHandle hDevice = {0};
    PMDAxisHandle hAxis;
    PMDresult result;
    PMDuint32 vmajor, vminor, start, time;
    PMDint32 position, current;
    PMDuint16 status = 0, error = 0, polls = 0;

    PMDGetCMotionVersion(&vmajor, &vminor);
    PMDprintf("C-Motion Version %lu.%lu\n", vmajor, vminor);

    PMDprintf("Opening serial port COM%d\n", PMDSerialPort1 + 1);
    PMD_ABORTONERROR(PMDDeviceOpenPeriphSerial(&hPeriph, NULL, PMDSerialPort1, PMDSerialBaud57600,
                                               PMDSerialParityNone, PMDSerialStopBits1))
    PMD_ABORTONERROR(PMDPeriphOpenDeviceMP(&hDevice, &hPeriph))
    PMD_RESULT(PMDDeviceGetVersion(&hDevice, &vmajor, &vminor))
    PMDprintf("Motion processor version %lu.%lu\n", vmajor, vminor);
    PMD_ABORTONERROR(PMDAxisOpen(&hAxis, &hDevice, PMDAxis1))
    PMD_RESULT(PMDGetInstructionError(&hAxis, &error))     /* the reset's code, read to clear it */
    PMDprintf("Instruction error at start: 0x%X %s\n", error, PMDGetErrorMessage(error));

    /* a move of 20000 counts at up to 4 counts/cycle, then polling the motion-complete event */
    PMD_RESULT(PMDSetProfileMode(&hAxis, PMDProfileModeTrapezoidal))
    PMD_RESULT(PMDSetPosition(&hAxis, 20000))
    PMD_RESULT(PMDSetVelocity(&hAxis, 4L << 16))
    PMD_RESULT(PMDSetAcceleration(&hAxis, 0x1000))
    PMD_RESULT(PMDSetDeceleration(&hAxis, 0x1000))
    PMD_RESULT(PMDResetEventStatus(&hAxis, 0))
    PMD_RESULT(PMDGetTime(&hAxis, &start))
    PMD_RESULT(PMDUpdate(&hAxis))
    do {
        PMD_RESULT(PMDGetEventStatus(&hAxis, &status))
        polls++;
    } while (result == PMD_ERR_OK && !(status & PMDEventStatusMotionComplete));
    PMD_RESULT(PMDGetTime(&hAxis, &time))
    PMD_RESULT(PMDGetActualPosition(&hAxis, &position))
    PMDprintf("Motion complete after %lu cycles, %u polls, at %ld\n", time - start, polls, position);

    /* the Magellan's current loop: a Navigator answers invalid instruction */
    result = PMDSetOperatingMode(&hAxis, PMDOperatingModeAllEnabled);
    PMDprintf("SetOperatingMode: 0x%X %s\n", result, PMDGetErrorMessage(result));
    PMD_RESULT(PMDGetCurrentLoopValue(&hAxis, PMDCurrentLoopPhaseA, PMDCurrentLoopValueNodeActualCurrent, &current))
    PMD_RESULT(PMDGetEventStatus(&hAxis, &status))
    PMDprintf("Instruction error event: %d\n", (status & PMDEventStatusInstructionError) != 0);
    PMD_RESULT(PMDGetInstructionError(&hAxis, &error))
    PMDprintf("Instruction error: 0x%X %s\n", error, PMDGetErrorMessage(error));
    PMD_RESULT(PMDResetEventStatus(&hAxis, (PMDuint16)~PMDEventStatusInstructionError))
    PMD_RESULT(PMDGetEventStatus(&hAxis, &status))
    PMDprintf("Event status: 0x%04X\n", status);

    PMD_RESULT(PMDAxisClose(&hAxis))
    PMD_RESULT(PMDDeviceClose(&hDevice))
    PMD_RESULT(PMDPeriphClose(&hPeriph))
    PMDprintf("Done\n");
    return 0;
}
