/* SPDX-License-Identifier: BSD-2-Clause */
/* The chip core: a PMD Navigator/Pilot-class motion processor's trajectory
 * side. Plain C, no FMI inside; the FMI wrappers in ../fmi drive it.
 *
 * Layers, each calling only those below it (tests/test_chip_layers.py):
 *   events     the chip's log and event status bits (events.h)
 *   status     register views derived from the state (status.h)
 *   machine    the switch and index inputs that follow the actual position (machine.h)
 *   memory     the external memory (memory.h)
 *   scurve     the S-curve generator (scurve.h)
 *   profile    the trajectory generators, stops, Update (profile.h)
 *   servo      the servo filter and the motor output (servo.h)
 *   trace      the trace facility (trace.h)
 *   registers  the plain stored registers, served by their table (registers.h)
 *   chip       life cycle and the per-cycle sequence (this header), fast-forward
 *   commands   the command handlers, and host.c, the dispatcher that calls them
 * This header is the whole chip for the FMI layer and the command handlers. */
#ifndef PMD_CHIP_H
#define PMD_CHIP_H

#include "chip_types.h"
#include "events.h"
#include "machine.h"
#include "memory.h"
#include "pmd_constants.h"
#include "profile.h"
#include "registers.h"
#include "scurve.h"
#include "servo.h"
#include "status.h"
#include "trace.h"

/* Chip-wide life cycle. The memory belongs to the caller; Reset keeps its contents. */
void pmd_chip_init(PmdChip *chip, uint32_t *memory, uint32_t memorySize);
void pmd_chip_reset(PmdChip *chip);

/* What can happen in the coming cycles: the one description every path that
 * leaves work out reads (pmd_chip_run_every_cycle, _with_rows, the closed-form
 * skip and its policy). Only commands and the plant's inputs change it, and a cycle's
 * events (a motion-complete pending, a breakpoint's action): so a run decides
 * it once, the policy before each attempt. Bit n of a mask: axis n. */
typedef struct {
    int quiet;                  /* no trace, no axis geared, with a breakpoint armed or a switch active or
                                 * latched: no coupling of the axes and none of those checks can fire */
    unsigned deferredFilters;   /* in a quiet run, the axes of an ideal servo (loopback, motor on): the
                                 * position error stays 0, so one closed-form step at the run's end
                                 * brings the filter up to date (pmd_servo_advance) */
    int skippable;              /* no trace, no breakpoint armed, no motion complete pending, every axis at
                                 * rest or in an external segment with an ideal servo: the closed form of
                                 * the segments may skip cycles (pmd_chip_skip_closed_form) */
} PmdRunFacts;
PmdRunFacts pmd_chip_run_facts(const PmdChip *chip);

/* The chip's run entry points, by what they do (each leaves the chip as
 * pmd_chip_run_one_cycle called `cycles` times would):
 *   pmd_chip_run_one_cycle               one cycle
 *   pmd_chip_run_every_cycle             every cycle, optionally storing the default rows
 *   pmd_chip_run_every_cycle_with_rows   every cycle, a row callback after each
 *   pmd_chip_run_fast_forwarding         cycles in batches, skipping in closed form where that pays
 *   pmd_chip_skip_closed_form            the closed-form skip itself, up to max cycles at once */

/* Runs one chip cycle: every axis's trajectory, then the status registers,
 * the breakpoints and the interrupt line. */
void pmd_chip_run_one_cycle(PmdChip *chip);

/* Runs `cycles` cycles, every one, deciding once what cannot happen during
 * the run. With record, row k (PMD_RECORD_WORDS words, pmd_chip_record) holds
 * the registers as cycle k left them. */
#define PMD_RECORD_WORDS (1 + 3 * PMD_AXES)
void pmd_chip_run_every_cycle(PmdChip *chip, int64_t cycles, int32_t *record);

/* Runs `cycles` cycles, every one, as pmd_chip_run_every_cycle(chip, cycles,
 * NULL) does, calling row(context) after each: every register then reads as
 * that cycle left it but the servo filter (the motor command) of the axes
 * pmd_chip_deferred_axes names, which the run brings up to date at its end
 * (record.columns' rows, fmu_src/fmi/record.c). */
void pmd_chip_run_every_cycle_with_rows(PmdChip *chip, int64_t cycles, void (*row)(void *context), void *context);
/* The axes (bit n: axis n) whose servo filter a run of the chip as it stands
 * leaves to its end: an ideal servo's in a quiet run. */
unsigned pmd_chip_deferred_axes(const PmdChip *chip);

/* One record row: chip time, then each axis's commanded position, velocity
 * and acceleration registers. */
void pmd_chip_record(const PmdChip *chip, int32_t row[PMD_RECORD_WORDS]);

/* Skips up to max cycles at once, in the closed form of the segments, where
 * that is exactly what running them one by one would do (fastforward.c);
 * returns how many it skipped (0 if it cannot). Call it after an ordinary
 * cycle, with inputs unchanged. */
int64_t pmd_chip_skip_closed_form(PmdChip *chip, int64_t max);

/* Runs `cycles` cycles with the result of pmd_chip_run_every_cycle(chip,
 * cycles, NULL): ordinary cycles in batches, pmd_chip_skip_closed_form where
 * a cheap bound says it pays (fastforward.c): a doStep that records nothing. */
void pmd_chip_run_fast_forwarding(PmdChip *chip, int64_t cycles);

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

#endif
