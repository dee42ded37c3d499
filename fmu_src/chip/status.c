/* SPDX-License-Identifier: BSD-2-Clause */
/* The status registers and the values the chip derives from its state
 * (reference 2.1-2.3, 4.5): read by the host, the cycle, breakpoints and the
 * trace; they change nothing. */
#include <string.h>

#include "status.h"

/* GetActualVelocity: whole counts per cycle in 16.16 (the low word is 0). */
int32_t pmd_actual_velocity(const PmdAxis *ax)
{
    return pmd_int32(((uint32_t)ax->actualPosition - (uint32_t)ax->previousActualPosition) << 16);
}

/* The input levels of the signal status, AxisOut aside. Switches are wired
 * active low, as on PMD boards: an active switch (input true) reads 0, an idle
 * one 1. The encoder A and B lines read 1; the index line as the switches:
 * 0 while its pulse is active (docs/machine.md). */
static uint16_t input_levels(const PmdAxis *ax)
{
    uint16_t level = PMDSignalEncoderAMask | PMDSignalEncoderBMask;
    if (!ax->indexInput)
        level |= PMDSignalEncoderIndexMask;
    if (!ax->homeInput)
        level |= PMDSignalEncoderHomeMask;
    if (!ax->positiveLimitInput)
        level |= PMDSignalPositiveLimitMask;
    if (!ax->negativeLimitInput)
        level |= PMDSignalNegativeLimitMask;
    return level;
}

/* The AxisOut pin (SetAxisOutSource): the chosen bit of the chosen axis's
 * event, activity or signal status register, low with source "none". A pin
 * fed by a signal status reads it without AxisOut bits, so that pins cannot
 * feed each other in a circle. */
static int axis_out_level(const PmdChip *chip, const PmdAxis *ax)
{
    int src = (int)PMD_FIELD_EX(ax->axisOutSource, PMDAxisOutSourceAxis);
    unsigned bit = PMD_FIELD_EX(ax->axisOutSource, PMDAxisOutSourceBit);
    uint16_t status;
    switch (PMD_FIELD_EX(ax->axisOutSource, PMDAxisOutSourceRegister)) {
    case PMDAxisOutSourceEventStatus: status = chip->s.axis[src].eventStatus; break;
    case PMDAxisOutSourceActivityStatus: status = pmd_activity_status(chip, src); break;
    case PMDAxisOutSourceSignalStatus:
        status = (uint16_t)((input_levels(&chip->s.axis[src]) ^ chip->s.axis[src].signalSense) &
                            PMDSignalStatusMask & ~PMDSignalAxisOutMask);
        break;
    default: return 0;
    }
    return (status >> bit) & 1u;
}

/* GetSignalStatus: the levels, each inverted where its sense bit is 1 (reference 2.3). */
uint16_t pmd_signal_status(const PmdChip *chip, int n)
{
    const PmdAxis *ax = &chip->s.axis[n];
    uint16_t level = input_levels(ax);
    if (axis_out_level(chip, ax))
        level |= PMDSignalAxisOutMask;
    return (uint16_t)((level ^ ax->signalSense) & PMDSignalStatusMask);
}

int pmd_host_interrupt(const PmdChip *chip)
{
    int n;
    for (n = 0; n < PMD_AXES; n++)
        if (chip->s.axis[n].eventStatus & chip->s.axis[n].interruptMask)
            return 1;
    return 0;
}

/* x in U as a double where it fits an int64 (pmd_fixed_in_u), else 0 and the
 * axis's bit set in *wide: its value is made from its parts (wide_reals). */
static inline double in_u(PmdFixed x, unsigned *wide, int n)
{
    int64_t u;
    if (pmd_fixed_in_u(x, &u))
        return (double)u;
    *wide |= 1u << n;
    return 0.0;
}

/* The velocities and accelerations beyond an int64 in U, from their parts. */
static void wide_reals(const PmdChip *chip, double cycleTime, unsigned wideVelocity, unsigned wideAcceleration,
                       PmdCommandedReals *r)
{
    int n;
    for (n = 0; n < PMD_AXES; n++) {
        const PmdTrajectory *t = &chip->s.axis[n].trajectory;
        if (wideVelocity & (1u << n))
            r->velocity[n] = pmd_fixed_wide_double(t->velocity) / cycleTime;
        if (wideAcceleration & (1u << n))
            r->acceleration[n] = pmd_fixed_wide_double(t->acceleration) / (cycleTime * cycleTime);
    }
}

/* The Reals of the four axes: each axis's fraction, velocity and acceleration
 * in U converted (in_u), divided by U, the velocity then by the cycle time
 * and the acceleration by its square, the position's whole counts added. The
 * twenty divisions of a row are the cost; where the compiler has vector types
 * (GCC, Clang) they run as packed ones: two lanes a division, the form every
 * processor the FMU is built for runs (SSE2, NEON; a four-lane AVX form bought
 * ~2 ns of a ~46 ns row and asked the host processor what it runs, which a
 * model of the chip should not). IEEE 754
 * rounds each lane as the scalar division, so both forms give the same
 * doubles, bit for bit (tests/test_exact_arithmetic.py checks them against the
 * scalar expressions; PMD_PORTABLE_LANES builds the plain C form). The lanes
 * are built from registers and stored whole: a vector loaded from scalars just
 * stored would stall on the store buffer. */
#define FRACTION(k) ((double)chip->s.axis[k].trajectory.fraction)
#define WHOLE(k) ((double)chip->s.axis[k].trajectory.position)
#define VELOCITY(k) in_u(chip->s.axis[k].trajectory.velocity, &wideVelocity, (k))
#define ACCELERATION(k) in_u(chip->s.axis[k].trajectory.acceleration, &wideAcceleration, (k))

#if defined(__GNUC__) && !defined(PMD_PORTABLE_LANES)
typedef double Pair __attribute__((vector_size(2 * sizeof(double))));
/* the pair form takes the axes two at a time (a C99 static assertion: a negative array size if not) */
typedef char PmdAxesInPairs[PMD_AXES % 2 == 0 ? 1 : -1];
/* the lanes of axes k and k + 1, F(k) each: F has no side effect but a function call's (a vector's
 * initializers are not sequenced with each other; calls are) */
#define PAIR(F, k) ((Pair){F(k), F((k) + 1)})
#define PAIR_OF(x) ((Pair){(x), (x)})

static void commanded_reals(const PmdChip *chip, double cycleTime, PmdCommandedReals *r)
{
    unsigned wideVelocity = 0, wideAcceleration = 0;
    int k;
    for (k = 0; k < PMD_AXES; k += 2) {
        Pair u = PAIR_OF((double)PMD_U_PER_COUNT);
        Pair position = PAIR(FRACTION, k) / u + PAIR(WHOLE, k);
        Pair velocity = PAIR(VELOCITY, k) / u / PAIR_OF(cycleTime);
        Pair acceleration = PAIR(ACCELERATION, k) / u / PAIR_OF(cycleTime * cycleTime);
        memcpy(r->position + k, &position, sizeof position);
        memcpy(r->velocity + k, &velocity, sizeof velocity);
        memcpy(r->acceleration + k, &acceleration, sizeof acceleration);
    }
    if (wideVelocity | wideAcceleration)
        wide_reals(chip, cycleTime, wideVelocity, wideAcceleration, r);
}


#else
static void commanded_reals(const PmdChip *chip, double cycleTime, PmdCommandedReals *r)
{
    unsigned wideVelocity = 0, wideAcceleration = 0;
    int k;
    for (k = 0; k < PMD_AXES; k++) {
        r->position[k] = FRACTION(k) / (double)PMD_U_PER_COUNT + WHOLE(k);
        r->velocity[k] = VELOCITY(k) / (double)PMD_U_PER_COUNT / cycleTime;
        r->acceleration[k] = ACCELERATION(k) / (double)PMD_U_PER_COUNT / (cycleTime * cycleTime);
    }
    if (wideVelocity | wideAcceleration)
        wide_reals(chip, cycleTime, wideVelocity, wideAcceleration, r);
}
#endif

void pmd_commanded_reals(const PmdChip *chip, double cycleTime, PmdCommandedReals *r)
{
    commanded_reals(chip, cycleTime, r);
}
