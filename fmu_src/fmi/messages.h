/* SPDX-License-Identifier: BSD-2-Clause */
/* The chip FMU's messages (messages.c): under the log categories the model
 * description declares, as SetDebugLogging enabled them; errors always. */
#ifndef PMD_MESSAGES_H
#define PMD_MESSAGES_H

#include "instance_types.h"

void pmd_instance_log(const PmdInstance *inst, PmdStatus status, PmdLogCategory category, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

#endif
