/* SPDX-License-Identifier: BSD-2-Clause */
/* Fuzz target: the serial packet codec (host/c/PMDserial.c; pmd-reference 3.1, 3.2), the chip's
 * packet decoder fed any byte stream, each packet's length from the chip's command table.
 *
 *   input = the bytes a host sends down the line
 *
 * Properties (abort() on a violation, after "property violated: ..."):
 *   - no sanitizer report (ASan, UBSan);
 *   - the decoder emits whole packets only: each is exactly 4 + 2 * (its opcode's argument words)
 *     bytes, the input's bytes in order, and what is left pending is shorter than a packet, so no
 *     partial command is ever executed; fed byte by byte or resumed after a reset (a disconnect)
 *     it emits the same packets from where it stands;
 *   - a packet's checksum is good exactly when its bytes add up to 0 mod 256, and a good packet
 *     encodes back to its own bytes (PMDSerialCommandPacket);
 *   - every reply the chip could send to it (status 0 with its reply words, or an error code
 *     alone, with or without the idle-line address byte) is well-formed: it parses back to the
 *     same status and words, and an error reply is 2 bytes (3 addressed);
 *   - the host's reply parser takes any slice of the input without reading outside it, and
 *     accepts only replies whose bytes add up to 0 mod 256. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "command_table.h"
#include "fuzz_property.h"
#include "PMDserial.h"

#define PROPERTY(holds, what)                                                                               \
    do {                                                                                                   \
        if (!(holds))                                                                                      \
            violated("%s", what);                                                                          \
    } while (0)

static signed char arg_words[256];

static void table(void)
{
    int op;
    for (op = 0; op < 256; op++)
        arg_words[op] = pmd_command_of_opcode[op] < 0 ? 0 : (signed char)pmd_commands[pmd_command_of_opcode[op]].argWords;
}

static int reply_words_of(uint8_t opcode)
{
    return pmd_command_of_opcode[opcode] < 0 ? 0 : pmd_commands[pmd_command_of_opcode[opcode]].replyWords;
}

static void check_reply(const PMDSerialPacket *p, uint8_t status, int address)
{
    uint8_t out[PMD_SERIAL_MAX_PACKET + 2 * PMD_SERIAL_MAX_REPLY], got_status = 0xFF;
    uint16_t words[PMD_SERIAL_MAX_REPLY], back[PMD_SERIAL_MAX_REPLY];
    int i, n = reply_words_of((uint8_t)p->instruction), nback = -1;
    size_t len;
    for (i = 0; i < n; i++)
        words[i] = (uint16_t)(p->instruction * 31u + (unsigned)i * 7u);
    len = PMDSerialReplyPacket(out, status, words, n, address);
    PROPERTY(len == PMDSerialReplyLength(status ? 0 : n, address >= 0), "a reply has 2 + 2 * words bytes");
    PROPERTY(PMDSerialParseReply(out, len, address >= 0, &got_status, back, PMD_SERIAL_MAX_REPLY, &nback) == 0,
             "the chip's reply parses");
    PROPERTY(got_status == status && nback == (status ? 0 : n), "a reply parses back to its status");
    for (i = 0; i < nback; i++)
        PROPERTY(back[i] == words[i], "a reply parses back to its words");
}

static void check_packet(const PMDSerialPacket *p, const uint8_t *bytes)
{
    uint8_t again[PMD_SERIAL_MAX_PACKET];
    unsigned sum = 0;
    size_t i;
    PROPERTY(p->length == 4 + 2 * (size_t)arg_words[(uint8_t)p->instruction], "a packet's length is its opcode's");
    PROPERTY(p->nargs == arg_words[(uint8_t)p->instruction], "a packet carries its opcode's words");
    for (i = 0; i < p->length; i++)
        sum += bytes[i];
    PROPERTY(p->checksumOk == ((sum & 0xFF) == 0), "the checksum is good exactly when the bytes add up to 0");
    PROPERTY(p->address == bytes[0] && p->instruction == (uint16_t)(bytes[2] << 8 | bytes[3]),
             "a packet's fields are its bytes");
    if (p->checksumOk) {
        PROPERTY(PMDSerialCommandPacket(again, p->address, p->instruction, p->args, p->nargs) == p->length &&
                 memcmp(again, bytes, p->length) == 0, "a good packet encodes back to its bytes");
        check_reply(p, 0, -1);
        check_reply(p, 2, -1);
        check_reply(p, 0, p->address);
    } else {
        check_reply(p, 9, -1);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    PMDSerialDecoder d, half;
    PMDSerialPacket p;
    size_t i, start = 0, cut = size / 2;
    uint8_t status;
    uint16_t words[PMD_SERIAL_MAX_REPLY];
    int nwords;
    table();
    PMDSerialDecoderReset(&d);
    for (i = 0; i < size; i++) {
        if (PMDSerialDecode(&d, arg_words, data[i], &p)) {
            PROPERTY(start + p.length == i + 1, "a packet is the bytes since the last one");
            check_packet(&p, data + start);
            start = i + 1;
        }
        PROPERTY(d.n == i + 1 - start, "the pending bytes are those since the last packet");
        PROPERTY(d.n < 4 || d.n < 4 + 2 * (size_t)arg_words[d.bytes[3]], "pending bytes are less than a packet");
    }
    /* a disconnect halfway: the decoder drops what was pending and starts afresh */
    PMDSerialDecoderReset(&half);
    for (i = cut; i < size; i++)
        if (PMDSerialDecode(&half, arg_words, data[i], &p))
            PROPERTY(p.length <= i + 1 - cut, "a packet after a reset is made of bytes after it");
    PROPERTY(half.n < PMD_SERIAL_MAX_PACKET, "a fresh decoder holds less than a packet");
    /* the host's parser on every prefix of the input (bounded) */
    for (i = 0; i <= size && i <= 2 + 2 * PMD_SERIAL_MAX_REPLY + 1; i++) {
        unsigned sum = 0;
        size_t k;
        if (PMDSerialParseReply(data, i, size % 2, &status, words, PMD_SERIAL_MAX_REPLY, &nwords) == 0) {
            for (k = 0; k < i; k++)
                sum += data[k];
            PROPERTY((sum & 0xFF) == 0, "a parsed reply's bytes add up to 0");
        }
    }
    return 0;
}
