/* The status registers and the values the chip derives from its state
 * (reference 2.1-2.3, 4.5): read by the host, the cycle, breakpoints and the
 * trace; they change nothing. */
#include "status.h"

int32_t pmd_position_error(const PmdAxis *ax)
{
    return pmd_int32((uint32_t)ax->actualPosition - (uint32_t)ax->trajectory.position);
}

/* GetActualVelocity: whole counts per cycle in 16.16 (the low word is 0). */
int32_t pmd_actual_velocity(const PmdAxis *ax)
{
    return pmd_int32(((uint32_t)ax->actualPosition - (uint32_t)ax->previousActualPosition) << 16);
}

uint16_t pmd_activity_status(const PmdChip *chip, int n)
{
    const PmdAxis *ax = &chip->s.axis[n];
    uint32_t s = PMD_FIELD_DP(0, PMDActivityProfileMode, ax->active.profileMode);
    if (ax->phasingInitialized)
        s |= PMDActivityPhasingInitializedMask;      /* InitializePhase (commands_hardware.c) */
    if (ax->atMaximumVelocity)
        s |= PMDActivityAtMaximumVelocityMask;
    if (pmd_abs32(pmd_position_error(ax)) <= ax->trackingWindow)
        s |= PMDActivityTrackingMask;
    if (ax->motion == PMD_MOTION_IDLE && ax->settleCount > ax->settleTime)
        s |= PMDActivityAxisSettledMask;
    if (ax->motorOn)
        s |= PMDActivityMotorOnMask;
    if (ax->captured)
        s |= PMDActivityPositionCaptureMask;
    if (ax->motion != PMD_MOTION_IDLE)
        s |= PMDActivityInMotionMask;
    if (ax->inPositiveLimit)
        s |= PMDActivityInPositiveLimitMask;
    if (ax->inNegativeLimit)
        s |= PMDActivityInNegativeLimitMask;
    /* Seed 000, 1.6: the profile segment number is 1 while an external profile runs, 0 once halted. */
    if (ax->motion == PMD_MOTION_EXTERNAL)
        s = PMD_FIELD_DP(s, PMDActivityProfileSegment, 1);
    else if (ax->motion == PMD_MOTION_SCURVE)
        s = PMD_FIELD_DP(s, PMDActivityProfileSegment, ax->scurvePhase);   /* reference 5: the S-curve phase 1..7 */
    return (uint16_t)s;
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
