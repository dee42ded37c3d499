/* Register views: the status registers and the values the chip derives from
 * its state. Ground floor: they read the state and call nothing. */
#ifndef PMD_STATUS_H
#define PMD_STATUS_H

#include "events.h"

static inline uint32_t pmd_abs32(int32_t x)
{
    return x < 0 ? 0u - (uint32_t)x : (uint32_t)x;
}

uint16_t pmd_activity_status(const PmdChip *chip, int axis);
uint16_t pmd_signal_status(const PmdChip *chip, int axis);
int pmd_host_interrupt(const PmdChip *chip);
int32_t pmd_position_error(const PmdAxis *ax);
int32_t pmd_actual_velocity(const PmdAxis *ax);
/* GetPhaseCommand of phase 0..2 on the FMU's idle commutator: a brushed DAC axis
 * (GetVersion's motor type) drives phase A with the motor command; B and C read 0. */
static inline int16_t pmd_phase_command(const PmdAxis *ax, int phase)
{
    return phase == PMDPhaseA ? ax->filter.output : 0;
}
#define pmd_commanded_velocity(t) pmd_fixed_register_1616((t)->velocity)
#define pmd_commanded_acceleration(t) pmd_fixed_register_1616((t)->acceleration)
/* The exact values as doubles, fraction kept: counts, counts/cycle, counts/cycle^2. */
#define pmd_commanded_position_counts(t) ((double)(t)->position + (double)(t)->fraction / (double)PMD_U_PER_COUNT)
#define pmd_commanded_velocity_counts(t) pmd_fixed_double((t)->velocity)
#define pmd_commanded_acceleration_counts(t) pmd_fixed_double((t)->acceleration)

#endif
