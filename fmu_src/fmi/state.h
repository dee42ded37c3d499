/* FMU state snapshots, shared by the FMI 2 and FMI 3 wrappers (state.c). */
#ifndef PMD_STATE_H
#define PMD_STATE_H

#include "instance.h"

size_t pmd_state_size(const PmdInstance *inst);
void pmd_state_write(const PmdInstance *inst, unsigned char *out);
/* Checks a snapshot of `size` bytes; logs why and returns PMD_ERROR if it is refused. */
PmdStatus pmd_state_check(const PmdInstance *inst, const char *fn, const unsigned char *in, size_t size);
/* Restores a checked snapshot. */
PmdStatus pmd_state_read(PmdInstance *inst, const char *fn, const unsigned char *in);

/* The FMU state objects of fmi2/fmi3 Get/Set/Free/Serialize/DeserializeFMUState. */
PmdStatus pmd_fmu_state_get(PmdInstance *inst, const char *fn, void **state);
PmdStatus pmd_fmu_state_set(PmdInstance *inst, const char *fn, const void *state);
PmdStatus pmd_fmu_state_free(PmdInstance *inst, const char *fn, void **state);
PmdStatus pmd_fmu_state_size(PmdInstance *inst, const char *fn, const void *state, size_t *size);
PmdStatus pmd_fmu_state_serialize(PmdInstance *inst, const char *fn, const void *state, unsigned char *bytes,
                                  size_t size);
PmdStatus pmd_fmu_state_deserialize(PmdInstance *inst, const char *fn, const unsigned char *bytes, size_t size,
                                    void **state);

#endif
