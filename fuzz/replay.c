/* SPDX-License-Identifier: BSD-2-Clause */
/* Replays fuzz inputs (files named on the command line) through a fuzz target
 * without libFuzzer: the regression tests build it with any C compiler. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int main(int argc, char **argv)
{
    int i;
    for (i = 1; i < argc; i++) {
        FILE *f = fopen(argv[i], "rb");
        static uint8_t buffer[1 << 20];
        size_t n;
        if (!f) {
            perror(argv[i]);
            return 2;
        }
        n = fread(buffer, 1, sizeof buffer, f);
        fclose(f);
        LLVMFuzzerTestOneInput(buffer, n);
    }
    printf("replayed %d inputs\n", argc - 1);
    return 0;
}
