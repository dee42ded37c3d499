/* SPDX-License-Identifier: BSD-2-Clause */
/* Chip life cycle and the per-cycle sequence: every axis's trajectory, then
 * limits, capture, the servo side, breakpoints, the servo filter and the trace. */
#include <string.h>

#include "chip.h"
#include "events.h"
#include "machine.h"
#include "profile.h"
#include "servo.h"
#include "status.h"
#include "trace.h"

void pmd_chip_init(PmdChip *chip, uint32_t *memory, uint32_t memorySize)
{
    chip->memory = memory;
    chip->memorySize = memorySize;
    pmd_chip_reset(chip);
}

/* Reset values: reference 4.2. External memory keeps its contents. */
void pmd_chip_reset(PmdChip *chip)
{
    uint8_t loopback = chip->s.loopback;
    uint16_t sampleTime = chip->s.sampleTime;
    PmdAxis inputs[PMD_AXES];
    unsigned plant = chip->machine ? chip->machine->plantAxes : 0;
    int n, f;

    uint16_t analogInput[PMD_ANALOG_CHANNELS], ioInput[PMD_IO_PORTS];

    memcpy(inputs, chip->s.axis, sizeof inputs);
    memcpy(analogInput, chip->s.analogInput, sizeof analogInput);
    memcpy(ioInput, chip->s.ioInput, sizeof ioInput);
    memset(&chip->s, 0, sizeof chip->s);
    /* the plant's inputs are wires, not registers: a reset does not change them */
    memcpy(chip->s.analogInput, analogInput, sizeof analogInput);
    memcpy(chip->s.ioInput, ioInput, sizeof ioInput);
    chip->s.loopback = loopback;
    chip->s.sampleTime = sampleTime;      /* the cycle grid is the FMU's: Reset keeps it */
    chip->s.hostIOError = PMD_ERR_ChipsetReset;   /* until read (reference 2.4) */
    pmd_registers_reset(chip);            /* the register table's reset values (registers.csv) */
    for (n = 0; n < PMD_AXES; n++) {
        PmdAxis *ax = &chip->s.axis[n];
        for (f = 0; f < PMD_FUNCTIONS; f++)
            ax->bufferOfFunction[f] = PMDBufferFunctionNone;
        /* the plant's inputs are wires, not registers: a reset does not change them */
        ax->actualPositionInput = inputs[n].actualPositionInput;
        ax->positiveLimitInput = inputs[n].positiveLimitInput;
        ax->negativeLimitInput = inputs[n].negativeLimitInput;
        ax->homeInput = inputs[n].homeInput;
        ax->indexInput = inputs[n].indexInput;
        /* a machine's motor is physics: it turns on through a chip reset */
        ax->motorAngle = inputs[n].motorAngle;
        ax->motorSpeed = inputs[n].motorSpeed;
        /* the encoder count as the last cycle sampled it (its offset gone), not the live input:
         * a command reads the plant only through a cycle (docs/decisions.md) */
        ax->actualPosition = loopback && !(plant & (1u << n))
                                 ? 0
                                 : pmd_int32((uint32_t)inputs[n].actualPosition - (uint32_t)inputs[n].actualOffset);
        ax->previousActualPosition = ax->actualPosition;
        /* the ideal servo's stage stays where it is while its counter restarts at 0, as a motor's does:
         * a machine's switches (machine.c) are at the stage's count actual - offset */
        if (loopback && !(plant & (1u << n)))
            ax->actualOffset = pmd_int32(0u - ((uint32_t)inputs[n].actualPosition - (uint32_t)inputs[n].actualOffset));
    }
}

/* Status triggers: the high word of the value selects bits, the low word
 * gives the state each selected bit must reach; any one reaching it fires
 * (reference 2.5, seed 000 1.6). */
static int status_reached(uint16_t status, int32_t value)
{
    uint16_t select = pmd_high_word((uint32_t)value), sense = pmd_low_word((uint32_t)value);
    return (uint16_t)(~(status ^ sense) & select) != 0;
}

static int breakpoint_reached(const PmdChip *chip, const PmdBreakpoint *bp)
{
    const PmdAxis *src = &chip->s.axis[bp->sourceAxis];
    switch (bp->trigger) {
    case PMDBreakpointGreaterOrEqualCommandedPosition: return src->trajectory.position >= bp->value;
    case PMDBreakpointLessOrEqualCommandedPosition: return src->trajectory.position <= bp->value;
    case PMDBreakpointGreaterOrEqualActualPosition: return src->actualPosition >= bp->value;
    case PMDBreakpointLessOrEqualActualPosition: return src->actualPosition <= bp->value;
    case PMDBreakpointTime: return chip->s.time == (uint32_t)bp->value;
    case PMDBreakpointEventStatus: return status_reached(src->eventStatus, bp->value);
    case PMDBreakpointActivityStatus: return status_reached(pmd_activity_status(chip, bp->sourceAxis), bp->value);
    case PMDBreakpointSignalStatus: return status_reached(pmd_signal_status(chip, bp->sourceAxis), bp->value);
    default: return 0;
    }
}

static void check_breakpoints(PmdChip *chip, int n)
{
    static const uint16_t eventBit[2] = {PMDEventBreakpoint1Mask, PMDEventBreakpoint2Mask};
    int i;
    for (i = 0; i < 2; i++) {
        PmdBreakpoint *bp = &chip->s.axis[n].breakpoint[i];
        if (bp->trigger == PMDBreakpointDisable || !breakpoint_reached(chip, bp))
            continue;
        pmd_log(chip, PMD_LOG_EVENTS, "axis %d: breakpoint %d fired (trigger %u, action %u) at chip time %u",
                n + 1, i + 1, (unsigned)bp->trigger, (unsigned)bp->action, (unsigned)chip->s.time);
        bp->trigger = PMDBreakpointDisable;     /* fires once */
        pmd_set_event(chip, n, eventBit[i]);
        switch (bp->action) {
        case PMDBreakpointActionUpdate:
            if (pmd_update(chip, n) != 0)
                pmd_set_event(chip, n, PMDEventInstructionErrorMask);
            break;
        /* A stop action is the stop an Update applies (pmd_stop), in every profile
         * mode, without the Update: the registers, active and buffered, stay as
         * they are (docs/decisions.md, breakpoint actions). */
        case PMDBreakpointActionAbruptStop:
            pmd_stop(chip, n, PMDAbruptStopMode);
            break;
        case PMDBreakpointActionSmoothStop:
            pmd_stop(chip, n, PMDSmoothStopMode);
            break;
        case PMDBreakpointActionMotorOff:
            chip->s.axis[n].motorOn = PMDMotorOff;     /* what SetMotorMode(0) stores */
            break;
        default:
            break;
        }
    }
}

/* Actual position: the commanded position (loopback, motor on: the ideal
 * servo), held (loopback, motor off), or the encoder input plus the
 * SetActualPosition offset. Returns whether the servo is ideal. The loopback
 * parameter is fixed for a whole run: pmd_chip_run_every_cycle reads it once and passes it.
 * A sample that wrapped between the maximum and the minimum sets the
 * wrap-around event (reference 2.2; pmd_wrapped). */
static inline int sample_actual(PmdChip *chip, int n, int loopback)
{
    PmdAxis *ax = &chip->s.axis[n];
    int ideal = 0;
    ax->previousActualPosition = ax->actualPosition;
    if (!loopback) {
        ax->actualPosition = pmd_int32((uint32_t)ax->actualPositionInput + (uint32_t)ax->actualOffset);
    } else if (ax->motorOn) {
        ax->actualPosition = ax->trajectory.position;
        ideal = 1;
    }
    if (pmd_wrapped(ax->previousActualPosition, ax->actualPosition))
        pmd_set_event(chip, n, PMDEventWrapAroundMask);
    return ideal;
}

/* Entering a limit sets its event bit and stops the axis; the activity bit
 * follows the switch (reference 4.5). Ignored with the limit-switch mode off. */
static void check_limits(PmdChip *chip, int n, uint16_t signals)
{
    PmdAxis *ax = &chip->s.axis[n];
    int positive = ax->limitSwitchMode && !(signals & PMDSignalPositiveLimitMask);   /* active reads 0 */
    int negative = ax->limitSwitchMode && !(signals & PMDSignalNegativeLimitMask);
    if ((positive && !ax->inPositiveLimit) || (negative && !ax->inNegativeLimit)) {
        pmd_set_event(chip, n, positive && !ax->inPositiveLimit ? PMDEventInPositiveLimitMask
                                                                : PMDEventInNegativeLimitMask);
        pmd_log(chip, PMD_LOG_EVENTS, "axis %d: %s limit entered: axis stopped", n + 1,
                positive && !ax->inPositiveLimit ? "positive" : "negative");
        pmd_abrupt_stop(chip, n);
    }
    ax->inPositiveLimit = (uint8_t)positive;
    ax->inNegativeLimit = (uint8_t)negative;
}

/* Position error beyond its limit: motion-error event; with auto-stop the axis
 * stops and its motor turns off; an external profile always stops (seed 000, 1.5). */
static void check_position_error(PmdChip *chip, int n)
{
    PmdAxis *ax = &chip->s.axis[n];
    uint32_t error = pmd_abs32(pmd_position_error(ax));
    if (error > ax->positionErrorLimit && !(ax->eventStatus & PMDEventMotionErrorMask)) {
        pmd_set_event(chip, n, PMDEventMotionErrorMask);
        pmd_log(chip, PMD_LOG_EVENTS, "axis %d: motion error: position error %u beyond %u", n + 1,
                (unsigned)error, (unsigned)ax->positionErrorLimit);
        if (ax->autoStopMode) {
            pmd_abrupt_stop(chip, n);
            ax->motorOn = 0;
        } else if (ax->motion == PMD_MOTION_EXTERNAL) {
            pmd_abrupt_stop(chip, n);
        }
    }
    /* settled: at rest and inside the settle window for more than the settle time */
    if (ax->motion == PMD_MOTION_IDLE && error <= ax->settleWindow) {
        if (ax->settleCount < 0xFFFF)
            ax->settleCount++;
    } else {
        ax->settleCount = 0;
    }
    if (ax->motionCompletePending && ax->settleCount > ax->settleTime) {
        ax->motionCompletePending = 0;
        pmd_set_event(chip, n, PMDEventMotionCompleteMask);
    }
}

/* The capture source's input (home or index) captures the actual position in
 * the cycle it becomes active, if the last capture has been read. */
static void check_capture(PmdChip *chip, int n, uint16_t signals)
{
    PmdAxis *ax = &chip->s.axis[n];
    int home = !(signals & PMDSignalEncoderHomeMask), index = !(signals & PMDSignalEncoderIndexMask);
    int edge = ax->captureSource == PMDCaptureSourceHome ? home && !ax->homeWasActive
                                                         : index && !ax->indexWasActive;
    if (edge && !ax->captured) {
        ax->captured = 1;
        ax->captureValue = ax->actualPosition;
        pmd_set_event(chip, n, PMDEventCaptureReceivedMask);
    }
    ax->homeWasActive = (uint8_t)home;
    ax->indexWasActive = (uint8_t)index;
}

/* Whether no limit or capture can happen: every switch idle, none latched, no
 * sense inversion. Only the checks below change the latches. */
static int switches_idle(const PmdAxis *ax)
{
    return !(ax->positiveLimitInput | ax->negativeLimitInput | ax->homeInput | ax->indexInput |
             ax->inPositiveLimit | ax->inNegativeLimit | ax->homeWasActive | ax->indexWasActive |
             (ax->signalSense != 0));
}

PmdRunFacts pmd_chip_run_facts(const PmdChip *chip)
{
    PmdRunFacts facts;
    int trace = chip->s.trace.active || chip->s.trace.start, n;
    unsigned busy = 0, ideal = 0, unskippable = 0;
    /* an axis whose inputs a machine drives may meet a switch or index edge in any cycle: every
     * cycle of it runs the checks, and none is skipped (docs/machine.md) */
    const unsigned machine = chip->machine ? chip->machine->axes : 0;
    for (n = 0; n < PMD_AXES; n++) {
        const PmdAxis *ax = &chip->s.axis[n];
        unsigned bit = 1u << n;
        int armed = ax->breakpoint[0].trigger != PMDBreakpointDisable ||
                    ax->breakpoint[1].trigger != PMDBreakpointDisable;
        if (chip->s.loopback && ax->motorOn)
            ideal |= bit;
        if (armed || ax->motion == PMD_MOTION_GEAR || !switches_idle(ax) || (machine & bit))
            busy |= bit;
        if (armed || ax->motionCompletePending || (machine & bit) ||
            (ax->motion != PMD_MOTION_IDLE && (ax->motion != PMD_MOTION_EXTERNAL || !(ideal & bit))))
            unskippable |= bit;
    }
    facts.quiet = !trace && !busy;
    facts.deferredFilters = facts.quiet ? ideal : 0;
    facts.skippable = !trace && !unskippable;
    return facts;
}

/* The servo side of axis n's cycle: position error, settling. */
static inline void check_servo(PmdChip *chip, int n, int ideal)
{
    PmdAxis *ax = &chip->s.axis[n];
    /* the ideal servo keeps the error at 0: a moving axis only resets its settle count */
    if (ideal && ax->motion != PMD_MOTION_IDLE && !ax->motionCompletePending)
        ax->settleCount = 0;
    else
        check_position_error(chip, n);
}

/* Axis n's columns of a record row: its commanded position, velocity and
 * acceleration registers. The values are read before any is stored (the
 * row's int32 words could alias the state's for all the compiler knows). */
static inline void record_axis(const PmdChip *chip, int n, int32_t *row)
{
    const PmdTrajectory *t = &chip->s.axis[n].trajectory;
    int32_t position = t->position, velocity = pmd_commanded_velocity(t);
    int32_t acceleration = pmd_commanded_acceleration(t);
    row[1 + 3 * n] = position;
    row[2 + 3 * n] = velocity;
    row[3 + 3 * n] = acceleration;
}

/* A row holds trajectory registers only: within a quiet run an ideal servo's
 * filter is brought up to date at the run's end (PmdRunFacts.deferredFilters), so its
 * output is not a column a row could show cycle by cycle. */
void pmd_chip_record(const PmdChip *chip, int32_t row[PMD_RECORD_WORDS])
{
    int n;
    row[0] = pmd_int32(chip->s.time);
    for (n = 0; n < PMD_AXES; n++)
        record_axis(chip, n, row);
}

/* A hint for the loops over the axes in cycle() and quiet_cycles(): unrolled, each axis's
 * cycle addresses its state at constant offsets and the four independent
 * recurrences interleave - bench/engine.c measured the quiet cycle 1.44x a
 * bare loop's time rolled, 1.24x unrolled (4-cycle segments). Other compilers
 * run the loop as written. */
#if defined(__clang__)
#define UNROLL_AXES _Pragma("clang loop unroll(full)")
#elif defined(__GNUC__) && __GNUC__ >= 8
#define UNROLL_AXES _Pragma("GCC unroll 4")
#else
#define UNROLL_AXES
#endif

/* Inlining hints for GCC and Clang (other compilers decide for themselves):
 * the rare path of a hot loop kept out of line, so that the loop keeps its
 * values in registers; a loop body inlined at each of its call sites, so that
 * each copy is compiled for its constant arguments (with a record or without). */
#if defined(__GNUC__)
#define NOINLINE __attribute__((noinline))
#define ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define NOINLINE
#define ALWAYS_INLINE inline
#endif

/* One chip cycle; with row, the cycle's record row (pmd_chip_record). In a
 * quiet run (PmdRunFacts.quiet) nothing couples the axes and the checks that cannot
 * fire are left out: each axis runs its cycle in turn, and its columns of the
 * row are final once it has (stored while its registers are at hand). The
 * servo filter runs once the cycle's events have acted on the axis (a motion
 * error's auto-stop, a breakpoint's motor off or update): its output is the
 * motor command the cycle ends with (docs/decisions.md). In a quiet run the
 * filters of the axes in closedForm (bit n: axis n) are left to pmd_chip_run_every_cycle,
 * which runs all their cycles at once at the end. A quiet run's middle cycles
 * are quiet_cycles(). */
static inline void cycle(PmdChip *chip, int quiet, int loopback, unsigned closedForm, int32_t *row)
{
    /* a machine's plant closes its axis's loop whatever the loopback parameter (never in a quiet run:
     * a machine's axes make none) */
    const unsigned plant = quiet || !chip->machine ? 0 : chip->machine->plantAxes;
    int n;
    chip->s.time = chip->s.nextTime++;
    if (quiet && row)
        row[0] = pmd_int32(chip->s.time);
    /* geared axes last: they follow their master's position of this cycle */
    UNROLL_AXES
    for (n = 0; n < PMD_AXES; n++) {
        /* pmd_profile_cycle's most frequent cases inline (it is out of line: quiet_axis_cycle calls it too) */
        if (chip->s.axis[n].motion == PMD_MOTION_EXTERNAL && chip->s.axis[n].segmentTime != 0)
            pmd_external_step(chip, n);
        else if (chip->s.axis[n].motion == PMD_MOTION_IDLE)
            pmd_rest_cycle(chip, n);
        else
            pmd_profile_cycle(chip, n);
        if (quiet) {
            check_servo(chip, n, sample_actual(chip, n, loopback));
            if (!(closedForm & (1u << n)))
                pmd_servo_cycle(chip, n);
            if (row)
                record_axis(chip, n, row);
        } else if (chip->s.axis[n].motion != PMD_MOTION_GEAR) {
            sample_actual(chip, n, loopback && !(plant & (1u << n)));
        }
    }
    if (quiet) {
        chip->s.updatedAxes = 0;           /* what pmd_trace_cycle does with no trace armed */
        return;
    }
    for (n = 0; n < PMD_AXES; n++) {
        if (chip->s.axis[n].motion == PMD_MOTION_GEAR) {
            pmd_gear_cycle(chip, n);
            sample_actual(chip, n, loopback && !(plant & (1u << n)));
        }
    }
    if (chip->machine)
        for (n = 0; n < PMD_AXES; n++)
            if (chip->machine->axes & (1u << n))
                pmd_machine_inputs(chip, n);
    for (n = 0; n < PMD_AXES; n++) {
        if (!switches_idle(&chip->s.axis[n])) {
            uint16_t signals = pmd_signal_status(chip, n);
            check_limits(chip, n, signals);
            check_capture(chip, n, signals);
        }
        check_servo(chip, n, loopback && !(plant & (1u << n)) && chip->s.axis[n].motorOn);
    }
    /* breakpoints last: a source axis may be any axis, and all have moved */
    for (n = 0; n < PMD_AXES; n++)
        if (chip->s.axis[n].breakpoint[0].trigger | chip->s.axis[n].breakpoint[1].trigger)
            check_breakpoints(chip, n);
    for (n = 0; n < PMD_AXES; n++)
        pmd_servo_cycle(chip, n);
    pmd_trace_cycle(chip);
    /* the plants last, with the motor commands the cycle ends with: the next cycle samples their encoders */
    if (plant)
        for (n = 0; n < PMD_AXES; n++)
            if (plant & (1u << n))
                pmd_machine_plant_cycle(chip, n);
    if (row)
        pmd_chip_record(chip, row);
}

void pmd_chip_run_one_cycle(PmdChip *chip)
{
    pmd_chip_run_every_cycle(chip, 1, NULL);
}

/* An ideal servo's filter left to one closed-form step at a quiet run's end
 * (PmdRunFacts.deferredFilters): in a quiet run an ideal servo's axis (loopback,
 * motor on) keeps its motor on - its position error, 0 every cycle, cannot
 * raise a motion error, and no breakpoint or command can act - so its filter
 * sees the error 0 throughout and its output depends only on the last
 * cycle's commanded velocity and acceleration. */

/* An ideal servo's axis at rest in a quiet run's middle cycles: check_servo
 * with its error 0 (sampled first: the ideal servo's sample, without the
 * wrap-around check, which quiet_cycles made on the commanded position as it
 * moved; the actual position it leaves is the run's last cycle's business). */
static NOINLINE void settle(PmdChip *chip, int n)
{
    PmdAxis *ax = &chip->s.axis[n];
    ax->previousActualPosition = ax->actualPosition = ax->trajectory.position;
    check_position_error(chip, n);
}

/* Axis n's cycle in quiet_cycles() but for an ideal servo's integration step:
 * cycle()'s, with an ideal servo's axis (closedForm) unsampled. Out of line:
 * the loop's registers stay with the integration steps. */
static NOINLINE void quiet_axis_cycle(PmdChip *chip, int n, int loopback, unsigned closedForm)
{
    pmd_profile_cycle(chip, n);
    if (closedForm & (1u << n)) {
        /* check_servo with an ideal servo's error 0: a moving axis, pending or not, only resets
         * its settle count, which the run's first cycle did (pmd_chip_run_every_cycle); at rest it settles */
        if (chip->s.axis[n].motion == PMD_MOTION_IDLE)
            settle(chip, n);
    } else {
        check_servo(chip, n, sample_actual(chip, n, loopback));
        pmd_servo_cycle(chip, n);
    }
}

/* The middle cycles of a quiet run (all but its first and last: see
 * pmd_chip_run_every_cycle), `cycles` of them, rows from row on (or none). An ideal
 * servo's axis inside an external segment - most cycles of a long run - takes
 * the integration step (pmd_external_step) and nothing else: it moves on, so
 * its servo side has nothing to do. Its columns of the row are stored before
 * a motion-complete event is raised (which changes no register shown): the
 * values are still in registers then. The chip time is kept in a local (the
 * row's stores could alias the state's for all the compiler knows). An
 * ideal servo's actual position is its commanded position, so the
 * wrap-around event of such an axis (closedForm) is watched on the commanded
 * position, cycle by cycle, until its bit is set (sample_actual watches the
 * others). */
static ALWAYS_INLINE void quiet_cycles(PmdChip *chip, int64_t cycles, int loopback, unsigned closedForm,
                                       int32_t *row)
{
    uint32_t time = chip->s.nextTime;
    unsigned plain = 0, watch = 0;
    int64_t k;
    int n;
    for (n = 0; n < PMD_AXES; n++) {
        if (pmd_external_plain(chip, n))
            plain |= 1u << n;
        if ((closedForm & (1u << n)) && !(chip->s.axis[n].eventStatus & PMDEventWrapAroundMask))
            watch |= 1u << n;
    }
    for (k = 0; k < cycles; k++, time++) {
        chip->s.time = time;
        chip->s.nextTime = time + 1;
        if (row)
            row[0] = pmd_int32(time);
        UNROLL_AXES
        for (n = 0; n < PMD_AXES; n++) {
            PmdAxis *ax = &chip->s.axis[n];
            int32_t before = ax->trajectory.position;
            if ((closedForm & (1u << n)) && ax->motion == PMD_MOTION_EXTERNAL &&
                (ax->segmentTime != 0 || (plain & (1u << n)))) {
                int rest;
                if (ax->segmentTime != 0) {
                    ax->segmentTime--;
                    rest = pmd_integrate(&ax->trajectory);
                } else {
                    rest = pmd_external_read_plain(chip, n);
                    if (ax->motion == PMD_MOTION_IDLE)
                        settle(chip, n);      /* a segment time 0 halted it */
                }
                if (row)
                    record_axis(chip, n, row);
                if (rest)
                    pmd_motion_complete(chip, n);
            } else {
                quiet_axis_cycle(chip, n, loopback, closedForm);
                if (row)
                    record_axis(chip, n, row);
            }
            if ((watch & (1u << n)) && pmd_wrapped(before, ax->trajectory.position)) {
                pmd_set_event(chip, n, PMDEventWrapAroundMask);
                watch &= ~(1u << n);
            }
        }
        if (row)
            row += PMD_RECORD_WORDS;
    }
    chip->s.updatedAxes = 0;               /* what pmd_trace_cycle does with no trace armed */
}

unsigned pmd_chip_deferred_axes(const PmdChip *chip)
{
    return pmd_chip_run_facts(chip).deferredFilters;
}

/* Every cycle through cycle(), as pmd_chip_run_every_cycle runs a run of one or two
 * cycles, the deferred filters advanced at the end: unlike quiet_cycles,
 * cycle() samples every axis's actual position and checks its servo side
 * (position error, settling, motion complete) each cycle, so only the filters
 * of the axes in closedForm lag behind a row. */
void pmd_chip_run_every_cycle_with_rows(PmdChip *chip, int64_t cycles, void (*row)(void *context), void *context)
{
    PmdRunFacts facts = pmd_chip_run_facts(chip);
    int quiet = facts.quiet, loopback = chip->s.loopback, n;
    unsigned closedForm = facts.deferredFilters;
    int64_t k;
    for (k = 0; k < cycles; k++) {
        cycle(chip, quiet, loopback, closedForm, NULL);
        row(context);
    }
    if (cycles > 0)
        for (n = 0; n < PMD_AXES; n++)
            if (closedForm & (1u << n))
                pmd_servo_advance(chip, n, cycles);
}

/* The middle cycles of a quiet run (quiet_cycles) leave an ideal servo's axis
 * (closedForm) unsampled and its settle count alone while it moves: within the
 * run no one else reads its actual position, and a cycle in which it moves
 * resets the count, which only the settling at rest moves again; an axis at
 * rest stays at rest until a command. The first cycle resets the count of an
 * axis that moves, the last sets the previous actual position
 * (GetActualVelocity) and the actual position as every cycle would have. */
void pmd_chip_run_every_cycle(PmdChip *chip, int64_t cycles, int32_t *record)
{
    PmdRunFacts facts = pmd_chip_run_facts(chip);
    int quiet = facts.quiet, loopback = chip->s.loopback, n;
    unsigned closedForm = facts.deferredFilters;
    int64_t k;
    for (k = 0; k < cycles; k++) {
        if (k == 1 && quiet && cycles > 2) {
            /* a copy of the loop each, compiled with and without a record */
            if (record)
                quiet_cycles(chip, cycles - 2, loopback, closedForm, record + PMD_RECORD_WORDS);
            else
                quiet_cycles(chip, cycles - 2, loopback, closedForm, NULL);
            k = cycles - 1;
        }
        if (k == cycles - 1 && k > 0)
            for (n = 0; n < PMD_AXES; n++)
                if (closedForm & (1u << n))
                    chip->s.axis[n].actualPosition = chip->s.axis[n].trajectory.position;  /* cycle k - 1's sample */
        cycle(chip, quiet, loopback, closedForm, record ? record + k * PMD_RECORD_WORDS : NULL);
    }
    if (cycles > 0)
        for (n = 0; n < PMD_AXES; n++)
            if (closedForm & (1u << n))
                pmd_servo_advance(chip, n, cycles);
}
