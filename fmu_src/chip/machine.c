/* SPDX-License-Identifier: BSD-2-Clause */
/* The machine around the chip (machine.h): a switch is a range of actual
 * position, an index pulse a single count. The chip samples its encoder once
 * a cycle, so a pulse the axis runs over between two samples is seen in the
 * cycle that passes it, as a real index pulse would be latched by the
 * encoder's interface: never lost, whatever the speed. */
#include <math.h>

#include "events.h"
#include "machine.h"
#include "pmd_constants.h"

/* Whether a multiple of period lies in [low, high] (low <= high, 64-bit: no wrap). */
static int multiple_within(int64_t low, int64_t high, int64_t period)
{
    int64_t q = high / period;
    if (high % period != 0 && high < 0)
        q--;                                   /* floor(high / period) */
    return q * period >= low;
}

/* Whether a multiple of period is among the register's values low..high, counted on from before
 * without wrapping (64-bit): a run past either end of the 32-bit register is two runs of its values. */
static int multiple_passed(int64_t low, int64_t high, int64_t period)
{
    const int64_t wrap = INT64_C(1) << 32;
    if (low < INT32_MIN)
        return multiple_within(low + wrap, INT32_MAX, period) || multiple_within(INT32_MIN, high, period);
    if (high > INT32_MAX)
        return multiple_within(low, INT32_MAX, period) || multiple_within(INT32_MIN, high - wrap, period);
    return multiple_within(low, high, period);
}

int pmd_machine_index_active(const PmdMachineAxis *m, int32_t before, int32_t now)
{
    /* the counts passed since the last sample: (before, now] upward, [now, before) downward,
     * the one count now at rest; the step as the 32-bit register wraps, counted on from before */
    int64_t step = pmd_int32((uint32_t)now - (uint32_t)before);
    int64_t low = step > 0 ? (int64_t)before + 1 : (int64_t)before + step;
    int64_t high = step < 0 ? (int64_t)before - 1 : (int64_t)before + step;
    unsigned i;
    if (m->indexPeriod != 0)
        return multiple_passed(low, high, m->indexPeriod);
    for (i = 0; i < m->indexCount; i++) {
        int64_t d = pmd_int32((uint32_t)m->indexPosition[i] - (uint32_t)before);   /* from before, wrapped */
        if (step == 0 ? d == 0 : step > 0 ? (d > 0 && d <= step) : (d < 0 && d >= step))
            return 1;
    }
    return 0;
}

/* A switch's input: true while the chip, at its reset signal sense, sees it
 * active; a switch the machine wires active high reads the other way. */
static uint8_t level(const PmdMachineAxis *m, uint16_t bit, int active)
{
    return (uint8_t)((m->signalSense & bit) ? !active : active != 0);
}

void pmd_machine_inputs(PmdChip *chip, int n)
{
    const PmdMachineAxis *m = &chip->machine->axis[n];
    PmdAxis *ax = &chip->s.axis[n];
    /* the stage's count: SetActualPosition and AdjustActualPosition move the register, not the stage */
    int32_t at = pmd_int32((uint32_t)ax->actualPosition - (uint32_t)ax->actualOffset);
    int32_t before = pmd_int32((uint32_t)ax->previousActualPosition - (uint32_t)ax->actualOffset);
    if (m->signals & PMD_MACHINE_HOME)
        ax->homeInput = level(m, PMDSignalEncoderHomeMask, at >= m->homeLow && at <= m->homeHigh);
    if (m->signals & PMD_MACHINE_POSITIVE_LIMIT)
        ax->positiveLimitInput = level(m, PMDSignalPositiveLimitMask, at >= m->positiveLimit);
    if (m->signals & PMD_MACHINE_NEGATIVE_LIMIT)
        ax->negativeLimitInput = level(m, PMDSignalNegativeLimitMask, at <= m->negativeLimit);
    if (m->signals & PMD_MACHINE_INDEX)
        ax->indexInput = level(m, PMDSignalEncoderIndexMask,
                               pmd_machine_index_active(m, before, at));
}

/* The plant's model (plant.h) with the machine's parameters and the axis's shaft. */
static PlantModel motor_of(const PmdChip *chip, int n)
{
    PlantModel m = chip->machine->axis[n].plant;
    m.angle = chip->s.axis[n].motorAngle;
    m.speed = chip->s.axis[n].motorSpeed;
    m.motorCommand = chip->s.axis[n].filter.output;
    return m;
}

void pmd_machine_plant_start(PmdChip *chip, int n)
{
    PlantModel m = chip->machine->axis[n].plant;
    plant_start(&m);
    chip->s.axis[n].motorAngle = m.angle;
    chip->s.axis[n].motorSpeed = m.speed;
    chip->s.axis[n].actualPositionInput = m.encoderCount;
}

void pmd_machine_plant_cycle(PmdChip *chip, int n)
{
    PlantModel m = motor_of(chip, n);
    /* the plant FMU's step of one communication step, h the cycle as the FMU's grid has it (sampleTime us) */
    plant_advance(&m, chip->s.sampleTime / 1e6);
    if (!isfinite(m.angle) || !isfinite(m.speed)) {
        /* the parser's ranges keep a motor finite for longer than any run; the plant FMU refuses such a
         * step, and so does the machine: the shaft stays where it was */
        pmd_log(chip, PMD_LOG_ERRORS, "axis %d: the machine's motor would leave the range of doubles (angle %g, "
                "speed %g): not moved", n + 1, m.angle, m.speed);
        return;
    }
    chip->s.axis[n].motorAngle = m.angle;
    chip->s.axis[n].motorSpeed = m.speed;
    chip->s.axis[n].actualPositionInput = m.encoderCount;
}
