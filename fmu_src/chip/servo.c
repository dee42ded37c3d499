/* SPDX-License-Identifier: BSD-2-Clause */
/* The servo filter and the motor output (seed 001: "PID + velocity
 * feedforward and motor bias", closed and open loop; reference 1.2 for the
 * registers and their scalings). The formula, its integer arithmetic and the
 * confidence of each choice: docs/decisions.md, "Servo filter and motor
 * output"; tests/reference.py's ServoFilter is the same page in Python.
 *
 * Closed loop (motor on), every cycle, E = commanded - actual (32-bit wrap):
 *   I = clamp(I + E, -integrationLimit, +integrationLimit)
 *   every derivativeTime cycles: D = sat16(E - E at the previous sample), held between
 *   S = sat32(Kp E + Kd D + floor(Ki I / 2^8) + floor(Kvff V / 2^16) + floor(Kaff A / 2^16))
 *   output = clamp(floor(Kout S / 2^16) + motorBias, -motorLimit, +motorLimit)
 * with V and A the commanded velocity and acceleration registers (16.16).
 * Open loop (motor off): output = the motor command register; the integral and
 * the derivative are 0 and the derivative's history follows the error, so the
 * loop closes again without a kick. */
#include "servo.h"
#include "status.h"

static inline int64_t clamp64(int64_t x, int64_t low, int64_t high)
{
    return x < low ? low : x > high ? high : x;
}

/* The registers' ranges (registers.csv) bound these; a value beyond them can
 * only come from a forged state, and changes nothing but the clamp. */
static inline int64_t integration_limit(const PmdFilterRegisters *r)
{
    return r->integrationLimit > (uint32_t)INT32_MAX ? INT32_MAX : (int64_t)r->integrationLimit;
}

static inline int64_t motor_limit(const PmdAxis *ax)
{
    return ax->motorLimit > INT16_MAX ? INT16_MAX : (int64_t)ax->motorLimit;
}

/* The closed loop's motor command from the filter's state and the error e.
 * Every product fits an int64: |Kp E| < 2^47, |Ki I| < 2^47, |Kvff V| < 2^47,
 * and after the sum's saturation |Kout S| < 2^47. */
static inline int16_t closed_loop_output(const PmdAxis *ax, int32_t e)
{
    const PmdFilter *f = &ax->filter;
    const PmdFilterRegisters *r = &f->active;
    int64_t s = (int64_t)r->kp * e + (int64_t)r->kd * f->derivative + pmd_floor_shift((int64_t)r->ki * f->integral, 8);
    if (r->kvff | r->kaff)
        s += pmd_floor_shift((int64_t)r->kvff * pmd_commanded_velocity(&ax->trajectory), 16) +
             pmd_floor_shift((int64_t)r->kaff * pmd_commanded_acceleration(&ax->trajectory), 16);
    s = clamp64(s, INT32_MIN, INT32_MAX);
    return (int16_t)clamp64(pmd_floor_shift((int64_t)r->kout * s, 16) + ax->motorBias, -motor_limit(ax),
                            motor_limit(ax));
}

static inline int16_t saturate16(int64_t x)
{
    return (int16_t)clamp64(x, INT16_MIN, INT16_MAX);
}

/* Open loop: the host's motor command, no bias, no limit; the filter waits. */
static void open_loop(PmdAxis *ax)
{
    PmdFilter *f = &ax->filter;
    f->integral = 0;
    f->derivative = 0;
    f->derivativeError = pmd_servo_error(ax);
    f->derivativeCount = 0;
    f->output = f->active.motorCommand;
}

/* The closed loop's cycle (e: this cycle's error). */
static void closed_loop_cycle(PmdAxis *ax, int32_t e)
{
    PmdFilter *f = &ax->filter;
    int64_t limit = integration_limit(&f->active);
    unsigned count = f->derivativeCount + 1u;
    if (e != 0 || f->integral > limit || f->integral < -limit)
        f->integral = (int32_t)clamp64((int64_t)f->integral + e, -limit, limit);
    if (count >= f->active.derivativeTime) {      /* a sample every derivativeTime cycles */
        f->derivative = saturate16((int64_t)e - f->derivativeError);
        f->derivativeError = e;
        count = 0;
    }
    f->derivativeCount = (uint16_t)count;
    f->output = closed_loop_output(ax, e);
}

void pmd_servo_cycle(PmdChip *chip, int n)
{
    PmdAxis *ax = &chip->s.axis[n];
    if (ax->motorOn)
        closed_loop_cycle(ax, pmd_servo_error(ax));
    else
        open_loop(ax);
}

void pmd_servo_advance(PmdChip *chip, int n, int64_t k)
{
    PmdAxis *ax = &chip->s.axis[n];
    PmdFilter *f = &ax->filter;
    int64_t limit = integration_limit(&f->active);
    uint64_t period = f->active.derivativeTime ? f->active.derivativeTime : 1u, samples = 0, count;
    int32_t e;
    if (!ax->motorOn) {
        open_loop(ax);                 /* a function of the error alone, which stays */
        return;
    }
    e = pmd_servo_error(ax);
    if (k <= 1) {
        closed_loop_cycle(ax, e);
        return;
    }
    /* The first cycle's clamp brings I within the limit; from there the sum
     * moves straight toward the limit in e's direction, so the rest is
     * I + (k - 1) e clamped once. Beyond 2^32 cycles any e != 0 has reached
     * it (2 limit < 2^32). */
    f->integral = (int32_t)clamp64((int64_t)f->integral + e, -limit, limit);
    if (e != 0)
        f->integral = (int32_t)(k > ((int64_t)1 << 32) ? (e > 0 ? limit : -limit)
                                                       : clamp64((int64_t)f->integral + (k - 1) * e, -limit, limit));
    /* One sample each time the count, plus one a cycle, reaches the period;
     * a count already at or past it (the period just lowered) samples at once. */
    count = f->derivativeCount;
    if (count + 1u >= period) {
        samples = 1;
        count = 0;
        k--;
    }
    samples += (count + (uint64_t)k) / period;
    f->derivativeCount = (uint16_t)((count + (uint64_t)k) % period);
    if (samples >= 1) {
        f->derivative = samples >= 2 ? 0 : saturate16((int64_t)e - f->derivativeError);
        f->derivativeError = e;
    }
    f->output = closed_loop_output(ax, e);
}
