/* SPDX-License-Identifier: BSD-2-Clause */
/* What an FMU's model provides to the FMI shells (fmi2.c, fmi3.c), which are
 * written once for both FMUs: the chip's model is fmu_src/fmi/ (model.c over
 * instance.h, model3.c for FMI 3's arrays), the plant's fmu_src/plant/plant_fmu.c.
 * The shells check the component, the pointers and the FMI state a call is
 * legal in, and map the FMI types; the model owns everything else: its
 * variables, its step, its FMU states and every message about them.
 *
 * fn names the FMI function in messages. FMI 2's values are plain C types;
 * FMI 3's arrays are of the FMI 3 types (fmi3PlatformTypes.h). */
#ifndef PMD_MODEL_H
#define PMD_MODEL_H

#include <stddef.h>
#include <stdint.h>

typedef enum { PMD_OK, PMD_WARNING, PMD_DISCARD, PMD_ERROR, PMD_FATAL } PmdStatus;

/* The FMI states, as bits so that a function can name the states it is legal in. */
typedef enum {
    PMD_INSTANTIATED = 1 << 0,
    PMD_INITIALIZATION_MODE = 1 << 1,
    PMD_STEP_MODE = 1 << 2,
    PMD_TERMINATED = 1 << 3
} PmdState;

#define PMD_ANY_STATE (PMD_INSTANTIATED | PMD_INITIALIZATION_MODE | PMD_STEP_MODE | PMD_TERMINATED)
#define PMD_GET_STATES (PMD_INITIALIZATION_MODE | PMD_STEP_MODE | PMD_TERMINATED)
#define PMD_SET_STATES (PMD_INSTANTIATED | PMD_INITIALIZATION_MODE | PMD_STEP_MODE)

/* How the model's messages reach the importer (the shell escapes and forwards them). */
typedef void (*PmdModelLogger)(void *environment, const char *instanceName, PmdStatus status, const char *category,
                               const char *message);

/* One instance of the model: the chip's PmdInstance (instance.h), the plant's PlantInstance (plant_fmu.h). */
typedef struct PmdModel PmdModel;

/* ---- life cycle ---- */

extern const char pmd_model_token[];          /* the instantiation token (FMI 2: the GUID) */
PmdModel *pmd_model_new(const char *instanceName, PmdModelLogger logger, void *environment);
/* The FMU's resources folder (allocated, taken over; NULL with why if the
 * importer named none that is a local folder). PMD_ERROR refuses the instantiation. */
PmdStatus pmd_model_resources(PmdModel *m, const char *fn, char *resources, const char *noResources);
void pmd_model_free(PmdModel *m);
void pmd_model_reset(PmdModel *m);
/* nCategories = 0: all categories; an unknown category is an error and changes nothing. */
PmdStatus pmd_model_set_debug_logging(PmdModel *m, const char *fn, int loggingOn, size_t nCategories,
                                      const char *const categories[]);
#ifdef __MINGW32__
#include <stdio.h> /* __MINGW_PRINTF_FORMAT */
#endif
/* An error of a call, logged whatever the debug logging (the shell's refusals). */
void pmd_model_error(const PmdModel *m, const char *format, ...)
#if defined(__MINGW32__) /* mingw-w64: the printf the build links (C99's with __USE_MINGW_ANSI_STDIO) */
    __attribute__((format(__MINGW_PRINTF_FORMAT, 2, 3)))
#elif defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

PmdState pmd_model_fmi_state(const PmdModel *m);
/* The state as the model's messages name it ("...: not allowed in <name>"). */
const char *pmd_model_state_name(PmdState state);
/* The current time: the last communication point, or the start time set so far. */
double pmd_model_time(const PmdModel *m);

/* FMI 2's SetupExperiment sets the start time, EnterInitializationMode(startTime) enters
 * initialization mode (FMI 2 passes pmd_model_time); Terminate leaves step mode for good. */
PmdStatus pmd_model_setup_experiment(PmdModel *m, const char *fn, double startTime);
PmdStatus pmd_model_enter_initialization(PmdModel *m, const char *fn, double startTime);
PmdStatus pmd_model_exit_initialization(PmdModel *m, const char *fn);
void pmd_model_terminate(PmdModel *m);
PmdStatus pmd_model_do_step(PmdModel *m, const char *fn, double t, double h);

/* ---- variables ----
 * A get checks every value reference first (..._given, which logs why not),
 * then lets the model bring its numeric outputs up to date (pmd_model_commit),
 * then reads them. A set is all or nothing: pmd_model_set_begin, every value's
 * set with apply = 0 (checks it and stages it), pmd_model_set_check (what the
 * staged values ask for together), then every set again with apply = 1. */
void pmd_model_commit(PmdModel *m);
void pmd_model_set_begin(PmdModel *m);
PmdStatus pmd_model_set_check(PmdModel *m, const char *fn);

/* FMI 2: one scalar at a time. */
typedef enum { PMD_FMI2_REAL, PMD_FMI2_INTEGER, PMD_FMI2_BOOLEAN } PmdFmi2Type;
int pmd_model2_given(PmdModel *m, const char *fn, unsigned vr, PmdFmi2Type type);
PmdStatus pmd_model2_get_real(PmdModel *m, const char *fn, unsigned vr, double *value);
PmdStatus pmd_model2_get_integer(PmdModel *m, const char *fn, unsigned vr, int32_t *value);
PmdStatus pmd_model2_get_boolean(PmdModel *m, const char *fn, unsigned vr, int *value);
PmdStatus pmd_model2_set_real(PmdModel *m, const char *fn, unsigned vr, double value, int apply);
PmdStatus pmd_model2_set_boolean(PmdModel *m, const char *fn, unsigned vr, int value, int apply);
/* Integers from vr[0] on, as many as the model takes at once (*taken >= 1: a block of an array's elements
 * is one pass), each checked (apply 0) or applied (apply 1) as pmd_model2_set_real's value is. */
PmdStatus pmd_model2_set_integers(PmdModel *m, const char *fn, const unsigned vr[], size_t n, const int32_t value[],
                                  int apply, size_t *taken);
/* Strings are neither committed before a get nor checked together before a set. */
PmdStatus pmd_model_get_string(PmdModel *m, const char *fn, unsigned vr, const char **value);
PmdStatus pmd_model_set_string(PmdModel *m, const char *fn, unsigned vr, const char *value, int apply);

/* FMI 3: a value reference holds one value or an array's elements, values[*k] on (*k advanced). */
typedef enum {
    PMD_FMI3_FLOAT32, PMD_FMI3_FLOAT64, PMD_FMI3_INT8, PMD_FMI3_UINT8, PMD_FMI3_INT16, PMD_FMI3_UINT16,
    PMD_FMI3_INT32, PMD_FMI3_UINT32, PMD_FMI3_INT64, PMD_FMI3_UINT64, PMD_FMI3_BOOLEAN, PMD_FMI3_STRING,
    PMD_FMI3_BINARY, PMD_FMI3_CLOCK
} PmdFmi3Type;
/* Whether the model has variables of this type; a call of a type it has none of is answered by
 * pmd_model3_no_such_type for its first value reference (logs why and returns PMD_ERROR). */
int pmd_model3_has(PmdFmi3Type type);
PmdStatus pmd_model3_no_such_type(PmdModel *m, const char *fn, PmdFmi3Type type, unsigned vr);
/* Whether the value references hold nValues values of the type together (logs why not). */
int pmd_model3_count(PmdModel *m, const char *fn, PmdFmi3Type type, const unsigned vrs[], size_t nvr,
                     size_t nValues);
int pmd_model3_given(PmdModel *m, const char *fn, unsigned vr, PmdFmi3Type type);
/* values: an array of the type's fmi3 C type (fmi3Float64, fmi3Int32, ...). */
PmdStatus pmd_model3_get(PmdModel *m, const char *fn, PmdFmi3Type type, unsigned vr, void *values, size_t *k);
PmdStatus pmd_model3_set(PmdModel *m, const char *fn, PmdFmi3Type type, unsigned vr, const void *values, size_t *k,
                         int apply);
PmdStatus pmd_model3_get_binary(PmdModel *m, const char *fn, unsigned vr, const unsigned char **value, size_t *size);
/* A set call of Binary values (the shell has checked vrs and their count only). */
PmdStatus pmd_model3_set_binaries(PmdModel *m, const char *fn, const unsigned vrs[], size_t nvr,
                                  const size_t sizes[], const unsigned char *const values[]);
/* fmi3DoStep's lastSuccessfulTime after a step from t that returned status. */
double pmd_model3_last_successful_time(const PmdModel *m, PmdStatus status, double t);

/* ---- FMU states: the objects of Get/Set/Free/Serialize/DeserializeFMUState ---- */
PmdStatus pmd_model_fmu_state_get(PmdModel *m, const char *fn, void **state);
PmdStatus pmd_model_fmu_state_set(PmdModel *m, const char *fn, const void *state);
PmdStatus pmd_model_fmu_state_free(PmdModel *m, const char *fn, void **state);
PmdStatus pmd_model_fmu_state_size(PmdModel *m, const char *fn, const void *state, size_t *size);
PmdStatus pmd_model_fmu_state_serialize(PmdModel *m, const char *fn, const void *state, unsigned char *bytes,
                                    size_t size);
PmdStatus pmd_model_fmu_state_deserialize(PmdModel *m, const char *fn, const unsigned char *bytes, size_t size,
                                      void **state);

#endif
