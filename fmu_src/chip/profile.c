/* The trajectory generator: external profile (seed 000), trapezoidal
 * point-to-point, stops and Update. All arithmetic is exact (chip_types.h). */
#include "chip.h"

/* ---- exact arithmetic ---------------------------------------------------- */

static int64_t floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

/* Two's-complement wrap of a 64-bit value into a 32-bit register, without
 * relying on implementation-defined conversions. */
static int32_t wrap32(int64_t x)
{
    return pmd_int32((uint32_t)((uint64_t)x & 0xFFFFFFFFu));
}

/* Wrapping add: a host can integrate a segment past any register range; the
 * chip's registers wrap, and so do we, without undefined behaviour. */
static int64_t wadd(int64_t a, int64_t b)
{
    uint64_t u = (uint64_t)a + (uint64_t)b;
    return u <= (uint64_t)INT64_MAX ? (int64_t)u : -(int64_t)(~u) - 1;
}

/* Moves the exact position by dp units U. */
static void move_by(PmdTrajectory *t, int64_t dp)
{
    int64_t carry = floor_div(dp, PMD_U_PER_COUNT);
    t->fraction += dp - carry * PMD_U_PER_COUNT;
    if (t->fraction >= PMD_U_PER_COUNT) {
        t->fraction -= PMD_U_PER_COUNT;
        carry++;
    }
    t->position = wrap32((int64_t)t->position + carry);
}

int32_t pmd_commanded_velocity(const PmdTrajectory *t)
{
    return wrap32(floor_div(t->velocity, PMD_U_PER_1616));
}

int32_t pmd_commanded_acceleration(const PmdTrajectory *t)
{
    return wrap32(floor_div(t->acceleration, PMD_U_PER_1616));
}

/* ---- external profile (seed 000) ----------------------------------------- */

static void halt(PmdChip *chip, int n)
{
    PmdAxis *ax = &chip->s.axis[n];
    if (ax->motion != PMD_MOTION_IDLE)
        pmd_set_event(chip, n, PMDEventMotionCompleteMask);
    ax->motion = PMD_MOTION_IDLE;
    ax->segmentTime = 0;
    ax->atMaximumVelocity = 0;
}

void pmd_abrupt_stop(PmdChip *chip, int n)
{
    PmdTrajectory *t = &chip->s.axis[n].trajectory;
    /* Reference 5, stops: velocity zeroed at once, commanded position held. */
    t->velocity = 0;
    t->acceleration = 0;
    t->jerk = 0;
    halt(chip, n);
}

/* The buffers an external profile may start on: a position buffer, and every
 * assigned buffer of the same non-zero length (seed 000: "each buffer must
 * have the same length"). */
static int external_buffers_ok(const PmdChip *chip, const PmdAxis *ax)
{
    int f, position = ax->bufferOfFunction[PMDBufferFunctionPosition];
    if (position < 0)
        return 0;
    for (f = 0; f < PMD_FUNCTIONS; f++) {
        int id = ax->bufferOfFunction[f];
        if (id >= 0 && (chip->s.buffer[id].length == 0 ||
                        chip->s.buffer[id].length != chip->s.buffer[position].length))
            return 0;
    }
    return 1;
}

/* Reads one segment: the entry at the position buffer's read index from every
 * assigned buffer ("corresponding entries are located at the same offset");
 * all their read indexes then move past it together, wrapping at the length.
 * Absent velocity, acceleration, jerk read 0; an absent time reads 1. */
static int read_segment(PmdChip *chip, int n, int32_t value[PMD_FUNCTIONS])
{
    PmdAxis *ax = &chip->s.axis[n];
    const PmdBuffer *pos;
    uint32_t offset;
    int f;

    if (!external_buffers_ok(chip, ax)) {
        pmd_log(chip, PMD_LOG_WARNINGS, "axis %d: external profile buffers changed while running "
                "(position buffer missing or lengths differ): profile halted", n + 1);
        return 0;
    }
    pos = &chip->s.buffer[ax->bufferOfFunction[PMDBufferFunctionPosition]];
    offset = pos->readIndex;
    if (pos->streamed && pos->unread == 0) {
        if (!ax->underrunWarned)
            pmd_log(chip, PMD_LOG_WARNINGS, "axis %d: external profile read index %u of buffer %d overtakes its "
                    "write index: reading old data, as the chip does", n + 1, (unsigned)offset,
                    ax->bufferOfFunction[PMDBufferFunctionPosition]);
        ax->underrunWarned = 1;
    } else {
        ax->underrunWarned = 0;
    }
    for (f = 0; f < PMD_FUNCTIONS; f++) {
        int id = ax->bufferOfFunction[f];
        value[f] = f == PMDBufferFunctionTime ? 1 : 0;
        if (id >= 0)
            value[f] = (int32_t)chip->memory[chip->s.buffer[id].start + offset];
    }
    for (f = 0; f < PMD_FUNCTIONS; f++) {
        int id = ax->bufferOfFunction[f];
        if (id >= 0) {
            PmdBuffer *b = &chip->s.buffer[id];
            b->readIndex = offset + 1 == b->length ? 0 : offset + 1;
            if (b->unread > 0)
                b->unread--;
        }
    }
    pmd_log(chip, PMD_LOG_SEGMENTS, "axis %d: segment at index %u: position %d velocity %d acceleration %d "
            "jerk %d time %u", n + 1, (unsigned)offset, value[0], value[1], value[2], value[3], (unsigned)value[4]);
    return 1;
}

static void integrate(PmdTrajectory *t)
{
    int64_t j = t->jerk;
    move_by(t, wadd(wadd(t->velocity, t->acceleration / 2), j));    /* P += V + A/2 + J/6 */
    t->velocity = wadd(t->velocity, wadd(t->acceleration, 3 * j));   /* V += A + J/2 */
    t->acceleration = wadd(t->acceleration, 6 * j);                   /* A += J */
}

/* One cycle of seed 000's pseudo code. The decrement closes every cycle that
 * does not stop, so a segment with time T lasts T cycles: the read cycle and
 * T-1 integration cycles (the worked table, chip times 11003..11013). */
static void external_cycle(PmdChip *chip, int n)
{
    PmdAxis *ax = &chip->s.axis[n];
    PmdTrajectory *t = &ax->trajectory;
    int64_t before = t->velocity;

    if (ax->segmentTime == 0) {
        int32_t v[PMD_FUNCTIONS];
        if (!read_segment(chip, n, v)) {
            pmd_abrupt_stop(chip, n);
            return;
        }
        t->position = v[PMDBufferFunctionPosition];
        t->fraction = 0;
        t->velocity = (int64_t)v[PMDBufferFunctionVelocity] * PMD_U_PER_1616;
        t->acceleration = (int64_t)v[PMDBufferFunctionAcceleration] * PMD_U_PER_1616;
        t->jerk = v[PMDBufferFunctionJerk];
        ax->segmentTime = (uint32_t)v[PMDBufferFunctionTime];
        if (ax->segmentTime == 0) {
            /* StopTrajectory(): this row's position is held, the axis stationary (seed 000, 1.5). */
            pmd_log(chip, PMD_LOG_EVENTS, "axis %d: external profile read time 0: halted", n + 1);
            pmd_abrupt_stop(chip, n);
            return;
        }
    } else {
        integrate(t);
    }
    ax->segmentTime--;
    /* Seed 000, 1.6: in external mode the motion-complete bit is set whenever
     * the axis comes to rest, which may happen many times in one profile. */
    if (before != 0 && t->velocity == 0)
        pmd_set_event(chip, n, PMDEventMotionCompleteMask);
}

/* ---- trapezoidal point-to-point ------------------------------------------ */

/* Distance, in 16.16 units, covered by moving x this cycle and then braking
 * by d per cycle to rest: x + (x-d) + (x-2d) + ... while positive. With
 * x = q*d + r this is (q+1)*x - d*q*(q+1)/2. x < 2^31 keeps it below 2^62. */
static int64_t run_out(int64_t x, int64_t d)
{
    int64_t q;
    if (x <= 0)
        return 0;
    if (x >= ((int64_t)1 << 31))
        return INT64_MAX;
    q = x / d;
    return (q + 1) * x - d * (q * (q + 1) / 2);
}

static int64_t min64(int64_t a, int64_t b) { return a < b ? a : b; }
static int64_t max64(int64_t a, int64_t b) { return a > b ? a : b; }

/* One cycle of the trapezoidal generator in 16.16 units. The velocity for
 * this cycle is the largest one that respects the maximum velocity and the
 * acceleration, and from which braking at the deceleration still stops at or
 * before the destination; the last cycles therefore cover exactly the
 * remaining distance and the move ends on the destination, at rest. A move
 * heading away from the destination, or unable to stop before it, brakes
 * first and comes back. */
static void trapezoidal_cycle(PmdChip *chip, int n)
{
    PmdAxis *ax = &chip->s.axis[n];
    PmdTrajectory *t = &ax->trajectory;
    const PmdProfileRegisters *r = &ax->active;
    int64_t acc = r->acceleration, dec = r->deceleration ? r->deceleration : r->acceleration;
    int64_t vmax = r->velocity;
    int64_t p = (int64_t)t->position * 65536 + t->fraction / PMD_U_PER_1616;
    int64_t v = floor_div(t->velocity, PMD_U_PER_1616);
    int64_t dest = (int64_t)r->position * 65536;
    int64_t d = dest - p;
    int64_t s = d > 0 ? 1 : d < 0 ? -1 : (v >= 0 ? 1 : -1);   /* frame in which the destination is ahead */
    int64_t dist = s * d, w = s * v, w2;

    if (dec == 0) {
        w2 = w;                                   /* no acceleration: the velocity cannot change */
    } else if (ax->motion == PMD_MOTION_SMOOTH_STOP) {
        w2 = w > 0 ? max64(w - dec, 0) : min64(w + dec, 0);
    } else if (w < 0) {
        w2 = min64(w + dec, 0);
    } else if (run_out(w, dec) - w > dist) {
        w2 = max64(w - dec, 0);
    } else {
        int64_t c = w <= vmax ? min64(w + acc, vmax) : max64(w - dec, vmax);
        if (run_out(c, dec) <= dist) {
            w2 = c;
        } else {
            /* run_out(w - dec) = run_out(w) - w <= dist: the braking velocity always fits. */
            int64_t lo = max64(w - dec, 0), hi = c;
            while (hi - lo > 1) {
                int64_t mid = lo + (hi - lo) / 2;
                if (run_out(mid, dec) <= dist)
                    lo = mid;
                else
                    hi = mid;
            }
            w2 = lo;
        }
    }
    move_by(t, s * w2 * PMD_U_PER_1616);
    t->velocity = s * w2 * PMD_U_PER_1616;
    t->acceleration = (s * w2 - v) * PMD_U_PER_1616;
    t->jerk = 0;
    ax->atMaximumVelocity = w2 == vmax && vmax > 0;
    if (p + s * w2 == dest)
        t->fraction = 0;                          /* landed: drop any sub-16.16 remainder */
    if (w2 == 0 && (ax->motion == PMD_MOTION_SMOOTH_STOP || p == dest)) {
        pmd_log(chip, PMD_LOG_EVENTS, "axis %d: motion complete at %d", n + 1, t->position);
        halt(chip, n);
    }
}

void pmd_profile_cycle(PmdChip *chip, int n)
{
    switch (chip->s.axis[n].motion) {
    case PMD_MOTION_EXTERNAL:
        external_cycle(chip, n);
        break;
    case PMD_MOTION_TRAPEZOIDAL:
    case PMD_MOTION_SMOOTH_STOP:
        trapezoidal_cycle(chip, n);
        break;
    default:
        /* at rest: the braking of the last moving cycle is over */
        chip->s.axis[n].trajectory.acceleration = 0;
        break;
    }
}

/* ---- Update ---------------------------------------------------------------- */

/* Copies the buffered registers to the active set and starts or stops the
 * profile they describe. A refused Update changes nothing. */
int pmd_update(PmdChip *chip, int n)
{
    PmdAxis *ax = &chip->s.axis[n];
    const PmdProfileRegisters *b = &ax->buffered;
    uint16_t stop = b->stopMode;

    if (stop == PMDNoStopMode && b->profileMode == PMDTrapezoidalProfile && b->velocity < 0) {
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: Update: negative velocity %d in trapezoidal mode", n + 1, b->velocity);
        return PMD_ERR_InvalidNegativeValue;
    }
    if (stop == PMDNoStopMode && b->profileMode == PMDExternalProfile && ax->motion != PMD_MOTION_EXTERNAL &&
        !external_buffers_ok(chip, ax)) {
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: Update: external profile needs a position buffer, and every "
                "assigned buffer of the same non-zero length", n + 1);
        return PMD_ERR_InvalidParameter;
    }
    ax->active = *b;
    ax->active.stopMode = PMDNoStopMode;
    ax->buffered.stopMode = PMDNoStopMode;      /* reference 4.1: the stop mode resets itself */

    if (stop == PMDAbruptStopMode) {
        pmd_abrupt_stop(chip, n);
    } else if (stop == PMDSmoothStopMode) {
        /* Seed 000, 1.5: a smooth stop changes nothing in external mode. */
        if (ax->motion == PMD_MOTION_TRAPEZOIDAL)
            ax->motion = PMD_MOTION_SMOOTH_STOP;
    } else if (b->profileMode == PMDExternalProfile) {
        if (ax->motion != PMD_MOTION_EXTERNAL) {
            ax->motion = PMD_MOTION_EXTERNAL;
            ax->segmentTime = 0;                 /* the first cycle reads a segment */
            ax->underrunWarned = 0;
        }
    } else {
        ax->motion = PMD_MOTION_TRAPEZOIDAL;
    }
    return 0;
}
