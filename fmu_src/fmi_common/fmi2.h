/* SPDX-License-Identifier: BSD-2-Clause */
/* What the FMI 2.0 shell (fmi2.c, written once for both FMUs over model.h)
 * offers the FMU's other FMI 2 files: fmi2_not_provided.c's refusals and the
 * chip's extension functions (fmu_src/fmi/record_fmi2.c). */
#ifndef PMD_FMI2_H
#define PMD_FMI2_H

#include "fmi2Functions.h"
#include "model.h"

/* The model behind c if a call to fn is legal in its state (a mask of
 * PmdState), else NULL (logged, if c is an instance). */
PmdModel *pmd_fmi2_begin(fmi2Component c, const char *fn, unsigned states);
/* Checks that arrays holding n values are not NULL; logs and returns 0 if one is. */
int pmd_fmi2_arrays_given(const PmdModel *m, const char *fn, size_t n, const void *a, const void *b);

/* Refuses `function` with fmi2Error, logging "<function>: not supported: <why>"
 * if c is an instance. */
fmi2Status pmd_fmi2_unsupported(fmi2Component c, const char *function, const char *why);

#endif
