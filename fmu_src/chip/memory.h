/* SPDX-License-Identifier: BSD-2-Clause */
/* The chip's external memory: the caller's array of memorySize 32-bit words. */
#ifndef PMD_MEMORY_H
#define PMD_MEMORY_H

#include "events.h"

/* The chip's one way of writing its external memory (WriteBuffer, trace
 * samples, the dual-port path): count words at address. Returns 0, or -1
 * (nothing written, an error logged) if the block leaves the memory. Every
 * caller checks its bounds first, so -1 is a bug: with PMD_CHECK_INVARIANTS
 * (sanitizer and fuzz builds) it aborts, so that fuzzing finds it. */
int pmd_memory_store(PmdChip *chip, uint32_t address, uint32_t count, const uint32_t *data);

/* The dual-port memory path, bypassing the processor, logged: returns -1
 * (nothing written) if the block leaves the memory, else pmd_memory_store's. */
int pmd_memory_write(PmdChip *chip, uint32_t address, uint32_t count, const uint32_t *data);

#endif
