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

#endif
