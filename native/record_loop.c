/* SPDX-License-Identifier: BSD-2-Clause */
/* Chip.run(cycles, record=names) in C (record_loop.h): the loop the harness ran in
 * Python (a grid read, a doStep of one cycle, one get per FMI type, every
 * cycle), over the same FMI functions of the FMU with the same arguments, so
 * that the rows and the FMU's log are the same, at the cost of the FMU's own
 * calls alone. */
#include <stdint.h>
#include <string.h>

#include "fmi2FunctionTypes.h"
#include "fmi3FunctionTypes.h"
#include "record_loop.h"


static int get_fmi2(const PmdLoopGroup *g, void *instance)
{
    switch (g->type) {
    case PMD_LOOP_DOUBLE: return ((fmi2GetRealTYPE *)g->get)(instance, g->vrs, g->n_vrs, g->values);
    case PMD_LOOP_INT32: return ((fmi2GetIntegerTYPE *)g->get)(instance, g->vrs, g->n_vrs, g->values);
    case PMD_LOOP_INT: return ((fmi2GetBooleanTYPE *)g->get)(instance, g->vrs, g->n_vrs, g->values);
    default: return fmi2Error;              /* no FMI 2 getter has these values' type */
    }
}

static int get_fmi3(const PmdLoopGroup *g, void *instance)
{
    switch (g->type) {
    case PMD_LOOP_DOUBLE:
        return ((fmi3GetFloat64TYPE *)g->get)(instance, g->vrs, g->n_vrs, g->values, g->n_values);
    case PMD_LOOP_INT32: return ((fmi3GetInt32TYPE *)g->get)(instance, g->vrs, g->n_vrs, g->values, g->n_values);
    case PMD_LOOP_UINT32:
        return ((fmi3GetUInt32TYPE *)g->get)(instance, g->vrs, g->n_vrs, g->values, g->n_values);
    case PMD_LOOP_UINT16:
        return ((fmi3GetUInt16TYPE *)g->get)(instance, g->vrs, g->n_vrs, g->values, g->n_values);
    case PMD_LOOP_INT16: return ((fmi3GetInt16TYPE *)g->get)(instance, g->vrs, g->n_vrs, g->values, g->n_values);
    case PMD_LOOP_BOOL:
        return ((fmi3GetBooleanTYPE *)g->get)(instance, g->vrs, g->n_vrs, g->values, g->n_values);
    default: return fmi3Error;              /* no FMI 3 getter has these values' type */
    }
}

/* The low bytes of a wider integer are its first ones (little-endian: every platform the FMU is built for) */
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "record.c copies an integer's low bytes as its first ones: little-endian only"
#endif

/* A field of a packed row (numpy's structured arrays align nothing): memcpy of a fixed size. */
static void store(unsigned char *row, const PmdLoopColumn *c)
{
    unsigned char *field = row + c->offset;
    if (c->truth) {
        int v;
        memcpy(&v, c->source, sizeof v);
        *field = v != 0;
        return;
    }
    switch (c->size) {          /* sizes_known() let no other size in */
    case 8: memcpy(field, c->source, 8); break;
    case 4: memcpy(field, c->source, 4); break;
    case 2: memcpy(field, c->source, 2); break;
    case 1: memcpy(field, c->source, 1); break;
    }
}

static int do_step(int fmi3, PmdFmiFunction fn, void *instance, double now, double step)
{
    if (fmi3) {
        /* FMPy's doStep passes these and ignores what they return; so did the harness */
        fmi3Boolean event_handling_needed, terminate_simulation, early_return;
        fmi3Float64 last_successful_time;
        return ((fmi3DoStepTYPE *)fn)(instance, now, step, fmi3True, &event_handling_needed,
                                      &terminate_simulation, &early_return, &last_successful_time);
    }
    return ((fmi2DoStepTYPE *)fn)(instance, now, step, fmi2True);
}

static int stopped(PmdStop *stop, size_t cycles, int call, int status)
{
    stop->done = cycles;
    stop->call = call;
    stop->status = status;
    return 1;
}

/* Whether every field is of a size store() copies (a row's fields are numpy's: 1, 2, 4 or 8 bytes). */
static int sizes_known(const PmdLoopColumn *columns, size_t n_columns)
{
    size_t c;
    for (c = 0; c < n_columns; c++)
        if (columns[c].size != 1 && columns[c].size != 2 && columns[c].size != 4 && columns[c].size != 8)
            return 0;
    return 1;
}

static inline int record(int fmi3, PmdFmiFunction do_step_fn, void *instance, const PmdLoopGroup *groups, size_t n_groups,
                         size_t grid_group, size_t grid_place, const PmdLoopColumn *columns, size_t n_columns,
                         void *rows, size_t row_bytes, size_t cycles, PmdStop *stop)
{
    const double *grid = (const double *)groups[grid_group].values + grid_place;
    unsigned char *row = rows;
    size_t i, g, c;
    int status;
    if (!sizes_known(columns, n_columns))
        return stopped(stop, 0, PMD_LOOP_FIELD_SIZE, 3);    /* nothing ran */
    if (cycles == 0)
        return 0;
    status = fmi3 ? get_fmi3(&groups[grid_group], instance) : get_fmi2(&groups[grid_group], instance);
    if (PMD_FAILED(status))
        return stopped(stop, 0, (int)grid_group, status);
    for (i = 0; i < cycles; i++, row += row_bytes) {
        /* Chip._step(1): from the last communication point to the end of the next cycle; the
         * expression as Python evaluated it, (next - now) + 1 * cycleTime */
        status = do_step(fmi3, do_step_fn, instance, grid[0], (grid[1] - grid[0]) + grid[2]);
        if (PMD_FAILED(status))
            return stopped(stop, i, -1, status);
        for (g = 0; g < n_groups; g++) {
            status = fmi3 ? get_fmi3(&groups[g], instance) : get_fmi2(&groups[g], instance);
            if (PMD_FAILED(status))
                return stopped(stop, i, (int)g, status);
        }
        for (c = 0; c < n_columns; c++)
            store(row, &columns[c]);
    }
    return 0;
}

int pmd_record_fmi2(PmdFmiFunction do_step_fn, void *instance, const PmdLoopGroup *groups, size_t n_groups,
                    size_t grid_group, size_t grid_place, const PmdLoopColumn *columns, size_t n_columns,
                    void *rows, size_t row_bytes, size_t cycles, PmdStop *stop)
{
    return record(0, do_step_fn, instance, groups, n_groups, grid_group, grid_place, columns, n_columns, rows,
                  row_bytes, cycles, stop);
}

int pmd_record_fmi3(PmdFmiFunction do_step_fn, void *instance, const PmdLoopGroup *groups, size_t n_groups,
                    size_t grid_group, size_t grid_place, const PmdLoopColumn *columns, size_t n_columns,
                    void *rows, size_t row_bytes, size_t cycles, PmdStop *stop)
{
    return record(1, do_step_fn, instance, groups, n_groups, grid_group, grid_place, columns, n_columns, rows,
                  row_bytes, cycles, stop);
}

/* Where record.data's rows lie after a doStep: FMI 2's extension, FMI 3's Binary getter. */
static int record_data(int fmi3, PmdFmiFunction get_data, unsigned int data_vr, void *instance, const void **data,
                       size_t *bytes)
{
    if (fmi3) {
        fmi3ValueReference vr = data_vr;
        fmi3Binary value = NULL;
        int status = ((fmi3GetBinaryTYPE *)get_data)(instance, &vr, 1, bytes, &value, 1);
        *data = value;
        return status;
    }
    return ((PmdGetRecordData *)get_data)(instance, data, bytes);
}

int pmd_record_step_lent(int fmi3, PmdFmiFunction set_buffer, PmdFmiFunction get_data, unsigned int data_vr,
                         PmdFmiFunction do_step_fn, void *instance, double now, double step, void *rows, size_t size,
                         size_t *recorded, int *call)
{
    const void *data = NULL;
    size_t bytes = 0;
    int status, got, ended;
    *recorded = 0;
    *call = PMD_STEP_LEND;
    status = ((PmdSetRecordBuffer *)set_buffer)(instance, rows, size);
    if (PMD_FAILED(status))
        return status;
    *call = PMD_STEP_DO_STEP;
    status = do_step(fmi3, do_step_fn, instance, now, step);
    if (!PMD_FAILED(status)) {
        got = record_data(fmi3, get_data, data_vr, instance, &data, &bytes);
        if (PMD_FAILED(got)) {
            *call = PMD_STEP_GET_DATA;
            status = got;
        } else {
            *recorded = data == rows ? bytes : 0;
        }
    }
    /* the loan ends whatever happened: the FMU keeps no pointer into the caller's memory */
    ended = ((PmdSetRecordBuffer *)set_buffer)(instance, NULL, 0);
    if (PMD_FAILED(ended) && !PMD_FAILED(status)) {
        *call = PMD_STEP_END_LOAN;
        return ended;
    }
    return status;
}
