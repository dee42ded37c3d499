/* SPDX-License-Identifier: BSD-2-Clause */
/* The host timing model: how long a command's transfer takes on the host interface, in whole
   nanoseconds, and which chip cycles fall due by the host clock (docs/host-time.md,
   docs/decisions.md "Host time"). Plain C99, no FMI: the C-Motion transport
   (PMDfmu.c) calls it; python/pmdfmu/hosttime.py is the same formula, and
   tests/test_host_time.py compares the two on every interface.

   The kinds and their parameters with their defaults come from modelDescription/
   host_interfaces.csv through modelDescription/generate_hosttime.py (PMDhosttime_table.h). */
#ifndef PMD_HOSTTIME_H
#define PMD_HOSTTIME_H

#include <stdint.h>
#include "PMDhosttime_table.h"

#ifdef __cplusplus
extern "C" {
#endif

/* PMDHostTransferNs's direction */
enum { PMDHostRequest = 0, PMDHostReply = 1 };

/* A kind with the table's defaults; an unknown kind gives `none`. */
PMDHostInterface PMDHostInterfaceOf(int kind);

/* The C library's default: parallel16 with its defaults (a polling loop must end). */
PMDHostInterface PMDHostInterfaceDefault(void);

/* The kind of a name of the table ("parallel16"), or -1; and the name of a kind, or NULL. */
int PMDHostInterfaceKind(const char *name);
const char *PMDHostInterfaceName(int kind);

/* The first parameter of h's kind outside its range in the table (a baud of 0 would make bytes take
   no time, a parity of 5 five bits), or NULL if every one is in range: its name, with its value and
   range in *value, *min and *max. A kind that is none of the table's is "kind". */
const char *PMDHostInterfaceRefused(const PMDHostInterface *h, uint32_t *value, uint32_t *min, uint32_t *max);

/* The request's transfer time: `words` host words sent (the instruction word and the data
   words, >= 1). */
uint64_t PMDHostRequestNs(const PMDHostInterface *host, int words);

/* The reply's transfer time, the chip's processing time included: `words` result words
   returned; a failed command (failed != 0) returns none (the serial reply is 2 bytes). */
uint64_t PMDHostReplyNs(const PMDHostInterface *host, int words, int failed);

/* Either of the two: direction PMDHostRequest or PMDHostReply (failed is read for a reply). */
uint64_t PMDHostTransferNs(const PMDHostInterface *host, int direction, int words, int failed);

/* How many cycles of the grid are due by the host clock: the grid's cycles at nextCycleNs,
   nextCycleNs + cycleNs, ... that are <= hostNs (0 if hostNs < nextCycleNs or cycleNs is 0). */
uint64_t PMDHostCyclesDue(uint64_t hostNs, uint64_t nextCycleNs, uint64_t cycleNs);

#ifdef __cplusplus
}
#endif

#endif
