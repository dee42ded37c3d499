/* SPDX-License-Identifier: BSD-2-Clause */
/* The cycle's floor divisions by the exact state's units (chip_types.h:
 * pmd_floor_counts, pmd_floor_1616) against C's signed division with the
 * floor fix-up (pmd_floor_div), at the int64 extremes, around every multiple
 * boundary near 0 and at ten million pseudo-random values of every magnitude.
 * Prints "agree N" or the first disagreement. */
#include <inttypes.h>
#include <stdio.h>

#include "chip_types.h"

static int check(int64_t a)
{
    if (pmd_floor_counts(a) == pmd_floor_div(a, PMD_U_PER_COUNT) &&
        pmd_floor_1616(a) == pmd_floor_div(a, PMD_U_PER_1616))
        return 0;
    printf("disagree at %" PRId64 "\n", a);
    return 1;
}

int main(void)
{
    static const int64_t units[2] = {PMD_U_PER_COUNT, PMD_U_PER_1616};
    uint64_t s = 88172645463325252u;
    long n = 0, i;
    int u, d;
    for (i = 0; i < 64; i++) {
        if (check(INT64_MIN + i) || check(INT64_MAX - i))
            return 1;
        n += 2;
    }
    for (u = 0; u < 2; u++)
        for (i = -3; i <= 3; i++)
            for (d = -1; d <= 1; d++, n++)
                if (check(i * units[u] + d))
                    return 1;
    for (i = 0; i < 10000000; i++, n++) {
        int64_t x;
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        x = (int64_t)(s >> ((s & 63) | 1));          /* every magnitude below 2^63 */
        if (check((s & 64) ? -x : x))
            return 1;
    }
    printf("agree %ld\n", n);
    return 0;
}
