/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 2.0 Co-Simulation, written once for both FMUs over the model API
 * (model.h: the chip's fmu_src/fmi/model.c, the plant's plant_fmu.c). Every
 * function checks its component, its pointers and the state it is called in,
 * and answers a bad call with fmi2Error and a log message naming the function,
 * the value and the reason. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2.h"
#include "token.h"

/* The environment's callbacks live beside the model (the fuzzers read inst, first). */
typedef struct {
    PmdModel *inst;
    fmi2CallbackFunctions functions;
} Component;

static const fmi2Status status_of[] = {fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal};

/* The logger's message is a printf format: a '%' goes out as "%%", and no
 * variadic arguments are passed (a logger written in another language often
 * cannot read them). */
static void log_escaped(const fmi2CallbackFunctions *functions, const char *instanceName, fmi2Status status,
                        const char *category, const char *message)
{
    char escaped[16384];
    size_t i = 0;
    for (; *message && i + 2 < sizeof escaped; message++) {
        if (*message == '%')
            escaped[i++] = '%';
        escaped[i++] = *message;
    }
    escaped[i] = '\0';
    functions->logger(functions->componentEnvironment, instanceName, status, category, escaped);
}

static void log_to_environment(void *environment, const char *instanceName, PmdStatus status, const char *category,
                               const char *message)
{
    log_escaped(&((const Component *)environment)->functions, instanceName, status_of[status], category, message);
}

PmdModel *pmd_fmi2_begin(fmi2Component c, const char *fn, unsigned states)
{
    PmdModel *m = c ? ((Component *)c)->inst : NULL;
    if (m && !(pmd_model_fmi_state(m) & states)) {
        pmd_model_error(m, "%s: not allowed in %s", fn, pmd_model_state_name(pmd_model_fmi_state(m)));
        return NULL;
    }
    return m;
}

int pmd_fmi2_arrays_given(const PmdModel *m, const char *fn, size_t n, const void *a, const void *b)
{
    if (n > 0 && (!a || !b)) {
        pmd_model_error(m, "%s: %zu values but an array is NULL", fn, n);
        return 0;
    }
    return 1;
}

#define begin pmd_fmi2_begin
#define arrays_given pmd_fmi2_arrays_given

fmi2Status pmd_fmi2_unsupported(fmi2Component c, const char *fn, const char *why)
{
    PmdModel *m = begin(c, fn, PMD_ANY_STATE);
    if (m)
        pmd_model_error(m, "%s: not supported: %s", fn, why);
    return fmi2Error;
}

/* The body of a function that hands the call to the model: fn is F's name,
 * inst the model if F is legal in the states (else fmi2Error, logged). */
#define CALL_MODEL(F, states, call)                                                                  \
    do {                                                                                             \
        static const char fn[] = #F;                                                                 \
        PmdModel *inst = begin(c, fn, states);                                                       \
        return inst ? status_of[call] : fmi2Error;                                                   \
    } while (0)

/* ---- inquiry, logging, life cycle ---- */

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[])
{
    CALL_MODEL(fmi2SetDebugLogging, PMD_ANY_STATE,
               pmd_model_set_debug_logging(inst, fn, loggingOn, nCategories, categories));
}

/* The resources folder of fmuResourceLocation, a file URI (RFC 8089; FMI 2.0.4
 * section 2.1.6: "file:///C:/temp/MyFMU/resources", older importers
 * "file:/C:/..."): percent-decoded, ending in '/'. NULL with why in *why if
 * it is none, not a file URI, on another host, or not decodable. */
static char *resources_of(const char *uri, const char **why)
{
    const char *p = uri, *end;
    char *folder, *out;
    if (!uri || !*uri)
        return *why = "the importer gave no fmuResourceLocation", NULL;
    if (strncmp(p, "file:", 5) != 0 && strncmp(p, "FILE:", 5) != 0)
        return *why = "fmuResourceLocation is not a file: URI", NULL;
    p += 5;
    if (p[0] == '/' && p[1] == '/') {             /* an authority: empty or localhost is this machine */
        p += 2;
        end = strchr(p, '/');
        if (!end)
            return *why = "fmuResourceLocation names no folder", NULL;
        if (end != p && !(end - p == 9 && strncmp(p, "localhost", 9) == 0))
            return *why = "fmuResourceLocation names another host", NULL;
        p = end;
    }
    if (*p != '/')
        return *why = "fmuResourceLocation's path is not absolute", NULL;
#ifdef _WIN32
    if (((p[1] >= 'A' && p[1] <= 'Z') || (p[1] >= 'a' && p[1] <= 'z')) && (p[2] == ':' || p[2] == '|'))
        p++;                                       /* /C:/x is C:/x */
#endif
    if (!(folder = out = (char *)malloc(strlen(p) + 2)))
        return *why = "out of host memory", NULL;
    for (; *p && *p != '?' && *p != '#'; p++) {
        if (*p == '%') {
            static const char hex[] = "0123456789abcdef0123456789ABCDEF";
            const char *hi = p[1] ? strchr(hex, p[1]) : NULL, *lo = hi && p[2] ? strchr(hex, p[2]) : NULL;
            int byte = lo ? (int)((hi - hex) % 16 * 16 + (lo - hex) % 16) : 0;
            if (!byte) {                          /* a bad escape, or %00, which no path holds */
                free(folder);
                return *why = "fmuResourceLocation has a bad percent-encoding", NULL;
            }
            *out++ = (char)byte;
            p += 2;
        } else {
            *out++ = *p;
        }
    }
    if (out[-1] != '/')
        *out++ = '/';
    *out = '\0';
    return folder;
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions *functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn)
{
    Component *comp;
    const char *noResources = NULL;
    char *resources, message[1024];
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
    /* the resources folder first: a packed FMU's token is there (token.h) */
    resources = resources_of(fmuResourceLocation, &noResources);
    if (!pmd_token_accepted("fmi2Instantiate", "GUID", fmuGUID, resources, noResources, message, sizeof message)) {
        log_escaped(functions, instanceName, fmi2Error, "errors", message);  /* it quotes the importer's GUID */
        free(resources);
        return NULL;
    }
    if (!(comp = (Component *)calloc(1, sizeof *comp))) {
        free(resources);
        return NULL;
    }
    comp->functions = *functions;
    if (!(comp->inst = pmd_model_new(instanceName, log_to_environment, comp))) {
        free(comp);
        free(resources);
        return NULL;
    }
    pmd_model_set_debug_logging(comp->inst, "fmi2Instantiate", loggingOn, 0, NULL);
    if (pmd_model_resources(comp->inst, "fmi2Instantiate", resources, noResources) != PMD_OK) {
        fmi2FreeInstance(comp);
        return NULL;
    }
    return comp;
}

void fmi2FreeInstance(fmi2Component c)
{
    if (!c)
        return;
    pmd_model_free(((Component *)c)->inst);
    free(c);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    (void)toleranceDefined; (void)tolerance; (void)stopTimeDefined; (void)stopTime;
    CALL_MODEL(fmi2SetupExperiment, PMD_INSTANTIATED, pmd_model_setup_experiment(inst, fn, startTime));
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    CALL_MODEL(fmi2EnterInitializationMode, PMD_INSTANTIATED,
               pmd_model_enter_initialization(inst, fn, pmd_model_time(inst)));
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    CALL_MODEL(fmi2ExitInitializationMode, PMD_INITIALIZATION_MODE, pmd_model_exit_initialization(inst, fn));
}

fmi2Status fmi2Terminate(fmi2Component c)
{
    PmdModel *inst = begin(c, "fmi2Terminate", PMD_INITIALIZATION_MODE | PMD_STEP_MODE);
    if (!inst)
        return fmi2Error;
    pmd_model_terminate(inst);
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c)
{
    PmdModel *inst = begin(c, "fmi2Reset", PMD_ANY_STATE);
    if (!inst)
        return fmi2Error;
    pmd_model_reset(inst);
    return fmi2OK;
}

/* ---- variables ---- */

/* A get checks every value reference before the model commits (the chip:
 * pending port writes executed first, a host reads its replies at the time it
 * wrote the batch, CONTRACT 2.2): a get refused for a value reference executes
 * nothing and returns no value. */
#define GET_FUNCTION(fn, T, get, type)                                                            \
    fmi2Status fn(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, T value[])        \
    {                                                                                            \
        PmdModel *inst = begin(c, #fn, PMD_GET_STATES);                                          \
        size_t i;                                                                                \
        if (!inst || !arrays_given(inst, #fn, nvr, vr, value))                                   \
            return fmi2Error;                                                                    \
        for (i = 0; i < nvr; i++)                                                                \
            if (!pmd_model2_given(inst, #fn, vr[i], type))                                       \
                return fmi2Error;                                                                \
        pmd_model_commit(inst);                                                                  \
        for (i = 0; i < nvr; i++)                                                                \
            if (get(inst, #fn, vr[i], &value[i]) != PMD_OK)                                      \
                return fmi2Error;                                                                \
        return fmi2OK;                                                                           \
    }

GET_FUNCTION(fmi2GetReal, fmi2Real, pmd_model2_get_real, PMD_FMI2_REAL)
GET_FUNCTION(fmi2GetInteger, fmi2Integer, pmd_model2_get_integer, PMD_FMI2_INTEGER)
GET_FUNCTION(fmi2GetBoolean, fmi2Boolean, pmd_model2_get_boolean, PMD_FMI2_BOOLEAN)

/* Sets are all or nothing: every value is checked, then what they ask for
 * together, before any is applied (model.h). */
#define SET_FUNCTION(fn, T, set)                                                                  \
    fmi2Status fn(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const T value[])  \
    {                                                                                            \
        PmdModel *inst = begin(c, #fn, PMD_SET_STATES);                                          \
        size_t i;                                                                                \
        if (!inst || !arrays_given(inst, #fn, nvr, vr, value))                                   \
            return fmi2Error;                                                                    \
        pmd_model_set_begin(inst);                                                               \
        for (i = 0; i < nvr; i++)                                                                \
            if (set(inst, #fn, vr[i], value[i], 0) != PMD_OK)                                    \
                return fmi2Error;                                                                \
        if (pmd_model_set_check(inst, #fn) != PMD_OK)                                            \
            return fmi2Error;                                                                    \
        for (i = 0; i < nvr; i++)                                                                \
            set(inst, #fn, vr[i], value[i], 1);                                                  \
        return fmi2OK;                                                                           \
    }

SET_FUNCTION(fmi2SetReal, fmi2Real, pmd_model2_set_real)
SET_FUNCTION(fmi2SetBoolean, fmi2Boolean, pmd_model2_set_boolean)

/* SET_FUNCTION's two passes (check, then apply), as many values a pass as the
 * model takes at once (the chip: a run of memory.data as one block). */
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[])
{
    static const char fn[] = "fmi2SetInteger";
    PmdModel *inst = begin(c, fn, PMD_SET_STATES);
    size_t i, taken;
    if (!inst || !arrays_given(inst, fn, nvr, vr, value))
        return fmi2Error;
    pmd_model_set_begin(inst);
    for (i = 0; i < nvr; i += taken)
        if (pmd_model2_set_integers(inst, fn, vr + i, nvr - i, value + i, 0, &taken) != PMD_OK)
            return fmi2Error;
    if (pmd_model_set_check(inst, fn) != PMD_OK)
        return fmi2Error;
    for (i = 0; i < nvr; i += taken)
        pmd_model2_set_integers(inst, fn, vr + i, nvr - i, value + i, 1, &taken);
    return fmi2OK;
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[])
{
    PmdModel *inst = begin(c, "fmi2GetString", PMD_GET_STATES);
    size_t i;
    if (!inst || !arrays_given(inst, "fmi2GetString", nvr, vr, value))
        return fmi2Error;
    for (i = 0; i < nvr; i++)
        if (pmd_model_get_string(inst, "fmi2GetString", vr[i], &value[i]) != PMD_OK)
            return fmi2Error;
    return fmi2OK;
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[])
{
    PmdModel *inst = begin(c, "fmi2SetString", PMD_SET_STATES);
    size_t i;
    int apply;
    if (!inst || !arrays_given(inst, "fmi2SetString", nvr, vr, value))
        return fmi2Error;
    pmd_model_set_begin(inst);
    for (apply = 0; apply <= 1; apply++)
        for (i = 0; i < nvr; i++)
            if (pmd_model_set_string(inst, "fmi2SetString", vr[i], value[i], apply) != PMD_OK)
                return fmi2Error;
    return fmi2OK;
}

/* ---- co-simulation ---- */

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    CALL_MODEL(fmi2DoStep, PMD_STEP_MODE,
               pmd_model_do_step(inst, fn, currentCommunicationPoint, communicationStepSize));
}

/* ---- FMU state ---- */

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *state)
{
    CALL_MODEL(fmi2GetFMUstate, PMD_ANY_STATE, pmd_model_fmu_state_get(inst, fn, state));
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate state)
{
    CALL_MODEL(fmi2SetFMUstate, PMD_ANY_STATE, pmd_model_fmu_state_set(inst, fn, state));
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *state)
{
    CALL_MODEL(fmi2FreeFMUstate, PMD_ANY_STATE, pmd_model_fmu_state_free(inst, fn, state));
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate state, size_t *size)
{
    CALL_MODEL(fmi2SerializedFMUstateSize, PMD_ANY_STATE, pmd_model_fmu_state_size(inst, fn, state, size));
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate state, fmi2Byte serializedState[], size_t size)
{
    CALL_MODEL(fmi2SerializeFMUstate, PMD_ANY_STATE,
               pmd_model_fmu_state_serialize(inst, fn, state, (unsigned char *)serializedState, size));
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[], size_t size,
                                   fmi2FMUstate *state)
{
    CALL_MODEL(fmi2DeSerializeFMUstate, PMD_ANY_STATE,
               pmd_model_fmu_state_deserialize(inst, fn, (const unsigned char *)serializedState, size, state));
}
