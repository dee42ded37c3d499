/* SPDX-License-Identifier: BSD-2-Clause */
/* The C-Motion library's FMU transport (PMDfmu.h): loads the FMI 2 binary of the
   PMDMotionProcessor FMU with dlopen and drives it as a co-simulation master does. */
#define _XOPEN_SOURCE 700     /* realpath, mkdtemp, nftw, nanosleep */
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <spawn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "fmi2FunctionTypes.h"
#include "c-motion.h"
#include "PMDfmu_ports.h"
#include "PMDline.h"
#ifdef PMD_HAVE_HOSTTIME
#include "PMDhosttime.h"
#endif

#ifndef PMD_FMI2_PLATFORM
#define PMD_FMI2_PLATFORM "linux64"
#endif

/* The longest message the FMU formats (fmu_src/fmi/instance.c: a refused script names the places
   it was looked for) */
#define PMD_FMU_MESSAGE 8192

extern char **environ;     /* unzip's environment: the caller's */

/* One chip: an FMU instance and the host's side of its ports. Every handle of the chip points here. */
typedef struct PMDFMUDevice {
    struct PMDFMUDevice *next;      /* the open chips, for PMDTaskWait (under open_devices_lock) */
    pthread_t opener;               /* the thread that opened it: its PMDTaskWait advances the chip */
    int handles;                    /* handles that use it; freed with the last */
    void *library;
    fmi2Component instance;
    char *unpacked;                 /* the temporary directory a .fmu file was unpacked into, or NULL */
    PMDFMUOptions options;
    fmi2CallbackFunctions callbacks;    /* the FMU's logger calls back with this device */
    char fmuError[PMD_FMU_MESSAGE];     /* the FMU's last error message, for the transport's line */
    PMDAxisHandle self;             /* the handle the cycle callback gets */
    fmi2Integer strobe;             /* the last host.strobe value set */
    fmi2Integer memoryStrobe;       /* the last memory.strobe value set */
    int initialized;                /* out of initialization mode: Terminate before FreeInstance */
    uint64_t hostNs;                /* the host clock: ns since the chip's time 0 */
    int commandsTakeTime;           /* 0 for the host interface `none`: commands run no cycle */
    uint64_t cycles;                /* cycles run since the chip was opened */
    uint64_t maxCycles;             /* PMDFMU_MAX_CYCLES: 0 none */
    int lastOpcode, lastAxis;       /* the command sent last (-1: none yet), what a program polls */
    unsigned long lastRepeats;      /* how many times in a row it was sent */
    PMDLine *line;                  /* PMDFMU_DEVICE's link to a chip elsewhere (no FMU here), or NULL */
    uint64_t openedNs;              /* a line's: the host's monotonic clock when it was opened */
#ifdef PMD_HAVE_HOSTTIME
    PMDHostInterface hostInterface;
#endif
    fmi2FreeInstanceTYPE *freeInstance;
    fmi2TerminateTYPE *terminate;
    fmi2DoStepTYPE *doStep;
    fmi2SetIntegerTYPE *setInteger;
    fmi2GetIntegerTYPE *getInteger;
    fmi2GetRealTYPE *getReal;
    fmi2GetBooleanTYPE *getBoolean;
} PMDFMUDevice;

/* Threads open and close their chips at the same time (one chip per thread), so the list is read
   and changed under the lock only; a chip's other fields are its thread's and need none. */
static pthread_mutex_t open_devices_lock = PTHREAD_MUTEX_INITIALIZER;
static PMDFMUDevice *open_devices;

/* ---- host time (host/c/PMDhosttime.h) ---- */

static uint64_t request_ns(const PMDFMUDevice *d, int words)
{
#ifdef PMD_HAVE_HOSTTIME
    return PMDHostRequestNs(&d->hostInterface, words);
#else
    (void)d, (void)words;
    return 0;
#endif
}

static uint64_t reply_ns(const PMDFMUDevice *d, int words, int failed)
{
#ifdef PMD_HAVE_HOSTTIME
    return PMDHostReplyNs(&d->hostInterface, words, failed);
#else
    (void)d, (void)words, (void)failed;
    return 0;
#endif
}

/* ---- logging ---- */

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status, fmi2String category,
                   fmi2String message, ...)
{
    PMDFMUDevice *d = env;
    char text[PMD_FMU_MESSAGE];
    va_list ap;
    (void)name;
    if (!d || !message)
        return;
    va_start(ap, message);              /* the FMU escapes '%' as "%%" and passes no arguments */
    vsnprintf(text, sizeof text, message, ap);
    va_end(ap);
    /* kept for the transport's line of the call that fails (errors come whatever the categories) */
    if (status >= fmi2Error)
        memcpy(d->fmuError, text, sizeof text);
    if (d->options.log)
        d->options.log(d->options.logContext, category ? category : "", (int)status, text);
}

/* Without options of its own a vendor-style program still hears why an opening failed: the
   transport's lines (never the chip's refusals, which its own error path sees) go to stderr. */
void PMDFMU_LogTransportToStderr(void *context, const char *category, int status, const char *message)
{
    (void)context;
    (void)status;
    if (strcmp(category, "transport") == 0)
        fprintf(stderr, "pmdfmu: %s\n", message);
}

static void log_text(PMDFMUDevice *d, const char *text)
{
    if (d->options.log)
        d->options.log(d->options.logContext, "transport", fmi2Error, text);
}

/* A refused FMI call: the transport's line names the call and quotes the FMU's reason (the
   error it logged), so that "fmi2ExitInitializationMode failed: ... script:2: reason" is one
   line, whichever categories the callback gets. */
static PMDresult fmi_failed(PMDFMUDevice *d, PMDresult result, const char *call)
{
    char text[PMD_FMU_MESSAGE + 128];
    const char *reason = d->fmuError;
    const size_t n = strlen(call);
    if (strncmp(reason, call, n) == 0 && reason[n] == ':' && reason[n + 1] == ' ')
        reason += n + 2;                /* the FMU's message names the call too */
    snprintf(text, sizeof text, "%s failed: %s", call, reason[0] ? reason : "the FMU logged no reason");
    d->fmuError[0] = '\0';
    log_text(d, text);
    return result;
}

/* ---- the time grid: the FMU's own outputs (time, nextCycleTime, activeCycleTime) ---- */

typedef struct {
    double now, next, cycle;    /* the last communication point, the next cycle's time, the cycle time (s) */
} Grid;

static PMDresult read_grid(PMDFMUDevice *d, Grid *g)
{
    const fmi2ValueReference vrs[3] = {PMD_FMU_VR_TIME, PMD_FMU_VR_NEXT_CYCLE_TIME, PMD_FMU_VR_ACTIVE_CYCLE_TIME};
    fmi2Real v[3];
    if (d->getReal(d->instance, vrs, 3, v) > fmi2Warning)
        return fmi_failed(d, PMD_ERR_Driver, "fmi2GetReal of the time grid");
    g->now = v[0], g->next = v[1], g->cycle = v[2];
    return PMD_ERR_OK;
}

/* A grid time in whole ns: the grid's times are whole microseconds (the sample time register). */
static uint64_t to_ns(double seconds)
{
    return seconds <= 0 ? 0 : (uint64_t)llround(seconds * 1e9);
}

/* PMDFMU_MAX_CYCLES reached: the program is waiting for something that has not come in that many
   cycles. One line on stderr (the program's own output may be a pipe that shows nothing else),
   naming the command it sent last: what a polling loop waits on. */
static void give_up(PMDFMUDevice *d)
{
    char text[512];
    const char *name = d->lastOpcode >= 0 ? PMDFMU_command_names[d->lastOpcode] : NULL;
    if (d->lastOpcode < 0)
        snprintf(text, sizeof text, "PMDFMU_MAX_CYCLES=%llu: the chip has run %llu cycles and the program is "
                 "still running; it has sent no command", (unsigned long long)d->maxCycles,
                 (unsigned long long)d->cycles);
    else
        snprintf(text, sizeof text, "PMDFMU_MAX_CYCLES=%llu: the chip has run %llu cycles and the program is "
                 "still waiting: its last command was PMD%s on axis %d (PMDAxis%d), sent %lu time%s in a row",
                 (unsigned long long)d->maxCycles, (unsigned long long)d->cycles, name ? name : "(unknown)",
                 d->lastAxis, d->lastAxis + 1, d->lastRepeats, d->lastRepeats == 1 ? "" : "s");
    if (d->options.log != PMDFMU_LogTransportToStderr)     /* which would print it a second time */
        log_text(d, text);
    fprintf(stderr, "%s\n", text);
    fflush(NULL);
    exit(PMDFMU_EXIT_MAX_CYCLES);
}

/* One doStep that runs the next `cycles` cycles of the grid (python/pmdfmu/chip.py: Chip._step). */
static PMDresult step(PMDFMUDevice *d, const Grid *g, uint64_t cycles)
{
    int over = 0;
    if (d->maxCycles && cycles > d->maxCycles - d->cycles) {
        cycles = d->maxCycles - d->cycles;        /* the last cycles allowed, then the end */
        over = 1;
    }
    if (cycles &&
        d->doStep(d->instance, g->now, (g->next - g->now) + (double)cycles * g->cycle, fmi2True) > fmi2Warning)
        return fmi_failed(d, PMD_ERR_Driver, "fmi2DoStep");
    d->cycles += cycles;
    if (over)
        give_up(d);
    return PMD_ERR_OK;
}

/* Runs every cycle whose grid time is at or before the host clock. */
static PMDresult run_due(PMDFMUDevice *d)
{
    for (;;) {
        Grid g = {0, 0, 0};
        uint64_t next, cycle, due;
        PMDresult r = read_grid(d, &g);
        if (r != PMD_ERR_OK)
            return r;
        next = to_ns(g.next), cycle = to_ns(g.cycle);
#ifdef PMD_HAVE_HOSTTIME
        due = PMDHostCyclesDue(d->hostNs, next, cycle);
#else
        due = cycle == 0 || d->hostNs < next ? 0 : (d->hostNs - next) / cycle + 1;
#endif
        if (due == 0)
            return PMD_ERR_OK;
        /* with a cycle callback, one cycle per doStep; a script's SetSampleTime may move the grid
           within a longer step, so the loop reads it again and runs what is still due */
        r = step(d, &g, d->options.cycle ? 1 : due);
        if (r != PMD_ERR_OK)
            return r;
        if (d->options.cycle)
            d->options.cycle(d->options.cycleContext, &d->self);
    }
}

/* ---- opening ---- */

void PMDFMUOptionsInit(PMDFMUOptions *options)
{
    memset(options, 0, sizeof *options);
    options->loopback = 1;
}

static char *read_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    char *text = NULL;
    long n;
    if (!f)
        return NULL;
    if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0 &&
        (text = malloc((size_t)n + 1)) != NULL) {
        if (fread(text, 1, (size_t)n, f) != (size_t)n) {
            free(text);
            text = NULL;
        } else {
            text[n] = '\0';
        }
    }
    fclose(f);
    return text;
}

/* The value of attribute `name` in the model description's text (guid, modelIdentifier). */
static int attribute(const char *xml, const char *name, char *out, size_t size)
{
    char key[64];
    const char *p, *end;
    snprintf(key, sizeof key, " %s=\"", name);
    p = strstr(xml, key);
    if (!p)
        return 0;
    p += strlen(key);
    end = strchr(p, '"');
    if (!end || (size_t)(end - p) >= size)
        return 0;
    memcpy(out, p, (size_t)(end - p));
    out[end - p] = '\0';
    return 1;
}

/* Runs argv (argv[0] looked for in PATH) with stdin from /dev/null and stdout and stderr into the
   open file `output`: a library writes nothing on its user's terminal. posix_spawn, not fork, in
   a process whose other threads may hold locks. The exit status, or -1 with errno. */
static int run_program(char *const argv[], int output)
{
    posix_spawn_file_actions_t actions;
    pid_t pid;
    int status, e;
    if ((e = posix_spawn_file_actions_init(&actions)) != 0)
        return errno = e, -1;
    if ((e = posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0)) == 0 &&
        (e = posix_spawn_file_actions_adddup2(&actions, output, 1)) == 0 &&
        (e = posix_spawn_file_actions_adddup2(&actions, output, 2)) == 0)
        e = posix_spawnp(&pid, argv[0], &actions, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    if (e != 0)
        return errno = e, -1;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return -1;
    /* killed by a signal: 128 + its number, as a shell says it */
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

/* What a program wrote into `output`, on one line: every run of blanks and line ends one blank
   (unzip wraps its sentences), at most size - 1 characters. */
static void read_output(int output, char *text, size_t size)
{
    ssize_t n;
    size_t i = 0;
    char c;
    int blank = 1;
    if (lseek(output, 0, SEEK_SET) != 0) {
        text[0] = '\0';
        return;
    }
    while (i + 1 < size && (n = read(output, &c, 1)) == 1) {
        int is_blank = c == ' ' || c == '\t' || c == '\n' || c == '\r';
        if (!is_blank)
            text[i++] = c;
        else if (!blank)
            text[i++] = ' ';
        blank = is_blank;
    }
    while (i > 0 && text[i - 1] == ' ')
        i--;
    text[i] = '\0';
}

static int remove_entry(const char *path, const struct stat *st, int type, struct FTW *ftw)
{
    (void)st, (void)type, (void)ftw;
    remove(path);
    return 0;           /* on with the rest: remove what can be removed */
}

/* The temporary directory and what it holds, children first, no link followed (nftw, not
   `rm -rf`: no child process, nothing on stderr). */
static void remove_tree(const char *dir)
{
    nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

/* errno's text (strerror_r: strerror's buffer may be shared by the threads) */
static const char *error_text(int e, char *text, size_t size)
{
    if (strerror_r(e, text, size) != 0)
        snprintf(text, size, "error %d", e);
    return text;
}

/* A .fmu file unpacked into a new temporary directory (NULL on failure, with why: unzip's own
   words, which go into the library's log line instead of onto the terminal). */
static char *unpack(const char *fmu, char *why, size_t size)
{
    char *dir = malloc(PATH_MAX), output[PATH_MAX], said[1024];
    const char *tmp = getenv("TMPDIR");
    char *argv[] = {"unzip", "-qq", "-o", (char *)fmu, "-d", dir, NULL};
    int out, status;
    if (!tmp || !*tmp)
        tmp = "/tmp";
    if (!dir) {
        snprintf(why, size, "out of memory");
        return NULL;
    }
    snprintf(dir, PATH_MAX, "%s/pmdfmu-XXXXXX", tmp);
    snprintf(output, sizeof output, "%s/pmdfmu-unzip-XXXXXX", tmp);
    if (!mkdtemp(dir)) {
        snprintf(why, size, "cannot make a directory in %s: %s", tmp, error_text(errno, said, sizeof said));
        free(dir);
        return NULL;
    }
    if ((out = mkstemp(output)) < 0) {
        snprintf(why, size, "cannot make a file in %s: %s", tmp, error_text(errno, said, sizeof said));
        remove_tree(dir);
        free(dir);
        return NULL;
    }
    unlink(output);                         /* the open file is all it needs */
    /* children other threads start from now on do not inherit it (one started between mkstemp and here
       may: mkostemp's O_CLOEXEC is not POSIX) */
    fcntl(out, F_SETFD, FD_CLOEXEC);
    status = run_program(argv, out);
    if (status < 0)
        snprintf(why, size, "cannot run unzip: %s", error_text(errno, said, sizeof said));
    else if (status > 0) {
        read_output(out, said, sizeof said);
        snprintf(why, size, "unzip exited with %d: %s", status, said[0] ? said : "(it said nothing)");
    }
    close(out);
    if (status != 0) {
        remove_tree(dir);
        free(dir);
        return NULL;
    }
    return dir;
}

static void free_device(PMDFMUDevice *d)
{
    PMDFMUDevice **p;
    pthread_mutex_lock(&open_devices_lock);
    for (p = &open_devices; *p; p = &(*p)->next)
        if (*p == d) {
            *p = d->next;
            break;
        }
    pthread_mutex_unlock(&open_devices_lock);
    if (d->line)
        PMDLineClose(d->line);
    if (d->instance) {
        if (d->initialized)     /* FMI 2 terminates an initialized instance; a failed one is only freed */
            d->terminate(d->instance);
        d->freeInstance(d->instance);
    }
    if (d->library)
        dlclose(d->library);
    if (d->unpacked) {
        remove_tree(d->unpacked);
        free(d->unpacked);
    }
    free(d);
}

/* A function of the FMU binary (POSIX: a dlsym result holds a function's address; ISO C has no
   conversion of an object pointer to a function pointer, so the bytes are copied). */
static void load(PMDFMUDevice *d, const char *name, void *function_pointer)
{
    void *p = dlsym(d->library, name);
    memcpy(function_pointer, &p, sizeof p);
}

/* The categories the log callback gets (PMDFMUOptions.logCategories); without a callback none,
   though the FMU's errors still come to the logger, for the transport's line. */
static PMDresult set_log_categories(PMDFMUDevice *d, fmi2SetDebugLoggingTYPE *setDebugLogging)
{
    static const char *const errorsAndWarnings[] = {"errors", "warnings", NULL};
    const char *const *categories = d->options.logCategories ? d->options.logCategories : errorsAndWarnings;
    size_t n = 0;
    fmi2Status status;
    while (categories[n])
        n++;
    /* FMI's SetDebugLogging reads 0 categories as all of them: an empty list is logging off */
    if (!d->options.log || n == 0)
        status = setDebugLogging(d->instance, fmi2False, 0, NULL);
    else
        status = setDebugLogging(d->instance, fmi2True, n, categories);
    return status > fmi2Warning ? fmi_failed(d, PMD_ERR_Driver, "fmi2SetDebugLogging") : PMD_ERR_OK;
}

static PMDresult open_device(PMDFMUDevice *d, const char *fmu)
{
    char dir[PATH_MAX], path[PATH_MAX + 512], guid[128], identifier[128], resources[PATH_MAX + 32];
    char *xml;
    struct stat st;
    char why[PATH_MAX + 1200];
    fmi2InstantiateTYPE *instantiate;
    fmi2SetDebugLoggingTYPE *setDebugLogging;

    if (!fmu || !*fmu) {
        log_text(d, "no FMU: set PMDFMUOptions.fmu or PMDFMU_FMU to the .fmu file or its unpacked directory");
        return PMD_ERR_OpeningPort;
    }
    if (stat(fmu, &st) != 0) {     /* named, but not there: say which name, not that none was given */
        snprintf(why, sizeof why, "cannot open the FMU %s: %s", fmu, error_text(errno, path, sizeof path));
        log_text(d, why);
        return PMD_ERR_OpeningPort;
    }
    if (!S_ISDIR(st.st_mode)) {
        char text[sizeof why + PATH_MAX + 32];
        d->unpacked = unpack(fmu, why, sizeof why);
        if (!d->unpacked) {
            snprintf(text, sizeof text, "cannot unpack the FMU %s: %s", fmu, why);
            log_text(d, text);
            return PMD_ERR_OpeningPort;
        }
        fmu = d->unpacked;
    }
    if (!realpath(fmu, dir)) {
        snprintf(why, sizeof why, "cannot resolve the FMU's path %s: %s", fmu, error_text(errno, path, sizeof path));
        log_text(d, why);
        return PMD_ERR_OpeningPort;
    }
    snprintf(path, sizeof path, "%s/modelDescription.xml", dir);
    xml = read_file(path);
    if (!xml || !attribute(xml, "guid", guid, sizeof guid) ||
        !attribute(xml, "modelIdentifier", identifier, sizeof identifier)) {
        free(xml);
        log_text(d, "no modelDescription.xml with a guid and a modelIdentifier in the FMU");
        return PMD_ERR_OpeningPort;
    }
    free(xml);
    snprintf(path, sizeof path, "%s/binaries/%s/%s.so", dir, PMD_FMI2_PLATFORM, identifier);
    d->library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!d->library) {
        log_text(d, dlerror());
        return PMD_ERR_OpeningPort;
    }
    load(d, "fmi2Instantiate", &instantiate);
    load(d, "fmi2FreeInstance", &d->freeInstance);
    load(d, "fmi2Terminate", &d->terminate);
    load(d, "fmi2DoStep", &d->doStep);
    load(d, "fmi2SetInteger", &d->setInteger);
    load(d, "fmi2GetInteger", &d->getInteger);
    load(d, "fmi2GetReal", &d->getReal);
    load(d, "fmi2GetBoolean", &d->getBoolean);
    load(d, "fmi2SetDebugLogging", &setDebugLogging);
    if (!instantiate || !d->freeInstance || !d->terminate || !d->doStep || !d->setInteger || !d->getInteger ||
        !d->getReal || !setDebugLogging) {
        log_text(d, "the FMU binary lacks an FMI 2 function");
        return PMD_ERR_OpeningPort;
    }
    snprintf(resources, sizeof resources, "file://%s/resources", dir);
    d->callbacks.logger = logger;
    d->callbacks.allocateMemory = calloc;
    d->callbacks.freeMemory = free;
    d->callbacks.componentEnvironment = d;
    d->instance = instantiate("pmd", fmi2CoSimulation, guid, resources, &d->callbacks, fmi2False,
                              d->options.log != NULL);
    if (!d->instance)
        return fmi_failed(d, PMD_ERR_OpeningPort, "fmi2Instantiate");
    return set_log_categories(d, setDebugLogging);
}

/* Sets the parameters and initializes at time 0. */
static PMDresult initialize(PMDFMUDevice *d)
{
    fmi2SetupExperimentTYPE *setup;
    fmi2EnterInitializationModeTYPE *enter;
    fmi2ExitInitializationModeTYPE *leave;
    fmi2SetRealTYPE *setReal;
    fmi2SetBooleanTYPE *setBoolean;
    fmi2SetStringTYPE *setString;
    const fmi2ValueReference cycleTime = PMD_FMU_VR_CYCLE_TIME, memorySize = PMD_FMU_VR_MEMORY_SIZE,
                             loopback = PMD_FMU_VR_LOOPBACK, script = PMD_FMU_VR_SCRIPT,
                             machineVr = PMD_FMU_VR_MACHINE;
    const fmi2Boolean loop = d->options.loopback ? fmi2True : fmi2False;
    const fmi2Integer size = d->options.memorySize;
    const fmi2String text = d->options.script;
    const fmi2String machine = d->options.machine ? d->options.machine : getenv("PMDFMU_MACHINE");
    load(d, "fmi2SetupExperiment", &setup);
    load(d, "fmi2EnterInitializationMode", &enter);
    load(d, "fmi2ExitInitializationMode", &leave);
    load(d, "fmi2SetReal", &setReal);
    load(d, "fmi2SetBoolean", &setBoolean);
    load(d, "fmi2SetString", &setString);
    if (!setup || !enter || !leave || !setReal || !setBoolean || !setString) {
        log_text(d, "the FMU binary lacks an FMI 2 function");
        return PMD_ERR_OpeningPort;
    }
    if (setup(d->instance, fmi2False, 0.0, 0.0, fmi2False, 0.0) > fmi2Warning)
        return fmi_failed(d, PMD_ERR_Driver, "fmi2SetupExperiment");
    if (d->options.cycleTime > 0 && setReal(d->instance, &cycleTime, 1, &d->options.cycleTime) > fmi2Warning)
        return fmi_failed(d, PMD_ERR_Driver, "fmi2SetReal of cycleTime");
    if (size > 0 && d->setInteger(d->instance, &memorySize, 1, &size) > fmi2Warning)
        return fmi_failed(d, PMD_ERR_Driver, "fmi2SetInteger of memorySize");
    if (setBoolean(d->instance, &loopback, 1, &loop) > fmi2Warning)
        return fmi_failed(d, PMD_ERR_Driver, "fmi2SetBoolean of loopback");
    if (text && setString(d->instance, &script, 1, &text) > fmi2Warning)
        return fmi_failed(d, PMD_ERR_Driver, "fmi2SetString of script");
    if (machine && *machine && setString(d->instance, &machineVr, 1, &machine) > fmi2Warning)
        return fmi_failed(d, PMD_ERR_Driver, "fmi2SetString of machine");
    if (enter(d->instance) > fmi2Warning)
        return fmi_failed(d, PMD_ERR_Driver, "fmi2EnterInitializationMode");
    if (leave(d->instance) > fmi2Warning) {
        /* a machine the environment names is the user's, not the program's: a program that sets no
           log callback would never say why it cannot open the chip */
        if (!d->options.machine && machine && *machine && !d->options.log && strstr(d->fmuError, "machine refused"))
            fprintf(stderr, "PMDFMU_MACHINE=%s: %s\n", machine, d->fmuError);
        return fmi_failed(d, PMD_ERR_Driver, "fmi2ExitInitializationMode");
    }
    d->initialized = 1;
    return PMD_ERR_OK;
}

PMDresult PMDSetupAxisInterface_FMU(PMDAxisHandle *axis_handle, PMDAxis axisNumber, const PMDFMUOptions *options)
{
    PMDFMUDevice *d;
    PMDresult r;
    const char *fmu;
    if (!axis_handle)
        return PMD_ERR_InvalidHandle;
    axis_handle->axis = axisNumber;
    axis_handle->transport_data = NULL;
    d = calloc(1, sizeof *d);
    if (!d)
        return PMD_ERR_OpeningPort;
    if (options)
        d->options = *options;
    else
        PMDFMUOptionsInit(&d->options);
    fmu = d->options.fmu ? d->options.fmu : getenv("PMDFMU_FMU");
#ifdef PMD_FMU_DEFAULT
    if (!fmu || !*fmu)
        fmu = PMD_FMU_DEFAULT;
#endif
#ifdef PMD_HAVE_HOSTTIME
    d->hostInterface = d->options.hostInterface ? *d->options.hostInterface : PMDHostInterfaceDefault();
    d->commandsTakeTime = d->hostInterface.kind != PMDHostNone;
    {
        uint32_t value, min, max;
        const char *refused = PMDHostInterfaceRefused(&d->hostInterface, &value, &min, &max);
        if (refused) {
            char text[160];
            snprintf(text, sizeof text, "host interface %s: %s = %lu is not in %lu .. %lu: no chip opened",
                     PMDHostInterfaceName(d->hostInterface.kind) ? PMDHostInterfaceName(d->hostInterface.kind) : "?",
                     refused, (unsigned long)value, (unsigned long)min, (unsigned long)max);
            log_text(d, text);
            free_device(d);
            return PMD_ERR_OpeningPort;
        }
    }
#endif
    d->options.hostInterface = NULL;        /* copied: the caller's may go */
    d->lastOpcode = -1;
    {
        /* the user's guard against a program that waits for ever: a value that is no whole number
           1 .. 2^64-1 opens no chip, rather than let the program run without it ("200k" was ignored,
           "-5" read by strtoull as 2^64 - 5, a number past 2^64 as 2^64 - 1) */
        const char *max = getenv("PMDFMU_MAX_CYCLES");
        char *end = NULL;
        if (max && *max) {
            errno = 0;
            d->maxCycles = max[0] >= '0' && max[0] <= '9' ? strtoull(max, &end, 10) : 0;
            if (!end || *end != '\0' || errno == ERANGE || d->maxCycles == 0) {
                fprintf(stderr, "PMDFMU_MAX_CYCLES=%s is not a whole number of cycles 1 .. 2^64-1: no chip opened\n",
                        max);
                free_device(d);
                return PMD_ERR_OpeningPort;
            }
        }
    }
    d->self.axis = 0;
    d->self.transport_data = d;
    r = open_device(d, fmu);
    if (r == PMD_ERR_OK)
        r = initialize(d);
    if (r != PMD_ERR_OK) {
        free_device(d);
        return r;
    }
    d->handles = 1;
    d->opener = pthread_self();
    pthread_mutex_lock(&open_devices_lock);
    d->next = open_devices;
    open_devices = d;
    pthread_mutex_unlock(&open_devices_lock);
    axis_handle->transport_data = d;
    return PMD_ERR_OK;
}

PMDresult PMDCopyAxisInterface(PMDAxisHandle *dest_handle, const PMDAxisHandle *src_handle, PMDAxis axis)
{
    PMDFMUDevice *d;
    if (!dest_handle || !src_handle)
        return PMD_ERR_InvalidHandle;
    d = src_handle->transport_data;
    if (!d)
        return PMD_ERR_InterfaceNotInitialized;
    d->handles++;
    dest_handle->axis = axis;
    dest_handle->transport_data = d;
    return PMD_ERR_OK;
}

PMDresult PMDCloseAxisInterface(PMDAxisHandle *axis_handle)
{
    PMDFMUDevice *d;
    if (!axis_handle)
        return PMD_ERR_InvalidHandle;
    d = axis_handle->transport_data;
    if (!d)
        return PMD_ERR_InterfaceNotInitialized;
    axis_handle->transport_data = NULL;
    if (--d->handles == 0)
        free_device(d);
    return PMD_ERR_OK;
}

static PMDresult device_of(PMDAxisInterface axis_intf, PMDFMUDevice **d)
{
    if (!axis_intf)
        return PMD_ERR_InvalidHandle;
    *d = axis_intf->transport_data;
    return *d ? PMD_ERR_OK : PMD_ERR_InterfaceNotInitialized;
}

/* ---- a chip over a line (PMDline.h) ---- */

static uint64_t monotonic_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (uint64_t)t.tv_sec * 1000000000u + (uint64_t)t.tv_nsec;
}

static void sleep_ns(uint64_t ns)
{
    struct timespec t;
    t.tv_sec = (time_t)(ns / 1000000000u);
    t.tv_nsec = (long)(ns % 1000000000u);
    while (nanosleep(&t, &t) != 0 && errno == EINTR)
        ;
}

/* What only the twin has (its FMU's variables, cycles, the dual-port memory): over a line without
   the twin's monitor (PMDFMU_MONITOR) the chip takes commands only */
static PMDresult not_over_a_line(PMDFMUDevice *d, const char *what)
{
    char text[256];
    snprintf(text, sizeof text, "%s needs the twin in-process, or its monitor (PMDFMU_MONITOR): over "
             "PMDFMU_DEVICE's line the chip takes commands only", what);
    log_text(d, text);
    return PMD_ERR_NotSupported;
}

/* One request to the twin's monitor (PMDline.h); a refusal's reason goes to the transport's log. */
static PMDresult monitor(PMDFMUDevice *d, const char *request, char *value, size_t size)
{
    char text[2300];
    PMDresult r = PMDLineMonitor(d->line, request, value, size);
    if (r != PMD_ERR_OK) {
        snprintf(text, sizeof text, "PMDFMU_MONITOR: %.40s: %s", request,
                 r == PMD_ERR_Driver ? value : "the monitor went or answered no line");
        log_text(d, text);
    }
    return r;
}

PMDresult PMDFMU_SetupAxisInterface_Line(PMDAxisHandle *axis_handle, PMDAxis axisNumber, const char *device,
                                         PMDuint32 baud, const PMDFMUOptions *options)
{
    return PMDFMU_SetupAxisInterface_LineAt(axis_handle, axisNumber, device, baud, 0, options);
}

PMDresult PMDFMU_SetupAxisInterface_LineAt(PMDAxisHandle *axis_handle, PMDAxis axisNumber, const char *device,
                                           PMDuint32 baud, unsigned address, const PMDFMUOptions *options)
{
    PMDFMUDevice *d;
    char why[512];
    PMDresult r;
    if (!axis_handle)
        return PMD_ERR_InvalidHandle;
    axis_handle->axis = axisNumber;
    axis_handle->transport_data = NULL;
    d = calloc(1, sizeof *d);
    if (!d)
        return PMD_ERR_OpeningPort;
    if (options)
        d->options = *options;
    d->options.hostInterface = NULL;
    d->lastOpcode = -1;
    r = PMDLineOpen(&d->line, device, baud, address, why, sizeof why);
    if (r != PMD_ERR_OK) {
        char text[600];
        snprintf(text, sizeof text, "PMDFMU_DEVICE=%s: %s", device, why);
        log_text(d, text);
        free(d);
        return r;
    }
    {
        const char *watch = getenv("PMDFMU_MONITOR");      /* pmdfmu serve --monitor's endpoint */
        if (watch && *watch && (r = PMDLineMonitorOpen(d->line, watch, why, sizeof why)) != PMD_ERR_OK) {
            char text[600];
            snprintf(text, sizeof text, "PMDFMU_MONITOR=%s: %s", watch, why);
            log_text(d, text);
            PMDLineClose(d->line);
            free(d);
            return r;
        }
    }
    if (d->options.cycle)
        log_text(d, "the options' cycle callback is not called over a line: the chip's cycles run in the "
                    "server (pmdfmu serve --record records them)");
    d->openedNs = monotonic_ns();
    d->handles = 1;
    d->opener = pthread_self();
    d->self.transport_data = d;
    pthread_mutex_lock(&open_devices_lock);
    d->next = open_devices;
    open_devices = d;
    pthread_mutex_unlock(&open_devices_lock);
    axis_handle->transport_data = d;
    return PMD_ERR_OK;
}

/* ---- the host port ---- */

PMDresult PMDFMU_Command(PMDAxisInterface axis_intf, PMDuint8 opcode, int chipWide, const PMDuint16 *args,
                         int nargs, PMDuint16 *reply, int nreply)
{
    PMDFMUDevice *d;
    fmi2ValueReference vrs[PMD_FMU_BATCH_WORDS + 4];
    fmi2Integer values[PMD_FMU_BATCH_WORDS + 4];
    int i, n = 1 + nargs;
    PMDresult r = device_of(axis_intf, &d);
    if (r != PMD_ERR_OK)
        return r;
    if (axis_intf->axis > 0xFF || nargs < 0 || n > PMD_FMU_BATCH_WORDS || nreply < 0 ||
        nreply > PMD_FMU_BATCH_WORDS)
        return PMD_ERR_InvalidHandle;
    if (opcode == d->lastOpcode && (int)axis_intf->axis == d->lastAxis)
        d->lastRepeats++;
    else
        d->lastOpcode = opcode, d->lastAxis = (int)axis_intf->axis, d->lastRepeats = 1;
    if (d->line)
        return PMDLineCommand(d->line, (PMDuint16)(opcode | (chipWide ? 0 : axis_intf->axis << 8)), args, nargs,
                              reply, nreply);
    /* the instruction word: opcode in bits 0-7, the axis above it (pmd-reference 1.1) */
    values[0] = opcode | (chipWide ? 0 : axis_intf->axis << 8);
    for (i = 0; i < nargs; i++)
        values[1 + i] = args[i];
    for (i = 0; i < n; i++)
        vrs[i] = PMD_FMU_VR_HOST_WORD + (fmi2ValueReference)i;
    d->strobe = (d->strobe + 1) & 0x7FFFFFFF;        /* a new value: the batch executes */
    vrs[n] = PMD_FMU_VR_HOST_WORD_COUNT, values[n] = n;
    vrs[n + 1] = PMD_FMU_VR_HOST_STROBE, values[n + 1] = d->strobe;

    /* the request crosses the host interface; the cycles due meanwhile run before it executes */
    if (d->commandsTakeTime) {
        d->hostNs += request_ns(d, n);
        if ((r = run_due(d)) != PMD_ERR_OK)
            return r;
    }
    if (d->setInteger(d->instance, vrs, (size_t)n + 2, values) > fmi2Warning)
        return fmi_failed(d, PMD_ERR_Driver, "fmi2SetInteger of the host port");
    /* a get executes the batch */
    vrs[0] = PMD_FMU_VR_HOST_ACK, vrs[1] = PMD_FMU_VR_HOST_ERROR, vrs[2] = PMD_FMU_VR_HOST_REPLY_COUNT;
    for (i = 0; i < nreply; i++)
        vrs[3 + i] = PMD_FMU_VR_HOST_REPLY + (fmi2ValueReference)i;
    if (d->getInteger(d->instance, vrs, (size_t)nreply + 3, values) > fmi2Warning)
        return fmi_failed(d, PMD_ERR_Driver, "fmi2GetInteger of the host port");
    if (values[0] != d->strobe) {
        log_text(d, "host.ack is not the strobe: the FMU did not execute the command");
        return PMD_ERR_NotResponding;
    }
    if (d->commandsTakeTime)
        d->hostNs += reply_ns(d, values[1] ? 0 : nreply, values[1] != 0);
    if (values[1] != 0)
        return (PMDresult)values[1];
    if (values[2] != nreply) {
        log_text(d, "the chip replied with another number of words than the command table says");
        return PMD_ERR_NotResponding;
    }
    for (i = 0; i < nreply; i++)
        reply[i] = (PMDuint16)values[3 + i];
    return PMD_ERR_OK;
}

/* ---- the dual-port memory ---- */

PMDresult PMDFMU_WriteDPRAM(void *const *transport, PMDuint32 offset, PMDuint32 count, const PMDuint32 *data)
{
    PMDFMUDevice *d;
    fmi2ValueReference vrs[PMD_FMU_MEMORY_WORDS + 3];
    fmi2Integer values[PMD_FMU_MEMORY_WORDS + 3];
    const fmi2ValueReference sizeVr = PMD_FMU_VR_MEMORY_SIZE, ackVr = PMD_FMU_VR_HOST_ACK;
    fmi2Integer size, ack;
    PMDuint32 done;
    if (!transport || !*transport)
        return PMD_ERR_InterfaceNotInitialized;
    d = *transport;
    if (d->line && !PMDLineHasMonitor(d->line))
        return not_over_a_line(d, "the dual-port memory");
    if (d->line) {
        PMDint32 words;
        PMDresult r = PMDFMU_GetInteger(&d->self, "memorySize", &words);
        if (r != PMD_ERR_OK)
            return r;
        size = (fmi2Integer)words;
    } else if (d->getInteger(d->instance, &sizeVr, 1, &size) > fmi2Warning) {
        return fmi_failed(d, PMD_ERR_Driver, "fmi2GetInteger of memorySize");
    }
    if (offset > (PMDuint32)size || count > (PMDuint32)size - offset || (count && !data))
        return PMD_ERR_InvalidAddress;
    /* a PMDuint32 is a long here (the vendor's type): a word wider than 32 bits is refused, none written */
    for (done = 0; done < count; done++)
        if (!PMDFMU_FitsU32((unsigned long long)data[done]))
            return PMD_ERR_ParameterOutOfRange;
    for (done = 0; d->line && done < count;) {     /* over the monitor: a write request per block */
        char request[32 + 11 * PMD_FMU_MEMORY_WORDS], value[PMD_LINE_MONITOR_REPLY];
        PMDuint32 i, n = count - done < PMD_FMU_MEMORY_WORDS ? count - done : PMD_FMU_MEMORY_WORDS;
        size_t at = (size_t)snprintf(request, sizeof request, "write %lu", (unsigned long)(offset + done));
        PMDresult r;
        for (i = 0; i < n; i++)
            at += (size_t)snprintf(request + at, sizeof request - at, " %lu",
                                   (unsigned long)(PMDuint32)PMDFMU_Int32(data[done + i]));
        if ((r = monitor(d, request, value, sizeof value)) != PMD_ERR_OK)
            return r;
        done += n;
    }
    for (done = 0; !d->line && done < count;) {
        PMDuint32 i, n = count - done < PMD_FMU_MEMORY_WORDS ? count - done : PMD_FMU_MEMORY_WORDS;
        for (i = 0; i < n; i++) {
            vrs[i] = PMD_FMU_VR_MEMORY_DATA + i;
            values[i] = PMDFMU_Int32(data[done + i]);     /* FMI 2 Integer: the same 32 bits */
        }
        d->memoryStrobe = (d->memoryStrobe + 1) & 0x7FFFFFFF;
        vrs[n] = PMD_FMU_VR_MEMORY_ADDRESS, values[n] = PMDFMU_Int32(offset + done);
        vrs[n + 1] = PMD_FMU_VR_MEMORY_COUNT, values[n + 1] = (fmi2Integer)n;
        vrs[n + 2] = PMD_FMU_VR_MEMORY_STROBE, values[n + 2] = d->memoryStrobe;
        if (d->setInteger(d->instance, vrs, n + 3, values) > fmi2Warning ||
            d->getInteger(d->instance, &ackVr, 1, &ack) > fmi2Warning)     /* a get executes the write */
            return fmi_failed(d, PMD_ERR_Driver, "the dual-port write (fmi2SetInteger of memory.*)");
        done += n;
    }
    return PMD_ERR_OK;
}

/* ---- time ---- */

/* The host's sleep over a line: the line's time passes in the server (its monitor's wait); without a
   monitor, or under --realtime (its monitor refuses), the host's own clock, the chip keeping its time. */
static void line_wait(PMDFMUDevice *d, uint64_t ns)
{
    char request[40], value[PMD_LINE_MONITOR_REPLY];
    snprintf(request, sizeof request, "wait %llu", (unsigned long long)ns);
    if (!PMDLineHasMonitor(d->line) || PMDLineMonitor(d->line, request, value, sizeof value) != PMD_ERR_OK)
        sleep_ns(ns);
}

PMDresult PMDFMU_Wait(PMDAxisInterface axis_intf, PMDuint32 microseconds)
{
    PMDFMUDevice *d;
    PMDresult r = device_of(axis_intf, &d);
    if (r != PMD_ERR_OK)
        return r;
    if (d->line) {
        line_wait(d, (uint64_t)microseconds * 1000u);
        return PMD_ERR_OK;
    }
    d->hostNs += (uint64_t)microseconds * 1000u;
    return run_due(d);
}

/* The first chip from d on (in the list) that the calling thread opened; under the lock. */
static PMDFMUDevice *opened_here(PMDFMUDevice *d)
{
    const pthread_t self = pthread_self();
    while (d && !pthread_equal(d->opener, self))
        d = d->next;
    return d;
}

/* The calling thread's chips, each stepped outside the lock (other threads open and close theirs
   meanwhile); a chip stays in the list while it runs, since only its own thread closes it. */
void PMDTaskWait(PMDuint32 milliseconds)
{
    PMDFMUDevice *d;
    int slept = 0;
    pthread_mutex_lock(&open_devices_lock);
    d = opened_here(open_devices);
    pthread_mutex_unlock(&open_devices_lock);
    while (d) {
        if (d->line && !slept) {       /* the chips on a line share its time: the host sleeps once */
            line_wait(d, (uint64_t)milliseconds * 1000000u);
            slept = 1;
        } else if (!d->line) {
            d->hostNs += (uint64_t)milliseconds * 1000000u;
            run_due(d);
        }
        pthread_mutex_lock(&open_devices_lock);
        d = opened_here(d->next);
        pthread_mutex_unlock(&open_devices_lock);
    }
}

PMDresult PMDFMU_RunCycles(PMDAxisInterface axis_intf, PMDuint32 cycles)
{
    PMDFMUDevice *d;
    Grid g = {0, 0, 0};
    PMDuint32 i;
    PMDresult r = device_of(axis_intf, &d);
    if (r != PMD_ERR_OK)
        return r;
    if (d->line && PMDLineHasMonitor(d->line)) {
        char request[32], value[PMD_LINE_MONITOR_REPLY];
        snprintf(request, sizeof request, "run %lu", (unsigned long)cycles);
        return monitor(d, request, value, sizeof value);
    }
    if (d->line)
        return not_over_a_line(d, "PMDFMU_RunCycles");
    for (i = 0; i < cycles; i += d->options.cycle ? 1 : cycles) {
        if ((r = read_grid(d, &g)) != PMD_ERR_OK || (r = step(d, &g, d->options.cycle ? 1 : cycles)) != PMD_ERR_OK)
            return r;
        if (d->options.cycle)
            d->options.cycle(d->options.cycleContext, &d->self);
    }
    /* the host clock moves to the time of the last cycle run if it was behind */
    if (cycles && (r = read_grid(d, &g)) != PMD_ERR_OK)
        return r;
    if (cycles && to_ns(g.next) - to_ns(g.cycle) > d->hostNs)
        d->hostNs = to_ns(g.next) - to_ns(g.cycle);
    return PMD_ERR_OK;
}

PMDresult PMDFMU_GetHostTime(PMDAxisInterface axis_intf, uint64_t *nanoseconds)
{
    PMDFMUDevice *d;
    PMDresult r = device_of(axis_intf, &d);
    if (r == PMD_ERR_OK && d->line && PMDLineHasMonitor(d->line)) {     /* the line's clock */
        char value[PMD_LINE_MONITOR_REPLY];
        if ((r = monitor(d, "time", value, sizeof value)) == PMD_ERR_OK && nanoseconds)
            *nanoseconds = strtoull(value, NULL, 10);
    } else if (r == PMD_ERR_OK && nanoseconds) {
        *nanoseconds = d->line ? monotonic_ns() - d->openedNs : d->hostNs;
    }
    return r;
}

static const PMDFMUVariable *variable(const char *name)
{
    int i;
    for (i = 0; name && i < PMD_FMU_VARIABLE_COUNT; i++)
        if (strcmp(PMDFMU_variables[i].name, name) == 0)
            return &PMDFMU_variables[i];
    return NULL;
}

/* What PMDFMU_GetInteger and PMDFMU_GetReal share: the device, the variable, of one of TYPES; over a
 * line, the monitor's reply to "get NAME" in text (PMD_LINE_MONITOR_REPLY bytes). */
static PMDresult get_variable(PMDAxisInterface axis_intf, const char *name, const char *types, const char *function,
                              PMDFMUDevice **d, const PMDFMUVariable **v, char *text)
{
    char request[96];
    PMDresult r = device_of(axis_intf, d);
    *v = variable(name);
    if (r != PMD_ERR_OK)
        return r;
    if ((*d)->line && !PMDLineHasMonitor((*d)->line))
        return not_over_a_line(*d, function);
    if (!*v || !strchr(types, (*v)->type))
        return PMD_ERR_InvalidAddress;
    if (!(*d)->line)
        return PMD_ERR_OK;
    snprintf(request, sizeof request, "get %s", (*v)->name);
    return monitor(*d, request, text, PMD_LINE_MONITOR_REPLY);
}

PMDresult PMDFMU_GetInteger(PMDAxisInterface axis_intf, const char *name, PMDint32 *value)
{
    PMDFMUDevice *d;
    const PMDFMUVariable *v;
    char text[PMD_LINE_MONITOR_REPLY];
    fmi2Integer x;
    PMDresult r = get_variable(axis_intf, name, "IB", "PMDFMU_GetInteger", &d, &v, text);
    if (r != PMD_ERR_OK)
        return r;
    if (d->line) {
        x = (fmi2Integer)strtol(text, NULL, 10);
    } else if (v->type == 'B') {
        fmi2Boolean b;
        if (!d->getBoolean || d->getBoolean(d->instance, &v->vr, 1, &b) > fmi2Warning)
            return fmi_failed(d, PMD_ERR_Driver, "fmi2GetBoolean");
        x = b ? 1 : 0;
    } else if (d->getInteger(d->instance, &v->vr, 1, &x) > fmi2Warning) {
        return fmi_failed(d, PMD_ERR_Driver, "fmi2GetInteger");
    }
    if (value)
        *value = x;
    return PMD_ERR_OK;
}

PMDresult PMDFMU_GetReal(PMDAxisInterface axis_intf, const char *name, double *value)
{
    PMDFMUDevice *d;
    const PMDFMUVariable *v;
    char text[PMD_LINE_MONITOR_REPLY];
    fmi2Real x;
    PMDresult r = get_variable(axis_intf, name, "R", "PMDFMU_GetReal", &d, &v, text);
    if (r != PMD_ERR_OK)
        return r;
    if (d->line)
        x = strtod(text, NULL);
    else if (d->getReal(d->instance, &v->vr, 1, &x) > fmi2Warning)
        return fmi_failed(d, PMD_ERR_Driver, "fmi2GetReal");
    if (value)
        *value = x;
    return PMD_ERR_OK;
}
