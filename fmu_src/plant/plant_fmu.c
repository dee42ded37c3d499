/* SPDX-License-Identifier: BSD-2-Clause */
/* The plant's model for the FMI shells (fmi_common/model.h, plant_fmu.h):
 * life cycle, variables by the generated table, doStep and FMU states. Every
 * refusal is logged with the function, the variable or value and the reason. */
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plant_fmu.h"

/* A doStep of more internal steps than this is refused rather than run for minutes. */
#define MAX_INTERNAL_STEPS 1e9
#define STATE_MAGIC "pmdplant"
#define STATE_VERSION 1u

const char pmd_model_token[] = PLANT_INSTANTIATION_TOKEN;

/* The plant logs errors only, and always. */
void pmd_model_error(const PlantInstance *inst, const char *format, ...)
{
    char message[1024];
    va_list args;
    if (!inst->logger)
        return;
    va_start(args, format);
    vsnprintf(message, sizeof message, format, args);
    va_end(args);
    inst->logger(inst->environment, inst->instanceName, PMD_ERROR, plant_log_category_names[PLANT_LOG_ERRORS], message);
}

const char *pmd_model_state_name(PmdState state)
{
    switch (state) {
    case PMD_INSTANTIATED: return "the instantiated state";
    case PMD_INITIALIZATION_MODE: return "initialization mode";
    case PMD_STEP_MODE: return "step mode";
    case PMD_TERMINATED: return "the terminated state";
    }
    return "an unknown state";
}

static void set(PlantInstance *inst, const PlantVariable *v, double value);

/* Every parameter and input at its start value, the state at the start. */
void pmd_model_reset(PlantInstance *inst)
{
    size_t i;
    memset(&inst->s, 0, sizeof inst->s);
    inst->s.state = PMD_INSTANTIATED;
    for (i = 0; i < PLANT_VARIABLE_COUNT; i++)
        if (plant_variables[i].causality == PLANT_PARAMETER || plant_variables[i].causality == PLANT_INPUT)
            set(inst, &plant_variables[i], plant_variables[i].start);
    plant_start(&inst->s.m);
}

PlantInstance *pmd_model_new(const char *instanceName, PmdModelLogger logger, void *environment)
{
    PlantInstance *inst = (PlantInstance *)calloc(1, sizeof *inst);
    if (!inst)
        return NULL;
    inst->instanceName = (char *)malloc(strlen(instanceName) + 1);
    if (!inst->instanceName) {
        free(inst);
        return NULL;
    }
    strcpy(inst->instanceName, instanceName);
    inst->logger = logger;
    inst->environment = environment;
    pmd_model_reset(inst);
    return inst;
}

PmdStatus pmd_model_resources(PlantInstance *inst, const char *fn, char *resources, const char *noResources)
{
    (void)inst; (void)fn; (void)noResources;
    free(resources);                                /* the plant reads no file */
    return PMD_OK;
}

void pmd_model_free(PlantInstance *inst)
{
    if (!inst)
        return;
    free(inst->instanceName);
    free(inst);
}

PmdState pmd_model_fmi_state(const PlantInstance *inst)
{
    return inst->s.state;
}

double pmd_model_time(const PlantInstance *inst)
{
    return inst->s.m.time;
}

void pmd_model_terminate(PlantInstance *inst)
{
    inst->s.state = PMD_TERMINATED;
}

PmdStatus pmd_model_set_debug_logging(PlantInstance *inst, const char *fn, int loggingOn, size_t nCategories,
                                      const char *const categories[])
{
    size_t i, c;
    if (nCategories > 0 && !categories) {
        pmd_model_error(inst, "%s: %zu categories but the array is NULL", fn, nCategories);
        return PMD_ERROR;
    }
    for (i = 0; i < nCategories; i++) {
        for (c = 0; c < PLANT_LOG_CATEGORY_COUNT; c++)
            if (categories[i] && strcmp(categories[i], plant_log_category_names[c]) == 0)
                break;
        if (c == PLANT_LOG_CATEGORY_COUNT) {
            pmd_model_error(inst, "%s: unknown log category \"%s\"", fn, categories[i] ? categories[i] : "(NULL)");
            return PMD_ERROR;
        }
    }
    (void)loggingOn;                                /* the plant logs errors only: always */
    return PMD_OK;
}

PmdStatus pmd_model_setup_experiment(PlantInstance *inst, const char *fn, double startTime)
{
    (void)fn;
    inst->s.m.time = startTime;
    return PMD_OK;
}

PmdStatus pmd_model_enter_initialization(PlantInstance *inst, const char *fn, double startTime)
{
    (void)fn;
    if (!isfinite(startTime)) {
        pmd_model_error(inst, "EnterInitializationMode: the start time %g is not finite", startTime);
        return PMD_ERROR;
    }
    inst->s.m.time = startTime;
    inst->s.state = PMD_INITIALIZATION_MODE;
    plant_start(&inst->s.m);
    return PMD_OK;
}

PmdStatus pmd_model_exit_initialization(PlantInstance *inst, const char *fn)
{
    (void)fn;
    plant_start(&inst->s.m);
    inst->s.state = PMD_STEP_MODE;
    return PMD_OK;
}

PmdStatus pmd_model_do_step(PlantInstance *inst, const char *fn, double t, double h)
{
    PlantModel *m = &inst->s.m, before;
    if (!isfinite(t) || !isfinite(h) || h <= 0) {
        pmd_model_error(inst, "%s: communication point %g, step size %g: the step size must be finite and > 0",
                        fn, t, h);
        return PMD_ERROR;
    }
    /* a master's communication points are sums or products of its step size */
    if (fabs(t - m->time) > 1e-6 * m->internalStep + 8 * DBL_EPSILON * fabs(m->time)) {
        pmd_model_error(inst, "%s: communication point %.17g is not the current time %.17g", fn, t, m->time);
        return PMD_ERROR;
    }
    if (plant_internal_steps(m, h) > MAX_INTERNAL_STEPS) {
        pmd_model_error(inst, "%s: a step of %g s is more than %g internal steps of %g s: not run", fn, h,
                        MAX_INTERNAL_STEPS, m->internalStep);
        return PMD_ERROR;
    }
    before = *m;
    plant_advance(m, h);
    if (!isfinite(m->angle) || !isfinite(m->speed) || !isfinite(m->current)) {
        pmd_model_error(inst, "%s: the step from %.17g s leaves the motor's state not finite (angle %g, "
                        "speed %g): not run", fn, t, m->angle, m->speed);
        *m = before;
        return PMD_ERROR;
    }
    m->time = t + h;
    return PMD_OK;
}

/* ---- variables ---- */

static const char *const type_names[] = {[PLANT_NONE] = "(none)", [PLANT_REAL] = "Real", [PLANT_INTEGER] = "Integer"};
static const char *const type3_names[] = {[PLANT3_FLOAT64] = "Float64", [PLANT3_INT32] = "Int32",
                                          [PLANT3_INT16] = "Int16"};
static const char *const causality_names[] = {[PLANT_PARAMETER] = "parameter", [PLANT_INPUT] = "input",
                                              [PLANT_OUTPUT] = "output", [PLANT_INDEPENDENT] = "independent"};

/* The variable with value reference vr if its type is `type` (a PlantType for
 * FMI 2, a PlantType3 for FMI 3), else NULL with a logged error. */
static const PlantVariable *lookup(const PlantInstance *inst, const char *fn, unsigned vr, int fmi3, unsigned type)
{
    size_t i;
    for (i = 0; i < PLANT_VARIABLE_COUNT; i++) {
        const PlantVariable *v = &plant_variables[i];
        if (v->vr != vr || (!fmi3 && v->type == PLANT_NONE))
            continue;
        if ((fmi3 ? v->type3 : v->type) != type) {
            pmd_model_error(inst, "%s: value reference %u (%s) is of type %s", fn, vr, v->name,
                            fmi3 ? type3_names[v->type3] : type_names[v->type]);
            return NULL;
        }
        return v;
    }
    pmd_model_error(inst, "%s: no variable has value reference %u", fn, vr);
    return NULL;
}

static int is_real(const PlantVariable *v)
{
    return v->type3 == PLANT3_FLOAT64;
}

static double member_value(const PlantModel *m, const PlantVariable *v)
{
    const char *member = (const char *)m + v->offset;
    double d;
    int32_t n;
    if (is_real(v)) {
        memcpy(&d, member, sizeof d);
        return d;
    }
    memcpy(&n, member, sizeof n);
    return n;
}

static double get(const PlantInstance *inst, const PlantVariable *v)
{
    return member_value(&inst->s.m, v);
}

static void set(PlantInstance *inst, const PlantVariable *v, double value)
{
    char *member = (char *)&inst->s.m + v->offset;
    int32_t n;
    if (is_real(v)) {
        memcpy(member, &value, sizeof value);
    } else {
        n = (int32_t)value;                         /* check: a whole number in the variable's range */
        memcpy(member, &n, sizeof n);
    }
}

/* Sets are all or nothing: every value is checked before any is set.
 * Parameters (variability fixed) before the end of initialization, inputs
 * until the end; outputs and time never. */
static PmdStatus check(const PlantInstance *inst, const char *fn, const PlantVariable *v, double value)
{
    unsigned states = v->causality == PLANT_PARAMETER ? PMD_INSTANTIATED | PMD_INITIALIZATION_MODE
                      : v->causality == PLANT_INPUT  ? PMD_SET_STATES
                                                     : 0;
    if (!states) {
        pmd_model_error(inst, "%s: %s is an %s and cannot be set", fn, v->name, causality_names[v->causality]);
        return PMD_ERROR;
    }
    if (!(inst->s.state & states)) {
        pmd_model_error(inst, "%s: %s, a %s, cannot be set in %s", fn, v->name, causality_names[v->causality],
                        pmd_model_state_name(inst->s.state));
        return PMD_ERROR;
    }
    if (!(value >= v->min && value <= v->max)) {      /* also NaN */
        pmd_model_error(inst, "%s: %s = %.17g is not in %.17g .. %.17g: not set", fn, v->name, value, v->min,
                        v->max);
        return PMD_ERROR;
    }
    if (!isfinite(value)) {
        pmd_model_error(inst, "%s: %s = %g is not finite: not set", fn, v->name, value);
        return PMD_ERROR;
    }
    return PMD_OK;
}

/* A value checked (apply 0) or set (apply 1); before step mode the start state follows the parameters. */
static PmdStatus set_value(PlantInstance *inst, const char *fn, const PlantVariable *v, double value, int apply)
{
    if (!v)
        return PMD_ERROR;
    if (!apply)
        return check(inst, fn, v, value);
    set(inst, v, value);
    if (inst->s.state != PMD_STEP_MODE)
        plant_start(&inst->s.m);
    return PMD_OK;
}

/* A type the plant has no variables of. */
static PmdStatus no_such_type(const PlantInstance *inst, const char *fn, unsigned vr)
{
    pmd_model_error(inst, "%s: no variable of this type has value reference %u", fn, vr);
    return PMD_ERROR;
}

/* Nothing to bring up to date before a get, nothing that values ask for together. */
void pmd_model_commit(PlantInstance *inst)
{
    (void)inst;
}

void pmd_model_set_begin(PlantInstance *inst)
{
    (void)inst;
}

PmdStatus pmd_model_set_check(PlantInstance *inst, const char *fn)
{
    (void)inst; (void)fn;
    return PMD_OK;
}

/* FMI 2: Real and Integer variables. */
int pmd_model2_given(PlantInstance *inst, const char *fn, unsigned vr, PmdFmi2Type type)
{
    switch (type) {
    case PMD_FMI2_REAL: return lookup(inst, fn, vr, 0, PLANT_REAL) != NULL;
    case PMD_FMI2_INTEGER: return lookup(inst, fn, vr, 0, PLANT_INTEGER) != NULL;
    case PMD_FMI2_BOOLEAN: break;
    }
    return no_such_type(inst, fn, vr) == PMD_OK;
}

PmdStatus pmd_model2_get_real(PlantInstance *inst, const char *fn, unsigned vr, double *value)
{
    const PlantVariable *v = lookup(inst, fn, vr, 0, PLANT_REAL);
    if (!v)
        return PMD_ERROR;
    *value = get(inst, v);
    return PMD_OK;
}

PmdStatus pmd_model2_get_integer(PlantInstance *inst, const char *fn, unsigned vr, int32_t *value)
{
    const PlantVariable *v = lookup(inst, fn, vr, 0, PLANT_INTEGER);
    if (!v)
        return PMD_ERROR;
    *value = (int32_t)get(inst, v);
    return PMD_OK;
}

PmdStatus pmd_model2_get_boolean(PlantInstance *inst, const char *fn, unsigned vr, int *value)
{
    (void)value;
    return no_such_type(inst, fn, vr);
}

PmdStatus pmd_model2_set_real(PlantInstance *inst, const char *fn, unsigned vr, double value, int apply)
{
    return set_value(inst, fn, lookup(inst, fn, vr, 0, PLANT_REAL), value, apply);
}

PmdStatus pmd_model2_set_integers(PlantInstance *inst, const char *fn, const unsigned vr[], size_t n,
                                  const int32_t value[], int apply, size_t *taken)
{
    (void)n;
    *taken = 1;
    return set_value(inst, fn, lookup(inst, fn, vr[0], 0, PLANT_INTEGER), (double)value[0], apply);
}

PmdStatus pmd_model2_set_boolean(PlantInstance *inst, const char *fn, unsigned vr, int value, int apply)
{
    (void)value; (void)apply;
    return no_such_type(inst, fn, vr);
}

PmdStatus pmd_model_get_string(PlantInstance *inst, const char *fn, unsigned vr, const char **value)
{
    (void)value;
    return no_such_type(inst, fn, vr);
}

PmdStatus pmd_model_set_string(PlantInstance *inst, const char *fn, unsigned vr, const char *value, int apply)
{
    (void)value; (void)apply;
    return no_such_type(inst, fn, vr);
}

/* FMI 3: every variable is a scalar, a Float64, an Int32 or an Int16 (motorCommand, like the chip's
 * axisN.motorCommand); time is the independent variable. */
int pmd_model3_has(PmdFmi3Type type)
{
    return type == PMD_FMI3_FLOAT64 || type == PMD_FMI3_INT32 || type == PMD_FMI3_INT16;
}

PmdStatus pmd_model3_no_such_type(PlantInstance *inst, const char *fn, PmdFmi3Type type, unsigned vr)
{
    (void)type;
    return no_such_type(inst, fn, vr);
}

int pmd_model3_count(PlantInstance *inst, const char *fn, PmdFmi3Type type, const unsigned vrs[], size_t nvr,
                     size_t nValues)
{
    (void)type; (void)vrs;
    if (nvr != nValues) {
        pmd_model_error(inst, "%s: nValues is %zu but %zu scalar value references are given", fn, nValues,
                        nvr);
        return 0;
    }
    return 1;
}

static const PlantVariable *lookup3(const PlantInstance *inst, const char *fn, unsigned vr, PmdFmi3Type type)
{
    return lookup(inst, fn, vr, 1, type == PMD_FMI3_FLOAT64 ? PLANT3_FLOAT64
                                   : type == PMD_FMI3_INT32 ? PLANT3_INT32 : PLANT3_INT16);
}

int pmd_model3_given(PlantInstance *inst, const char *fn, unsigned vr, PmdFmi3Type type)
{
    return lookup3(inst, fn, vr, type) != NULL;
}

PmdStatus pmd_model3_get(PlantInstance *inst, const char *fn, PmdFmi3Type type, unsigned vr, void *values, size_t *k)
{
    const PlantVariable *v = lookup3(inst, fn, vr, type);
    if (!v)
        return PMD_ERROR;
    switch (type) {
    case PMD_FMI3_FLOAT64: ((double *)values)[*k] = get(inst, v); break;
    case PMD_FMI3_INT32: ((int32_t *)values)[*k] = (int32_t)get(inst, v); break;
    case PMD_FMI3_INT16: ((int16_t *)values)[*k] = (int16_t)get(inst, v); break;
    case PMD_FMI3_FLOAT32: case PMD_FMI3_INT8: case PMD_FMI3_UINT8: case PMD_FMI3_UINT16: case PMD_FMI3_UINT32:
    case PMD_FMI3_INT64: case PMD_FMI3_UINT64: case PMD_FMI3_BOOLEAN: case PMD_FMI3_STRING: case PMD_FMI3_BINARY:
    case PMD_FMI3_CLOCK:
        return no_such_type(inst, fn, vr);         /* pmd_model3_has said no: the shell never asks */
    }
    ++*k;
    return PMD_OK;
}

PmdStatus pmd_model3_set(PlantInstance *inst, const char *fn, PmdFmi3Type type, unsigned vr, const void *values,
                         size_t *k, int apply)
{
    double value;
    switch (type) {
    case PMD_FMI3_FLOAT64: value = ((const double *)values)[*k]; break;
    case PMD_FMI3_INT32: value = ((const int32_t *)values)[*k]; break;
    case PMD_FMI3_INT16: value = ((const int16_t *)values)[*k]; break;
    case PMD_FMI3_FLOAT32: case PMD_FMI3_INT8: case PMD_FMI3_UINT8: case PMD_FMI3_UINT16: case PMD_FMI3_UINT32:
    case PMD_FMI3_INT64: case PMD_FMI3_UINT64: case PMD_FMI3_BOOLEAN: case PMD_FMI3_STRING: case PMD_FMI3_BINARY:
    case PMD_FMI3_CLOCK:
        return no_such_type(inst, fn, vr);         /* pmd_model3_has said no: the shell never asks */
    }
    ++*k;
    return set_value(inst, fn, lookup3(inst, fn, vr, type), value, apply);
}

PmdStatus pmd_model3_get_binary(PlantInstance *inst, const char *fn, unsigned vr, const unsigned char **value,
                                size_t *size)
{
    (void)value; (void)size;
    return no_such_type(inst, fn, vr);
}

PmdStatus pmd_model3_set_binaries(PlantInstance *inst, const char *fn, const unsigned vrs[], size_t nvr,
                                  const size_t sizes[], const unsigned char *const values[])
{
    (void)sizes; (void)values;
    return nvr > 0 ? no_such_type(inst, fn, vrs[0]) : PMD_OK;
}

/* the plant's time, where a refused step left it */
double pmd_model3_last_successful_time(const PlantInstance *inst, PmdStatus status, double t)
{
    (void)status; (void)t;
    return inst->s.m.time;
}

/* ---- FMU states ---- */

typedef struct {
    char magic[8];
    uint32_t version;
    uint32_t size;
    PlantInstanceState s;
} PlantSnapshot;

/* A state to restore: every variable finite and in its range, a known FMI
 * state, and the encoder count that of the angle. */
static int snapshot_valid(const PlantInstance *inst, const char *fn, const PlantSnapshot *snap)
{
    size_t i;
    if (memcmp(snap->magic, STATE_MAGIC, sizeof snap->magic) != 0 || snap->version != STATE_VERSION ||
        snap->size != sizeof *snap) {
        pmd_model_error(inst, "%s: not a state of this FMU (magic, version %u or size %u differ)", fn,
                        (unsigned)snap->version, (unsigned)snap->size);
        return 0;
    }
    switch (snap->s.state) {
    case PMD_INSTANTIATED: case PMD_INITIALIZATION_MODE: case PMD_STEP_MODE: case PMD_TERMINATED:
        break;
    default:
        pmd_model_error(inst, "%s: the state holds no FMI state (%d)", fn, (int)snap->s.state);
        return 0;
    }
    for (i = 0; i < PLANT_VARIABLE_COUNT; i++) {
        const PlantVariable *v = &plant_variables[i];
        double value = member_value(&snap->s.m, v);
        if (!isfinite(value) || value < v->min || value > v->max) {
            pmd_model_error(inst, "%s: the state's %s = %g is not in %g .. %g", fn, v->name, value, v->min,
                            v->max);
            return 0;
        }
    }
    if (snap->s.m.encoderCount != plant_encoder_count(&snap->s.m)) {
        pmd_model_error(inst, "%s: the state's encoder count %ld is not that of its angle %.17g", fn,
                        (long)snap->s.m.encoderCount, snap->s.m.angle);
        return 0;
    }
    return 1;
}

PmdStatus pmd_model_fmu_state_get(PlantInstance *inst, const char *fn, void **state)
{
    PlantSnapshot *snap;
    if (!state) {
        pmd_model_error(inst, "%s: the state pointer is NULL", fn);
        return PMD_ERROR;
    }
    snap = (PlantSnapshot *)(*state ? *state : calloc(1, sizeof *snap));     /* a given state is overwritten */
    if (!snap) {
        pmd_model_error(inst, "%s: out of memory", fn);
        return PMD_ERROR;
    }
    memcpy(snap->magic, STATE_MAGIC, sizeof snap->magic);
    snap->version = STATE_VERSION;
    snap->size = sizeof *snap;
    memcpy(&snap->s, &inst->s, sizeof snap->s);
    *state = snap;
    return PMD_OK;
}

PmdStatus pmd_model_fmu_state_set(PlantInstance *inst, const char *fn, const void *state)
{
    if (!state) {
        pmd_model_error(inst, "%s: the state is NULL", fn);
        return PMD_ERROR;
    }
    if (!snapshot_valid(inst, fn, (const PlantSnapshot *)state))
        return PMD_ERROR;
    memcpy(&inst->s, &((const PlantSnapshot *)state)->s, sizeof inst->s);
    return PMD_OK;
}

PmdStatus pmd_model_fmu_state_free(PlantInstance *inst, const char *fn, void **state)
{
    (void)inst;
    (void)fn;
    if (state) {
        free(*state);
        *state = NULL;
    }
    return PMD_OK;
}

PmdStatus pmd_model_fmu_state_size(PlantInstance *inst, const char *fn, const void *state, size_t *size)
{
    if (!state || !size) {
        pmd_model_error(inst, "%s: the state or the size pointer is NULL", fn);
        return PMD_ERROR;
    }
    *size = sizeof(PlantSnapshot);
    return PMD_OK;
}

PmdStatus pmd_model_fmu_state_serialize(PlantInstance *inst, const char *fn, const void *state, unsigned char *bytes,
                                    size_t size)
{
    if (!state || !bytes || size != sizeof(PlantSnapshot)) {
        pmd_model_error(inst, "%s: needs a state and %zu bytes (given %zu)", fn, sizeof(PlantSnapshot), size);
        return PMD_ERROR;
    }
    memcpy(bytes, state, size);
    return PMD_OK;
}

PmdStatus pmd_model_fmu_state_deserialize(PlantInstance *inst, const char *fn, const unsigned char *bytes,
                                      size_t size, void **state)
{
    PlantSnapshot *snap;
    if (!bytes || !state || size != sizeof(PlantSnapshot)) {
        pmd_model_error(inst, "%s: a state of this FMU is %zu bytes (given %zu)", fn, sizeof(PlantSnapshot),
                        size);
        return PMD_ERROR;
    }
    snap = (PlantSnapshot *)calloc(1, sizeof *snap);
    if (!snap) {
        pmd_model_error(inst, "%s: out of memory", fn);
        return PMD_ERROR;
    }
    memcpy(snap, bytes, size);
    if (!snapshot_valid(inst, fn, snap)) {
        free(snap);
        return PMD_ERROR;
    }
    *state = snap;
    return PMD_OK;
}
