/* SPDX-License-Identifier: BSD-2-Clause */
/* The trace facility (trace.c): sampling at the end of each cycle. */
#ifndef PMD_TRACE_H
#define PMD_TRACE_H

#include "events.h"

void pmd_trace_cycle(PmdChip *chip);
/* Starts sampling now (condition met, or SetTraceStart's immediate condition). */
void pmd_trace_start(PmdChip *chip);
void pmd_trace_stop(PmdChip *chip, const char *why);
/* 0, or PMD_ERR_TraceRunning (logged, naming the command) while a trace runs. */
int pmd_trace_busy(const PmdChip *chip, const char *command);

#endif
