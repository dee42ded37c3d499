/* SPDX-License-Identifier: BSD-2-Clause */
/* The ground floor of the chip core: the chip's log and its event status
 * bits. It depends on the chip's data only (chip_types.h, where PmdChip is);
 * every other part of the chip reports through it, and none of it calls back up. */
#ifndef PMD_EVENTS_H
#define PMD_EVENTS_H

#include "chip_types.h"
#include "log_categories.h"     /* generated from modelDescription/log_categories.csv */
#include "pmd_constants.h"

#ifdef __MINGW32__
#include <stdio.h> /* __MINGW_PRINTF_FORMAT */
#endif
/* Logging: pmd_log formats only when the category is enabled. */
void pmd_log(const PmdChip *chip, PmdLogCategory category, const char *format, ...)
#if defined(__MINGW32__) /* mingw-w64: the printf the build links (C99's with __USE_MINGW_ANSI_STDIO) */
    __attribute__((format(__MINGW_PRINTF_FORMAT, 3, 4)))
#elif defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
#define PMD_LOGGING(chip, category) ((chip)->logMask & (1u << (category)))

/* Sets event status bits of axis n (reference 2.1); a bit newly set is logged. */
void pmd_set_event(PmdChip *chip, int axis, uint16_t mask);

#endif
