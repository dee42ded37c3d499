/* SPDX-License-Identifier: BSD-2-Clause */
/* The profile chapter (reference 1.2, 4.1): Update and MultiUpdate, the gear
 * master, the bump-free actual position changes and the trajectory's outputs.
 * The buffered profile registers themselves are rows of registers.csv. */
#include "commands.h"

int cmd_Update(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg; (void)reply;
    return pmd_update(chip, axis);
}

/* Axes update in ascending order; the first failure aborts the rest (reference 4.1). */
int cmd_MultiUpdate(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    int n;
    (void)axis; (void)reply;
    if (arg[0] & ~(int64_t)((1u << PMD_AXES) - 1u)) {
        pmd_log(chip, PMD_LOG_ERRORS, "MultiUpdate(0x%X): mask has bits beyond axis 4", (unsigned)arg[0]);
        return PMD_ERR_InvalidParameter;
    }
    for (n = 0; n < PMD_AXES; n++) {
        if (arg[0] & (1 << n)) {
            int err = pmd_update(chip, n);
            if (err)
                return err;
        }
    }
    return 0;
}

int cmd_GetCommandedVelocity(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = pmd_commanded_velocity(&AXIS(axis)->trajectory);
    return 0;
}

int cmd_GetCommandedAcceleration(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = pmd_commanded_acceleration(&AXIS(axis)->trajectory);
    return 0;
}

int cmd_SetGearMaster(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)reply;
    if (arg[0] >= PMD_AXES || arg[1] > PMDPositionSourceCommanded) {
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: SetGearMaster: master axis %d (0..3) or source %d (0..1) out of "
                "range", axis + 1, (int)arg[0], (int)arg[1]);
        return PMD_ERR_InvalidParameter;
    }
    AXIS(axis)->gearMasterAxis = (uint16_t)arg[0];
    AXIS(axis)->gearMasterSource = (uint16_t)arg[1];
    return 0;
}

int cmd_GetGearMaster(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = AXIS(axis)->gearMasterAxis;
    reply[1] = AXIS(axis)->gearMasterSource;
    return 0;
}

int cmd_ClearPositionError(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg; (void)reply;
    AXIS(axis)->buffered.clearPositionError = 1;
    return 0;
}

/* Moves the actual position by delta, and the commanded position and active
 * destination with it, so that nothing moves (reference 1.2); gear slaves of
 * this axis see no jump either. */
static void shift_actual(PmdChip *chip, int axis, int32_t delta)
{
    PmdAxis *ax = AXIS(axis);
    int n;
    ax->trajectory.position = pmd_int32((uint32_t)ax->trajectory.position + (uint32_t)delta);
    ax->active.position = pmd_int32((uint32_t)ax->active.position + (uint32_t)delta);
    /* with loopback too: a machine's switches stay where they are on the stage (machine.c) */
    ax->actualOffset = pmd_int32((uint32_t)ax->actualOffset + (uint32_t)delta);
    ax->actualPosition = pmd_int32((uint32_t)ax->actualPosition + (uint32_t)delta);
    ax->previousActualPosition = pmd_int32((uint32_t)ax->previousActualPosition + (uint32_t)delta);
    for (n = 0; n < PMD_AXES; n++)
        if (AXIS(n)->gearMasterAxis == axis)
            AXIS(n)->gearMasterLast = pmd_int32((uint32_t)AXIS(n)->gearMasterLast + (uint32_t)delta);
}

int cmd_SetActualPosition(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)reply;
    shift_actual(chip, axis, pmd_int32((uint32_t)arg[0] - (uint32_t)AXIS(axis)->actualPosition));
    return 0;
}

int cmd_AdjustActualPosition(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)reply;
    shift_actual(chip, axis, (int32_t)arg[0]);
    return 0;
}

int cmd_GetActualVelocity(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = pmd_actual_velocity(AXIS(axis));
    return 0;
}

int cmd_GetPositionError(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    (void)arg;
    reply[0] = pmd_position_error(AXIS(axis));
    return 0;
}
