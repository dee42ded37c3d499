/* SPDX-License-Identifier: BSD-2-Clause */
/* The chip FMU's messages (messages.h). */
#include <stdarg.h>
#include <stdio.h>

#include "messages.h"

static void log_message(const PmdInstance *inst, PmdStatus status, PmdLogCategory category, const char *format,
                        va_list args)
{
    char message[8192];              /* a refused script names the places it was looked for */
    vsnprintf(message, sizeof message, format, args);
    inst->logger(inst->environment, inst->instanceName, status, pmd_log_category_names[category], message);
}

void pmd_instance_log(const PmdInstance *inst, PmdStatus status, PmdLogCategory category, const char *format, ...)
{
    va_list args;
    /* errors are always logged; the rest as SetDebugLogging says */
    if (!inst->logger || (status < PMD_ERROR && !(inst->loggingOn && (inst->categories & (1u << category)))))
        return;
    va_start(args, format);
    log_message(inst, status, category, format, args);
    va_end(args);
}

void pmd_model_error(const PmdInstance *inst, const char *format, ...)
{
    va_list args;
    if (!inst->logger)
        return;
    va_start(args, format);
    log_message(inst, PMD_ERROR, PMD_LOG_ERRORS, format, args);
    va_end(args);
}
