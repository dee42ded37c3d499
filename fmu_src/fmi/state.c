/* SPDX-License-Identifier: BSD-2-Clause */
/* FMU state: a snapshot of an instance as one self-describing block of bytes.
 *
 * A snapshot is the declared state (state_fields.h: the instance's
 * PmdInstanceState and the chip's PmdChipState, copied field by field into a
 * zeroed image), followed by the memory words, behind a header that lets a
 * restore refuse anything that is not a snapshot of this FMU build: magic,
 * format version, instantiation token, image size, memory size, total size
 * and a checksum of the body. What belongs to this process (names, hooks,
 * logging, the compiled script, the record buffer) is in the PmdInstance shell
 * around the declared state and stays the instance's: a snapshot holds how far
 * the script ran. The checksum catches accidents, not forgeries: a restore
 * also checks every field against its declared range and against the fields
 * it depends on, and refuses the whole snapshot, naming the field. The same
 * bytes serve fmi2/fmi3 Get/SetFMUState and (De)SerializeFMUState, in this
 * process or another one of the same build and platform. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "state.h"
#include "state_fields.h"

#define MAGIC PMD_STATE_MAGIC
typedef PmdStateHeader Header;
typedef PmdStateImage Image;

size_t pmd_state_size(const PmdInstance *inst)
{
    return sizeof(Header) + sizeof(Image) + (size_t)inst->s.memorySize * sizeof(uint32_t);
}

/* Where a field of the image lives in the instance: the instance's part in
 * inst->s, the chip's in inst->chip.s. */
static const unsigned char *live_field(const PmdInstance *inst, size_t offset)
{
    if (offset >= offsetof(Image, chip))
        return (const unsigned char *)&inst->chip.s + (offset - offsetof(Image, chip));
    return (const unsigned char *)&inst->s + (offset - offsetof(Image, instance));
}

typedef struct {
    unsigned char *image;
    const PmdInstance *inst;
} Writer;

static int write_leaf(const PmdStateLeaf *leaf, void *context)
{
    const Writer *w = (const Writer *)context;
    memcpy(w->image + leaf->offset, live_field(w->inst, leaf->offset), leaf->size);
    return 0;
}

/* The image holds the declared fields and zeros elsewhere: no padding byte
 * (whatever the compiler left in it) reaches the snapshot. */
void pmd_state_write(const PmdInstance *inst, unsigned char *out)
{
    Header h;
    Writer w;

    w.image = out + sizeof h;
    w.inst = inst;
    memset(w.image, 0, sizeof(Image));
    pmd_state_walk(0, write_leaf, &w);
    memcpy(w.image + sizeof(Image), inst->chip.memory, (size_t)inst->s.memorySize * sizeof(uint32_t));

    memset(&h, 0, sizeof h);
    memcpy(h.magic, MAGIC, sizeof h.magic);
    h.formatVersion = PMD_STATE_VERSION;
    h.instanceSize = (uint32_t)sizeof(Image);
    strncpy(h.token, PMD_INSTANTIATION_TOKEN, sizeof h.token - 1);
    h.totalSize = pmd_state_size(inst);
    h.memoryWords = (uint64_t)inst->s.memorySize;
    h.checksum = pmd_fnv1a(PMD_FNV1A_BASIS, w.image, (size_t)h.totalSize - sizeof h);
    memcpy(out, &h, sizeof h);
}

/* ---- what a field's value depends on ---- */

#define WHY(...) (snprintf(why, whySize, __VA_ARGS__), -1)

static int check_buffers(const PmdChipState *s, uint32_t memoryWords, char *why, size_t whySize)
{
    int i;
    for (i = 0; i < PMD_BUFFERS; i++) {
        const PmdBuffer *b = &s->buffer[i];
        if (b->length > 0 && (b->start > memoryWords || b->length > memoryWords - b->start))
            return WHY("chip.s.buffer[%d]: start 0x%X + length %u leave the %u-word memory", i, (unsigned)b->start,
                       (unsigned)b->length, (unsigned)memoryWords);
        if (b->length == 0 ? (b->readIndex | b->writeIndex | b->unread) != 0
                           : b->readIndex >= b->length || b->writeIndex >= b->length || b->unread > b->length)
            return WHY("chip.s.buffer[%d]: readIndex %u, writeIndex %u or unread %u does not fit length %u", i,
                       (unsigned)b->readIndex, (unsigned)b->writeIndex, (unsigned)b->unread, (unsigned)b->length);
    }
    return 0;
}

/* Trace words: variable slots hold the PMDTraceVariable{Axis,ID} fields,
 * conditions the PMDTraceTrigger{Axis,Bit,State} and PMDTraceCondition fields. */
static int check_trace(const PmdChipState *s, char *why, size_t whySize)
{
    const PmdTrace *t = &s->trace;
    const uint16_t condition[2] = {t->start, t->stop};
    int k;
    for (k = 0; k < PMD_TRACE_SLOTS; k++)
        if (PMD_FIELD_EX(t->variable[k], PMDTraceVariableAxis) >= PMD_AXES ||
            (t->variable[k] & ~(PMDTraceVariableAxisMask | PMDTraceVariableIDMask)) ||
            PMD_FIELD_EX(t->variable[k], PMDTraceVariableID) > PMDTraceAnalogInput8)
            return WHY("chip.s.trace.variable[%d] = 0x%04X: not an axis 0..3 and a variable 0..27", k,
                       (unsigned)t->variable[k]);
    for (k = 0; k < 2; k++)
        if (condition[k] && (PMD_FIELD_EX(condition[k], PMDTraceTriggerAxis) >= PMD_AXES ||
                             PMD_FIELD_EX(condition[k], PMDTraceCondition) > PMDTraceConditionSignalStatus))
            return WHY("chip.s.trace.%s = 0x%04X: not an axis 0..3 and a condition 0..4", k ? "stop" : "start",
                       (unsigned)condition[k]);
    /* A stopped trace's period and buffer 0 may change (only a running trace
     * locks them), and a start resets the countdown: these hold while it runs. */
    if (!t->active)
        return 0;
    if (s->buffer[0].length == 0)
        return WHY("chip.s.trace.active = 1 with trace buffer 0 of length 0");
    if (t->countdown >= t->period)
        return WHY("chip.s.trace.countdown = %u is not below the period %u", (unsigned)t->countdown,
                   (unsigned)t->period);
    if (t->count > s->buffer[0].length)
        return WHY("chip.s.trace.count = %u is more than trace buffer 0 holds (%u)", (unsigned)t->count,
                   (unsigned)s->buffer[0].length);
    return 0;
}

/* A moving S-curve: what pmd_scurve_cycle reads must describe the plan's unit
 * curve. A smooth stop shortens the cruise (t4) and keeps the plan's p6Total,
 * so p6Total is at least what the phases give; 0 means "already there". */
static int check_scurve(const PmdSCurve *c, int n, char *why, size_t whySize)
{
    int64_t total = 4 * c->t1 + 2 * c->t2 + c->t4, p6 = pmd_scurve_p6_total(c->t1, c->t2, c->t4);
    if (c->p6Total == 0)
        return 0;
    if (p6 < 0 || c->p6Total < p6)
        return WHY("chip.s.axis[%d].scurve.p6Total = %lld is less than 6 t1 (t1 + t2) (2 t1 + t2 + t4) or that "
                   "passes 2^62", n, (long long)c->p6Total);
    if (c->step >= total || c->p6 > c->p6Total || !pmd_scurve_on_curve(c))
        return WHY("chip.s.axis[%d].scurve: step %lld, p6 %lld, v2 %lld or a %lld is not on the unit curve", n,
                   (long long)c->step, (long long)c->p6, (long long)c->v2, (long long)c->a);
    return 0;
}

static int check_axes(const PmdChip *chip, char *why, size_t whySize)
{
    int n, f;
    for (n = 0; n < PMD_AXES; n++) {
        const PmdAxis *ax = &chip->s.axis[n];
        for (f = 0; f < PMD_FUNCTIONS; f++)
            if (ax->bufferOfFunction[f] >= 0 && ax->bufferOfFunction[f] < PMD_FIRST_PROFILE_BUFFER)
                return WHY("chip.s.axis[%d].bufferOfFunction[%d] = %d: buffers 0 and 1 belong to the trace", n, f,
                           ax->bufferOfFunction[f]);
        if (ax->buffersChecked == chip->s.bufferEpoch + 1 && !pmd_segment_plan_valid(chip, n))
            return WHY("chip.s.axis[%d].segmentStart/segmentBuffer: not what its buffers give", n);
        if (ax->active.stopMode != PMDNoStopMode || ax->active.clearPositionError)
            return WHY("chip.s.axis[%d].active: stopMode %u or clearPositionError %u (Update clears them)", n,
                       (unsigned)ax->active.stopMode, (unsigned)ax->active.clearPositionError);
        if (ax->motion == PMD_MOTION_SCURVE && check_scurve(&ax->scurve, n, why, whySize))
            return -1;
    }
    return 0;
}

/* The instance's declared state beside the chip's; live is the instance the
 * snapshot would replace. */
static int check_instance(const PmdInstanceState *s, const PmdChip *chip, const PmdInstance *live,
                          uint64_t memoryWords, char *why, size_t whySize)
{
    if ((uint64_t)s->memorySize != memoryWords)
        return WHY("memorySize %d and the header's %llu words differ", s->memorySize,
                   (unsigned long long)memoryWords);
    if (s->state & (s->state - 1))
        return WHY("state = %u is not one FMI state", (unsigned)s->state);
    if (!pmd_cycle_time_valid(s->cycleTime))
        return WHY("cycleTime %g is not a whole number of microseconds, 1..65535", s->cycleTime);
    if (s->state & (PMD_STEP_MODE | PMD_TERMINATED)) {
        /* the grid as doStep leaves it: its cycle time is the sample time register's, and the
         * next cycle is the first at or after time (before step mode, ExitInitializationMode
         * sets it up) */
        PmdGrid g;
        if (chip->s.sampleTime == 0)
            return WHY("chip.s.sampleTime = 0: the time grid's cycle time is 1..65535 microseconds");
        g = pmd_grid(s, &chip->s);
        if (!(fabs(s->time - g.anchorTime) / g.cycleTime < (double)(INT64_C(1) << 53)))
            return WHY("time %.17g is not within 2^53 cycles of anchorTime %.17g", s->time, s->anchorTime);
        if (s->nextCycle != pmd_cycles_before(&g, s->time))
            return WHY("nextCycle %lld is not where time %.17g lies on the grid of anchorTime %.17g, anchorCycle "
                       "%lld", (long long)s->nextCycle, s->time, s->anchorTime, (long long)s->anchorCycle);
        if (s->scriptDigest != live->s.scriptDigest || s->scriptNext > live->script.count)
            return WHY("scriptDigest: the state runs another script than this instance (restore it into an "
                       "instance initialized with the same script)");
        if (s->machineDigest != live->s.machineDigest)
            return WHY("machineDigest: the state runs in another machine than this instance (restore it into an "
                       "instance initialized with the same machine)");
    } else if (s->scriptNext != 0) {
        return WHY("scriptNext = %zu before the script is compiled", s->scriptNext);
    }
    if (s->memoryStrobe != s->memoryStrobeSeen && s->memoryCount > s->memorySize - s->memoryAddress)
        return WHY("memoryAddress %d + memoryCount %d of the pending write leave the %d-word memory",
                   s->memoryAddress, s->memoryCount, s->memorySize);
    if (check_buffers(&chip->s, (uint32_t)memoryWords, why, whySize) || check_trace(&chip->s, why, whySize))
        return -1;
    return check_axes(chip, why, whySize);
}

PmdStatus pmd_state_check(const PmdInstance *inst, const char *fn, const unsigned char *in, size_t size)
{
    Header h;
    char token[sizeof h.token] = {0}, field[256] = "";
    const char *why = NULL;
    if (!in || size < sizeof h) {
        why = "it is shorter than a snapshot header";
    } else {
        memcpy(&h, in, sizeof h);
        strncpy(token, PMD_INSTANTIATION_TOKEN, sizeof token - 1);
        if (memcmp(h.magic, MAGIC, sizeof h.magic) != 0)
            why = "it is not a pmdfmu snapshot (bad magic)";
        else if (h.formatVersion != PMD_STATE_VERSION)
            why = "its format version is not this build's";
        else if (memcmp(h.token, token, sizeof token) != 0)
            why = "it comes from another FMU (instantiation token differs)";
        else if (h.instanceSize != sizeof(Image))
            why = "it comes from a build with another state layout";
        else if (h.memoryWords < 1 || h.memoryWords > PMD_MAX_MEMORY_WORDS ||
                 h.totalSize != sizeof h + sizeof(Image) + h.memoryWords * sizeof(uint32_t))
            why = "its sizes are inconsistent";
        else if (h.totalSize != size)
            why = "it is truncated or has trailing bytes";
        else if (pmd_fnv1a(PMD_FNV1A_BASIS, in + sizeof h, size - sizeof h) != h.checksum)
            why = "it is corrupted (checksum mismatch)";
    }
    if (!why) {
        /* the declared state as the checks read it: the chip's inside a chip without memory or logger */
        PmdInstanceState *s = (PmdInstanceState *)malloc(sizeof *s);
        PmdChip *chip = (PmdChip *)calloc(1, sizeof *chip);
        if (!s || !chip) {
            why = "no host memory to check it";
        } else {
            memcpy(s, in + sizeof h + offsetof(Image, instance), sizeof *s);
            memcpy(&chip->s, in + sizeof h + offsetof(Image, chip), sizeof chip->s);
            if (pmd_state_check_ranges(in + sizeof h, field, sizeof field) ||
                check_instance(s, chip, inst, h.memoryWords, field, sizeof field))
                why = field;
        }
        free(s);
        free(chip);
    }
    if (why) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: FMU state of %zu bytes refused: %s", fn, size, why);
        return PMD_ERROR;
    }
    return PMD_OK;
}

/* Restores a snapshot pmd_state_check accepted: the declared state and the
 * memory; this process's fields (the memory block, hooks, logging, the script
 * and the record buffer) stay the instance's. */
PmdStatus pmd_state_read(PmdInstance *inst, const char *fn, const unsigned char *in)
{
    Header h;
    PmdInstanceState s;
    uint32_t *memory = inst->chip.memory;

    memcpy(&h, in, sizeof h);
    memcpy(&s, in + sizeof h + offsetof(Image, instance), sizeof s);
    /* a state in step mode that records needs the record.data buffer (of this instance's record.capacity);
     * before step mode nothing records until the end of initialization sizes it (record.capacity may
     * still be 0 then, as it may be when record.enabled is set in initialization mode) */
    if (s.recordEnabled && s.state == PMD_STEP_MODE && pmd_record_allocate(inst, fn))
        return PMD_ERROR;
    if ((int64_t)h.memoryWords != inst->s.memorySize) {
        memory = (uint32_t *)realloc(inst->chip.memory, (size_t)h.memoryWords * sizeof(uint32_t));
        if (!memory) {
            pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: out of host memory for %llu words", fn,
                             (unsigned long long)h.memoryWords);
            return PMD_ERROR;
        }
        inst->chip.memory = memory;
    }
    memcpy(memory, in + sizeof h + sizeof(Image), (size_t)h.memoryWords * sizeof(uint32_t));
    inst->s = s;
    memcpy(&inst->chip.s, in + sizeof h + offsetof(Image, chip), sizeof inst->chip.s);
    inst->chip.memorySize = (uint32_t)inst->s.memorySize;
    inst->recordCount = 0;                          /* the restored state has recorded nothing yet */
    return PMD_OK;
}

/* ---- FMU state objects, as both FMI versions hand them out ---- */

/* An FMU state object is a snapshot's bytes behind their size. */
typedef struct {
    size_t size;
    unsigned char bytes[];
} Snapshot;

static Snapshot *snapshot_alloc(const PmdInstance *inst, const char *fn, Snapshot *reuse, size_t size)
{
    Snapshot *s = (Snapshot *)realloc(reuse, sizeof(Snapshot) + size);
    if (s)
        s->size = size;
    else
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: out of host memory for %zu bytes", fn, size);
    return s;
}

static int state_given(const PmdInstance *inst, const char *fn, const void *state)
{
    if (!state)
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: the FMU state is NULL", fn);
    return state != NULL;
}

PmdStatus pmd_model_fmu_state_get(PmdInstance *inst, const char *fn, void **state)
{
    Snapshot *s;
    if (!state_given(inst, fn, state) || !(s = snapshot_alloc(inst, fn, (Snapshot *)*state, pmd_state_size(inst))))
        return PMD_ERROR;
    pmd_state_write(inst, s->bytes);
    *state = s;
    return PMD_OK;
}

PmdStatus pmd_model_fmu_state_set(PmdInstance *inst, const char *fn, const void *state)
{
    const Snapshot *s = (const Snapshot *)state;
    if (!state_given(inst, fn, state) || pmd_state_check(inst, fn, s->bytes, s->size) != PMD_OK)
        return PMD_ERROR;
    return pmd_state_read(inst, fn, s->bytes);
}

PmdStatus pmd_model_fmu_state_free(PmdInstance *inst, const char *fn, void **state)
{
    if (!state_given(inst, fn, state))
        return PMD_ERROR;
    free(*state);
    *state = NULL;
    return PMD_OK;
}

PmdStatus pmd_model_fmu_state_size(PmdInstance *inst, const char *fn, const void *state, size_t *size)
{
    if (!state_given(inst, fn, state) || !pmd_arrays_given(inst, fn, 1, size, size))
        return PMD_ERROR;
    *size = ((const Snapshot *)state)->size;
    return PMD_OK;
}

PmdStatus pmd_model_fmu_state_serialize(PmdInstance *inst, const char *fn, const void *state, unsigned char *bytes,
                                  size_t size)
{
    const Snapshot *s = (const Snapshot *)state;
    if (!state_given(inst, fn, state) || !pmd_arrays_given(inst, fn, 1, bytes, bytes))
        return PMD_ERROR;
    if (size != s->size) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: size %zu is not the state's %zu", fn, size, s->size);
        return PMD_ERROR;
    }
    memcpy(bytes, s->bytes, size);
    return PMD_OK;
}

PmdStatus pmd_model_fmu_state_deserialize(PmdInstance *inst, const char *fn, const unsigned char *bytes, size_t size,
                                    void **state)
{
    Snapshot *s;
    if (!state_given(inst, fn, state) || pmd_state_check(inst, fn, bytes, size) != PMD_OK ||
        !(s = snapshot_alloc(inst, fn, NULL, size)))
        return PMD_ERROR;
    memcpy(s->bytes, bytes, size);
    *state = s;
    return PMD_OK;
}
