/* SPDX-License-Identifier: BSD-2-Clause */
/* The chip's model in FMI 3's terms (model.h): the same chip, names, value
 * references and timing as FMI 2, with native types and the host and memory
 * ports as arrays (variables3.h). Element e of an FMI 3 variable is the FMI 2
 * scalar with value reference vr + e. */
#include <string.h>

#include "fmi3PlatformTypes.h"
#include "instance.h"
#include "variables3.h"

/* FMI 3 types by the shell's PmdFmi3Type: their names in messages, and the chip's PmdType3 of
 * each it has variables of (-1: none) */
static const char *const type_names[] = {
    [PMD_FMI3_FLOAT32] = "Float32", [PMD_FMI3_FLOAT64] = "Float64", [PMD_FMI3_INT8] = "Int8",
    [PMD_FMI3_UINT8] = "UInt8", [PMD_FMI3_INT16] = "Int16", [PMD_FMI3_UINT16] = "UInt16",
    [PMD_FMI3_INT32] = "Int32", [PMD_FMI3_UINT32] = "UInt32", [PMD_FMI3_INT64] = "Int64",
    [PMD_FMI3_UINT64] = "UInt64", [PMD_FMI3_BOOLEAN] = "Boolean", [PMD_FMI3_STRING] = "String",
    [PMD_FMI3_BINARY] = "Binary", [PMD_FMI3_CLOCK] = "Clock"};
static const signed char chip_type[] = {
    [PMD_FMI3_FLOAT32] = -1, [PMD_FMI3_FLOAT64] = PMD3_FLOAT64, [PMD_FMI3_INT8] = -1, [PMD_FMI3_UINT8] = -1,
    [PMD_FMI3_INT16] = PMD3_INT16, [PMD_FMI3_UINT16] = PMD3_UINT16, [PMD_FMI3_INT32] = PMD3_INT32,
    [PMD_FMI3_UINT32] = PMD3_UINT32, [PMD_FMI3_INT64] = -1, [PMD_FMI3_UINT64] = -1,
    [PMD_FMI3_BOOLEAN] = PMD3_BOOLEAN, [PMD_FMI3_STRING] = PMD3_STRING, [PMD_FMI3_BINARY] = PMD3_BINARY,
    [PMD_FMI3_CLOCK] = -1};
/* by PmdType3: the name of a variable's own type */
static const char *const own_type_names[] = {
    [PMD3_FLOAT64] = "Float64", [PMD3_INT32] = "Int32", [PMD3_UINT32] = "UInt32", [PMD3_UINT16] = "UInt16",
    [PMD3_INT16] = "Int16", [PMD3_BOOLEAN] = "Boolean", [PMD3_STRING] = "String", [PMD3_BINARY] = "Binary"};

static const PmdVariable3 *lookup(PmdInstance *inst, const char *fn, unsigned vr, PmdFmi3Type type)
{
    int row = pmd_variable_row(inst, fn, vr, pmd_variable3_of_vr, PMD_VR3_MAX);
    const PmdVariable3 *v = row < 0 ? NULL : &pmd_variables3[row];
    if (v && v->type != chip_type[type]) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: value reference %u (%s) is a %s, not %s", fn, vr,
                         v->name, own_type_names[v->type], type_names[type]);
        return NULL;
    }
    return v;
}

int pmd_model3_has(PmdFmi3Type type)
{
    return chip_type[type] >= 0;
}

PmdStatus pmd_model3_no_such_type(PmdInstance *inst, const char *fn, PmdFmi3Type type, unsigned vr)
{
    return lookup(inst, fn, vr, type) ? PMD_OK : PMD_ERROR;
}

int pmd_model3_count(PmdInstance *inst, const char *fn, PmdFmi3Type type, const unsigned vrs[], size_t nvr,
                     size_t nValues)
{
    size_t i, total = 0;
    for (i = 0; i < nvr; i++) {
        const PmdVariable3 *v = lookup(inst, fn, vrs[i], type);
        if (!v)
            return 0;
        total += v->count;
    }
    if (total != nValues) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: nValues is %zu but the value references hold %zu "
                         "values", fn, nValues, total);
        return 0;
    }
    return 1;
}

int pmd_model3_given(PmdInstance *inst, const char *fn, unsigned vr, PmdFmi3Type type)
{
    return lookup(inst, fn, vr, type) != NULL;
}

/* A type get_element or set_element has no case for (String and Binary have
 * functions of their own): a bug of this file, refused rather than read or
 * written as another type. */
static PmdStatus unhandled_type(PmdInstance *inst, const char *fn, PmdFmi3Type type, unsigned vr)
{
    pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: value reference %u: this FMU has no %s element access",
                     fn, vr, type_names[type]);
    return PMD_ERROR;
}

static PmdStatus get_element(PmdInstance *inst, const char *fn, PmdFmi3Type type, unsigned vr, void *values, size_t k)
{
    double d;
    int32_t n = 0;
    int b;
    PmdStatus s;
    switch (type) {
    case PMD_FMI3_FLOAT64:
        s = pmd_model2_get_real(inst, fn, vr, &d);
        ((fmi3Float64 *)values)[k] = d;
        return s;
    case PMD_FMI3_BOOLEAN:
        s = pmd_model2_get_boolean(inst, fn, vr, &b);
        ((fmi3Boolean *)values)[k] = b != 0;
        return s;
    case PMD_FMI3_INT32:
        s = pmd_model2_get_integer(inst, fn, vr, &n);
        ((fmi3Int32 *)values)[k] = n;
        return s;
    case PMD_FMI3_UINT32:
        s = pmd_model2_get_integer(inst, fn, vr, &n);
        ((fmi3UInt32 *)values)[k] = (uint32_t)n;          /* the register's 32 bits */
        return s;
    case PMD_FMI3_UINT16:
        s = pmd_model2_get_integer(inst, fn, vr, &n);
        ((fmi3UInt16 *)values)[k] = (uint16_t)((uint32_t)n & 0xFFFFu);
        return s;
    case PMD_FMI3_INT16:                                /* a signed 16-bit register: its value fits */
        s = pmd_model2_get_integer(inst, fn, vr, &n);
        ((fmi3Int16 *)values)[k] = (int16_t)n;
        return s;
    case PMD_FMI3_FLOAT32: case PMD_FMI3_INT8: case PMD_FMI3_UINT8: case PMD_FMI3_INT64: case PMD_FMI3_UINT64:
    case PMD_FMI3_STRING: case PMD_FMI3_BINARY: case PMD_FMI3_CLOCK:
        break;
    }
    return unhandled_type(inst, fn, type, vr);
}

static PmdStatus set_element(PmdInstance *inst, const char *fn, PmdFmi3Type type, unsigned vr, const void *values,
                             size_t k, int apply)
{
    switch (type) {
    case PMD_FMI3_FLOAT64: return pmd_model2_set_real(inst, fn, vr, ((const fmi3Float64 *)values)[k], apply);
    case PMD_FMI3_BOOLEAN: return pmd_model2_set_boolean(inst, fn, vr, ((const fmi3Boolean *)values)[k], apply);
    case PMD_FMI3_INT32: return pmd_set_integer(inst, fn, vr, ((const fmi3Int32 *)values)[k], apply);
    case PMD_FMI3_UINT32: return pmd_set_integer(inst, fn, vr, ((const fmi3UInt32 *)values)[k], apply);
    case PMD_FMI3_UINT16: return pmd_set_integer(inst, fn, vr, ((const fmi3UInt16 *)values)[k], apply);
    case PMD_FMI3_INT16: return pmd_set_integer(inst, fn, vr, ((const fmi3Int16 *)values)[k], apply);
    case PMD_FMI3_FLOAT32: case PMD_FMI3_INT8: case PMD_FMI3_UINT8: case PMD_FMI3_INT64: case PMD_FMI3_UINT64:
    case PMD_FMI3_STRING: case PMD_FMI3_BINARY: case PMD_FMI3_CLOCK:
        break;
    }
    return unhandled_type(inst, fn, type, vr);
}

/* The variables.csv row of an FMI 3 variable: its first element's FMI 2 scalar's */
static int family_of(const PmdVariable3 *v)
{
    return pmd_variables[pmd_variable_of_vr[v->vr]].family;
}

PmdStatus pmd_model3_get(PmdInstance *inst, const char *fn, PmdFmi3Type type, unsigned vr, void *values, size_t *k)
{
    const PmdVariable3 *v = &pmd_variables3[pmd_variable3_of_vr[vr]];      /* the shell checked vr */
    unsigned e;
    if (type == PMD_FMI3_UINT16 && family_of(v) == VAR_host_reply) {    /* the whole reply of a command */
        PmdStatus s = pmd_get_host_reply(inst, fn, v->vr, (fmi3UInt16 *)values + *k, v->count);
        *k += v->count;
        return s;
    }
    for (e = 0; e < v->count; e++)
        if (get_element(inst, fn, type, v->vr + e, values, (*k)++) != PMD_OK)
            return PMD_ERROR;
    return PMD_OK;
}

/* The memory.data array (a strobe's words, Chip.write_memory) is set as one
 * block (pmd_set_memory_data: the same checks, messages and order as element
 * by element, without a lookup and two switches per word and pass). */
PmdStatus pmd_model3_set(PmdInstance *inst, const char *fn, PmdFmi3Type type, unsigned vr, const void *values,
                         size_t *k, int apply)
{
    const PmdVariable3 *v = &pmd_variables3[pmd_variable3_of_vr[vr]];      /* the shell counted vr */
    unsigned e;
    if (type == PMD_FMI3_UINT32 && v->count > 1 && pmd_memory_data_span(v->vr, v->count) == v->count) {
        PmdStatus s = pmd_set_memory_data(inst, fn, v->vr, (const fmi3UInt32 *)values + *k, 0, v->count, apply);
        *k += v->count;
        return s;
    }
    if (type == PMD_FMI3_UINT16 && family_of(v) == VAR_host_word) {     /* a command's words, set whole */
        PmdStatus s = pmd_set_host_words(inst, fn, v->vr, (const fmi3UInt16 *)values + *k, v->count, apply);
        *k += v->count;
        return s;
    }
    for (e = 0; e < v->count; e++)
        if (set_element(inst, fn, type, v->vr + e, values, (*k)++, apply) != PMD_OK)
            return PMD_ERROR;
    return PMD_OK;
}

PmdStatus pmd_model3_set_binaries(PmdInstance *inst, const char *fn, const unsigned vrs[], size_t nvr,
                                  const size_t sizes[], const unsigned char *const values[])
{
    (void)sizes; (void)values;
    if (nvr > 0) {                                  /* record.data, the only Binary, is an output */
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: value reference %u (%s) is an output and cannot be "
                         "set", fn, vrs[0], pmd_variables3[pmd_variable3_of_vr[vrs[0]]].name);
        return PMD_ERROR;
    }
    return PMD_OK;
}

/* A step refused runs nothing: the last successful time is where it was asked to start; a Warning ran it. */
double pmd_model3_last_successful_time(const PmdInstance *inst, PmdStatus status, double t)
{
    return status <= PMD_WARNING ? inst->s.time : t;
}
