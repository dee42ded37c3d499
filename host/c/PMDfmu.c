/* The C-Motion library's FMU transport (PMDfmu.h): loads the FMI 2 binary of the
   PMDMotionProcessor FMU with dlopen and drives it as a co-simulation master does. */
#define _XOPEN_SOURCE 700     /* realpath, mkdtemp */
#include <dlfcn.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fmi2FunctionTypes.h"
#include "c-motion.h"
#include "PMDfmu_ports.h"
#ifdef PMD_HAVE_HOSTTIME
#include "PMDhosttime.h"
#endif

#ifndef PMD_FMI2_PLATFORM
#define PMD_FMI2_PLATFORM "linux64"
#endif

/* One chip: an FMU instance and the host's side of its ports. Every handle of the chip points here. */
typedef struct PMDFMUDevice {
    struct PMDFMUDevice *next;      /* the open chips, for PMDTaskWait */
    int handles;                    /* handles that use it; freed with the last */
    void *library;
    fmi2Component instance;
    char *unpacked;                 /* the temporary directory a .fmu file was unpacked into, or NULL */
    PMDFMUOptions options;
    PMDAxisHandle self;             /* the handle the cycle callback gets */
    fmi2Integer strobe;             /* the last host.strobe value set */
    fmi2Integer memoryStrobe;       /* the last memory.strobe value set */
    uint64_t hostNs;                /* the host clock: ns since the chip's time 0 */
    int commandsTakeTime;           /* 0 for the host interface `none`: commands run no cycle */
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
    char text[2048];
    va_list ap;
    (void)name;
    if (!d || !d->options.log)
        return;
    va_start(ap, message);              /* the FMU escapes '%' as "%%" and passes no arguments */
    vsnprintf(text, sizeof text, message, ap);
    va_end(ap);
    d->options.log(d->options.logContext, category ? category : "", (int)status, text);
}

static void log_text(PMDFMUDevice *d, const char *text)
{
    if (d->options.log)
        d->options.log(d->options.logContext, "transport", fmi2Error, text);
}

/* ---- the time grid: the FMU's own outputs (time, nextCycleTime, activeCycleTime) ---- */

typedef struct {
    double now, next, cycle;    /* the last communication point, the next cycle's time, the cycle time (s) */
} Grid;

static int read_grid(PMDFMUDevice *d, Grid *g)
{
    const fmi2ValueReference vrs[3] = {PMD_FMU_VR_TIME, PMD_FMU_VR_NEXT_CYCLE_TIME, PMD_FMU_VR_ACTIVE_CYCLE_TIME};
    fmi2Real v[3];
    if (d->getReal(d->instance, vrs, 3, v) > fmi2Warning)
        return 0;
    g->now = v[0], g->next = v[1], g->cycle = v[2];
    return 1;
}

/* A grid time in whole ns: the grid's times are whole microseconds (the sample time register). */
static uint64_t to_ns(double seconds)
{
    return seconds <= 0 ? 0 : (uint64_t)llround(seconds * 1e9);
}

/* One doStep that runs the next `cycles` cycles of the grid (python/pmdfmu/chip.py: Chip._step). */
static PMDresult step(PMDFMUDevice *d, const Grid *g, uint64_t cycles)
{
    if (d->doStep(d->instance, g->now, (g->next - g->now) + (double)cycles * g->cycle, fmi2True) > fmi2Warning) {
        log_text(d, "fmi2DoStep failed");
        return PMD_ERR_Driver;
    }
    return PMD_ERR_OK;
}

/* Runs every cycle whose grid time is at or before the host clock. */
static PMDresult run_due(PMDFMUDevice *d)
{
    for (;;) {
        Grid g;
        uint64_t next, cycle, due;
        PMDresult r;
        if (!read_grid(d, &g))
            return PMD_ERR_Driver;
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

static int run_program(char *const argv[])
{
    int status;
    pid_t pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0) {
        execvp(argv[0], argv);
        _exit(127);
    }
    if (waitpid(pid, &status, 0) < 0)
        return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static void remove_tree(const char *dir)
{
    char *argv[] = {"rm", "-rf", (char *)dir, NULL};
    run_program(argv);
}

/* A .fmu file unpacked into a new temporary directory (NULL on failure). */
static char *unpack(const char *fmu)
{
    char *dir = malloc(PATH_MAX);
    const char *tmp = getenv("TMPDIR");
    char *argv[] = {"unzip", "-qq", "-o", (char *)fmu, "-d", dir, NULL};
    if (!dir)
        return NULL;
    snprintf(dir, PATH_MAX, "%s/pmdfmu-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(dir)) {
        free(dir);
        return NULL;
    }
    if (run_program(argv) != 0) {
        remove_tree(dir);
        free(dir);
        return NULL;
    }
    return dir;
}

static void free_device(PMDFMUDevice *d)
{
    PMDFMUDevice **p;
    for (p = &open_devices; *p; p = &(*p)->next)
        if (*p == d) {
            *p = d->next;
            break;
        }
    if (d->instance) {
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

static PMDresult open_device(PMDFMUDevice *d, const char *fmu)
{
    char dir[PATH_MAX], path[PATH_MAX + 512], guid[128], identifier[128], resources[PATH_MAX + 32];
    char *xml;
    struct stat st;
    fmi2InstantiateTYPE *instantiate;
    static fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};

    if (!fmu || stat(fmu, &st) != 0) {
        log_text(d, "no FMU: set PMDFMUOptions.fmu or PMDFMU_FMU to the .fmu file or its unpacked directory");
        return PMD_ERR_OpeningPort;
    }
    if (!S_ISDIR(st.st_mode)) {
        d->unpacked = unpack(fmu);
        if (!d->unpacked) {
            log_text(d, "cannot unpack the FMU (unzip)");
            return PMD_ERR_OpeningPort;
        }
        fmu = d->unpacked;
    }
    if (!realpath(fmu, dir))
        return PMD_ERR_OpeningPort;
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
    if (!instantiate || !d->freeInstance || !d->terminate || !d->doStep || !d->setInteger || !d->getInteger ||
        !d->getReal) {
        log_text(d, "the FMU binary lacks an FMI 2 function");
        return PMD_ERR_OpeningPort;
    }
    snprintf(resources, sizeof resources, "file://%s/resources", dir);
    d->instance = instantiate("pmd", fmi2CoSimulation, guid, resources, &callbacks, fmi2False,
                              d->options.log != NULL);
    if (!d->instance) {
        log_text(d, "fmi2Instantiate failed");
        return PMD_ERR_OpeningPort;
    }
    return PMD_ERR_OK;
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
                             loopback = PMD_FMU_VR_LOOPBACK, script = PMD_FMU_VR_SCRIPT;
    const fmi2Boolean loop = d->options.loopback ? fmi2True : fmi2False;
    const fmi2Integer size = d->options.memorySize;
    const fmi2String text = d->options.script;
    load(d, "fmi2SetupExperiment", &setup);
    load(d, "fmi2EnterInitializationMode", &enter);
    load(d, "fmi2ExitInitializationMode", &leave);
    load(d, "fmi2SetReal", &setReal);
    load(d, "fmi2SetBoolean", &setBoolean);
    load(d, "fmi2SetString", &setString);
    if (!setup || !enter || !leave || !setReal || !setBoolean || !setString)
        return PMD_ERR_OpeningPort;
    if (setup(d->instance, fmi2False, 0.0, 0.0, fmi2False, 0.0) > fmi2Warning ||
        (d->options.cycleTime > 0 && setReal(d->instance, &cycleTime, 1, &d->options.cycleTime) > fmi2Warning) ||
        (size > 0 && d->setInteger(d->instance, &memorySize, 1, &size) > fmi2Warning) ||
        setBoolean(d->instance, &loopback, 1, &loop) > fmi2Warning ||
        (text && setString(d->instance, &script, 1, &text) > fmi2Warning) ||
        enter(d->instance) > fmi2Warning || leave(d->instance) > fmi2Warning) {
        log_text(d, "the FMU refused a parameter or its initialization");
        return PMD_ERR_Driver;
    }
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
#endif
    d->options.hostInterface = NULL;        /* copied: the caller's may go */
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
    d->next = open_devices;
    open_devices = d;
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
    if (d->setInteger(d->instance, vrs, (size_t)n + 2, values) > fmi2Warning) {
        log_text(d, "fmi2SetInteger of the host port failed");
        return PMD_ERR_Driver;
    }
    /* a get executes the batch */
    vrs[0] = PMD_FMU_VR_HOST_ACK, vrs[1] = PMD_FMU_VR_HOST_ERROR, vrs[2] = PMD_FMU_VR_HOST_REPLY_COUNT;
    for (i = 0; i < nreply; i++)
        vrs[3 + i] = PMD_FMU_VR_HOST_REPLY + (fmi2ValueReference)i;
    if (d->getInteger(d->instance, vrs, (size_t)nreply + 3, values) > fmi2Warning) {
        log_text(d, "fmi2GetInteger of the host port failed");
        return PMD_ERR_Driver;
    }
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
    if (d->getInteger(d->instance, &sizeVr, 1, &size) > fmi2Warning)
        return PMD_ERR_Driver;
    if (offset > (PMDuint32)size || count > (PMDuint32)size - offset || (count && !data))
        return PMD_ERR_InvalidAddress;
    for (done = 0; done < count;) {
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
            d->getInteger(d->instance, &ackVr, 1, &ack) > fmi2Warning) {     /* a get executes the write */
            log_text(d, "the FMU refused a dual-port write");
            return PMD_ERR_Driver;
        }
        done += n;
    }
    return PMD_ERR_OK;
}

/* ---- time ---- */

PMDresult PMDFMU_Wait(PMDAxisInterface axis_intf, PMDuint32 microseconds)
{
    PMDFMUDevice *d;
    PMDresult r = device_of(axis_intf, &d);
    if (r != PMD_ERR_OK)
        return r;
    d->hostNs += (uint64_t)microseconds * 1000u;
    return run_due(d);
}

void PMDTaskWait(PMDuint32 milliseconds)
{
    PMDFMUDevice *d;
    for (d = open_devices; d; d = d->next) {
        d->hostNs += (uint64_t)milliseconds * 1000000u;
        run_due(d);
    }
}

PMDresult PMDFMU_RunCycles(PMDAxisInterface axis_intf, PMDuint32 cycles)
{
    PMDFMUDevice *d;
    Grid g;
    PMDuint32 i;
    PMDresult r = device_of(axis_intf, &d);
    if (r != PMD_ERR_OK)
        return r;
    for (i = 0; i < cycles; i += d->options.cycle ? 1 : cycles) {
        if (!read_grid(d, &g))
            return PMD_ERR_Driver;
        if ((r = step(d, &g, d->options.cycle ? 1 : cycles)) != PMD_ERR_OK)
            return r;
        if (d->options.cycle)
            d->options.cycle(d->options.cycleContext, &d->self);
    }
    /* the host clock moves to the time of the last cycle run if it was behind */
    if (cycles && read_grid(d, &g) && to_ns(g.next) - to_ns(g.cycle) > d->hostNs)
        d->hostNs = to_ns(g.next) - to_ns(g.cycle);
    return PMD_ERR_OK;
}

PMDresult PMDFMU_GetHostTime(PMDAxisInterface axis_intf, uint64_t *nanoseconds)
{
    PMDFMUDevice *d;
    PMDresult r = device_of(axis_intf, &d);
    if (r == PMD_ERR_OK && nanoseconds)
        *nanoseconds = d->hostNs;
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

PMDresult PMDFMU_GetInteger(PMDAxisInterface axis_intf, const char *name, PMDint32 *value)
{
    PMDFMUDevice *d;
    const PMDFMUVariable *v = variable(name);
    fmi2Integer x;
    PMDresult r = device_of(axis_intf, &d);
    if (r != PMD_ERR_OK)
        return r;
    if (!v || (v->type != 'I' && v->type != 'B'))
        return PMD_ERR_InvalidAddress;
    if (v->type == 'B') {
        fmi2Boolean b;
        if (!d->getBoolean || d->getBoolean(d->instance, &v->vr, 1, &b) > fmi2Warning)
            return PMD_ERR_Driver;
        x = b ? 1 : 0;
    } else if (d->getInteger(d->instance, &v->vr, 1, &x) > fmi2Warning) {
        return PMD_ERR_Driver;
    }
    if (value)
        *value = x;
    return PMD_ERR_OK;
}

PMDresult PMDFMU_GetReal(PMDAxisInterface axis_intf, const char *name, double *value)
{
    PMDFMUDevice *d;
    const PMDFMUVariable *v = variable(name);
    fmi2Real x;
    PMDresult r = device_of(axis_intf, &d);
    if (r != PMD_ERR_OK)
        return r;
    if (!v || v->type != 'R')
        return PMD_ERR_InvalidAddress;
    if (d->getReal(d->instance, &v->vr, 1, &x) > fmi2Warning)
        return PMD_ERR_Driver;
    if (value)
        *value = x;
    return PMD_ERR_OK;
}
