/* FMI 3.0 Co-Simulation over the plant instance (plant_fmu.h): the same model,
 * names and value references as FMI 2, with native types (motorCommand is an
 * Int16, like the chip's axisN.motorCommand) and the independent variable
 * `time`. No event mode, no early return. Every function checks its instance,
 * its pointers and the state it is called in, and answers a bad call with
 * fmi3Error and a log message. */
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"
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

static fmi3Status unsupported(fmi3Instance c, const char *fn, const char *why)
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

static void refuse_instance(fmi3InstanceEnvironment environment, fmi3LogMessageCallback logMessage,
                            const char *why)
{
    if (logMessage)
        logMessage(environment, fmi3Error, "errors", why);
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
        refuse_instance(instanceEnvironment, logMessage, "fmi3InstantiateCoSimulation: instanceName is NULL");
        return NULL;
    }
    if (!instantiationToken || strcmp(instantiationToken, PLANT_INSTANTIATION_TOKEN) != 0) {
        refuse_instance(instanceEnvironment, logMessage, "fmi3InstantiateCoSimulation: the instantiation token "
                        "does not match this binary's " PLANT_INSTANTIATION_TOKEN);
        return NULL;
    }
    if (eventModeUsed) {
        refuse_instance(instanceEnvironment, logMessage, "fmi3InstantiateCoSimulation: this FMU has no event "
                        "mode (hasEventMode is false)");
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

fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName, fmi3String instantiationToken,
                                          fmi3String resourcePath, fmi3Boolean visible, fmi3Boolean loggingOn,
                                          fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage)
{
    (void)instanceName; (void)instantiationToken; (void)resourcePath; (void)visible; (void)loggingOn;
    refuse_instance(instanceEnvironment, logMessage, "fmi3InstantiateModelExchange: Co-Simulation only");
    return NULL;
}

fmi3Instance fmi3InstantiateScheduledExecution(fmi3String instanceName, fmi3String instantiationToken,
                                               fmi3String resourcePath, fmi3Boolean visible,
                                               fmi3Boolean loggingOn, fmi3InstanceEnvironment instanceEnvironment,
                                               fmi3LogMessageCallback logMessage,
                                               fmi3ClockUpdateCallback clockUpdate,
                                               fmi3LockPreemptionCallback lockPreemption,
                                               fmi3UnlockPreemptionCallback unlockPreemption)
{
    (void)instanceName; (void)instantiationToken; (void)resourcePath; (void)visible; (void)loggingOn;
    (void)clockUpdate; (void)lockPreemption; (void)unlockPreemption;
    refuse_instance(instanceEnvironment, logMessage, "fmi3InstantiateScheduledExecution: Co-Simulation only");
    return NULL;
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

fmi3Status fmi3EnterStepMode(fmi3Instance c)
{
    return unsupported(c, "fmi3EnterStepMode", "there is no event mode: initialization leads to step mode");
}

fmi3Status fmi3EnterEventMode(fmi3Instance c)
{
    return unsupported(c, "fmi3EnterEventMode", "hasEventMode is false");
}

fmi3Status fmi3GetOutputDerivatives(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr,
                                    const fmi3Int32 orders[], fmi3Float64 values[], size_t nValues)
{
    (void)vrs; (void)nvr; (void)orders; (void)values; (void)nValues;
    return unsupported(c, "fmi3GetOutputDerivatives", "maxOutputDerivativeOrder is 0");
}

fmi3Status fmi3ActivateModelPartition(fmi3Instance c, fmi3ValueReference clockReference,
                                      fmi3Float64 activationTime)
{
    (void)clockReference; (void)activationTime;
    return unsupported(c, "fmi3ActivateModelPartition", "Co-Simulation only");
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

/* ---- what this FMU does not provide ---- */

fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance c, fmi3ValueReference valueReference,
                                               size_t *nDependencies)
{
    (void)valueReference; (void)nDependencies;
    return unsupported(c, "fmi3GetNumberOfVariableDependencies", "the model description declares the dependencies");
}

fmi3Status fmi3GetVariableDependencies(fmi3Instance c, fmi3ValueReference dependent,
                                       size_t elementIndicesOfDependent[], fmi3ValueReference independents[],
                                       size_t elementIndicesOfIndependents[], fmi3DependencyKind dependencyKinds[],
                                       size_t nDependencies)
{
    (void)dependent; (void)elementIndicesOfDependent; (void)independents; (void)elementIndicesOfIndependents;
    (void)dependencyKinds; (void)nDependencies;
    return unsupported(c, "fmi3GetVariableDependencies", "the model description declares the dependencies");
}

#define NO_DERIVATIVE(fn)                                                                                   \
    fmi3Status fn(fmi3Instance c, const fmi3ValueReference unknowns[], size_t nUnknowns,                    \
                  const fmi3ValueReference knowns[], size_t nKnowns, const fmi3Float64 seed[], size_t nSeed, \
                  fmi3Float64 sensitivity[], size_t nSensitivity)                                           \
    {                                                                                                       \
        (void)unknowns; (void)nUnknowns; (void)knowns; (void)nKnowns; (void)seed; (void)nSeed;              \
        (void)sensitivity; (void)nSensitivity;                                                              \
        return unsupported(c, #fn, "providesDirectionalDerivatives and providesAdjointDerivatives are false"); \
    }

NO_DERIVATIVE(fmi3GetDirectionalDerivative)
NO_DERIVATIVE(fmi3GetAdjointDerivative)

#define NO_ARGUMENTS(fn, why)                   \
    fmi3Status fn(fmi3Instance c)               \
    {                                           \
        return unsupported(c, #fn, why);        \
    }

NO_ARGUMENTS(fmi3EnterConfigurationMode, "there are no structural parameters")
NO_ARGUMENTS(fmi3ExitConfigurationMode, "there are no structural parameters")
NO_ARGUMENTS(fmi3EvaluateDiscreteStates, "there is no event mode")
NO_ARGUMENTS(fmi3EnterContinuousTimeMode, "Co-Simulation only")

#define NO_CLOCKS "there are no clocks"

fmi3Status fmi3GetIntervalDecimal(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr,
                                  fmi3Float64 intervals[], fmi3IntervalQualifier qualifiers[])
{
    (void)vrs; (void)nvr; (void)intervals; (void)qualifiers;
    return unsupported(c, "fmi3GetIntervalDecimal", NO_CLOCKS);
}

fmi3Status fmi3GetIntervalFraction(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr,
                                   fmi3UInt64 counters[], fmi3UInt64 resolutions[],
                                   fmi3IntervalQualifier qualifiers[])
{
    (void)vrs; (void)nvr; (void)counters; (void)resolutions; (void)qualifiers;
    return unsupported(c, "fmi3GetIntervalFraction", NO_CLOCKS);
}

fmi3Status fmi3GetShiftDecimal(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, fmi3Float64 shifts[])
{
    (void)vrs; (void)nvr; (void)shifts;
    return unsupported(c, "fmi3GetShiftDecimal", NO_CLOCKS);
}

fmi3Status fmi3GetShiftFraction(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, fmi3UInt64 counters[],
                                fmi3UInt64 resolutions[])
{
    (void)vrs; (void)nvr; (void)counters; (void)resolutions;
    return unsupported(c, "fmi3GetShiftFraction", NO_CLOCKS);
}

fmi3Status fmi3SetIntervalDecimal(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr,
                                  const fmi3Float64 intervals[])
{
    (void)vrs; (void)nvr; (void)intervals;
    return unsupported(c, "fmi3SetIntervalDecimal", NO_CLOCKS);
}

fmi3Status fmi3SetIntervalFraction(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr,
                                   const fmi3UInt64 counters[], const fmi3UInt64 resolutions[])
{
    (void)vrs; (void)nvr; (void)counters; (void)resolutions;
    return unsupported(c, "fmi3SetIntervalFraction", NO_CLOCKS);
}

fmi3Status fmi3SetShiftDecimal(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr,
                               const fmi3Float64 shifts[])
{
    (void)vrs; (void)nvr; (void)shifts;
    return unsupported(c, "fmi3SetShiftDecimal", NO_CLOCKS);
}

fmi3Status fmi3SetShiftFraction(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr,
                                const fmi3UInt64 counters[], const fmi3UInt64 resolutions[])
{
    (void)vrs; (void)nvr; (void)counters; (void)resolutions;
    return unsupported(c, "fmi3SetShiftFraction", NO_CLOCKS);
}

fmi3Status fmi3UpdateDiscreteStates(fmi3Instance c, fmi3Boolean *discreteStatesNeedUpdate,
                                    fmi3Boolean *terminateSimulation, fmi3Boolean *nominalsOfContinuousStatesChanged,
                                    fmi3Boolean *valuesOfContinuousStatesChanged, fmi3Boolean *nextEventTimeDefined,
                                    fmi3Float64 *nextEventTime)
{
    (void)discreteStatesNeedUpdate; (void)terminateSimulation; (void)nominalsOfContinuousStatesChanged;
    (void)valuesOfContinuousStatesChanged; (void)nextEventTimeDefined; (void)nextEventTime;
    return unsupported(c, "fmi3UpdateDiscreteStates", "there is no event mode");
}

/* Model Exchange functions: this FMU is Co-Simulation only. */
#define ME_ONLY "Co-Simulation only"

fmi3Status fmi3CompletedIntegratorStep(fmi3Instance c, fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi3Boolean *enterEventMode, fmi3Boolean *terminateSimulation)
{
    (void)noSetFMUStatePriorToCurrentPoint; (void)enterEventMode; (void)terminateSimulation;
    return unsupported(c, "fmi3CompletedIntegratorStep", ME_ONLY);
}

fmi3Status fmi3SetTime(fmi3Instance c, fmi3Float64 time)
{
    (void)time;
    return unsupported(c, "fmi3SetTime", ME_ONLY);
}

#define STATE_VECTOR(fn, T)                                              \
    fmi3Status fn(fmi3Instance c, T values[], size_t n)                  \
    {                                                                    \
        (void)values; (void)n;                                           \
        return unsupported(c, #fn, ME_ONLY);                             \
    }

STATE_VECTOR(fmi3SetContinuousStates, const fmi3Float64)
STATE_VECTOR(fmi3GetContinuousStateDerivatives, fmi3Float64)
STATE_VECTOR(fmi3GetEventIndicators, fmi3Float64)
STATE_VECTOR(fmi3GetContinuousStates, fmi3Float64)
STATE_VECTOR(fmi3GetNominalsOfContinuousStates, fmi3Float64)

fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance c, size_t *nEventIndicators)
{
    (void)nEventIndicators;
    return unsupported(c, "fmi3GetNumberOfEventIndicators", ME_ONLY);
}

fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance c, size_t *nContinuousStates)
{
    (void)nContinuousStates;
    return unsupported(c, "fmi3GetNumberOfContinuousStates", ME_ONLY);
}
