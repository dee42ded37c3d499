/* SPDX-License-Identifier: BSD-2-Clause */
/* Status and interrupts (reference 1.2, 2.1-2.4): the event, activity and
 * signal status, the capture, the host interrupt and the host I/O error. The
 * interrupt mask and the event status register are rows of registers.csv. */
#include "commands.h"

int cmd_GetHostIOError(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis; (void)arg;
    reply[0] = chip->s.hostIOError;
    chip->s.hostIOError = 0;                /* reading clears it (reference 2.4) */
    return 0;
}

int cmd_ResetEventStatus(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)reply;
    AXIS(axis)->eventStatus &= (uint16_t)arg[0];     /* bits written as 0 are cleared */
    return 0;
}

int cmd_GetActivityStatus(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = pmd_activity_status(chip, axis);
    return 0;
}

int cmd_GetSignalStatus(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = pmd_signal_status(chip, axis);
    return 0;
}

/* Reading the captured value re-arms the capture (reference 2.1, bit 9). */
int cmd_GetCaptureValue(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = AXIS(axis)->captureValue;
    AXIS(axis)->captured = 0;
    return 0;
}

/* The interrupt line is high while any axis has a masked event bit set;
 * ClearInterrupt cannot lower it before the host resets those bits. */
int cmd_ClearInterrupt(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)chip; (void)axis; (void)arg; (void)reply;
    return 0;
}

int cmd_GetInterruptAxis(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    int n;
    (void)axis; (void)arg;
    reply[0] = 0;
    for (n = 0; n < PMD_AXES; n++)
        if (AXIS(n)->eventStatus & AXIS(n)->interruptMask)
            reply[0] |= 1 << n;
    return 0;
}
