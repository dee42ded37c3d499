/* SPDX-License-Identifier: BSD-2-Clause */
/* The harness's native side (python/pmdfmu/native.py loads it with ctypes):
 * loops that would cost a Python call per cycle or per word, run in C over
 * the FMU's own FMI functions. Not part of any FMU: it calls an FMU only
 * through the function pointers and instance the harness hands it. */
#include <stddef.h>

#include "abi.h"
#include "host_port.h"
#include "system.h"
#include "memory_port.h"
#include "record_loop.h"

/* The harness checks it loaded a library of its own version. */
int pmd_native_abi(void)
{
    return PMD_NATIVE_ABI;
}

#define SIZE(type) sizeof(type)
#define AT(type, member) offsetof(type, member)

size_t pmd_native_layout(size_t *out, size_t n)
{
    /* python/pmdfmu/native.py LAYOUT lists the same, in this order */
    const size_t layout[] = {
        SIZE(PmdStop), AT(PmdStop, done), AT(PmdStop, call), AT(PmdStop, status),
        SIZE(PmdLoopGroup), AT(PmdLoopGroup, get), AT(PmdLoopGroup, vrs), AT(PmdLoopGroup, n_vrs),
        AT(PmdLoopGroup, n_values), AT(PmdLoopGroup, type), AT(PmdLoopGroup, values),
        SIZE(PmdLoopColumn), AT(PmdLoopColumn, source), AT(PmdLoopColumn, offset), AT(PmdLoopColumn, size),
        AT(PmdLoopColumn, truth),
        SIZE(PmdMemoryPort), AT(PmdMemoryPort, data), AT(PmdMemoryPort, address), AT(PmdMemoryPort, count),
        AT(PmdMemoryPort, strobe), AT(PmdMemoryPort, ack),
        SIZE(PmdHostPort), AT(PmdHostPort, get_int), AT(PmdHostPort, set_int), AT(PmdHostPort, set_words),
        AT(PmdHostPort, get_words), AT(PmdHostPort, get_real), AT(PmdHostPort, do_step), AT(PmdHostPort, instance),
        AT(PmdHostPort, fmi3), AT(PmdHostPort, word), AT(PmdHostPort, reply), AT(PmdHostPort, word_count),
        AT(PmdHostPort, strobe), AT(PmdHostPort, ack), AT(PmdHostPort, error), AT(PmdHostPort, reply_count),
        AT(PmdHostPort, grid), AT(PmdHostPort, timed), AT(PmdHostPort, host_ns), AT(PmdHostPort, request_ns),
        AT(PmdHostPort, reply_ns), AT(PmdHostPort, failed_ns), AT(PmdHostPort, in), AT(PmdHostPort, out),
        AT(PmdHostPort, count), AT(PmdHostPort, error_word), AT(PmdHostPort, ack_word),
        AT(PmdHostPort, strobe_sent), AT(PmdHostPort, stop),
        SIZE(PmdSystemValue), AT(PmdSystemValue, integer), AT(PmdSystemValue, real),
        SIZE(PmdSystemOp), AT(PmdSystemOp, kind), AT(PmdSystemOp, type), AT(PmdSystemOp, fn),
        AT(PmdSystemOp, instance), AT(PmdSystemOp, vr), AT(PmdSystemOp, value),
        SIZE(PmdSystemColumn), AT(PmdSystemColumn, value), AT(PmdSystemColumn, offset), AT(PmdSystemColumn, size),
        AT(PmdSystemColumn, real),
        PMD_LOOP_DOUBLE, PMD_LOOP_INT32, PMD_LOOP_UINT32, PMD_LOOP_UINT16, PMD_LOOP_INT16, PMD_LOOP_INT, PMD_LOOP_BOOL,
        PMD_MEMORY_SET, PMD_MEMORY_SET_INT32, PMD_MEMORY_GET,
        PMD_STEP_LEND, PMD_STEP_DO_STEP, PMD_STEP_GET_DATA, PMD_STEP_END_LOAN,
        (size_t)-PMD_LOOP_FIELD_SIZE,
        PMD_HOST_GET_STROBE, PMD_HOST_SET_WORDS, PMD_HOST_SET_INT, PMD_HOST_GET_ACK, PMD_HOST_GET_REPLY,
        PMD_HOST_GRID, PMD_HOST_DO_STEP, PMD_HOST_ACK, PMD_HOST_WORDS,
        PMD_SYSTEM_GET, PMD_SYSTEM_SET, PMD_SYSTEM_STEP,
    };
    size_t i, count = sizeof layout / sizeof layout[0];
    for (i = 0; i < count && i < n; i++)
        out[i] = layout[i];
    return count;
}
