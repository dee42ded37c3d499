/* SPDX-License-Identifier: BSD-2-Clause */
/* pmdfmu.System's steps in C (system.h): the calls examples/systems' Python master makes through
 * FMPy, one value reference a call, in its order, at the cost of the FMUs' own calls. */
#include <string.h>

#include "fmi2FunctionTypes.h"
#include "fmi3FunctionTypes.h"
#include "system.h"

static int get(const PmdSystemOp *op, PmdSystemValue *v, int fmi3)
{
    int status;
    if (op->type == PMD_LOOP_DOUBLE) {
        double d;
        status = fmi3 ? ((fmi3GetFloat64TYPE *)op->fn)(op->instance, &op->vr, 1, &d, 1)
                      : ((fmi2GetRealTYPE *)op->fn)(op->instance, &op->vr, 1, &d);
        v->real = d;
        v->integer = (int64_t)d;
        return status;
    }
    switch (op->type) {
    case PMD_LOOP_INT32: {
        int32_t x;
        status = fmi3 ? ((fmi3GetInt32TYPE *)op->fn)(op->instance, &op->vr, 1, &x, 1)
                      : ((fmi2GetIntegerTYPE *)op->fn)(op->instance, &op->vr, 1, &x);
        v->integer = x;
        break;
    }
    case PMD_LOOP_UINT32: {
        uint32_t x;
        status = ((fmi3GetUInt32TYPE *)op->fn)(op->instance, &op->vr, 1, &x, 1);
        v->integer = x;
        break;
    }
    case PMD_LOOP_INT16: {
        int16_t x;
        status = ((fmi3GetInt16TYPE *)op->fn)(op->instance, &op->vr, 1, &x, 1);
        v->integer = x;
        break;
    }
    case PMD_LOOP_UINT16: {
        uint16_t x;
        status = ((fmi3GetUInt16TYPE *)op->fn)(op->instance, &op->vr, 1, &x, 1);
        v->integer = x;
        break;
    }
    case PMD_LOOP_INT: {
        fmi2Boolean x;
        status = ((fmi2GetBooleanTYPE *)op->fn)(op->instance, &op->vr, 1, &x);
        v->integer = x != 0;
        break;
    }
    case PMD_LOOP_BOOL: {
        fmi3Boolean x;
        status = ((fmi3GetBooleanTYPE *)op->fn)(op->instance, &op->vr, 1, &x, 1);
        v->integer = x != 0;
        break;
    }
    default: return fmi2Error;
    }
    v->real = (double)v->integer;
    return status;
}

static int set(const PmdSystemOp *op, const PmdSystemValue *v, int fmi3)
{
    switch (op->type) {
    case PMD_LOOP_DOUBLE: {
        double d = v->real;
        return fmi3 ? ((fmi3SetFloat64TYPE *)op->fn)(op->instance, &op->vr, 1, &d, 1)
                    : ((fmi2SetRealTYPE *)op->fn)(op->instance, &op->vr, 1, &d);
    }
    case PMD_LOOP_INT32: {
        int32_t x = (int32_t)v->integer;
        return fmi3 ? ((fmi3SetInt32TYPE *)op->fn)(op->instance, &op->vr, 1, &x, 1)
                    : ((fmi2SetIntegerTYPE *)op->fn)(op->instance, &op->vr, 1, &x);
    }
    case PMD_LOOP_UINT32: {
        uint32_t x = (uint32_t)v->integer;
        return ((fmi3SetUInt32TYPE *)op->fn)(op->instance, &op->vr, 1, &x, 1);
    }
    case PMD_LOOP_INT16: {
        int16_t x = (int16_t)v->integer;
        return ((fmi3SetInt16TYPE *)op->fn)(op->instance, &op->vr, 1, &x, 1);
    }
    case PMD_LOOP_UINT16: {
        uint16_t x = (uint16_t)v->integer;
        return ((fmi3SetUInt16TYPE *)op->fn)(op->instance, &op->vr, 1, &x, 1);
    }
    case PMD_LOOP_INT: {
        fmi2Boolean x = v->integer != 0;
        return ((fmi2SetBooleanTYPE *)op->fn)(op->instance, &op->vr, 1, &x);
    }
    case PMD_LOOP_BOOL: {
        fmi3Boolean x = v->integer != 0;
        return ((fmi3SetBooleanTYPE *)op->fn)(op->instance, &op->vr, 1, &x, 1);
    }
    default: return fmi2Error;
    }
}

static int do_step(const PmdSystemOp *op, double t, double h)
{
    if (op->type == 3) {
        fmi3Boolean event_handling_needed, terminate_simulation, early_return;
        fmi3Float64 last_successful_time;
        return ((fmi3DoStepTYPE *)op->fn)(op->instance, t, h, fmi3True, &event_handling_needed,
                                          &terminate_simulation, &early_return, &last_successful_time);
    }
    return ((fmi2DoStepTYPE *)op->fn)(op->instance, t, h, fmi2True);
}

/* The op's FMI version: a get or set's type says it for the types of one version only; the others
 * (Real/Float64, Integer/Int32) take it from the step op of the same instance. */
static int fmi3_of(const PmdSystemOp *ops, size_t n_ops, const PmdSystemOp *op)
{
    size_t i;
    for (i = 0; i < n_ops; i++)
        if (ops[i].kind == PMD_SYSTEM_STEP && ops[i].instance == op->instance)
            return ops[i].type == 3;
    return 0;
}

int pmd_system_run(const PmdSystemOp *ops, size_t n_ops, PmdSystemValue *values, const PmdSystemColumn *columns,
                   size_t n_columns, double start, double step, int64_t first, size_t steps, void *rows,
                   size_t row_bytes, PmdStop *stop)
{
    unsigned char fmi3[64];
    unsigned char *row = rows;
    size_t i, o, c;
    if (n_ops > sizeof fmi3) {
        stop->done = 0;
        stop->call = -1;
        stop->status = fmi2Error;
        return 1;
    }
    for (o = 0; o < n_ops; o++)
        fmi3[o] = (unsigned char)fmi3_of(ops, n_ops, &ops[o]);
    for (i = 0; i < steps; i++) {
        int64_t k = first + (int64_t)i;
        double t = start + (double)k * step;
        for (o = 0; o < n_ops; o++) {
            const PmdSystemOp *op = &ops[o];
            int status = op->kind == PMD_SYSTEM_GET ? get(op, &values[op->value], fmi3[o])
                       : op->kind == PMD_SYSTEM_SET ? set(op, &values[op->value], fmi3[o])
                                                    : do_step(op, t, step);
            if (PMD_FAILED(status)) {
                stop->done = i;
                stop->call = (int)o;
                stop->status = status;
                return 1;
            }
        }
        if (!row)
            continue;
        k += 1;
        memcpy(row, &k, sizeof k);
        for (c = 0; c < n_columns; c++) {
            const PmdSystemColumn *col = &columns[c];
            const PmdSystemValue *v = &values[col->value];
            if (col->real)
                memcpy(row + col->offset, &v->real, sizeof v->real);
            else
                memcpy(row + col->offset, &v->integer, col->size);   /* the low bytes: little-endian */
        }
        row += row_bytes;
    }
    return 0;
}
