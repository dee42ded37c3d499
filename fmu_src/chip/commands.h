/* SPDX-License-Identifier: BSD-2-Clause */
/* What every command handler file needs. The handlers live in commands_*.c,
 * one file per chapter of the reference's opcode table (1.2); the plain stored
 * registers have none (registers.c serves them by registers.csv). The
 * dispatcher (host.c) has decoded the arguments by the table; a handler checks
 * their ranges (reference 1.2, 4.3), acts, and returns 0 or the host I/O error
 * code, having changed nothing when it refuses. */
#ifndef PMD_COMMANDS_H
#define PMD_COMMANDS_H

#include "chip.h"
#include "command_table.h"

#define AXIS(n) (&chip->s.axis[n])

#endif
