/* One plant FMU instance: the model (plant.h), the FMI state it is in, and its
 * variables served by the generated table (plant_variables.h). Independent of
 * the FMI version; plant_fmi2.c and plant_fmi3.c map the FMI APIs onto it. */
#ifndef PLANT_FMU_H
#define PLANT_FMU_H

#include <stddef.h>

#include "plant.h"
#include "plant_variables.h"

typedef enum { PLANT_OK, PLANT_WARNING, PLANT_DISCARD, PLANT_ERROR, PLANT_FATAL } PlantStatus;

/* The FMI states, as bits so that a function can name the states it is legal in. */
typedef enum {
    PLANT_INSTANTIATED = 1 << 0,
    PLANT_INITIALIZATION_MODE = 1 << 1,
    PLANT_STEP_MODE = 1 << 2,
    PLANT_TERMINATED = 1 << 3
} PlantState;

#define PLANT_ANY_STATE (PLANT_INSTANTIATED | PLANT_INITIALIZATION_MODE | PLANT_STEP_MODE | PLANT_TERMINATED)
#define PLANT_GET_STATES (PLANT_INITIALIZATION_MODE | PLANT_STEP_MODE | PLANT_TERMINATED)
#define PLANT_SET_STATES (PLANT_INSTANTIATED | PLANT_INITIALIZATION_MODE | PLANT_STEP_MODE)

typedef void (*PlantLogger)(void *environment, const char *instanceName, PlantStatus status, const char *category,
                            const char *message);

/* What an FMU state holds: plain data, no pointer. */
typedef struct {
    PlantState state;
    PlantModel m;
} PlantInstanceState;

typedef struct {
    PlantInstanceState s;
    char *instanceName;
    PlantLogger logger;
    void *environment;
    int loggingOn;
} PlantInstance;

PlantInstance *plant_instance_new(const char *instanceName, PlantLogger logger, void *environment);
void plant_instance_free(PlantInstance *inst);
void plant_instance_reset(PlantInstance *inst);
void plant_log(const PlantInstance *inst, PlantStatus status, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* The instance if it is in one of the states, else NULL with a logged error. */
PlantInstance *plant_begin(PlantInstance *inst, const char *fn, unsigned states);
int plant_arrays_given(const PlantInstance *inst, const char *fn, size_t n, const void *a, const void *b);
PlantStatus plant_set_debug_logging(PlantInstance *inst, const char *fn, int loggingOn, size_t nCategories,
                                    const char *const categories[]);

PlantStatus plant_enter_initialization(PlantInstance *inst, double startTime);
PlantStatus plant_exit_initialization(PlantInstance *inst);
PlantStatus plant_do_step(PlantInstance *inst, const char *fn, double t, double h);

/* The variable with value reference vr if its type is `type` (a PlantType for
 * FMI 2, a PlantType3 for FMI 3), else NULL with a logged error. */
const PlantVariable *plant_lookup(const PlantInstance *inst, const char *fn, unsigned vr, int fmi3, unsigned type);
double plant_get(const PlantInstance *inst, const PlantVariable *v);
/* Sets are all or nothing: check every value, then set them all. */
PlantStatus plant_check(const PlantInstance *inst, const char *fn, const PlantVariable *v, double value);
void plant_set(PlantInstance *inst, const PlantVariable *v, double value);
/* After a set call's values are in: the start state follows the parameters. */
void plant_set_done(PlantInstance *inst);

/* FMU states: copies of PlantInstanceState, checked field by field on restore. */
PlantStatus plant_state_get(PlantInstance *inst, const char *fn, void **state);
PlantStatus plant_state_set(PlantInstance *inst, const char *fn, const void *state);
PlantStatus plant_state_free(PlantInstance *inst, const char *fn, void **state);
size_t plant_state_size(void);
PlantStatus plant_state_serialize(PlantInstance *inst, const char *fn, const void *state, unsigned char *bytes,
                                  size_t size);
PlantStatus plant_state_deserialize(PlantInstance *inst, const char *fn, const unsigned char *bytes, size_t size,
                                    void **state);

#endif
