/* SPDX-License-Identifier: BSD-2-Clause */
/* What the fuzz targets share: a property that does not hold stops the run
 * with its message (libFuzzer keeps the input that broke it). */
#ifndef FUZZ_PROPERTY_H
#define FUZZ_PROPERTY_H

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

static void violated(const char *format, ...)
{
    va_list args;
    fprintf(stderr, "property violated: ");
    va_start(args, format);
    vfprintf(stderr, format, args);
    va_end(args);
    fprintf(stderr, "\n");
    abort();
}

#endif
