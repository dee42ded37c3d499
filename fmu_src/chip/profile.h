/* SPDX-License-Identifier: BSD-2-Clause */
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
/* Motion complete now (mode commanded) or once the axis settles (mode actual). */
void pmd_motion_complete(PmdChip *chip, int axis);

/* ---- the external profile's integration step (seed 000): most cycles of a
 * long run. Inline, for profile.c's external cycle and for chip.c's quiet
 * cycle, which takes it before anything else for an axis inside a segment. */

/* The carry floor(f / PMD_U_PER_COUNT) of the f an integration step forms.
 * Every state keeps 0 <= fraction < 6 * 2^32 and 0 <= V's, A/2's fraction
 * < 2^33 (state_fields.c holds a restored state to them), and j is an int32,
 * so f = fraction + 3 (V + A/2's fractions) + j lies in [-2^31, 18 * 2^32 +
 * 2^31): floor(f / 2^33) = y is -1 .. 9 and the carry floor(y / 3) is
 * floor((y + 3) * 11 / 32) - 1, exact for 0 <= y + 3 < 32. One shift and a
 * small multiplication: the carry is the one value every integration step
 * waits for (the next step's fraction depends on it), and this is the
 * shortest exact way measured to it (bench/engine.c's contenders). */
static inline int64_t pmd_integration_carry(int64_t f)
{
    return ((pmd_floor_shift(f, 33) + 3) * 11 >> 5) - 1;
}

/* One step of the recurrence, exactly (chip_types.h): in 2^-33 count (3 U)
 * V + A/2 is whole, J/2 is j and J is 2 j; J/6 is j U. Returns whether the
 * velocity came to rest (exactly 0 from non-zero): seed 000, 1.6 sets motion
 * complete then. Branch-free but for that rare case: V was 0 before the step
 * too exactly when A + J/2 was 0, i.e. when A after it (A + J) equals J/2. */
static inline int pmd_integrate(PmdTrajectory *t)
{
    int64_t j = t->jerk;
    PmdFixed half = pmd_fixed_half(t->acceleration), halfJerk;
    int64_t f = t->fraction + 3 * (t->velocity.fraction + half.fraction) + j;        /* P += V + A/2 + J/6 */
    int64_t carry = pmd_integration_carry(f);                                         /* -1 .. 3 */
    t->fraction = f - carry * PMD_U_PER_COUNT;
    t->position = pmd_int32((uint32_t)t->position + (uint32_t)t->velocity.counts + (uint32_t)half.counts +
                            (uint32_t)carry);
    t->velocity = pmd_fixed_make(pmd_int64((uint64_t)t->velocity.counts + (uint64_t)t->acceleration.counts),
                                 t->velocity.fraction + t->acceleration.fraction + j); /* V += A + J/2 */
    t->acceleration = pmd_fixed_add_raw(t->acceleration, 2 * j);                     /* A += J */
    if (!pmd_fixed_is_zero(t->velocity))
        return 0;
    halfJerk = pmd_fixed_make(0, j);
    return t->acceleration.counts != halfJerk.counts || t->acceleration.fraction != halfJerk.fraction;
}

/* An external profile's cycle inside a segment (segmentTime != 0), seed 000's
 * pseudo code: the decrement closes the cycle; in external mode motion
 * complete is set whenever the axis comes to rest (1.6). */
static inline void pmd_external_step(PmdChip *chip, int n)
{
    PmdAxis *ax = &chip->s.axis[n];
    ax->segmentTime--;
    if (pmd_integrate(&ax->trajectory))
        pmd_motion_complete(chip, n);
}

/* An axis at rest (PMD_MOTION_IDLE): the braking of the last moving cycle is
 * over. Inline: chip.c's cycle() takes it without a call. */
static inline void pmd_rest_cycle(PmdChip *chip, int n)
{
    chip->s.axis[n].trajectory.acceleration = PMD_FIXED_ZERO;
}

/* The segment v read (seed 000's pseudo code after the read): the
 * registers loaded, the read cycle counted. Returns whether the axis came to
 * rest (moving: it was moving before), for the caller to call
 * pmd_motion_complete (after it has read the registers it wants). */
void pmd_external_halt(PmdChip *chip, int axis);
static inline int pmd_external_begin(PmdChip *chip, int n, const int32_t v[PMD_FUNCTIONS], int moving)
{
    PmdAxis *ax = &chip->s.axis[n];
    PmdTrajectory *t = &ax->trajectory;
    t->position = v[PMDBufferFunctionPosition];
    t->fraction = 0;
    t->velocity = pmd_fixed_from_1616(v[PMDBufferFunctionVelocity]);
    t->acceleration = pmd_fixed_from_1616(v[PMDBufferFunctionAcceleration]);
    t->jerk = v[PMDBufferFunctionJerk];
    ax->segmentTime = (uint32_t)v[PMDBufferFunctionTime];
    if (ax->segmentTime == 0) {
        pmd_external_halt(chip, n);
        return 0;
    }
    ax->segmentTime--;
    return moving && pmd_fixed_is_zero(t->velocity);
}

/* A segment read in the usual layout (pmd_external_plain held at the run's
 * start): read_segment without its checks, which cannot fail then - one load
 * per function at the position buffer's read index, each buffer's read index
 * moved past it. Returns what pmd_external_begin does. */
int pmd_external_plain(const PmdChip *chip, int axis);
static inline int pmd_external_read_plain(PmdChip *chip, int n)
{
    PmdAxis *ax = &chip->s.axis[n];
    const PmdBuffer *pos = &chip->s.buffer[ax->segmentBuffer[0]];      /* the plan lists position first */
    uint32_t offset = pos->readIndex, next = offset + 1 == pos->length ? 0 : offset + 1;
    const uint32_t *word = chip->memory + offset;
    int32_t v[PMD_FUNCTIONS];
    int f;
    for (f = 0; f < PMD_FUNCTIONS; f++)
        v[f] = (int32_t)word[ax->segmentStart[f]];
    for (f = 0; f < PMD_FUNCTIONS; f++)
        chip->s.buffer[ax->segmentBuffer[f]].readIndex = next;
    ax->underrunWarned = 0;
    return pmd_external_begin(chip, n, v, !pmd_fixed_is_zero(ax->trajectory.velocity));
}

#endif
