/* The trace facility (trace.c): sampling at the end of each cycle. */
#ifndef PMD_TRACE_H
#define PMD_TRACE_H

#include "events.h"

void pmd_trace_cycle(PmdChip *chip);
/* 0, or PMD_ERR_TraceRunning (logged, naming the command) while a trace runs. */
int pmd_trace_busy(const PmdChip *chip, const char *command);

#endif
