/* SPDX-License-Identifier: BSD-2-Clause */
/* Exact 64 x 64 -> 128-bit products and 128 / 64-bit division, for the
 * S-curve's rational positions. Uses the compiler's 128-bit integers where it
 * has them, else (or with PMD_PORTABLE_WIDE) plain C99 on 32-bit halves; the
 * test suite checks that both agree. */
#ifndef PMD_WIDE_H
#define PMD_WIDE_H

#include <stdint.h>

typedef struct {
    uint64_t hi, lo;
} PmdU128;

#if defined(__SIZEOF_INT128__) && defined(__GNUC__) && !defined(PMD_PORTABLE_WIDE)
__extension__ typedef unsigned __int128 pmd_native_u128;

static inline PmdU128 pmd_mul64(uint64_t a, uint64_t b)
{
    pmd_native_u128 p = (pmd_native_u128)a * b;
    PmdU128 r;
    r.hi = (uint64_t)(p >> 64);
    r.lo = (uint64_t)p;
    return r;
}

/* n / d for n.hi < d (the quotient fits 64 bits). */
static inline uint64_t pmd_div128(PmdU128 n, uint64_t d, uint64_t *remainder)
{
    pmd_native_u128 x = ((pmd_native_u128)n.hi << 64) | n.lo;
    *remainder = (uint64_t)(x % d);
    return (uint64_t)(x / d);
}
#else
static inline PmdU128 pmd_mul64(uint64_t a, uint64_t b)
{
    uint64_t a0 = a & 0xFFFFFFFFu, a1 = a >> 32, b0 = b & 0xFFFFFFFFu, b1 = b >> 32;
    uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    uint64_t mid = (p00 >> 32) + (p01 & 0xFFFFFFFFu) + (p10 & 0xFFFFFFFFu);
    PmdU128 r;
    r.lo = (p00 & 0xFFFFFFFFu) | (mid << 32);
    r.hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
    return r;
}

/* Restoring long division, one bit at a time; r < d before every shift, so a
 * bit shifted out of r means r + 2^64 >= d. */
static inline uint64_t pmd_div128(PmdU128 n, uint64_t d, uint64_t *remainder)
{
    uint64_t q = 0, r = n.hi;
    int i;
    for (i = 63; i >= 0; i--) {
        uint64_t carry = r >> 63;
        r = (r << 1) | ((n.lo >> i) & 1u);
        q <<= 1;
        if (carry || r >= d) {
            r -= d;
            q |= 1;
        }
    }
    *remainder = r;
    return q;
}
#endif

static inline int pmd_le128(PmdU128 x, PmdU128 y)
{
    return x.hi < y.hi || (x.hi == y.hi && x.lo <= y.lo);
}

/* floor(a * b / c) for a * b / c < 2^64. */
static inline uint64_t pmd_muldiv(uint64_t a, uint64_t b, uint64_t c, uint64_t *remainder)
{
    return pmd_div128(pmd_mul64(a, b), c, remainder);
}

#endif
