#ifndef PMD_NATIVE_RECORD_H
#define PMD_NATIVE_RECORD_H

/* Recording a run cycle by cycle through an FMU's own FMI functions
 * (Chip.run(cycles, record=names), python/pmdfmu/chip.py): per cycle, one
 * doStep to the next cycle of the FMU's grid and one get per FMI type, the
 * columns copied into the rows of a numpy structured array. */

#include <stddef.h>

#include "native.h"

/* An FMI function of the FMU, any signature (ISO C converts function pointers among themselves only) */
typedef void (*PmdRecordFunction)(void);

/* The C type of a getter's values. */
typedef enum {
    PMD_RECORD_DOUBLE,      /* fmi2Real, fmi3Float64 */
    PMD_RECORD_INT32,       /* fmi2Integer, fmi3Int32 */
    PMD_RECORD_UINT32,      /* fmi3UInt32 */
    PMD_RECORD_UINT16,      /* fmi3UInt16 */
    PMD_RECORD_INT16,       /* fmi3Int16 */
    PMD_RECORD_INT,         /* fmi2Boolean (an int) */
    PMD_RECORD_BOOL         /* fmi3Boolean (a bool, one byte: 0 or 1) */
} PmdRecordType;

/* One get a cycle: the FMU's fmi2Get<Type> or fmi3Get<Type> of these value
 * references, into `values` (FMI 3 arrays are read whole: n_values counts
 * their elements; in FMI 2, n_values == n_vrs). */
typedef struct {
    PmdRecordFunction get;
    const unsigned int *vrs;
    size_t n_vrs;
    size_t n_values;
    int type;               /* PmdRecordType of values */
    void *values;
} PmdRecordGroup;

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
} PmdRecordColumn;

/* Where a recording stopped early: after `cycles` whole rows, a call (-1 the
 * doStep, else the group's index) returned `status` > Warning. */
typedef struct {
    size_t cycles;
    int call;
    int status;
} PmdRecordStop;

/* Records `cycles` rows of `row_bytes` each into `rows`. The grid group's
 * values at grid_place .. grid_place + 2 are the FMU's time, nextCycleTime and
 * activeCycleTime (doubles): read once before the first cycle, then with the
 * columns after each doStep, each doStep going from time to the next cycle's
 * end, (nextCycleTime - time) + activeCycleTime. Returns 0, or 1 and *stop
 * filled if a call failed. */
PMD_NATIVE_EXPORT int pmd_record_fmi2(PmdRecordFunction do_step, void *instance, const PmdRecordGroup *groups, size_t n_groups,
                                      size_t grid_group, size_t grid_place, const PmdRecordColumn *columns,
                                      size_t n_columns, void *rows, size_t row_bytes, size_t cycles,
                                      PmdRecordStop *stop);
PMD_NATIVE_EXPORT int pmd_record_fmi3(PmdRecordFunction do_step, void *instance, const PmdRecordGroup *groups, size_t n_groups,
                                      size_t grid_group, size_t grid_place, const PmdRecordColumn *columns,
                                      size_t n_columns, void *rows, size_t row_bytes, size_t cycles,
                                      PmdRecordStop *stop);

/* Writes a zero to the first byte of `bytes` and to every byte of it that
 * starts a 4 KiB page: the harness's thread faults in the pages of a
 * recording's next chunk while the FMU fills the one before (Chip.run), so
 * that the kernel zeroes them on another core. Only bytes of the range are
 * written: a page it shares with the chunk being filled keeps that chunk's. */
PMD_NATIVE_EXPORT void pmd_record_prefault(unsigned char *bytes, size_t size);

#endif
