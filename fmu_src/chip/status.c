/* The status registers and the values the chip derives from its state
 * (reference 2.1-2.3, 4.5): read by the host, the cycle, breakpoints and the
 * trace; they change nothing. */
#include <string.h>
#if defined(__GNUC__) && defined(__x86_64__)
#include <cpuid.h>
#endif

#include "status.h"

/* GetActualVelocity: whole counts per cycle in 16.16 (the low word is 0). */
int32_t pmd_actual_velocity(const PmdAxis *ax)
{
    return pmd_int32(((uint32_t)ax->actualPosition - (uint32_t)ax->previousActualPosition) << 16);
}

/* The input levels of the signal status, AxisOut aside. Switches are wired
 * active low, as on PMD boards: an active switch (input true) reads 0, an idle
 * one 1. The encoder A, B and index lines read 1. */
static uint16_t input_levels(const PmdAxis *ax)
{
    uint16_t level = PMDSignalEncoderAMask | PMDSignalEncoderBMask | PMDSignalEncoderIndexMask;
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

/* The four axes' Reals computed together, each quantity as the lanes of one
 * vector where the compiler has vectors (GCC, Clang): the twenty divisions of a
 * row run as five packed ones with AVX, ten with SSE2. Each lane rounds as its
 * scalar operation would (IEEE 754), so the values do not depend on the form.
 * The lanes are built from registers and stored whole: a vector loaded from
 * scalars just stored, or the reverse, would stall on the store buffer. */
#if defined(__GNUC__) && !defined(PMD_PORTABLE_LANES)   /* PMD_PORTABLE_LANES: the plain C form (a test) */
typedef double Lanes __attribute__((vector_size(PMD_AXES * sizeof(double))));
#define LANES(a, b, c, d) ((Lanes){(a), (b), (c), (d)})
#define LANES_DIVIDE(x, y) ((x) /= (y))
#define LANES_ADD(x, y) ((x) += (y))
#else
typedef struct {
    double v[PMD_AXES];
} Lanes;
static Lanes lanes(double a, double b, double c, double d)
{
    Lanes x;
    x.v[0] = a, x.v[1] = b, x.v[2] = c, x.v[3] = d;
    return x;
}
#define LANES(a, b, c, d) lanes((a), (b), (c), (d))
#define LANES_DIVIDE(x, y) LANES_EACH(x, /=, y)
#define LANES_ADD(x, y) LANES_EACH(x, +=, y)
#define LANES_EACH(x, op, y)                                                                                          \
    do {                                                                                                              \
        int lane_;                                                                                                    \
        for (lane_ = 0; lane_ < PMD_AXES; lane_++)                                                                    \
            (x).v[lane_] op (y).v[lane_];                                                                             \
    } while (0)
#endif
#define LANES_OF(x) LANES((x), (x), (x), (x))
/* A lane per axis k, F(k) each: F has no side effect but a function call's (a
 * vector's initializers are not sequenced with each other; calls are). */
#define AXIS_LANES(F) LANES(F(0), F(1), F(2), F(3))

/* x in U as a double where it fits an int64 (pmd_fixed_in_u), else 0 and the
 * axis's bit set in *wide: its lane is redone from its parts. */
static inline double in_u(PmdFixed x, unsigned *wide, int n)
{
    int64_t u;
    if (pmd_fixed_in_u(x, &u))
        return (double)u;
    *wide |= 1u << n;
    return 0.0;
}

/* The body of pmd_commanded_reals, compiled twice on x86-64 (below). */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void commanded_reals(const PmdChip *chip, double cycleTime, PmdCommandedReals *r)
{
    const PmdTrajectory *t[PMD_AXES];
    unsigned wideVelocity = 0, wideAcceleration = 0;
    int n;
    Lanes u = LANES_OF((double)PMD_U_PER_COUNT), perCycle = LANES_OF(cycleTime);
    Lanes perCycle2 = LANES_OF(cycleTime * cycleTime), position, whole, velocity, acceleration;
    for (n = 0; n < PMD_AXES; n++)
        t[n] = &chip->s.axis[n].trajectory;
#define FRACTION(k) ((double)t[k]->fraction)
#define WHOLE(k) ((double)t[k]->position)
#define VELOCITY(k) in_u(t[k]->velocity, &wideVelocity, (k))
#define ACCELERATION(k) in_u(t[k]->acceleration, &wideAcceleration, (k))
    position = AXIS_LANES(FRACTION);
    whole = AXIS_LANES(WHOLE);
    velocity = AXIS_LANES(VELOCITY);
    acceleration = AXIS_LANES(ACCELERATION);
    LANES_DIVIDE(position, u);
    LANES_ADD(position, whole);
    LANES_DIVIDE(velocity, u);
    LANES_DIVIDE(velocity, perCycle);
    LANES_DIVIDE(acceleration, u);
    LANES_DIVIDE(acceleration, perCycle2);
    memcpy(r->position, &position, sizeof r->position);
    memcpy(r->velocity, &velocity, sizeof r->velocity);
    memcpy(r->acceleration, &acceleration, sizeof r->acceleration);
    if (wideVelocity | wideAcceleration)
        for (n = 0; n < PMD_AXES; n++) {
            if (wideVelocity & (1u << n))
                r->velocity[n] = pmd_fixed_wide_double(t[n]->velocity) / cycleTime;
            if (wideAcceleration & (1u << n))
                r->acceleration[n] = pmd_fixed_wide_double(t[n]->acceleration) / (cycleTime * cycleTime);
        }
}

/* An x86-64 build with GCC or Clang has an AVX form too, taken where the
 * processor has AVX (PmdChip.avx): four lanes a division instead of two. */
#if defined(__GNUC__) && defined(__x86_64__)
__attribute__((target("avx"))) static void commanded_reals_avx(const PmdChip *chip, double cycleTime,
                                                               PmdCommandedReals *r)
{
    commanded_reals(chip, cycleTime, r);
}
#define HAS_AVX_FORM 1

/* CPUID 1 says AVX and OSXSAVE, and XCR0 that the system saves the XMM and YMM
 * registers: what __builtin_cpu_supports("avx") tells, without the
 * process-wide variables of libgcc it reads. */
int pmd_processor_has_avx(void)
{
    unsigned a, b, c, d, low, high;
    if (!__get_cpuid(1, &a, &b, &c, &d) || !(c & bit_AVX) || !(c & bit_OSXSAVE))
        return 0;
    __asm__ volatile("xgetbv" : "=a"(low), "=d"(high) : "c"(0));
    (void)high;
    return (low & 6u) == 6u;
}
#else
int pmd_processor_has_avx(void)
{
    return 0;
}
#endif

void pmd_commanded_reals(const PmdChip *chip, double cycleTime, PmdCommandedReals *r)
{
#ifdef HAS_AVX_FORM
    if (chip->avx) {
        commanded_reals_avx(chip, cycleTime, r);
        return;
    }
#endif
    commanded_reals(chip, cycleTime, r);
}
