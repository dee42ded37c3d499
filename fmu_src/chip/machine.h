/* SPDX-License-Identifier: BSD-2-Clause */
/* The machine around the chip: switch and index inputs that follow each
 * axis's actual position (docs/machine.md). */
#ifndef PMD_MACHINE_H
#define PMD_MACHINE_H

#include "chip_types.h"

/* Sets the inputs chip->machine drives on axis n from the actual position
 * this cycle sampled (and the one before it, for the index): called every
 * cycle after the actual positions are sampled, before the limit and capture
 * checks read the inputs, so that a switch edge acts in the cycle the axis
 * reaches it. */
void pmd_machine_inputs(PmdChip *chip, int n);

/* Starts axis n's motor (servo = "plant") at its initial angle and speed, its
 * encoder count in the actual position input: at the end of initialization. */
void pmd_machine_plant_start(PmdChip *chip, int n);

/* Axis n's motor through one chip cycle (the sample time) under the motor
 * command the cycle ended with, its encoder count into the actual position
 * input the next cycle samples: called after every other part of the cycle,
 * which is the order of a Gauss-Seidel master that steps the chip and then
 * the plant with the chip's new command (docs/machine.md). */
void pmd_machine_plant_cycle(PmdChip *chip, int n);

/* Whether the index pulse of m is active at actual position `now`, coming
 * from `before` (the last cycle's): a pulse position passed since then, or
 * reached and held. */
int pmd_machine_index_active(const PmdMachineAxis *m, int32_t before, int32_t now);

#endif
