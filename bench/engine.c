/* Benchmark 1 (issue 5): the chip core running an external profile on 4 axes
 * with all five buffers, every cycle's commanded position, velocity and
 * acceleration stored (pmd_chip_run's record rows, as the FMU records them),
 * against a plain C loop of the same exact recurrence storing the same rows,
 * measured in the same run. The plain loop floors the position's fraction
 * (its one non-binary unit) with C's division (the baseline of the target);
 * the same loop once more with the core's own floor division (chip_types.h)
 * shows what the core's bookkeeping costs on top of the arithmetic. Prints ns
 * per axis-cycle: plain, plain with the core's division, core. All three must
 * store the same rows. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "chip.h"

#define AXES 4
#define ROWS 64
#ifndef CYCLES
#define CYCLES 2000000
#endif

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int32_t rows[AXES][5][ROWS];

static void make_rows(void)
{
    uint32_t s = 12345;
    int a, r;
    for (a = 0; a < AXES; a++)
        for (r = 0; r < ROWS; r++) {
            s = s * 1103515245u + 12345u; rows[a][0][r] = (int32_t)(s >> 16) - 32768;
            s = s * 1103515245u + 12345u; rows[a][1][r] = (int32_t)(s >> 12) - 0x80000;
            s = s * 1103515245u + 12345u; rows[a][2][r] = (int32_t)(s >> 20) - 0x800;
            s = s * 1103515245u + 12345u; rows[a][3][r] = (int32_t)(s >> 12) - 0x80000;
            rows[a][4][r] = 1 + (int32_t)(r % 7);         /* short segments: reads and integrations mixed */
        }
}

/* ---- the baseline: the recurrence alone, in the core's exact representation ---- */

/* chip_types.h: position in whole counts + a fraction in U = 2^-32/6 count;
 * velocity and acceleration in whole counts + a fraction in 2^-33 count. */
typedef struct { int32_t pos; int64_t frac, v, vf, a, af; int32_t j; uint32_t left; int row; } Plain;

/* floor(x / y) the plain way */
static int64_t fdiv(int64_t x, int64_t y) { int64_t q = x / y; return (x % y != 0 && ((x < 0) != (y < 0))) ? q - 1 : q; }

#define FLOOR_COUNTS(x) (core_division ? pmd_floor_counts(x) : fdiv((x), PMD_U_PER_COUNT))
#define ONE ((int64_t)1 << 33)

static double run_plain(int32_t *out, int core_division)
{
    Plain p[AXES];
    double t0;
    long k;
    int a;
    memset(p, 0, sizeof p);
    t0 = now();
    for (k = 0; k < CYCLES; k++) {
        out[0] = (int32_t)k;
        for (a = 0; a < AXES; a++) {
            Plain *x = &p[a];
            if (x->left == 0) {
                int64_t v = rows[a][1][x->row], acc = rows[a][2][x->row];
                x->pos = rows[a][0][x->row]; x->frac = 0;
                x->v = fdiv(v, 65536); x->vf = (v - x->v * 65536) << 17;
                x->a = fdiv(acc, 65536); x->af = (acc - x->a * 65536) << 17;
                x->j = rows[a][3][x->row];
                x->left = (uint32_t)rows[a][4][x->row];
                x->row = (x->row + 1) % ROWS;
            } else {
                /* P += V + A/2 + J/6: 2^-33 count is 3 U, J/6 is j U (>> floors: GCC shifts arithmetically) */
                int64_t hc = x->a >> 1, hf = (x->af >> 1) | ((x->a & 1) << 32);
                int64_t f = x->frac + 3 * (x->vf + hf) + x->j, carry = FLOOR_COUNTS(f), s;
                x->frac = f - carry * PMD_U_PER_COUNT;
                x->pos = (int32_t)((uint32_t)x->pos + (uint32_t)(x->v + hc + carry));
                /* V += A + J/2 (j in 2^-33 count), A += J (2 j); the whole counts never pass int64 */
                s = x->vf + x->af + x->j;
                x->v += x->a + (s >> 33); x->vf = s & (ONE - 1);
                s = x->af + 2 * (int64_t)x->j;
                x->a += s >> 33; x->af = s & (ONE - 1);
            }
            x->left--;
            out[1 + 3 * a] = x->pos;
            out[2 + 3 * a] = (int32_t)((uint32_t)(x->v * 65536) + (uint32_t)(x->vf >> 17));
            out[3 + 3 * a] = (int32_t)((uint32_t)(x->a * 65536) + (uint32_t)(x->af >> 17));
        }
        out += PMD_RECORD_WORDS;
    }
    return now() - t0;
}

/* ---- the chip core ---- */

static double run_chip(int32_t *out, uint32_t *memory)
{
    PmdChip chip;
    double t0;
    int a, f;
    memset(&chip, 0, sizeof chip);
    pmd_chip_init(&chip, memory, 0x4000);
    chip.s.loopback = 1;
    for (a = 0; a < AXES; a++)
        for (f = 0; f < 5; f++) {
            int id = 2 + 5 * a + f;
            PmdBuffer *b = &chip.s.buffer[id];
            b->start = (uint32_t)(0x200 + id * ROWS);
            b->length = ROWS;
            memcpy(memory + b->start, rows[a][f], sizeof rows[a][f]);
            chip.s.axis[a].bufferOfFunction[f] = (int16_t)id;
        }
    for (a = 0; a < AXES; a++) {
        chip.s.axis[a].buffered.profileMode = PMDExternalProfile;
        pmd_update(&chip, a);
    }
    t0 = now();
    pmd_chip_run(&chip, CYCLES, out);
    return now() - t0;
}

int main(void)
{
    size_t bytes = sizeof(int32_t) * PMD_RECORD_WORDS * CYCLES;
    int32_t *plain = malloc(bytes), *tuned = malloc(bytes), *core = malloc(bytes);
    uint32_t *memory = calloc(0x4000, sizeof(uint32_t));
    double tp = 1e9, tt = 1e9, tc = 1e9;
    int rep;
    make_rows();
    for (rep = 0; rep < 3; rep++) {               /* best of three: the machine is shared */
        double x = run_plain(plain, 0), y = run_plain(tuned, 1), z = run_chip(core, memory);
        tp = x < tp ? x : tp;
        tt = y < tt ? y : tt;
        tc = z < tc ? z : tc;
    }
    if (memcmp(plain, core, bytes) != 0 || memcmp(tuned, core, bytes) != 0) {
        fprintf(stderr, "the core and the plain loop disagree\n");
        return 1;
    }
    printf("%.3f %.3f %.3f\n", 1e9 * tp / (CYCLES * (double)AXES), 1e9 * tt / (CYCLES * (double)AXES),
           1e9 * tc / (CYCLES * (double)AXES));
    return 0;
}
