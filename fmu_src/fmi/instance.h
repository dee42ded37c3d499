/* One FMU instance: the chip, its memory, the host and dual-port memory
 * ports, the parameters and the time grid. Declared state (PmdInstanceState,
 * the chip's PmdChipState) apart from the process shell (PmdInstance).
 * Independent of the FMI version: the chip's model (fmi_common/model.h), which
 * the FMI shells (fmi_common/fmi2.c, fmi3.c) map the FMI APIs onto; this file
 * declares what the chip's model files (instance.c, record.c, state.c, model3.c)
 * share beyond that API. */
#ifndef PMD_INSTANCE_H
#define PMD_INSTANCE_H

#include <stddef.h>

#include "chip.h"
#include "model.h"
#include "record.h"
#include "script.h"
#include "variables.h"

#define PMD_MAX_MEMORY_WORDS (1u << 26)   /* 256 MiB of external memory at most */

/* The instance's declared state: plain data, no pointer, nothing of this
 * process. An FMU state (state.c) is this struct, the chip's (chip.s) and the
 * memory words, copied field by field by the list in state_fields.c. */
typedef struct {
    PmdState state;

    /* parameters */
    double cycleTime;                /* initialization loads it into the chip's sample time register */
    int32_t memorySize;

    /* The time grid: chip cycle k runs at anchorTime + (k - anchorCycle) * the
     * cycle time, which is the chip's sample time register (pmd_grid); nextCycle
     * is the next k to run, time the last communication point. A host batch or
     * script step that changes the sample time restarts the grid at the next
     * cycle (CONTRACT 2.2). Initialization sets it up at time 0, cycle 0. */
    double time;
    int64_t nextCycle;
    double anchorTime;
    int64_t anchorCycle;

    /* host port */
    int32_t hostWord[PMD_BATCH_WORDS];
    int32_t hostWordCount, hostStrobe, hostAck;
    int32_t hostReply[PMD_BATCH_WORDS];
    int32_t hostReplyCount, hostError;

    /* dual-port memory port */
    int32_t memoryAddress, memoryCount, memoryStrobe, memoryStrobeSeen;
    int32_t memoryData[PMD_BATCH_WORDS];

    /* how far the script ran */
    size_t scriptNext;               /* the next step to run */
    uint64_t scriptDigest;           /* of the compiled script it runs (0: none): a snapshot runs on only with it */

    uint8_t recordEnabled;           /* record.enabled */
} PmdInstanceState;

/* The process shell around the declared state: names, hooks and buffers of
 * this process, which an FMU state neither holds nor restores. It is the chip's
 * PmdModel (model.h). */
typedef struct PmdModel PmdInstance;
struct PmdModel {
    PmdInstanceState s;
    PmdChip chip;                    /* chip.s is declared state; its memory block and logger are this process's */
    char *instanceName;
    PmdModelLogger logger;
    void *environment;
    int loggingOn;
    unsigned categories;             /* bit per PmdLogCategory enabled by SetDebugLogging */

    /* the script parameter, compiled at the end of initialization: a path or the
     * script's text (README, "Scripts"); NULL: its start value, scriptStart (a
     * packed FMU's, read from its resources at instantiation) or "" */
    char *scriptPath;
    char *scriptStart;
    PmdScript script;
    /* where relative paths are looked for: the FMU's resources folder, as the
     * importer named it at instantiation (ending in a separator), or NULL and why */
    char *resources;
    const char *noResources;

    /* bulk recording (record.data; FMI 2: pmdfmu_fmi2GetRecordData): a row per
     * cycle of the last doStep, PMD_RECORD_WORDS int32 or the columns of
     * record.columns (record.c). The buffer, its size and record.columns are
     * this process's: a restored state keeps the instance's record.capacity
     * and record.columns and has recorded nothing yet. */
    uint32_t recordCapacity;         /* cycles (the record.capacity parameter) */
    int32_t *record;
    uint32_t recordRows;             /* cycles the record buffer holds (record.capacity when it was allocated) */
    size_t recordBytes;              /* bytes the record buffer holds */
    uint32_t recordCount;            /* cycles recorded by the last doStep */
    uint32_t recordRowBytes;         /* bytes of each of those rows (as record.columns stood at that doStep) */
    /* FMI 2: the caller's memory the rows go to instead of the buffer while it
     * lends it (pmdfmu_fmi2SetRecordBuffer), NULL when it does not; the FMU
     * never frees it nor keeps it past the caller's NULL or a reset */
    unsigned char *recordLent;
    size_t recordLentBytes;
    PmdRecordColumns columns;        /* record.columns */
    PmdRecordColumns stagedColumns;  /* a set call's new record.columns, compiled by its check */

    /* A set call checks every value, then what they ask for together (a memory
     * write that must fit the memory, a memory size that must hold the
     * buffers), then applies them: a refused call changes nothing. */
    struct {
        int32_t memorySize, memoryAddress, memoryCount, memoryStrobe;
        uint32_t *memory;            /* the new memory block of a memorySize change, allocated by the check */
    } staged;
};

#define PMD_MAX_RECORD_CYCLES (1u << 24)

/* The model API (model.h) is this instance's public face; what follows is
 * shared by the chip's model files beyond it. */

/* The `script` parameter's value: as set, or its start value. */
const char *pmd_script_value(const PmdInstance *inst);
/* Whether seconds is a cycle time the sample time register holds: whole microseconds, 1..65535. */
int pmd_cycle_time_valid(double seconds);

/* The time grid as it stands: chip cycle k runs at anchorTime + (k - anchorCycle)
 * * cycleTime, nextCycle is the next k to run. From the end of initialization
 * on, the declared anchor and nextCycle, and the chip's sample time register
 * in seconds (sampleTime / 1e6, correctly rounded); before it, the grid
 * initialization will set up: anchored at time 0, cycle 0, with the cycleTime
 * parameter as the register will hold it. */
typedef struct {
    double anchorTime, cycleTime;
    int64_t anchorCycle, nextCycle;
} PmdGrid;
PmdGrid pmd_grid(const PmdInstanceState *s, const PmdChipState *chip);
/* The grid index of the first cycle at or after t (within a master's rounding). */
int64_t pmd_cycles_before(const PmdGrid *grid, double t);
/* Allocates record.data's buffer (record.capacity cycles of record.columns' rows) unless it
 * exists; never in doStep. A larger block keeps the rows recorded. */
PmdStatus pmd_record_allocate(PmdInstance *inst, const char *fn);
/* record.data's bytes: the rows the last doStep recorded (lent until the next call). */
void pmd_record_data(const PmdInstance *inst, const unsigned char **data, size_t *size);
/* FMI 2's pmdfmu_fmi2SetRecordBuffer: the caller's memory for the rows of the recording doSteps that follow, or
 * NULL for record.data's buffer again. */
void pmd_record_lend(PmdInstance *inst, void *rows, size_t bytes);
/* Where a recording doStep writes its rows, and how many fit there (record.columns as it stands). */
unsigned char *pmd_record_rows(const PmdInstance *inst);
int64_t pmd_record_room(const PmdInstance *inst);

/* record.columns (record.c). Compiles a value: names checked and resolved to
 * value references once; PMD_ERROR with a message naming fn, the value and
 * the reason, *out untouched. */
PmdStatus pmd_record_columns_compile(PmdInstance *inst, const char *fn, const char *text, PmdRecordColumns *out);
void pmd_record_columns_free(PmdRecordColumns *columns);
/* The set call's staged value: checked (and the buffer grown if recording) with apply = 0, installed with 1. */
PmdStatus pmd_record_columns_set(PmdInstance *inst, const char *fn, const char *text, int apply);
/* A recording doStep with record.columns: runs `cycles` cycles one by one, each
 * ending as a one-cycle doStep ends (nextCycle advanced), and writes each
 * cycle's row into record.data from row `first` on. */
void pmd_record_cycles(PmdInstance *inst, int64_t cycles, int64_t first);

/* Checks that arrays holding n values are not NULL; logs and returns 0 if one is. */
int pmd_arrays_given(const PmdInstance *inst, const char *fn, size_t n, const void *a, const void *b);

/* The row of a generated variable table that holds vr (of_vr: the row by value
 * reference, -1 none; max: the largest value reference), or -1, logged as "no
 * variable has value reference vr": the FMI 2 table's and variables3.h's alike. */
int pmd_variable_row(const PmdInstance *inst, const char *fn, unsigned vr, const short *of_vr, unsigned max);

/* Variable access beyond model.h's, one value at a time (model.h: a set call
 * is all or nothing). Integer values come as the FMI type holds them (FMI 3
 * UInt32 unsigned), so that a message shows the value the caller sent. */
PmdStatus pmd_set_integer(PmdInstance *inst, const char *fn, unsigned vr, int64_t value, int apply);
/* A block of memory.data (a strobe's words, Chip.write_memory), set at once
 * rather than value by value, with the same checks, messages and staging.
 * pmd_memory_data_span: how many of the n value references vr, vr + 1, ..
 * are elements of memory.data (0 if vr is none; element k + 1 is vr + k:
 * FMI 3's array and FMI 2's scalars alike, variables3.h). pmd_set_memory_data:
 * pmd_set_integer of each of those n elements in turn, the words 32-bit (FMI
 * 2 Integer: isSigned; FMI 3 UInt32: not). */
size_t pmd_memory_data_span(unsigned vr, size_t n);
PmdStatus pmd_set_memory_data(PmdInstance *inst, const char *fn, unsigned vr, const void *words, int isSigned,
                              size_t n, int apply);

/* Executes pending host and memory port writes (host batch first; CONTRACT 2.1). */
void pmd_commit_ports(PmdInstance *inst);

void pmd_instance_log(const PmdInstance *inst, PmdStatus status, PmdLogCategory category, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

#endif
