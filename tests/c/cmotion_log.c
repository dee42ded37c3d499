/* SPDX-License-Identifier: BSD-2-Clause */
/* The C-Motion library's log callback (PMDfmu.h): what the FMU and the transport say reaches it,
   and nothing else reaches the terminal. tests/test_cmotion_library.py runs it.

   Usage: cmotion_log script TEXT [CYCLES [CATEGORY ...]]   a chip running the script TEXT for
                                                            CYCLES cycles, logging the categories
          cmotion_log fmu PATH                              a chip of the FMU at PATH
          cmotion_log serial BAUD                           a chip whose commands are timed as a
                                                            serial line at BAUD
   Output: every message of the log callback on stderr, one line each:
             L <category> <status> <message>
           and on stdout the setup's result, then the run's:
             S <result>
             R <result> */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "c-motion.h"
#include "PMDhosttime.h"

#define MAX_CATEGORIES 8

static void print_message(void *context, const char *category, int status, const char *message)
{
    (void)context;
    fprintf(stderr, "L %s %d %s\n", category, status, message);
}

int main(int argc, char **argv)
{
    PMDFMUOptions options;
    PMDAxisHandle axis;
    const char *categories[MAX_CATEGORIES + 1];
    PMDHostInterface host = PMDHostInterfaceOf(PMDHostSerial);
    PMDresult r;
    int i, n = 0;
    if (argc < 3 ||
        (strcmp(argv[1], "script") != 0 && strcmp(argv[1], "fmu") != 0 && strcmp(argv[1], "serial") != 0) ||
        argc > 4 + MAX_CATEGORIES) {
        fprintf(stderr, "usage: cmotion_log script TEXT [CYCLES [CATEGORY ...]] | cmotion_log fmu PATH | "
                        "cmotion_log serial BAUD\n");
        return 2;
    }
    PMDFMUOptionsInit(&options);
    options.log = print_message;
    if (strcmp(argv[1], "fmu") == 0) {
        options.fmu = argv[2];
    } else if (strcmp(argv[1], "serial") == 0) {
        host.baud = (PMDuint32)strtoul(argv[2], NULL, 10);
        options.hostInterface = &host;
    } else {
        options.script = argv[2];
        for (i = 4; i < argc; i++)
            categories[n++] = argv[i];
        categories[n] = NULL;
        if (n)
            options.logCategories = categories;
    }
    r = PMDSetupAxisInterface_FMU(&axis, PMDAxis1, &options);
    printf("S 0x%X\n", (unsigned)r);
    if (r != PMD_ERR_OK)
        return 0;
    if (argc > 3)
        printf("R 0x%X\n", (unsigned)PMDFMU_RunCycles(&axis, (PMDuint32)strtoul(argv[3], NULL, 10)));
    PMDCloseAxisInterface(&axis);
    return 0;
}
