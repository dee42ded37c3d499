/* The plant FMU instance (plant_fmu.h): life cycle, variables by the
 * generated table, doStep and FMU states. Every refusal is logged with the
 * function, the variable or value and the reason. */
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

void plant_log(const PlantInstance *inst, PlantStatus status, const char *format, ...)
{
    char message[1024];
    va_list args;
    /* errors are always logged, the rest only with debug logging on */
    if (!inst->logger || (status < PLANT_ERROR && !inst->loggingOn))
        return;
    va_start(args, format);
    vsnprintf(message, sizeof message, format, args);
    va_end(args);
    inst->logger(inst->environment, inst->instanceName, status, plant_log_category_names[PLANT_LOG_ERRORS], message);
}

static const char *state_name(PlantState state)
{
    switch (state) {
    case PLANT_INSTANTIATED: return "the instantiated state";
    case PLANT_INITIALIZATION_MODE: return "initialization mode";
    case PLANT_STEP_MODE: return "step mode";
    case PLANT_TERMINATED: return "the terminated state";
    }
    return "an unknown state";
}

/* Every parameter and input at its start value, the state at the start. */
void plant_instance_reset(PlantInstance *inst)
{
    size_t i;
    memset(&inst->s, 0, sizeof inst->s);
    inst->s.state = PLANT_INSTANTIATED;
    for (i = 0; i < PLANT_VARIABLE_COUNT; i++)
        if (plant_variables[i].causality == PLANT_PARAMETER || plant_variables[i].causality == PLANT_INPUT)
            plant_set(inst, &plant_variables[i], plant_variables[i].start);
    plant_start(&inst->s.m);
}

PlantInstance *plant_instance_new(const char *instanceName, PlantLogger logger, void *environment)
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
    plant_instance_reset(inst);
    return inst;
}

void plant_instance_free(PlantInstance *inst)
{
    if (!inst)
        return;
    free(inst->instanceName);
    free(inst);
}

PlantInstance *plant_begin(PlantInstance *inst, const char *fn, unsigned states)
{
    if (!inst)
        return NULL;
    if (!(inst->s.state & states)) {
        plant_log(inst, PLANT_ERROR, "%s: not allowed in %s", fn, state_name(inst->s.state));
        return NULL;
    }
    return inst;
}

int plant_arrays_given(const PlantInstance *inst, const char *fn, size_t n, const void *a, const void *b)
{
    if (n > 0 && (!a || !b)) {
        plant_log(inst, PLANT_ERROR, "%s: %zu values but an array is NULL", fn, n);
        return 0;
    }
    return 1;
}

PlantStatus plant_set_debug_logging(PlantInstance *inst, const char *fn, int loggingOn, size_t nCategories,
                                    const char *const categories[])
{
    size_t i, c;
    if (nCategories > 0 && !categories) {
        plant_log(inst, PLANT_ERROR, "%s: %zu categories but the array is NULL", fn, nCategories);
        return PLANT_ERROR;
    }
    for (i = 0; i < nCategories; i++) {
        for (c = 0; c < PLANT_LOG_CATEGORY_COUNT; c++)
            if (categories[i] && strcmp(categories[i], plant_log_category_names[c]) == 0)
                break;
        if (c == PLANT_LOG_CATEGORY_COUNT) {
            plant_log(inst, PLANT_ERROR, "%s: unknown log category \"%s\"", fn, categories[i] ? categories[i] : "(NULL)");
            return PLANT_ERROR;
        }
    }
    inst->loggingOn = loggingOn != 0;
    return PLANT_OK;
}

PlantStatus plant_enter_initialization(PlantInstance *inst, double startTime)
{
    if (!isfinite(startTime)) {
        plant_log(inst, PLANT_ERROR, "EnterInitializationMode: the start time %g is not finite", startTime);
        return PLANT_ERROR;
    }
    inst->s.m.time = startTime;
    inst->s.state = PLANT_INITIALIZATION_MODE;
    plant_start(&inst->s.m);
    return PLANT_OK;
}

PlantStatus plant_exit_initialization(PlantInstance *inst)
{
    plant_start(&inst->s.m);
    inst->s.state = PLANT_STEP_MODE;
    return PLANT_OK;
}

PlantStatus plant_do_step(PlantInstance *inst, const char *fn, double t, double h)
{
    PlantModel *m = &inst->s.m, before;
    if (!isfinite(t) || !isfinite(h) || h <= 0) {
        plant_log(inst, PLANT_ERROR, "%s: communication point %g, step size %g: the step size must be finite and > 0",
                  fn, t, h);
        return PLANT_ERROR;
    }
    /* a master's communication points are sums or products of its step size */
    if (fabs(t - m->time) > 1e-6 * m->internalStep + 8 * DBL_EPSILON * fabs(m->time)) {
        plant_log(inst, PLANT_ERROR, "%s: communication point %.17g is not the current time %.17g", fn, t, m->time);
        return PLANT_ERROR;
    }
    if (plant_internal_steps(m, h) > MAX_INTERNAL_STEPS) {
        plant_log(inst, PLANT_ERROR, "%s: a step of %g s is more than %g internal steps of %g s: not run", fn, h,
                  MAX_INTERNAL_STEPS, m->internalStep);
        return PLANT_ERROR;
    }
    before = *m;
    plant_advance(m, h);
    if (!isfinite(m->angle) || !isfinite(m->speed) || !isfinite(m->current)) {
        plant_log(inst, PLANT_ERROR, "%s: the step from %.17g s leaves the motor's state not finite (angle %g, "
                  "speed %g): not run", fn, t, m->angle, m->speed);
        *m = before;
        return PLANT_ERROR;
    }
    m->time = t + h;
    return PLANT_OK;
}

/* ---- variables ---- */

static const char *const type_names[] = {[PLANT_NONE] = "(none)", [PLANT_REAL] = "Real", [PLANT_INTEGER] = "Integer"};
static const char *const type3_names[] = {[PLANT3_FLOAT64] = "Float64", [PLANT3_INT32] = "Int32",
                                          [PLANT3_INT16] = "Int16"};
static const char *const causality_names[] = {[PLANT_PARAMETER] = "parameter", [PLANT_INPUT] = "input",
                                              [PLANT_OUTPUT] = "output", [PLANT_INDEPENDENT] = "independent"};

const PlantVariable *plant_lookup(const PlantInstance *inst, const char *fn, unsigned vr, int fmi3, unsigned type)
{
    size_t i;
    for (i = 0; i < PLANT_VARIABLE_COUNT; i++) {
        const PlantVariable *v = &plant_variables[i];
        if (v->vr != vr || (!fmi3 && v->type == PLANT_NONE))
            continue;
        if ((fmi3 ? v->type3 : v->type) != type) {
            plant_log(inst, PLANT_ERROR, "%s: value reference %u (%s) is of type %s", fn, vr, v->name,
                      fmi3 ? type3_names[v->type3] : type_names[v->type]);
            return NULL;
        }
        return v;
    }
    plant_log(inst, PLANT_ERROR, "%s: no variable has value reference %u", fn, vr);
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

double plant_get(const PlantInstance *inst, const PlantVariable *v)
{
    return member_value(&inst->s.m, v);
}

void plant_set(PlantInstance *inst, const PlantVariable *v, double value)
{
    char *member = (char *)&inst->s.m + v->offset;
    int32_t n;
    if (is_real(v)) {
        memcpy(member, &value, sizeof value);
    } else {
        n = (int32_t)value;                         /* plant_check: a whole number in the variable's range */
        memcpy(member, &n, sizeof n);
    }
}

/* Parameters (variability fixed) before the end of initialization, inputs
 * until the end; outputs and time never. */
PlantStatus plant_check(const PlantInstance *inst, const char *fn, const PlantVariable *v, double value)
{
    unsigned states = v->causality == PLANT_PARAMETER ? PLANT_INSTANTIATED | PLANT_INITIALIZATION_MODE
                      : v->causality == PLANT_INPUT  ? PLANT_SET_STATES
                                                     : 0;
    if (!states) {
        plant_log(inst, PLANT_ERROR, "%s: %s is an %s and cannot be set", fn, v->name, causality_names[v->causality]);
        return PLANT_ERROR;
    }
    if (!(inst->s.state & states)) {
        plant_log(inst, PLANT_ERROR, "%s: %s, a %s, cannot be set in %s", fn, v->name, causality_names[v->causality],
                  state_name(inst->s.state));
        return PLANT_ERROR;
    }
    if (!(value >= v->min && value <= v->max)) {      /* also NaN */
        plant_log(inst, PLANT_ERROR, "%s: %s = %.17g is not in %.17g .. %.17g: not set", fn, v->name, value, v->min,
                  v->max);
        return PLANT_ERROR;
    }
    if (!isfinite(value)) {
        plant_log(inst, PLANT_ERROR, "%s: %s = %g is not finite: not set", fn, v->name, value);
        return PLANT_ERROR;
    }
    return PLANT_OK;
}

void plant_set_done(PlantInstance *inst)
{
    if (inst->s.state != PLANT_STEP_MODE)
        plant_start(&inst->s.m);
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
        plant_log(inst, PLANT_ERROR, "%s: not a state of this FMU (magic, version %u or size %u differ)", fn,
                  (unsigned)snap->version, (unsigned)snap->size);
        return 0;
    }
    switch (snap->s.state) {
    case PLANT_INSTANTIATED: case PLANT_INITIALIZATION_MODE: case PLANT_STEP_MODE: case PLANT_TERMINATED:
        break;
    default:
        plant_log(inst, PLANT_ERROR, "%s: the state holds no FMI state (%d)", fn, (int)snap->s.state);
        return 0;
    }
    for (i = 0; i < PLANT_VARIABLE_COUNT; i++) {
        const PlantVariable *v = &plant_variables[i];
        double value = member_value(&snap->s.m, v);
        if (!isfinite(value) || value < v->min || value > v->max) {
            plant_log(inst, PLANT_ERROR, "%s: the state's %s = %g is not in %g .. %g", fn, v->name, value, v->min,
                      v->max);
            return 0;
        }
    }
    if (snap->s.m.encoderCount != plant_encoder_count(&snap->s.m)) {
        plant_log(inst, PLANT_ERROR, "%s: the state's encoder count %ld is not that of its angle %.17g", fn,
                  (long)snap->s.m.encoderCount, snap->s.m.angle);
        return 0;
    }
    return 1;
}

PlantStatus plant_state_get(PlantInstance *inst, const char *fn, void **state)
{
    PlantSnapshot *snap;
    if (!state) {
        plant_log(inst, PLANT_ERROR, "%s: the state pointer is NULL", fn);
        return PLANT_ERROR;
    }
    snap = (PlantSnapshot *)(*state ? *state : calloc(1, sizeof *snap));     /* a given state is overwritten */
    if (!snap) {
        plant_log(inst, PLANT_ERROR, "%s: out of memory", fn);
        return PLANT_ERROR;
    }
    memcpy(snap->magic, STATE_MAGIC, sizeof snap->magic);
    snap->version = STATE_VERSION;
    snap->size = sizeof *snap;
    memcpy(&snap->s, &inst->s, sizeof snap->s);
    *state = snap;
    return PLANT_OK;
}

PlantStatus plant_state_set(PlantInstance *inst, const char *fn, const void *state)
{
    if (!state) {
        plant_log(inst, PLANT_ERROR, "%s: the state is NULL", fn);
        return PLANT_ERROR;
    }
    if (!snapshot_valid(inst, fn, (const PlantSnapshot *)state))
        return PLANT_ERROR;
    memcpy(&inst->s, &((const PlantSnapshot *)state)->s, sizeof inst->s);
    return PLANT_OK;
}

PlantStatus plant_state_free(PlantInstance *inst, const char *fn, void **state)
{
    (void)inst;
    (void)fn;
    if (state) {
        free(*state);
        *state = NULL;
    }
    return PLANT_OK;
}

size_t plant_state_size(void)
{
    return sizeof(PlantSnapshot);
}

PlantStatus plant_state_serialize(PlantInstance *inst, const char *fn, const void *state, unsigned char *bytes,
                                  size_t size)
{
    if (!state || !bytes || size != sizeof(PlantSnapshot)) {
        plant_log(inst, PLANT_ERROR, "%s: needs a state and %zu bytes (given %zu)", fn, sizeof(PlantSnapshot), size);
        return PLANT_ERROR;
    }
    memcpy(bytes, state, size);
    return PLANT_OK;
}

PlantStatus plant_state_deserialize(PlantInstance *inst, const char *fn, const unsigned char *bytes, size_t size,
                                    void **state)
{
    PlantSnapshot *snap;
    if (!bytes || !state || size != sizeof(PlantSnapshot)) {
        plant_log(inst, PLANT_ERROR, "%s: a state of this FMU is %zu bytes (given %zu)", fn, sizeof(PlantSnapshot),
                  size);
        return PLANT_ERROR;
    }
    snap = (PlantSnapshot *)calloc(1, sizeof *snap);
    if (!snap) {
        plant_log(inst, PLANT_ERROR, "%s: out of memory", fn);
        return PLANT_ERROR;
    }
    memcpy(snap, bytes, size);
    if (!snapshot_valid(inst, fn, snap)) {
        free(snap);
        return PLANT_ERROR;
    }
    *state = snap;
    return PLANT_OK;
}
