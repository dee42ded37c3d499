/* FMI 3.0 Co-Simulation over the instance (instance.h): the same chip, names,
 * value references and timing as FMI 2, with native types and the host and
 * memory ports as arrays (variables3.h). No event mode, no early return.
 * Every function checks its instance, its pointers and the state it is called
 * in, and answers a bad call with fmi3Error and a log message. */
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"
#include "fmi3_not_provided.h"
#include "instance.h"
#include "state.h"
#include "variables3.h"

typedef struct {
    PmdInstance *inst;
    fmi3InstanceEnvironment environment;
    fmi3LogMessageCallback logMessage;
} Component;

static const fmi3Status status_of[] = {fmi3OK, fmi3Warning, fmi3Discard, fmi3Error, fmi3Fatal};
/* by PmdType3 (variables3.h): the FMI 3 type names the functions' messages use */
static const char *const type_names[] = {
    [PMD3_FLOAT64] = "Float64", [PMD3_INT32] = "Int32", [PMD3_UINT32] = "UInt32", [PMD3_UINT16] = "UInt16",
    [PMD3_INT16] = "Int16", [PMD3_BOOLEAN] = "Boolean", [PMD3_STRING] = "String", [PMD3_BINARY] = "Binary"};

static void log_to_environment(void *environment, const char *instanceName, PmdStatus status, const char *category,
                               const char *message)
{
    const Component *comp = (const Component *)environment;
    (void)instanceName;
    if (comp->logMessage)
        comp->logMessage(comp->environment, status_of[status], category, message);
}

static PmdInstance *begin(fmi3Instance c, const char *fn, unsigned states)
{
    return c ? pmd_begin(((Component *)c)->inst, fn, states) : NULL;
}

/* The refusal of every function this FMU does not provide (fmi3_not_provided.c). */
fmi3Status pmd_fmi3_unsupported(fmi3Instance c, const char *fn, const char *why)
{
    PmdInstance *inst = begin(c, fn, PMD_ANY_STATE);
    if (inst)
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: not supported: %s", fn, why);
    return fmi3Error;
}

/* ---- inquiry, logging, life cycle ---- */

const char *fmi3GetVersion(void) { return fmi3Version; }

fmi3Status fmi3SetDebugLogging(fmi3Instance c, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[])
{
    PmdInstance *inst = begin(c, "fmi3SetDebugLogging", PMD_ANY_STATE);
    return inst ? status_of[pmd_set_debug_logging(inst, "fmi3SetDebugLogging", loggingOn, nCategories, categories)]
                : fmi3Error;
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
    (void)visible; (void)earlyReturnAllowed; (void)requiredIntermediateVariables;
    (void)nRequiredIntermediateVariables; (void)intermediateUpdate;
    if (!instanceName) {
        pmd_fmi3_refuse_instance(instanceEnvironment, logMessage,
                                 "fmi3InstantiateCoSimulation: instanceName is NULL");
        return NULL;
    }
    if (!instantiationToken || strcmp(instantiationToken, PMD_INSTANTIATION_TOKEN) != 0) {
        pmd_fmi3_refuse_instance(instanceEnvironment, logMessage, "fmi3InstantiateCoSimulation: the "
                                 "instantiation token does not match this binary's " PMD_INSTANTIATION_TOKEN);
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
    comp->inst = pmd_instance_new(instanceName, log_to_environment, comp);
    if (!comp->inst) {
        free(comp);
        return NULL;
    }
    pmd_set_debug_logging(comp->inst, "fmi3InstantiateCoSimulation", loggingOn, 0, NULL);
    if (pmd_instance_resources(comp->inst, "fmi3InstantiateCoSimulation", resources_of(resourcePath),
                               resourcePath ? "the importer gave an empty resourcePath"
                                            : "the importer gave no resourcePath (NULL)") != PMD_OK) {
        fmi3FreeInstance(comp);
        return NULL;
    }
    return comp;
}

void fmi3FreeInstance(fmi3Instance c)
{
    if (!c)
        return;
    pmd_instance_free(((Component *)c)->inst);
    free(c);
}

fmi3Status fmi3EnterInitializationMode(fmi3Instance c, fmi3Boolean toleranceDefined, fmi3Float64 tolerance,
                                       fmi3Float64 startTime, fmi3Boolean stopTimeDefined, fmi3Float64 stopTime)
{
    PmdInstance *inst = begin(c, "fmi3EnterInitializationMode", PMD_INSTANTIATED);
    (void)toleranceDefined; (void)tolerance; (void)stopTimeDefined; (void)stopTime;
    return inst ? status_of[pmd_enter_initialization(inst, "fmi3EnterInitializationMode", startTime)] : fmi3Error;
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance c)
{
    PmdInstance *inst = begin(c, "fmi3ExitInitializationMode", PMD_INITIALIZATION_MODE);
    return inst ? status_of[pmd_exit_initialization(inst, "fmi3ExitInitializationMode")] : fmi3Error;
}

fmi3Status fmi3Terminate(fmi3Instance c)
{
    PmdInstance *inst = begin(c, "fmi3Terminate", PMD_INITIALIZATION_MODE | PMD_STEP_MODE);
    if (!inst)
        return fmi3Error;
    inst->s.state = PMD_TERMINATED;
    return fmi3OK;
}

fmi3Status fmi3Reset(fmi3Instance c)
{
    PmdInstance *inst = begin(c, "fmi3Reset", PMD_ANY_STATE);
    if (!inst)
        return fmi3Error;
    pmd_instance_reset(inst);
    return fmi3OK;
}

/* ---- variables ---- */

static const PmdVariable3 *lookup(PmdInstance *inst, const char *fn, fmi3ValueReference vr, const char *type)
{
    const PmdVariable3 *v;
    if (vr > PMD_VR3_MAX || pmd_variable3_of_vr[vr] < 0) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: no variable has value reference %u", fn, vr);
        return NULL;
    }
    v = &pmd_variables3[pmd_variable3_of_vr[vr]];
    /* the typed getters and setters pass type_names[type] itself: the pointers compare equal, no strcmp
     * per value reference (a recording master gets every cycle); other callers' names compare by text */
    if (type_names[v->type] != type && strcmp(type_names[v->type], type) != 0) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: value reference %u (%s) is a %s, not %s", fn, vr,
                         v->name, type_names[v->type], type);
        return NULL;
    }
    return v;
}

/* Values are counted over all elements of all the value references (an
 * array contributes all its elements). */
static int count_matches(PmdInstance *inst, const char *fn, const char *type, const fmi3ValueReference vrs[],
                         size_t nvr, size_t nValues)
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

/* A type get_element or set_element has no case for (String and Binary have
 * functions of their own): a bug of this file, refused rather than read or
 * written as another type. */
static PmdStatus unhandled_type(PmdInstance *inst, const char *fn, PmdType3 type, unsigned vr)
{
    pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: value reference %u: this FMU has no %s element access",
                     fn, vr, type_names[type]);
    return PMD_ERROR;
}

/* Element e of an FMI 3 variable is the FMI 2 scalar with value reference vr + e. */
static PmdStatus get_element(PmdInstance *inst, const char *fn, PmdType3 type, unsigned vr, void *values, size_t k)
{
    double d;
    int32_t n = 0;
    int b;
    PmdStatus s;
    switch (type) {
    case PMD3_FLOAT64:
        s = pmd_get_real(inst, fn, vr, &d);
        ((fmi3Float64 *)values)[k] = d;
        return s;
    case PMD3_BOOLEAN:
        s = pmd_get_boolean(inst, fn, vr, &b);
        ((fmi3Boolean *)values)[k] = b != 0;
        return s;
    case PMD3_INT32:
        s = pmd_get_integer(inst, fn, vr, &n);
        ((fmi3Int32 *)values)[k] = n;
        return s;
    case PMD3_UINT32:
        s = pmd_get_integer(inst, fn, vr, &n);
        ((fmi3UInt32 *)values)[k] = (uint32_t)n;          /* the register's 32 bits */
        return s;
    case PMD3_UINT16:
        s = pmd_get_integer(inst, fn, vr, &n);
        ((fmi3UInt16 *)values)[k] = (uint16_t)((uint32_t)n & 0xFFFFu);
        return s;
    case PMD3_INT16:                                    /* a signed 16-bit register: its value fits */
        s = pmd_get_integer(inst, fn, vr, &n);
        ((fmi3Int16 *)values)[k] = (int16_t)n;
        return s;
    default:
        return unhandled_type(inst, fn, type, vr);
    }
}

static PmdStatus set_element(PmdInstance *inst, const char *fn, PmdType3 type, unsigned vr, const void *values,
                             size_t k, int apply)
{
    switch (type) {
    case PMD3_FLOAT64: return pmd_set_real(inst, fn, vr, ((const fmi3Float64 *)values)[k], apply);
    case PMD3_BOOLEAN: return pmd_set_boolean(inst, fn, vr, ((const fmi3Boolean *)values)[k], apply);
    case PMD3_INT32: return pmd_set_integer(inst, fn, vr, ((const fmi3Int32 *)values)[k], apply);
    case PMD3_UINT32: return pmd_set_integer(inst, fn, vr, ((const fmi3UInt32 *)values)[k], apply);
    case PMD3_UINT16: return pmd_set_integer(inst, fn, vr, ((const fmi3UInt16 *)values)[k], apply);
    case PMD3_INT16: return pmd_set_integer(inst, fn, vr, ((const fmi3Int16 *)values)[k], apply);
    default: return unhandled_type(inst, fn, type, vr);
    }
}

/* Gets see pending port writes executed first (CONTRACT 2.2). */
static fmi3Status get_values(fmi3Instance c, const char *fn, PmdType3 type, const fmi3ValueReference vrs[],
                             size_t nvr, void *values, size_t nValues)
{
    PmdInstance *inst = begin(c, fn, PMD_GET_STATES);
    size_t i, k = 0;
    unsigned e;
    if (!inst || !pmd_arrays_given(inst, fn, nvr, vrs, values) ||
        !count_matches(inst, fn, type_names[type], vrs, nvr, nValues))
        return fmi3Error;
    if (inst->s.state != PMD_TERMINATED)
        pmd_commit_ports(inst);
    for (i = 0; i < nvr; i++) {
        const PmdVariable3 *v = &pmd_variables3[pmd_variable3_of_vr[vrs[i]]];
        for (e = 0; e < v->count; e++)
            if (get_element(inst, fn, type, v->vr + e, values, k++) != PMD_OK)
                return fmi3Error;
    }
    return fmi3OK;
}

/* Sets are all or nothing: every value is checked before any is applied. The
 * memory.data array (a strobe's words, Chip.write_memory) is set as one block
 * (pmd_set_memory_data: the same checks, messages and order as element by
 * element, without a lookup and two switches per word and pass). */
static fmi3Status set_values(fmi3Instance c, const char *fn, PmdType3 type, const fmi3ValueReference vrs[],
                             size_t nvr, const void *values, size_t nValues)
{
    PmdInstance *inst = begin(c, fn, PMD_SET_STATES);
    size_t i, k;
    unsigned e;
    int apply;
    if (!inst || !pmd_arrays_given(inst, fn, nvr, vrs, values) ||
        !count_matches(inst, fn, type_names[type], vrs, nvr, nValues))
        return fmi3Error;
    pmd_set_begin(inst);
    for (apply = 0; apply <= 1; apply++) {
        if (apply && pmd_set_check(inst, fn) != PMD_OK)
            return fmi3Error;
        for (i = 0, k = 0; i < nvr; i++) {
            const PmdVariable3 *v = &pmd_variables3[pmd_variable3_of_vr[vrs[i]]];
            if (type == PMD3_UINT32 && v->count > 1 && pmd_memory_data_span(v->vr, v->count) == v->count) {
                if (pmd_set_memory_data(inst, fn, v->vr, (const fmi3UInt32 *)values + k, 0, v->count, apply) !=
                    PMD_OK)
                    return fmi3Error;
                k += v->count;
                continue;
            }
            for (e = 0; e < v->count; e++)
                if (set_element(inst, fn, type, v->vr + e, values, k++, apply) != PMD_OK)
                    return fmi3Error;
        }
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

GETSET(fmi3Float64, Float64, PMD3_FLOAT64)
GETSET(fmi3Int32, Int32, PMD3_INT32)
GETSET(fmi3UInt32, UInt32, PMD3_UINT32)
GETSET(fmi3UInt16, UInt16, PMD3_UINT16)
GETSET(fmi3Int16, Int16, PMD3_INT16)
GETSET(fmi3Boolean, Boolean, PMD3_BOOLEAN)

/* Types this FMU has no variables of: any value reference is an error. */
static fmi3Status no_such_type(fmi3Instance c, const char *fn, const char *type, const fmi3ValueReference vrs[],
                               size_t nvr, unsigned states)
{
    PmdInstance *inst = begin(c, fn, states);
    if (!inst || !pmd_arrays_given(inst, fn, nvr, vrs, vrs))
        return fmi3Error;
    return nvr == 0 || lookup(inst, fn, vrs[0], type) ? fmi3OK : fmi3Error;
}

#define NO_SUCH_TYPE(T, Type)                                                                               \
    fmi3Status fmi3Get##Type(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, T values[],        \
                             size_t nValues)                                                                \
    {                                                                                                       \
        (void)values; (void)nValues;                                                                        \
        return no_such_type(c, "fmi3Get" #Type, #Type, vrs, nvr, PMD_GET_STATES);                           \
    }                                                                                                       \
    fmi3Status fmi3Set##Type(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, const T values[],  \
                             size_t nValues)                                                                \
    {                                                                                                       \
        (void)values; (void)nValues;                                                                        \
        return no_such_type(c, "fmi3Set" #Type, #Type, vrs, nvr, PMD_SET_STATES);                           \
    }

NO_SUCH_TYPE(fmi3Float32, Float32)
NO_SUCH_TYPE(fmi3Int8, Int8)
NO_SUCH_TYPE(fmi3UInt8, UInt8)
NO_SUCH_TYPE(fmi3Int64, Int64)
NO_SUCH_TYPE(fmi3UInt64, UInt64)

fmi3Status fmi3GetString(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, fmi3String values[],
                         size_t nValues)
{
    PmdInstance *inst = begin(c, "fmi3GetString", PMD_GET_STATES);
    size_t i;
    if (!inst || !pmd_arrays_given(inst, "fmi3GetString", nvr, vrs, values) ||
        !count_matches(inst, "fmi3GetString", "String", vrs, nvr, nValues))
        return fmi3Error;
    for (i = 0; i < nvr; i++)
        if (pmd_get_string(inst, "fmi3GetString", vrs[i], &values[i]) != PMD_OK)
            return fmi3Error;
    return fmi3OK;
}

fmi3Status fmi3SetString(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, const fmi3String values[],
                         size_t nValues)
{
    PmdInstance *inst = begin(c, "fmi3SetString", PMD_SET_STATES);
    size_t i;
    int apply;
    if (!inst || !pmd_arrays_given(inst, "fmi3SetString", nvr, vrs, values) ||
        !count_matches(inst, "fmi3SetString", "String", vrs, nvr, nValues))
        return fmi3Error;
    for (apply = 0; apply <= 1; apply++)
        for (i = 0; i < nvr; i++)
            if (pmd_set_string(inst, "fmi3SetString", vrs[i], values[i], apply) != PMD_OK)
                return fmi3Error;
    return fmi3OK;
}

fmi3Status fmi3GetBinary(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, size_t valueSizes[],
                         fmi3Binary values[], size_t nValues)
{
    PmdInstance *inst = begin(c, "fmi3GetBinary", PMD_GET_STATES);
    size_t i;
    if (!inst || !pmd_arrays_given(inst, "fmi3GetBinary", nvr, vrs, values) ||
        !pmd_arrays_given(inst, "fmi3GetBinary", nvr, valueSizes, valueSizes) ||
        !count_matches(inst, "fmi3GetBinary", "Binary", vrs, nvr, nValues))
        return fmi3Error;
    for (i = 0; i < nvr; i++)
        if (pmd_get_binary(inst, "fmi3GetBinary", vrs[i], &values[i], &valueSizes[i]) != PMD_OK)
            return fmi3Error;
    return fmi3OK;
}

fmi3Status fmi3SetBinary(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, const size_t valueSizes[],
                         const fmi3Binary values[], size_t nValues)
{
    PmdInstance *inst = begin(c, "fmi3SetBinary", PMD_SET_STATES);
    (void)valueSizes; (void)values;
    if (!inst || !pmd_arrays_given(inst, "fmi3SetBinary", nvr, vrs, vrs) ||
        !count_matches(inst, "fmi3SetBinary", "Binary", vrs, nvr, nValues))
        return fmi3Error;
    if (nvr > 0) {                                  /* record.data, the only Binary, is an output */
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "fmi3SetBinary: value reference %u (%s) is an output and "
                         "cannot be set", vrs[0], pmd_variables3[pmd_variable3_of_vr[vrs[0]]].name);
        return fmi3Error;
    }
    return fmi3OK;
}

fmi3Status fmi3GetClock(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, fmi3Clock values[])
{
    (void)values;
    return no_such_type(c, "fmi3GetClock", "Clock", vrs, nvr, PMD_GET_STATES);
}

fmi3Status fmi3SetClock(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, const fmi3Clock values[])
{
    (void)values;
    return no_such_type(c, "fmi3SetClock", "Clock", vrs, nvr, PMD_SET_STATES);
}

/* ---- co-simulation ---- */

fmi3Status fmi3DoStep(fmi3Instance c, fmi3Float64 currentCommunicationPoint, fmi3Float64 communicationStepSize,
                      fmi3Boolean noSetFMUStatePriorToCurrentPoint, fmi3Boolean *eventHandlingNeeded,
                      fmi3Boolean *terminateSimulation, fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime)
{
    PmdInstance *inst = begin(c, "fmi3DoStep", PMD_STEP_MODE);
    PmdStatus status;
    (void)noSetFMUStatePriorToCurrentPoint;
    if (!inst)
        return fmi3Error;
    if (!eventHandlingNeeded || !terminateSimulation || !earlyReturn || !lastSuccessfulTime) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "fmi3DoStep: an output argument is NULL");
        return fmi3Error;
    }
    status = pmd_do_step(inst, "fmi3DoStep", currentCommunicationPoint, communicationStepSize);
    *eventHandlingNeeded = fmi3False;
    *terminateSimulation = fmi3False;
    *earlyReturn = fmi3False;
    *lastSuccessfulTime = status <= PMD_WARNING ? inst->s.time : currentCommunicationPoint;  /* Warning: it ran */
    return status_of[status];
}

/* ---- FMU state (state.c) ---- */

fmi3Status fmi3GetFMUState(fmi3Instance c, fmi3FMUState *state)
{
    PmdInstance *inst = begin(c, "fmi3GetFMUState", PMD_ANY_STATE);
    return inst ? status_of[pmd_fmu_state_get(inst, "fmi3GetFMUState", state)] : fmi3Error;
}

fmi3Status fmi3SetFMUState(fmi3Instance c, fmi3FMUState state)
{
    PmdInstance *inst = begin(c, "fmi3SetFMUState", PMD_ANY_STATE);
    return inst ? status_of[pmd_fmu_state_set(inst, "fmi3SetFMUState", state)] : fmi3Error;
}

fmi3Status fmi3FreeFMUState(fmi3Instance c, fmi3FMUState *state)
{
    PmdInstance *inst = begin(c, "fmi3FreeFMUState", PMD_ANY_STATE);
    return inst ? status_of[pmd_fmu_state_free(inst, "fmi3FreeFMUState", state)] : fmi3Error;
}

fmi3Status fmi3SerializedFMUStateSize(fmi3Instance c, fmi3FMUState state, size_t *size)
{
    PmdInstance *inst = begin(c, "fmi3SerializedFMUStateSize", PMD_ANY_STATE);
    return inst ? status_of[pmd_fmu_state_size(inst, "fmi3SerializedFMUStateSize", state, size)] : fmi3Error;
}

fmi3Status fmi3SerializeFMUState(fmi3Instance c, fmi3FMUState state, fmi3Byte serializedState[], size_t size)
{
    PmdInstance *inst = begin(c, "fmi3SerializeFMUState", PMD_ANY_STATE);
    return inst ? status_of[pmd_fmu_state_serialize(inst, "fmi3SerializeFMUState", state, serializedState, size)]
                : fmi3Error;
}

fmi3Status fmi3DeserializeFMUState(fmi3Instance c, const fmi3Byte serializedState[], size_t size,
                                   fmi3FMUState *state)
{
    PmdInstance *inst = begin(c, "fmi3DeserializeFMUState", PMD_ANY_STATE);
    return inst ? status_of[pmd_fmu_state_deserialize(inst, "fmi3DeserializeFMUState", serializedState, size,
                                                      state)]
                : fmi3Error;
}
