/* SPDX-License-Identifier: BSD-2-Clause */
#ifndef PMD_NATIVE_SYSTEM_H
#define PMD_NATIVE_SYSTEM_H

/* A system of FMUs stepped together cycle by cycle (pmdfmu.System, python/pmdfmu/system.py): per
 * communication step a list of operations (the gets and sets of the connections, each FMU's doStep,
 * the gets of the recorded columns) over the FMUs' own FMI functions, in the order the harness's
 * master (examples/systems' run_master) calls them, and one row of columns copied from the values. */

#include <stddef.h>
#include <stdint.h>

#include "native.h"
#include "record_loop.h"

/* A value between a get and the sets that read it: both readings, so that an Integer output can
 * feed a Real input as FMPy's master passes a Python int to a Real setter. */
typedef struct {
    int64_t integer;
    double real;
} PmdSystemValue;

enum { PMD_SYSTEM_GET, PMD_SYSTEM_SET, PMD_SYSTEM_STEP };

/* One operation. get / set: fn the FMU's fmi2Get/Set<Type> or fmi3Get/Set<Type> of one value
 * reference, `type` its PmdLoopType, `value` its slot. step: fn the FMU's doStep, `type` the FMI
 * version (2 or 3), from start + k * step of `step` s (k: the step's index). */
typedef struct {
    int kind;
    int type;
    PmdFmiFunction fn;
    void *instance;
    unsigned int vr;
    size_t value;
} PmdSystemOp;

/* One field of a row: `size` bytes at `offset` from the row's value `value` (its integer's low bytes
 * for an integer or boolean field, its real for a double). */
typedef struct {
    size_t value;
    size_t offset;
    size_t size;
    int real;
} PmdSystemColumn;

/* Runs `steps` steps k = first .. first + steps - 1, each the ops in order, then a row (row_bytes, the
 * int64 step number k + 1 at offset 0, then the columns; rows may be NULL: no rows). Returns 0, or 1
 * with *stop: after `done` whole steps, op `call` returned `status` > Warning. */
PMD_NATIVE_EXPORT int pmd_system_run(const PmdSystemOp *ops, size_t n_ops, PmdSystemValue *values,
                                     const PmdSystemColumn *columns, size_t n_columns, double start, double step,
                                     int64_t first, size_t steps, void *rows, size_t row_bytes, PmdStop *stop);

#endif
