/* SPDX-License-Identifier: BSD-2-Clause */
#ifndef PMD_NATIVE_HOST_PORT_H
#define PMD_NATIVE_HOST_PORT_H

/* A host command in one native call (Chip.command, the Axis methods, Chip.batch, Chip.wait_for:
 * python/pmdfmu/host_port.py): the calls the harness made from Python per batch (tests/stepwise.py,
 * send_stepwise), over the FMU's own FMI functions: a get of host.strobe; one set of host.word[..],
 * host.wordCount and a new host.strobe; a get of host.ack, host.error, host.replyCount and the reply
 * words, which executes the batch (CONTRACT 2.2: gets see pending port writes executed). With host
 * time (timed), the request's time passes first and the cycles due run (a grid get, then per step a
 * grid get and a doStep, as Chip._run_due), and the reply's time after. */

#include <stddef.h>
#include <stdint.h>

#include "native.h"

#define PMD_HOST_WORDS 64        /* host.word[64], host.reply[64]: the C side's PMD_BATCH_WORDS */

/* The harness owns it (a ctypes struct per Chip); a call reads its set-up and writes its
 * outputs (host_ns, in, out, count, error, ack, stop) and keeps no pointer into it. */
typedef struct {
    /* FMI 2: get_int fmi2GetInteger, set_int fmi2SetInteger, get_real fmi2GetReal; FMI 3:
     * get_int fmi3GetInt32, set_int fmi3SetInt32, set_words fmi3SetUInt16, get_words fmi3GetUInt16,
     * get_real fmi3GetFloat64 */
    PmdFmiFunction get_int, set_int, set_words, get_words, get_real, do_step;
    void *instance;
    int fmi3;
    /* value references: FMI 2 word[i], reply[i] each element's; FMI 3 word[0], reply[0] the arrays' */
    unsigned int word[PMD_HOST_WORDS];
    unsigned int reply[PMD_HOST_WORDS];
    unsigned int word_count, strobe, ack, error, reply_count;
    unsigned int grid[3];                     /* time, nextCycleTime, activeCycleTime */
    /* host time: on when timed; request_ns[w] for w words sent, reply_ns[r] for r words returned,
     * failed_ns for a refused command's reply (hosttime.HostInterface) */
    int timed;
    int64_t host_ns;
    int64_t request_ns[PMD_HOST_WORDS + 1];
    int64_t reply_ns[PMD_HOST_WORDS + 1];
    int64_t failed_ns;
    /* the words sent (pmd_host_batch's input), the last batch's outputs */
    uint16_t in[PMD_HOST_WORDS];
    uint16_t out[PMD_HOST_WORDS];
    int32_t count, error_word, ack_word, strobe_sent;
    PmdStop stop;                             /* call: PmdHostCall, status: the FMI status */
} PmdHostPort;

/* Which call failed (stop.call); PMD_HOST_ACK: host.ack is not the strobe sent (status 0) */
enum { PMD_HOST_GET_STROBE, PMD_HOST_SET_WORDS, PMD_HOST_SET_INT, PMD_HOST_GET_ACK, PMD_HOST_GET_REPLY,
       PMD_HOST_GRID, PMD_HOST_DO_STEP, PMD_HOST_ACK };

/* The result word: bits 0..31 the first two reply words (reply[0] << 16 | reply[1]), 32..47
 * host.error, 48..55 host.replyCount (all of the reply in out[]), bit 62 a wait's time-out, bit 63 a
 * failure (stop says where; nothing after that call ran). */
#define PMD_HOST_TIMEOUT (UINT64_C(1) << 62)
#define PMD_HOST_FAILED (UINT64_C(1) << 63)

/* One batch of the n words in[0 .. n), untimed; `expect` reply words are read with the ack
 * (FMI 2: more only if the FMU returns more). */
PMD_NATIVE_EXPORT uint64_t pmd_host_batch(PmdHostPort *port, size_t n, size_t expect);

/* One command of n <= 4 words (shape: n | expect << 8), 16 bits each, words 0 and 1 in lo (word 0 in the
 * low bits), 2 and 3 in hi, timed if port->timed. Its arguments are all C ints and a pointer, which
 * ctypes passes without argtypes (a Python int masked to an int), at a third of the cost. */
PMD_NATIVE_EXPORT uint64_t pmd_host_command(PmdHostPort *port, unsigned int shape, unsigned int lo,
                                            unsigned int hi);

/* Polls: the command (n words packed, one reply word) until its reply has a bit of mask, it fails or
 * host.error is set; after an unsatisfied poll, a time-out if limit_ns >= 0 and the host clock is past
 * it; else untimed, one cycle runs (the host clock to its time, as Chip.run(1)). Returns the last
 * poll's result word. */
PMD_NATIVE_EXPORT uint64_t pmd_host_wait_for(PmdHostPort *port, size_t n, uint64_t words, uint32_t mask,
                                             int64_t limit_ns);

#endif
