/* SPDX-License-Identifier: BSD-2-Clause */
/* The servo filter and the motor output of every axis (servo.c): the PID with
 * velocity and acceleration feedforward, the output scale, the motor bias and
 * the motor limit in closed loop, the motor command register in open loop.
 * docs/decisions.md, "Servo filter and motor output", gives the formula. */
#ifndef PMD_SERVO_H
#define PMD_SERVO_H

#include "events.h"

/* The filter's position error: commanded - actual, wrapped to 32 bits.
 * GetPositionError reads the other sign, actual - commanded (reference 1.2). */
static inline int32_t pmd_servo_error(const PmdAxis *ax)
{
    return pmd_int32((uint32_t)ax->trajectory.position - (uint32_t)ax->actualPosition);
}

/* One cycle of axis n's filter, once its actual position is sampled and the
 * cycle's events have acted: filter.output is the cycle's motor command. */
void pmd_servo_cycle(PmdChip *chip, int axis);

/* k >= 1 cycles of axis n's filter at once, exactly as running them one by
 * one, when the motor mode and the position error stayed what they are now
 * through all of them, nothing but those cycles changed the filter, and the
 * commanded velocity and acceleration are those of the last of them: an ideal
 * servo's (error 0) in a quiet run (chip.c), an axis fast-forwarded
 * (fastforward.c). Call it once the cycles' trajectories have run. */
void pmd_servo_advance(PmdChip *chip, int axis, int64_t k);

#endif
