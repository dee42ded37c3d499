/* SPDX-License-Identifier: BSD-2-Clause */
/* Breakpoints (reference 2.5, seed 004): two per axis, each a packed word of
 * source axis, action and trigger, and a 32-bit comparison value. */
#include "commands.h"

static int breakpoint_id(const PmdChip *chip, int axis, const char *name, int64_t id)
{
    if (id > 1) {
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: %s: breakpoint %d is not 0 or 1", axis + 1, name, (int)id);
        return PMD_ERR_InvalidParameter;
    }
    return 0;
}

int cmd_SetBreakpoint(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    PmdBreakpoint *bp;
    int err = breakpoint_id(chip, axis, "SetBreakpoint", arg[0]);
    (void)reply;
    if (err)
        return err;
    if (arg[1] >= PMD_AXES || arg[2] > PMDBreakpointActionMotorOff || arg[3] > PMDBreakpointSignalStatus) {
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: SetBreakpoint: source axis %d, action %d or trigger %d out of range",
                axis + 1, (int)arg[1], (int)arg[2], (int)arg[3]);
        return PMD_ERR_InvalidParameter;
    }
    bp = &AXIS(axis)->breakpoint[arg[0]];
    bp->sourceAxis = (uint16_t)arg[1];
    bp->action = (uint16_t)arg[2];
    bp->trigger = (uint16_t)arg[3];
    /* A "crossed" trigger becomes >= or <= by where the source is now (reference 2.5). */
    if (bp->trigger == PMDBreakpointCommandedPositionCrossed)
        bp->trigger = AXIS(bp->sourceAxis)->trajectory.position < bp->value
                          ? PMDBreakpointGreaterOrEqualCommandedPosition : PMDBreakpointLessOrEqualCommandedPosition;
    else if (bp->trigger == PMDBreakpointActualPositionCrossed)
        bp->trigger = AXIS(bp->sourceAxis)->actualPosition < bp->value
                          ? PMDBreakpointGreaterOrEqualActualPosition : PMDBreakpointLessOrEqualActualPosition;
    return 0;
}

int cmd_GetBreakpoint(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    const PmdBreakpoint *bp;
    int err = breakpoint_id(chip, axis, "GetBreakpoint", arg[0]);
    if (err)
        return err;
    bp = &AXIS(axis)->breakpoint[arg[0]];
    reply[0] = bp->sourceAxis;
    reply[1] = bp->action;
    reply[2] = bp->trigger;
    return 0;
}

int cmd_SetBreakpointValue(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    int err = breakpoint_id(chip, axis, "SetBreakpointValue", arg[0]);
    (void)reply;
    if (!err)
        AXIS(axis)->breakpoint[arg[0]].value = (int32_t)arg[1];
    return err;
}

int cmd_GetBreakpointValue(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply)
{
    int err = breakpoint_id(chip, axis, "GetBreakpointValue", arg[0]);
    if (!err)
        reply[0] = AXIS(axis)->breakpoint[arg[0]].value;
    return err;
}
