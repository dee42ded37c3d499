/* SPDX-License-Identifier: BSD-2-Clause */
/* The chip's serial packet protocol (pmd-reference 3.1-3.3), both ends, as pure functions: no I/O.
   A command packet is address, checksum, the instruction word's high byte (the axis field), the
   opcode, then the data words big-endian; a reply is status (the host I/O error code), checksum,
   the result words big-endian, or on error the 2 bytes alone; in multi-drop idle-line mode a reply
   starts with the responder's address. Every packet's bytes, checksum included, add up to 0 mod
   256. python/pmdfmu/serial_protocol.py is the same codec for `pmdfmu serve`; both are tested
   against tests/data/serial_vectors.csv. */
#ifndef PMD_SERIAL_H
#define PMD_SERIAL_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Data words a packet may carry: more than any command has (commands.csv: at most 5) */
#define PMD_SERIAL_MAX_ARGS 8
#define PMD_SERIAL_MAX_PACKET (4 + 2 * PMD_SERIAL_MAX_ARGS)
/* A reply's words: as many as the host port returns (host.reply[64]) */
#define PMD_SERIAL_MAX_REPLY 64

/* The byte that makes data's n bytes and itself add up to 0 mod 256 */
uint8_t PMDSerialChecksum(const uint8_t *data, size_t n);

/* A command packet into out (PMD_SERIAL_MAX_PACKET bytes): returns its length, 0 if nargs is
   outside 0..PMD_SERIAL_MAX_ARGS. */
size_t PMDSerialCommandPacket(uint8_t *out, uint8_t address, uint16_t instruction, const uint16_t *args, int nargs);

/* A reply's length: 2 + 2 * words, and its address byte first (idle-line) if addressed. */
size_t PMDSerialReplyLength(int words, int addressed);

/* The chip's reply into out (PMD_SERIAL_MAX_PACKET + 2 * PMD_SERIAL_MAX_REPLY bytes): the words
   only if status is 0; address < 0 for none. Returns its length. */
size_t PMDSerialReplyPacket(uint8_t *out, uint8_t status, const uint16_t *words, int nwords, int address);

/* A whole reply of n bytes, read as the host reads it: 0 and the status and words (at most
   maxwords), or -1 if it is malformed (a checksum that does not add up, a length that is not
   2 + 2 * words with the address byte if addressed, more words than maxwords). */
int PMDSerialParseReply(const uint8_t *data, size_t n, int addressed, uint8_t *status, uint16_t *words,
                        int maxwords, int *nwords);

/* The chip's receiver. A packet's length comes from its opcode (byte 3): argWords[opcode] data
   words (an opcode the chip lacks: 0; a value outside 0..PMD_SERIAL_MAX_ARGS counts as 0). */
typedef struct {
    uint8_t bytes[PMD_SERIAL_MAX_PACKET];
    size_t n;                   /* bytes of the packet not yet whole */
} PMDSerialDecoder;

typedef struct {
    uint8_t address;
    uint16_t instruction;       /* (axis byte << 8) | opcode */
    uint16_t args[PMD_SERIAL_MAX_ARGS];
    int nargs;
    int checksumOk;             /* 0: answered with the checksum error, never executed */
    size_t length;              /* the packet's bytes */
} PMDSerialPacket;

void PMDSerialDecoderReset(PMDSerialDecoder *decoder);

/* One byte in: 1 when it completes a packet (then *packet holds it), else 0. */
int PMDSerialDecode(PMDSerialDecoder *decoder, const signed char argWords[256], uint8_t byte, PMDSerialPacket *packet);

#ifdef __cplusplus
}
#endif

#endif
