/* The trajectory generators and Update (profile.c): one cycle of an axis's
 * profile, the stops, and the copy of the buffered registers to the active set. */
#ifndef PMD_PROFILE_H
#define PMD_PROFILE_H

#include "events.h"

void pmd_profile_cycle(PmdChip *chip, int axis);
void pmd_gear_cycle(PmdChip *chip, int axis);
int pmd_update(PmdChip *chip, int axis);
void pmd_abrupt_stop(PmdChip *chip, int axis);
/* Stops the axis in stop mode PMDAbruptStopMode or PMDSmoothStopMode, in any
 * profile mode, as Update does with a buffered stop mode; changes no register. */
void pmd_stop(PmdChip *chip, int axis, uint16_t stopMode);
void pmd_halt(PmdChip *chip, int axis);
int pmd_segment_plan_valid(const PmdChip *chip, int n);

#endif
