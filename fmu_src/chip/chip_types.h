/* The chip's state: plain data, no pointers, so a copy is a snapshot.
 * Register names follow the Navigator/Pilot programmer's reference. */
#ifndef PMD_CHIP_TYPES_H
#define PMD_CHIP_TYPES_H

#include <stdint.h>

#define PMD_AXES 4
#define PMD_BUFFERS 32       /* buffer IDs 0..31; 0 and 1 belong to the trace (seed 000, 1.1) */
#define PMD_FIRST_PROFILE_BUFFER 2
#define PMD_FUNCTIONS 5      /* PMDBufferFunctionPosition .. PMDBufferFunctionTime */
#define PMD_MAX_FIELDS 8     /* argument or reply values of one command */
#define PMD_BATCH_WORDS 64   /* host.word[1..64], host.reply[1..64] */

/* A 32-bit register read as a signed value (two's complement, portably). */
static inline int32_t pmd_int32(uint32_t u)
{
    return u <= (uint32_t)INT32_MAX ? (int32_t)u : -(int32_t)(~u) - 1;
}


/* Exact trajectory state.
 *
 * Seed 000's external-profile recurrence, run once per cycle,
 *     P += V + A/2 + J/6,   V += A + J/2,   A += J,
 * with P in 32.0 counts, V and A in 16.16 and J in 0.32, has only integer
 * terms in the unit U = 2^-32/6 count:
 *     J/6 = j (the raw 0.32 value),  J/2 = 3j,  J = 6j,
 *     V = 6 * 2^16 * v and A = 6 * 2^16 * a for raw 16.16 values v, a.
 * A stays a multiple of 6, so A/2 is exact too. Holding V and A in U and the
 * position as whole counts plus a fraction in U makes every cycle exact: no
 * rounding, no drift, however long a segment runs (CONTRACT 2.3). Register
 * reads truncate toward minus infinity: GetCommandedVelocity = floor(V / (6 * 2^16)). */
#define PMD_U_PER_COUNT (6LL << 32)
#define PMD_U_PER_1616 (6LL << 16)

/* Division rounding toward minus infinity (the registers truncate that way). */
static inline int64_t pmd_floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

/* floor(a / (3 * 2^k)) for 3 <= k <= 61, exact for every int64 a: both units
 * above are 3 * 2^k (k = 33, 17). Run every cycle, so without a signed
 * division: the floored shift (no shift of a negative value) leaves
 * |y| <= 2^(63-k), and the bias 3 * 2^(63-k) makes the division by 3 unsigned. */
static inline int64_t pmd_floor_div_3x2k(int64_t a, int k)
{
    int64_t y = a >= 0 ? a >> k : ~(~a >> k);                     /* floor(a / 2^k) */
    return (int64_t)((uint64_t)(y + ((int64_t)3 << (63 - k))) / 3u) - ((int64_t)1 << (63 - k));
}
#define pmd_floor_counts(u) pmd_floor_div_3x2k((u), 33)           /* floor(u / PMD_U_PER_COUNT) */
#define pmd_floor_1616(u) pmd_floor_div_3x2k((u), 17)             /* floor(u / PMD_U_PER_1616) */

/* A 64-bit value in a 32-bit register: two's-complement wrap. */
static inline int32_t pmd_wrap32(int64_t x)
{
    return pmd_int32((uint32_t)((uint64_t)x & 0xFFFFFFFFu));
}

/* GetCommandedVelocity / GetCommandedAcceleration: U per cycle to 16.16, floored. */
static inline int32_t pmd_register_1616(int64_t u)
{
    return pmd_wrap32(pmd_floor_1616(u));
}

typedef struct {
    int32_t position;      /* whole counts; wraps like the 32-bit register */
    int64_t fraction;      /* 0 <= fraction < PMD_U_PER_COUNT */
    int64_t velocity;      /* U per cycle */
    int64_t acceleration;  /* U per cycle^2 */
    int32_t jerk;          /* raw 0.32: 2^-32 counts per cycle^3 */
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
    int32_t actualOffset;         /* without loopback: actual = input + offset (SetActualPosition) */
    uint32_t positionErrorLimit;
    uint16_t settleTime, settleWindow, trackingWindow, settleCount;
    uint8_t autoStopMode, motionCompleteMode, motionCompletePending;
    uint8_t limitSwitchMode, inPositiveLimit, inNegativeLimit;

    /* signals and capture */
    uint16_t signalSense;
    uint8_t captureSource, homeWasActive, captured;
    int32_t captureValue;

    /* inputs from the plant; a switch input is true while the switch is active */
    int32_t actualPositionInput;
    uint8_t positiveLimitInput, negativeLimitInput, homeInput;
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
    uint8_t sampleTimeChanged;
    uint32_t time;           /* GetTime: chip time of the last executed cycle */
    uint32_t nextTime;       /* chip time of the next cycle */
    uint16_t hostIOError;    /* first error since last read; 1 after reset */
    uint8_t loopback;        /* actual position := commanded position */
} PmdChipState;

/* Log categories, in the order of modelDescription/generate.py's LOG_CATEGORIES. */
typedef enum {
    PMD_LOG_ERRORS, PMD_LOG_WARNINGS, PMD_LOG_COMMANDS, PMD_LOG_BUFFERS, PMD_LOG_SEGMENTS, PMD_LOG_EVENTS,
    PMD_LOG_CATEGORY_COUNT
} PmdLogCategory;

typedef void (*PmdLogger)(void *context, PmdLogCategory category, const char *message);

/* The chip: its state, its external memory and where it logs. */
typedef struct PmdChip {
    PmdChipState s;
    uint32_t *memory;
    uint32_t memorySize;     /* in 32-bit words */
    PmdLogger logger;
    void *logContext;
    unsigned logMask;        /* bit per PmdLogCategory: format messages only when someone listens */
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
typedef int (*PmdHandler)(struct PmdChip *chip, int axis, const int64_t *arg, int64_t *reply);

typedef struct {
    unsigned char opcode;
    const char *name;
    unsigned char chipWide;  /* C-Motion sends it with axis 0; the axis field is not used */
    unsigned char argWords, replyWords, nArgs, nReply;
    PmdField args[PMD_MAX_FIELDS];
    PmdField reply[PMD_MAX_FIELDS];
    PmdHandler handler;
} PmdCommand;

#endif
