/* SPDX-License-Identifier: BSD-2-Clause */
/* C-Motion Engine user code as public ION/CME programs are written (their constructs, none of
   their code; docs/sources.md): USER_CODE_VERSION and USER_CODE_TASK, the engine's own axis
   (PMDAxisOpen with no device), a velocity move timed by polling GetTime around PMDTaskWait, a
   smooth stop awaited with PMDutil's WaitForEvent, and a trace of commanded position and
   velocity downloaded from buffer 0. Built for the host, the task is the program.
   tests/test_cmotion_programs.py runs it against the twin and pins what it prints. */
#include "c-motion.h"
#include "PMDdiag.h"
#include "PMDperiph.h"
#include "PMDdevice.h"
#include "PMDsys.h"
#include "PMDutil.h"

#define MAJOR_VERSION 1
#define MINOR_VERSION 0

USER_CODE_VERSION(MAJOR_VERSION, MINOR_VERSION)

#define TRACE_WORDS 128     /* 64 samples of two variables */

USER_CODE_TASK(VelocityTrace)
{
    PMDAxisHandle hAxis;
    PMDresult result;
    PMDuint32 start, now, count = 0, i;
    PMDuint16 status = 0;
    PMDint32 sample[TRACE_WORDS];

    PMD_ABORTONERROR(PMDAxisOpen(&hAxis, NULL, PMDAxis1))

    /* trace buffer 0: commanded position and velocity every 4 cycles, from the next update */
    PMD_RESULT(PMDSetBufferStart(&hAxis, 0, 0x200))
    PMD_RESULT(PMDSetBufferLength(&hAxis, 0, TRACE_WORDS))
    PMD_RESULT(PMDSetTracePeriod(&hAxis, 4))
    PMD_RESULT(PMDSetTraceVariable(&hAxis, PMDTraceVariableNumber1, PMDAxis1, PMDTraceVariableCommandedPosition))
    PMD_RESULT(PMDSetTraceVariable(&hAxis, PMDTraceVariableNumber2, PMDAxis1, PMDTraceVariableCommandedVelocity))
    PMD_RESULT(PMDSetTraceMode(&hAxis, PMDTraceModeOneTime))
    PMD_RESULT(PMDSetTraceStart(&hAxis, PMDAxis1, PMDTraceConditionNextUpdate, 0, 0))

    /* velocity mode up to 2 counts/cycle, for 50 ms of chip time */
    PMD_RESULT(PMDSetProfileMode(&hAxis, PMDProfileModeVelocity))
    PMD_RESULT(PMDSetVelocity(&hAxis, 2L << 16))
    PMD_RESULT(PMDSetAcceleration(&hAxis, 0x800))
    PMD_RESULT(PMDSetDeceleration(&hAxis, 0x800))
    PMD_RESULT(PMDUpdate(&hAxis))
    PMD_RESULT(PMDGetTime(&hAxis, &start))
    do {
        PMDTaskWait(5);
        PMD_RESULT(PMDGetTime(&hAxis, &now))
    } while (now - start < 500);
    PMDprintf("Ran %lu cycles\n", now - start);

    PMD_RESULT(PMDSetStopMode(&hAxis, PMDStopModeSmooth))
    PMD_RESULT(PMDUpdate(&hAxis))
    result = WaitForEvent(&hAxis, PMDEventStatusMotionComplete, 1000);
    PMDprintf("Smooth stop: %s\n", PMDGetErrorMessage(result));

    do {
        PMD_RESULT(PMDGetTraceStatus(&hAxis, &status))
    } while (result == PMD_ERR_OK && (status & PMDTraceStatusActivity));
    PMD_RESULT(PMDGetTraceCount(&hAxis, &count))
    PMDprintf("Trace: %lu words\n", count);
    if (count > TRACE_WORDS)
        count = TRACE_WORDS;
    PMD_RESULT(ReadBuffer(&hAxis, 0, sample, count))
    for (i = 0; i + 1 < count; i += 2)
        PMDprintf("%lu %ld %ld\n", i / 2, sample[i], sample[i + 1]);

    PMD_RESULT(PMDAxisClose(&hAxis))
}
