/* SPDX-License-Identifier: BSD-2-Clause */
/* Chip.write_memory's strobes in C (memory_port.h): the calls the harness made
 * from Python per block of 64 words, the same FMI functions with the same
 * arguments in the same order, so that the memory, the port's variables and
 * the FMU's log are the same, at the cost of the FMU's own calls alone. */
#include <string.h>

#include "fmi2FunctionTypes.h"
#include "fmi3FunctionTypes.h"
#include "memory_port.h"

#define BLOCK_WORDS 64       /* memory.data[64]: the words one strobe writes */


static int stopped(PmdStop *stop, size_t blocks, int call, int status)
{
    stop->done = blocks;
    stop->call = call;
    stop->status = status;
    return 1;
}

/* The strobe of the block after `strobe`: memory.strobe is an Int32 the harness keeps non-negative. */
static int32_t next_strobe(int32_t strobe)
{
    return (int32_t)(((uint32_t)strobe + 1) & 0x7FFFFFFF);
}

int pmd_memory_write_fmi2(PmdFmiFunction set, PmdFmiFunction get, void *instance, const PmdMemoryPort *port,
                          uint32_t address, const uint32_t *words, size_t n, int32_t strobe, PmdStop *stop)
{
    /* one fmi2SetInteger: the block's data elements first, then address, count, strobe */
    fmi2ValueReference vrs[BLOCK_WORDS + 3];
    fmi2Integer values[BLOCK_WORDS + 3], ack;
    size_t start, block = 0;
    memcpy(vrs, port->data, sizeof port->data);
    for (start = 0; start < n; start += BLOCK_WORDS, block++) {
        size_t count = n - start < BLOCK_WORDS ? n - start : BLOCK_WORDS;
        int status;
        strobe = next_strobe(strobe);
        vrs[count] = port->address;
        vrs[count + 1] = port->count;
        vrs[count + 2] = port->strobe;
        memcpy(values, words + start, count * sizeof *values);  /* the word's 32 bits as a signed Integer */
        values[count] = (fmi2Integer)(address + start);
        values[count + 1] = (fmi2Integer)count;
        values[count + 2] = strobe;
        status = ((fmi2SetIntegerTYPE *)set)(instance, vrs, count + 3, values);
        if (PMD_FAILED(status))
            return stopped(stop, block, PMD_MEMORY_SET, status);
        status = ((fmi2GetIntegerTYPE *)get)(instance, &port->ack, 1, &ack);
        if (PMD_FAILED(status))
            return stopped(stop, block, PMD_MEMORY_GET, status);
    }
    return 0;
}

int pmd_memory_write_fmi3(PmdFmiFunction set, PmdFmiFunction set_int32, PmdFmiFunction get, void *instance,
                          const PmdMemoryPort *port, uint32_t address, const uint32_t *words, size_t n,
                          int32_t strobe, PmdStop *stop)
{
    /* memory.data is one UInt32 array of 64 set whole (a short block's tail 0), memory.address after it */
    const fmi3ValueReference data[2] = {port->data[0], port->address}, control[2] = {port->count, port->strobe};
    fmi3UInt32 values[BLOCK_WORDS + 1];
    fmi3Int32 counted[2], ack;
    size_t start, block = 0;
    for (start = 0; start < n; start += BLOCK_WORDS, block++) {
        size_t count = n - start < BLOCK_WORDS ? n - start : BLOCK_WORDS;
        int status;
        strobe = next_strobe(strobe);
        memcpy(values, words + start, count * sizeof *values);
        memset(values + count, 0, (BLOCK_WORDS - count) * sizeof *values);
        values[BLOCK_WORDS] = address + (uint32_t)start;
        status = ((fmi3SetUInt32TYPE *)set)(instance, data, 2, values, BLOCK_WORDS + 1);
        if (PMD_FAILED(status))
            return stopped(stop, block, PMD_MEMORY_SET, status);
        counted[0] = (fmi3Int32)count;
        counted[1] = strobe;
        status = ((fmi3SetInt32TYPE *)set_int32)(instance, control, 2, counted, 2);
        if (PMD_FAILED(status))
            return stopped(stop, block, PMD_MEMORY_SET_INT32, status);
        status = ((fmi3GetInt32TYPE *)get)(instance, &port->ack, 1, &ack, 1);
        if (PMD_FAILED(status))
            return stopped(stop, block, PMD_MEMORY_GET, status);
    }
    return 0;
}
