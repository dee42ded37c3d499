/* Command handlers, one per row of modelDescription/commands.csv. The
 * dispatcher (host.c) has decoded the arguments by the table; a handler checks
 * their ranges (reference 1.2, 4.3), acts, and returns 0 or the host I/O
 * error code, having changed nothing when it refuses. */
#include <stddef.h>

#include "chip.h"
#include "command_table.h"

#define AXIS(n) (&chip->s.axis[n])

/* ---- miscellaneous ---- */

int cmd_NoOperation(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)chip; (void)axis; (void)arg; (void)reply;
    return 0;
}

int cmd_Reset(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis; (void)arg; (void)reply;
    pmd_chip_reset(chip);
    return 0;
}

int cmd_GetVersion(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)chip; (void)axis; (void)arg;
    reply[0] = 2;            /* generation: Navigator (reference 1.2, GetVersion) */
    reply[1] = 1;            /* motor type: brushed servo */
    reply[2] = PMD_AXES;
    reply[3] = 0;            /* special */
    reply[4] = 0;            /* custom */
    reply[5] = 1;            /* major */
    reply[6] = 0;            /* minor */
    return 0;
}

int cmd_GetHostIOError(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis; (void)arg;
    reply[0] = chip->s.hostIOError;
    chip->s.hostIOError = 0;                /* reading clears it (reference 2.4) */
    return 0;
}

/* ---- profile registers (buffered: reference 4.1) ---- */

int cmd_Update(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg; (void)reply;
    return pmd_update(chip, axis);
}

/* Axes update in ascending order; the first failure aborts the rest (reference 4.1). */
int cmd_MultiUpdate(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    int n;
    (void)axis; (void)reply;
    if (arg[0] & ~(int64_t)((1u << PMD_AXES) - 1u)) {
        pmd_log(chip, PMD_LOG_ERRORS, "MultiUpdate(0x%X): mask has bits beyond axis 4", (unsigned)arg[0]);
        return PMD_ERR_InvalidParameter;
    }
    for (n = 0; n < PMD_AXES; n++) {
        if (arg[0] & (1 << n)) {
            int err = pmd_update(chip, n);
            if (err)
                return err;
        }
    }
    return 0;
}

/* ---- trajectory outputs ---- */

int cmd_GetCommandedVelocity(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = pmd_commanded_velocity(&AXIS(axis)->trajectory);
    return 0;
}

int cmd_GetCommandedAcceleration(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = pmd_commanded_acceleration(&AXIS(axis)->trajectory);
    return 0;
}

/* ---- breakpoints (reference 2.5, seed 004) ---- */

static int breakpoint_id(const PmdChip *chip, int axis, const char *name, int64_t id)
{
    if (id > 1) {
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: %s: breakpoint %d is not 0 or 1", axis + 1, name, (int)id);
        return PMD_ERR_InvalidParameter;
    }
    return 0;
}

int cmd_SetBreakpoint(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    PmdBreakpoint *bp;
    int err = breakpoint_id(chip, axis, "SetBreakpoint", arg[0]);
    (void)reply;
    if (err)
        return err;
    if (arg[1] >= PMD_AXES || arg[2] > PMDBreakpointActionMotorOff || arg[3] > PMDBreakpointSignalStatus) {
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: SetBreakpoint: source axis %d, action %d or trigger %d out of range",
                axis + 1, (int)arg[1], (int)arg[2], (int)arg[3]);
        return PMD_ERR_InvalidParameter;
    }
    bp = &AXIS(axis)->breakpoint[arg[0]];
    bp->sourceAxis = (uint16_t)arg[1];
    bp->action = (uint16_t)arg[2];
    bp->trigger = (uint16_t)arg[3];
    /* A "crossed" trigger becomes >= or <= by where the source is now (reference 2.5). */
    if (bp->trigger == PMDBreakpointCommandedPositionCrossed)
        bp->trigger = AXIS(bp->sourceAxis)->trajectory.position < bp->value
                          ? PMDBreakpointGreaterOrEqualCommandedPosition : PMDBreakpointLessOrEqualCommandedPosition;
    else if (bp->trigger == PMDBreakpointActualPositionCrossed)
        bp->trigger = AXIS(bp->sourceAxis)->actualPosition < bp->value
                          ? PMDBreakpointGreaterOrEqualActualPosition : PMDBreakpointLessOrEqualActualPosition;
    return 0;
}

int cmd_GetBreakpoint(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    const PmdBreakpoint *bp;
    int err = breakpoint_id(chip, axis, "GetBreakpoint", arg[0]);
    if (err)
        return err;
    bp = &AXIS(axis)->breakpoint[arg[0]];
    reply[0] = bp->sourceAxis;
    reply[1] = bp->action;
    reply[2] = bp->trigger;
    return 0;
}

int cmd_SetBreakpointValue(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    int err = breakpoint_id(chip, axis, "SetBreakpointValue", arg[0]);
    (void)reply;
    if (!err)
        AXIS(axis)->breakpoint[arg[0]].value = (int32_t)arg[1];
    return err;
}

int cmd_GetBreakpointValue(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    int err = breakpoint_id(chip, axis, "GetBreakpointValue", arg[0]);
    if (!err)
        reply[0] = AXIS(axis)->breakpoint[arg[0]].value;
    return err;
}

/* ---- status registers and interrupts ---- */

int cmd_ResetEventStatus(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)reply;
    AXIS(axis)->eventStatus &= (uint16_t)arg[0];     /* bits written as 0 are cleared */
    return 0;
}

int cmd_GetActivityStatus(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = pmd_activity_status(chip, axis);
    return 0;
}

/* ---- buffer memory (reference 4.3) ---- */

static PmdBuffer *buffer(PmdChip *chip, const char *name, int64_t id)
{
    if (id >= PMD_BUFFERS) {
        pmd_log(chip, PMD_LOG_ERRORS, "%s: buffer ID %d is not 0..31", name, (int)id);
        return NULL;
    }
    return &chip->s.buffer[id];
}

/* start + length must stay inside the memory; both reset the indexes. */
static int set_block(PmdChip *chip, const char *name, int64_t id, int64_t start, int64_t length)
{
    PmdBuffer *b = buffer(chip, name, id);
    if (!b)
        return PMD_ERR_InvalidParameter;
    if (id == 0 && pmd_trace_busy(chip, name))
        return PMD_ERR_TraceRunning;
    if (start < 0 || length < 0 || length > 0x3FFFFFFF || start + length > chip->memorySize) {
        pmd_log(chip, PMD_LOG_ERRORS, "%s: buffer %d at 0x%llX length 0x%llX leaves the %u-word memory",
                name, (int)id, (long long)start, (long long)length, (unsigned)chip->memorySize);
        return PMD_ERR_BlockOutOfBounds;
    }
    b->start = (uint32_t)start;
    b->length = (uint32_t)length;
    chip->s.bufferEpoch++;
    b->readIndex = b->writeIndex = b->unread = 0;
    b->streamed = 0;
    pmd_log(chip, PMD_LOG_BUFFERS, "buffer %d: start 0x%X length %u", (int)id, (unsigned)b->start,
            (unsigned)b->length);
    return 0;
}

int cmd_SetBufferStart(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis; (void)reply;
    if (arg[0] >= PMD_BUFFERS)
        return set_block(chip, "SetBufferStart", arg[0], 0, 0);
    return set_block(chip, "SetBufferStart", arg[0], arg[1], chip->s.buffer[arg[0]].length);
}

int cmd_SetBufferLength(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis; (void)reply;
    if (arg[0] >= PMD_BUFFERS)
        return set_block(chip, "SetBufferLength", arg[0], 0, 0);
    return set_block(chip, "SetBufferLength", arg[0], chip->s.buffer[arg[0]].start, arg[1]);
}

#define GET_BUFFER_REGISTER(command, field)                                      \
    int cmd_##command(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply) \
    {                                                                            \
        const PmdBuffer *b = buffer(chip, #command, arg[0]);                     \
        (void)axis;                                                              \
        if (!b)                                                                  \
            return PMD_ERR_InvalidParameter;                                     \
        reply[0] = b->field;                                                     \
        return 0;                                                                \
    }

GET_BUFFER_REGISTER(GetBufferStart, start)
GET_BUFFER_REGISTER(GetBufferLength, length)
GET_BUFFER_REGISTER(GetBufferWriteIndex, writeIndex)
GET_BUFFER_REGISTER(GetBufferReadIndex, readIndex)

/* An index at or past the length is refused with 0x07 (reference 4.3). */
static int set_index(PmdChip *chip, const char *name, int64_t id, int64_t index, int write)
{
    PmdBuffer *b = buffer(chip, name, id);
    if (!b)
        return PMD_ERR_InvalidParameter;
    if (id == 0 && write && pmd_trace_busy(chip, name))
        return PMD_ERR_TraceRunning;
    if (index >= b->length) {
        pmd_log(chip, PMD_LOG_ERRORS, "%s: index %lld is not below buffer %d's length %u", name, (long long)index,
                (int)id, (unsigned)b->length);
        return PMD_ERR_BlockOutOfBounds;
    }
    if (write) {
        b->writeIndex = (uint32_t)index;
        b->streamed = 1;
    } else {
        b->readIndex = (uint32_t)index;
    }
    b->unread = (b->writeIndex + b->length - b->readIndex) % b->length;
    return 0;
}

int cmd_SetBufferWriteIndex(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis; (void)reply;
    return set_index(chip, "SetBufferWriteIndex", arg[0], arg[1], 1);
}

int cmd_SetBufferReadIndex(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis; (void)reply;
    return set_index(chip, "SetBufferReadIndex", arg[0], arg[1], 0);
}

static int nonempty(const PmdChip *chip, const char *name, int64_t id, const PmdBuffer *b)
{
    if (b->length == 0) {
        pmd_log(chip, PMD_LOG_ERRORS, "%s: buffer %d has length 0", name, (int)id);
        return PMD_ERR_BlockOutOfBounds;
    }
    return 0;
}

int cmd_WriteBuffer(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    PmdBuffer *b = buffer(chip, "WriteBuffer", arg[0]);
    uint32_t value;
    int err;
    (void)axis; (void)reply;
    if (!b)
        return PMD_ERR_InvalidParameter;
    if ((err = nonempty(chip, "WriteBuffer", arg[0], b)) != 0)
        return err;
    if (arg[0] == 0 && pmd_trace_busy(chip, "WriteBuffer"))
        return PMD_ERR_TraceRunning;
    if (b->streamed && b->unread == b->length)
        pmd_log(chip, PMD_LOG_WARNINGS, "WriteBuffer: buffer %d write index %u overtakes its read index: "
                "overwriting unread data, as the chip does", (int)arg[0], (unsigned)b->writeIndex);
    value = (uint32_t)arg[1];
    pmd_memory_store(chip, b->start + b->writeIndex, 1, &value);
    b->writeIndex = b->writeIndex + 1 == b->length ? 0 : b->writeIndex + 1;
    if (b->unread < b->length)
        b->unread++;
    b->streamed = 1;
    return 0;
}

int cmd_ReadBuffer(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    PmdBuffer *b = buffer(chip, "ReadBuffer", arg[0]);
    int err;
    (void)axis;
    if (!b)
        return PMD_ERR_InvalidParameter;
    if ((err = nonempty(chip, "ReadBuffer", arg[0], b)) != 0)
        return err;
    reply[0] = (int32_t)chip->memory[b->start + b->readIndex];
    b->readIndex = b->readIndex + 1 == b->length ? 0 : b->readIndex + 1;
    if (b->unread > 0)
        b->unread--;
    return 0;
}

static int buffer_function(const PmdChip *chip, int axis, const char *name, int64_t function)
{
    if (function < PMDBufferFunctionPosition || function > PMDBufferFunctionTime) {
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: %s: function %d is not 0 (position) .. 4 (time)", axis + 1, name,
                (int)function);
        return PMD_ERR_InvalidParameter;
    }
    return 0;
}

int cmd_SetBufferFunction(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    int err = buffer_function(chip, axis, "SetBufferFunction", arg[0]);
    (void)reply;
    if (err)
        return err;
    /* IDs 0 and 1 belong to the trace (seed 000, 1.1). */
    if (arg[1] != PMDBufferFunctionNone && (arg[1] < PMD_FIRST_PROFILE_BUFFER || arg[1] >= PMD_BUFFERS)) {
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: SetBufferFunction: buffer %d is not 2..31 or -1", axis + 1,
                (int)arg[1]);
        return PMD_ERR_InvalidParameter;
    }
    AXIS(axis)->bufferOfFunction[arg[0]] = (int16_t)arg[1];
    chip->s.bufferEpoch++;
    pmd_log(chip, PMD_LOG_BUFFERS, "axis %d: buffer %d feeds function %d", axis + 1, (int)arg[1], (int)arg[0]);
    return 0;
}

int cmd_GetBufferFunction(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    int err = buffer_function(chip, axis, "GetBufferFunction", arg[0]);
    if (!err)
        reply[0] = AXIS(axis)->bufferOfFunction[arg[0]];
    return err;
}

/* ---- axis registers that are not double-buffered (reference 4.1) ---- */

int cmd_SetGearMaster(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)reply;
    if (arg[0] >= PMD_AXES || arg[1] > PMDPositionSourceCommanded) {
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: SetGearMaster: master axis %d (0..3) or source %d (0..1) out of "
                "range", axis + 1, (int)arg[0], (int)arg[1]);
        return PMD_ERR_InvalidParameter;
    }
    AXIS(axis)->gearMasterAxis = (uint16_t)arg[0];
    AXIS(axis)->gearMasterSource = (uint16_t)arg[1];
    return 0;
}

int cmd_GetGearMaster(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = AXIS(axis)->gearMasterAxis;
    reply[1] = AXIS(axis)->gearMasterSource;
    return 0;
}

int cmd_ClearPositionError(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg; (void)reply;
    AXIS(axis)->buffered.clearPositionError = 1;
    return 0;
}

/* Moves the actual position by delta, and the commanded position and active
 * destination with it, so that nothing moves (reference 1.2); gear slaves of
 * this axis see no jump either. */
static void shift_actual(PmdChip *chip, int axis, int32_t delta)
{
    PmdAxis *ax = AXIS(axis);
    int n;
    ax->trajectory.position = pmd_int32((uint32_t)ax->trajectory.position + (uint32_t)delta);
    ax->active.position = pmd_int32((uint32_t)ax->active.position + (uint32_t)delta);
    if (!chip->s.loopback)
        ax->actualOffset = pmd_int32((uint32_t)ax->actualOffset + (uint32_t)delta);
    ax->actualPosition = pmd_int32((uint32_t)ax->actualPosition + (uint32_t)delta);
    ax->previousActualPosition = pmd_int32((uint32_t)ax->previousActualPosition + (uint32_t)delta);
    for (n = 0; n < PMD_AXES; n++)
        if (AXIS(n)->gearMasterAxis == axis)
            AXIS(n)->gearMasterLast = pmd_int32((uint32_t)AXIS(n)->gearMasterLast + (uint32_t)delta);
}

int cmd_SetActualPosition(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)reply;
    shift_actual(chip, axis, pmd_int32((uint32_t)arg[0] - (uint32_t)AXIS(axis)->actualPosition));
    return 0;
}

int cmd_AdjustActualPosition(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)reply;
    shift_actual(chip, axis, (int32_t)arg[0]);
    return 0;
}

int cmd_GetActualVelocity(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = pmd_actual_velocity(AXIS(axis));
    return 0;
}

int cmd_GetPositionError(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = pmd_position_error(AXIS(axis));
    return 0;
}

int cmd_GetSignalStatus(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = pmd_signal_status(chip, axis);
    return 0;
}

/* Reading the captured value re-arms the capture (reference 2.1, bit 9). */
int cmd_GetCaptureValue(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = AXIS(axis)->captureValue;
    AXIS(axis)->captured = 0;
    return 0;
}

/* The interrupt line is high while any axis has a masked event bit set;
 * ClearInterrupt cannot lower it before the host resets those bits. */
int cmd_ClearInterrupt(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)chip; (void)axis; (void)arg; (void)reply;
    return 0;
}

int cmd_GetInterruptAxis(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    int n;
    (void)axis; (void)arg;
    reply[0] = 0;
    for (n = 0; n < PMD_AXES; n++)
        if (AXIS(n)->eventStatus & AXIS(n)->interruptMask)
            reply[0] |= 1 << n;
    return 0;
}

/* The cycle time, in microseconds; the FMU restarts its cycle grid at once
 * (CONTRACT 2.2): PMD_GRID_CHANGED tells pmd_host_batch's caller. */
int cmd_SetSampleTime(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis; (void)reply;
    if (arg[0] == 0) {
        pmd_log(chip, PMD_LOG_ERRORS, "SetSampleTime(0): the cycle time is 1..65535 microseconds");
        return PMD_ERR_InvalidParameter;
    }
    chip->s.sampleTime = (uint16_t)arg[0];
    return PMD_GRID_CHANGED;
}

int cmd_GetSampleTime(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis; (void)arg;
    reply[0] = chip->s.sampleTime;
    return 0;
}
