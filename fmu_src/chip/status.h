/* SPDX-License-Identifier: BSD-2-Clause */
/* Register views: the status registers and the values the chip derives from
 * its state. Ground floor: they read the state and call nothing. */
#ifndef PMD_STATUS_H
#define PMD_STATUS_H

#include "events.h"

static inline uint32_t pmd_abs32(int32_t x)
{
    return x < 0 ? 0u - (uint32_t)x : (uint32_t)x;
}

uint16_t pmd_signal_status(const PmdChip *chip, int axis);
int pmd_host_interrupt(const PmdChip *chip);
int32_t pmd_actual_velocity(const PmdAxis *ax);

/* Whether a position's change from previous to current wrapped between the
 * maximum and the minimum (the wrap-around event, reference 2.2, in the words
 * of the C-Motion Magellan Programming Reference): the change, taken as the signed 32-bit step the
 * encoder counter made, crossed INT32_MAX -> INT32_MIN going up or the other
 * way going down. That is: the sign changed, and the step has the sign the
 * previous position had (a step across 0 has the other). Branch-free: the
 * quiet loop asks it every cycle of an ideal servo's axis (chip.c). */
static inline int pmd_wrapped(int32_t previous, int32_t current)
{
    uint32_t p = (uint32_t)previous, c = (uint32_t)current;
    return (int)(((p ^ c) & ~(p ^ (c - p))) >> 31);
}

static inline int32_t pmd_position_error(const PmdAxis *ax)
{
    return pmd_int32((uint32_t)ax->actualPosition - (uint32_t)ax->trajectory.position);
}

/* GetActivityStatus. Inline and without branches: a recording reads it every
 * cycle (record.c). Each flag is a bit of the state, 0 or 1 (the state's
 * booleans are: state_fields.c checks a restored state's), shifted into place. */
static inline uint16_t pmd_activity_status(const PmdChip *chip, int n)
{
    const PmdAxis *ax = &chip->s.axis[n];
    uint32_t moving = ax->motion != PMD_MOTION_IDLE;
    /* Seed 000, 1.6: the profile segment number is 1 while an external profile runs, 0 once halted;
     * reference 5: an S-curve shows its phase 1..7 */
    uint32_t segment = ax->motion == PMD_MOTION_EXTERNAL ? 1u : ax->motion == PMD_MOTION_SCURVE ? ax->scurvePhase : 0u;
    uint32_t s = PMD_FIELD_DP(0, PMDActivityProfileMode, ax->active.profileMode)
               | (uint32_t)ax->phasingInitialized * PMDActivityPhasingInitializedMask     /* InitializePhase */
               | (uint32_t)ax->atMaximumVelocity * PMDActivityAtMaximumVelocityMask
               | (uint32_t)(pmd_abs32(pmd_position_error(ax)) <= ax->trackingWindow) * PMDActivityTrackingMask
               | (uint32_t)(!moving && ax->settleCount > ax->settleTime) * PMDActivityAxisSettledMask
               | (uint32_t)ax->motorOn * PMDActivityMotorOnMask
               | (uint32_t)ax->captured * PMDActivityPositionCaptureMask
               | moving * PMDActivityInMotionMask
               | (uint32_t)ax->inPositiveLimit * PMDActivityInPositiveLimitMask
               | (uint32_t)ax->inNegativeLimit * PMDActivityInNegativeLimitMask;
    return (uint16_t)PMD_FIELD_DP(s, PMDActivityProfileSegment, segment);
}
/* GetPhaseCommand of phase 0..2 on the FMU's idle commutator: a brushed DAC axis
 * (GetVersion's motor type) drives phase A with the motor command; B and C read 0. */
static inline int16_t pmd_phase_command(const PmdAxis *ax, int phase)
{
    return phase == PMDPhaseA ? ax->filter.output : 0;
}
#define pmd_commanded_velocity(t) pmd_fixed_register_1616((t)->velocity)
#define pmd_commanded_acceleration(t) pmd_fixed_register_1616((t)->acceleration)

/* The commanded trajectory of every axis as the FMU's Reals, fraction kept:
 * counts, counts/s, counts/s^2 for a cycle of cycleTime s. The one definition
 * of axisN.position, .velocity and .acceleration, for the getters and the
 * recorder alike (fmu_src/fmi/values.h). */
typedef struct {
    double position[PMD_AXES], velocity[PMD_AXES], acceleration[PMD_AXES];
} PmdCommandedReals;
void pmd_commanded_reals(const PmdChip *chip, double cycleTime, PmdCommandedReals *r);

#endif
