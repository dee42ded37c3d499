/* FMU state: a snapshot of an instance as one self-describing block of bytes.
 *
 * The instance is plain data except for its memory block and its logging
 * hooks, so a snapshot is the instance struct (pointers cleared) followed by
 * the memory words (the compiled script stays the instance's: a snapshot
 * holds how far the script ran), behind a header that lets a restore refuse anything that
 * is not a snapshot of this FMU build: magic, format version, instantiation
 * token, struct size, memory size, total size and a checksum of the body.
 * The same bytes serve fmi2/fmi3 Get/SetFMUState and (De)SerializeFMUState,
 * in this process or another one of the same build and platform. */
#include <stdlib.h>
#include <string.h>

#include "state.h"

#define MAGIC "PMDFMUST"
#define FORMAT_VERSION 1u

typedef struct {
    char magic[8];
    uint32_t formatVersion;
    uint32_t instanceSize;       /* sizeof(PmdInstance): the layout of this build */
    char token[48];              /* PMD_INSTANTIATION_TOKEN */
    uint64_t totalSize;
    uint64_t memoryWords;
    uint64_t checksum;           /* FNV-1a over everything after the header */
} Header;

static uint64_t fnv1a(const unsigned char *p, size_t n)
{
    uint64_t h = 14695981039346656037u;
    size_t i;
    for (i = 0; i < n; i++) {
        h ^= p[i];
        h *= 1099511628211u;
    }
    return h;
}

size_t pmd_state_size(const PmdInstance *inst)
{
    return sizeof(Header) + sizeof(PmdInstance) + (size_t)inst->memorySize * sizeof(uint32_t);
}

void pmd_state_write(const PmdInstance *inst, unsigned char *out)
{
    Header h;
    PmdInstance copy;
    unsigned char *body = out + sizeof h;

    memcpy(&copy, inst, sizeof copy);
    /* what belongs to this process, not to the state */
    copy.chip.memory = NULL;
    copy.chip.logger = NULL;
    copy.chip.logContext = NULL;
    copy.instanceName = NULL;
    copy.logger = NULL;
    copy.environment = NULL;
    copy.scriptPath = NULL;
    memset(&copy.script, 0, sizeof copy.script);
    copy.record = NULL;
    memcpy(body, &copy, sizeof copy);
    memcpy(body + sizeof copy, inst->chip.memory, (size_t)inst->memorySize * sizeof(uint32_t));

    memset(&h, 0, sizeof h);
    memcpy(h.magic, MAGIC, sizeof h.magic);
    h.formatVersion = FORMAT_VERSION;
    h.instanceSize = (uint32_t)sizeof(PmdInstance);
    strncpy(h.token, PMD_INSTANTIATION_TOKEN, sizeof h.token - 1);
    h.totalSize = pmd_state_size(inst);
    h.memoryWords = (uint64_t)inst->memorySize;
    h.checksum = fnv1a(body, (size_t)h.totalSize - sizeof h);
    memcpy(out, &h, sizeof h);
}

PmdStatus pmd_state_check(const PmdInstance *inst, const char *fn, const unsigned char *in, size_t size)
{
    Header h;
    const char *why = NULL;
    if (!in || size < sizeof h) {
        why = "it is shorter than a snapshot header";
    } else {
        memcpy(&h, in, sizeof h);
        if (memcmp(h.magic, MAGIC, sizeof h.magic) != 0)
            why = "it is not a pmdfmu snapshot (bad magic)";
        else if (h.formatVersion != FORMAT_VERSION)
            why = "its format version is not this build's";
        else if (strncmp(h.token, PMD_INSTANTIATION_TOKEN, sizeof h.token) != 0)
            why = "it comes from another FMU (instantiation token differs)";
        else if (h.instanceSize != sizeof(PmdInstance))
            why = "it comes from a build with another state layout";
        else if (h.memoryWords < 1 || h.memoryWords > PMD_MAX_MEMORY_WORDS ||
                 h.totalSize != sizeof h + sizeof(PmdInstance) + h.memoryWords * sizeof(uint32_t))
            why = "its sizes are inconsistent";
        else if (h.totalSize != size)
            why = "it is truncated or has trailing bytes";
        else if (fnv1a(in + sizeof h, size - sizeof h) != h.checksum)
            why = "it is corrupted (checksum mismatch)";
    }
    if (why) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: FMU state of %zu bytes refused: %s", fn, size, why);
        return PMD_ERROR;
    }
    return PMD_OK;
}

PmdStatus pmd_state_read(PmdInstance *inst, const char *fn, const unsigned char *in)
{
    Header h;
    PmdInstance saved = *inst, copy;
    uint32_t *memory = inst->chip.memory;
    memcpy(&h, in, sizeof h);
    memcpy(&copy, in + sizeof h, sizeof copy);
    if ((int64_t)h.memoryWords != inst->memorySize) {
        memory = (uint32_t *)realloc(inst->chip.memory, (size_t)h.memoryWords * sizeof(uint32_t));
        if (!memory) {
            pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: out of host memory for %llu words", fn,
                             (unsigned long long)h.memoryWords);
            return PMD_ERROR;
        }
    }
    memcpy(memory, in + sizeof h + sizeof copy, (size_t)h.memoryWords * sizeof(uint32_t));
    *inst = copy;
    /* this process's hooks, and this instance's logging settings, stay */
    inst->chip.memory = memory;
    inst->chip.logger = saved.chip.logger;
    inst->chip.logContext = saved.chip.logContext;
    inst->chip.logMask = saved.chip.logMask;
    inst->instanceName = saved.instanceName;
    inst->logger = saved.logger;
    inst->environment = saved.environment;
    inst->loggingOn = saved.loggingOn;
    inst->categories = saved.categories;
    /* the script is this instance's parameter; the snapshot keeps only how far it ran */
    inst->scriptPath = saved.scriptPath;
    inst->script = saved.script;
    /* so is the recording buffer; the restored state has recorded nothing yet */
    inst->record = saved.record;
    inst->recordCapacity = saved.recordCapacity;
    inst->recordEnabled = (uint8_t)(inst->recordEnabled && inst->record);
    inst->recordCount = 0;
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

PmdStatus pmd_fmu_state_get(PmdInstance *inst, const char *fn, void **state)
{
    Snapshot *s;
    if (!state_given(inst, fn, state) || !(s = snapshot_alloc(inst, fn, (Snapshot *)*state, pmd_state_size(inst))))
        return PMD_ERROR;
    pmd_state_write(inst, s->bytes);
    *state = s;
    return PMD_OK;
}

PmdStatus pmd_fmu_state_set(PmdInstance *inst, const char *fn, const void *state)
{
    const Snapshot *s = (const Snapshot *)state;
    if (!state_given(inst, fn, state) || pmd_state_check(inst, fn, s->bytes, s->size) != PMD_OK)
        return PMD_ERROR;
    return pmd_state_read(inst, fn, s->bytes);
}

PmdStatus pmd_fmu_state_free(PmdInstance *inst, const char *fn, void **state)
{
    if (!state_given(inst, fn, state))
        return PMD_ERROR;
    free(*state);
    *state = NULL;
    return PMD_OK;
}

PmdStatus pmd_fmu_state_size(PmdInstance *inst, const char *fn, const void *state, size_t *size)
{
    if (!state_given(inst, fn, state) || !pmd_arrays_given(inst, fn, 1, size, size))
        return PMD_ERROR;
    *size = ((const Snapshot *)state)->size;
    return PMD_OK;
}

PmdStatus pmd_fmu_state_serialize(PmdInstance *inst, const char *fn, const void *state, unsigned char *bytes,
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

PmdStatus pmd_fmu_state_deserialize(PmdInstance *inst, const char *fn, const unsigned char *bytes, size_t size,
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
