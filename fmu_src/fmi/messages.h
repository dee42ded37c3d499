/* SPDX-License-Identifier: BSD-2-Clause */
/* The chip FMU's messages (messages.c): under the log categories the model
 * description declares, as SetDebugLogging enabled them; errors always. */
#ifndef PMD_MESSAGES_H
#define PMD_MESSAGES_H

#include "instance_types.h"

#ifdef __MINGW32__
#include <stdio.h> /* __MINGW_PRINTF_FORMAT */
#endif
void pmd_instance_log(const PmdInstance *inst, PmdStatus status, PmdLogCategory category, const char *format, ...)
#if defined(__MINGW32__) /* mingw-w64: the printf the build links (C99's with __USE_MINGW_ANSI_STDIO) */
    __attribute__((format(__MINGW_PRINTF_FORMAT, 4, 5)))
#elif defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

#endif
