/* SPDX-License-Identifier: BSD-2-Clause */
/* Fuzz target: the script parser. The input is a script; it loads a
 * table "t.csv" when it asks for one, which the fuzzer writes next to it. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "script.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static char dir[64];
    char path[96], error[1024];
    PmdScript script;
    FILE *f;
    size_t half = size / 2;
    if (!dir[0])
        snprintf(dir, sizeof dir, "/tmp/pmdfuzz-%d", (int)getpid());
    snprintf(path, sizeof path, "mkdir -p %s", dir);
    if (system(path) != 0)
        return 0;
    /* the first half is the script, the second a table it may load as "t.csv" */
    snprintf(path, sizeof path, "%s/t.csv", dir);
    if (!(f = fopen(path, "wb")))
        return 0;
    fwrite(data + half, 1, size - half, f);
    fclose(f);
    snprintf(path, sizeof path, "%s/s.script", dir);
    if (!(f = fopen(path, "wb")))
        return 0;
    fwrite(data, 1, half, f);
    fclose(f);
    if (pmd_script_load(path, 0x4000, &script, error, sizeof error) == 0)
        pmd_script_free(&script);
    else if (!error[0])
        abort();                      /* a refusal always says why */
    return 0;
}
