/* SPDX-License-Identifier: BSD-2-Clause */
#ifndef PMD_NATIVE_MEMORY_PORT_H
#define PMD_NATIVE_MEMORY_PORT_H

/* Writing external memory through the FMU's memory port (Chip.write_memory,
 * python/pmdfmu/chip.py): per block of up to 64 words one set of
 * memory.data, .address, .count and a new .strobe, then a get of host.ack,
 * which executes the write (CONTRACT 2.2: gets see pending port writes
 * executed), through the FMU's own FMI functions with the arguments the
 * harness's Python loop passed (Chip._memory_strobe). */

#include <stddef.h>
#include <stdint.h>

#include "native.h"

/* The value references a strobe uses. FMI 2: memory.data[1] .. [64] (each
 * element its own Integer variable); FMI 3: data[0] is the UInt32 array
 * memory.data, the others unused. */
typedef struct {
    unsigned int data[64];
    unsigned int address;
    unsigned int count;
    unsigned int strobe;
    unsigned int ack;               /* host.ack: the get that executes the write */
} PmdMemoryPort;

/* Where a write stopped (PmdStop): in block `done` (the blocks before it written), a
 * call returned `status` > Warning; call is PMD_MEMORY_SET (fmi2SetInteger,
 * fmi3SetUInt32), PMD_MEMORY_SET_INT32 (fmi3SetInt32: count and strobe) or
 * PMD_MEMORY_GET (the get of host.ack). */
enum { PMD_MEMORY_SET, PMD_MEMORY_SET_INT32, PMD_MEMORY_GET };

/* Writes words[0 .. n) at address.., 64 a block, block k with memory.strobe
 * (strobe + k + 1) & 0x7FFFFFFF (strobe: the value memory.strobe holds).
 * FMI 2: set is fmi2SetInteger, get fmi2GetInteger. FMI 3: set is
 * fmi3SetUInt32 (memory.data whole, the words past a short block's count 0,
 * and memory.address), set_int32 fmi3SetInt32 (count, strobe), get
 * fmi3GetInt32. Returns 0, or 1 with *stop filled at the first call that
 * failed (nothing after it is called). */
PMD_NATIVE_EXPORT int pmd_memory_write_fmi2(PmdFmiFunction set, PmdFmiFunction get, void *instance,
                                            const PmdMemoryPort *port, uint32_t address, const uint32_t *words,
                                            size_t n, int32_t strobe, PmdStop *stop);
PMD_NATIVE_EXPORT int pmd_memory_write_fmi3(PmdFmiFunction set, PmdFmiFunction set_int32,
                                            PmdFmiFunction get, void *instance, const PmdMemoryPort *port,
                                            uint32_t address, const uint32_t *words, size_t n, int32_t strobe,
                                            PmdStop *stop);

#endif
