/* SPDX-License-Identifier: BSD-2-Clause */
/* The chip's function beside the FMI 3 ones, in its FMI 3 binary only: the
 * twin of FMI 2's pmdfmu_fmi2SetRecordBuffer (record_fmi2.c), so that the
 * harness records into its result without a copy in both versions
 * (docs/performance.md, "Recording"; the harness's native/record_loop.c). */
#include "fmi3.h"
#include "instance.h"

/* The caller lends the FMU memory of its own (size bytes; 4-byte aligned for
 * the default rows) for the rows of the recording doSteps that follow, NULL
 * gives record.data's buffer back; fmi3GetBinary of record.data then reports
 * the rows there. The memory must stay valid until NULL is lent or the
 * instance is reset or freed; a step recording more cycles than fit is
 * refused, as one beyond record.capacity is. An importer that does not know
 * this function ignores it. */
FMI3_Export fmi3Status pmdfmu_fmi3SetRecordBuffer(fmi3Instance c, void *rows, size_t size)
{
    static const char fn[] = "pmdfmu_fmi3SetRecordBuffer";
    PmdInstance *inst = pmd_fmi3_begin(c, fn, PMD_ANY_STATE);
    if (!inst)
        return fmi3Error;
    pmd_record_lend(inst, fn, rows, size);
    return fmi3OK;
}
