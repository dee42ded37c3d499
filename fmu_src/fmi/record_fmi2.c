/* SPDX-License-Identifier: BSD-2-Clause */
/* The chip's two functions beside the FMI 2 ones, in its FMI 2 binary only:
 * bulk recording (record.c) for FMI 2, which has no Binary type
 * (docs/performance.md, "Recording"; the harness's native/record_loop.c).
 * FMI 3 has the second one as pmdfmu_fmi3SetRecordBuffer (record_fmi3.c). */
#include "fmi2.h"
#include "instance.h"

/* record.data in FMI 2, which has no Binary type: this FMU's one function
 * beside the FMI 2 ones (an importer that does not know it ignores it). It
 * lends the buffer fmi3GetBinary gives for record.data in FMI 3: the rows of
 * the cycles the last doStep recorded (record.enabled), valid until the next
 * call to the instance; *size in bytes. docs/performance.md, "Recording". */
FMI2_Export fmi2Status pmdfmu_fmi2GetRecordData(fmi2Component c, const void **data, size_t *size)
{
    PmdInstance *inst = pmd_fmi2_begin(c, "pmdfmu_fmi2GetRecordData", PMD_GET_STATES);
    const unsigned char *bytes;
    if (!inst || !pmd_fmi2_arrays_given(inst, "pmdfmu_fmi2GetRecordData", 1, data, size))
        return fmi2Error;
    pmd_record_data(inst, &bytes, size);
    *data = bytes;
    return fmi2OK;
}

/* The other side of the same buffer: the caller lends the FMU memory of its
 * own (size bytes; 4-byte aligned for the default rows) for the rows of the
 * recording doSteps that follow, NULL gives record.data's buffer back;
 * pmdfmu_fmi2GetRecordData then reports the rows there. The harness records
 * into its result this way, without a copy. The memory must stay valid until
 * NULL is lent or the instance is reset or freed; a step recording more cycles
 * than fit is refused, as one beyond record.capacity is. */
FMI2_Export fmi2Status pmdfmu_fmi2SetRecordBuffer(fmi2Component c, void *rows, size_t size)
{
    static const char fn[] = "pmdfmu_fmi2SetRecordBuffer";
    PmdInstance *inst = pmd_fmi2_begin(c, fn, PMD_ANY_STATE);
    if (!inst)
        return fmi2Error;
    pmd_record_lend(inst, fn, rows, size);
    return fmi2OK;
}
