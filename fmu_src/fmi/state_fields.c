/* SPDX-License-Identifier: BSD-2-Clause */
/* The declared state (state_fields.h): one row per field of
 * PmdInstanceState, PmdChipState and every struct inside them, with the
 * values the field may hold. Ranges are those the commands and the engine
 * keep a field in (the handler's check or the register's width); what depends on other fields
 * (a buffer inside the memory, a read index below its buffer's length...) is
 * checked by state.c. tests/test_state_forgery.py checks that every struct
 * member is listed here (from the compiler's debug information) and that a
 * value just outside each range is refused, naming the field. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "instance.h"
#include "register_table.h"
#include "state_fields.h"

#define MEMBER(T, m) offsetof(T, m), sizeof(((T *)0)->m), 1
#define ELEMENTS(T, m) offsetof(T, m), sizeof(((T *)0)->m[0]), (unsigned)(sizeof(((T *)0)->m) / sizeof(((T *)0)->m[0]))

/* ... is the range: lo, hi (often a macro such as ANY_I32) */
#define UNSIGNED(T, m, ...) {#m, MEMBER(T, m), PMD_SF_UNSIGNED, __VA_ARGS__, NULL}
#define SIGNED(T, m, ...) {#m, MEMBER(T, m), PMD_SF_SIGNED, __VA_ARGS__, NULL}
#define UNSIGNEDS(T, m, ...) {#m, ELEMENTS(T, m), PMD_SF_UNSIGNED, __VA_ARGS__, NULL}
#define SIGNEDS(T, m, ...) {#m, ELEMENTS(T, m), PMD_SF_SIGNED, __VA_ARGS__, NULL}
#define REAL(T, m) {#m, MEMBER(T, m), PMD_SF_REAL, 0, 0, NULL}
#define STRUCT(T, m, S) {#m, MEMBER(T, m), PMD_SF_STRUCT, 0, 0, &S}
#define STRUCTS(T, m, S) {#m, ELEMENTS(T, m), PMD_SF_STRUCT, 0, 0, &S}
#define DESCRIBE(T, list) {#T, sizeof(T), sizeof list / sizeof list[0], list}

#define BOOL 0, 1
#define ANY_U8 0, UINT8_MAX
#define ANY_U16 0, UINT16_MAX
#define ANY_U32 0, UINT32_MAX
#define ANY_I16 INT16_MIN, INT16_MAX
#define ANY_I32 INT32_MIN, INT32_MAX
#define ANY_I64 INT64_MIN, INT64_MAX
#define AXIS_NUMBER 0, PMD_AXES - 1

static const PmdStateField profile_registers_fields[] = {
    SIGNED(PmdProfileRegisters, position, ANY_I32),
    SIGNED(PmdProfileRegisters, velocity, ANY_I32),
    UNSIGNED(PmdProfileRegisters, acceleration, PMD_REG_Acceleration_RANGE),
    UNSIGNED(PmdProfileRegisters, deceleration, PMD_REG_Deceleration_RANGE),
    UNSIGNED(PmdProfileRegisters, jerk, PMD_REG_Jerk_RANGE),
    SIGNED(PmdProfileRegisters, gearRatio, ANY_I32),
    UNSIGNED(PmdProfileRegisters, profileMode, PMD_REG_ProfileMode_RANGE),
    UNSIGNED(PmdProfileRegisters, stopMode, PMD_REG_StopMode_RANGE),
    UNSIGNED(PmdProfileRegisters, clearPositionError, BOOL),
};
static const PmdStateStruct profile_registers = DESCRIBE(PmdProfileRegisters, profile_registers_fields);

/* The S-curve plan (scurve.c) keeps 6 t1 (t1 + t2) (2 t1 + t2 + t4) below
 * 2^62, so no phase is longer than 2^60 cycles. */
#define CYCLES_60 0, (INT64_C(1) << 60)
#define CYCLES_62 0, (INT64_C(1) << 62)
static const PmdStateField scurve_fields[] = {
    SIGNED(PmdSCurve, t1, CYCLES_60),
    SIGNED(PmdSCurve, t2, CYCLES_60),
    SIGNED(PmdSCurve, t4, CYCLES_60),
    SIGNED(PmdSCurve, step, CYCLES_62),
    SIGNED(PmdSCurve, p6, CYCLES_62),
    SIGNED(PmdSCurve, v2, CYCLES_62),
    SIGNED(PmdSCurve, a, -(INT64_C(1) << 62), INT64_C(1) << 62),
    SIGNED(PmdSCurve, p6Total, CYCLES_62),
    SIGNED(PmdSCurve, distance, -(INT64_C(1) << 32) + 1, (INT64_C(1) << 32) - 1),   /* of two int32 positions */
    SIGNED(PmdSCurve, start, ANY_I32),
    UNSIGNED(PmdSCurve, stopping, BOOL),
};
static const PmdStateStruct scurve = DESCRIBE(PmdSCurve, scurve_fields);

static const PmdStateField fixed_fields[] = {
    SIGNED(PmdFixed, counts, ANY_I64),
    SIGNED(PmdFixed, fraction, 0, PMD_FIXED_ONE - 1),
};
static const PmdStateStruct fixed = DESCRIBE(PmdFixed, fixed_fields);

static const PmdStateField trajectory_fields[] = {
    SIGNED(PmdTrajectory, position, ANY_I32),
    SIGNED(PmdTrajectory, fraction, 0, PMD_U_PER_COUNT - 1),
    STRUCT(PmdTrajectory, velocity, fixed),
    STRUCT(PmdTrajectory, acceleration, fixed),
    SIGNED(PmdTrajectory, jerk, ANY_I32),
};
static const PmdStateStruct trajectory = DESCRIBE(PmdTrajectory, trajectory_fields);

/* The filter group (registers.csv, buffered "filter"): the host's set and the active set alike. */
static const PmdStateField filter_registers_fields[] = {
    UNSIGNED(PmdFilterRegisters, kp, ANY_U16),
    UNSIGNED(PmdFilterRegisters, ki, ANY_U16),
    UNSIGNED(PmdFilterRegisters, kd, ANY_U16),
    UNSIGNED(PmdFilterRegisters, kvff, ANY_U16),
    UNSIGNED(PmdFilterRegisters, kaff, ANY_U16),
    UNSIGNED(PmdFilterRegisters, kout, ANY_U16),
    UNSIGNED(PmdFilterRegisters, integrationLimit, PMD_REG_IntegrationLimit_RANGE),
    UNSIGNED(PmdFilterRegisters, derivativeTime, PMD_REG_DerivativeTime_RANGE),
    SIGNED(PmdFilterRegisters, motorCommand, ANY_I16),
};
static const PmdStateStruct filter_registers = DESCRIBE(PmdFilterRegisters, filter_registers_fields);

/* The servo filter (servo.c): the integral stays within the integration limit
 * (below 2^31), the derivative sample count below the derivative time. */
static const PmdStateField filter_fields[] = {
    STRUCT(PmdFilter, buffered, filter_registers),
    STRUCT(PmdFilter, active, filter_registers),
    SIGNED(PmdFilter, integral, -INT32_MAX, INT32_MAX),
    SIGNED(PmdFilter, derivativeError, ANY_I32),
    SIGNED(PmdFilter, derivative, ANY_I16),
    UNSIGNED(PmdFilter, derivativeCount, 0, UINT16_MAX - 1),
    SIGNED(PmdFilter, output, ANY_I16),
};
static const PmdStateStruct filter = DESCRIBE(PmdFilter, filter_fields);

static const PmdStateField breakpoint_fields[] = {
    UNSIGNED(PmdBreakpoint, sourceAxis, AXIS_NUMBER),
    UNSIGNED(PmdBreakpoint, action, PMDBreakpointNoAction, PMDBreakpointActionMotorOff),
    UNSIGNED(PmdBreakpoint, trigger, PMDBreakpointDisable, PMDBreakpointSignalStatus),
    SIGNED(PmdBreakpoint, value, ANY_I32),
};
static const PmdStateStruct breakpoint = DESCRIBE(PmdBreakpoint, breakpoint_fields);

/* Packed words (commands_hardware.c): the largest word whose fields SetAxisOutSource and
 * SetSerialPortMode accept; the fields' values are stored and read back, never used as indexes. */
#define AXIS_OUT_SOURCE_MAX PMD_FIELD_DP(PMD_FIELD_DP(PMDAxisOutSourceBitMask, PMDAxisOutSourceAxis, PMD_AXES - 1), \
                                         PMDAxisOutSourceRegister, PMDAxisOutSourceSignalStatus)
#define SERIAL_PORT_MODE_MAX \
    PMD_FIELD_DP(PMD_FIELD_DP(PMDSerialPortStopBitsMask | PMDSerialPortProtocolMask | PMDSerialPortMultiDropIDMask, \
                              PMDSerialPortBaud, PMDSerialBaud416667), \
                 PMDSerialPortParity, PMDSerialParityEven)

static const PmdStateField axis_fields[] = {
    STRUCT(PmdAxis, buffered, profile_registers),
    STRUCT(PmdAxis, active, profile_registers),
    STRUCT(PmdAxis, scurve, scurve),
    STRUCT(PmdAxis, trajectory, trajectory),
    UNSIGNED(PmdAxis, motion, PMD_MOTION_IDLE, PMD_MOTION_GEAR),
    UNSIGNED(PmdAxis, atMaximumVelocity, BOOL),
    UNSIGNED(PmdAxis, motorOn, PMD_REG_MotorMode_RANGE),
    UNSIGNED(PmdAxis, underrunWarned, BOOL),
    UNSIGNED(PmdAxis, scurvePhase, 0, 7),
    UNSIGNED(PmdAxis, buffersChecked, ANY_U32),
    UNSIGNEDS(PmdAxis, segmentStart, 0, PMD_MAX_MEMORY_WORDS),
    UNSIGNED(PmdAxis, segmentFunctions, 0, (1 << PMD_FUNCTIONS) - 1),
    UNSIGNED(PmdAxis, segmentBufferCount, 0, PMD_FUNCTIONS),
    UNSIGNEDS(PmdAxis, segmentBuffer, 0, PMD_BUFFERS - 1),
    UNSIGNED(PmdAxis, segmentTime, ANY_U32),
    SIGNEDS(PmdAxis, bufferOfFunction, PMDBufferFunctionNone, PMD_BUFFERS - 1),
    UNSIGNED(PmdAxis, eventStatus, ANY_U16),
    UNSIGNED(PmdAxis, interruptMask, ANY_U16),
    STRUCTS(PmdAxis, breakpoint, breakpoint),
    UNSIGNED(PmdAxis, gearMasterAxis, AXIS_NUMBER),
    UNSIGNED(PmdAxis, gearMasterSource, PMDPositionSourceActual, PMDPositionSourceCommanded),
    SIGNED(PmdAxis, gearMasterLast, ANY_I32),
    SIGNED(PmdAxis, actualPosition, ANY_I32),
    SIGNED(PmdAxis, previousActualPosition, ANY_I32),
    SIGNED(PmdAxis, actualOffset, ANY_I32),
    UNSIGNED(PmdAxis, positionErrorLimit, PMD_REG_PositionErrorLimit_RANGE),
    UNSIGNED(PmdAxis, settleTime, ANY_U16),
    UNSIGNED(PmdAxis, settleWindow, ANY_U16),
    UNSIGNED(PmdAxis, trackingWindow, ANY_U16),
    UNSIGNED(PmdAxis, settleCount, ANY_U16),
    UNSIGNED(PmdAxis, autoStopMode, PMD_REG_AutoStopMode_RANGE),
    UNSIGNED(PmdAxis, motionCompleteMode, PMD_REG_MotionCompleteMode_RANGE),
    UNSIGNED(PmdAxis, motionCompletePending, BOOL),
    UNSIGNED(PmdAxis, limitSwitchMode, PMD_REG_LimitSwitchMode_RANGE),
    UNSIGNED(PmdAxis, inPositiveLimit, BOOL),
    UNSIGNED(PmdAxis, inNegativeLimit, BOOL),
    UNSIGNED(PmdAxis, signalSense, PMD_REG_SignalSense_RANGE),
    UNSIGNED(PmdAxis, captureSource, PMD_REG_CaptureSource_RANGE),
    UNSIGNED(PmdAxis, homeWasActive, BOOL),
    UNSIGNED(PmdAxis, captured, BOOL),
    UNSIGNED(PmdAxis, indexWasActive, BOOL),
    SIGNED(PmdAxis, captureValue, ANY_I32),
    STRUCT(PmdAxis, filter, filter),
    UNSIGNED(PmdAxis, motorLimit, PMD_REG_MotorLimit_RANGE),
    SIGNED(PmdAxis, motorBias, ANY_I16),
    UNSIGNED(PmdAxis, outputMode, PMD_REG_OutputMode_RANGE),
    UNSIGNED(PmdAxis, startVelocity, ANY_U32),
    UNSIGNED(PmdAxis, axisMode, PMD_REG_AxisMode_RANGE),
    UNSIGNED(PmdAxis, axisOutSource, 0, AXIS_OUT_SOURCE_MAX),
    UNSIGNED(PmdAxis, encoderSource, PMD_REG_EncoderSource_RANGE),
    UNSIGNED(PmdAxis, encoderModulus, ANY_U16),
    UNSIGNED(PmdAxis, actualPositionUnits, PMD_REG_ActualPositionUnits_RANGE),
    UNSIGNED(PmdAxis, encoderCounts, ANY_U16),
    UNSIGNED(PmdAxis, encoderSteps, ANY_U16),
    UNSIGNED(PmdAxis, stepRange, ANY_U16),
    UNSIGNED(PmdAxis, commutationMode, PMD_REG_CommutationMode_RANGE),
    UNSIGNED(PmdAxis, numberPhases, PMD_REG_NumberPhases_RANGE),
    UNSIGNED(PmdAxis, phaseInitializeMode, PMD_REG_PhaseInitializeMode_RANGE),
    UNSIGNED(PmdAxis, phasePrescale, PMD_REG_PhasePrescale_RANGE),
    UNSIGNED(PmdAxis, phaseCorrectionMode, PMD_REG_PhaseCorrectionMode_RANGE),
    UNSIGNED(PmdAxis, phaseInitializeTime, ANY_U16),
    UNSIGNED(PmdAxis, phaseCounts, ANY_U16),
    UNSIGNED(PmdAxis, phaseOffset, ANY_U16),
    UNSIGNED(PmdAxis, phaseAngle, ANY_U16),
    UNSIGNED(PmdAxis, phasingInitialized, BOOL),
    SIGNED(PmdAxis, actualPositionInput, ANY_I32),
    UNSIGNED(PmdAxis, positiveLimitInput, BOOL),
    UNSIGNED(PmdAxis, negativeLimitInput, BOOL),
    UNSIGNED(PmdAxis, homeInput, BOOL),
    UNSIGNED(PmdAxis, indexInput, BOOL),
    REAL(PmdAxis, motorAngle),
    REAL(PmdAxis, motorSpeed),
};
static const PmdStateStruct axis = DESCRIBE(PmdAxis, axis_fields);

static const PmdStateField buffer_fields[] = {
    UNSIGNED(PmdBuffer, start, 0, PMD_MAX_MEMORY_WORDS),
    UNSIGNED(PmdBuffer, length, 0, PMD_MAX_MEMORY_WORDS),
    UNSIGNED(PmdBuffer, readIndex, 0, PMD_MAX_MEMORY_WORDS - 1),
    UNSIGNED(PmdBuffer, writeIndex, 0, PMD_MAX_MEMORY_WORDS - 1),
    UNSIGNED(PmdBuffer, unread, 0, PMD_MAX_MEMORY_WORDS),
    UNSIGNED(PmdBuffer, streamed, BOOL),
};
static const PmdStateStruct buffer = DESCRIBE(PmdBuffer, buffer_fields);

/* Variable slots and conditions are packed words (the PMDTraceVariable* and
 * PMDTraceTrigger* / PMDTraceCondition fields); state.c checks their parts. */
#define TRACE_VARIABLE_MAX PMD_FIELD_DP(PMD_AXES - 1, PMDTraceVariableID, PMDTraceAnalogInput8)
#define TRACE_CONDITION_MAX PMD_FIELD_DP(PMDTraceTriggerAxisMask | PMDTraceConditionMask | PMDTraceTriggerBitMask, \
                                         PMDTraceTriggerState, PMDTraceTriggerStateHigh)
static const PmdStateField trace_fields[] = {
    UNSIGNED(PmdTrace, mode, PMD_REG_TraceMode_RANGE),
    UNSIGNED(PmdTrace, period, PMD_REG_TracePeriod_RANGE),
    UNSIGNEDS(PmdTrace, variable, 0, TRACE_VARIABLE_MAX),
    UNSIGNED(PmdTrace, start, 0, TRACE_CONDITION_MAX),
    UNSIGNED(PmdTrace, stop, 0, TRACE_CONDITION_MAX),
    UNSIGNED(PmdTrace, active, BOOL),
    UNSIGNED(PmdTrace, wrapped, BOOL),
    UNSIGNED(PmdTrace, countdown, 0, UINT16_MAX - 1),
    UNSIGNED(PmdTrace, count, 0, PMD_MAX_MEMORY_WORDS),
};
static const PmdStateStruct trace = DESCRIBE(PmdTrace, trace_fields);

static const PmdStateField chip_state_fields[] = {
    STRUCTS(PmdChipState, axis, axis),
    STRUCTS(PmdChipState, buffer, buffer),
    STRUCT(PmdChipState, trace, trace),
    UNSIGNED(PmdChipState, updatedAxes, 0, PMDAxis1Mask | PMDAxis2Mask | PMDAxis3Mask | PMDAxis4Mask),
    UNSIGNED(PmdChipState, bufferEpoch, ANY_U32),
    UNSIGNED(PmdChipState, sampleTime, ANY_U16),                          /* 0 until initialized */
    UNSIGNED(PmdChipState, time, ANY_U32),
    UNSIGNED(PmdChipState, nextTime, ANY_U32),
    UNSIGNED(PmdChipState, hostIOError, ANY_U8),
    UNSIGNED(PmdChipState, loopback, BOOL),
    UNSIGNED(PmdChipState, serialPortMode, 0, SERIAL_PORT_MODE_MAX),
    UNSIGNED(PmdChipState, diagnosticPortMode, PMD_REG_DiagnosticPortMode_RANGE),
    UNSIGNED(PmdChipState, synchronizationMode, PMD_REG_SynchronizationMode_RANGE),
    UNSIGNEDS(PmdChipState, analogInput, ANY_U16),
    UNSIGNEDS(PmdChipState, ioInput, ANY_U16),
    UNSIGNEDS(PmdChipState, ioOutput, ANY_U16),
};
static const PmdStateStruct chip_state = DESCRIBE(PmdChipState, chip_state_fields);

/* The grid's fields: state.c checks that time lies on the grid with nextCycle
 * where it belongs (doStep keeps the indexes below 2^62). */
#define CYCLE_INDEX -(INT64_C(1) << 62), INT64_C(1) << 62
static const PmdStateField instance_state_fields[] = {
    UNSIGNED(PmdInstanceState, state, PMD_INSTANTIATED, PMD_TERMINATED),      /* one bit of PmdState: state.c */
    REAL(PmdInstanceState, cycleTime),
    SIGNED(PmdInstanceState, memorySize, 1, PMD_MAX_MEMORY_WORDS),
    REAL(PmdInstanceState, time),
    SIGNED(PmdInstanceState, nextCycle, CYCLE_INDEX),
    REAL(PmdInstanceState, anchorTime),
    SIGNED(PmdInstanceState, anchorCycle, CYCLE_INDEX),
    SIGNEDS(PmdInstanceState, hostWord, -32768, 65535),
    SIGNED(PmdInstanceState, hostWordCount, 0, PMD_BATCH_WORDS),
    SIGNED(PmdInstanceState, hostStrobe, ANY_I32),
    SIGNED(PmdInstanceState, hostAck, ANY_I32),
    SIGNEDS(PmdInstanceState, hostReply, ANY_U16),
    SIGNED(PmdInstanceState, hostReplyCount, 0, PMD_BATCH_WORDS),
    SIGNED(PmdInstanceState, hostError, ANY_U8),
    SIGNED(PmdInstanceState, memoryAddress, 0, PMD_MAX_MEMORY_WORDS),
    SIGNED(PmdInstanceState, memoryCount, 0, PMD_BATCH_WORDS),
    SIGNED(PmdInstanceState, memoryStrobe, ANY_I32),
    SIGNED(PmdInstanceState, memoryStrobeSeen, ANY_I32),
    SIGNEDS(PmdInstanceState, memoryData, ANY_I32),
    UNSIGNED(PmdInstanceState, scriptNext, 0, INT64_MAX),            /* within this instance's script: state.c */
    UNSIGNED(PmdInstanceState, scriptDigest, 0, INT64_MAX),
    UNSIGNED(PmdInstanceState, machineDigest, 0, INT64_MAX),
    UNSIGNED(PmdInstanceState, recordEnabled, BOOL),
};
static const PmdStateStruct instance_state = DESCRIBE(PmdInstanceState, instance_state_fields);

/* The instance's fields keep their names; the chip's are named chip.s. as the instance reaches them. */
static const PmdStateField image_fields[] = {
    {"", MEMBER(PmdStateImage, instance), PMD_SF_STRUCT, 0, 0, &instance_state},
    {"chip.s", MEMBER(PmdStateImage, chip), PMD_SF_STRUCT, 0, 0, &chip_state},
};
const PmdStateStruct pmd_state_image = DESCRIBE(PmdStateImage, image_fields);

/* ---- walking the list ---- */

typedef int (*Visit)(const PmdStateLeaf *leaf, void *context);

/* prefix NULL: no paths (a snapshot copies ~700 leaves; only messages need their names) */
static int walk(const PmdStateStruct *s, size_t base, const char *prefix, Visit visit, void *context)
{
    size_t f;
    unsigned e;
    for (f = 0; f < s->nFields; f++) {
        const PmdStateField *field = &s->fields[f];
        for (e = 0; e < field->count; e++) {
            PmdStateLeaf leaf;
            int result;
            leaf.path[0] = '\0';
            if (prefix && field->count > 1)
                snprintf(leaf.path, sizeof leaf.path, "%s%s[%u]", prefix, field->name, e);
            else if (prefix)
                snprintf(leaf.path, sizeof leaf.path, "%s%s", prefix, field->name);
            leaf.offset = base + field->offset + e * field->size;
            if (field->kind == PMD_SF_STRUCT) {
                char sub[sizeof leaf.path + 1];
                if (prefix && !*field->name)
                    snprintf(sub, sizeof sub, "%s", prefix);
                else if (prefix)
                    snprintf(sub, sizeof sub, "%s.", leaf.path);
                result = walk(field->sub, leaf.offset, prefix ? sub : NULL, visit, context);
            } else {
                leaf.size = field->size;
                leaf.kind = field->kind;
                leaf.min = field->min;
                leaf.max = field->max;
                result = visit(&leaf, context);
            }
            if (result)
                return result;
        }
    }
    return 0;
}

int pmd_state_walk(int named, int (*visit)(const PmdStateLeaf *leaf, void *context), void *context)
{
    return walk(&pmd_state_image, 0, named ? "" : NULL, visit, context);
}

/* ---- range checks ---- */

typedef struct {
    const unsigned char *image;
    char *why;
    size_t whySize;
} RangeCheck;

static int check_leaf(const PmdStateLeaf *leaf, void *context)
{
    const RangeCheck *c = (const RangeCheck *)context;
    const unsigned char *p = c->image + leaf->offset;
    uint8_t u8; uint16_t u16; uint32_t u32; uint64_t u64;
    int64_t value;
    double real;
    switch (leaf->kind) {
    case PMD_SF_REAL:
        memcpy(&real, p, sizeof real);
        if (isfinite(real))
            return 0;
        snprintf(c->why, c->whySize, "%s = %g is not finite", leaf->path, real);
        return -1;
    default:
        break;
    }
    switch (leaf->size) {
    case 1: memcpy(&u8, p, 1); u64 = u8; value = leaf->kind == PMD_SF_SIGNED ? (int8_t)u8 : (int64_t)u8; break;
    case 2: memcpy(&u16, p, 2); u64 = u16; value = leaf->kind == PMD_SF_SIGNED ? (int16_t)u16 : (int64_t)u16; break;
    case 4: memcpy(&u32, p, 4); u64 = u32; value = leaf->kind == PMD_SF_SIGNED ? (int32_t)u32 : (int64_t)u32; break;
    default: memcpy(&u64, p, 8); value = (int64_t)u64; break;
    }
    if (leaf->kind == PMD_SF_UNSIGNED && u64 > (uint64_t)INT64_MAX) {
        snprintf(c->why, c->whySize, "%s = %llu is not in %lld..%lld", leaf->path, (unsigned long long)u64,
                 (long long)leaf->min, (long long)leaf->max);
        return -1;
    }
    if (value < leaf->min || value > leaf->max) {
        snprintf(c->why, c->whySize, "%s = %lld is not in %lld..%lld", leaf->path, (long long)value,
                 (long long)leaf->min, (long long)leaf->max);
        return -1;
    }
    return 0;
}

int pmd_state_check_ranges(const void *image, char *why, size_t whySize)
{
    RangeCheck c;
    c.image = (const unsigned char *)image;
    c.why = why;
    c.whySize = whySize;
    if (pmd_state_walk(0, check_leaf, &c) == 0)
        return 0;
    return pmd_state_walk(1, check_leaf, &c);       /* again, to name the field */
}
