/* SPDX-License-Identifier: BSD-2-Clause */
/* The baseline of pmdfmu.System's bench (bench/system.py): the Gauss-Seidel step of
 * examples/systems, FMI 2, written out as a plain C loop over the same FMI functions in the same
 * order as native/system.c calls them (get plant.encoderCount, set chip.axis1.actualPosition, the
 * chip's doStep; get chip.axis1.motorCommand, set plant.motorCommand, the plant's doStep; one get a
 * recorded column: 3 chip Integers, the plant's Integer and 4 Reals), a row of 7 values a step. */
#include <stdint.h>
#include <string.h>

#include "fmi2FunctionTypes.h"

typedef struct {
    fmi2GetIntegerTYPE *get_int[2];
    fmi2SetIntegerTYPE *set_int[2];
    fmi2GetRealTYPE *get_real[2];
    fmi2DoStepTYPE *do_step[2];
    void *instance[2];                 /* chip, plant */
    unsigned int encoder, actual, motor, plant_motor;
    unsigned int chip_columns[3], plant_int, plant_reals[4];
} Loop;

int bare_loop(const Loop *l, double start, double step, long steps, unsigned char *rows, size_t row_bytes)
{
    long k;
    for (k = 0; k < steps; k++, rows += row_bytes) {
        double t = start + (double)k * step, reals[4];
        fmi2Integer v, ints[4];
        int64_t n = k + 1;
        int i;
        if (l->get_int[1](l->instance[1], &l->encoder, 1, &v) > 1) return 1;
        if (l->set_int[0](l->instance[0], &l->actual, 1, &v) > 1) return 1;
        if (l->do_step[0](l->instance[0], t, step, fmi2True) > 1) return 1;
        if (l->get_int[0](l->instance[0], &l->motor, 1, &v) > 1) return 1;
        if (l->set_int[1](l->instance[1], &l->plant_motor, 1, &v) > 1) return 1;
        if (l->do_step[1](l->instance[1], t, step, fmi2True) > 1) return 1;
        for (i = 0; i < 3; i++)
            if (l->get_int[0](l->instance[0], &l->chip_columns[i], 1, &ints[i]) > 1) return 1;
        if (l->get_int[1](l->instance[1], &l->plant_int, 1, &ints[3]) > 1) return 1;
        for (i = 0; i < 4; i++)
            if (l->get_real[1](l->instance[1], &l->plant_reals[i], 1, &reals[i]) > 1) return 1;
        memcpy(rows, &n, 8);
        memcpy(rows + 8, ints, sizeof ints);
        memcpy(rows + 8 + sizeof ints, reals, sizeof reals);
    }
    return 0;
}
