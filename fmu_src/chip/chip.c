/* Chip life cycle, the per-cycle sequence, status registers and breakpoints. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "chip.h"

void pmd_log(const PmdChip *chip, PmdLogCategory category, const char *format, ...)
{
    char message[512];
    va_list args;
    if (!PMD_LOGGING(chip, category) || !chip->logger)
        return;
    va_start(args, format);
    vsnprintf(message, sizeof message, format, args);
    va_end(args);
    chip->logger(chip->logContext, category, message);
}

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
    PmdAxis inputs[PMD_AXES];
    int n, f;

    memcpy(inputs, chip->s.axis, sizeof inputs);
    memset(&chip->s, 0, sizeof chip->s);
    chip->s.loopback = loopback;
    chip->s.hostIOError = PMD_ERR_ChipsetReset;   /* until read (reference 2.4) */
    for (n = 0; n < PMD_AXES; n++) {
        PmdAxis *ax = &chip->s.axis[n];
        ax->motorOn = 1;
        for (f = 0; f < PMD_FUNCTIONS; f++)
            ax->bufferOfFunction[f] = PMDBufferFunctionNone;
        /* the plant's inputs are wires, not registers: a reset does not change them */
        ax->actualPositionInput = inputs[n].actualPositionInput;
        ax->positiveLimitInput = inputs[n].positiveLimitInput;
        ax->negativeLimitInput = inputs[n].negativeLimitInput;
        ax->homeInput = inputs[n].homeInput;
        ax->actualPosition = loopback ? 0 : ax->actualPositionInput;
    }
}

void pmd_set_event(PmdChip *chip, int n, uint16_t mask)
{
    PmdAxis *ax = &chip->s.axis[n];
    if ((ax->eventStatus & mask) != mask)
        pmd_log(chip, PMD_LOG_EVENTS, "axis %d: event status |= 0x%04X", n + 1, (unsigned)mask);
    ax->eventStatus |= mask;
}

uint16_t pmd_activity_status(const PmdChip *chip, int n)
{
    const PmdAxis *ax = &chip->s.axis[n];
    uint16_t s = (uint16_t)((ax->active.profileMode & 7u) << 3);
    if (ax->atMaximumVelocity)
        s |= PMDActivityAtMaximumVelocityMask;
    if (ax->actualPosition == ax->trajectory.position)     /* |position error| <= tracking window (0) */
        s |= PMDActivityTrackingMask;
    if (ax->motorOn)
        s |= PMDActivityMotorOnMask;
    if (ax->motion != PMD_MOTION_IDLE)
        s |= PMDActivityInMotionMask;
    /* Seed 000, 1.6: the profile segment number is 1 while an external profile runs, 0 once halted. */
    if (ax->motion == PMD_MOTION_EXTERNAL)
        s |= 1u << 13;
    return s;
}

uint16_t pmd_signal_status(const PmdChip *chip, int n)
{
    const PmdAxis *ax = &chip->s.axis[n];
    uint16_t s = 0;
    if (ax->homeInput)
        s |= PMDSignalEncoderHomeMask;
    if (ax->positiveLimitInput)
        s |= PMDSignalPositiveLimitMask;
    if (ax->negativeLimitInput)
        s |= PMDSignalNegativeLimitMask;
    return s;
}

int pmd_host_interrupt(const PmdChip *chip)
{
    int n;
    for (n = 0; n < PMD_AXES; n++)
        if (chip->s.axis[n].eventStatus & chip->s.axis[n].interruptMask)
            return 1;
    return 0;
}

int pmd_memory_write(PmdChip *chip, uint32_t address, uint32_t count, const uint32_t *data)
{
    if (address > chip->memorySize || count > chip->memorySize - address)
        return -1;
    memcpy(chip->memory + address, data, count * sizeof *data);
    pmd_log(chip, PMD_LOG_BUFFERS, "dual-port memory: %u words written at 0x%X", (unsigned)count, (unsigned)address);
    return 0;
}

/* Status triggers: the high word of the value selects bits, the low word
 * gives the state each selected bit must reach; any one reaching it fires
 * (reference 2.5, seed 000 1.6). */
static int status_reached(uint16_t status, int32_t value)
{
    uint16_t select = (uint16_t)((uint32_t)value >> 16), sense = (uint16_t)((uint32_t)value & 0xFFFFu);
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
        case PMDBreakpointActionAbruptStop:
            pmd_abrupt_stop(chip, n);
            break;
        case PMDBreakpointActionSmoothStop:
            if (chip->s.axis[n].motion == PMD_MOTION_TRAPEZOIDAL)
                chip->s.axis[n].motion = PMD_MOTION_SMOOTH_STOP;
            break;
        case PMDBreakpointActionMotorOff:
            chip->s.axis[n].motorOn = 0;
            break;
        default:
            break;
        }
    }
}

void pmd_chip_cycle(PmdChip *chip)
{
    int n;
    chip->s.time = chip->s.nextTime++;
    for (n = 0; n < PMD_AXES; n++) {
        PmdAxis *ax = &chip->s.axis[n];
        pmd_profile_cycle(chip, n);
        ax->actualPosition = chip->s.loopback ? ax->trajectory.position : ax->actualPositionInput;
    }
    /* breakpoints last: a source axis may be any axis, and all have moved */
    for (n = 0; n < PMD_AXES; n++)
        check_breakpoints(chip, n);
}
