/* Fast-forward: many chip cycles at once, bit-identical to running them one
 * by one, when nothing needs individual cycles.
 *
 * Inside an external-profile segment seed 000's recurrence has an exact
 * closed form in the units of chip_types.h: after n integration steps from
 * (P, V, A) with jerk j,
 *     P += n V + n^2 A / 2 + j n^3,   V += n A + 3 j n^2,   A += 6 j n.
 * So a run of cycles in which every axis is idle or integrating inside a
 * segment, no breakpoint is armed, no trace runs and the servo is ideal (the
 * position error stays 0) costs a few multiplications per axis instead of one
 * step per cycle. Anything else - a segment read, a velocity coming to rest
 * (an event), a value that could wrap - is left to the ordinary cycle.
 *
 * It needs 128-bit integers; without them it skips nothing, which is the
 * portable fallback: the same results, cycle by cycle. */
#include <math.h>

#include "chip.h"

#if defined(__SIZEOF_INT128__) && defined(__GNUC__) && !defined(PMD_PORTABLE_WIDE)
__extension__ typedef __int128 i128;

#define LIMIT62 ((i128)1 << 62)

static i128 velocity_after(const PmdTrajectory *t, int64_t k)
{
    return (i128)t->velocity + (i128)k * t->acceleration + (i128)3 * t->jerk * k * k;
}

/* Displacement of k integration steps, in U (exact while |V| < 2^62 on the way). */
static i128 displacement(const PmdTrajectory *t, int64_t k)
{
    i128 kk = (i128)k * k;
    return (i128)k * t->velocity + kk * (t->acceleration / 2) + kk * k * t->jerk;
}

/* The first step k in 1..n at which the velocity becomes exactly 0 from a
 * non-zero value (an external profile's motion-complete event), or n + 1. */
static int64_t first_rest(const PmdTrajectory *t, int64_t n)
{
    double a = 3.0 * t->jerk, b = (double)t->acceleration, c = (double)t->velocity, roots[2];
    int r, nroots = 0;
    int64_t best = n + 1, k;
    if (t->velocity == 0 && t->acceleration == 0 && t->jerk == 0)
        return n + 1;
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

/* Whether |V| and |A| stay below 2^62 over steps 0..n (V is quadratic in k:
 * its extremes are at the ends or the vertex). */
static int stays_small(const PmdTrajectory *t, int64_t n)
{
    i128 v0 = velocity_after(t, 0), vn = velocity_after(t, n), an = (i128)t->acceleration + (i128)6 * t->jerk * n;
    if (v0 <= -LIMIT62 || v0 >= LIMIT62 || vn <= -LIMIT62 || vn >= LIMIT62 || an <= -LIMIT62 || an >= LIMIT62)
        return 0;
    if (t->jerk != 0) {
        double vertex = -(double)t->acceleration / (6.0 * t->jerk);
        if (vertex > 0 && vertex < (double)n) {
            i128 v = velocity_after(t, (int64_t)vertex);
            if (v <= -LIMIT62 || v >= LIMIT62)
                return 0;
        }
    }
    return 1;
}

static void advance(PmdTrajectory *t, int64_t k)
{
    const i128 u = (i128)PMD_U_PER_COUNT;
    i128 total = (i128)t->position * u + t->fraction + displacement(t, k);
    i128 counts = total / u, fraction = total % u;
    if (fraction < 0) {
        fraction += u;
        counts--;
    }
    t->position = pmd_int32((uint32_t)((uint64_t)counts & 0xFFFFFFFFu));
    t->fraction = (int64_t)fraction;
    t->velocity = (int64_t)velocity_after(t, k);
    t->acceleration += 6 * (int64_t)t->jerk * k;
}

/* The cycles (at most max) that can be skipped now. */
static int64_t skippable(const PmdChip *chip, int64_t max)
{
    int n, i;
    int64_t k = max;
    if (chip->s.trace.active || chip->s.trace.start)
        return 0;
    for (n = 0; n < PMD_AXES && k > 0; n++) {
        const PmdAxis *ax = &chip->s.axis[n];
        for (i = 0; i < 2; i++)
            if (ax->breakpoint[i].trigger != PMDBreakpointDisable)
                return 0;
        if (ax->motionCompletePending)
            return 0;
        if (ax->motion == PMD_MOTION_IDLE)
            continue;
        if (ax->motion != PMD_MOTION_EXTERNAL || !chip->s.loopback || !ax->motorOn)
            return 0;
        if ((int64_t)ax->segmentTime < k)       /* the cycle with segment time 0 reads: not skipped */
            k = ax->segmentTime;
        if (k > 0) {
            k = first_rest(&ax->trajectory, k) - 1;
            if (k > 0 && !stays_small(&ax->trajectory, k))
                return 0;
        }
    }
    return k;
}

int64_t pmd_chip_fast_forward(PmdChip *chip, int64_t max)
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
            ax->trajectory.acceleration = 0;
        }
    }
    chip->s.nextTime += (uint32_t)k;
    chip->s.time = chip->s.nextTime - 1;
    chip->s.updatedAxes = 0;
    return k;
}
#else
int64_t pmd_chip_fast_forward(PmdChip *chip, int64_t max)
{
    (void)chip; (void)max;
    return 0;
}
#endif
