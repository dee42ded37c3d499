/* SPDX-License-Identifier: BSD-2-Clause */
/* One plant FMU instance: the model (plant.h), the FMI state it is in, and its
 * variables served by the generated table (plant_variables.h). It is the
 * plant's model for the FMI shells (fmi_common/model.h: plant_fmu.c implements
 * it), which map the FMI APIs onto it. */
#ifndef PLANT_FMU_H
#define PLANT_FMU_H

#include <stddef.h>

#include "model.h"
#include "plant.h"
#include "plant_variables.h"

/* What an FMU state holds: plain data, no pointer. */
typedef struct {
    PmdState state;
    PlantModel m;
} PlantInstanceState;

typedef struct PmdModel PlantInstance;
struct PmdModel {
    PlantInstanceState s;
    char *instanceName;
    PmdModelLogger logger;
    void *environment;
};

#endif
