/* SPDX-License-Identifier: BSD-2-Clause */
/* Fuzz target: the host port. The input is a stream of 16-bit words, fed to
 * the chip as command batches of random sizes, with chip cycles in between.
 * Nothing may crash, and the chip must stay consistent. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "chip.h"

#define MEMORY 0x1000

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static uint32_t memory[MEMORY];
    PmdChip chip;
    uint16_t words[PMD_BATCH_WORDS], reply[PMD_BATCH_WORDS];
    size_t i = 0;
    memset(&chip, 0, sizeof chip);
    memset(memory, 0, sizeof memory);
    pmd_chip_init(&chip, memory, MEMORY);
    chip.s.loopback = 1;
    while (i + 1 < size) {
        int count = data[i++] % (PMD_BATCH_WORDS + 1), n = 0, replies, cycles;
        for (; n < count && i + 1 < size; n++, i += 2)
            words[n] = (uint16_t)(data[i] << 8 | data[i + 1]);
        pmd_host_batch(&chip, words, n, reply, &replies, NULL);
        if (replies < 0 || replies > PMD_BATCH_WORDS)
            abort();
        cycles = i < size ? data[i++] % 8 : 0;
        while (cycles--)
            pmd_chip_run_one_cycle(&chip);
        pmd_chip_skip_closed_form(&chip, 1000);
    }
    return 0;
}
