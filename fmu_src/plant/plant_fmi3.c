/* FMI 3.0 Co-Simulation over the plant instance (plant_fmu.h): the same model,
 * names and value references as FMI 2, with native types (motorCommand is an
 * Int16, like the chip's axisN.motorCommand) and the independent variable
 * `time`. No event mode, no early return. Every function checks its instance,
 * its pointers and the state it is called in, and answers a bad call with
 * fmi3Error and a log message. */
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"
#include "fmi3_not_provided.h"
#include "plant_fmu.h"

typedef struct {
    PlantInstance *inst;
    fmi3InstanceEnvironment environment;
    fmi3LogMessageCallback logMessage;
} Component;

static const fmi3Status status_of[] = {fmi3OK, fmi3Warning, fmi3Discard, fmi3Error, fmi3Fatal};

static void log_to_environment(void *environment, const char *instanceName, PlantStatus status, const char *category,
                               const char *message)
{
    const Component *comp = (const Component *)environment;
    (void)instanceName;
    if (comp->logMessage)
        comp->logMessage(comp->environment, status_of[status], category, message);
}

static PlantInstance *begin(fmi3Instance c, const char *fn, unsigned states)
{
    return c ? plant_begin(((Component *)c)->inst, fn, states) : NULL;
}

/* The refusal of every function this FMU does not provide (fmi3_not_provided.c). */
fmi3Status pmd_fmi3_unsupported(fmi3Instance c, const char *fn, const char *why)
{
    PlantInstance *inst = begin(c, fn, PLANT_ANY_STATE);
    if (inst)
        plant_log(inst, PLANT_ERROR, "%s: not supported: %s", fn, why);
    return fmi3Error;
}

/* ---- inquiry, logging, life cycle ---- */

const char *fmi3GetVersion(void) { return fmi3Version; }

fmi3Status fmi3SetDebugLogging(fmi3Instance c, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[])
{
    PlantInstance *inst = begin(c, "fmi3SetDebugLogging", PLANT_ANY_STATE);
    return inst ? status_of[plant_set_debug_logging(inst, "fmi3SetDebugLogging", loggingOn, nCategories, categories)]
                : fmi3Error;
}

fmi3Instance fmi3InstantiateCoSimulation(fmi3String instanceName, fmi3String instantiationToken,
                                         fmi3String resourcePath, fmi3Boolean visible, fmi3Boolean loggingOn,
                                         fmi3Boolean eventModeUsed, fmi3Boolean earlyReturnAllowed,
                                         const fmi3ValueReference requiredIntermediateVariables[],
                                         size_t nRequiredIntermediateVariables,
                                         fmi3InstanceEnvironment instanceEnvironment,
                                         fmi3LogMessageCallback logMessage,
                                         fmi3IntermediateUpdateCallback intermediateUpdate)
{
    Component *comp;
    (void)resourcePath; (void)visible; (void)earlyReturnAllowed; (void)requiredIntermediateVariables;
    (void)nRequiredIntermediateVariables; (void)intermediateUpdate;
    if (!instanceName) {
        pmd_fmi3_refuse_instance(instanceEnvironment, logMessage,
                                 "fmi3InstantiateCoSimulation: instanceName is NULL");
        return NULL;
    }
    if (!instantiationToken || strcmp(instantiationToken, PLANT_INSTANTIATION_TOKEN) != 0) {
        pmd_fmi3_refuse_instance(instanceEnvironment, logMessage, "fmi3InstantiateCoSimulation: the "
                                 "instantiation token does not match this binary's " PLANT_INSTANTIATION_TOKEN);
        return NULL;
    }
    if (eventModeUsed) {
        pmd_fmi3_refuse_instance(instanceEnvironment, logMessage, "fmi3InstantiateCoSimulation: this FMU "
                                 "has no event mode (hasEventMode is false)");
        return NULL;
    }
    comp = (Component *)calloc(1, sizeof *comp);
    if (!comp)
        return NULL;
    comp->environment = instanceEnvironment;
    comp->logMessage = logMessage;
    comp->inst = plant_instance_new(instanceName, log_to_environment, comp);
    if (!comp->inst) {
        free(comp);
        return NULL;
    }
    plant_set_debug_logging(comp->inst, "fmi3InstantiateCoSimulation", loggingOn, 0, NULL);
    return comp;
}

void fmi3FreeInstance(fmi3Instance c)
{
    if (!c)
        return;
    plant_instance_free(((Component *)c)->inst);
    free(c);
}

fmi3Status fmi3EnterInitializationMode(fmi3Instance c, fmi3Boolean toleranceDefined, fmi3Float64 tolerance,
                                       fmi3Float64 startTime, fmi3Boolean stopTimeDefined, fmi3Float64 stopTime)
{
    PlantInstance *inst = begin(c, "fmi3EnterInitializationMode", PLANT_INSTANTIATED);
    (void)toleranceDefined; (void)tolerance; (void)stopTimeDefined; (void)stopTime;
    return inst ? status_of[plant_enter_initialization(inst, startTime)] : fmi3Error;
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance c)
{
    PlantInstance *inst = begin(c, "fmi3ExitInitializationMode", PLANT_INITIALIZATION_MODE);
    return inst ? status_of[plant_exit_initialization(inst)] : fmi3Error;
}

fmi3Status fmi3Terminate(fmi3Instance c)
{
    PlantInstance *inst = begin(c, "fmi3Terminate", PLANT_INITIALIZATION_MODE | PLANT_STEP_MODE);
    if (!inst)
        return fmi3Error;
    inst->s.state = PLANT_TERMINATED;
    return fmi3OK;
}

fmi3Status fmi3Reset(fmi3Instance c)
{
    PlantInstance *inst = begin(c, "fmi3Reset", PLANT_ANY_STATE);
    if (!inst)
        return fmi3Error;
    plant_instance_reset(inst);
    return fmi3OK;
}

/* ---- variables: every one is a scalar ---- */

static int count_matches(PlantInstance *inst, const char *fn, size_t nvr, size_t nValues)
{
    if (nvr != nValues) {
        plant_log(inst, PLANT_ERROR, "%s: nValues is %zu but %zu scalar value references are given", fn, nValues,
                  nvr);
        return 0;
    }
    return 1;
}

/* A get refused for one value reference returns no value. */
#define GETSET(T, Type, type3)                                                                              \
    fmi3Status fmi3Get##Type(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, T values[],        \
                             size_t nValues)                                                                \
    {                                                                                                       \
        PlantInstance *inst = begin(c, "fmi3Get" #Type, PLANT_GET_STATES);                                  \
        size_t i;                                                                                           \
        if (!inst || !plant_arrays_given(inst, "fmi3Get" #Type, nvr, vrs, values) ||                        \
            !count_matches(inst, "fmi3Get" #Type, nvr, nValues))                                            \
            return fmi3Error;                                                                               \
        for (i = 0; i < nvr; i++)                                                                           \
            if (!plant_lookup(inst, "fmi3Get" #Type, vrs[i], 1, type3))                                     \
                return fmi3Error;                                                                           \
        for (i = 0; i < nvr; i++)                                                                           \
            values[i] = (T)plant_get(inst, plant_lookup(inst, "fmi3Get" #Type, vrs[i], 1, type3));          \
        return fmi3OK;                                                                                      \
    }                                                                                                       \
    fmi3Status fmi3Set##Type(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, const T values[],  \
                             size_t nValues)                                                                \
    {                                                                                                       \
        PlantInstance *inst = begin(c, "fmi3Set" #Type, PLANT_SET_STATES);                                  \
        const PlantVariable *v;                                                                             \
        size_t i;                                                                                           \
        if (!inst || !plant_arrays_given(inst, "fmi3Set" #Type, nvr, vrs, values) ||                        \
            !count_matches(inst, "fmi3Set" #Type, nvr, nValues))                                            \
            return fmi3Error;                                                                               \
        for (i = 0; i < nvr; i++)                                                                           \
            if (!(v = plant_lookup(inst, "fmi3Set" #Type, vrs[i], 1, type3)) ||                             \
                plant_check(inst, "fmi3Set" #Type, v, (double)values[i]) != PLANT_OK)                       \
                return fmi3Error;                                                                           \
        for (i = 0; i < nvr; i++)                                                                           \
            plant_set(inst, plant_lookup(inst, "fmi3Set" #Type, vrs[i], 1, type3), (double)values[i]);      \
        plant_set_done(inst);                                                                               \
        return fmi3OK;                                                                                      \
    }

GETSET(fmi3Float64, Float64, PLANT3_FLOAT64)
GETSET(fmi3Int32, Int32, PLANT3_INT32)
GETSET(fmi3Int16, Int16, PLANT3_INT16)

/* Types this FMU has no variables of: any value reference is an error. */
static fmi3Status no_such_type(fmi3Instance c, const char *fn, const fmi3ValueReference vrs[], size_t nvr,
                               unsigned states)
{
    PlantInstance *inst = begin(c, fn, states);
    if (!inst || !plant_arrays_given(inst, fn, nvr, vrs, vrs))
        return fmi3Error;
    if (nvr > 0) {
        plant_log(inst, PLANT_ERROR, "%s: no variable of this type has value reference %u", fn, vrs[0]);
        return fmi3Error;
    }
    return fmi3OK;
}

#define NO_SUCH_TYPE(T, Type)                                                                               \
    fmi3Status fmi3Get##Type(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, T values[],        \
                             size_t nValues)                                                                \
    {                                                                                                       \
        (void)values; (void)nValues;                                                                        \
        return no_such_type(c, "fmi3Get" #Type, vrs, nvr, PLANT_GET_STATES);                                \
    }                                                                                                       \
    fmi3Status fmi3Set##Type(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, const T values[],  \
                             size_t nValues)                                                                \
    {                                                                                                       \
        (void)values; (void)nValues;                                                                        \
        return no_such_type(c, "fmi3Set" #Type, vrs, nvr, PLANT_SET_STATES);                                \
    }

NO_SUCH_TYPE(fmi3Float32, Float32)
NO_SUCH_TYPE(fmi3Int8, Int8)
NO_SUCH_TYPE(fmi3UInt8, UInt8)
NO_SUCH_TYPE(fmi3UInt16, UInt16)
NO_SUCH_TYPE(fmi3UInt32, UInt32)
NO_SUCH_TYPE(fmi3Int64, Int64)
NO_SUCH_TYPE(fmi3UInt64, UInt64)
NO_SUCH_TYPE(fmi3Boolean, Boolean)
NO_SUCH_TYPE(fmi3String, String)

fmi3Status fmi3GetBinary(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, size_t valueSizes[],
                         fmi3Binary values[], size_t nValues)
{
    (void)valueSizes; (void)values; (void)nValues;
    return no_such_type(c, "fmi3GetBinary", vrs, nvr, PLANT_GET_STATES);
}

fmi3Status fmi3SetBinary(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, const size_t valueSizes[],
                         const fmi3Binary values[], size_t nValues)
{
    (void)valueSizes; (void)values; (void)nValues;
    return no_such_type(c, "fmi3SetBinary", vrs, nvr, PLANT_SET_STATES);
}

fmi3Status fmi3GetClock(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, fmi3Clock values[])
{
    (void)values;
    return no_such_type(c, "fmi3GetClock", vrs, nvr, PLANT_GET_STATES);
}

fmi3Status fmi3SetClock(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, const fmi3Clock values[])
{
    (void)values;
    return no_such_type(c, "fmi3SetClock", vrs, nvr, PLANT_SET_STATES);
}

/* ---- co-simulation ---- */

fmi3Status fmi3DoStep(fmi3Instance c, fmi3Float64 currentCommunicationPoint, fmi3Float64 communicationStepSize,
                      fmi3Boolean noSetFMUStatePriorToCurrentPoint, fmi3Boolean *eventHandlingNeeded,
                      fmi3Boolean *terminateSimulation, fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime)
{
    PlantInstance *inst = begin(c, "fmi3DoStep", PLANT_STEP_MODE);
    PlantStatus status;
    (void)noSetFMUStatePriorToCurrentPoint;
    if (!inst)
        return fmi3Error;
    if (!eventHandlingNeeded || !terminateSimulation || !earlyReturn || !lastSuccessfulTime) {
        plant_log(inst, PLANT_ERROR, "fmi3DoStep: an output argument is NULL");
        return fmi3Error;
    }
    status = plant_do_step(inst, "fmi3DoStep", currentCommunicationPoint, communicationStepSize);
    *eventHandlingNeeded = fmi3False;
    *terminateSimulation = fmi3False;
    *earlyReturn = fmi3False;
    *lastSuccessfulTime = inst->s.m.time;
    return status_of[status];
}

/* ---- FMU state ---- */

fmi3Status fmi3GetFMUState(fmi3Instance c, fmi3FMUState *state)
{
    PlantInstance *inst = begin(c, "fmi3GetFMUState", PLANT_ANY_STATE);
    return inst ? status_of[plant_state_get(inst, "fmi3GetFMUState", state)] : fmi3Error;
}

fmi3Status fmi3SetFMUState(fmi3Instance c, fmi3FMUState state)
{
    PlantInstance *inst = begin(c, "fmi3SetFMUState", PLANT_ANY_STATE);
    return inst ? status_of[plant_state_set(inst, "fmi3SetFMUState", state)] : fmi3Error;
}

fmi3Status fmi3FreeFMUState(fmi3Instance c, fmi3FMUState *state)
{
    PlantInstance *inst = begin(c, "fmi3FreeFMUState", PLANT_ANY_STATE);
    return inst ? status_of[plant_state_free(inst, "fmi3FreeFMUState", state)] : fmi3Error;
}

fmi3Status fmi3SerializedFMUStateSize(fmi3Instance c, fmi3FMUState state, size_t *size)
{
    PlantInstance *inst = begin(c, "fmi3SerializedFMUStateSize", PLANT_ANY_STATE);
    if (!inst)
        return fmi3Error;
    if (!state || !size) {
        plant_log(inst, PLANT_ERROR, "fmi3SerializedFMUStateSize: the state or the size pointer is NULL");
        return fmi3Error;
    }
    *size = plant_state_size();
    return fmi3OK;
}

fmi3Status fmi3SerializeFMUState(fmi3Instance c, fmi3FMUState state, fmi3Byte serializedState[], size_t size)
{
    PlantInstance *inst = begin(c, "fmi3SerializeFMUState", PLANT_ANY_STATE);
    return inst ? status_of[plant_state_serialize(inst, "fmi3SerializeFMUState", state, serializedState, size)]
                : fmi3Error;
}

fmi3Status fmi3DeserializeFMUState(fmi3Instance c, const fmi3Byte serializedState[], size_t size,
                                   fmi3FMUState *state)
{
    PlantInstance *inst = begin(c, "fmi3DeserializeFMUState", PLANT_ANY_STATE);
    return inst ? status_of[plant_state_deserialize(inst, "fmi3DeserializeFMUState", serializedState, size, state)]
                : fmi3Error;
}
