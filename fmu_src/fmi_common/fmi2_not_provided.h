/* The FMI 2.0 functions the chip's and the plant's FMUs do not provide
 * (fmi2_not_provided.c, compiled into both). Each FMU's wrapper defines the
 * refusal they all end in. */
#ifndef FMI2_NOT_PROVIDED_H
#define FMI2_NOT_PROVIDED_H

#include "fmi2Functions.h"

/* Refuses `function` with fmi2Error, logging "<function>: not supported: <why>"
 * if c is an instance (defined by fmi2.c and plant_fmi2.c). */
fmi2Status pmd_fmi2_unsupported(fmi2Component c, const char *function, const char *why);

#endif
