/* SPDX-License-Identifier: BSD-2-Clause */
/* The chip's log and its event status bits: the ground floor (events.h). */
#include <stdarg.h>
#include <stdio.h>

#include "events.h"

void pmd_log(const PmdChip *chip, PmdLogCategory category, const char *format, ...)
{
    char message[512];
    va_list args;
    if (!PMD_LOGGING(chip, category) || !chip->logger)
        return;
    va_start(args, format);
    vsnprintf(message, sizeof message, format, args);
    va_end(args);
    chip->logger(chip->logContext, category, message);
}

void pmd_set_event(PmdChip *chip, int n, uint16_t mask)
{
    PmdAxis *ax = &chip->s.axis[n];
    if ((ax->eventStatus & mask) != mask)
        pmd_log(chip, PMD_LOG_EVENTS, "axis %d: event status |= 0x%04X", n + 1, (unsigned)mask);
    ax->eventStatus |= mask;
}
