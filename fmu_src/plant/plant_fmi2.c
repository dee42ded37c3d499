/* FMI 2.0 Co-Simulation over the plant instance (plant_fmu.h). Every function
 * checks its component, its pointers and the state it is called in, and
 * answers a bad call with fmi2Error and a log message. */
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "fmi2_not_provided.h"
#include "plant_fmu.h"

typedef struct {
    PlantInstance *inst;
    fmi2CallbackFunctions functions;
} Component;

static const fmi2Status status_of[] = {fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal};

/* The logger's message is a printf format: a '%' goes out as "%%", and no
 * variadic arguments are passed. */
static void log_to_environment(void *environment, const char *instanceName, PlantStatus status, const char *category,
                               const char *message)
{
    const Component *comp = (const Component *)environment;
    char escaped[2048];
    size_t i = 0;
    for (; *message && i + 2 < sizeof escaped; message++) {
        if (*message == '%')
            escaped[i++] = '%';
        escaped[i++] = *message;
    }
    escaped[i] = '\0';
    comp->functions.logger(comp->functions.componentEnvironment, instanceName, status_of[status], category, escaped);
}

static PlantInstance *begin(fmi2Component c, const char *fn, unsigned states)
{
    return c ? plant_begin(((Component *)c)->inst, fn, states) : NULL;
}

/* The refusal of every function this FMU does not provide (fmi2_not_provided.c). */
fmi2Status pmd_fmi2_unsupported(fmi2Component c, const char *fn, const char *why)
{
    PlantInstance *inst = begin(c, fn, PLANT_ANY_STATE);
    if (inst)
        plant_log(inst, PLANT_ERROR, "%s: not supported: %s", fn, why);
    return fmi2Error;
}

/* ---- inquiry, logging, life cycle ---- */

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[])
{
    PlantInstance *inst = begin(c, "fmi2SetDebugLogging", PLANT_ANY_STATE);
    return inst ? status_of[plant_set_debug_logging(inst, "fmi2SetDebugLogging", loggingOn, nCategories, categories)]
                : fmi2Error;
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions *functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn)
{
    Component *comp;
    (void)fmuResourceLocation;
    (void)visible;
    if (!functions || !functions->logger)
        return NULL;
    if (!instanceName) {
        functions->logger(functions->componentEnvironment, "?", fmi2Error, "errors",
                          "fmi2Instantiate: instanceName is NULL");
        return NULL;
    }
    if (fmuType != fmi2CoSimulation) {
        functions->logger(functions->componentEnvironment, instanceName, fmi2Error, "errors",
                          "fmi2Instantiate: this FMU supports Co-Simulation only");
        return NULL;
    }
    if (!fmuGUID || strcmp(fmuGUID, PLANT_INSTANTIATION_TOKEN) != 0) {
        functions->logger(functions->componentEnvironment, instanceName, fmi2Error, "errors",
                          "fmi2Instantiate: the GUID does not match this binary's " PLANT_INSTANTIATION_TOKEN);
        return NULL;
    }
    comp = (Component *)calloc(1, sizeof *comp);
    if (!comp)
        return NULL;
    comp->functions = *functions;
    comp->inst = plant_instance_new(instanceName, log_to_environment, comp);
    if (!comp->inst) {
        free(comp);
        return NULL;
    }
    plant_set_debug_logging(comp->inst, "fmi2Instantiate", loggingOn, 0, NULL);
    return comp;
}

void fmi2FreeInstance(fmi2Component c)
{
    if (!c)
        return;
    plant_instance_free(((Component *)c)->inst);
    free(c);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    PlantInstance *inst = begin(c, "fmi2SetupExperiment", PLANT_INSTANTIATED);
    (void)toleranceDefined; (void)tolerance; (void)stopTimeDefined; (void)stopTime;
    if (!inst)
        return fmi2Error;
    inst->s.m.time = startTime;
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    PlantInstance *inst = begin(c, "fmi2EnterInitializationMode", PLANT_INSTANTIATED);
    return inst ? status_of[plant_enter_initialization(inst, inst->s.m.time)] : fmi2Error;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    PlantInstance *inst = begin(c, "fmi2ExitInitializationMode", PLANT_INITIALIZATION_MODE);
    return inst ? status_of[plant_exit_initialization(inst)] : fmi2Error;
}

fmi2Status fmi2Terminate(fmi2Component c)
{
    PlantInstance *inst = begin(c, "fmi2Terminate", PLANT_INITIALIZATION_MODE | PLANT_STEP_MODE);
    if (!inst)
        return fmi2Error;
    inst->s.state = PLANT_TERMINATED;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c)
{
    PlantInstance *inst = begin(c, "fmi2Reset", PLANT_ANY_STATE);
    if (!inst)
        return fmi2Error;
    plant_instance_reset(inst);
    return fmi2OK;
}

/* ---- variables ---- */

/* A get refused for one value reference returns no value. */
#define GET_FUNCTION(fn, T, type)                                                                 \
    fmi2Status fn(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, T value[])        \
    {                                                                                            \
        PlantInstance *inst = begin(c, #fn, PLANT_GET_STATES);                                   \
        size_t i;                                                                                \
        if (!inst || !plant_arrays_given(inst, #fn, nvr, vr, value))                             \
            return fmi2Error;                                                                    \
        for (i = 0; i < nvr; i++)                                                                \
            if (!plant_lookup(inst, #fn, vr[i], 0, type))                                        \
                return fmi2Error;                                                                \
        for (i = 0; i < nvr; i++)                                                                \
            value[i] = (T)plant_get(inst, plant_lookup(inst, #fn, vr[i], 0, type));              \
        return fmi2OK;                                                                           \
    }

/* Sets are all or nothing: every value is checked before any is set. */
#define SET_FUNCTION(fn, T, type)                                                                 \
    fmi2Status fn(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const T value[])  \
    {                                                                                            \
        PlantInstance *inst = begin(c, #fn, PLANT_SET_STATES);                                   \
        const PlantVariable *v;                                                                  \
        size_t i;                                                                                \
        if (!inst || !plant_arrays_given(inst, #fn, nvr, vr, value))                             \
            return fmi2Error;                                                                    \
        for (i = 0; i < nvr; i++)                                                                \
            if (!(v = plant_lookup(inst, #fn, vr[i], 0, type)) ||                                \
                plant_check(inst, #fn, v, (double)value[i]) != PLANT_OK)                         \
                return fmi2Error;                                                                \
        for (i = 0; i < nvr; i++)                                                                \
            plant_set(inst, plant_lookup(inst, #fn, vr[i], 0, type), (double)value[i]);          \
        plant_set_done(inst);                                                                    \
        return fmi2OK;                                                                           \
    }

GET_FUNCTION(fmi2GetReal, fmi2Real, PLANT_REAL)
GET_FUNCTION(fmi2GetInteger, fmi2Integer, PLANT_INTEGER)
SET_FUNCTION(fmi2SetReal, fmi2Real, PLANT_REAL)
SET_FUNCTION(fmi2SetInteger, fmi2Integer, PLANT_INTEGER)

/* Types this FMU has no variables of: any value reference is an error. */
static fmi2Status no_such_type(fmi2Component c, const char *fn, size_t nvr, const fmi2ValueReference vr[],
                               const void *value, unsigned states)
{
    PlantInstance *inst = begin(c, fn, states);
    if (!inst || !plant_arrays_given(inst, fn, nvr, vr, value))
        return fmi2Error;
    if (nvr > 0) {
        plant_log(inst, PLANT_ERROR, "%s: no variable of this type has value reference %u", fn, vr[0]);
        return fmi2Error;
    }
    return fmi2OK;
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[])
{
    return no_such_type(c, "fmi2GetBoolean", nvr, vr, value, PLANT_GET_STATES);
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[])
{
    return no_such_type(c, "fmi2SetBoolean", nvr, vr, value, PLANT_SET_STATES);
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[])
{
    return no_such_type(c, "fmi2GetString", nvr, vr, value, PLANT_GET_STATES);
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[])
{
    return no_such_type(c, "fmi2SetString", nvr, vr, value, PLANT_SET_STATES);
}

/* ---- co-simulation ---- */

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    PlantInstance *inst = begin(c, "fmi2DoStep", PLANT_STEP_MODE);
    (void)noSetFMUStatePriorToCurrentPoint;
    return inst ? status_of[plant_do_step(inst, "fmi2DoStep", currentCommunicationPoint, communicationStepSize)]
                : fmi2Error;
}

/* ---- FMU state ---- */

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *state)
{
    PlantInstance *inst = begin(c, "fmi2GetFMUstate", PLANT_ANY_STATE);
    return inst ? status_of[plant_state_get(inst, "fmi2GetFMUstate", state)] : fmi2Error;
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate state)
{
    PlantInstance *inst = begin(c, "fmi2SetFMUstate", PLANT_ANY_STATE);
    return inst ? status_of[plant_state_set(inst, "fmi2SetFMUstate", state)] : fmi2Error;
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *state)
{
    PlantInstance *inst = begin(c, "fmi2FreeFMUstate", PLANT_ANY_STATE);
    return inst ? status_of[plant_state_free(inst, "fmi2FreeFMUstate", state)] : fmi2Error;
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate state, size_t *size)
{
    PlantInstance *inst = begin(c, "fmi2SerializedFMUstateSize", PLANT_ANY_STATE);
    if (!inst)
        return fmi2Error;
    if (!state || !size) {
        plant_log(inst, PLANT_ERROR, "fmi2SerializedFMUstateSize: the state or the size pointer is NULL");
        return fmi2Error;
    }
    *size = plant_state_size();
    return fmi2OK;
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate state, fmi2Byte serializedState[], size_t size)
{
    PlantInstance *inst = begin(c, "fmi2SerializeFMUstate", PLANT_ANY_STATE);
    return inst ? status_of[plant_state_serialize(inst, "fmi2SerializeFMUstate", state,
                                                  (unsigned char *)serializedState, size)] : fmi2Error;
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[], size_t size,
                                   fmi2FMUstate *state)
{
    PlantInstance *inst = begin(c, "fmi2DeSerializeFMUstate", PLANT_ANY_STATE);
    return inst ? status_of[plant_state_deserialize(inst, "fmi2DeSerializeFMUstate",
                                                    (const unsigned char *)serializedState, size, state)]
                : fmi2Error;
}
