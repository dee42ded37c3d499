/* SPDX-License-Identifier: BSD-2-Clause */
/* The value of each Real, Integer and Boolean variable of the chip's FMU:
 * one table per type, read by the getters (instance.c) and by record.columns'
 * rows (record.c). Tables only (X macros), no functions. */
#ifndef PMD_VALUES_H
#define PMD_VALUES_H

#include "instance_types.h"

/* One table (family, expression) per type, expanded into the getters'
 * switches (pmd_model2_get_real, _integer, _boolean in instance.c) and into
 * the record.columns readers' (record.c), so that a getter and a column cannot disagree - the same
 * expression, hence the same floating-point operations. An expression reads
 * inst (PmdInstance *), i (the variable's index: its axis 0..3 or array
 * element) and, a Real, g (const PmdGrid *, the grid as it stands) and reals
 * (const PmdCommandedReals *, pmd_commanded_reals at g's cycle time: the
 * readers compute it where a PMD_READS_REALS family is read). */
#define PMD_AXIS(i) (&inst->chip.s.axis[(i)])
#define PMD_READS_REALS(family) \
    ((family) == VAR_axis_position || (family) == VAR_axis_velocity || (family) == VAR_axis_acceleration)
#define PMD_REAL_VALUES(X) \
    X(VAR_time, inst->s.time) \
    X(VAR_cycleTime, inst->s.cycleTime) \
    X(VAR_activeCycleTime, g->cycleTime) \
    X(VAR_nextCycleTime, g->anchorTime + (double)(g->nextCycle - g->anchorCycle) * g->cycleTime) \
    X(VAR_nextCycle, (double)g->nextCycle) \
    X(VAR_script_lastCycle, (double)inst->script.lastCycle) \
    X(VAR_axis_position, reals->position[i]) \
    X(VAR_axis_velocity, reals->velocity[i]) \
    X(VAR_axis_acceleration, reals->acceleration[i]) \
    /* full scale is the 16-bit command's 2^15 (GetCurrentMotorCommand: 100/2^15 % per count) */ \
    X(VAR_axis_motorOutput, PMD_AXIS(i)->filter.output / 32768.0)
#define PMD_INTEGER_VALUES(X) \
    X(VAR_memorySize, inst->s.memorySize) \
    X(VAR_chipTime, pmd_int32(inst->chip.s.time)) \
    X(VAR_axis_commandedPosition, PMD_AXIS(i)->trajectory.position) \
    X(VAR_axis_commandedVelocity, pmd_commanded_velocity(&PMD_AXIS(i)->trajectory)) \
    X(VAR_axis_commandedAcceleration, pmd_commanded_acceleration(&PMD_AXIS(i)->trajectory)) \
    X(VAR_axis_activityStatus, pmd_activity_status(&inst->chip, i)) \
    X(VAR_axis_eventStatus, PMD_AXIS(i)->eventStatus) \
    X(VAR_axis_motorCommand, PMD_AXIS(i)->filter.output) \
    X(VAR_axis_actualPosition, PMD_AXIS(i)->actualPositionInput) \
    X(VAR_host_word, inst->s.hostWord[i]) \
    X(VAR_host_wordCount, inst->s.hostWordCount) \
    X(VAR_host_strobe, inst->s.hostStrobe) \
    X(VAR_host_ack, inst->s.hostAck) \
    X(VAR_host_reply, inst->s.hostReply[i]) \
    X(VAR_host_replyCount, inst->s.hostReplyCount) \
    X(VAR_host_error, inst->s.hostError) \
    X(VAR_memory_address, inst->s.memoryAddress) \
    X(VAR_memory_count, inst->s.memoryCount) \
    X(VAR_memory_strobe, inst->s.memoryStrobe) \
    X(VAR_memory_data, inst->s.memoryData[i]) \
    X(VAR_analog, inst->chip.s.analogInput[i]) \
    X(VAR_io_input, inst->chip.s.ioInput[i]) \
    X(VAR_io_output, inst->chip.s.ioOutput[i]) \
    X(VAR_record_capacity, (int32_t)inst->recordCapacity) \
    X(VAR_record_rowSize, (int32_t)inst->columns.rowBytes) \
    X(VAR_script_axes, inst->script.axes)
#define PMD_BOOLEAN_VALUES(X) \
    X(VAR_loopback, inst->chip.s.loopback) \
    X(VAR_axis_positiveLimit, PMD_AXIS(i)->positiveLimitInput) \
    X(VAR_axis_negativeLimit, PMD_AXIS(i)->negativeLimitInput) \
    X(VAR_axis_home, PMD_AXIS(i)->homeInput) \
    X(VAR_axis_index, PMD_AXIS(i)->indexInput) \
    X(VAR_record_enabled, inst->s.recordEnabled) \
    X(VAR_host_interrupt, pmd_host_interrupt(&inst->chip))

#endif
