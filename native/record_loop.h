/* SPDX-License-Identifier: BSD-2-Clause */
#ifndef PMD_NATIVE_RECORD_LOOP_H
#define PMD_NATIVE_RECORD_LOOP_H

/* Recording a run cycle by cycle through an FMU's own FMI functions
 * (Chip.run(cycles, record=names), python/pmdfmu/chip.py): per cycle, one
 * doStep to the next cycle of the FMU's grid and one get per FMI type, the
 * columns copied into the rows of a numpy structured array. */

#include <stddef.h>

#include "native.h"

/* The C type of a getter's values. */
typedef enum {
    PMD_LOOP_DOUBLE,      /* fmi2Real, fmi3Float64 */
    PMD_LOOP_INT32,       /* fmi2Integer, fmi3Int32 */
    PMD_LOOP_UINT32,      /* fmi3UInt32 */
    PMD_LOOP_UINT16,      /* fmi3UInt16 */
    PMD_LOOP_INT16,       /* fmi3Int16 */
    PMD_LOOP_INT,         /* fmi2Boolean (an int) */
    PMD_LOOP_BOOL         /* fmi3Boolean (a bool, one byte: 0 or 1) */
} PmdLoopType;

/* One get a cycle: the FMU's fmi2Get<Type> or fmi3Get<Type> of these value
 * references, into `values` (FMI 3 arrays are read whole: n_values counts
 * their elements; in FMI 2, n_values == n_vrs). */
typedef struct {
    PmdFmiFunction get;
    const unsigned int *vrs;
    size_t n_vrs;
    size_t n_values;
    int type;               /* PmdLoopType of values */
    void *values;
} PmdLoopGroup;

/* One field of a row: `size` bytes at `offset` from the row's start, copied
 * from a value in a group's buffer (`source`, its address). An integer field
 * takes the low bytes of a value as wide or wider (the harness's Python loop
 * masked FMI 2's signed Integer to the register's width: the same bits); a
 * boolean field of an fmi2Boolean (`truth`) is value != 0. */
typedef struct {
    const void *source;
    size_t offset;
    size_t size;            /* 1, 2, 4 or 8 */
    int truth;              /* the source is an fmi2Boolean (int), the field numpy's one-byte bool */
} PmdLoopColumn;

/* Records `cycles` rows of `row_bytes` each into `rows`. The grid group's
 * values at grid_place .. grid_place + 2 are the FMU's time, nextCycleTime and
 * activeCycleTime (doubles): read once before the first cycle, then with the
 * columns after each doStep, each doStep going from time to the next cycle's
 * end, (nextCycleTime - time) + activeCycleTime. Returns 0, or 1 and *stop
 * filled if a call failed: after `done` whole rows, the call `call` (-1 the
 * doStep, else the group's index) returned `status` > Warning; or, before any
 * call, `call` PMD_LOOP_FIELD_SIZE, a column of another size. */
PMD_NATIVE_EXPORT int pmd_record_fmi2(PmdFmiFunction do_step, void *instance, const PmdLoopGroup *groups, size_t n_groups,
                                      size_t grid_group, size_t grid_place, const PmdLoopColumn *columns,
                                      size_t n_columns, void *rows, size_t row_bytes, size_t cycles,
                                      PmdStop *stop);
PMD_NATIVE_EXPORT int pmd_record_fmi3(PmdFmiFunction do_step, void *instance, const PmdLoopGroup *groups, size_t n_groups,
                                      size_t grid_group, size_t grid_place, const PmdLoopColumn *columns,
                                      size_t n_columns, void *rows, size_t row_bytes, size_t cycles,
                                      PmdStop *stop);

/* The call pmd_record_fmi2/3 name when a column's size is none of 1, 2, 4, 8: no call ran */
enum { PMD_LOOP_FIELD_SIZE = -2 };

/* The FMU's extension functions beside the FMI ones (fmu_src/fmi/record_fmi2.c, record_fmi3.c):
 * pmdfmu_fmi2SetRecordBuffer and pmdfmu_fmi3SetRecordBuffer have the same C type; FMI 2's
 * record.data, which FMI 3 reads with fmi3GetBinary */
typedef int PmdSetRecordBuffer(void *instance, void *rows, size_t size);
typedef int PmdGetRecordData(void *instance, const void **data, size_t *size);

/* Which call of pmd_record_step_lent failed */
enum { PMD_STEP_LEND, PMD_STEP_DO_STEP, PMD_STEP_GET_DATA, PMD_STEP_END_LOAN };

/* One recording doStep of an FMU into the caller's memory (Chip.run):
 * `rows` (`size` bytes) lent to the FMU (set_buffer: pmdfmu_fmi2SetRecordBuffer,
 * pmdfmu_fmi3SetRecordBuffer), the step from `now` of `step` s (do_step:
 * fmi2DoStep, fmi3DoStep), the bytes it recorded there asked for (get_data:
 * pmdfmu_fmi2GetRecordData, or fmi3GetBinary of record.data, value reference
 * data_vr; *recorded, 0 if the rows are elsewhere) and the loan ended, in
 * this one call: no Python code (a KeyboardInterrupt, an exception) runs
 * while the FMU holds a pointer into the caller's memory, so the loan cannot
 * outlive it. Returns the doStep's status (Warning: a grid change inside the
 * step), or that of the first call that failed (*call). */
PMD_NATIVE_EXPORT int pmd_record_step_lent(int fmi3, PmdFmiFunction set_buffer, PmdFmiFunction get_data,
                                           unsigned int data_vr, PmdFmiFunction do_step, void *instance,
                                           double now, double step, void *rows, size_t size, size_t *recorded,
                                           int *call);

#endif
