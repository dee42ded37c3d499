/* SPDX-License-Identifier: BSD-2-Clause */
/* The trace facility (reference 4.4): up to four variables, sampled every
 * `period` cycles at the end of the cycle into buffer 0, one 32-bit word per
 * slot, in slot order. One-time mode stops when the buffer is full; rolling
 * mode wraps and sets the data-wrap bit. */
#include "events.h"
#include "memory.h"
#include "status.h"
#include "trace.h"

#define TRACE (&chip->s.trace)

int pmd_trace_busy(const PmdChip *chip, const char *command)
{
    if (!chip->s.trace.active)
        return 0;
    pmd_log(chip, PMD_LOG_ERRORS, "%s: not allowed while a trace is running", command);
    return PMD_ERR_TraceRunning;
}

/* Variable IDs (reference 2.6), 1..27 (SetTraceVariable refuses others); 7,
 * 10 and 11 read the servo filter (servo.c) as the cycle left it: the motor
 * command, the integral, the derivative; 15..19 the idle commutator's
 * registers as GetPhaseAngle, GetPhaseOffset and GetPhaseCommand read them. */
static int32_t trace_value(const PmdChip *chip, uint16_t slot)
{
    int n = (int)PMD_FIELD_EX(slot, PMDTraceVariableAxis);
    const PmdAxis *ax = &chip->s.axis[n];
    switch (PMD_FIELD_EX(slot, PMDTraceVariableID)) {
    case 1: return pmd_position_error(ax);
    case 2: return ax->trajectory.position;
    case 3: return pmd_commanded_velocity(&ax->trajectory);
    case 4: return pmd_commanded_acceleration(&ax->trajectory);
    case 5: return ax->actualPosition;
    case 6: return pmd_actual_velocity(ax);
    case 7: return ax->filter.output;
    case 8: return pmd_int32(chip->s.time);
    case 9: return ax->captureValue;
    case 10: return ax->filter.integral;
    case 11: return ax->filter.derivative;
    case 12: return ax->eventStatus;
    case 13: return pmd_activity_status(chip, n);
    case 14: return pmd_signal_status(chip, n);
    case 15: return ax->phaseAngle;
    case 16: return ax->phaseOffset;
    case 17: return pmd_phase_command(ax, PMDPhaseA);
    case 18: return pmd_phase_command(ax, PMDPhaseB);
    case 19: return pmd_phase_command(ax, PMDPhaseC);
    default:                   /* 20..27: the analog inputs 1..8 (chip-wide: the slot's axis does not matter) */
        return chip->s.analogInput[PMD_FIELD_EX(slot, PMDTraceVariableID) - PMDTraceAnalogInput1];
    }
}

/* Start and stop words: fields PMDTraceTriggerAxis, PMDTraceCondition,
 * PMDTraceTriggerBit (a status bit) and PMDTraceTriggerState. */
static int condition_met(const PmdChip *chip, uint16_t word)
{
    int n = (int)PMD_FIELD_EX(word, PMDTraceTriggerAxis), bit = (int)PMD_FIELD_EX(word, PMDTraceTriggerBit);
    unsigned state = PMD_FIELD_EX(word, PMDTraceTriggerState);
    uint16_t status;
    switch (PMD_FIELD_EX(word, PMDTraceCondition)) {
    case PMDTraceConditionUpdate: return (chip->s.updatedAxes & (PMDAxis1Mask << n)) != 0;
    case PMDTraceConditionEventStatus: status = chip->s.axis[n].eventStatus; break;
    case PMDTraceConditionActivityStatus: status = pmd_activity_status(chip, n); break;
    case PMDTraceConditionSignalStatus: status = pmd_signal_status(chip, n); break;
    default: return 0;
    }
    return ((status >> bit) & 1u) == state;
}

static int slots_in_use(const PmdTrace *tr)
{
    int k = 0;
    while (k < PMD_TRACE_SLOTS && PMD_FIELD_EX(tr->variable[k], PMDTraceVariableID) != 0)   /* variable 0 ends the list */
        k++;
    return k;
}

void pmd_trace_start(PmdChip *chip)
{
    TRACE->active = 1;
    TRACE->wrapped = 0;
    TRACE->count = 0;
    TRACE->countdown = 0;
    TRACE->start = 0;
    pmd_log(chip, PMD_LOG_EVENTS, "trace started (chip time %u)", (unsigned)chip->s.time);
}

/* A rolling trace that wrapped leaves buffer 0's read index on its oldest
 * sample (the write index) when it stops, so that ReadBuffer reads the samples
 * oldest first (reference 4.3: the rolling trace moves the read index when it
 * completes; docs/decisions.md, Trace). */
void pmd_trace_stop(PmdChip *chip, const char *why)
{
    TRACE->active = 0;
    if (TRACE->mode == PMDTraceRollingBuffer && TRACE->wrapped)
        chip->s.buffer[0].readIndex = chip->s.buffer[0].writeIndex;
    pmd_log(chip, PMD_LOG_EVENTS, "trace stopped: %s (%u values)", why, (unsigned)TRACE->count);
}

static void sample(PmdChip *chip)
{
    PmdBuffer *b = &chip->s.buffer[0];
    int k, slots = slots_in_use(TRACE);
    for (k = 0; k < slots; k++) {
        uint32_t value = (uint32_t)trace_value(chip, TRACE->variable[k]);
        pmd_memory_store(chip, b->start + b->writeIndex, 1, &value);
        if (++b->writeIndex == b->length) {
            b->writeIndex = 0;
            if (TRACE->mode == PMDTraceRollingBuffer)
                TRACE->wrapped = 1;
        }
        if (TRACE->count < b->length)
            TRACE->count++;                     /* a rolling trace reports at most a full buffer */
    }
    if (TRACE->mode == PMDTraceOneTime && TRACE->count + (uint32_t)slots > b->length)
        pmd_trace_stop(chip, "buffer full");
}

void pmd_trace_cycle(PmdChip *chip)
{
    if (!TRACE->active && TRACE->start && condition_met(chip, TRACE->start)) {
        /* Buffer 0 may have changed since SetTraceStart armed the trace (only a
         * running trace locks it): a trace starts only into a buffer it can fill. */
        if (chip->s.buffer[0].length == 0) {
            TRACE->start = 0;
            pmd_log(chip, PMD_LOG_WARNINGS, "trace start condition met, but trace buffer 0 now has length 0: "
                    "trace not started");
        } else {
            pmd_trace_start(chip);
        }
    }
    if (TRACE->active) {
        if (TRACE->countdown == 0) {
            TRACE->countdown = (uint16_t)(TRACE->period - 1);
            sample(chip);
        } else {
            TRACE->countdown--;
        }
    }
    if (TRACE->active && TRACE->stop && condition_met(chip, TRACE->stop)) {
        TRACE->stop = 0;
        pmd_trace_stop(chip, "stop condition");
    }
    chip->s.updatedAxes = 0;
}
