/* SPDX-License-Identifier: BSD-2-Clause */
/* A minimal co-simulation master over the FMUs' own binaries, in FMI 2 or FMI 3
 * (tests/test_binaries.py): the same program, built for each platform an FMU carries
 * (linux64 natively, Windows with mingw-w64 under Wine, aarch64 under qemu-user), loads
 * each binary with dlopen or LoadLibrary and prints the same rows, so the rows of every
 * platform can be compared with the linux64 ones bit for bit.
 *
 *     fmi_master STEPS STEP_SIZE ARGUMENT...
 *       fmu VERSION LIBRARY RESOURCES TOKEN   instantiate an FMU (the first is 0, then 1, ...);
 *                                             RESOURCES: FMI 2's URI, FMI 3's path
 *       set K TYPE VR VALUE                   a start value of FMU K, set before initialization
 *       wire K TYPE VR K2 VR2                 before each step, FMU K2's input VR2 = FMU K's output VR
 *       out K TYPE VR                         a column of every row
 *
 * TYPE is the variable's type in its FMI version's description: Real, Integer, Boolean,
 * String (FMI 2), Float64, Int16, Int32, UInt16, UInt32, Boolean, String (FMI 3). A Jacobi
 * master: every wire reads the outputs of the communication point, then every FMU steps
 * from t = k * STEP_SIZE. A row: the step k, then each column, an integer in decimal and
 * a double as the hexadecimal of its 64 bits (exact whatever the platform's printf). */
#include <inttypes.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _WIN32
#include <windows.h>
#else
#include <dlfcn.h>
#endif

#include "fmi2Functions.h"
#include "fmi3Functions.h"

#define MAX_FMUS 4
#define MAX_ITEMS 64

typedef void (*Function)(void);

typedef struct {
    int version;
    void *instance;
    /* FMI 2 */
    fmi2InstantiateTYPE *fmi2Instantiate;
    fmi2SetupExperimentTYPE *fmi2SetupExperiment;
    fmi2EnterInitializationModeTYPE *fmi2EnterInitializationMode;
    fmi2ExitInitializationModeTYPE *fmi2ExitInitializationMode;
    fmi2GetRealTYPE *fmi2GetReal;
    fmi2GetIntegerTYPE *fmi2GetInteger;
    fmi2SetRealTYPE *fmi2SetReal;
    fmi2SetIntegerTYPE *fmi2SetInteger;
    fmi2SetBooleanTYPE *fmi2SetBoolean;
    fmi2SetStringTYPE *fmi2SetString;
    fmi2DoStepTYPE *fmi2DoStep;
    fmi2TerminateTYPE *fmi2Terminate;
    fmi2FreeInstanceTYPE *fmi2FreeInstance;
    /* FMI 3 */
    fmi3InstantiateCoSimulationTYPE *fmi3InstantiateCoSimulation;
    fmi3EnterInitializationModeTYPE *fmi3EnterInitializationMode;
    fmi3ExitInitializationModeTYPE *fmi3ExitInitializationMode;
    fmi3GetFloat64TYPE *fmi3GetFloat64;
    fmi3GetInt16TYPE *fmi3GetInt16;
    fmi3GetInt32TYPE *fmi3GetInt32;
    fmi3GetUInt16TYPE *fmi3GetUInt16;
    fmi3GetUInt32TYPE *fmi3GetUInt32;
    fmi3SetFloat64TYPE *fmi3SetFloat64;
    fmi3SetInt16TYPE *fmi3SetInt16;
    fmi3SetInt32TYPE *fmi3SetInt32;
    fmi3SetUInt16TYPE *fmi3SetUInt16;
    fmi3SetUInt32TYPE *fmi3SetUInt32;
    fmi3SetBooleanTYPE *fmi3SetBoolean;
    fmi3SetStringTYPE *fmi3SetString;
    fmi3DoStepTYPE *fmi3DoStep;
    fmi3TerminateTYPE *fmi3Terminate;
    fmi3FreeInstanceTYPE *fmi3FreeInstance;
} Fmu;

/* a value of any type the master moves: integers widened to 64 bits */
typedef struct {
    int isReal;
    double real;
    int64_t integer;
} Value;

typedef struct {
    int fmu, fmu2;
    char type[16];
    unsigned vr, vr2;
    Value value;
} Item;

static Fmu fmus[MAX_FMUS];
static int nFmus;

static void die(const char *format, ...)
{
    va_list args;
    va_start(args, format);
    fputs("fmi_master: ", stderr);
    vfprintf(stderr, format, args);
    fputc('\n', stderr);
    va_end(args);
    exit(1);
}

static Function symbol(void *library, const char *name)
{
    Function f;
#ifdef _WIN32
    f = (Function)GetProcAddress((HMODULE)library, name);
#else
    void *address = dlsym(library, name);
    memcpy(&f, &address, sizeof f); /* POSIX: a function's address as an object pointer */
#endif
    if (!f)
        die("the library has no %s", name);
    return f;
}

#define LOAD(name) (f->name = (name##TYPE *)symbol(library, #name))

static void logger2(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status, fmi2String category,
                    fmi2String message, ...)
{
    va_list args;
    (void)env;
    if (status < fmi2Warning)
        return;
    va_start(args, message);
    fprintf(stderr, "%s [%s]: ", name, category);
    vfprintf(stderr, message, args);
    fputc('\n', stderr);
    va_end(args);
}

static void logger3(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category, fmi3String message)
{
    (void)env;
    if (status >= fmi3Warning)
        fprintf(stderr, "[%s]: %s\n", category, message);
}

static void check(int status, const char *call)
{
    if (status > 1) /* fmi2OK/fmi3OK 0, Warning 1 */
        die("%s returned status %d", call, status);
}

static void instantiate(Fmu *f, int version, const char *path, const char *resources, const char *token)
{
    static const fmi2CallbackFunctions callbacks = {logger2, calloc, free, NULL, NULL};
    char name[16];
    void *library;
#ifdef _WIN32
    library = (void *)LoadLibraryA(path);
#else
    library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
#endif
    if (!library)
        die("cannot load %s", path);
    f->version = version;
    snprintf(name, sizeof name, "fmu%d", nFmus);
    if (version == 2) {
        LOAD(fmi2Instantiate);
        LOAD(fmi2SetupExperiment);
        LOAD(fmi2EnterInitializationMode);
        LOAD(fmi2ExitInitializationMode);
        LOAD(fmi2GetReal);
        LOAD(fmi2GetInteger);
        LOAD(fmi2SetReal);
        LOAD(fmi2SetInteger);
        LOAD(fmi2SetBoolean);
        LOAD(fmi2SetString);
        LOAD(fmi2DoStep);
        LOAD(fmi2Terminate);
        LOAD(fmi2FreeInstance);
        f->instance = f->fmi2Instantiate(name, fmi2CoSimulation, token, resources, &callbacks, fmi2False, fmi2False);
        if (f->instance)
            check(f->fmi2SetupExperiment(f->instance, fmi2False, 0.0, 0.0, fmi2False, 0.0), "fmi2SetupExperiment");
    } else {
        LOAD(fmi3InstantiateCoSimulation);
        LOAD(fmi3EnterInitializationMode);
        LOAD(fmi3ExitInitializationMode);
        LOAD(fmi3GetFloat64);
        LOAD(fmi3GetInt16);
        LOAD(fmi3GetInt32);
        LOAD(fmi3GetUInt16);
        LOAD(fmi3GetUInt32);
        LOAD(fmi3SetFloat64);
        LOAD(fmi3SetInt16);
        LOAD(fmi3SetInt32);
        LOAD(fmi3SetUInt16);
        LOAD(fmi3SetUInt32);
        LOAD(fmi3SetBoolean);
        LOAD(fmi3SetString);
        LOAD(fmi3DoStep);
        LOAD(fmi3Terminate);
        LOAD(fmi3FreeInstance);
        f->instance = f->fmi3InstantiateCoSimulation(name, token, resources, fmi3False, fmi3False, fmi3False, fmi3False, NULL, 0,
                                      NULL, logger3, NULL);
    }
    if (!f->instance)
        die("%s: instantiation failed", path);
}

static int is_type(const Item *item, const char *type)
{
    return strcmp(item->type, type) == 0;
}

static Value get(const Item *item)
{
    const Fmu *f = &fmus[item->fmu];
    fmi3ValueReference vr = item->vr;
    Value v = {0, 0.0, 0};
    int status = 0;
    if (is_type(item, "Real") || is_type(item, "Float64")) {
        v.isReal = 1;
        status = f->version == 2 ? f->fmi2GetReal(f->instance, &vr, 1, &v.real)
                                 : f->fmi3GetFloat64(f->instance, &vr, 1, &v.real, 1);
    } else if (f->version == 2) {
        fmi2Integer i = 0;
        status = f->fmi2GetInteger(f->instance, &vr, 1, &i);
        v.integer = i;
    } else if (is_type(item, "Int16")) {
        fmi3Int16 i = 0;
        status = f->fmi3GetInt16(f->instance, &vr, 1, &i, 1);
        v.integer = i;
    } else if (is_type(item, "Int32")) {
        fmi3Int32 i = 0;
        status = f->fmi3GetInt32(f->instance, &vr, 1, &i, 1);
        v.integer = i;
    } else if (is_type(item, "UInt16")) {
        fmi3UInt16 i = 0;
        status = f->fmi3GetUInt16(f->instance, &vr, 1, &i, 1);
        v.integer = i;
    } else if (is_type(item, "UInt32")) {
        fmi3UInt32 i = 0;
        status = f->fmi3GetUInt32(f->instance, &vr, 1, &i, 1);
        v.integer = i;
    } else {
        die("cannot get a %s", item->type);
    }
    check(status, "a get");
    return v;
}

/* sets FMU k's vr of the item's type to v (text: a String's value) */
static void set(int k, const char *type, unsigned vr32, Value v, const char *text)
{
    const Fmu *f = &fmus[k];
    fmi3ValueReference vr = vr32;
    int status;
    Item item;
    memset(&item, 0, sizeof item);
    snprintf(item.type, sizeof item.type, "%s", type);
    if (is_type(&item, "String")) {
        status = f->version == 2 ? f->fmi2SetString(f->instance, &vr, 1, &text) : f->fmi3SetString(f->instance, &vr, 1, &text, 1);
    } else if (is_type(&item, "Boolean")) {
        fmi2Boolean b2 = v.integer != 0;
        fmi3Boolean b3 = v.integer != 0;
        status = f->version == 2 ? f->fmi2SetBoolean(f->instance, &vr, 1, &b2) : f->fmi3SetBoolean(f->instance, &vr, 1, &b3, 1);
    } else if (is_type(&item, "Real") || is_type(&item, "Float64")) {
        status = f->version == 2 ? f->fmi2SetReal(f->instance, &vr, 1, &v.real) : f->fmi3SetFloat64(f->instance, &vr, 1, &v.real, 1);
    } else if (f->version == 2) {
        fmi2Integer i = (fmi2Integer)v.integer;
        status = f->fmi2SetInteger(f->instance, &vr, 1, &i);
    } else if (is_type(&item, "Int16")) {
        fmi3Int16 i = (fmi3Int16)v.integer;
        status = f->fmi3SetInt16(f->instance, &vr, 1, &i, 1);
    } else if (is_type(&item, "Int32")) {
        fmi3Int32 i = (fmi3Int32)v.integer;
        status = f->fmi3SetInt32(f->instance, &vr, 1, &i, 1);
    } else if (is_type(&item, "UInt16")) {
        fmi3UInt16 i = (fmi3UInt16)v.integer;
        status = f->fmi3SetUInt16(f->instance, &vr, 1, &i, 1);
    } else if (is_type(&item, "UInt32")) {
        fmi3UInt32 i = (fmi3UInt32)v.integer;
        status = f->fmi3SetUInt32(f->instance, &vr, 1, &i, 1);
    } else {
        die("cannot set a %s", type);
    }
    check(status, "a set");
}

static void print_row(long k, const Item *outs, int nOuts)
{
    int i;
    printf("%ld", k);
    for (i = 0; i < nOuts; i++) {
        Value v = get(&outs[i]);
        if (v.isReal) {
            uint64_t bits;
            memcpy(&bits, &v.real, sizeof bits);
            printf(" 0x%016" PRIx64, bits);
        } else {
            printf(" %" PRId64, v.integer);
        }
    }
    putchar('\n');
}

static int fmu_index(const char *text)
{
    int k = atoi(text);
    if (k < 0 || k >= nFmus)
        die("no FMU %s", text);
    return k;
}

int main(int argc, char **argv)
{
    static Item wires[MAX_ITEMS], outs[MAX_ITEMS];
    int nWires = 0, nOuts = 0, i, k;
    long steps, step;
    double h;
    if (argc < 3)
        die("usage: fmi_master STEPS STEP_SIZE [fmu VERSION LIBRARY RESOURCES TOKEN | set K TYPE VR VALUE | "
            "wire K TYPE VR K2 VR2 | out K TYPE VR] ...");
    steps = atol(argv[1]);
    h = strtod(argv[2], NULL);
    for (i = 3; i < argc;) {
        const char *word = argv[i];
        if (strcmp(word, "fmu") == 0 && i + 4 < argc) {
            if (nFmus == MAX_FMUS)
                die("more than %d FMUs", MAX_FMUS);
            instantiate(&fmus[nFmus], atoi(argv[i + 1]), argv[i + 2], argv[i + 3], argv[i + 4]);
            nFmus++;
            i += 5;
        } else if (strcmp(word, "set") == 0 && i + 4 < argc) {
            Value v = {0, 0.0, 0};
            v.real = strtod(argv[i + 4], NULL);
            v.integer = strtoll(argv[i + 4], NULL, 0);
            set(fmu_index(argv[i + 1]), argv[i + 2], (unsigned)strtoul(argv[i + 3], NULL, 0), v, argv[i + 4]);
            i += 5;
        } else if (strcmp(word, "wire") == 0 && i + 5 < argc && nWires < MAX_ITEMS) {
            Item *w = &wires[nWires++];
            w->fmu = fmu_index(argv[i + 1]);
            snprintf(w->type, sizeof w->type, "%s", argv[i + 2]);
            w->vr = (unsigned)strtoul(argv[i + 3], NULL, 0);
            w->fmu2 = fmu_index(argv[i + 4]);
            w->vr2 = (unsigned)strtoul(argv[i + 5], NULL, 0);
            i += 6;
        } else if (strcmp(word, "out") == 0 && i + 3 < argc && nOuts < MAX_ITEMS) {
            Item *o = &outs[nOuts++];
            o->fmu = fmu_index(argv[i + 1]);
            snprintf(o->type, sizeof o->type, "%s", argv[i + 2]);
            o->vr = (unsigned)strtoul(argv[i + 3], NULL, 0);
            i += 4;
        } else {
            die("cannot read the arguments from %s on", word);
        }
    }
    for (k = 0; k < nFmus; k++) {
        Fmu *f = &fmus[k];
        if (f->version == 2) {
            check(f->fmi2EnterInitializationMode(f->instance), "fmi2EnterInitializationMode");
            check(f->fmi2ExitInitializationMode(f->instance), "fmi2ExitInitializationMode");
        } else {
            check(f->fmi3EnterInitializationMode(f->instance, fmi3False, 0.0, 0.0, fmi3False, 0.0),
                  "fmi3EnterInitializationMode");
            check(f->fmi3ExitInitializationMode(f->instance), "fmi3ExitInitializationMode");
        }
    }
    print_row(0, outs, nOuts);
    for (step = 0; step < steps; step++) {
        double t = (double)step * h;
        for (i = 0; i < nWires; i++)
            wires[i].value = get(&wires[i]);
        for (i = 0; i < nWires; i++)
            set(wires[i].fmu2, wires[i].type, wires[i].vr2, wires[i].value, NULL);
        for (k = 0; k < nFmus; k++) {
            Fmu *f = &fmus[k];
            if (f->version == 2) {
                check(f->fmi2DoStep(f->instance, t, h, fmi2True), "fmi2DoStep");
            } else {
                fmi3Boolean eventNeeded, terminate, earlyReturn;
                fmi3Float64 last;
                check(f->fmi3DoStep(f->instance, t, h, fmi3True, &eventNeeded, &terminate, &earlyReturn, &last),
                      "fmi3DoStep");
            }
        }
        print_row(step + 1, outs, nOuts);
    }
    for (k = 0; k < nFmus; k++) {
        Fmu *f = &fmus[k];
        if (f->version == 2) {
            check(f->fmi2Terminate(f->instance), "fmi2Terminate");
            f->fmi2FreeInstance(f->instance);
        } else {
            check(f->fmi3Terminate(f->instance), "fmi3Terminate");
            f->fmi3FreeInstance(f->instance);
        }
    }
    return 0;
}
