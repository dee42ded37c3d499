/* SPDX-License-Identifier: BSD-2-Clause */
/* One FMU instance: the chip, its memory, the host and dual-port memory
 * ports, the parameters and the time grid. Declared state (PmdInstanceState,
 * the chip's PmdChipState) apart from the process shell (PmdInstance).
 * Independent of the FMI version: the chip's model (fmi_common/model.h), which
 * the FMI shells (fmi_common/fmi2.c, fmi3.c) map the FMI APIs onto; this file
 * declares what the chip's model files (instance.c, record.c, state.c, model3.c)
 * share beyond that API. */
#ifndef PMD_INSTANCE_H
#define PMD_INSTANCE_H

#include <stddef.h>

#include "instance_types.h"
#include "messages.h"
#include "record.h"

/* The model API (model.h) is this instance's public face; what follows is
 * shared by the chip's model files beyond it. */

/* The `script` parameter's value: as set, or its start value. */
const char *pmd_script_value(const PmdInstance *inst);
/* Whether seconds is a cycle time the sample time register holds: whole microseconds, 1..65535. */
int pmd_cycle_time_valid(double seconds);

/* The time grid as it stands (PmdGrid, instance_types.h): from the end of
 * initialization on, the declared anchor and nextCycle, and the chip's sample
 * time register in seconds (sampleTime / 1e6, correctly rounded); before it,
 * the grid initialization will set up: anchored at time 0, cycle 0, with the
 * cycleTime parameter as the register will hold it. */
PmdGrid pmd_grid(const PmdInstanceState *s, const PmdChipState *chip);
/* The grid index of the first cycle at or after t (within a master's rounding). */
int64_t pmd_cycles_before(const PmdGrid *grid, double t);
/* Checks that arrays holding n values are not NULL; logs and returns 0 if one is. */
int pmd_arrays_given(const PmdInstance *inst, const char *fn, size_t n, const void *a, const void *b);

/* The row of a generated variable table that holds vr (of_vr: the row by value
 * reference, -1 none; max: the largest value reference), or -1, logged as "no
 * variable has value reference vr": the FMI 2 table's and variables3.h's alike. */
int pmd_variable_row(const PmdInstance *inst, const char *fn, unsigned vr, const short *of_vr, unsigned max);

/* Variable access beyond model.h's, one value at a time (model.h: a set call
 * is all or nothing). Integer values come as the FMI type holds them (FMI 3
 * UInt32 unsigned), so that a message shows the value the caller sent. */
PmdStatus pmd_set_integer(PmdInstance *inst, const char *fn, unsigned vr, int64_t value, int apply);
/* A block of memory.data (a strobe's words, Chip.write_memory), set at once
 * rather than value by value, with the same checks, messages and staging.
 * pmd_memory_data_span: how many of the n value references vr, vr + 1, ..
 * are elements of memory.data (0 if vr is none; element k + 1 is vr + k:
 * FMI 3's array and FMI 2's scalars alike, variables3.h). pmd_set_memory_data:
 * pmd_set_integer of each of those n elements in turn, the words 32-bit (FMI
 * 2 Integer: isSigned; FMI 3 UInt32: not). */
/* FMI 3's host port arrays as blocks (model3.c): pmd_set_host_words is pmd_set_integer of n
 * elements of host.word from vr on, pmd_get_host_reply pmd_model2_get_integer of n of host.reply
 * (their 16 bits) */
PmdStatus pmd_set_host_words(PmdInstance *inst, const char *fn, unsigned vr, const uint16_t *words, size_t n,
                             int apply);
PmdStatus pmd_get_host_reply(PmdInstance *inst, const char *fn, unsigned vr, uint16_t *words, size_t n);
size_t pmd_memory_data_span(unsigned vr, size_t n);
PmdStatus pmd_set_memory_data(PmdInstance *inst, const char *fn, unsigned vr, const void *words, int isSigned,
                              size_t n, int apply);

/* Executes pending host and memory port writes (host batch first; CONTRACT 2.1). */
void pmd_commit_ports(PmdInstance *inst);

#endif
