/* The FMU instance over the chip core: variables, ports and the time grid
 * (CONTRACT 2.1, 2.2). */
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "instance.h"

const char *const pmd_log_category_names[PMD_LOG_CATEGORY_COUNT] = {
    "errors", "warnings", "commands", "buffers", "segments", "events"};

#define DEFAULT_CYCLE_TIME 1e-4
#define DEFAULT_MEMORY_SIZE 0x4000     /* seed 000, 1.1: memory_size = 0x4000 (16Kx32) */

void pmd_instance_log(const PmdInstance *inst, PmdStatus status, PmdLogCategory category, const char *format, ...)
{
    char message[1024];
    va_list args;
    /* errors are always logged; the rest as SetDebugLogging says */
    if (!inst->logger || (status < PMD_ERROR && !(inst->loggingOn && (inst->categories & (1u << category)))))
        return;
    va_start(args, format);
    vsnprintf(message, sizeof message, format, args);
    va_end(args);
    inst->logger(inst->environment, inst->instanceName, status, pmd_log_category_names[category], message);
}

/* The chip formats a message only when its category is enabled (chip.logMask).
 * A refused command is the chip's answer, not an FMU failure: it goes out
 * under "errors" with status Warning. */
static void chip_logger(void *context, PmdLogCategory category, const char *message)
{
    const PmdInstance *inst = (const PmdInstance *)context;
    PmdStatus status = category <= PMD_LOG_WARNINGS ? PMD_WARNING : PMD_OK;
    if (inst->logger)
        inst->logger(inst->environment, inst->instanceName, status, pmd_log_category_names[category], message);
}

static void update_chip_log_mask(PmdInstance *inst)
{
    inst->chip.logMask = inst->loggingOn ? inst->categories : 0;
}

static void set_defaults(PmdInstance *inst)
{
    inst->state = PMD_INSTANTIATED;
    inst->cycleTime = DEFAULT_CYCLE_TIME;
    inst->time = 0;
    inst->nextCycle = 0;
    inst->activeCycleTime = DEFAULT_CYCLE_TIME;
    inst->anchorTime = 0;
    inst->anchorCycle = 0;
    memset(inst->hostWord, 0, sizeof inst->hostWord);
    memset(inst->hostReply, 0, sizeof inst->hostReply);
    memset(inst->memoryData, 0, sizeof inst->memoryData);
    inst->hostWordCount = inst->hostStrobe = inst->hostAck = inst->hostReplyCount = inst->hostError = 0;
    inst->memoryAddress = inst->memoryCount = inst->memoryStrobe = inst->memoryStrobeSeen = 0;
    memset(&inst->chip.s, 0, sizeof inst->chip.s);
    inst->chip.s.loopback = 1;
    free(inst->scriptPath);
    inst->scriptPath = NULL;
    pmd_script_free(&inst->script);
    inst->scriptNext = 0;
    free(inst->record);
    inst->record = NULL;
    inst->recordRows = 0;
    inst->recordEnabled = 0;
    inst->scriptDigest = 0;
    inst->recordCapacity = 65536;
    inst->recordCount = 0;
    memset(inst->chip.memory, 0, (size_t)inst->memorySize * sizeof(uint32_t));
    pmd_chip_init(&inst->chip, inst->chip.memory, (uint32_t)inst->memorySize);
}

PmdInstance *pmd_instance_new(const char *instanceName, PmdInstanceLogger logger, void *environment)
{
    PmdInstance *inst = (PmdInstance *)calloc(1, sizeof *inst);
    if (!inst)
        return NULL;
    inst->instanceName = (char *)malloc(strlen(instanceName) + 1);
    inst->memorySize = DEFAULT_MEMORY_SIZE;
    inst->chip.memory = (uint32_t *)calloc((size_t)inst->memorySize, sizeof(uint32_t));
    if (!inst->instanceName || !inst->chip.memory) {
        pmd_instance_free(inst);
        return NULL;
    }
    strcpy(inst->instanceName, instanceName);
    inst->logger = logger;
    inst->environment = environment;
    inst->chip.logger = chip_logger;
    inst->chip.logContext = inst;
    set_defaults(inst);
    return inst;
}

void pmd_instance_free(PmdInstance *inst)
{
    if (!inst)
        return;
    free(inst->chip.memory);
    free(inst->instanceName);
    free(inst->scriptPath);
    pmd_script_free(&inst->script);
    free(inst->record);
    free(inst->staged.memory);
    free(inst);
}

void pmd_instance_reset(PmdInstance *inst)
{
    uint32_t *memory = (uint32_t *)realloc(inst->chip.memory, DEFAULT_MEMORY_SIZE * sizeof(uint32_t));
    if (memory) {   /* shrinking cannot fail in practice; if it does, keep the larger block */
        inst->chip.memory = memory;
        inst->memorySize = DEFAULT_MEMORY_SIZE;
    }
    set_defaults(inst);
}

PmdStatus pmd_set_debug_logging(PmdInstance *inst, const char *fn, int loggingOn, size_t nCategories,
                                const char *const categories[])
{
    size_t i;
    int c;
    if (!pmd_arrays_given(inst, fn, nCategories, categories, categories))
        return PMD_ERROR;
    for (i = 0; i < nCategories; i++) {
        int known = 0;
        for (c = 0; c < PMD_LOG_CATEGORY_COUNT; c++)
            known |= categories[i] && strcmp(categories[i], pmd_log_category_names[c]) == 0;
        if (!known) {
            pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: unknown log category \"%s\"", fn,
                             categories[i] ? categories[i] : "(NULL)");
            return PMD_ERROR;
        }
    }
    inst->loggingOn = loggingOn;
    if (nCategories == 0) {
        inst->categories = loggingOn ? (1u << PMD_LOG_CATEGORY_COUNT) - 1u : 0;
    } else {
        inst->categories = 0;
        for (i = 0; i < nCategories; i++) {
            for (c = 0; c < PMD_LOG_CATEGORY_COUNT; c++)
                if (categories[i] && strcmp(categories[i], pmd_log_category_names[c]) == 0)
                    inst->categories |= 1u << c;
        }
    }
    update_chip_log_mask(inst);
    return PMD_OK;
}

static const char *state_name(PmdState state)
{
    switch (state) {
    case PMD_INSTANTIATED: return "instantiated";
    case PMD_INITIALIZATION_MODE: return "initialization mode";
    case PMD_STEP_MODE: return "step mode";
    default: return "terminated";
    }
}

PmdInstance *pmd_begin(PmdInstance *inst, const char *fn, unsigned states)
{
    if (!inst)
        return NULL;
    if (!(inst->state & states)) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: not allowed in %s", fn, state_name(inst->state));
        return NULL;
    }
    return inst;
}

int pmd_arrays_given(const PmdInstance *inst, const char *fn, size_t n, const void *a, const void *b)
{
    if (n > 0 && (!a || !b)) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: %zu values but an array is NULL", fn, n);
        return 0;
    }
    return 1;
}

/* ---- time grid ---------------------------------------------------------------- */

/* Cycles with k * cycleTime < t are before t. A master's t is a sum of
 * floating-point steps, so k * cycleTime == t can arrive as a hair above or
 * below; within the tolerance a grid point counts as "at t". */
int64_t pmd_cycles_before(const PmdInstance *inst, double t)
{
    double x = (t - inst->anchorTime) / inst->activeCycleTime;
    return inst->anchorCycle + (int64_t)ceil(x - (1e-6 + 8 * DBL_EPSILON * fabs(x)));
}

/* SetSampleTime (a batch reported the grid changed): the grid restarts with
 * the new cycle time at `at`, the time of the next cycle. */
static void restart_grid(PmdInstance *inst, double at)
{
    inst->anchorTime = at;
    inst->anchorCycle = inst->nextCycle;
    inst->activeCycleTime = inst->chip.s.sampleTime * 1e-6;
}

/* How many cycles may run without the FMU stepping in: up to the end of the step and the next script step. */
static int64_t cycles_to_skip(const PmdInstance *inst, int64_t end)
{
    int64_t n = end - inst->nextCycle;
    if (inst->scriptNext < inst->script.count && inst->script.steps[inst->scriptNext].cycle - inst->nextCycle < n)
        n = inst->script.steps[inst->scriptNext].cycle - inst->nextCycle;
    return n;
}

/* Runs the script steps due before the next cycle; returns whether one changed the grid. */
static int run_script(PmdInstance *inst)
{
    int changed = 0;
    while (inst->scriptNext < inst->script.count && inst->script.steps[inst->scriptNext].cycle <= inst->nextCycle) {
        const PmdScriptStep *step = &inst->script.steps[inst->scriptNext++];
        if (step->nWords) {
            uint16_t reply[PMD_BATCH_WORDS];
            int count, stepChanged, err = pmd_host_batch(&inst->chip, step->words, step->nWords, reply, &count,
                                                         &stepChanged);
            changed |= stepChanged;
            if (err)
                pmd_instance_log(inst, PMD_WARNING, PMD_LOG_WARNINGS, "%s:%d: the chip refused the command: host "
                                 "I/O error 0x%02X", inst->scriptPath, step->line, err);
        } else if (pmd_memory_write(&inst->chip, step->address, step->count, inst->script.pool + step->first)) {
            /* compiled for this memory size, but a restored FMU state may have brought another */
            pmd_instance_log(inst, PMD_WARNING, PMD_LOG_WARNINGS, "%s:%d: the table's %u words at 0x%X leave the "
                             "%d-word memory: not written", inst->scriptPath, step->line, (unsigned)step->count,
                             (unsigned)step->address, inst->memorySize);
        }
    }
    return changed;
}

#define MAX_CYCLES_PER_STEP ((double)(1LL << 53))
#define MAX_CYCLE_INDEX ((double)(1LL << 62))
/* SetSampleTime's finest grid: 1 microsecond (the register counts microseconds) */
#define FINEST_CYCLE_TIME 1e-6

/* A time on the grid of cycleTime anchored at anchorTime: finite and within
 * 2^53 cycles of the anchor (the cycle index must fit an integer exactly).
 * The grid is a parameter: initialization checks the grid it will set up. */
static PmdStatus on_the_grid(const PmdInstance *inst, const char *fn, double t, double anchorTime, double cycleTime)
{
    double x = (t - anchorTime) / cycleTime;
    if (!(fabs(x) < MAX_CYCLES_PER_STEP)) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: time %g is not finite or lies beyond 2^53 cycles of "
                         "%g s", fn, t, cycleTime);
        return PMD_ERROR;
    }
    return PMD_OK;
}

/* FMI 2 sets the start time before initialization: the same check as
 * EnterInitializationMode's, at the cycle time set so far (it checks again). */
PmdStatus pmd_setup_experiment(PmdInstance *inst, const char *fn, double startTime)
{
    PmdStatus status = on_the_grid(inst, fn, startTime, inst->anchorTime, inst->cycleTime);
    if (status == PMD_OK)
        inst->time = startTime;
    return status;
}

PmdStatus pmd_enter_initialization(PmdInstance *inst, const char *fn, double startTime)
{
    PmdStatus status = on_the_grid(inst, fn, startTime, inst->anchorTime, inst->cycleTime);
    if (status != PMD_OK)
        return status;
    inst->activeCycleTime = inst->cycleTime;
    inst->time = startTime;
    inst->state = PMD_INITIALIZATION_MODE;
    return PMD_OK;
}

/* The record.data buffer, allocated when recording is enabled: an instance
 * that never records does not carry it, and doStep never allocates. */
PmdStatus pmd_record_allocate(PmdInstance *inst, const char *fn)
{
    int32_t *record;
    if (inst->record && inst->recordRows == inst->recordCapacity)
        return PMD_OK;
    if (inst->recordCapacity == 0) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: record.enabled: record.capacity is 0", fn);
        return PMD_ERROR;
    }
    record = (int32_t *)malloc((size_t)inst->recordCapacity * PMD_RECORD_WORDS * sizeof(int32_t));
    if (!record) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: record.enabled: no host memory for record.capacity %u",
                         fn, (unsigned)inst->recordCapacity);
        return PMD_ERROR;
    }
    free(inst->record);                             /* sized for another record.capacity */
    inst->record = record;
    inst->recordRows = inst->recordCapacity;
    inst->recordCount = 0;
    return PMD_OK;
}

/* What can fail comes first and changes no state field: the grid is checked,
 * the script compiled into a local, record.data sized for record.capacity (a
 * buffer of this process, which may have changed in initialization); a refused
 * ExitInitializationMode leaves the state as it was. */
PmdStatus pmd_exit_initialization(PmdInstance *inst, const char *fn)
{
    PmdScript script;
    PmdStatus status = on_the_grid(inst, fn, inst->time, 0, inst->cycleTime);

    if (status != PMD_OK)
        return status;
    memset(&script, 0, sizeof script);
    if (inst->scriptPath && *inst->scriptPath) {
        char error[1024];
        if (pmd_script_load(inst->scriptPath, (uint32_t)inst->memorySize, &script, error, sizeof error)) {
            pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: script refused: %s", fn, error);
            return PMD_ERROR;
        }
    }
    if (inst->recordEnabled && pmd_record_allocate(inst, fn) != PMD_OK) {
        pmd_script_free(&script);
        return PMD_ERROR;
    }
    if (inst->scriptPath && *inst->scriptPath) {
        pmd_script_free(&inst->script);
        inst->script = script;
        inst->scriptNext = 0;
    }
    inst->scriptDigest = pmd_script_digest(&inst->script);
    if (!inst->recordEnabled) {                     /* an instance that does not record carries no buffer */
        free(inst->record);
        inst->record = NULL;
        inst->recordRows = 0;
    }
    inst->recordCount = 0;
    inst->activeCycleTime = inst->cycleTime;
    inst->anchorTime = 0;
    inst->anchorCycle = 0;
    /* GetSampleTime reads the cycle time, a whole number of microseconds (pmd_set_real checked it) */
    inst->chip.s.sampleTime = (uint16_t)floor(inst->cycleTime * 1e6 + 0.5);
    inst->nextCycle = pmd_cycles_before(inst, inst->time);
    inst->state = PMD_STEP_MODE;
    return PMD_OK;
}

PmdStatus pmd_do_step(PmdInstance *inst, const char *fn, double t, double h)
{
    int64_t end, recorded = 0, ran = 0;
    double x, fine;
    if (!isfinite(t) || !isfinite(h) || h <= 0) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: communication point %g, step size %g: the step "
                         "size must be finite and > 0", fn, t, h);
        return PMD_ERROR;
    }
    if (fabs(t - inst->time) > 1e-6 * inst->activeCycleTime + 8 * DBL_EPSILON * fabs(inst->time)) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: communication point %.17g is not the current "
                         "time %.17g", fn, t, inst->time);
        return PMD_ERROR;
    }
    /* The step's end must be a cycle index on the current grid; and a pending
     * batch or a script step may restart the grid inside the step (anchored
     * between t and t + h) at any cycle time down to 1 us, so the step must also
     * hold fewer than 2^53 cycles of 1 us, and its last index stay far from
     * overflow: no grid change can then overflow it. */
    x = (t + h - inst->anchorTime) / inst->activeCycleTime;
    fine = h / (inst->activeCycleTime < FINEST_CYCLE_TIME ? inst->activeCycleTime : FINEST_CYCLE_TIME);
    if (!(fabs(x) < MAX_CYCLES_PER_STEP && fine < MAX_CYCLES_PER_STEP &&
          (double)inst->nextCycle + fine < MAX_CYCLE_INDEX)) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: a step of %g s to %g s holds more than 2^53 cycles "
                         "of 1 us (the finest cycle time SetSampleTime can choose), or ends beyond 2^53 cycles of the "
                         "grid: not run", fn, h, t + h);
        return PMD_ERROR;
    }
    end = pmd_cycles_before(inst, t + h);
    if (inst->recordEnabled && end - inst->nextCycle > (int64_t)inst->recordCapacity) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: recording a step of %lld cycles, but record.capacity "
                         "is %u: not run", fn, (long long)(end - inst->nextCycle), (unsigned)inst->recordCapacity);
        return PMD_ERROR;
    }
    pmd_commit_ports(inst);
    end = pmd_cycles_before(inst, t + h);               /* the batch may have restarted the grid */
    inst->recordCount = 0;
    /* script steps due at a cycle run just before it, inside the step that runs it */
    while (inst->nextCycle < end) {
        if (run_script(inst)) {
            restart_grid(inst, inst->anchorTime + (double)(inst->nextCycle - inst->anchorCycle) *
                                                      inst->activeCycleTime);
            end = pmd_cycles_before(inst, t + h);
            continue;
        }
        if (inst->recordEnabled) {               /* every cycle recorded: no fast-forward */
            /* rows past record.capacity are not recorded: the grid may have restarted finer inside the step */
            int64_t k = cycles_to_skip(inst, end), room = (int64_t)inst->recordRows - recorded;
            int64_t r = k < room ? k : room;
            pmd_chip_run(&inst->chip, r, inst->record + (size_t)recorded * PMD_RECORD_WORDS);
            pmd_chip_run(&inst->chip, k - r, NULL);
            recorded += r;
            ran += k;
            inst->nextCycle += k;
        } else {
            pmd_chip_cycle(&inst->chip);
            inst->nextCycle++;
            inst->nextCycle += pmd_chip_fast_forward(&inst->chip, cycles_to_skip(inst, end));
        }
    }
    inst->time = t + h;
    inst->recordCount = (uint32_t)recorded;
    if (ran > recorded) {
        pmd_instance_log(inst, PMD_WARNING, PMD_LOG_WARNINGS, "%s: SetSampleTime restarted the cycle grid during a "
                         "recording step: it ran %lld cycles, record.data holds the first %lld (record.capacity)",
                         fn, (long long)ran, (long long)recorded);
        return PMD_WARNING;
    }
    return PMD_OK;
}

/* ---- ports ---------------------------------------------------------------- */

void pmd_set_begin(PmdInstance *inst)
{
    free(inst->staged.memory);                      /* left by a call that was refused after its check */
    inst->staged.memory = NULL;
    inst->staged.memorySize = inst->memorySize;
    inst->staged.memoryAddress = inst->memoryAddress;
    inst->staged.memoryCount = inst->memoryCount;
    inst->staged.memoryStrobe = inst->memoryStrobe;
}

/* What the staged values ask for together: a new memory.strobe a write that
 * fits the memory (as it will be), a new memorySize room for every buffer the
 * host has set up and for a pending write. The new memory block is allocated
 * last, so that nothing can fail once values are applied. */
PmdStatus pmd_set_check(PmdInstance *inst, const char *fn)
{
    uint32_t size = (uint32_t)inst->staged.memorySize;
    int id;
    if (inst->staged.memoryStrobe != inst->memoryStrobeSeen &&
        ((uint32_t)inst->staged.memoryAddress > size ||
         (uint32_t)inst->staged.memoryCount > size - (uint32_t)inst->staged.memoryAddress)) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: memory.strobe %d: writing %u words at address %u "
                         "leaves the %u-word memory: write refused, nothing set", fn, inst->staged.memoryStrobe,
                         (unsigned)inst->staged.memoryCount, (unsigned)inst->staged.memoryAddress, (unsigned)size);
        return PMD_ERROR;
    }
    if (size == (uint32_t)inst->memorySize)
        return PMD_OK;
    for (id = 0; id < PMD_BUFFERS; id++) {
        const PmdBuffer *b = &inst->chip.s.buffer[id];
        if (b->length > 0 && (b->start > size || b->length > size - b->start)) {
            pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: memorySize = %u: buffer %d (start 0x%X, length %u) "
                             "would leave the memory: not set (set the memory size before the buffers)", fn,
                             (unsigned)size, id, (unsigned)b->start, (unsigned)b->length);
            return PMD_ERROR;
        }
    }
    inst->staged.memory = (uint32_t *)calloc(size, sizeof(uint32_t));
    if (!inst->staged.memory) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: memorySize = %u: out of host memory: not set", fn,
                         (unsigned)size);
        return PMD_ERROR;
    }
    return PMD_OK;
}

void pmd_commit_ports(PmdInstance *inst)
{
    int i;
    if (inst->hostStrobe != inst->hostAck) {
        uint16_t words[PMD_BATCH_WORDS], reply[PMD_BATCH_WORDS];
        int count = 0, gridChanged;
        for (i = 0; i < inst->hostWordCount; i++)
            words[i] = (uint16_t)(inst->hostWord[i] & 0xFFFF);
        inst->hostError = pmd_host_batch(&inst->chip, words, inst->hostWordCount, reply, &count, &gridChanged);
        for (i = 0; i < PMD_BATCH_WORDS; i++)
            inst->hostReply[i] = i < count ? reply[i] : 0;
        inst->hostReplyCount = count;
        inst->hostAck = inst->hostStrobe;
        if (gridChanged)
            restart_grid(inst, inst->time);
    }
    if (inst->memoryStrobe != inst->memoryStrobeSeen) {
        uint32_t data[PMD_BATCH_WORDS];
        for (i = 0; i < inst->memoryCount; i++)
            data[i] = (uint32_t)inst->memoryData[i];
        pmd_memory_write(&inst->chip, (uint32_t)inst->memoryAddress, (uint32_t)inst->memoryCount, data);
        inst->memoryStrobeSeen = inst->memoryStrobe;
    }
}

/* ---- variables ------------------------------------------------------------- */

static const char *const type_names[] = {"Real", "Integer", "Boolean", "String", "Binary"};
static const PmdVariable *lookup(PmdInstance *inst, const char *fn, unsigned vr, PmdType type);

int pmd_variable_given(PmdInstance *inst, const char *fn, unsigned vr, int type)
{
    return lookup(inst, fn, vr, (PmdType)type) != NULL;
}

static const PmdVariable *lookup(PmdInstance *inst, const char *fn, unsigned vr, PmdType type)
{
    const PmdVariable *v;
    if (vr > PMD_VR_MAX || pmd_variable_of_vr[vr] < 0) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: no variable has value reference %u", fn, vr);
        return NULL;
    }
    v = &pmd_variables[pmd_variable_of_vr[vr]];
    if (v->type != type) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: value reference %u (%s) is a %s, not %s", fn, vr,
                         v->name, type_names[v->type], type_names[type]);
        return NULL;
    }
    return v;
}

PmdStatus pmd_no_variable(PmdInstance *inst, const char *fn, unsigned vr, const char *type)
{
    if (vr <= PMD_VR_MAX && pmd_variable_of_vr[vr] >= 0)
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: value reference %u (%s) is a %s, not %s", fn, vr,
                         pmd_variables[pmd_variable_of_vr[vr]].name,
                         type_names[pmd_variables[pmd_variable_of_vr[vr]].type], type);
    else
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: no variable has value reference %u", fn, vr);
    return PMD_ERROR;
}

/* Parameters are fixed: settable before the end of initialization only;
 * outputs and time never. */
static int settable(PmdInstance *inst, const char *fn, const PmdVariable *v)
{
    if (v->causality == PMD_OUTPUT || v->causality == PMD_INDEPENDENT) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: %s is an %s and cannot be set", fn, v->name,
                         v->causality == PMD_OUTPUT ? "output" : "independent variable");
        return 0;
    }
    if (v->causality == PMD_PARAMETER && !(inst->state & (PMD_INSTANTIATED | PMD_INITIALIZATION_MODE))) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: %s is a fixed parameter and cannot be set after "
                         "initialization", fn, v->name);
        return 0;
    }
    return 1;
}

/* The axis of a per-axis variable (index 0..3); only per-axis cases use it:
 * for other variables index is an array element and no axis exists. */
#define AXIS_OF(v) (&inst->chip.s.axis[(v)->index])

PmdStatus pmd_get_real(PmdInstance *inst, const char *fn, unsigned vr, double *value)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_REAL);
    const PmdTrajectory *t;
    if (!v)
        return PMD_ERROR;
    if (v->family == VAR_cycleTime || v->family == VAR_time) {
        *value = v->family == VAR_time ? inst->time : inst->cycleTime;
        return PMD_OK;
    }
    t = &AXIS_OF(v)->trajectory;               /* the Reals left are per axis */
    switch (v->family) {
    case VAR_axis_position:
        *value = pmd_commanded_position_counts(t);
        break;
    case VAR_axis_velocity:
        *value = pmd_commanded_velocity_counts(t) / inst->activeCycleTime;
        break;
    default:   /* VAR_axis_acceleration */
        *value = pmd_commanded_acceleration_counts(t) / (inst->activeCycleTime * inst->activeCycleTime);
        break;
    }
    return PMD_OK;
}

PmdStatus pmd_get_integer(PmdInstance *inst, const char *fn, unsigned vr, int32_t *value)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_INTEGER);
    if (!v)
        return PMD_ERROR;
    switch (v->family) {
    case VAR_memorySize: *value = inst->memorySize; break;
    case VAR_chipTime: *value = pmd_int32(inst->chip.s.time); break;
    case VAR_axis_commandedPosition: *value = AXIS_OF(v)->trajectory.position; break;
    case VAR_axis_commandedVelocity: *value = pmd_commanded_velocity(&AXIS_OF(v)->trajectory); break;
    case VAR_axis_commandedAcceleration: *value = pmd_commanded_acceleration(&AXIS_OF(v)->trajectory); break;
    case VAR_axis_activityStatus: *value = pmd_activity_status(&inst->chip, v->index); break;
    case VAR_axis_eventStatus: *value = AXIS_OF(v)->eventStatus; break;
    case VAR_axis_actualPosition: *value = AXIS_OF(v)->actualPositionInput; break;
    case VAR_host_word: *value = inst->hostWord[v->index]; break;
    case VAR_host_wordCount: *value = inst->hostWordCount; break;
    case VAR_host_strobe: *value = inst->hostStrobe; break;
    case VAR_host_ack: *value = inst->hostAck; break;
    case VAR_host_reply: *value = inst->hostReply[v->index]; break;
    case VAR_host_replyCount: *value = inst->hostReplyCount; break;
    case VAR_host_error: *value = inst->hostError; break;
    case VAR_memory_address: *value = inst->memoryAddress; break;
    case VAR_memory_count: *value = inst->memoryCount; break;
    case VAR_memory_strobe: *value = inst->memoryStrobe; break;
    case VAR_record_capacity: *value = (int32_t)inst->recordCapacity; break;
    default: *value = inst->memoryData[v->index]; break;   /* VAR_memory_data */
    }
    return PMD_OK;
}

PmdStatus pmd_get_boolean(PmdInstance *inst, const char *fn, unsigned vr, int *value)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_BOOLEAN);
    if (!v)
        return PMD_ERROR;
    switch (v->family) {
    case VAR_loopback: *value = inst->chip.s.loopback; break;
    case VAR_axis_positiveLimit: *value = AXIS_OF(v)->positiveLimitInput; break;
    case VAR_axis_negativeLimit: *value = AXIS_OF(v)->negativeLimitInput; break;
    case VAR_axis_home: *value = AXIS_OF(v)->homeInput; break;
    case VAR_record_enabled: *value = inst->recordEnabled; break;
    default: *value = pmd_host_interrupt(&inst->chip); break;   /* VAR_host_interrupt */
    }
    return PMD_OK;
}

static PmdStatus out_of_range(PmdInstance *inst, const char *fn, const PmdVariable *v, double value,
                              const char *range)
{
    pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: %s = %.17g is out of range (%s): not set", fn, v->name,
                     value, range);
    return PMD_ERROR;
}

int pmd_cycle_time_valid(double seconds)
{
    double us = seconds * 1e6;
    return us >= 0.5 && us < 65535.5 && fabs(us - floor(us + 0.5)) <= 1e-9 * us;
}

PmdStatus pmd_set_real(PmdInstance *inst, const char *fn, unsigned vr, double value, int apply)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_REAL);
    if (!v || !settable(inst, fn, v))
        return PMD_ERROR;
    /* The only Real that can be set is cycleTime. The chip's sample time
     * register (GetSampleTime) holds whole microseconds, 1..65535: a cycle time
     * it cannot hold is refused rather than rounded. */
    if (!pmd_cycle_time_valid(value))
        return out_of_range(inst, fn, v, value, "a whole number of microseconds, 1e-6 .. 0.065535 s");
    if (apply)
        inst->cycleTime = value;
    return PMD_OK;
}

/* A new memory size keeps the words both sizes have and every register
 * (pmd_set_check made sure the buffers fit and allocated the block). */
static void set_memory_size(PmdInstance *inst, int32_t words)
{
    uint32_t *memory = inst->staged.memory;
    if (!memory)
        return;                                     /* the same size: nothing to do */
    memcpy(memory, inst->chip.memory, (size_t)(words < inst->memorySize ? words : inst->memorySize) * sizeof *memory);
    free(inst->chip.memory);
    inst->staged.memory = NULL;
    inst->chip.memory = memory;
    inst->chip.memorySize = (uint32_t)words;
    inst->memorySize = words;
}

PmdStatus pmd_set_integer(PmdInstance *inst, const char *fn, unsigned vr, int64_t value, int apply)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_INTEGER);
    if (!v || !settable(inst, fn, v))
        return PMD_ERROR;
    switch (v->family) {
    case VAR_memorySize:
        if (value < 1 || value > PMD_MAX_MEMORY_WORDS)
            return out_of_range(inst, fn, v, (double)value, "1 .. 2^26 words");
        break;
    case VAR_host_word:
        if (value < -32768 || value > 65535)
            return out_of_range(inst, fn, v, (double)value, "a 16-bit word, -32768 .. 65535");
        break;
    case VAR_host_wordCount:
    case VAR_memory_count:
        if (value < 0 || value > PMD_BATCH_WORDS)
            return out_of_range(inst, fn, v, (double)value, "0 .. 64");
        break;
    case VAR_memory_address:
        if (value < 0 || value > PMD_MAX_MEMORY_WORDS)
            return out_of_range(inst, fn, v, (double)value, "0 .. 2^26");
        break;
    case VAR_record_capacity:
        if (value < 0 || value > PMD_MAX_RECORD_CYCLES)
            return out_of_range(inst, fn, v, (double)value, "0 .. 2^24 cycles");
        break;
    case VAR_memory_data:
        if (value < INT32_MIN || value > UINT32_MAX)      /* FMI 2 Integer or FMI 3 UInt32: the word's 32 bits */
            return out_of_range(inst, fn, v, (double)value, "a 32-bit word");
        break;
    default:                                                /* Int32 variables: FMI already bounds them */
        if (value < INT32_MIN || value > INT32_MAX)
            return out_of_range(inst, fn, v, (double)value, "a 32-bit signed integer");
        break;
    }
    if (!apply) {
        switch (v->family) {                                /* what pmd_set_check looks at */
        case VAR_memorySize: inst->staged.memorySize = (int32_t)value; break;
        case VAR_memory_address: inst->staged.memoryAddress = (int32_t)value; break;
        case VAR_memory_count: inst->staged.memoryCount = (int32_t)value; break;
        case VAR_memory_strobe: inst->staged.memoryStrobe = (int32_t)value; break;
        default: break;
        }
        return PMD_OK;
    }
    switch (v->family) {
    case VAR_memorySize: set_memory_size(inst, inst->staged.memorySize); break;   /* the call's last value */
    case VAR_axis_actualPosition: AXIS_OF(v)->actualPositionInput = (int32_t)value; break;
    case VAR_host_word: inst->hostWord[v->index] = (int32_t)value; break;
    case VAR_host_wordCount: inst->hostWordCount = (int32_t)value; break;
    case VAR_host_strobe: inst->hostStrobe = (int32_t)value; break;
    case VAR_memory_address: inst->memoryAddress = (int32_t)value; break;
    case VAR_memory_count: inst->memoryCount = (int32_t)value; break;
    case VAR_memory_strobe: inst->memoryStrobe = (int32_t)value; break;
    case VAR_record_capacity: inst->recordCapacity = (uint32_t)value; break;
    default: inst->memoryData[v->index] = pmd_int32((uint32_t)value); break;   /* VAR_memory_data */
    }
    return PMD_OK;
}

PmdStatus pmd_set_boolean(PmdInstance *inst, const char *fn, unsigned vr, int value, int apply)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_BOOLEAN);
    if (!v || !settable(inst, fn, v))
        return PMD_ERROR;
    value = value != 0;
    if (!apply)          /* recording needs its buffer: allocated by the check, so that applying cannot fail */
        return v->family == VAR_record_enabled && value ? pmd_record_allocate(inst, fn) : PMD_OK;
    switch (v->family) {
    case VAR_loopback: inst->chip.s.loopback = (uint8_t)value; break;
    case VAR_axis_positiveLimit: AXIS_OF(v)->positiveLimitInput = (uint8_t)value; break;
    case VAR_axis_negativeLimit: AXIS_OF(v)->negativeLimitInput = (uint8_t)value; break;
    case VAR_record_enabled: inst->recordEnabled = (uint8_t)value; break;
    default: AXIS_OF(v)->homeInput = (uint8_t)value; break;   /* VAR_axis_home */
    }
    return PMD_OK;
}

PmdStatus pmd_get_string(PmdInstance *inst, const char *fn, unsigned vr, const char **value)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_STRING);
    if (!v)
        return PMD_ERROR;
    *value = inst->scriptPath ? inst->scriptPath : "";     /* the only String: script */
    return PMD_OK;
}

PmdStatus pmd_set_string(PmdInstance *inst, const char *fn, unsigned vr, const char *value, int apply)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_STRING);
    char *copy;
    if (!v || !settable(inst, fn, v))
        return PMD_ERROR;
    if (!value) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: %s: the value is NULL", fn, v->name);
        return PMD_ERROR;
    }
    if (!apply)
        return PMD_OK;
    copy = (char *)malloc(strlen(value) + 1);
    if (!copy) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: out of host memory", fn);
        return PMD_ERROR;
    }
    strcpy(copy, value);
    free(inst->scriptPath);
    inst->scriptPath = copy;
    return PMD_OK;
}

PmdStatus pmd_get_binary(PmdInstance *inst, const char *fn, unsigned vr, const unsigned char **value, size_t *size)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_BINARY);
    if (!v)
        return PMD_ERROR;
    /* the only Binary: record.data, little-endian int32 words as this platform stores them */
    *value = (const unsigned char *)inst->record;
    *size = (size_t)inst->recordCount * PMD_RECORD_WORDS * sizeof(int32_t);
    return PMD_OK;
}
