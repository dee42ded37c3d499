/* SPDX-License-Identifier: BSD-2-Clause */
/* Drives the real FMU binary (dlopen) through FMI 2.0 from C.
 *
 *   instances FMU.so GUID SCENARIO threads   four instances, each running the scenario with its own
 *                                            offset, sequentially and then from four threads at once:
 *                                            the outputs must be identical
 *   instances FMU.so GUID SCENARIO cycles N  N times: instantiate, run, save state, run, restore, run,
 *                                            serialize/deserialize, free (for valgrind)
 *
 * A scenario file has one action per line: "H words..." a host batch, "M address words..." a memory
 * write, "S cycles" a doStep. Written by tests/test_instances.py with the harness's encoder. Like any
 * host, the driver reads after each port write: the port executes at the next get or doStep. */
#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"

#define MAX_ACTIONS 4096
#define MAX_WORDS 70

typedef struct { char kind; int n; long words[MAX_WORDS]; } Action;

static Action actions[MAX_ACTIONS];
static int nActions;
static const char *guid;

#define F(name) static name##TYPE *name##_
F(fmi2Instantiate); F(fmi2FreeInstance); F(fmi2SetupExperiment); F(fmi2EnterInitializationMode);
F(fmi2ExitInitializationMode); F(fmi2SetInteger); F(fmi2GetInteger); F(fmi2DoStep); F(fmi2GetFMUstate);
F(fmi2SetFMUstate); F(fmi2FreeFMUstate); F(fmi2SerializedFMUstateSize); F(fmi2SerializeFMUstate);
F(fmi2DeSerializeFMUstate); F(fmi2Terminate);

static void logger(fmi2ComponentEnvironment e, fmi2String n, fmi2Status s, fmi2String c, fmi2String m, ...)
{
    (void)e; (void)n; (void)c;
    if (s >= fmi2Error)
        fprintf(stderr, "FMU error: %s\n", m);
}

static const fmi2CallbackFunctions callbacks = {logger, NULL, NULL, NULL, NULL};

/* value references of the ports (FMI 2 table: host.word[1] = 1001 ...) */
enum { WORD = 1001, WORD_COUNT = 1100, STROBE = 1101, M_ADDRESS = 1400, M_COUNT = 1401, M_STROBE = 1402,
       M_DATA = 1501 };
static const fmi2ValueReference outputs[] = {10, 100, 101, 102, 106, 107, 200, 201, 202, 300, 301, 302, 400};
#define NOUT (sizeof outputs / sizeof outputs[0])

static int check(fmi2Status s, const char *what)
{
    if (s > fmi2Warning) {
        fprintf(stderr, "%s failed\n", what);
        exit(1);
    }
    return 0;
}

/* Runs the scenario on c; appends the outputs after every step to out. */
static size_t run(fmi2Component c, int offset, double *time, fmi2Integer *out)
{
    int i, k;
    fmi2Integer strobe, mstrobe;
    const fmi2ValueReference strobes[] = {STROBE, M_STROBE}, ack = 1102;
    fmi2Integer now[2];
    size_t n = 0;
    check(fmi2GetInteger_(c, strobes, 2, now), "strobes");      /* continue from the FMU's own */
    strobe = now[0];
    mstrobe = now[1];
    for (i = 0; i < nActions; i++) {
        const Action *a = &actions[i];
        fmi2ValueReference vr[MAX_WORDS + 3];
        fmi2Integer v[MAX_WORDS + 3];
        if (a->kind == 'H') {
            for (k = 0; k < a->n; k++) {
                vr[k] = WORD + (fmi2ValueReference)k;
                v[k] = (fmi2Integer)a->words[k];
            }
            vr[k] = WORD_COUNT; v[k++] = a->n;
            vr[k] = STROBE; v[k++] = ++strobe;
            check(fmi2SetInteger_(c, vr, (size_t)k, v), "host batch");
            check(fmi2GetInteger_(c, &ack, 1, v), "host.ack");        /* a get executes the batch now */
        } else if (a->kind == 'M') {
            for (k = 0; k < a->n - 1; k++) {
                vr[k] = M_DATA + (fmi2ValueReference)k;
                v[k] = (fmi2Integer)(a->words[k + 1] + offset);     /* each instance its own profile */
            }
            vr[k] = M_ADDRESS; v[k++] = (fmi2Integer)a->words[0];
            vr[k] = M_COUNT; v[k++] = a->n - 1;
            vr[k] = M_STROBE; v[k++] = ++mstrobe;
            check(fmi2SetInteger_(c, vr, (size_t)k, v), "memory write");
            check(fmi2GetInteger_(c, &ack, 1, v), "host.ack");
        } else {
            double h = (double)a->words[0] * 1e-4;
            check(fmi2DoStep_(c, *time, h, fmi2False), "doStep");
            *time += h;
            check(fmi2GetInteger_(c, outputs, NOUT, out + n), "outputs");
            n += NOUT;
        }
    }
    return n;
}

static fmi2Component start(void)
{
    fmi2Component c = fmi2Instantiate_("c", fmi2CoSimulation, guid, "", &callbacks, fmi2False, fmi2False);
    if (!c)
        exit(1);
    check(fmi2SetupExperiment_(c, fmi2False, 0, 0, fmi2False, 0), "setup");
    check(fmi2EnterInitializationMode_(c), "enter");
    check(fmi2ExitInitializationMode_(c), "exit");
    return c;
}

typedef struct { int offset; fmi2Integer *out; size_t n; } Job;

static void *job(void *arg)
{
    Job *j = (Job *)arg;
    fmi2Component c = start();
    double t = 0;
    j->n = run(c, j->offset, &t, j->out);
    fmi2FreeInstance_(c);
    return NULL;
}

static void load(const char *path)
{
    char line[4096];
    FILE *f = fopen(path, "r");
    if (!f)
        exit(2);
    while (fgets(line, sizeof line, f) && nActions < MAX_ACTIONS) {
        Action *a = &actions[nActions++];
        char *p = line + 1, *end;
        a->kind = line[0];
        a->n = 0;
        while (a->n < MAX_WORDS && (a->words[a->n] = strtol(p, &end, 10), end != p)) {
            a->n++;
            p = end;
        }
    }
    fclose(f);
}

int main(int argc, char **argv)
{
    void *lib;
    int i;
    if (argc < 5)
        return 2;
    lib = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        fprintf(stderr, "%s\n", dlerror());
        return 2;
    }
#define LOAD(name) *(void **)(&name##_) = dlsym(lib, #name)
    LOAD(fmi2Instantiate); LOAD(fmi2FreeInstance); LOAD(fmi2SetupExperiment); LOAD(fmi2EnterInitializationMode);
    LOAD(fmi2ExitInitializationMode); LOAD(fmi2SetInteger); LOAD(fmi2GetInteger); LOAD(fmi2DoStep);
    LOAD(fmi2GetFMUstate); LOAD(fmi2SetFMUstate); LOAD(fmi2FreeFMUstate); LOAD(fmi2SerializedFMUstateSize);
    LOAD(fmi2SerializeFMUstate); LOAD(fmi2DeSerializeFMUstate); LOAD(fmi2Terminate);
    guid = argv[2];
    load(argv[3]);
    if (strcmp(argv[4], "threads") == 0) {
        Job seq[4], par[4];
        pthread_t threads[4];
        for (i = 0; i < 4; i++) {
            seq[i].offset = par[i].offset = 1000 * i;
            seq[i].out = calloc(MAX_ACTIONS * NOUT, sizeof(fmi2Integer));
            par[i].out = calloc(MAX_ACTIONS * NOUT, sizeof(fmi2Integer));
            job(&seq[i]);
        }
        for (i = 0; i < 4; i++)
            pthread_create(&threads[i], NULL, job, &par[i]);
        for (i = 0; i < 4; i++)
            pthread_join(threads[i], NULL);
        for (i = 0; i < 4; i++) {
            if (seq[i].n == 0 || seq[i].n != par[i].n ||
                memcmp(seq[i].out, par[i].out, seq[i].n * sizeof(fmi2Integer)) != 0) {
                fprintf(stderr, "instance %d: threads differ from sequential\n", i);
                return 1;
            }
            if (i > 0 && memcmp(seq[i].out, seq[0].out, seq[i].n * sizeof(fmi2Integer)) == 0) {
                fprintf(stderr, "instance %d ran the same profile as instance 0\n", i);
                return 1;
            }
        }
        for (i = 0; i < 4; i++) {
            free(seq[i].out);
            free(par[i].out);
        }
        printf("4 threads = sequential (%zu values each)\n", seq[0].n);
    } else {
        int rounds = atoi(argv[5]);
        fmi2Integer *a = calloc(MAX_ACTIONS * NOUT, sizeof(fmi2Integer)), *b = calloc(MAX_ACTIONS * NOUT, sizeof(fmi2Integer));
        for (i = 0; i < rounds; i++) {
            fmi2Component c = start();
            fmi2FMUstate s = NULL, d = NULL;
            size_t size = 0, n1, n2;
            fmi2Byte *blob;
            double t = 0, saved;
            run(c, 0, &t, a);
            saved = t;
            check(fmi2GetFMUstate_(c, &s), "get state");
            n1 = run(c, 0, &t, a);
            check(fmi2SetFMUstate_(c, s), "set state");
            t = saved;
            n2 = run(c, 0, &t, b);
            if (n1 != n2 || memcmp(a, b, n1 * sizeof(fmi2Integer)) != 0) {
                fprintf(stderr, "round %d: restored run differs\n", i);
                return 1;
            }
            check(fmi2SerializedFMUstateSize_(c, s, &size), "size");
            blob = malloc(size);
            check(fmi2SerializeFMUstate_(c, s, blob, size), "serialize");
            check(fmi2DeSerializeFMUstate_(c, blob, size, &d), "deserialize");
            free(blob);
            fmi2FreeFMUstate_(c, &s);
            fmi2FreeFMUstate_(c, &d);
            fmi2Terminate_(c);
            fmi2FreeInstance_(c);
        }
        free(a);
        free(b);
        printf("%d rounds\n", rounds);
    }
    dlclose(lib);
    return 0;
}
