/* SPDX-License-Identifier: BSD-2-Clause */
/* Fast-forward: many chip cycles at once, bit-identical to running them one
 * by one, when nothing needs individual cycles.
 *
 * Inside an external-profile segment seed 000's recurrence has an exact
 * closed form: after k integration steps from (P, V, A) with jerk J = j/2^32,
 *     P += k V + k^2 A/2 + k^3 J/6,   V += k A + k^2 J/2,   A += k J.
 * In the state's units (chip_types.h) - V, A and A/2 in 2^-33 count (V', A',
 * A'/2), the position's fraction in U = 2^-32/6 count -
 *     V' += k A' + j k^2,   A' += 2 j k,   P += 3 k V' + 3 k^2 A'/2 + k^3 j (in U).
 * So a run of cycles in which every axis is idle or integrating inside a
 * segment, no breakpoint is armed, no trace runs and the servo is ideal (the
 * position error stays 0) costs a few multiplications per axis instead of one
 * step per cycle. The servo filter then sees a constant position error (0, or
 * an idle axis's), which it also runs in closed form (servo.c). Anything
 * else - a segment read, a velocity coming to rest (an event), a position
 * wrapping between the int32 ends while its wrap-around bit is clear (an
 * event), a state beyond the bounds below - is left to the ordinary cycle.
 *
 * It needs 128-bit integers; without them it skips nothing, which is the
 * portable fallback: the same results, cycle by cycle. */
#include <math.h>

#include "chip.h"
#include "servo.h"
#include "status.h"

#if defined(__SIZEOF_INT128__) && defined(__GNUC__) && !defined(PMD_PORTABLE_WIDE)
__extension__ typedef __int128 i128;
__extension__ typedef unsigned __int128 u128;

#define TWO33 ((i128)1 << 33)
/* Every segment stays inside: |A| <= 2^15 + 2^31 counts per cycle^2 (chip_types.h). */
#define ACCELERATION_LIMIT ((int64_t)1 << 40)

/* V' and A': exact, |V'| < 2^96 and, within ACCELERATION_LIMIT, |A'| < 2^73. */
static i128 in33(PmdFixed x)
{
    return (i128)x.counts * TWO33 + x.fraction;
}

/* V' after k steps, 0 <= k < 2^32: below 2^106 in magnitude. */
static i128 velocity_after(const PmdTrajectory *t, int64_t k)
{
    return in33(t->velocity) + (i128)k * in33(t->acceleration) + (i128)t->jerk * k * k;
}

/* Whether a velocity V' is held exactly by the state the cycles keep: its
 * whole counts within int64, where their wrapping changes nothing. */
static int fits_state(i128 v)
{
    return v >= (i128)INT64_MIN * TWO33 && v < ((i128)INT64_MAX + 1) * TWO33;
}

/* The real zeros of the velocity after k steps, V' + k A' + j k^2 as a
 * polynomial in k, as doubles (within a step of the exact ones); returns how many. */
static int velocity_zeros(const PmdTrajectory *t, double roots[2])
{
    double a = (double)t->jerk, b = (double)in33(t->acceleration), c = (double)in33(t->velocity);
    int nroots = 0;
    if (a == 0) {
        if (b != 0)
            roots[nroots++] = -c / b;
    } else {
        double disc = b * b - 4 * a * c;
        if (disc >= 0) {
            roots[nroots++] = (-b - sqrt(disc)) / (2 * a);
            roots[nroots++] = (-b + sqrt(disc)) / (2 * a);
        }
    }
    return nroots;
}

/* The first step k in 1..n at which the velocity becomes exactly 0 from a
 * non-zero value (an external profile's motion-complete event), or n + 1. */
static int64_t first_rest(const PmdTrajectory *t, int64_t n)
{
    double roots[2];
    int r, nroots;
    int64_t best = n + 1, k;
    if (pmd_fixed_is_zero(t->velocity) && pmd_fixed_is_zero(t->acceleration) && t->jerk == 0)
        return n + 1;
    nroots = velocity_zeros(t, roots);
    /* the double estimates are within a step of the integer roots: check their neighbours exactly */
    for (r = 0; r < nroots; r++) {
        if (!(roots[r] > -2.0 && roots[r] < (double)n + 2.0))
            continue;
        for (k = (int64_t)floor(roots[r]) - 1; k <= (int64_t)floor(roots[r]) + 2; k++)
            if (k >= 1 && k <= n && k < best && velocity_after(t, k) == 0 && velocity_after(t, k - 1) != 0)
                best = k;
    }
    return best;
}

/* Whether the closed form holds over steps 0..n (n < 2^32): the acceleration
 * within ACCELERATION_LIMIT (the products below then fit 128 bits) and the
 * velocity's whole counts within int64 at every step, so that its exact zeros
 * are the state's. V is quadratic in k: its extremes are at the ends or next
 * to the vertex. */
static int in_bounds(const PmdTrajectory *t, int64_t n)
{
    int64_t an = t->acceleration.counts, k;
    if (an >= ACCELERATION_LIMIT || an < -ACCELERATION_LIMIT)
        return 0;
    if (!fits_state(velocity_after(t, 0)) || !fits_state(velocity_after(t, n)))
        return 0;
    if (t->jerk != 0) {
        double vertex = -(double)in33(t->acceleration) / (2.0 * t->jerk);
        if (vertex > 0 && vertex < (double)n)
            for (k = (int64_t)vertex - 1; k <= (int64_t)vertex + 2; k++)
                if (k >= 0 && k <= n && !fits_state(velocity_after(t, k)))
                    return 0;
    }
    return 1;
}

/* floor(x / U) and x mod U, for any x. */
static i128 floor_u(i128 x, i128 *rest)
{
    const i128 u = (i128)PMD_U_PER_COUNT;
    i128 q = x / u, r = x % u;
    if (r < 0) {
        r += u;
        q--;
    }
    *rest = r;
    return q;
}

/* The position's whole counts after k integration steps (k < 2^32,
 * in_bounds), not wrapped, and its fraction in U (*rest). Each term is split
 * into whole counts and U, so that no product passes 2^106. */
static i128 counts_after(const PmdTrajectory *t, int64_t k, i128 *rest)
{
    const i128 kk = (i128)k * k;
    const u128 k3 = (u128)kk * (u128)k;                                    /* < 2^96 */
    PmdFixed half = pmd_fixed_half(t->acceleration);                         /* A'/2 */
    i128 q3 = (i128)(k3 / (u128)PMD_U_PER_COUNT);                          /* k^3 = q3 U + r3 */
    i128 r3 = (i128)(k3 % (u128)PMD_U_PER_COUNT);
    i128 counts = (i128)t->position + (i128)k * t->velocity.counts + kk * half.counts + q3 * t->jerk;
    i128 fraction = (i128)t->fraction + (i128)3 * k * t->velocity.fraction + (i128)3 * kk * half.fraction +
                    r3 * t->jerk;
    return counts + floor_u(fraction, rest);
}

/* Whether the position leaves the int32 range within steps 1..n (in_bounds):
 * with an ideal servo the actual position would then wrap between the
 * maximum and the minimum, an event (reference 2.2). The position is a cubic
 * in the step count whose derivative is proportional to the velocity's
 * polynomial: its extremes over 1..n are at n or next to the velocity's zeros. */
static int leaves_int32(const PmdTrajectory *t, int64_t n)
{
    double roots[2], dn = (double)n;
    /* most skips stay far from the ends: a bound on the distance covered,
     * n|V| + n^2|A|/2 + n^3|J|/6 counts (V, A in 2^-33 count, J in 2^-32),
     * with a margin for the doubles' rounding and the floor, says so cheaply */
    double reach = (dn * fabs((double)in33(t->velocity)) + dn * dn * fabs((double)in33(t->acceleration)) / 2) /
                   (double)TWO33 + dn * dn * dn * fabs((double)t->jerk) / 6 / 4294967296.0;
    int r, nroots;
    int64_t k;
    i128 rest, p;
    reach = reach * (1 + 1e-9) + 2;
    if ((double)t->position + reach < (double)INT32_MAX && (double)t->position - reach > (double)INT32_MIN)
        return 0;
    nroots = velocity_zeros(t, roots);
    p = counts_after(t, n, &rest);
    if (p < INT32_MIN || p > INT32_MAX)
        return 1;
    for (r = 0; r < nroots; r++) {
        if (!(roots[r] > -2.0 && roots[r] < (double)n + 2.0))
            continue;
        for (k = (int64_t)floor(roots[r]) - 1; k <= (int64_t)floor(roots[r]) + 2; k++) {
            if (k < 1 || k > n)
                continue;
            p = counts_after(t, k, &rest);
            if (p < INT32_MIN || p > INT32_MAX)
                return 1;
        }
    }
    return 0;
}

/* The state after k integration steps (k < 2^32, in_bounds). The position's
 * whole counts matter mod 2^32 only, its fraction exactly. */
static void advance(PmdTrajectory *t, int64_t k)
{
    i128 rest, counts = counts_after(t, k, &rest);
    u128 v = (u128)velocity_after(t, k), a = (u128)(in33(t->acceleration) + (i128)2 * t->jerk * k);

    t->position = pmd_int32((uint32_t)(u128)counts);
    t->fraction = (int64_t)rest;
    /* two's complement: the shifts floor, the casts keep whole counts mod 2^64 */
    t->velocity.counts = pmd_int64((uint64_t)(v >> PMD_FIXED_BITS));
    t->velocity.fraction = (int64_t)((uint64_t)v & (uint64_t)(PMD_FIXED_ONE - 1));
    t->acceleration.counts = pmd_int64((uint64_t)(a >> PMD_FIXED_BITS));
    t->acceleration.fraction = (int64_t)((uint64_t)a & (uint64_t)(PMD_FIXED_ONE - 1));
}

/* The cycles (at most max) that can be skipped now: PmdRunFacts.skippable, and
 * the exact bounds of every moving axis's segment. A skip never passes a
 * wrap-around of a moving axis whose event bit is clear: it is halved until
 * none is left inside, and the ordinary cycles take the wrap (sample_actual). */
static int64_t skippable(const PmdChip *chip, int64_t max)
{
    int n;
    int64_t k = max;
    if (!pmd_chip_run_facts(chip).skippable)
        return 0;
    for (n = 0; n < PMD_AXES && k > 0; n++) {
        const PmdAxis *ax = &chip->s.axis[n];
        if (ax->motion == PMD_MOTION_IDLE)
            continue;
        if ((int64_t)ax->segmentTime < k)       /* the cycle with segment time 0 reads: not skipped */
            k = ax->segmentTime;
        if (k > 0) {
            if (!in_bounds(&ax->trajectory, k))      /* before first_rest: its products must fit */
                return 0;
            k = first_rest(&ax->trajectory, k) - 1;
            if (!(ax->eventStatus & PMDEventWrapAroundMask))
                while (k > 0 && leaves_int32(&ax->trajectory, k))
                    k /= 2;
        }
    }
    return k;
}

int64_t pmd_chip_skip_closed_form(PmdChip *chip, int64_t max)
{
    int64_t k = max > 1 ? skippable(chip, max) : 0;
    int n;
    if (k <= 0)
        return 0;
    for (n = 0; n < PMD_AXES; n++) {
        PmdAxis *ax = &chip->s.axis[n];
        if (ax->motion == PMD_MOTION_EXTERNAL) {
            PmdTrajectory before = ax->trajectory;
            advance(&before, k - 1);
            ax->previousActualPosition = before.position;   /* the ideal servo: actual = commanded */
            advance(&ax->trajectory, k);
            ax->actualPosition = ax->trajectory.position;
            ax->segmentTime -= (uint32_t)k;
            ax->settleCount = 0;
        } else {
            /* at rest: the position error is constant; the settle count grows while it is in the window */
            int32_t e = pmd_position_error(ax);
            uint32_t error = e < 0 ? 0u - (uint32_t)e : (uint32_t)e;
            ax->previousActualPosition = ax->actualPosition;
            if (error <= ax->settleWindow)
                ax->settleCount = (uint16_t)(ax->settleCount + k > 0xFFFF ? 0xFFFF : ax->settleCount + k);
            ax->trajectory.acceleration = PMD_FIXED_ZERO;
        }
        /* either way the position error stayed what the last cycle left: the
         * filter's closed form, its output from the last cycle's trajectory */
        pmd_servo_advance(chip, n, k);
    }
    chip->s.nextTime += (uint32_t)k;
    chip->s.time = chip->s.nextTime - 1;
    chip->s.updatedAxes = 0;
    return k;
}
#else
int64_t pmd_chip_skip_closed_form(PmdChip *chip, int64_t max)
{
    (void)chip; (void)max;
    return 0;
}
#endif

/* An attempt at fast-forward (skippable, advance: 128-bit products and
 * divisions, a square root, per moving axis) costs about what a few dozen
 * ordinary cycles do; it is tried only when it could skip at least this many. */
#define FAST_FORWARD_MIN 64
/* Ordinary cycles between attempts that did not pay grow by doubling up to
 * this: a doStep over short segments runs in a few long batches, and one that
 * reaches long segments waits at most about as long again as it has run. */
#define BATCH_MAX ((int64_t)1 << 20)

/* A cheap upper bound on what pmd_chip_skip_closed_form could skip now (at most
 * max): PmdRunFacts.skippable and the least remaining segment time of the
 * moving axes, without the exact bounds; 0 when it cannot apply. */
static int64_t fast_forward_bound(const PmdChip *chip, int64_t max)
{
    int64_t k = max;
    int n;
    if (!pmd_chip_run_facts(chip).skippable)
        return 0;
    for (n = 0; n < PMD_AXES; n++) {
        const PmdAxis *ax = &chip->s.axis[n];
        if (ax->motion != PMD_MOTION_IDLE && (int64_t)ax->segmentTime < k)
            k = ax->segmentTime;
    }
    return k;
}

/* The policy: ordinary cycles in batches (pmd_chip_run_every_cycle), fast-forward after
 * one when the bound says it can pay. Every fast-forward follows an ordinary
 * cycle, as pmd_chip_skip_closed_form asks, and both are exact, so the result is
 * that of pmd_chip_run_every_cycle(chip, cycles, NULL) whichever way the cycles went. */
void pmd_chip_run_fast_forwarding(PmdChip *chip, int64_t cycles)
{
    int64_t batch = 1;
    while (cycles > 0) {
        int64_t m = batch < cycles ? batch : cycles, k = 0;
        /* fewer than FAST_FORWARD_MIN cycles left after the batch: no attempt could pay, so they join it
         * (a host's poll steps a dozen cycles at a time: one batch, not four) */
        if (cycles - m < FAST_FORWARD_MIN)
            m = cycles;
        pmd_chip_run_every_cycle(chip, m, NULL);
        cycles -= m;
        if (cycles > 1 && fast_forward_bound(chip, cycles) >= FAST_FORWARD_MIN)
            k = pmd_chip_skip_closed_form(chip, cycles);
        cycles -= k;
        /* after a skip, one ordinary cycle (a segment read, a motion-complete event) and try again */
        batch = k > 0 ? 1 : (batch < BATCH_MAX ? 2 * batch : BATCH_MAX);
    }
}
