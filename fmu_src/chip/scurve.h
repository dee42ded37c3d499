/* SPDX-License-Identifier: BSD-2-Clause */
/* The S-curve generator (scurve.c): plans a move, then runs it cycle by cycle;
 * profile.c ends the motion when the curve says it is finished. */
#ifndef PMD_SCURVE_H
#define PMD_SCURVE_H

#include "events.h"

int pmd_scurve_plan(const PmdChip *chip, int axis, const PmdProfileRegisters *r, PmdSCurve *plan);
/* One cycle of the move; returns 1 when the axis has arrived (at rest, phase 0). */
int pmd_scurve_cycle(PmdChip *chip, int axis);
void pmd_scurve_smooth_stop(PmdAxis *ax);
/* p6Total of a plan with these phase lengths (each at most 2^60), or -1 past 2^62. */
int64_t pmd_scurve_p6_total(int64_t t1, int64_t t2, int64_t t4);
/* Whether p6, v2 and a are the unit curve's after `step` steps of these phases. */
int pmd_scurve_on_curve(const PmdSCurve *c);

#endif
