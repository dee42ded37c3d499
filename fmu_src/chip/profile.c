/* SPDX-License-Identifier: BSD-2-Clause */
/* The trajectory generator: external profile (seed 000), trapezoidal
 * point-to-point, stops and Update. All arithmetic is exact (chip_types.h). */
#include "events.h"
#include "profile.h"
#include "scurve.h"

/* ---- exact arithmetic (chip_types.h) --------------------------------------- */

/* Moves the exact position by x / 2^16 counts (a 16.16 value of any size):
 * the whole counts wrap like the register, the rest joins the fraction. */
static void move_by_1616(PmdTrajectory *t, int64_t x)
{
    int64_t f = t->fraction + (int64_t)((uint64_t)x & 0xFFFFu) * PMD_U_PER_1616;
    uint32_t carry = f >= PMD_U_PER_COUNT;
    t->fraction = f - (carry ? PMD_U_PER_COUNT : 0);
    t->position = pmd_int32((uint32_t)t->position + (uint32_t)pmd_floor_shift(x, 16) + carry);
}

/* ---- external profile (seed 000) ----------------------------------------- */

/* Motion complete (reference 4.5): at once in mode 0 (commanded); in mode 1
 * (actual) once the axis has settled, which the cycle checks. */
void pmd_motion_complete(PmdChip *chip, int n)
{
    if (chip->s.axis[n].motionCompleteMode == PMDMotionCompleteActualPosition)
        chip->s.axis[n].motionCompletePending = 1;
    else
        pmd_set_event(chip, n, PMDEventMotionCompleteMask);
}

void pmd_halt(PmdChip *chip, int n)
{
    PmdAxis *ax = &chip->s.axis[n];
    if (ax->motion != PMD_MOTION_IDLE)
        pmd_motion_complete(chip, n);
    ax->motion = PMD_MOTION_IDLE;
    ax->segmentTime = 0;
    ax->atMaximumVelocity = 0;
}

void pmd_abrupt_stop(PmdChip *chip, int n)
{
    PmdTrajectory *t = &chip->s.axis[n].trajectory;
    /* Reference 5, stops: velocity zeroed at once, commanded position held. */
    t->velocity = PMD_FIXED_ZERO;
    t->acceleration = PMD_FIXED_ZERO;
    t->jerk = 0;
    pmd_halt(chip, n);
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

/* Notes where each function's value lives and which distinct buffers a
 * segment read moves (buffers may share an ID): read_segment then costs a
 * load per function. Redone whenever the buffer set-up changes. */
static void plan_reads(const PmdChip *chip, PmdAxis *ax)
{
    int f, i;
    ax->segmentFunctions = 0;
    ax->segmentBufferCount = 0;
    for (f = 0; f < PMD_FUNCTIONS; f++) {
        int id = ax->bufferOfFunction[f];
        ax->segmentStart[f] = id >= 0 ? chip->s.buffer[id].start : 0;
        if (id < 0)
            continue;
        ax->segmentFunctions |= (uint8_t)(1u << f);
        for (i = 0; i < ax->segmentBufferCount && ax->segmentBuffer[i] != id; i++)
            ;
        if (i == ax->segmentBufferCount)
            ax->segmentBuffer[ax->segmentBufferCount++] = (uint8_t)id;
    }
}

/* Whether axis n's segment plan is what its buffers give now: a restored FMU
 * state that says its plan is current must not read elsewhere (state.c). */
int pmd_segment_plan_valid(const PmdChip *chip, int n)
{
    const PmdAxis *ax = &chip->s.axis[n];
    PmdAxis plan = *ax;
    int f;
    if (!external_buffers_ok(chip, ax))
        return 0;
    plan_reads(chip, &plan);
    for (f = 0; f < PMD_FUNCTIONS; f++)
        if (plan.segmentStart[f] != ax->segmentStart[f] || (f < plan.segmentBufferCount &&
                                                             plan.segmentBuffer[f] != ax->segmentBuffer[f]))
            return 0;
    return plan.segmentFunctions == ax->segmentFunctions && plan.segmentBufferCount == ax->segmentBufferCount;
}

/* Reads one segment: the entry at the position buffer's read index from every
 * assigned buffer ("corresponding entries are located at the same offset");
 * all their read indexes then move past it together, wrapping at the (common)
 * length. Absent velocity, acceleration, jerk read 0; an absent time reads 1. */
static int read_segment(PmdChip *chip, int n, int32_t value[PMD_FUNCTIONS])
{
    PmdAxis *ax = &chip->s.axis[n];
    const PmdBuffer *pos;
    uint32_t offset, next;
    int f, i;

    /* buffers checked again only after a set-up or assignment changed (the epoch moved) */
    if (ax->buffersChecked != chip->s.bufferEpoch + 1) {
        if (!external_buffers_ok(chip, ax)) {
            pmd_log(chip, PMD_LOG_WARNINGS, "axis %d: external profile buffers changed while running "
                    "(position buffer missing or lengths differ): profile halted", n + 1);
            return 0;
        }
        plan_reads(chip, ax);
        ax->buffersChecked = chip->s.bufferEpoch + 1;
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
    /* every value is read before any index moves; without a branch per
     * function: an absent function's word (segmentStart 0) is read too, and
     * is in the memory (offset < the position buffer's end), then not used */
    for (f = 0; f < PMD_FUNCTIONS; f++) {
        int32_t word = (int32_t)chip->memory[ax->segmentStart[f] + offset];
        value[f] = (ax->segmentFunctions >> f) & 1 ? word : (f == PMDBufferFunctionTime ? 1 : 0);
    }
    next = offset + 1 == pos->length ? 0 : offset + 1;
    for (i = 0; i < ax->segmentBufferCount; i++) {
        PmdBuffer *b = &chip->s.buffer[ax->segmentBuffer[i]];
        b->readIndex = next;
        if (b->unread > 0)
            b->unread--;
    }
    if (PMD_LOGGING(chip, PMD_LOG_SEGMENTS))
        pmd_log(chip, PMD_LOG_SEGMENTS, "axis %d: segment at index %u: position %d velocity %d acceleration %d "
                "jerk %d time %u", n + 1, (unsigned)offset, value[0], value[1], value[2], value[3], (unsigned)value[4]);
    return 1;
}

/* Whether axis n's segment reads may take pmd_external_read_plain for a whole
 * run (no command runs within one): its read plan is current (read_segment
 * would not check it again), it reads five distinct buffers (one per function,
 * the usual layout), its position buffer is not streamed (no underrun to warn
 * of), no buffer has unread entries to count down (a read only lowers them)
 * and no one logs segments. */
int pmd_external_plain(const PmdChip *chip, int n)
{
    const PmdAxis *ax = &chip->s.axis[n];
    int i;
    if (ax->buffersChecked != chip->s.bufferEpoch + 1 || ax->segmentBufferCount != PMD_FUNCTIONS ||
        PMD_LOGGING(chip, PMD_LOG_SEGMENTS) || chip->s.buffer[ax->segmentBuffer[0]].streamed)
        return 0;
    for (i = 0; i < PMD_FUNCTIONS; i++)
        if (chip->s.buffer[ax->segmentBuffer[i]].unread != 0)
            return 0;
    return 1;
}

/* The segment time 0 (seed 000, 1.5): StopTrajectory(), the read row's
 * position held, the axis stationary. */
void pmd_external_halt(PmdChip *chip, int n)
{
    pmd_log(chip, PMD_LOG_EVENTS, "axis %d: external profile read time 0: halted", n + 1);
    pmd_abrupt_stop(chip, n);
}

/* One cycle of seed 000's pseudo code. The decrement closes every cycle that
 * does not stop, so a segment with time T lasts T cycles: the read cycle and
 * T-1 integration cycles (the worked table, chip times 11003..11013). Seed
 * 000, 1.6: in external mode the motion-complete bit is set whenever the axis
 * comes to rest, which may happen many times in one profile. */
static void external_cycle(PmdChip *chip, int n)
{
    PmdAxis *ax = &chip->s.axis[n];
    int32_t v[PMD_FUNCTIONS];
    int moving;

    if (ax->segmentTime != 0) {               /* inside a segment: most cycles */
        pmd_external_step(chip, n);
        return;
    }
    moving = !pmd_fixed_is_zero(ax->trajectory.velocity);
    if (!read_segment(chip, n, v)) {
        pmd_abrupt_stop(chip, n);
        return;
    }
    if (pmd_external_begin(chip, n, v, moving))
        pmd_motion_complete(chip, n);
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

/* Sets this cycle's velocity v2 (16.16 units) after v: position, velocity and
 * acceleration follow exactly. */
static void step_velocity(PmdTrajectory *t, int64_t v, int64_t v2)
{
    move_by_1616(t, v2);
    t->velocity = pmd_fixed_from_1616(v2);
    t->acceleration = pmd_fixed_from_1616(v2 - v);
    t->jerk = 0;
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
    int64_t v = pmd_fixed_to_1616(t->velocity);             /* |v| <= 2^62: the sums below fit */
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
    step_velocity(t, v, s * w2);
    ax->atMaximumVelocity = w2 == vmax && vmax > 0;
    if (p + s * w2 == dest)
        t->fraction = 0;                          /* landed: drop any sub-16.16 remainder */
    if (w2 == 0 && (ax->motion == PMD_MOTION_SMOOTH_STOP || p == dest)) {
        pmd_log(chip, PMD_LOG_EVENTS, "axis %d: motion complete at %d", n + 1, t->position);
        pmd_halt(chip, n);
    }
}

/* ---- velocity contouring ---------------------------------------------------- */

/* Ramps toward the active (signed) velocity: speeding up at the acceleration,
 * slowing down - also on the way through zero to the other direction - at the
 * deceleration (reference 5); holds it indefinitely. A smooth stop ramps to 0. */
static void velocity_cycle(PmdChip *chip, int n)
{
    PmdAxis *ax = &chip->s.axis[n];
    PmdTrajectory *t = &ax->trajectory;
    int64_t acc = ax->active.acceleration;
    int64_t dec = ax->active.deceleration ? ax->active.deceleration : acc;
    int64_t target = ax->motion == PMD_MOTION_SMOOTH_STOP ? 0 : ax->active.velocity;
    int64_t v = pmd_fixed_to_1616(t->velocity), v2;

    if (v == target) {
        v2 = v;
    } else if (v != 0 && (target == 0 || (target > 0) != (v > 0) || (target > 0 ? target < v : target > v))) {
        int64_t floor_ = (target != 0 && (target > 0) == (v > 0)) ? target : 0;   /* slow down to here */
        v2 = v > 0 ? max64(v - dec, floor_) : min64(v + dec, floor_);
    } else {
        v2 = target > v ? min64(v + acc, target) : max64(v - acc, target);
    }
    step_velocity(t, v, v2);
    ax->atMaximumVelocity = v2 == target && v2 != 0;
    if (v2 == 0 && target == 0)
        pmd_halt(chip, n);
}

/* ---- electronic gear ---------------------------------------------------------- */

/* The slave's commanded position follows the master's actual or commanded
 * position times the 16.16 ratio (reference 5): each cycle it moves by the
 * master's change times the ratio, exactly; that move is its velocity, and
 * the change from the last velocity truncated to 16.16 its acceleration. */
void pmd_gear_cycle(PmdChip *chip, int n)
{
    PmdAxis *ax = &chip->s.axis[n];
    PmdTrajectory *t = &ax->trajectory;
    const PmdAxis *master = &chip->s.axis[ax->gearMasterAxis];
    int32_t position = ax->gearMasterSource == PMDPositionSourceCommanded ? master->trajectory.position
                                                                          : master->actualPosition;
    int64_t delta = pmd_wrap32((int64_t)position - ax->gearMasterLast);
    int64_t d16 = delta * ax->active.gearRatio;            /* 16.16 slave counts, |d16| <= 2^62 */
    PmdFixed before = pmd_fixed_floor_1616(t->velocity);
    ax->gearMasterLast = position;
    move_by_1616(t, d16);
    t->velocity = pmd_fixed_from_1616(d16);
    t->acceleration = pmd_fixed_sub(t->velocity, before);
    t->jerk = 0;
}

void pmd_profile_cycle(PmdChip *chip, int n)
{
    if (chip->s.axis[n].motion == PMD_MOTION_EXTERNAL) {      /* most of a long run's work: tested first */
        external_cycle(chip, n);
        return;
    }
    switch (chip->s.axis[n].motion) {
    case PMD_MOTION_TRAPEZOIDAL:
        trapezoidal_cycle(chip, n);
        break;
    case PMD_MOTION_SMOOTH_STOP:
        if (chip->s.axis[n].active.profileMode == PMDVelocityContouringProfile)
            velocity_cycle(chip, n);
        else
            trapezoidal_cycle(chip, n);
        break;
    case PMD_MOTION_VELOCITY:
        velocity_cycle(chip, n);
        break;
    case PMD_MOTION_SCURVE:
        if (pmd_scurve_cycle(chip, n))
            pmd_halt(chip, n);
        break;
    case PMD_MOTION_GEAR:
        break;                 /* after the other axes: pmd_gear_cycle */
    default:
        pmd_rest_cycle(chip, n);
        break;
    }
}

/* ---- stops ------------------------------------------------------------------ */

/* A stop in stop mode `stopMode` (PMDAbruptStopMode or PMDSmoothStopMode), in
 * whatever profile the axis runs: what an Update does with a buffered stop mode,
 * and what a breakpoint's stop action does (chip.c), so the two cannot differ.
 * It touches no register, active or buffered: Update copies them itself.
 * - abrupt (reference 5, stops): velocity zeroed at once, commanded position held;
 * - smooth: trapezoidal and velocity contouring brake at the deceleration, an
 *   S-curve runs its deceleration phases (scurve.c); a geared axis has no
 *   deceleration, so it stops abruptly (reference 5, S2 p.136, p.191); an
 *   external profile changes nothing (seed 000, 1.5: "If a SmoothStop is issued
 *   no change in motion will occur"); an axis at rest stays at rest. */
void pmd_stop(PmdChip *chip, int n, uint16_t stopMode)
{
    PmdAxis *ax = &chip->s.axis[n];
    if (stopMode == PMDAbruptStopMode || (stopMode == PMDSmoothStopMode && ax->motion == PMD_MOTION_GEAR)) {
        pmd_abrupt_stop(chip, n);
    } else if (stopMode == PMDSmoothStopMode) {
        if (ax->motion == PMD_MOTION_TRAPEZOIDAL || ax->motion == PMD_MOTION_VELOCITY)
            ax->motion = PMD_MOTION_SMOOTH_STOP;
        else if (ax->motion == PMD_MOTION_SCURVE)
            pmd_scurve_smooth_stop(ax);
    }
}

/* ---- Update ---------------------------------------------------------------- */

/* The direction a move would start in: +1, -1, or 0 when it has none (no
 * motion, or an external or geared profile, whose direction the host owns). */
static int move_direction(const PmdAxis *ax, const PmdProfileRegisters *b)
{
    switch (b->profileMode) {
    case PMDTrapezoidalProfile:
    case PMDSCurveProfile:
        return b->position > ax->trajectory.position ? 1 : b->position < ax->trajectory.position ? -1 : 0;
    case PMDVelocityContouringProfile:
        return b->velocity > 0 ? 1 : b->velocity < 0 ? -1 : 0;
    default:
        return 0;
    }
}

/* A trapezoidal "move" that has not moved: still at rest on its destination
 * (e.g. the Update of a host's set-up, before the next cycle ends it). Seed
 * 001's rule is about changes in motion, so such an axis is at rest. */
static int trapezoidal_at_rest(const PmdAxis *ax)
{
    const PmdTrajectory *t = &ax->trajectory;
    return pmd_fixed_is_zero(t->velocity) && t->fraction == 0 && t->position == ax->active.position;
}

/* The checks an Update makes before it changes anything. */
static int update_refused(PmdChip *chip, int n)
{
    PmdAxis *ax = &chip->s.axis[n];
    const PmdProfileRegisters *b = &ax->buffered;
    int direction;

    if (b->stopMode != PMDNoStopMode)
        return 0;
    if (b->velocity < 0 && b->profileMode != PMDVelocityContouringProfile && b->profileMode != PMDExternalProfile &&
        b->profileMode != PMDElectronicGearProfile) {
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: Update: negative velocity %d in profile mode %d", n + 1,
                b->velocity, b->profileMode);
        return PMD_ERR_InvalidNegativeValue;
    }
    if (ax->motion == PMD_MOTION_TRAPEZOIDAL && !trapezoidal_at_rest(ax) && b->profileMode == PMDTrapezoidalProfile &&
        (b->acceleration != ax->active.acceleration || b->deceleration != ax->active.deceleration)) {
        /* Seed 001: the acceleration may change only at rest; the update is
         * ignored except for the position. */
        ax->active.position = b->position;
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: Update: acceleration changed during a trapezoidal move: only the "
                "destination was applied", n + 1);
        return PMD_ERR_InvalidParameterChange;
    }
    if (ax->motion == PMD_MOTION_SCURVE &&
        (b->profileMode != ax->active.profileMode || b->position != ax->active.position ||
         b->velocity != ax->active.velocity || b->acceleration != ax->active.acceleration ||
         b->jerk != ax->active.jerk || b->clearPositionError)) {
        /* reference 5: no parameter changes while an S-curve moves */
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: Update: S-curve parameters changed during the move", n + 1);
        return PMD_ERR_InvalidParameterChange;
    }
    if (ax->limitSwitchMode && (direction = move_direction(ax, b)) != 0) {
        if (ax->eventStatus & (PMDEventInPositiveLimitMask | PMDEventInNegativeLimitMask)) {
            pmd_log(chip, PMD_LOG_ERRORS, "axis %d: Update: a limit event is pending (ResetEventStatus first)", n + 1);
            return PMD_ERR_LimitEventPending;
        }
        if ((direction > 0 && ax->inPositiveLimit) || (direction < 0 && ax->inNegativeLimit)) {
            pmd_log(chip, PMD_LOG_ERRORS, "axis %d: Update: move further into the %s limit", n + 1,
                    direction > 0 ? "positive" : "negative");
            return PMD_ERR_InvalidMoveIntoLimit;
        }
    }
    if (b->profileMode == PMDExternalProfile && ax->motion != PMD_MOTION_EXTERNAL && !external_buffers_ok(chip, ax)) {
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: Update: external profile needs a position buffer, and every "
                "assigned buffer of the same non-zero length", n + 1);
        return PMD_ERR_InvalidParameter;
    }
    return 0;
}

/* Copies the buffered registers to the active set and starts or stops the
 * profile they describe. A refused Update changes nothing. */
int pmd_update(PmdChip *chip, int n)
{
    PmdAxis *ax = &chip->s.axis[n];
    const PmdProfileRegisters *b = &ax->buffered;
    uint16_t stop = b->stopMode;
    PmdSCurve plan;
    int err = update_refused(chip, n);

    if (!err && stop == PMDNoStopMode && b->profileMode == PMDSCurveProfile && ax->motion != PMD_MOTION_SCURVE)
        err = pmd_scurve_plan(chip, n, b, &plan);
    if (err)
        return err;
    chip->s.updatedAxes |= (uint8_t)(PMDAxis1Mask << n);
    if (b->clearPositionError) {
        /* reference 4.1: the commanded position becomes the actual position */
        ax->trajectory.position = ax->actualPosition;
        ax->trajectory.fraction = 0;
    }
    ax->active = *b;
    ax->filter.active = ax->filter.buffered;    /* reference 4.1: the filter group too */
    ax->active.stopMode = PMDNoStopMode;
    ax->active.clearPositionError = 0;
    ax->buffered.stopMode = PMDNoStopMode;      /* reference 4.1: the stop mode resets itself */
    ax->buffered.clearPositionError = 0;

    if (stop != PMDNoStopMode) {
        pmd_stop(chip, n, stop);
    } else {
        switch (b->profileMode) {
        case PMDExternalProfile:
            if (ax->motion != PMD_MOTION_EXTERNAL) {
                ax->motion = PMD_MOTION_EXTERNAL;
                ax->segmentTime = 0;             /* the first cycle reads a segment */
                ax->underrunWarned = 0;
            }
            break;
        case PMDVelocityContouringProfile:
            ax->motion = PMD_MOTION_VELOCITY;
            break;
        case PMDSCurveProfile:
            if (ax->motion != PMD_MOTION_SCURVE) {
                ax->scurve = plan;
                ax->motion = PMD_MOTION_SCURVE;
            }
            break;
        case PMDElectronicGearProfile:
            if (ax->motion != PMD_MOTION_GEAR) {
                const PmdAxis *master = &chip->s.axis[ax->gearMasterAxis];
                ax->gearMasterLast = ax->gearMasterSource == PMDPositionSourceCommanded
                                         ? master->trajectory.position : master->actualPosition;
                ax->motion = PMD_MOTION_GEAR;
            }
            break;
        default:
            ax->motion = PMD_MOTION_TRAPEZOIDAL;
            break;
        }
    }
    return 0;
}
