/* SPDX-License-Identifier: BSD-2-Clause */
/* A host command in C (host_port.h): the FMI calls Chip._send made from Python (tests/stepwise.py,
 * send_stepwise), in the same order with the same values, so that the chip, the port's variables and
 * the FMU's log are the same, at the cost of the FMU's own calls. */
#include <string.h>

#include "fmi2FunctionTypes.h"
#include "fmi3FunctionTypes.h"
#include "host_port.h"

static uint64_t failed(PmdHostPort *p, int call, int status)
{
    p->stop.call = call;
    p->stop.status = status;
    return PMD_HOST_FAILED;
}

/* The result word of the batch just sent (host_port.h) */
static uint64_t result(const PmdHostPort *p)
{
    uint64_t r = (uint64_t)(p->count > 0 ? p->out[0] : 0) << 16 | (p->count > 1 ? p->out[1] : 0);
    return r | (uint64_t)(uint16_t)p->error_word << 32 | (uint64_t)(uint8_t)p->count << 48;
}

static uint64_t send_fmi2(PmdHostPort *p, size_t n, size_t expect)
{
    fmi2ValueReference vrs[3 + PMD_HOST_WORDS];
    fmi2Integer values[3 + PMD_HOST_WORDS], strobe;
    size_t i;
    int status = ((fmi2GetIntegerTYPE *)p->get_int)(p->instance, &p->strobe, 1, &strobe);
    if (PMD_FAILED(status))
        return failed(p, PMD_HOST_GET_STROBE, status);
    p->strobe_sent = (int32_t)(((uint32_t)strobe + 1) & 0x7FFFFFFF);  /* whoever set the last one */
    memcpy(vrs, p->word, n * sizeof *vrs);
    vrs[n] = p->word_count;
    vrs[n + 1] = p->strobe;
    for (i = 0; i < n; i++)
        values[i] = p->in[i];
    values[n] = (fmi2Integer)n;
    values[n + 1] = p->strobe_sent;
    status = ((fmi2SetIntegerTYPE *)p->set_int)(p->instance, vrs, n + 2, values);
    if (PMD_FAILED(status))
        return failed(p, PMD_HOST_SET_INT, status);
    /* ack, error, replyCount and the reply words expected, in one get that executes the batch */
    if (expect > PMD_HOST_WORDS)
        expect = PMD_HOST_WORDS;
    vrs[0] = p->ack;
    vrs[1] = p->error;
    vrs[2] = p->reply_count;
    memcpy(vrs + 3, p->reply, expect * sizeof *vrs);
    status = ((fmi2GetIntegerTYPE *)p->get_int)(p->instance, vrs, 3 + expect, values);
    if (PMD_FAILED(status))
        return failed(p, PMD_HOST_GET_ACK, status);
    p->ack_word = values[0];
    p->error_word = values[1];
    p->count = values[2] < 0 ? 0 : values[2] > PMD_HOST_WORDS ? PMD_HOST_WORDS : values[2];
    if ((size_t)p->count > expect) {  /* more than the command returns: the rest in a second get */
        status = ((fmi2GetIntegerTYPE *)p->get_int)(p->instance, p->reply + expect, (size_t)p->count - expect,
                                                     values + 3 + expect);
        if (PMD_FAILED(status))
            return failed(p, PMD_HOST_GET_REPLY, status);
    }
    for (i = 0; i < (size_t)p->count; i++)
        p->out[i] = (uint16_t)values[3 + i];
    return 0;
}

static uint64_t send_fmi3(PmdHostPort *p, size_t n)
{
    fmi3ValueReference control[2] = {p->word_count, p->strobe}, got[2] = {p->ack, p->reply_count},
                       reply[2] = {p->error, p->reply[0]};
    fmi3UInt16 words[PMD_HOST_WORDS], replies[1 + PMD_HOST_WORDS];
    fmi3Int32 strobe, counts[2], acked[2];
    int status = ((fmi3GetInt32TYPE *)p->get_int)(p->instance, &p->strobe, 1, &strobe, 1);
    if (PMD_FAILED(status))
        return failed(p, PMD_HOST_GET_STROBE, status);
    p->strobe_sent = (int32_t)(((uint32_t)strobe + 1) & 0x7FFFFFFF);
    memcpy(words, p->in, n * sizeof *words);
    memset(words + n, 0, (PMD_HOST_WORDS - n) * sizeof *words);     /* the array is set whole */
    status = ((fmi3SetUInt16TYPE *)p->set_words)(p->instance, &p->word[0], 1, words, PMD_HOST_WORDS);
    if (PMD_FAILED(status))
        return failed(p, PMD_HOST_SET_WORDS, status);
    counts[0] = (fmi3Int32)n;
    counts[1] = p->strobe_sent;
    status = ((fmi3SetInt32TYPE *)p->set_int)(p->instance, control, 2, counts, 2);
    if (PMD_FAILED(status))
        return failed(p, PMD_HOST_SET_INT, status);
    status = ((fmi3GetInt32TYPE *)p->get_int)(p->instance, got, 2, acked, 2);
    if (PMD_FAILED(status))
        return failed(p, PMD_HOST_GET_ACK, status);
    p->ack_word = acked[0];
    p->count = acked[1] < 0 ? 0 : acked[1] > PMD_HOST_WORDS ? PMD_HOST_WORDS : acked[1];
    /* host.error, then the reply array (read whole) if there is a reply: a set reads host.error alone */
    status = ((fmi3GetUInt16TYPE *)p->get_words)(p->instance, reply, p->count ? 2 : 1, replies,
                                                 p->count ? 1 + PMD_HOST_WORDS : 1);
    if (PMD_FAILED(status))
        return failed(p, PMD_HOST_GET_REPLY, status);
    p->error_word = replies[0];
    memcpy(p->out, replies + 1, (size_t)p->count * sizeof *p->out);
    return 0;
}

static uint64_t send(PmdHostPort *p, size_t n, size_t expect)
{
    uint64_t r;
    if (n > PMD_HOST_WORDS)
        return failed(p, PMD_HOST_SET_INT, fmi2Error);
    r = p->fmi3 ? send_fmi3(p, n) : send_fmi2(p, n, expect);
    if (r)
        return r;
    if (p->ack_word != p->strobe_sent)
        return failed(p, PMD_HOST_ACK, 0);
    return result(p);
}

uint64_t pmd_host_batch(PmdHostPort *p, size_t n, size_t expect)
{
    return send(p, n, expect);
}

/* Python's round(x * 1e6) * 1000 of a grid time (whole microseconds: round half to even, x >= 0) */
static int64_t grid_ns(double x)
{
    double r = x * 1e6;
    int64_t t = (int64_t)r;
    double f = r - (double)t;
    if (f > 0.5 || (f == 0.5 && (t & 1)))
        t++;
    return t * 1000;
}

static int get_grid(PmdHostPort *p, double grid[3])
{
    if (p->fmi3)
        return ((fmi3GetFloat64TYPE *)p->get_real)(p->instance, p->grid, 3, grid, 3);
    return ((fmi2GetRealTYPE *)p->get_real)(p->instance, p->grid, 3, grid);
}

/* Chip._do_step(cycles): a grid get, then the doStep to the end of the cycles' last */
static uint64_t step(PmdHostPort *p, int64_t cycles)
{
    double grid[3];
    int status = get_grid(p, grid);
    if (PMD_FAILED(status))
        return failed(p, PMD_HOST_GRID, status);
    if (p->fmi3) {
        fmi3Boolean event_handling_needed, terminate_simulation, early_return;
        fmi3Float64 last_successful_time;
        status = ((fmi3DoStepTYPE *)p->do_step)(p->instance, grid[0], (grid[1] - grid[0]) + (double)cycles * grid[2],
                                                fmi3True, &event_handling_needed, &terminate_simulation,
                                                &early_return, &last_successful_time);
    } else {
        status = ((fmi2DoStepTYPE *)p->do_step)(p->instance, grid[0], (grid[1] - grid[0]) + (double)cycles * grid[2],
                                                fmi2True);
    }
    return PMD_FAILED(status) ? failed(p, PMD_HOST_DO_STEP, status) : 0;
}

/* Chip._run_due: every cycle at or before the host clock (hosttime.cycles_due) */
static uint64_t run_due(PmdHostPort *p)
{
    for (;;) {
        double grid[3];
        int64_t next_ns, cycle_ns, due;
        uint64_t r;
        int status = get_grid(p, grid);
        if (PMD_FAILED(status))
            return failed(p, PMD_HOST_GRID, status);
        next_ns = grid_ns(grid[1]);
        cycle_ns = grid_ns(grid[2]);
        due = cycle_ns <= 0 || p->host_ns < next_ns ? 0 : (p->host_ns - next_ns) / cycle_ns + 1;
        if (!due)
            return 0;
        r = step(p, due);
        if (r)
            return r;
    }
}

static uint64_t command(PmdHostPort *p, size_t n, uint64_t words, size_t expect)
{
    uint64_t r;
    size_t i;
    for (i = 0; i < n; i++)
        p->in[i] = (uint16_t)(words >> (16 * i));
    if (!p->timed)
        return send(p, n, expect);
    p->host_ns += p->request_ns[n];
    r = run_due(p);
    if (r)
        return r;
    r = send(p, n, expect);
    if (r & PMD_HOST_FAILED)
        return r;
    p->host_ns += p->error_word ? p->failed_ns : p->reply_ns[p->count];
    return r;
}

uint64_t pmd_host_command(PmdHostPort *p, unsigned int shape, unsigned int lo, unsigned int hi)
{
    size_t n = shape & 0xFF;
    if (n > 4)
        return failed(p, PMD_HOST_SET_INT, fmi2Error);
    return command(p, n, (uint64_t)(uint32_t)lo | (uint64_t)(uint32_t)hi << 32, (shape >> 8) & 0xFF);
}

uint64_t pmd_host_wait_for(PmdHostPort *p, size_t n, uint64_t words, uint32_t mask, int64_t limit_ns)
{
    if (n > 4)
        return failed(p, PMD_HOST_SET_INT, fmi2Error);
    for (;;) {
        uint64_t r = command(p, n, words, 1);
        double grid[3];
        int status;
        if ((r & PMD_HOST_FAILED) || p->error_word || ((r >> 16) & 0xFFFF & mask))
            return r;
        if (limit_ns >= 0 && p->host_ns > limit_ns)
            return r | PMD_HOST_TIMEOUT;
        if (p->timed)
            continue;
        /* Chip.run(1): one cycle, the host clock up to its time if it was behind */
        r = step(p, 1);
        if (r)
            return r;
        status = get_grid(p, grid);
        if (PMD_FAILED(status))
            return failed(p, PMD_HOST_GRID, status);
        {
            int64_t last = grid_ns(grid[1]) - grid_ns(grid[2]);
            if (last < 0)
                last = 0;
            if (last > p->host_ns)
                p->host_ns = last;
        }
    }
}
