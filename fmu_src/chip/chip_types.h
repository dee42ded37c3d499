/* SPDX-License-Identifier: BSD-2-Clause */
/* The chip's state: plain data, no pointers, so a copy is a snapshot; and the
 * chip object (PmdChip) around it: that state, this process's memory block and
 * logger. Register names follow the Navigator/Pilot programmer's reference. */
#ifndef PMD_CHIP_TYPES_H
#define PMD_CHIP_TYPES_H

#include <stddef.h>
#include <stdint.h>

#include "plant.h"              /* a machine's motor (servo = "plant"): fmu_src/plant */

#define PMD_AXES 4
#define PMD_BUFFERS 32       /* buffer IDs 0..31; 0 and 1 belong to the trace (seed 000, 1.1) */
#define PMD_FIRST_PROFILE_BUFFER 2
#define PMD_FUNCTIONS 5      /* PMDBufferFunctionPosition .. PMDBufferFunctionTime */
#define PMD_MAX_FIELDS 8     /* argument or reply values of one command */
#define PMD_BATCH_WORDS 64   /* host.word[1..64], host.reply[1..64] */
#define PMD_ANALOG_CHANNELS 8 /* ReadAnalog channels 0..7: the FMU inputs analog[1..8] */
#define PMD_IO_PORTS 16      /* ReadIO/WriteIO addresses 0..15: io.input[1..16], io.output[1..16] */

/* A 32-bit value's two 16-bit words: the host port carries the high word
 * first (reference 1.1); a status breakpoint's value is a select mask (high
 * word) and a sense mask (low word) (reference 2.5). */
static inline uint16_t pmd_high_word(uint32_t u) { return (uint16_t)(u >> 16); }
static inline uint16_t pmd_low_word(uint32_t u) { return (uint16_t)(u & 0xFFFFu); }
static inline uint32_t pmd_word_pair(uint16_t high, uint16_t low) { return ((uint32_t)high << 16) | low; }

/* A 32-bit register read as a signed value (two's complement, portably). */
static inline int32_t pmd_int32(uint32_t u)
{
    return u <= (uint32_t)INT32_MAX ? (int32_t)u : -(int32_t)(~u) - 1;
}


/* Exact trajectory state.
 *
 * Seed 000's external-profile recurrence, run once per cycle,
 *     P += V + A/2 + J/6,   V += A + J/2,   A += J,
 * starts from P in 32.0 counts, V and A in 16.16 and J in 0.32 (J = j / 2^32
 * count for the raw value j). J/2 = j / 2^33, so V and A/2 stay multiples of
 * 2^-33 count and A of 2^-32 count: binary fixed point. Only the position
 * gains a non-binary term, J/6; it is kept in the unit U = 2^-32/6 count, in
 * which J/6 = j and V + A/2 (a multiple of 2^-33 count = 3 U) are integers.
 *
 *   position  whole counts (int32, wrapping like the register)
 *             + fraction in U, 0 <= fraction < PMD_U_PER_COUNT = 6 * 2^32;
 *   velocity, acceleration  PmdFixed: whole counts (int64, wrapping mod 2^64)
 *             + fraction in 2^-33 count, 0 <= fraction < 2^33.
 *
 * Why two parts: the registers need P mod 2^32 counts, so V and A/2 mod 2^32
 * counts to 2^-33 count: 65 bits, more than one int64 in any one unit (which
 * is how velocity and acceleration once wrapped). With a 64-bit whole part
 * (A/2 is then right mod 2^63 counts) each cycle is a few additions, shifts
 * and masks and one floored division of the position's fraction
 * (pmd_floor_counts), in unsigned or bounded arithmetic: no rounding, no
 * drift and no overflow, however long a segment runs (CONTRACT 2.3). Within
 * an external segment the whole parts do not even wrap: |V| <= 2^15 + 2^47 +
 * 2^62 counts and |A| <= 2^15 + 2^31 for any segment time below 2^32.
 *
 * Register reads truncate toward minus infinity and wrap to 32 bits:
 * GetCommandedPosition = position, GetCommandedVelocity = floor(V * 2^16)
 * = (counts << 16) | (fraction >> 17), the same for the acceleration. */
#define PMD_U_PER_COUNT (6LL << 32)
#define PMD_U_PER_1616 (6LL << 16)

/* Division rounding toward minus infinity (the registers truncate that way). */
static inline int64_t pmd_floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

/* floor(a / 2^k), 0 <= k <= 63, without shifting a negative value. */
static inline int64_t pmd_floor_shift(int64_t a, int k)
{
    return a >= 0 ? a >> k : ~(~a >> k);
}

/* floor(a / (3 * 2^k)) for 3 <= k <= 61, exact for every int64 a: both units
 * above are 3 * 2^k (k = 33, 17). Run every cycle, so without a signed
 * division: the floored shift leaves |y| <= 2^(63-k), and the bias
 * 3 * 2^(63-k) makes the division by 3 unsigned. */
static inline int64_t pmd_floor_div_3x2k(int64_t a, int k)
{
    int64_t y = pmd_floor_shift(a, k);                            /* floor(a / 2^k) */
    return (int64_t)((uint64_t)(y + ((int64_t)3 << (63 - k))) / 3u) - ((int64_t)1 << (63 - k));
}
#define pmd_floor_counts(u) pmd_floor_div_3x2k((u), 33)           /* floor(u / PMD_U_PER_COUNT) */
#define pmd_floor_1616(u) pmd_floor_div_3x2k((u), 17)             /* floor(u / PMD_U_PER_1616) */

/* A 64-bit value in a 32-bit register: two's-complement wrap. */
static inline int32_t pmd_wrap32(int64_t x)
{
    return pmd_int32((uint32_t)((uint64_t)x & 0xFFFFFFFFu));
}

/* A 64-bit word read as a signed value (two's complement, portably). */
static inline int64_t pmd_int64(uint64_t u)
{
    return u <= (uint64_t)INT64_MAX ? (int64_t)u : -(int64_t)(~u) - 1;
}

/* ---- velocity and acceleration: whole counts + 33 fraction bits ---- */

#define PMD_FIXED_BITS 33
#define PMD_FIXED_ONE ((int64_t)1 << PMD_FIXED_BITS)               /* a count in the fraction's unit */

typedef struct {
    int64_t counts;        /* whole counts: the value floored; arithmetic wraps mod 2^64 */
    int64_t fraction;      /* the rest in 2^-33 count: 0 <= fraction < PMD_FIXED_ONE */
} PmdFixed;

#define PMD_FIXED_ZERO ((PmdFixed){0, 0})

static inline int pmd_fixed_is_zero(PmdFixed x)
{
    return x.counts == 0 && x.fraction == 0;
}

/* counts + s / 2^33 for |s| < 2^62: the whole part of s carried, wrapping. */
static inline PmdFixed pmd_fixed_make(int64_t counts, int64_t s)
{
    PmdFixed r;
    r.counts = pmd_int64((uint64_t)counts + (uint64_t)pmd_floor_shift(s, PMD_FIXED_BITS));
    r.fraction = (int64_t)((uint64_t)s & (uint64_t)(PMD_FIXED_ONE - 1));
    return r;
}

/* A 16.16 value x (any int64: x / 2^16 counts), exactly. */
static inline PmdFixed pmd_fixed_from_1616(int64_t x)
{
    PmdFixed r;
    r.counts = pmd_floor_shift(x, 16);
    r.fraction = (int64_t)(((uint64_t)x & 0xFFFFu) << (PMD_FIXED_BITS - 16));
    return r;
}

static inline PmdFixed pmd_fixed_add(PmdFixed x, PmdFixed y)
{
    return pmd_fixed_make(pmd_int64((uint64_t)x.counts + (uint64_t)y.counts), x.fraction + y.fraction);
}

static inline PmdFixed pmd_fixed_sub(PmdFixed x, PmdFixed y)
{
    return pmd_fixed_make(pmd_int64((uint64_t)x.counts - (uint64_t)y.counts), x.fraction - y.fraction);
}

/* x + d / 2^33 count for |d| < 2^61: the jerk terms J/2 = j, J = 2 j. */
static inline PmdFixed pmd_fixed_add_raw(PmdFixed x, int64_t d)
{
    return pmd_fixed_make(x.counts, x.fraction + d);
}

/* x / 2, exact when the fraction is even (an acceleration's always is). */
static inline PmdFixed pmd_fixed_half(PmdFixed x)
{
    PmdFixed r;
    r.counts = pmd_floor_shift(x.counts, 1);
    r.fraction = (x.fraction >> 1) | (int64_t)(((uint64_t)x.counts & 1u) << (PMD_FIXED_BITS - 1));
    return r;
}

/* x truncated to 16.16 (toward minus infinity). */
static inline PmdFixed pmd_fixed_floor_1616(PmdFixed x)
{
    x.fraction &= ~((PMD_FIXED_ONE >> 16) - 1);
    return x;
}

/* The 32-bit 16.16 register: floor(x * 2^16), wrapped. */
static inline int32_t pmd_fixed_register_1616(PmdFixed x)
{
    return pmd_int32((uint32_t)((uint64_t)x.counts << 16) | (uint32_t)(x.fraction >> (PMD_FIXED_BITS - 16)));
}

/* floor(x * 2^16) as a wide 16.16 value for the trajectory generators'
 * arithmetic: exact while |x| < 2^46 counts per cycle, held at +-2^62 beyond
 * (only an external profile handed over mid-segment can be that fast), so
 * that their sums cannot overflow. */
#define PMD_WIDE_1616_LIMIT ((int64_t)1 << 46)
static inline int64_t pmd_fixed_to_1616(PmdFixed x)
{
    if (x.counts >= PMD_WIDE_1616_LIMIT)
        return PMD_WIDE_1616_LIMIT << 16;
    if (x.counts < -PMD_WIDE_1616_LIMIT)
        return -(PMD_WIDE_1616_LIMIT << 16);
    return x.counts * 65536 + (x.fraction >> (PMD_FIXED_BITS - 16));
}

/* The Real outputs convert x in counts (pmd_commanded_reals): a value that
 * fits an int64 in U (|x| < 2^31/6 counts) from that integer, as the state once
 * held it, so that those Reals stay bit-identical: (double)*u / PMD_U_PER_COUNT
 * (pmd_fixed_in_u is 1); a larger one from its parts (pmd_fixed_wide_double). */
static inline int pmd_fixed_in_u(PmdFixed x, int64_t *u)
{
    const int64_t most = INT64_MAX / PMD_U_PER_COUNT;            /* whole counts that fit */
    int64_t rest = 3 * x.fraction;                                /* the fraction in U: below PMD_U_PER_COUNT */
    if (x.counts > -most && x.counts < most) {                    /* the usual case: no bound is near */
        *u = x.counts * PMD_U_PER_COUNT + rest;
        return 1;
    }
    if (x.counts >= 0 && x.counts <= most && x.counts * PMD_U_PER_COUNT <= INT64_MAX - rest) {
        *u = x.counts * PMD_U_PER_COUNT + rest;
        return 1;
    }
    if (x.counts < 0 && x.counts >= -most - 1 &&
        (x.counts + 1) * PMD_U_PER_COUNT >= INT64_MIN + (PMD_U_PER_COUNT - rest)) {
        *u = (x.counts + 1) * PMD_U_PER_COUNT + (rest - PMD_U_PER_COUNT);
        return 1;
    }
    return 0;
}

static inline double pmd_fixed_wide_double(PmdFixed x)
{
    return (double)x.counts + (double)x.fraction / (double)PMD_FIXED_ONE;
}

typedef struct {
    int32_t position;        /* whole counts; wraps like the 32-bit register */
    int64_t fraction;        /* of the position, in U: 0 <= fraction < PMD_U_PER_COUNT */
    PmdFixed velocity;       /* counts per cycle */
    PmdFixed acceleration;   /* counts per cycle^2 */
    int32_t jerk;            /* raw 0.32: 2^-32 counts per cycle^3 */
} PmdTrajectory;

/* The double-buffered trajectory registers (reference 4.1): the host writes
 * the buffered set, Update copies it to the active set. */
typedef struct {
    int32_t position;        /* destination, counts */
    int32_t velocity;        /* maximum velocity, 16.16 */
    uint32_t acceleration;   /* 16.16 */
    uint32_t deceleration;   /* 16.16, 0 = use acceleration */
    uint32_t jerk;           /* 0.32 */
    int32_t gearRatio;       /* 16.16 slave counts per master count */
    uint16_t profileMode;
    uint16_t stopMode;
    uint8_t clearPositionError;   /* ClearPositionError: applied by the next Update */
} PmdProfileRegisters;

/* The double-buffered filter registers (reference 4.1, filter group): the
 * host writes the buffered set, Update copies it to the active set. */
typedef struct {
    uint16_t kp, ki, kd, kvff, kaff, kout;
    uint32_t integrationLimit;   /* counts * cycles */
    uint16_t derivativeTime;     /* cycles between derivative samples */
    int16_t motorCommand;        /* SetMotorCommand: the motor output in open loop (motor off) */
} PmdFilterRegisters;

/* The servo filter of one axis (servo.c): its registers and its state. */
typedef struct {
    PmdFilterRegisters buffered, active;
    int32_t integral;            /* GetIntegral: sum of position errors, within the integration limit */
    int32_t derivativeError;     /* the position error at the last derivative sample */
    int16_t derivative;          /* GetDerivative: the error's change over the last derivative time */
    uint16_t derivativeCount;    /* cycles since the last derivative sample */
    int16_t output;              /* GetCurrentMotorCommand: the motor command of the last cycle */
} PmdFilter;

typedef struct {
    uint16_t sourceAxis;
    uint16_t action;
    uint16_t trigger;        /* 0 = disabled; reset to 0 when it fires */
    int32_t value;
} PmdBreakpoint;

/* What the trajectory generator is doing. */
typedef enum {
    PMD_MOTION_IDLE = 0,           /* at rest, no profile executing */
    PMD_MOTION_TRAPEZOIDAL,        /* point-to-point move toward the active destination */
    PMD_MOTION_SMOOTH_STOP,        /* braking at the deceleration rate to rest */
    PMD_MOTION_EXTERNAL,           /* reading segments from the buffers (seed 000) */
    PMD_MOTION_VELOCITY,           /* velocity contouring toward the active velocity */
    PMD_MOTION_SCURVE,             /* S-curve point-to-point (scurve.c) */
    PMD_MOTION_GEAR                /* following the gear master */
} PmdMotion;

/* An S-curve move: the unit-jerk curve with whole-cycle phases I..VII of
 * lengths t1, t2, t1, t4, t1, t2, t1, scaled to the distance (scurve.c). */
typedef struct {
    int64_t t1, t2, t4;
    int64_t step;            /* cycles executed */
    int64_t p6, v2, a;       /* the unit curve after `step` cycles: 6 P, 2 V, A */
    int64_t p6Total;         /* p6 at the end: 6 t1 (t1 + t2) (2 t1 + t2 + t4) */
    int64_t distance;        /* destination - start, counts */
    int32_t start;
    uint8_t stopping;        /* smooth stop: the cruise was cut short */
} PmdSCurve;

typedef struct {
    PmdProfileRegisters buffered, active;
    PmdSCurve scurve;
    PmdTrajectory trajectory;
    uint8_t motion;              /* PmdMotion */
    uint8_t atMaximumVelocity;
    uint8_t motorOn;
    uint8_t underrunWarned;      /* a read-past-write warning was logged and not yet cleared by a refill */
    uint8_t scurvePhase;         /* S-curve phase 1..7 shown as the profile segment while moving */
    uint32_t buffersChecked;     /* the buffer epoch at which this axis's buffers were last found fit to run */
    /* what an external profile reads, derived from the buffer set-up at that epoch (read_segment) */
    uint32_t segmentStart[PMD_FUNCTIONS];      /* start word of each assigned function's buffer */
    uint8_t segmentFunctions;                  /* bit per assigned function */
    uint8_t segmentBufferCount;                /* the distinct buffers read, whose indexes move */
    uint8_t segmentBuffer[PMD_FUNCTIONS];
    uint32_t segmentTime;        /* external profile: cycles left in the segment (seed 000 pseudo code) */
    int16_t bufferOfFunction[PMD_FUNCTIONS];   /* SetBufferFunction: buffer ID or -1 */
    uint16_t eventStatus;
    uint16_t interruptMask;
    PmdBreakpoint breakpoint[2];

    /* gear (not buffered) */
    uint16_t gearMasterAxis, gearMasterSource;
    int32_t gearMasterLast;       /* the master's position one cycle ago */

    /* actual position, errors and windows (reference 4.5) */
    int32_t actualPosition;
    int32_t previousActualPosition;
    int32_t actualOffset;         /* SetActualPosition's shifts: without loopback actual = input + offset;
                                   * with it, the stage's count a machine's switches are at is actual - offset */
    uint32_t positionErrorLimit;
    uint16_t settleTime, settleWindow, trackingWindow, settleCount;
    uint8_t autoStopMode, motionCompleteMode, motionCompletePending;
    uint8_t limitSwitchMode, inPositiveLimit, inNegativeLimit;

    /* signals and capture */
    uint16_t signalSense;
    uint8_t captureSource, homeWasActive, captured;
    uint8_t indexWasActive;       /* the index input as the last cycle's capture check saw it */
    int32_t captureValue;

    /* the servo filter and the motor output (servo.c) */
    PmdFilter filter;
    uint16_t motorLimit;          /* |motor command| limit, 0..32767 */
    int16_t motorBias;
    uint16_t outputMode;          /* DAC, PWM sign/magnitude, PWM 50/50: stored (docs/commands.md) */
    uint32_t startVelocity;       /* stepper motor types only: stored */

    /* hardware the FMU has no counterpart of: stored and read back (docs/commands.md) */
    uint16_t axisMode, axisOutSource, encoderSource, encoderModulus, actualPositionUnits;
    uint16_t encoderCounts, encoderSteps, stepRange;       /* SetEncoderToStepRatio, SetStepRange */
    uint16_t commutationMode, numberPhases, phaseInitializeMode, phasePrescale, phaseCorrectionMode;
    uint16_t phaseInitializeTime, phaseCounts, phaseOffset, phaseAngle;
    uint8_t phasingInitialized;   /* InitializePhase: activity bit 0 */

    /* inputs from the plant; a switch input is true while the switch is active */
    int32_t actualPositionInput;
    uint8_t positiveLimitInput, negativeLimitInput, homeInput;
    uint8_t indexInput;           /* the encoder's index line: true while the index pulse is active */

    /* the machine's motor (servo = "plant", machine.c): its shaft, physics rather than a register,
     * whose encoder count is actualPositionInput; a chip reset leaves it turning */
    double motorAngle;            /* rad */
    double motorSpeed;            /* rad/s */
} PmdAxis;

typedef struct {
    uint32_t start;          /* in 32-bit words */
    uint32_t length;         /* in 32-bit words */
    uint32_t readIndex;
    uint32_t writeIndex;
    uint32_t unread;         /* entries written by WriteBuffer and not yet read (for the overrun warnings) */
    uint8_t streamed;        /* written through WriteBuffer or SetBufferWriteIndex since set up */
} PmdBuffer;

/* The trace facility: samples into buffer 0 (reference 4.4). */
#define PMD_TRACE_SLOTS 4
typedef struct {
    uint16_t mode;           /* 0 one-time, 1 rolling */
    uint16_t period;         /* cycles between samples */
    uint16_t variable[PMD_TRACE_SLOTS];   /* bits 0-3 axis, 8-15 variable ID */
    uint16_t start, stop;    /* armed conditions; 0 once met */
    uint8_t active, wrapped;
    uint16_t countdown;      /* cycles to the next sample */
    uint32_t count;          /* values stored since the trace began */
} PmdTrace;

typedef struct {
    PmdAxis axis[PMD_AXES];
    PmdBuffer buffer[PMD_BUFFERS];
    PmdTrace trace;
    uint8_t updatedAxes;     /* axes updated since the last cycle's trace check (trace condition 1) */
    uint32_t bufferEpoch;    /* counts buffer set-ups and assignments: a running profile rechecks its buffers */
    uint16_t sampleTime;     /* SetSampleTime, microseconds */
    uint32_t time;           /* GetTime: chip time of the last executed cycle */
    uint32_t nextTime;       /* chip time of the next cycle */
    uint16_t hostIOError;    /* first error since last read; 1 after reset */
    uint8_t loopback;        /* actual position := commanded position */
    /* chip-wide hardware without a counterpart here: stored and read back */
    uint16_t serialPortMode, diagnosticPortMode, synchronizationMode;
    /* the peripheral bus (modelDescription/hardware.csv): inputs from the plant, WriteIO's latches */
    uint16_t analogInput[PMD_ANALOG_CHANNELS];   /* ReadAnalog(channel) */
    uint16_t ioInput[PMD_IO_PORTS];              /* ReadIO(address) */
    uint16_t ioOutput[PMD_IO_PORTS];             /* WriteIO(address, data) */
} PmdChipState;

/* The machine around the chip (docs/machine.md): per axis, which of its
 * switch and index inputs follow the axis's actual position, and where they
 * are active. Read-only configuration of the process (the FMU's `machine`
 * parameter, parsed by fmu_src/machine/machine_toml.c), not chip state: the
 * inputs it drives are the PmdAxis inputs above, which the state holds. */
#define PMD_MACHINE_INDEX_POSITIONS 16
enum {
    PMD_MACHINE_HOME = 1,             /* home = [lo, hi]: active for lo <= actual <= hi */
    PMD_MACHINE_POSITIVE_LIMIT = 2,   /* positive_limit = P: active for actual >= P */
    PMD_MACHINE_NEGATIVE_LIMIT = 4,   /* negative_limit = N: active for actual <= N */
    PMD_MACHINE_INDEX = 8             /* index = K or [p, ...]: a pulse at each multiple of K or listed position */
};
enum { PMD_MACHINE_SERVO_IDEAL, PMD_MACHINE_SERVO_PLANT };
typedef struct {
    uint8_t signals;                  /* PMD_MACHINE_* bits: the inputs the machine drives */
    uint16_t signalSense;             /* signal-status bits (home, limits, index) wired active high: the
                                       * level the chip sees is inverted unless SetSignalSense says so */
    int32_t homeLow, homeHigh;
    int32_t positiveLimit, negativeLimit;
    uint32_t indexPeriod;             /* 0: the listed positions */
    uint8_t indexCount;
    int32_t indexPosition[PMD_MACHINE_INDEX_POSITIONS];
    uint8_t servo;                    /* PMD_MACHINE_SERVO_*: servo = "ideal" or "plant" */
    PlantModel plant;                 /* servo = "plant": the motor's parameters (its state is PmdAxis's) */
} PmdMachineAxis;
typedef struct PmdMachine {
    PmdMachineAxis axis[PMD_AXES];
    unsigned axes;                    /* bit n: axis n has an input the machine drives (a plant's too) */
    unsigned plantAxes;               /* bit n: axis n's loop closes through the plant */
} PmdMachine;

/* Where the chip logs: each message under its category, a PmdLogCategory
 * (log_categories.h, generated from log_categories.csv: this header stays
 * plain C that compiles without the generated ones). */
typedef void (*PmdLogger)(void *context, unsigned category, const char *message);

/* The chip: its state, its external memory and where it logs. */
typedef struct PmdChip {
    PmdChipState s;
    uint32_t *memory;
    uint32_t memorySize;     /* in 32-bit words */
    PmdLogger logger;
    void *logContext;
    unsigned logMask;        /* bit per PmdLogCategory: format messages only when someone listens */
    const PmdMachine *machine;   /* the machine around the chip (its owner's), or NULL: inputs from the FMU */
} PmdChip;

/* Command table types (the table itself is generated from modelDescription/commands.csv). */
typedef enum { PMD_U16, PMD_I16, PMD_U32, PMD_I32, PMD_BITS } PmdFieldKind;

typedef struct {
    unsigned char kind;      /* PmdFieldKind */
    unsigned char word;      /* first data word of the value */
    unsigned char shift;     /* PMD_BITS: position and width inside the word */
    unsigned char width;
    unsigned char fixed;     /* fraction bits of a fixed-point value (16: 16.16, 32: 0.32), else 0 */
} PmdField;

/* A handler gets the decoded argument values, fills the reply values and
 * returns 0 or the host I/O error code; on error it has changed nothing. */
typedef int (*PmdHandler)(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply);

/* Register table types (the table itself is generated from modelDescription/registers.csv):
 * a plain stored register, whose Set and Get registers.c serves without a
 * handler of its own, as QEMU's RegisterAccessInfo (.reset, .ro) describes one. */
typedef enum {
    PMD_NOT_BUFFERED,
    PMD_BUFFERED_PROFILE,    /* in PmdAxis.buffered; Update copies it to PmdAxis.active (reference 4.1) */
    PMD_BUFFERED_FILTER      /* in PmdAxis.filter.buffered; Update copies it to .filter.active */
} PmdBufferedGroup;

/* Refuses a Set before anything else (e.g. pmd_trace_busy): 0 or the host I/O error code. */
typedef int (*PmdGuard)(const PmdChip *chip, const char *command);

typedef struct {
    const char *name;          /* its commands are Set<name> and Get<name> */
    unsigned char chipWide;    /* stored once in PmdChipState, else in every PmdAxis */
    unsigned char buffered;    /* PmdBufferedGroup */
    unsigned char readOnly;    /* the table serves only Get (a Set, if any, is a command with a handler) */
    unsigned char isSigned;    /* Get returns it as a signed value */
    unsigned char size;        /* of the member, in bytes: 1, 2 or 4 */
    size_t offset;             /* of the member in PmdChipState, PmdAxis or (buffered) PmdProfileRegisters or PmdFilterRegisters */
    unsigned char hasReset;    /* else pmd_chip_reset derives the value (e.g. the actual position) */
    int64_t reset, min, max;   /* reference 4.2's reset value; a Set outside min..max is refused */
    unsigned char error;       /* with this host I/O error code */
    const char *refusal;       /* and this reason in the log */
    PmdGuard guard;            /* or NULL */
} PmdRegister;

typedef struct {
    unsigned char opcode;
    const char *name;
    unsigned char chipWide;  /* C-Motion sends it with axis 0; the axis field is not used */
    unsigned char argWords, replyWords, nArgs, nReply;
    PmdField args[PMD_MAX_FIELDS];
    PmdField reply[PMD_MAX_FIELDS];
    PmdHandler handler;      /* NULL for a register's Set and Get: */
    const PmdRegister *reg;  /* registers.c serves them by the register table */
} PmdCommand;

#endif
