/* SPDX-License-Identifier: BSD-2-Clause */
/* Buffer memory (reference 4.3): 32 buffers in the external memory, set up
 * by start and length, read and written at their indexes, and assigned to an
 * axis's trajectory functions (SetBufferFunction, seed 000). */
#include <stddef.h>

#include "commands.h"

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
