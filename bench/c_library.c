/* SPDX-License-Identifier: BSD-2-Clause */
/* The C library's command cost (bench/c_library.py): a command through the C library
 * (PMDSetVelocity, a Set of one 32-bit argument; PMDGetPosition, a Get with a 2-word reply)
 * against the FMI calls that command needs, made straight from C on another instance of the
 * same FMU binary: one fmi2SetInteger of host.word[1..n], host.wordCount and host.strobe, one
 * fmi2GetInteger of host.ack, host.error, host.replyCount and host.reply[..] (host/c/PMDfmu.c,
 * PMDFMU_Command). The library's chip uses the host interface `none`: its commands take no
 * host time, so no doStep runs between them and both contenders make exactly the same calls.
 *
 *   bench_c_library FMU_DIR FMU_BINARY TOKEN COMMANDS RUNS
 *
 * FMU_DIR: the unpacked FMI 2 FMU the library opens; FMU_BINARY: its binary, dlopened for the
 * direct calls (the same file: the same code); TOKEN: its guid. Each run sends COMMANDS commands
 * per contender, the contenders taking turns (library, fmi, library, fmi ...), after one run of
 * each not counted (warm caches). One line per run and contender, timed with CLOCK_MONOTONIC:
 * "set library SECONDS", "set fmi SECONDS", "get library SECONDS", "get fmi SECONDS".
 *
 * The direct calls check host.ack == strobe and host.error == 0 as the library does, so the
 * baseline executes every command; at the end both chips must hold the same velocity (the last
 * Set's value) and reply the same position, or the program fails. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "c-motion.h"
#include "PMDfmu.h"
#include "PMDfmu_ports.h"
#include "PMDhosttime.h"
#include "PMDopcodes.h"
#include "fmi2Functions.h"

/* the position both chips are given, so that GetPosition's reply is not a default 0 */
#define POSITION 0x12345678L

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void fail(const char *what)
{
    fprintf(stderr, "bench_c_library: %s\n", what);
    exit(1);
}

static void library_log(void *context, const char *category, int status, const char *message)
{
    (void)context;
    fprintf(stderr, "bench_c_library: library [%s] %d: %s\n", category, status, message);
}

static void fmu_log(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status, fmi2String category,
                    fmi2String message, ...)
{
    (void)env, (void)name;
    if (status >= fmi2Error)
        fprintf(stderr, "bench_c_library: FMU [%s]: %s\n", category, message);
}

/* the velocity of the i-th Set: a different value every command, the same sequence for both */
static long velocity_of(long i)
{
    return 0x10000L + (i & 0xFFFFL) * 16;
}

/* ---- the direct FMI calls: one instance of the FMU binary, the host port's value references ---- */

static struct {
    void *library;
    fmi2Component instance;
    fmi2SetIntegerTYPE *setInteger;
    fmi2GetIntegerTYPE *getInteger;
    fmi2Integer strobe;     /* the last host.strobe value set, as the library keeps it */
} fmi;

typedef void (*Function)(void);

/* POSIX: a dlsym result holds a function's address; ISO C has no conversion of an object pointer to a
   function pointer, so the bytes are copied */
static Function symbol(const char *name)
{
    Function f;
    void *p = dlsym(fmi.library, name);
    if (!p) {
        fprintf(stderr, "bench_c_library: no %s in the FMU binary\n", name);
        exit(1);
    }
    memcpy(&f, &p, sizeof f);
    return f;
}

#define FUNCTION(name) ((name##TYPE *)symbol(#name))

static void fmi_open(const char *dir, const char *binary, const char *token)
{
    static fmi2CallbackFunctions callbacks;
    char resources[4096];
    callbacks.logger = fmu_log;
    callbacks.allocateMemory = calloc;
    callbacks.freeMemory = free;
    fmi.library = dlopen(binary, RTLD_NOW | RTLD_LOCAL);
    if (!fmi.library)
        fail(dlerror());
    fmi.setInteger = FUNCTION(fmi2SetInteger);
    fmi.getInteger = FUNCTION(fmi2GetInteger);
    snprintf(resources, sizeof resources, "file://%s/resources", dir);
    fmi.instance = FUNCTION(fmi2Instantiate)("pmd", fmi2CoSimulation, token, resources, &callbacks, fmi2False,
                                              fmi2False);
    if (!fmi.instance)
        fail("fmi2Instantiate failed");
    if (FUNCTION(fmi2SetupExperiment)(fmi.instance, fmi2False, 0.0, 0.0, fmi2False, 0.0) > fmi2Warning ||
        FUNCTION(fmi2EnterInitializationMode)(fmi.instance) > fmi2Warning ||
        FUNCTION(fmi2ExitInitializationMode)(fmi.instance) > fmi2Warning)
        fail("initializing the FMU instance failed");
}

static void fmi_close(void)
{
    FUNCTION(fmi2Terminate)(fmi.instance);
    FUNCTION(fmi2FreeInstance)(fmi.instance);
    dlclose(fmi.library);
}

/* the value reference lists, built once: what a hand-written caller of the port would send; the
   replies' list (ack, error, count, then the reply words) serves a Set (its first 3) and a Get */
static const fmi2ValueReference set_vrs[5] = {PMD_FMU_VR_HOST_WORD, PMD_FMU_VR_HOST_WORD + 1,
                                              PMD_FMU_VR_HOST_WORD + 2, PMD_FMU_VR_HOST_WORD_COUNT,
                                              PMD_FMU_VR_HOST_STROBE};
static const fmi2ValueReference get_vrs[5] = {PMD_FMU_VR_HOST_ACK, PMD_FMU_VR_HOST_ERROR,
                                              PMD_FMU_VR_HOST_REPLY_COUNT, PMD_FMU_VR_HOST_REPLY,
                                              PMD_FMU_VR_HOST_REPLY + 1};
static const fmi2ValueReference get_request_vrs[3] = {PMD_FMU_VR_HOST_WORD, PMD_FMU_VR_HOST_WORD_COUNT,
                                                      PMD_FMU_VR_HOST_STROBE};

/* a command of axis 1 with two argument words (a 32-bit Set), its execution checked */
static void fmi_set32(int opcode, long value)
{
    fmi2Integer words[5], reply[3];
    words[0] = opcode;       /* axis 1 (0) in bits 8-15 */
    words[1] = (fmi2Integer)(((unsigned long)value >> 16) & 0xFFFFu);
    words[2] = (fmi2Integer)((unsigned long)value & 0xFFFFu);
    words[3] = 3;
    fmi.strobe = (fmi.strobe + 1) & 0x7FFFFFFF;
    words[4] = fmi.strobe;
    if (fmi.setInteger(fmi.instance, set_vrs, 5, words) > fmi2Warning ||
        fmi.getInteger(fmi.instance, get_vrs, 3, reply) > fmi2Warning)
        fail("an FMI call of a Set failed");
    if (reply[0] != fmi.strobe || reply[1] != 0 || reply[2] != 0)
        fail("the FMU did not execute a Set (host.ack, host.error or host.replyCount)");
}

/* a command of axis 1 without arguments and a 2-word reply (a 32-bit Get), its execution checked */
static long fmi_get32(int opcode)
{
    fmi2Integer words[3], reply[5];
    words[0] = opcode;
    words[1] = 1;
    fmi.strobe = (fmi.strobe + 1) & 0x7FFFFFFF;
    words[2] = fmi.strobe;
    if (fmi.setInteger(fmi.instance, get_request_vrs, 3, words) > fmi2Warning ||
        fmi.getInteger(fmi.instance, get_vrs, 5, reply) > fmi2Warning)
        fail("an FMI call of a Get failed");
    if (reply[0] != fmi.strobe || reply[1] != 0 || reply[2] != 2)
        fail("the FMU did not execute a Get (host.ack, host.error or host.replyCount)");
    return PMDFMU_Int32(((PMDuint32)reply[3] << 16) | (PMDuint32)reply[4]);
}

/* ---- the contenders: COMMANDS commands each, timed ---- */

static PMDAxisHandle axis;
static volatile long sink;  /* the replies go somewhere: no call is dead code */

static double library_sets(long commands, long from)
{
    double t = now();
    for (long i = from; i < from + commands; i++)
        if (PMDSetVelocity(&axis, velocity_of(i)) != PMD_ERR_OK)
            fail("PMDSetVelocity failed");
    return now() - t;
}

static double fmi_sets(long commands, long from)
{
    double t = now();
    for (long i = from; i < from + commands; i++)
        fmi_set32(PMDOPSetVelocity, velocity_of(i));
    return now() - t;
}

static double library_gets(long commands)
{
    PMDint32 position = 0;
    long sum = 0;
    double t = now();
    for (long i = 0; i < commands; i++) {
        if (PMDGetPosition(&axis, &position) != PMD_ERR_OK)
            fail("PMDGetPosition failed");
        sum += position;
    }
    t = now() - t;
    sink = sum;
    return t;
}

static double fmi_gets(long commands)
{
    long sum = 0;
    double t = now();
    for (long i = 0; i < commands; i++)
        sum += fmi_get32(PMDOPGetPosition);
    t = now() - t;
    sink = sum;
    return t;
}

int main(int argc, char **argv)
{
    PMDFMUOptions options;
    PMDHostInterface none = PMDHostInterfaceOf(PMDHostNone);
    long commands, runs, sent = 0;
    PMDint32 position, velocity;
    if (argc != 6) {
        fprintf(stderr, "usage: bench_c_library FMU_DIR FMU_BINARY TOKEN COMMANDS RUNS\n");
        return 2;
    }
    commands = atol(argv[4]);
    runs = atol(argv[5]);
    if (commands < 1 || runs < 1)
        fail("COMMANDS and RUNS are whole numbers above 0");

    PMDFMUOptionsInit(&options);
    options.fmu = argv[1];
    options.hostInterface = &none;  /* commands take no host time: no doStep between them */
    options.log = library_log;
    if (PMDSetupAxisInterface_FMU(&axis, PMDAxis1, &options) != PMD_ERR_OK)
        fail("PMDSetupAxisInterface_FMU failed");
    fmi_open(argv[1], argv[2], argv[3]);

    /* the same position on both chips, each through its own path */
    if (PMDSetPosition(&axis, POSITION) != PMD_ERR_OK)
        fail("PMDSetPosition failed");
    fmi_set32(PMDOPSetPosition, POSITION);

    for (long run = -1; run < runs; run++) {   /* run -1: warming up, not printed */
        double a = library_sets(commands, sent), b = fmi_sets(commands, sent);
        sent += commands;
        if (run >= 0)
            printf("set library %.9f\nset fmi %.9f\n", a, b);
    }
    for (long run = -1; run < runs; run++) {
        double a = library_gets(commands), b = fmi_gets(commands);
        if (run >= 0)
            printf("get library %.9f\nget fmi %.9f\n", a, b);
    }

    /* both chips executed the same commands: the last velocity, the position */
    if (PMDGetVelocity(&axis, &velocity) != PMD_ERR_OK || PMDGetPosition(&axis, &position) != PMD_ERR_OK)
        fail("reading back the library's chip failed");
    if (velocity != velocity_of(sent - 1) || fmi_get32(PMDOPGetVelocity) != velocity)
        fail("the two chips hold different velocities: a Set did not execute");
    if (position != POSITION || fmi_get32(PMDOPGetPosition) != position)
        fail("the two chips reply different positions");
    fmi_close();
    PMDCloseAxisInterface(&axis);
    return 0;
}
