/* SPDX-License-Identifier: BSD-2-Clause */
/* The trace commands (reference 1.2, 2.6, 4.4): what is sampled and when the
 * trace starts and stops; trace.c samples. The trace mode and period are rows
 * of registers.csv, guarded by pmd_trace_busy. */
#include "commands.h"

#define TRACE (&chip->s.trace)

int cmd_SetTraceVariable(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    int err = pmd_trace_busy(chip, "SetTraceVariable");
    (void)axis; (void)reply;
    if (err)
        return err;
    if (arg[0] >= PMD_TRACE_SLOTS || arg[1] >= PMD_AXES || arg[2] > PMDTraceAnalogInput8) {
        pmd_log(chip, PMD_LOG_ERRORS, "SetTraceVariable: slot %d (0..3), axis %d (0..3) or variable %d (0..27) "
                "out of range", (int)arg[0], (int)arg[1], (int)arg[2]);
        return PMD_ERR_InvalidParameter;
    }
    TRACE->variable[arg[0]] = (uint16_t)(PMD_FIELD_DP(0, PMDTraceVariableAxis, arg[1]) |
                                         PMD_FIELD_DP(0, PMDTraceVariableID, arg[2]));
    return 0;
}

int cmd_GetTraceVariable(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis;
    if (arg[0] >= PMD_TRACE_SLOTS) {
        pmd_log(chip, PMD_LOG_ERRORS, "GetTraceVariable: slot %d is not 0..3", (int)arg[0]);
        return PMD_ERR_InvalidParameter;
    }
    reply[0] = PMD_FIELD_EX(TRACE->variable[arg[0]], PMDTraceVariableAxis);
    reply[1] = PMD_FIELD_EX(TRACE->variable[arg[0]], PMDTraceVariableID);
    return 0;
}

static int condition_word(const PmdChip *chip, const char *name, const int64_t *arg, uint16_t *word)
{
    if (arg[0] >= PMD_AXES || arg[1] > PMDTraceConditionSignalStatus || arg[3] > PMDTraceTriggerStateHigh) {
        pmd_log(chip, PMD_LOG_ERRORS, "%s: axis %d (0..3), condition %d (0..4) or state %d (0..1) out of range",
                name, (int)arg[0], (int)arg[1], (int)arg[3]);
        return PMD_ERR_InvalidParameter;
    }
    *word = (uint16_t)(PMD_FIELD_DP(0, PMDTraceTriggerAxis, arg[0]) | PMD_FIELD_DP(0, PMDTraceCondition, arg[1]) |
                       PMD_FIELD_DP(0, PMDTraceTriggerBit, arg[2]) | PMD_FIELD_DP(0, PMDTraceTriggerState, arg[3]));
    return 0;
}

/* Condition 0 (immediate) starts now; any other arms the start register. */
int cmd_SetTraceStart(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    uint16_t word;
    int err = pmd_trace_busy(chip, "SetTraceStart");
    (void)axis; (void)reply;
    if (!err)
        err = condition_word(chip, "SetTraceStart", arg, &word);
    if (err)
        return err;
    if (chip->s.buffer[0].length == 0) {
        pmd_log(chip, PMD_LOG_ERRORS, "SetTraceStart: trace buffer 0 has length 0");
        return PMD_ERR_TraceBufferZero;
    }
    if (arg[1] == PMDTraceConditionImmediate)
        pmd_trace_start(chip);
    else
        TRACE->start = word;
    return 0;
}

int cmd_SetTraceStop(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    uint16_t word;
    int err = condition_word(chip, "SetTraceStop", arg, &word);
    (void)axis; (void)reply;
    if (err)
        return err;
    if (arg[1] == PMDTraceConditionImmediate) {
        TRACE->stop = 0;
        if (TRACE->active)
            pmd_trace_stop(chip, "SetTraceStop");
        TRACE->start = 0;
    } else {
        TRACE->stop = word;
    }
    return 0;
}

static void condition_fields(uint16_t word, int64_t *reply)
{
    reply[0] = PMD_FIELD_EX(word, PMDTraceTriggerAxis);
    reply[1] = PMD_FIELD_EX(word, PMDTraceCondition);
    reply[2] = PMD_FIELD_EX(word, PMDTraceTriggerBit);
    reply[3] = PMD_FIELD_EX(word, PMDTraceTriggerState);
}

int cmd_GetTraceStart(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis; (void)arg;
    condition_fields(TRACE->start, reply);
    return 0;
}

int cmd_GetTraceStop(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis; (void)arg;
    condition_fields(TRACE->stop, reply);
    return 0;
}

int cmd_GetTraceStatus(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis; (void)arg;
    reply[0] = (TRACE->mode ? PMDTraceStatusMode : 0) | (TRACE->active ? PMDTraceStatusActivity : 0) |
               (TRACE->wrapped ? PMDTraceStatusDataWrap : 0);
    return 0;
}

