/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 3.0 Co-Simulation, written once for both FMUs over the model API
 * (model.h: the chip's fmu_src/fmi/model.c and model3.c, the plant's
 * plant_fmu.c): native types, arrays as the model declares them. No event
 * mode, no early return. Every function checks its instance, its pointers and
 * the state it is called in, and answers a bad call with fmi3Error and a log
 * message. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3.h"
#include "token.h"

/* The environment's callbacks live beside the model (the fuzzers read inst, first). */
typedef struct {
    PmdModel *inst;
    fmi3InstanceEnvironment environment;
    fmi3LogMessageCallback logMessage;
} Component;

static const fmi3Status status_of[] = {fmi3OK, fmi3Warning, fmi3Discard, fmi3Error, fmi3Fatal};

static void log_to_environment(void *environment, const char *instanceName, PmdStatus status, const char *category,
                               const char *message)
{
    const Component *comp = (const Component *)environment;
    (void)instanceName;
    if (comp->logMessage)
        comp->logMessage(comp->environment, status_of[status], category, message);
}

PmdModel *pmd_fmi3_begin(fmi3Instance c, const char *fn, unsigned states)
{
    PmdModel *m = c ? ((Component *)c)->inst : NULL;
    if (m && !(pmd_model_fmi_state(m) & states)) {
        pmd_model_error(m, "%s: not allowed in %s", fn, pmd_model_state_name(pmd_model_fmi_state(m)));
        return NULL;
    }
    return m;
}

#define begin pmd_fmi3_begin

static int arrays_given(const PmdModel *m, const char *fn, size_t n, const void *a, const void *b)
{
    if (n > 0 && (!a || !b)) {
        pmd_model_error(m, "%s: %zu values but an array is NULL", fn, n);
        return 0;
    }
    return 1;
}

fmi3Status pmd_fmi3_unsupported(fmi3Instance c, const char *fn, const char *why)
{
    PmdModel *m = begin(c, fn, PMD_ANY_STATE);
    if (m)
        pmd_model_error(m, "%s: not supported: %s", fn, why);
    return fmi3Error;
}

void pmd_fmi3_refuse_instance(fmi3InstanceEnvironment environment, fmi3LogMessageCallback logMessage,
                              const char *why)
{
    if (logMessage)
        logMessage(environment, fmi3Error, "errors", why);
}

/* The body of a function that hands the call to the model: fn is F's name,
 * inst the model if F is legal in the states (else fmi3Error, logged). */
#define CALL_MODEL(F, states, call)                                                                  \
    do {                                                                                             \
        static const char fn[] = #F;                                                                 \
        PmdModel *inst = begin(c, fn, states);                                                       \
        return inst ? status_of[call] : fmi3Error;                                                   \
    } while (0)

/* ---- inquiry, logging, life cycle ---- */

const char *fmi3GetVersion(void) { return fmi3Version; }

fmi3Status fmi3SetDebugLogging(fmi3Instance c, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[])
{
    CALL_MODEL(fmi3SetDebugLogging, PMD_ANY_STATE,
               pmd_model_set_debug_logging(inst, fn, loggingOn, nCategories, categories));
}

/* A copy of resourcePath (FMI 3.0 section 2.3.1: the absolute path of the
 * resources folder, with a trailing separator, or NULL), or NULL. */
static char *resources_of(const char *resourcePath)
{
    char *folder;
    if (!resourcePath || !*resourcePath || !(folder = (char *)malloc(strlen(resourcePath) + 1)))
        return NULL;
    strcpy(folder, resourcePath);
    return folder;
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
    char *resources, message[1024];
    const char *noResources;
    (void)visible; (void)earlyReturnAllowed; (void)requiredIntermediateVariables;
    (void)nRequiredIntermediateVariables; (void)intermediateUpdate;
    if (!instanceName) {
        pmd_fmi3_refuse_instance(instanceEnvironment, logMessage,
                                 "fmi3InstantiateCoSimulation: instanceName is NULL");
        return NULL;
    }
    if (eventModeUsed) {
        pmd_fmi3_refuse_instance(instanceEnvironment, logMessage, "fmi3InstantiateCoSimulation: this FMU "
                                 "has no event mode (hasEventMode is false)");
        return NULL;
    }
    /* the resources folder first: a packed FMU's token is there (token.h) */
    resources = resources_of(resourcePath);
    noResources = resourcePath ? "the importer gave an empty resourcePath" : "the importer gave no resourcePath (NULL)";
    if (!pmd_token_accepted("fmi3InstantiateCoSimulation", "instantiation token", instantiationToken, resources,
                            noResources, message, sizeof message)) {
        pmd_fmi3_refuse_instance(instanceEnvironment, logMessage, message);
        free(resources);
        return NULL;
    }
    if (!(comp = (Component *)calloc(1, sizeof *comp))) {
        free(resources);
        return NULL;
    }
    comp->environment = instanceEnvironment;
    comp->logMessage = logMessage;
    if (!(comp->inst = pmd_model_new(instanceName, log_to_environment, comp))) {
        free(comp);
        free(resources);
        return NULL;
    }
    pmd_model_set_debug_logging(comp->inst, "fmi3InstantiateCoSimulation", loggingOn, 0, NULL);
    if (pmd_model_resources(comp->inst, "fmi3InstantiateCoSimulation", resources, noResources) != PMD_OK) {
        fmi3FreeInstance(comp);
        return NULL;
    }
    return comp;
}

void fmi3FreeInstance(fmi3Instance c)
{
    if (!c)
        return;
    pmd_model_free(((Component *)c)->inst);
    free(c);
}

fmi3Status fmi3EnterInitializationMode(fmi3Instance c, fmi3Boolean toleranceDefined, fmi3Float64 tolerance,
                                       fmi3Float64 startTime, fmi3Boolean stopTimeDefined, fmi3Float64 stopTime)
{
    (void)toleranceDefined; (void)tolerance; (void)stopTimeDefined; (void)stopTime;
    CALL_MODEL(fmi3EnterInitializationMode, PMD_INSTANTIATED, pmd_model_enter_initialization(inst, fn, startTime));
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance c)
{
    CALL_MODEL(fmi3ExitInitializationMode, PMD_INITIALIZATION_MODE, pmd_model_exit_initialization(inst, fn));
}

fmi3Status fmi3Terminate(fmi3Instance c)
{
    PmdModel *inst = begin(c, "fmi3Terminate", PMD_INITIALIZATION_MODE | PMD_STEP_MODE);
    if (!inst)
        return fmi3Error;
    pmd_model_terminate(inst);
    return fmi3OK;
}

fmi3Status fmi3Reset(fmi3Instance c)
{
    PmdModel *inst = begin(c, "fmi3Reset", PMD_ANY_STATE);
    if (!inst)
        return fmi3Error;
    pmd_model_reset(inst);
    return fmi3OK;
}

/* ---- variables ---- */

/* A type the model has no variables of: refused for its first value reference, if any. */
static fmi3Status no_such_type(fmi3Instance c, const char *fn, PmdFmi3Type type, const fmi3ValueReference vrs[],
                               size_t nvr, unsigned states)
{
    PmdModel *inst = begin(c, fn, states);
    if (!inst || !arrays_given(inst, fn, nvr, vrs, vrs))
        return fmi3Error;
    return nvr == 0 || pmd_model3_no_such_type(inst, fn, type, vrs[0]) == PMD_OK ? fmi3OK : fmi3Error;
}

/* The model for a call of nvr value references holding nValues values of the
 * type, else NULL and *refusal the answer (a type the model has none of: as
 * no_such_type answers). Values are counted over all elements of all the value
 * references (an array contributes all its elements). sizes: GetBinary's
 * valueSizes, checked after the values (the other calls pass vrs again). */
static PmdModel *begin_values(fmi3Instance c, const char *fn, PmdFmi3Type type, unsigned states,
                              const fmi3ValueReference vrs[], size_t nvr, const void *values, const void *sizes,
                              size_t nValues, fmi3Status *refusal)
{
    PmdModel *inst;
    *refusal = fmi3Error;
    if (!pmd_model3_has(type)) {
        *refusal = no_such_type(c, fn, type, vrs, nvr, states);
        return NULL;
    }
    inst = begin(c, fn, states);
    if (!inst || !arrays_given(inst, fn, nvr, vrs, values) || !arrays_given(inst, fn, nvr, sizes, sizes) ||
        !pmd_model3_count(inst, fn, type, vrs, nvr, nValues))
        return NULL;
    return inst;
}

/* A get checks every value reference before the model commits (the chip:
 * pending port writes executed first, CONTRACT 2.2): a get refused for a value
 * reference returns no value. */
static fmi3Status get_values(fmi3Instance c, const char *fn, PmdFmi3Type type, const fmi3ValueReference vrs[],
                             size_t nvr, void *values, size_t nValues)
{
    fmi3Status refusal;
    PmdModel *inst = begin_values(c, fn, type, PMD_GET_STATES, vrs, nvr, values, vrs, nValues, &refusal);
    size_t i, k = 0;
    if (!inst)
        return refusal;
    for (i = 0; i < nvr; i++)
        if (!pmd_model3_given(inst, fn, vrs[i], type))
            return fmi3Error;
    pmd_model_commit(inst);
    for (i = 0; i < nvr; i++)
        if (pmd_model3_get(inst, fn, type, vrs[i], values, &k) != PMD_OK)
            return fmi3Error;
    return fmi3OK;
}

/* Sets are all or nothing: every value is checked, then what they ask for
 * together, before any is applied (model.h). */
static fmi3Status set_values(fmi3Instance c, const char *fn, PmdFmi3Type type, const fmi3ValueReference vrs[],
                             size_t nvr, const void *values, size_t nValues)
{
    fmi3Status refusal;
    PmdModel *inst = begin_values(c, fn, type, PMD_SET_STATES, vrs, nvr, values, vrs, nValues, &refusal);
    size_t i, k;
    int apply;
    if (!inst)
        return refusal;
    pmd_model_set_begin(inst);
    for (apply = 0; apply <= 1; apply++) {
        if (apply && pmd_model_set_check(inst, fn) != PMD_OK)
            return fmi3Error;
        for (i = 0, k = 0; i < nvr; i++)
            if (pmd_model3_set(inst, fn, type, vrs[i], values, &k, apply) != PMD_OK)
                return fmi3Error;
    }
    return fmi3OK;
}

#define GETSET(T, Type, type3)                                                                              \
    fmi3Status fmi3Get##Type(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, T values[],        \
                             size_t nValues)                                                                \
    {                                                                                                       \
        return get_values(c, "fmi3Get" #Type, type3, vrs, nvr, values, nValues);                            \
    }                                                                                                       \
    fmi3Status fmi3Set##Type(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, const T values[],  \
                             size_t nValues)                                                                \
    {                                                                                                       \
        return set_values(c, "fmi3Set" #Type, type3, vrs, nvr, values, nValues);                            \
    }

GETSET(fmi3Float32, Float32, PMD_FMI3_FLOAT32)
GETSET(fmi3Float64, Float64, PMD_FMI3_FLOAT64)
GETSET(fmi3Int8, Int8, PMD_FMI3_INT8)
GETSET(fmi3UInt8, UInt8, PMD_FMI3_UINT8)
GETSET(fmi3Int16, Int16, PMD_FMI3_INT16)
GETSET(fmi3UInt16, UInt16, PMD_FMI3_UINT16)
GETSET(fmi3Int32, Int32, PMD_FMI3_INT32)
GETSET(fmi3UInt32, UInt32, PMD_FMI3_UINT32)
GETSET(fmi3Int64, Int64, PMD_FMI3_INT64)
GETSET(fmi3UInt64, UInt64, PMD_FMI3_UINT64)
GETSET(fmi3Boolean, Boolean, PMD_FMI3_BOOLEAN)

/* Strings are neither committed before a get nor checked together before a set. */
fmi3Status fmi3GetString(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, fmi3String values[],
                         size_t nValues)
{
    fmi3Status refusal;
    PmdModel *inst = begin_values(c, "fmi3GetString", PMD_FMI3_STRING, PMD_GET_STATES, vrs, nvr, values, vrs,
                                  nValues, &refusal);
    size_t i;
    if (!inst)
        return refusal;
    for (i = 0; i < nvr; i++)
        if (pmd_model_get_string(inst, "fmi3GetString", vrs[i], &values[i]) != PMD_OK)
            return fmi3Error;
    return fmi3OK;
}

fmi3Status fmi3SetString(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, const fmi3String values[],
                         size_t nValues)
{
    fmi3Status refusal;
    PmdModel *inst = begin_values(c, "fmi3SetString", PMD_FMI3_STRING, PMD_SET_STATES, vrs, nvr, values, vrs,
                                  nValues, &refusal);
    size_t i;
    int apply;
    if (!inst)
        return refusal;
    for (apply = 0; apply <= 1; apply++)
        for (i = 0; i < nvr; i++)
            if (pmd_model_set_string(inst, "fmi3SetString", vrs[i], values[i], apply) != PMD_OK)
                return fmi3Error;
    return fmi3OK;
}

fmi3Status fmi3GetBinary(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, size_t valueSizes[],
                         fmi3Binary values[], size_t nValues)
{
    fmi3Status refusal;
    PmdModel *inst = begin_values(c, "fmi3GetBinary", PMD_FMI3_BINARY, PMD_GET_STATES, vrs, nvr, values,
                                  valueSizes, nValues, &refusal);
    size_t i;
    if (!inst)
        return refusal;
    for (i = 0; i < nvr; i++)
        if (pmd_model3_get_binary(inst, "fmi3GetBinary", vrs[i], &values[i], &valueSizes[i]) != PMD_OK)
            return fmi3Error;
    return fmi3OK;
}

/* The shell checks the value references and their count only: the model says whether a Binary can be set. */
fmi3Status fmi3SetBinary(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, const size_t valueSizes[],
                         const fmi3Binary values[], size_t nValues)
{
    fmi3Status refusal;
    PmdModel *inst = begin_values(c, "fmi3SetBinary", PMD_FMI3_BINARY, PMD_SET_STATES, vrs, nvr, vrs, vrs, nValues,
                                  &refusal);
    return inst ? status_of[pmd_model3_set_binaries(inst, "fmi3SetBinary", vrs, nvr, valueSizes, values)] : refusal;
}

fmi3Status fmi3GetClock(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, fmi3Clock values[])
{
    (void)values;
    return no_such_type(c, "fmi3GetClock", PMD_FMI3_CLOCK, vrs, nvr, PMD_GET_STATES);
}

fmi3Status fmi3SetClock(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, const fmi3Clock values[])
{
    (void)values;
    return no_such_type(c, "fmi3SetClock", PMD_FMI3_CLOCK, vrs, nvr, PMD_SET_STATES);
}

/* ---- co-simulation ---- */

fmi3Status fmi3DoStep(fmi3Instance c, fmi3Float64 currentCommunicationPoint, fmi3Float64 communicationStepSize,
                      fmi3Boolean noSetFMUStatePriorToCurrentPoint, fmi3Boolean *eventHandlingNeeded,
                      fmi3Boolean *terminateSimulation, fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime)
{
    PmdModel *inst = begin(c, "fmi3DoStep", PMD_STEP_MODE);
    PmdStatus status;
    (void)noSetFMUStatePriorToCurrentPoint;
    if (!inst)
        return fmi3Error;
    if (!eventHandlingNeeded || !terminateSimulation || !earlyReturn || !lastSuccessfulTime) {
        pmd_model_error(inst, "fmi3DoStep: an output argument is NULL");
        return fmi3Error;
    }
    status = pmd_model_do_step(inst, "fmi3DoStep", currentCommunicationPoint, communicationStepSize);
    *eventHandlingNeeded = fmi3False;
    *terminateSimulation = fmi3False;
    *earlyReturn = fmi3False;
    *lastSuccessfulTime = pmd_model3_last_successful_time(inst, status, currentCommunicationPoint);
    return status_of[status];
}

/* ---- FMU state ---- */

fmi3Status fmi3GetFMUState(fmi3Instance c, fmi3FMUState *state)
{
    CALL_MODEL(fmi3GetFMUState, PMD_ANY_STATE, pmd_model_fmu_state_get(inst, fn, state));
}

fmi3Status fmi3SetFMUState(fmi3Instance c, fmi3FMUState state)
{
    CALL_MODEL(fmi3SetFMUState, PMD_ANY_STATE, pmd_model_fmu_state_set(inst, fn, state));
}

fmi3Status fmi3FreeFMUState(fmi3Instance c, fmi3FMUState *state)
{
    CALL_MODEL(fmi3FreeFMUState, PMD_ANY_STATE, pmd_model_fmu_state_free(inst, fn, state));
}

fmi3Status fmi3SerializedFMUStateSize(fmi3Instance c, fmi3FMUState state, size_t *size)
{
    CALL_MODEL(fmi3SerializedFMUStateSize, PMD_ANY_STATE, pmd_model_fmu_state_size(inst, fn, state, size));
}

fmi3Status fmi3SerializeFMUState(fmi3Instance c, fmi3FMUState state, fmi3Byte serializedState[], size_t size)
{
    CALL_MODEL(fmi3SerializeFMUState, PMD_ANY_STATE,
               pmd_model_fmu_state_serialize(inst, fn, state, serializedState, size));
}

fmi3Status fmi3DeserializeFMUState(fmi3Instance c, const fmi3Byte serializedState[], size_t size,
                                   fmi3FMUState *state)
{
    CALL_MODEL(fmi3DeserializeFMUState, PMD_ANY_STATE,
               pmd_model_fmu_state_deserialize(inst, fn, serializedState, size, state));
}
