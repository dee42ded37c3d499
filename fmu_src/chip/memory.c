/* SPDX-License-Identifier: BSD-2-Clause */
/* The chip's external memory (reference 4.3): the one way the chip writes it,
 * and the dual-port path from outside. */
#include <stdlib.h>
#include <string.h>

#include "events.h"
#include "memory.h"

int pmd_memory_store(PmdChip *chip, uint32_t address, uint32_t count, const uint32_t *data)
{
    if (address > chip->memorySize || count > chip->memorySize - address) {
        pmd_log(chip, PMD_LOG_ERRORS, "internal error: %u words at 0x%X leave the %u-word memory: not written",
                (unsigned)count, (unsigned)address, (unsigned)chip->memorySize);
#ifdef PMD_CHECK_INVARIANTS
        abort();
#endif
        return -1;
    }
    memcpy(chip->memory + address, data, count * sizeof *data);
    return 0;
}

int pmd_memory_write(PmdChip *chip, uint32_t address, uint32_t count, const uint32_t *data)
{
    if (address > chip->memorySize || count > chip->memorySize - address)
        return -1;               /* from outside: the caller says why */
    pmd_memory_store(chip, address, count, data);
    pmd_log(chip, PMD_LOG_BUFFERS, "dual-port memory: %u words written at 0x%X", (unsigned)count, (unsigned)address);
    return 0;
}
