/* SPDX-License-Identifier: BSD-2-Clause */
/* The chip FMU's instance as data: the declared state (PmdInstanceState),
 * the process shell around it (PmdInstance, the chip's PmdModel of model.h),
 * record.columns compiled and the time grid. Types only: instance.c, record.c,
 * state.c and the chip's other model files share them. */
#ifndef PMD_INSTANCE_TYPES_H
#define PMD_INSTANCE_TYPES_H

#include <stddef.h>
#include <stdint.h>

#include "chip.h"
#include "model.h"
#include "machine_toml.h"
#include "script.h"
#include "variables.h"

/* One column: a variable of variables.csv (its FMI 2 scalar), resolved once
 * to the family and index its value is read by (values.h). */
typedef struct {
    unsigned short family;           /* PmdFamily */
    unsigned short index;            /* the axis or array element */
    unsigned char bytes;             /* of its FMI 3 type: 8, 4, 2 (the low bits), 1 (a Boolean: 0 or 1) */
    uint32_t offset;                 /* of its value in a row */
} PmdRecordColumn;

/* record.columns compiled: count 0 is "" (the default row of PMD_RECORD_WORDS int32).
 * The columns are kept in the order of their families (each at its offset in
 * the row): a row switches once per family, then reads each of its columns. */
typedef struct {
    char *text;                      /* the value as set; NULL: "" */
    PmdRecordColumn *column;
    size_t count;
    int readsReals;                  /* a column's family is PMD_READS_REALS */
    uint32_t rowBytes;               /* of one row of record.data */
} PmdRecordColumns;

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
    uint64_t machineDigest;          /* of the machine it runs in (0: none): a snapshot runs on only in it */

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
     * script's text (docs/scripts.md); NULL: its start value, scriptStart (a
     * packed FMU's, read from its resources at instantiation) or "" */
    char *scriptPath;
    char *scriptStart;
    PmdScript script;
    /* the machine parameter, parsed at the end of initialization like the script
     * (docs/machine.md); NULL: "" (no machine). chip.machine points at machine
     * while it has an axis with an input to drive. */
    char *machinePath;
    PmdMachine machine;
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
    /* the caller's memory the rows go to instead of the buffer while it lends
     * it (pmdfmu_fmi2SetRecordBuffer, pmdfmu_fmi3SetRecordBuffer: recordLender,
     * which messages name), NULL when it does not; the FMU never frees it nor
     * keeps it past the caller's NULL or a reset */
    unsigned char *recordLent;
    size_t recordLentBytes;
    const char *recordLender;
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

#endif
