/* SPDX-License-Identifier: BSD-2-Clause */
/* Bulk recording (record.c): record.data's buffer, the memory a caller
 * lends for it, and record.columns, the values a recording doStep
 * writes per cycle besides the chip time. Independent of the FMI version. */
#ifndef PMD_RECORD_H
#define PMD_RECORD_H

#include "instance_types.h"

/* Allocates record.data's buffer (record.capacity cycles of record.columns' rows) unless it
 * exists; never in doStep. A larger block keeps the rows recorded. */
PmdStatus pmd_record_allocate(PmdInstance *inst, const char *fn);
/* record.data's bytes: the rows the last doStep recorded (lent until the next call). */
void pmd_record_data(const PmdInstance *inst, const unsigned char **data, size_t *size);
/* pmdfmu_fmi2SetRecordBuffer and pmdfmu_fmi3SetRecordBuffer (fn, which messages about the memory name): the
 * caller's memory for the rows of the recording doSteps that follow, or NULL for record.data's buffer again. */
void pmd_record_lend(PmdInstance *inst, const char *fn, void *rows, size_t bytes);
/* Where a recording doStep writes its rows, and how many fit there (record.columns as it stands). */
unsigned char *pmd_record_rows(const PmdInstance *inst);
int64_t pmd_record_room(const PmdInstance *inst);

/* record.columns. Compiles a value: names checked and resolved to
 * value references once; PMD_ERROR with a message naming fn, the value and
 * the reason, *out untouched. */
PmdStatus pmd_record_columns_compile(PmdInstance *inst, const char *fn, const char *text, PmdRecordColumns *out);
void pmd_record_columns_free(PmdRecordColumns *columns);
/* The set call's staged value: checked (and the buffer grown if recording) with apply = 0, installed with 1. */
PmdStatus pmd_record_columns_set(PmdInstance *inst, const char *fn, const char *text, int apply);
/* A recording doStep with record.columns: runs `cycles` cycles, every one,
 * and writes each cycle's row into record.data from row `first` on, as the
 * getters would read it after that cycle. grid: the instance's grid as it
 * stands (a cycle changes no part of it); row k reads its next cycle as
 * grid->nextCycle + k + 1, and the instance advances its own nextCycle. */
void pmd_record_cycles(PmdInstance *inst, const PmdGrid *grid, int64_t cycles, int64_t first);

#endif
