/* The chip core: a PMD Navigator/Pilot-class motion processor's trajectory
 * side. Plain C, no FMI inside; the FMI wrappers in ../fmi drive it. */
#ifndef PMD_CHIP_H
#define PMD_CHIP_H

#include "chip_types.h"
#include "log_categories.h"     /* generated from modelDescription/log_categories.csv */
#include "pmd_constants.h"
#include "registers.h"

typedef void (*PmdLogger)(void *context, PmdLogCategory category, const char *message);

/* The chip: its state, its external memory and where it logs. */
struct PmdChip {
    PmdChipState s;
    uint32_t *memory;
    uint32_t memorySize;     /* in 32-bit words */
    PmdLogger logger;
    void *logContext;
    unsigned logMask;        /* bit per PmdLogCategory: format messages only when someone listens */
};

/* Chip-wide life cycle. The memory belongs to the caller; Reset keeps its contents. */
void pmd_chip_init(PmdChip *chip, uint32_t *memory, uint32_t memorySize);
void pmd_chip_reset(PmdChip *chip);

/* Runs one chip cycle: every axis's trajectory, then the status registers,
 * the breakpoints and the interrupt line. */
void pmd_chip_cycle(PmdChip *chip);

/* Runs `cycles` cycles, exactly as pmd_chip_cycle would one by one, deciding
 * once what cannot happen during the run. With record, row k (PMD_RECORD_WORDS
 * words, pmd_chip_record) holds the registers as cycle k left them. */
#define PMD_RECORD_WORDS (1 + 3 * PMD_AXES)
void pmd_chip_run(PmdChip *chip, int64_t cycles, int32_t *record);

/* One record row: chip time, then each axis's commanded position, velocity
 * and acceleration registers. */
void pmd_chip_record(const PmdChip *chip, int32_t row[PMD_RECORD_WORDS]);

/* Runs up to max cycles at once where that is exactly what running them one by
 * one would do (fastforward.c); returns how many it ran (0 if it cannot). Call
 * it after an ordinary cycle, with inputs unchanged. */
int64_t pmd_chip_fast_forward(PmdChip *chip, int64_t max);

/* Executes a batch of host words (whole commands as C-Motion sends them).
 * Get replies are appended to reply (at most PMD_BATCH_WORDS words).
 * Returns the host I/O error code of the first failing command, or 0.
 * *gridChanged (unless gridChanged is NULL) is 1 if a command of the batch
 * changed the cycle time (SetSampleTime): the caller restarts its time grid
 * there; else 0. A command handler says so by returning PMD_GRID_CHANGED, a
 * bit above the 8-bit error codes that pmd_host_batch strips. */
#define PMD_GRID_CHANGED 0x100
int pmd_host_batch(PmdChip *chip, const uint16_t *words, int count, uint16_t *reply, int *replyCount,
                   int *gridChanged);

/* Packs one value into a command's data words as the host port carries it. */
void pmd_encode_field(const PmdField *field, int64_t value, uint16_t *words);

/* The chip's one way of writing its external memory (WriteBuffer, trace
 * samples, the dual-port path): count words at address. Returns 0, or -1
 * (nothing written, an error logged) if the block leaves the memory. Every
 * caller checks its bounds first, so -1 is a bug: with PMD_CHECK_INVARIANTS
 * (sanitizer and fuzz builds) it aborts, so that fuzzing finds it. */
int pmd_memory_store(PmdChip *chip, uint32_t address, uint32_t count, const uint32_t *data);

/* The dual-port memory path, bypassing the processor, logged: returns -1
 * (nothing written) if the block leaves the memory, else pmd_memory_store's. */
int pmd_memory_write(PmdChip *chip, uint32_t address, uint32_t count, const uint32_t *data);

/* Register views. */
uint16_t pmd_activity_status(const PmdChip *chip, int axis);
uint16_t pmd_signal_status(const PmdChip *chip, int axis);
int pmd_host_interrupt(const PmdChip *chip);
#define pmd_commanded_velocity(t) pmd_fixed_register_1616((t)->velocity)
#define pmd_commanded_acceleration(t) pmd_fixed_register_1616((t)->acceleration)
/* The exact values as doubles, fraction kept: counts, counts/cycle, counts/cycle^2. */
#define pmd_commanded_position_counts(t) ((double)(t)->position + (double)(t)->fraction / (double)PMD_U_PER_COUNT)
#define pmd_commanded_velocity_counts(t) pmd_fixed_double((t)->velocity)
#define pmd_commanded_acceleration_counts(t) pmd_fixed_double((t)->acceleration)
int32_t pmd_position_error(const PmdAxis *ax);
int32_t pmd_actual_velocity(const PmdAxis *ax);

/* Engine entry points used by the command handlers and the cycle. */
void pmd_profile_cycle(PmdChip *chip, int axis);
void pmd_gear_cycle(PmdChip *chip, int axis);
void pmd_trace_cycle(PmdChip *chip);
int pmd_trace_busy(const PmdChip *chip, const char *command);
int pmd_update(PmdChip *chip, int axis);
void pmd_abrupt_stop(PmdChip *chip, int axis);
void pmd_halt(PmdChip *chip, int axis);
int pmd_scurve_plan(const PmdChip *chip, int axis, const PmdProfileRegisters *r, PmdSCurve *plan);
void pmd_scurve_cycle(PmdChip *chip, int axis);
void pmd_scurve_smooth_stop(PmdAxis *ax);
/* p6Total of a plan with these phase lengths (each at most 2^60), or -1 past 2^62. */
int64_t pmd_scurve_p6_total(int64_t t1, int64_t t2, int64_t t4);
/* Whether p6, v2 and a are the unit curve's after `step` steps of these phases. */
int pmd_scurve_on_curve(const PmdSCurve *c);
int pmd_segment_plan_valid(const PmdChip *chip, int n);
void pmd_set_event(PmdChip *chip, int axis, uint16_t mask);

/* Logging: pmd_log formats only when the category is enabled. */
void pmd_log(const PmdChip *chip, PmdLogCategory category, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
#define PMD_LOGGING(chip, category) ((chip)->logMask & (1u << (category)))

#endif
