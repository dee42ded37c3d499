/* SPDX-License-Identifier: BSD-2-Clause */
/* FMU state snapshots (state.c): the chip's FMU states for both FMI shells. */
#ifndef PMD_STATE_H
#define PMD_STATE_H

#include "instance.h"

size_t pmd_state_size(const PmdInstance *inst);
void pmd_state_write(const PmdInstance *inst, unsigned char *out);
/* Checks a snapshot of `size` bytes; logs why and returns PMD_ERROR if it is refused. */
PmdStatus pmd_state_check(const PmdInstance *inst, const char *fn, const unsigned char *in, size_t size);
/* Restores a checked snapshot. */
PmdStatus pmd_state_read(PmdInstance *inst, const char *fn, const unsigned char *in);

/* The FMU state objects of fmi2/fmi3 Get/Set/Free/Serialize/DeserializeFMUState are
 * pmd_model_fmu_state_* of model.h, over these. */

#endif
