/* SPDX-License-Identifier: BSD-2-Clause */
/* The host timing model (PMDhosttime.h). Every time is a whole number of nanoseconds; a
   transfer whose exact time is a fraction of a nanosecond (a serial byte at 57600 baud) is
   rounded up, transfer by transfer, so the host clock never runs on a float. */
#include <string.h>

#include "PMDhosttime.h"

static const PMDHostInterface defaults[PMDHostKinds] = PMD_HOST_INTERFACE_DEFAULTS;
static const char *const names[PMDHostKinds] = PMD_HOST_INTERFACE_NAMES;

PMDHostInterface PMDHostInterfaceOf(int kind)
{
    return defaults[kind >= 0 && kind < PMDHostKinds ? kind : PMDHostNone];
}

PMDHostInterface PMDHostInterfaceDefault(void)
{
    return PMDHostInterfaceOf(PMDHostParallel16);
}

int PMDHostInterfaceKind(const char *name)
{
    int k;
    for (k = 0; name && k < PMDHostKinds; k++)
        if (strcmp(name, names[k]) == 0)
            return k;
    return -1;
}

const char *PMDHostInterfaceName(int kind)
{
    return kind >= 0 && kind < PMDHostKinds ? names[kind] : NULL;
}

static const struct {
    int kind;
    const char *name;
    size_t offset;
    uint32_t min, max;
} ranges[] = PMD_HOST_INTERFACE_RANGES;

const char *PMDHostInterfaceRefused(const PMDHostInterface *h, uint32_t *value, uint32_t *min, uint32_t *max)
{
    size_t i;
    if (h->kind < 0 || h->kind >= PMDHostKinds) {
        *value = (uint32_t)h->kind, *min = 0, *max = PMDHostKinds - 1;
        return "kind";
    }
    for (i = 0; i < sizeof ranges / sizeof *ranges; i++) {
        uint32_t v;
        if (ranges[i].kind != h->kind)
            continue;
        memcpy(&v, (const char *)h + ranges[i].offset, sizeof v);
        if (v < ranges[i].min || v > ranges[i].max) {
            *value = v, *min = ranges[i].min, *max = ranges[i].max;
            return ranges[i].name;
        }
    }
    return NULL;
}

/* ceil(bits * 1e9 / rate): the time of `bits` bits at `rate` bits per second */
static uint64_t bits_ns(uint64_t bits, uint32_t rate)
{
    return rate ? (bits * 1000000000u + rate - 1) / rate : 0;
}

/* A serial byte: 1 start bit, the data bits, the parity bit if any, the stop bits (pmd-reference 3.3). */
static uint64_t serial_bits_per_byte(const PMDHostInterface *h)
{
    return 1u + h->dataBits + h->parity + h->stopBits;
}

/* The parallel port's bus cycles per 16-bit word: one on the 16-bit bus, two bytes on the 8-bit one. */
static uint64_t bus_cycles_per_word(const PMDHostInterface *h)
{
    return h->kind == PMDHostParallel8 ? 2u : 1u;
}

uint64_t PMDHostRequestNs(const PMDHostInterface *h, int words)
{
    uint64_t w = words > 0 ? (uint64_t)words : 0u;
    switch (h->kind) {
    case PMDHostParallel16:
    case PMDHostParallel8:
        /* each word: a status read until HostRdy, then the word's write (pmd-reference 3.4, steps 1-2) */
        return w * (1u + bus_cycles_per_word(h)) * h->busCycleNs;
    case PMDHostSerial:
        /* address, checksum, then each word high byte first: 4 + 2 * data words bytes (reference 3.1) */
        return bits_ns((2u + 2u * w) * serial_bits_per_byte(h), h->baud);
    case PMDHostSPI:
        return bits_ns((h->requestHeaderWords + w) * 16u, h->clockHz);
    case PMDHostFixed:
        return h->requestNs;
    default:
        return 0;
    }
}

uint64_t PMDHostReplyNs(const PMDHostInterface *h, int words, int failed)
{
    uint64_t w = failed || words < 0 ? 0u : (uint64_t)words;
    switch (h->kind) {
    case PMDHostParallel16:
    case PMDHostParallel8:
        /* the chip works until HostRdy; one status read tests the I/O-error bit; then each result
           word (and the checksum word if read): a status read and the word's read (reference 3.4,
           steps 3-5). A failed command returns no word. */
        return h->processingNs + h->busCycleNs +
               (failed ? 0u : (w + h->checksum) * (1u + bus_cycles_per_word(h)) * h->busCycleNs);
    case PMDHostSerial:
        /* status, checksum, then the words: 2 + 2 * words bytes; 2 bytes on an error (reference 3.2) */
        return h->processingNs + bits_ns((2u + 2u * w) * serial_bits_per_byte(h), h->baud);
    case PMDHostSPI:
        return h->processingNs + bits_ns((h->replyHeaderWords + w) * 16u, h->clockHz);
    case PMDHostFixed:
        return h->replyNs;
    default:
        return 0;
    }
}

uint64_t PMDHostTransferNs(const PMDHostInterface *h, int direction, int words, int failed)
{
    return direction == PMDHostReply ? PMDHostReplyNs(h, words, failed) : PMDHostRequestNs(h, words);
}

uint64_t PMDHostCyclesDue(uint64_t hostNs, uint64_t nextCycleNs, uint64_t cycleNs)
{
    return cycleNs == 0 || hostNs < nextCycleNs ? 0u : (hostNs - nextCycleNs) / cycleNs + 1u;
}
