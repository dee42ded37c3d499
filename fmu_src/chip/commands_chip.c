/* SPDX-License-Identifier: BSD-2-Clause */
/* Chip-wide commands of the reference's "Miscellaneous" chapter (1.2): no
 * operation, reset, version and the cycle time. */
#include "commands.h"

int cmd_NoOperation(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)chip; (void)axis; (void)arg; (void)reply;
    return 0;
}

int cmd_Reset(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis; (void)arg; (void)reply;
    pmd_chip_reset(chip);
    return 0;
}

int cmd_GetVersion(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)chip; (void)axis; (void)arg;
    reply[0] = 2;            /* generation: Navigator (reference 1.2, GetVersion) */
    reply[1] = 1;            /* motor type: brushed servo */
    reply[2] = PMD_AXES;
    reply[3] = 0;            /* special */
    reply[4] = 0;            /* custom */
    reply[5] = 1;            /* major */
    reply[6] = 0;            /* minor */
    return 0;
}

/* The cycle time, in microseconds; the FMU restarts its cycle grid at once
 * (CONTRACT 2.2): PMD_GRID_CHANGED tells pmd_host_batch's caller. */
int cmd_SetSampleTime(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis; (void)reply;
    if (arg[0] == 0) {
        pmd_log(chip, PMD_LOG_ERRORS, "SetSampleTime(0): the cycle time is 1..65535 microseconds");
        return PMD_ERR_InvalidParameter;
    }
    chip->s.sampleTime = (uint16_t)arg[0];
    return PMD_GRID_CHANGED;
}

int cmd_GetSampleTime(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)axis; (void)arg;
    reply[0] = chip->s.sampleTime;
    return 0;
}
