/* SPDX-License-Identifier: BSD-2-Clause */
/* The serial packet codec (PMDserial.h; pmd-reference 3.1, 3.2). */
#include "PMDserial.h"

uint8_t PMDSerialChecksum(const uint8_t *data, size_t n)
{
    unsigned sum = 0;
    size_t i;
    for (i = 0; i < n; i++)
        sum += data[i];
    return (uint8_t)(0x100u - (sum & 0xFFu));
}

size_t PMDSerialCommandPacket(uint8_t *out, uint8_t address, uint16_t instruction, const uint16_t *args, int nargs)
{
    size_t n = 4;
    int i;
    if (nargs < 0 || nargs > PMD_SERIAL_MAX_ARGS)
        return 0;
    out[0] = address;
    out[1] = 0;
    out[2] = (uint8_t)(instruction >> 8);
    out[3] = (uint8_t)instruction;
    for (i = 0; i < nargs; i++) {
        out[n++] = (uint8_t)(args[i] >> 8);
        out[n++] = (uint8_t)args[i];
    }
    out[1] = PMDSerialChecksum(out, n);
    return n;
}

size_t PMDSerialReplyLength(int words, int addressed)
{
    return (addressed ? 1u : 0u) + 2u + 2u * (size_t)(words > 0 ? words : 0);
}

size_t PMDSerialReplyPacket(uint8_t *out, uint8_t status, const uint16_t *words, int nwords, int address)
{
    size_t n = 0, head;
    int i;
    if (address >= 0)
        out[n++] = (uint8_t)address;
    head = n;
    out[n++] = status;
    out[n++] = 0;
    /* on error the 2 bytes alone (reference 3.2) */
    for (i = 0; !status && i < nwords && i < PMD_SERIAL_MAX_REPLY; i++) {
        out[n++] = (uint8_t)(words[i] >> 8);
        out[n++] = (uint8_t)words[i];
    }
    out[head + 1] = PMDSerialChecksum(out, n);
    return n;
}

int PMDSerialParseReply(const uint8_t *data, size_t n, int addressed, uint8_t *status, uint16_t *words,
                        int maxwords, int *nwords)
{
    size_t skip = addressed ? 1u : 0u, i;
    int count;
    if (n < skip + 2 || (n - skip) % 2 || PMDSerialChecksum(data, n) != 0)
        return -1;
    count = (int)((n - skip - 2) / 2);
    if (count > maxwords || (data[skip] != 0 && count != 0))
        return -1;
    *status = data[skip];
    for (i = 0; i < (size_t)count; i++)
        words[i] = (uint16_t)(data[skip + 2 + 2 * i] << 8 | data[skip + 3 + 2 * i]);
    *nwords = count;
    return 0;
}

void PMDSerialDecoderReset(PMDSerialDecoder *decoder)
{
    decoder->n = 0;
}

int PMDSerialDecode(PMDSerialDecoder *decoder, const signed char argWords[256], uint8_t byte, PMDSerialPacket *packet)
{
    int words, i;
    size_t length;
    decoder->bytes[decoder->n++] = byte;
    if (decoder->n < 4)
        return 0;
    words = argWords[decoder->bytes[3]];
    if (words < 0 || words > PMD_SERIAL_MAX_ARGS)
        words = 0;
    length = 4 + 2 * (size_t)words;
    if (decoder->n < length)
        return 0;
    packet->address = decoder->bytes[0];
    packet->instruction = (uint16_t)(decoder->bytes[2] << 8 | decoder->bytes[3]);
    packet->nargs = words;
    for (i = 0; i < words; i++)
        packet->args[i] = (uint16_t)(decoder->bytes[4 + 2 * i] << 8 | decoder->bytes[5 + 2 * i]);
    packet->checksumOk = PMDSerialChecksum(decoder->bytes, length) == 0;
    packet->length = length;
    decoder->n = 0;
    return 1;
}
