/* SPDX-License-Identifier: BSD-2-Clause */
/* The plain stored registers of modelDescription/registers.csv (registers.c):
 * their Set and Get commands are served by the generated register table. */
#ifndef PMD_REGISTERS_H
#define PMD_REGISTERS_H

#include "chip_types.h"

/* The Set or Get command c of a register of the register table: what a
 * handler does for any other command. */
int pmd_register_command(PmdChip *chip, const PmdCommand *c, int axis, const int64_t *arg, int64_t *reply);

/* Writes every register's reset value of the register table (reference 4.2),
 * and those of the packed and paired registers that handlers serve. */
void pmd_registers_reset(PmdChip *chip);

#endif
