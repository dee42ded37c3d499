/* The FMI 3.0 functions the chip's and the plant's FMUs do not provide
 * (fmi3_not_provided.c, compiled into both): both are Co-Simulation only,
 * without event mode, clocks, structural parameters or derivatives. Each
 * FMU's wrapper defines the refusal they all end in. */
#ifndef FMI3_NOT_PROVIDED_H
#define FMI3_NOT_PROVIDED_H

#include "fmi3Functions.h"

/* Refuses `function` with fmi3Error, logging "<function>: not supported: <why>"
 * if c is an instance (defined by fmi3.c and plant_fmi3.c). */
fmi3Status pmd_fmi3_unsupported(fmi3Instance c, const char *function, const char *why);

/* Refuses an instantiation: logs why (the message names the function) as an
 * error, if the importer gave a logMessage callback; no instance exists yet. */
void pmd_fmi3_refuse_instance(fmi3InstanceEnvironment environment, fmi3LogMessageCallback logMessage,
                              const char *why);

#endif
