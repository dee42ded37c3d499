/* SPDX-License-Identifier: BSD-2-Clause */
/* S-curve point-to-point (seed 001): jerk-limited, phases I-VII, symmetric
 * deceleration, from rest to rest, ending exactly on the destination.
 *
 * The move is a unit-jerk curve with whole-cycle phase lengths t1, t2, t1, t4,
 * t1, t2, t1, scaled to the distance D. Run with seed 000's recurrence and
 * jerk +1, 0 or -1, the unit curve stays integer in sixths:
 *     p6 += 3 v2 + 3 a + j,   v2 += 2 a + j,   a += j     (p6 = 6P, v2 = 2V)
 * and ends at rest at p6Total = 6 t1 (t1 + t2) (2 t1 + t2 + t4). The move's
 * position is start + D * p6 / p6Total, exact as a rational; its jerk,
 * acceleration and velocity peak at D / (p6Total/6) * (1, t1, t1 (t1 + t2)).
 * The phase lengths are the continuous optimum rounded up, then checked
 * exactly against the limits, so those peaks never exceed them. */
#include <math.h>

#include "scurve.h"
#include "wide.h"

#define MAX_P6 ((int64_t)1 << 62)

/* Phase (1..7) of the cycle that executes step `step`. */
static int phase_of(const PmdSCurve *c, int64_t step)
{
    int64_t b[7];
    int k;
    b[0] = c->t1;
    b[1] = b[0] + c->t2;
    b[2] = b[1] + c->t1;
    b[3] = b[2] + c->t4;
    b[4] = b[3] + c->t1;
    b[5] = b[4] + c->t2;
    b[6] = b[5] + c->t1;
    for (k = 0; k < 6 && step >= b[k]; k++)
        ;
    return k + 1;
}

static const int jerk_of_phase[8] = {0, 1, 0, -1, 0, -1, 0, 1};

static int64_t total_steps(const PmdSCurve *c)
{
    return 4 * c->t1 + 2 * c->t2 + c->t4;
}

/* p6Total, or -1 when it would pass 2^62. */
static int64_t p6_total(int64_t t1, int64_t t2, int64_t t4)
{
    double estimate = 6.0 * (double)t1 * (double)(t1 + t2) * (double)(2 * t1 + t2 + t4);
    if (estimate >= (double)MAX_P6 / 2)
        return -1;
    return 6 * t1 * (t1 + t2) * (2 * t1 + t2 + t4);
}

int64_t pmd_scurve_p6_total(int64_t t1, int64_t t2, int64_t t4)
{
    return p6_total(t1, t2, t4);
}

/* The unit curve after c->step steps, phase by phase in closed form: m steps
 * of jerk j from (p6, v2, a) add 3 m v2 + 3 m^2 a + j m^3, 2 m a + j m^2 and
 * j m. The terms are summed modulo 2^64 (unsigned): on the curve every value
 * stays within p6Total < 2^62, so the sums are exact whatever the terms are. */
int pmd_scurve_on_curve(const PmdSCurve *c)
{
    const int64_t length[7] = {c->t1, c->t2, c->t1, c->t4, c->t1, c->t2, c->t1};
    uint64_t p6 = 0, v2 = 0, a = 0, left = (uint64_t)c->step;
    int k;
    for (k = 0; k < 7 && left > 0; k++) {
        uint64_t m = left < (uint64_t)length[k] ? left : (uint64_t)length[k];
        uint64_t j = (uint64_t)(int64_t)jerk_of_phase[k + 1];
        p6 += 3 * m * v2 + 3 * m * m * a + j * m * m * m;
        v2 += 2 * m * a + j * m * m;
        a += j * m;
        left -= m;
    }
    return p6 == (uint64_t)c->p6 && v2 == (uint64_t)c->v2 && a == (uint64_t)c->a;
}

/* Which limit the plan breaks: 1 jerk, 2 acceleration, 3 velocity, 0 none.
 * D * (peak of the unit curve) / (p6Total / 6) <= limit, compared exactly. */
static int broken_limit(uint64_t d, const PmdProfileRegisters *r, int64_t t1, int64_t t2, int64_t p6)
{
    if (!pmd_le128(pmd_mul64(d * 6, (uint64_t)1 << 32), pmd_mul64(r->jerk, (uint64_t)p6)))
        return 1;
    if (!pmd_le128(pmd_mul64(d << 16, (uint64_t)(6 * t1)), pmd_mul64(r->acceleration, (uint64_t)p6)))
        return 2;
    if (!pmd_le128(pmd_mul64(d << 16, (uint64_t)(6 * t1 * (t1 + t2))), pmd_mul64((uint64_t)r->velocity, (uint64_t)p6)))
        return 3;
    return 0;
}

static int64_t whole_cycles(double t)
{
    return t > 0 ? (int64_t)ceil(t - 1e-9) : 0;
}

/* Plans a move from the axis's commanded position to r->position. Returns 0
 * (plan filled in) or an error code; changes nothing else. */
int pmd_scurve_plan(const PmdChip *chip, int n, const PmdProfileRegisters *r, PmdSCurve *plan)
{
    const PmdAxis *ax = &chip->s.axis[n];
    int64_t distance = (int64_t)r->position - ax->trajectory.position;
    double d = fabs((double)distance), jerk = r->jerk / 4294967296.0, acc = r->acceleration / 65536.0;
    double vel = r->velocity / 65536.0, t1, t2 = 0, t4 = 0;
    int64_t p6 = 0;
    int broken, tries;

    plan->step = plan->p6 = plan->v2 = plan->a = 0;
    plan->distance = distance;
    plan->start = ax->trajectory.position;
    plan->stopping = 0;
    plan->t1 = plan->t2 = plan->t4 = 0;
    plan->p6Total = 0;
    if (distance == 0)
        return 0;
    if (r->jerk == 0 || r->acceleration == 0 || r->velocity <= 0) {
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: S-curve needs jerk, acceleration and velocity above 0", n + 1);
        return PMD_ERR_InvalidParameter;
    }
    /* the continuous optimum (seed 001: phases I-VII) */
    if (vel * jerk >= acc * acc) {
        t1 = acc / jerk;
        t2 = vel / acc - t1;
    } else {
        t1 = sqrt(vel / jerk);
    }
    if (d >= vel * (2 * t1 + t2)) {
        t4 = d / vel - (2 * t1 + t2);
    } else {
        t1 = acc / jerk;                          /* maximum velocity not reached */
        t2 = (-3 * t1 + sqrt(t1 * t1 + 4 * d / acc)) / 2;
        if (t2 < 0 || vel * jerk < acc * acc) {   /* nor the maximum acceleration */
            t2 = 0;
            t1 = cbrt(d / (2 * jerk));
        }
    }
    plan->t1 = whole_cycles(t1) > 0 ? whole_cycles(t1) : 1;
    plan->t2 = whole_cycles(t2);
    plan->t4 = whole_cycles(t4);
    for (tries = 0; tries < 4096; tries++) {
        p6 = p6_total(plan->t1, plan->t2, plan->t4);
        if (p6 < 0)
            break;
        broken = broken_limit((uint64_t)(distance < 0 ? -distance : distance), r, plan->t1, plan->t2, p6);
        if (!broken) {
            plan->p6Total = p6;
            return 0;
        }
        if (broken == 1)
            plan->t1++;
        else if (broken == 2)
            plan->t2++;
        else
            plan->t4++;
    }
    pmd_log(chip, PMD_LOG_ERRORS, "axis %d: S-curve of %lld counts at these limits is too long to plan exactly "
            "(6 t1 (t1+t2) (2t1+t2+t4) must stay below 2^62)", n + 1, (long long)distance);
    return PMD_ERR_InvalidParameter;
}

/* floor(sign * a * m / c) for a, c > 0. */
static int64_t scaled_floor(int negative, uint64_t a, int64_t m, uint64_t c)
{
    uint64_t rem, q = pmd_muldiv(a, (uint64_t)(m < 0 ? -m : m), c, &rem);
    if (negative != (m < 0))
        return -(int64_t)q - (rem != 0);
    return (int64_t)q;
}

/* Arrived: at rest, no phase shown; the caller ends the motion (pmd_halt). */
static int finish(PmdAxis *ax)
{
    ax->trajectory.velocity = ax->trajectory.acceleration = PMD_FIXED_ZERO;
    ax->scurvePhase = 0;
    return 1;
}

int pmd_scurve_cycle(PmdChip *chip, int n)
{
    PmdAxis *ax = &chip->s.axis[n];
    PmdSCurve *c = &ax->scurve;
    PmdTrajectory *t = &ax->trajectory;
    int negative = c->distance < 0;
    uint64_t d = (uint64_t)(negative ? -c->distance : c->distance), rem, q;
    int phase = phase_of(c, c->step), j = jerk_of_phase[phase];

    if (c->p6Total == 0)                         /* already there */
        return finish(ax);
    c->p6 += 3 * c->v2 + 3 * c->a + j;
    c->v2 += 2 * c->a + j;
    c->a += j;
    c->step++;

    /* the registers: truncated toward minus infinity (CONTRACT 2.3) */
    q = pmd_muldiv(d, (uint64_t)c->p6, (uint64_t)c->p6Total, &rem);
    if (negative && rem) {
        q++;
        rem = (uint64_t)c->p6Total - rem;
    }
    t->position = pmd_int32((uint32_t)c->start + (uint32_t)(negative ? -(int64_t)q : (int64_t)q));
    t->fraction = (int64_t)pmd_muldiv(rem, (uint64_t)PMD_U_PER_COUNT, (uint64_t)c->p6Total, &rem);
    t->velocity = pmd_fixed_from_1616(scaled_floor(negative, d << 16, 3 * c->v2, (uint64_t)c->p6Total));
    t->acceleration = pmd_fixed_from_1616(scaled_floor(negative, d << 16, 6 * c->a, (uint64_t)c->p6Total));
    t->jerk = 0;
    ax->atMaximumVelocity = phase == 4;
    ax->scurvePhase = (uint8_t)phase;
    if (c->step == total_steps(c)) {
        if (!c->stopping) {
            t->position = pmd_int32((uint32_t)c->start + (uint32_t)c->distance);   /* exactly the destination */
            t->fraction = 0;
        }
        return finish(ax);
    }
    return 0;
}

/* A smooth stop leaves out what is left of the cruise: the deceleration
 * phases V-VII follow at once (after phase III if still accelerating), so the
 * axis comes to rest jerk-limited, short of the destination. */
void pmd_scurve_smooth_stop(PmdAxis *ax)
{
    PmdSCurve *c = &ax->scurve;
    int64_t cruise_start = 2 * c->t1 + c->t2;
    if (c->step < cruise_start)
        c->t4 = 0;
    else if (c->step < cruise_start + c->t4)
        c->t4 = c->step - cruise_start;
    c->stopping = 1;
}
