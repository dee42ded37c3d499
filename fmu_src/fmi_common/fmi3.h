/* SPDX-License-Identifier: BSD-2-Clause */
/* What the FMI 3.0 shell (fmi3.c, written once for both FMUs over model.h)
 * offers the FMU's other FMI 3 files: fmi3_not_provided.c's refusals and the
 * chip's extension function (fmu_src/fmi/record_fmi3.c). */
#ifndef PMD_FMI3_H
#define PMD_FMI3_H

#include "fmi3Functions.h"
#include "model.h"

/* The model behind c if a call to fn is legal in its state (a mask of
 * PmdState), else NULL (logged, if c is an instance). */
PmdModel *pmd_fmi3_begin(fmi3Instance c, const char *fn, unsigned states);

/* Refuses `function` with fmi3Error, logging "<function>: not supported: <why>"
 * if c is an instance. */
fmi3Status pmd_fmi3_unsupported(fmi3Instance c, const char *function, const char *why);

/* Refuses an instantiation: logs why (the message names the function) as an
 * error, if the importer gave a logMessage callback; no instance exists yet. */
void pmd_fmi3_refuse_instance(fmi3InstanceEnvironment environment, fmi3LogMessageCallback logMessage,
                              const char *why);

#endif
