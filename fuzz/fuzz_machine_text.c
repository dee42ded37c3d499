/* SPDX-License-Identifier: BSD-2-Clause */
/* Fuzz target: a machine file's text (the `machine` parameter's value when it
 * holds a line feed), parsed by pmd_machine_parse_text (docs/machine.md).
 *
 *   input = the text (bytes after a NUL are ignored: the parameter is a C string)
 *
 * Properties (abort() on a violation, after "property violated: ..."):
 *   - no sanitizer report (ASan, UBSan);
 *   - a refusal says why: "(machine text):LINE: reason" with LINE a line the
 *     text has, and leaves the machine all zero (digest 0, no axis);
 *   - a parsed machine is what the file may mean: home lo <= hi, positive
 *     limit above negative, index period >= 1 or 1..16 listed positions,
 *     signal sense only the index, home and limit bits, an axis bit exactly
 *     where an input is driven, the digest 0 exactly without an axis;
 *   - parsing is deterministic (twice, the same digest and the same meaning);
 *   - the machine applied to a chip for every pair of positions near its
 *     switches and pulses gives each input exactly what its definition says.
 *
 * FUZZ_MACHINE_TRACE=1 prints what each input meant, or why it was refused. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chip.h"
#include "fuzz_property.h"
#include "machine.h"
#include "machine_toml.h"

static int lines_of(const char *text)
{
    int n = 1;
    for (; *text; text++)
        n += *text == '\n';
    return n;
}

static int64_t floor_div(int64_t a, int64_t b)
{
    return a / b - (a % b != 0 && a < 0);
}

/* The definition of the index pulse, independently of machine.c: some pulse position among the
 * counts the axis passed, (before, now] or [now, before), or now at rest. */
static int index_reference(const PmdMachineAxis *m, int64_t before, int64_t now)
{
    int64_t low = now > before ? before + 1 : now, high = now < before ? before - 1 : now;
    int i;
    if (m->indexPeriod)
        return floor_div(high, m->indexPeriod) * (int64_t)m->indexPeriod >= low;
    for (i = 0; i < m->indexCount; i++)
        if (m->indexPosition[i] >= low && m->indexPosition[i] <= high)
            return 1;
    return 0;
}

static void check_inputs(const PmdMachine *machine, int n, int32_t before, int32_t now)
{
    static PmdChip chip;
    const PmdMachineAxis *m = &machine->axis[n];
    PmdAxis *ax = &chip.s.axis[n];
    int sense;
    memset(&chip, 0, sizeof chip);
    chip.machine = machine;
    ax->previousActualPosition = before;
    ax->actualPosition = now;
    pmd_machine_inputs(&chip, n);
    sense = (m->signalSense & PMDSignalEncoderHomeMask) != 0;
    if ((m->signals & PMD_MACHINE_HOME) && ax->homeInput != ((now >= m->homeLow && now <= m->homeHigh) ^ sense))
        violated("axis %d home input at %d", n + 1, (int)now);
    sense = (m->signalSense & PMDSignalPositiveLimitMask) != 0;
    if ((m->signals & PMD_MACHINE_POSITIVE_LIMIT) && ax->positiveLimitInput != ((now >= m->positiveLimit) ^ sense))
        violated("axis %d positive limit input at %d", n + 1, (int)now);
    sense = (m->signalSense & PMDSignalNegativeLimitMask) != 0;
    if ((m->signals & PMD_MACHINE_NEGATIVE_LIMIT) && ax->negativeLimitInput != ((now <= m->negativeLimit) ^ sense))
        violated("axis %d negative limit input at %d", n + 1, (int)now);
    sense = (m->signalSense & PMDSignalEncoderIndexMask) != 0;
    /* steps small enough not to wrap the 32-bit register: the reference works in int64 */
    if ((m->signals & PMD_MACHINE_INDEX) && ax->indexInput != (index_reference(m, before, now) ^ sense))
        violated("axis %d index input from %d to %d", n + 1, (int)before, (int)now);
    if (!(m->signals & PMD_MACHINE_HOME) && ax->homeInput)
        violated("axis %d: a home input the machine does not drive changed", n + 1);
}

/* Positions near a value, kept within int32 and away from its ends (no wrap between two of them). */
static void near(int64_t x, int32_t *out, int *count)
{
    int64_t d;
    for (d = -3; d <= 3; d++) {
        int64_t p = x + d;
        if (p > INT32_MIN + 8 && p < INT32_MAX - 8)
            out[(*count)++] = (int32_t)p;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static char error[1024], meaning[4096], again[4096];
    char *text = (char *)malloc(size + 1);
    PmdMachine machine, second;
    int result, n, i, j;
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    result = pmd_machine_parse_text(text, PMD_MACHINE_TEXT_NAME, &machine, error, sizeof error);
    if (result != 0) {
        static const PmdMachine zero;
        int line = 0;
        if (result != -1 || sscanf(error, PMD_MACHINE_TEXT_NAME ":%d: ", &line) != 1 || line < 1 ||
            line > lines_of(text) || !strstr(error, ": "))
            violated("refusal without name:line: reason: %d \"%s\"", result, error);
        if (memcmp(&machine, &zero, sizeof machine) != 0 || pmd_machine_digest(&machine) != 0)
            violated("a refused machine is not all zero");
        if (getenv("FUZZ_MACHINE_TRACE"))
            printf("refused: %s\n", error);
        free(text);
        return 0;
    }
    if ((pmd_machine_digest(&machine) == 0) != (machine.axes == 0))
        violated("digest 0 is exactly no axis");
    for (n = 0; n < PMD_AXES; n++) {
        const PmdMachineAxis *m = &machine.axis[n];
        int32_t at[64];
        int count = 0;
        /* an axis the machine drives: a switch or index input, or its loop closed through the plant */
        if (((machine.axes >> n) & 1u) != (m->signals != 0 || m->servo == PMD_MACHINE_SERVO_PLANT))
            violated("axis %d: axes bit and signals disagree", n + 1);
        if (((machine.plantAxes >> n) & 1u) != (m->servo == PMD_MACHINE_SERVO_PLANT))
            violated("axis %d: plantAxes bit and servo disagree", n + 1);
        if ((m->signals & PMD_MACHINE_HOME) && m->homeLow > m->homeHigh)
            violated("axis %d: home lo above hi", n + 1);
        if ((m->signals & PMD_MACHINE_POSITIVE_LIMIT) && (m->signals & PMD_MACHINE_NEGATIVE_LIMIT) &&
            m->positiveLimit <= m->negativeLimit)
            violated("axis %d: limits overlap", n + 1);
        if ((m->signals & PMD_MACHINE_INDEX) &&
            (m->indexPeriod == 0 ? m->indexCount < 1 || m->indexCount > PMD_MACHINE_INDEX_POSITIONS
                                 : m->indexPeriod > INT32_MAX))
            violated("axis %d: index", n + 1);
        if (m->signalSense & ~(PMDSignalEncoderIndexMask | PMDSignalEncoderHomeMask | PMDSignalPositiveLimitMask |
                               PMDSignalNegativeLimitMask))
            violated("axis %d: signal sense bits", n + 1);
        if (!m->signals)
            continue;
        near(0, at, &count);
        near(m->homeLow, at, &count);
        near(m->homeHigh, at, &count);
        near(m->positiveLimit, at, &count);
        near(m->negativeLimit, at, &count);
        if (m->indexPeriod)
            near(m->indexPeriod, at, &count);
        else if (m->indexCount)
            near(m->indexPosition[0], at, &count);
        for (i = 0; i < count; i++)
            for (j = 0; j < count; j++)
                if (at[i] - (int64_t)at[j] < ((int64_t)1 << 30) && at[j] - (int64_t)at[i] < ((int64_t)1 << 30))
                    check_inputs(&machine, n, at[i], at[j]);
    }
    pmd_machine_describe(&machine, meaning, sizeof meaning);
    if (pmd_machine_parse_text(text, PMD_MACHINE_TEXT_NAME, &second, error, sizeof error) != 0 ||
        pmd_machine_digest(&second) != pmd_machine_digest(&machine))
        violated("a second parse differs");
    pmd_machine_describe(&second, again, sizeof again);
    if (strcmp(meaning, again) != 0)
        violated("a second parse means something else");
    if (getenv("FUZZ_MACHINE_TRACE"))
        printf("%s", meaning);
    free(text);
    return 0;
}
