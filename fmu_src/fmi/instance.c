/* SPDX-License-Identifier: BSD-2-Clause */
/* The FMU instance over the chip core: variables, ports and the time grid
 * (CONTRACT 2.1, 2.2). */
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "instance.h"
#include "machine.h"
#include "values.h"

#define DEFAULT_CYCLE_TIME 1e-4
#define DEFAULT_MEMORY_SIZE 0x4000     /* seed 000, 1.1: memory_size = 0x4000 (16Kx32) */

const char pmd_model_token[] = PMD_INSTANTIATION_TOKEN;

/* The chip formats a message only when its category is enabled (chip.logMask).
 * A refused command is the chip's answer, not an FMU failure: it goes out
 * under "errors" with status Warning. */
static void chip_logger(void *context, unsigned category, const char *message)
{
    const PmdInstance *inst = (const PmdInstance *)context;
    PmdStatus status = category == PMD_LOG_ERRORS || category == PMD_LOG_WARNINGS ? PMD_WARNING : PMD_OK;
    if (inst->logger)
        inst->logger(inst->environment, inst->instanceName, status, pmd_log_category_names[category], message);
}

static void update_chip_log_mask(PmdInstance *inst)
{
    inst->chip.logMask = inst->loggingOn ? inst->categories : 0;
}

/* The declared state as instantiation leaves it; the memory size stays the caller's. */
static void set_defaults(PmdInstance *inst)
{
    int32_t memorySize = inst->s.memorySize;
    memset(&inst->s, 0, sizeof inst->s);
    inst->s.state = PMD_INSTANTIATED;
    inst->s.cycleTime = DEFAULT_CYCLE_TIME;
    inst->s.memorySize = memorySize;
    memset(&inst->chip.s, 0, sizeof inst->chip.s);
    inst->chip.s.loopback = 1;
    free(inst->scriptPath);
    inst->scriptPath = NULL;
    pmd_script_free(&inst->script);
    free(inst->machinePath);
    inst->machinePath = NULL;
    memset(&inst->machine, 0, sizeof inst->machine);
    inst->chip.machine = NULL;
    free(inst->record);
    inst->record = NULL;
    inst->recordRows = 0;
    inst->recordBytes = 0;
    inst->recordLent = NULL;
    inst->recordLentBytes = 0;
    inst->recordLender = NULL;
    inst->recordCapacity = 65536;
    inst->recordCount = 0;
    pmd_record_columns_free(&inst->columns);
    pmd_record_columns_free(&inst->stagedColumns);
    inst->recordRowBytes = inst->columns.rowBytes;
    memset(inst->chip.memory, 0, (size_t)memorySize * sizeof(uint32_t));
    pmd_chip_init(&inst->chip, inst->chip.memory, (uint32_t)memorySize);
}

PmdInstance *pmd_model_new(const char *instanceName, PmdModelLogger logger, void *environment)
{
    PmdInstance *inst = (PmdInstance *)calloc(1, sizeof *inst);
    if (!inst)
        return NULL;
    inst->instanceName = (char *)malloc(strlen(instanceName) + 1);
    inst->s.memorySize = DEFAULT_MEMORY_SIZE;
    inst->chip.memory = (uint32_t *)calloc((size_t)inst->s.memorySize, sizeof(uint32_t));
    if (!inst->instanceName || !inst->chip.memory) {
        pmd_model_free(inst);
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

void pmd_model_free(PmdInstance *inst)
{
    if (!inst)
        return;
    free(inst->chip.memory);
    free(inst->instanceName);
    free(inst->scriptPath);
    free(inst->scriptStart);
    free(inst->machinePath);
    free(inst->resources);
    pmd_script_free(&inst->script);
    free(inst->record);
    pmd_record_columns_free(&inst->columns);
    pmd_record_columns_free(&inst->stagedColumns);
    free(inst->staged.memory);
    free(inst);
}

PmdStatus pmd_model_resources(PmdInstance *inst, const char *fn, char *resources, const char *noResources)
{
    char error[1024];
    inst->resources = resources;
    inst->noResources = noResources;
    if (resources && pmd_script_read_start(resources, &inst->scriptStart, error, sizeof error) < 0) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: the script parameter's start value: %s", fn, error);
        return PMD_ERROR;
    }
    return PMD_OK;
}

const char *pmd_script_value(const PmdInstance *inst)
{
    return inst->scriptPath ? inst->scriptPath : inst->scriptStart ? inst->scriptStart : "";
}

void pmd_model_reset(PmdInstance *inst)
{
    uint32_t *memory = (uint32_t *)realloc(inst->chip.memory, DEFAULT_MEMORY_SIZE * sizeof(uint32_t));
    if (memory) {   /* shrinking cannot fail in practice; if it does, keep the larger block */
        inst->chip.memory = memory;
        inst->s.memorySize = DEFAULT_MEMORY_SIZE;
    }
    set_defaults(inst);
}

PmdStatus pmd_model_set_debug_logging(PmdInstance *inst, const char *fn, int loggingOn, size_t nCategories,
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
            char names[512] = "";
            for (c = 0; c < PMD_LOG_CATEGORY_COUNT; c++) {
                strncat(names, c ? ", " : "", sizeof names - strlen(names) - 1);
                strncat(names, pmd_log_category_names[c], sizeof names - strlen(names) - 1);
            }
            pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: unknown log category \"%s\" (the FMU's: %s)", fn,
                             categories[i] ? categories[i] : "(NULL)", names);
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

const char *pmd_model_state_name(PmdState state)
{
    switch (state) {
    case PMD_INSTANTIATED: return "instantiated";
    case PMD_INITIALIZATION_MODE: return "initialization mode";
    case PMD_STEP_MODE: return "step mode";
    case PMD_TERMINATED: return "terminated";
    }
    return "terminated";
}

PmdState pmd_model_fmi_state(const PmdInstance *inst)
{
    return inst->s.state;
}

double pmd_model_time(const PmdInstance *inst)
{
    return inst->s.time;
}

void pmd_model_terminate(PmdInstance *inst)
{
    inst->s.state = PMD_TERMINATED;
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

/* What initialization loads into the sample time register: the cycleTime
 * parameter in whole microseconds (pmd_model2_set_real checked that it is one). */
static uint16_t sample_time_of(double cycleTime)
{
    return (uint16_t)floor(cycleTime * 1e6 + 0.5);
}

/* Cycles with k * cycleTime < t are before t. A master's t is a sum of
 * floating-point steps, so k * cycleTime == t can arrive as a hair above or
 * below; within the tolerance a grid point counts as "at t". */
static int64_t cycles_before(double anchorTime, int64_t anchorCycle, double cycleTime, double t)
{
    double x = (t - anchorTime) / cycleTime;
    return anchorCycle + (int64_t)ceil(x - (1e-6 + 8 * DBL_EPSILON * fabs(x)));
}

int64_t pmd_cycles_before(const PmdGrid *grid, double t)
{
    return cycles_before(grid->anchorTime, grid->anchorCycle, grid->cycleTime, t);
}

PmdGrid pmd_grid(const PmdInstanceState *s, const PmdChipState *chip)
{
    PmdGrid g;
    if (s->state & (PMD_STEP_MODE | PMD_TERMINATED)) {
        g.anchorTime = s->anchorTime;
        g.anchorCycle = s->anchorCycle;
        g.cycleTime = chip->sampleTime / 1e6;
        g.nextCycle = s->nextCycle;
    } else {                                        /* what pmd_model_exit_initialization sets up */
        g.anchorTime = 0;
        g.anchorCycle = 0;
        g.cycleTime = sample_time_of(s->cycleTime) / 1e6;
        g.nextCycle = cycles_before(0, 0, g.cycleTime, s->time);
    }
    return g;
}

/* SetSampleTime (a batch said the grid changed): the grid restarts with the
 * new cycle time at `at`, the time of the next cycle. Before the end of
 * initialization there is no grid to restart: initialization sets it up. */
static void restart_grid(PmdInstance *inst, double at)
{
    if (inst->s.state != PMD_STEP_MODE)
        return;
    inst->s.anchorTime = at;
    inst->s.anchorCycle = inst->s.nextCycle;
}

/* The script step to run next, or NULL once the script has run. */
static const PmdScriptStep *next_script_step(const PmdInstance *inst)
{
    return inst->s.scriptNext < inst->script.count ? &inst->script.steps[inst->s.scriptNext] : NULL;
}

/* How many cycles may run without the FMU stepping in: up to the end of the step and the next script step. */
static int64_t cycles_to_skip(const PmdInstance *inst, int64_t end)
{
    const PmdScriptStep *next = next_script_step(inst);
    int64_t n = end - inst->s.nextCycle;
    if (next && next->cycle - inst->s.nextCycle < n)
        n = next->cycle - inst->s.nextCycle;
    return n;
}

/* Runs the script steps due before the next cycle; returns whether one changed the grid. */
static int run_script(PmdInstance *inst)
{
    const PmdScriptStep *step;
    int changed = 0;
    while ((step = next_script_step(inst)) != NULL && step->cycle <= inst->s.nextCycle) {
        inst->s.scriptNext++;
        if (step->nWords) {
            uint16_t reply[PMD_BATCH_WORDS];
            int count, stepChanged, err = pmd_host_batch(&inst->chip, step->words, step->nWords, reply, &count,
                                                         &stepChanged);
            changed |= stepChanged;
            if (err)
                pmd_instance_log(inst, PMD_WARNING, PMD_LOG_WARNINGS, "%s:%d: the chip refused the command: host "
                                 "I/O error 0x%02X", inst->script.name, step->line, err);
        } else if (pmd_memory_write(&inst->chip, step->address, step->count, inst->script.pool + step->first)) {
            /* compiled for this memory size, but a restored FMU state may have brought another */
            pmd_instance_log(inst, PMD_WARNING, PMD_LOG_WARNINGS, "%s:%d: the table's %u words at 0x%X leave the "
                             "%d-word memory: not written", inst->script.name, step->line, (unsigned)step->count,
                             (unsigned)step->address, inst->s.memorySize);
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
PmdStatus pmd_model_setup_experiment(PmdInstance *inst, const char *fn, double startTime)
{
    PmdStatus status = on_the_grid(inst, fn, startTime, inst->s.anchorTime, inst->s.cycleTime);
    if (status == PMD_OK)
        inst->s.time = startTime;
    return status;
}

PmdStatus pmd_model_enter_initialization(PmdInstance *inst, const char *fn, double startTime)
{
    PmdStatus status = on_the_grid(inst, fn, startTime, inst->s.anchorTime, inst->s.cycleTime);
    if (status != PMD_OK)
        return status;
    inst->s.time = startTime;
    inst->s.state = PMD_INITIALIZATION_MODE;
    return PMD_OK;
}

/* What can fail comes first and changes no state field: the grid is checked,
 * the script compiled into a local, record.data sized for record.capacity (a
 * buffer of this process, which may have changed in initialization); a refused
 * ExitInitializationMode leaves the state as it was. */
/* The machine parameter parsed into machine (all zero for ""), what it means
 * logged under "machine"; PMD_ERROR with the file's line and reason. */
static PmdStatus parse_machine(PmdInstance *inst, const char *fn, PmdMachine *machine)
{
    char error[8192], name[1100], meaning[2048];
    const char *value = inst->machinePath ? inst->machinePath : "";
    PmdScriptPlaces places;
    places.resources = inst->resources;
    places.noResources = inst->noResources;
    if (pmd_machine_parse(value, &places, machine, name, sizeof name, error, sizeof error)) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: machine refused: %s", fn, error);
        return PMD_ERROR;
    }
    if (*value) {
        pmd_machine_describe(machine, meaning, sizeof meaning);
        pmd_instance_log(inst, PMD_OK, PMD_LOG_MACHINE, "%s: machine read from %s:\n%s", fn, name, meaning);
    }
    return PMD_OK;
}

PmdStatus pmd_model_exit_initialization(PmdInstance *inst, const char *fn)
{
    PmdScript script;
    PmdMachine machine;
    const char *value = pmd_script_value(inst);
    PmdStatus status = on_the_grid(inst, fn, inst->s.time, 0, inst->s.cycleTime);
    size_t i;

    if (status != PMD_OK)
        return status;
    if (parse_machine(inst, fn, &machine) != PMD_OK)
        return PMD_ERROR;
    memset(&script, 0, sizeof script);
    if (*value) {
        char error[8192];
        PmdScriptPlaces places;
        places.resources = inst->resources;
        places.noResources = inst->noResources;
        if (pmd_script_compile(value, &places, (uint32_t)inst->s.memorySize, &script, error, sizeof error)) {
            /* a path holding a line feed is read as text too: say why it was (docs/scripts.md) */
            pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: script refused: %s%s", fn, error,
                             pmd_script_is_text(value) ? " (the value holds a line feed, so it was read as script "
                             "text)" : "");
            return PMD_ERROR;
        }
    }
    if (inst->s.recordEnabled && pmd_record_allocate(inst, fn) != PMD_OK) {
        pmd_script_free(&script);
        return PMD_ERROR;
    }
    if (*value) {
        pmd_script_free(&inst->script);
        inst->script = script;
        inst->s.scriptNext = 0;
        /* which files it read (pmdfmu pack copies them into the FMU it writes) */
        if (pmd_script_is_text(value))
            pmd_instance_log(inst, PMD_OK, PMD_LOG_BUFFERS, "%s: script given as text", fn);
        else
            pmd_instance_log(inst, PMD_OK, PMD_LOG_BUFFERS, "%s: script read from %s", fn, script.name);
        for (i = 0; i < script.tableCount; i++)
            pmd_instance_log(inst, PMD_OK, PMD_LOG_BUFFERS, "%s: %s:%d: segment table \"%s\" read from %s", fn,
                             script.name, script.tables[i].line, script.tables[i].name, script.tables[i].path);
    }
    inst->s.scriptDigest = pmd_script_digest(&inst->script);
    inst->machine = machine;
    inst->chip.machine = machine.axes ? &inst->machine : NULL;
    inst->s.machineDigest = pmd_machine_digest(&inst->machine);
    if (!inst->s.recordEnabled) {                     /* an instance that does not record carries no buffer */
        free(inst->record);
        inst->record = NULL;
        inst->recordRows = 0;
        inst->recordBytes = 0;
    }
    inst->recordCount = 0;
    /* the grid: the cycle time is the sample time register's (GetSampleTime reads it), anchored at 0 */
    inst->s.nextCycle = pmd_grid(&inst->s, &inst->chip.s).nextCycle;
    inst->s.anchorTime = 0;
    inst->s.anchorCycle = 0;
    inst->chip.s.sampleTime = sample_time_of(inst->s.cycleTime);
    /* a machine's motors at their initial angle and speed, as a plant FMU leaves initialization */
    for (i = 0; i < PMD_AXES; i++)
        if (inst->machine.plantAxes & (1u << i))
            pmd_machine_plant_start(&inst->chip, (int)i);
    inst->s.state = PMD_STEP_MODE;
    return PMD_OK;
}

PmdStatus pmd_model_do_step(PmdInstance *inst, const char *fn, double t, double h)
{
    int64_t end, k, recorded = 0, ran = 0;
    double x, fine;
    PmdGrid g = pmd_grid(&inst->s, &inst->chip.s);
    if (!isfinite(t) || !isfinite(h) || h <= 0) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: communication point %g, step size %g: the step "
                         "size must be finite and > 0", fn, t, h);
        return PMD_ERROR;
    }
    if (fabs(t - inst->s.time) > 1e-6 * g.cycleTime + 8 * DBL_EPSILON * fabs(inst->s.time)) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: communication point %.17g is not the current "
                         "time %.17g", fn, t, inst->s.time);
        return PMD_ERROR;
    }
    /* The step's end must be a cycle index on the current grid; and a pending
     * batch or a script step may restart the grid inside the step (anchored
     * between t and t + h) at any cycle time down to 1 us, so the step must also
     * hold fewer than 2^53 cycles of 1 us, and its last index stay far from
     * overflow: no grid change can then overflow it. */
    x = (t + h - g.anchorTime) / g.cycleTime;
    fine = h / (g.cycleTime < FINEST_CYCLE_TIME ? g.cycleTime : FINEST_CYCLE_TIME);
    if (!(fabs(x) < MAX_CYCLES_PER_STEP && fine < MAX_CYCLES_PER_STEP &&
          (double)inst->s.nextCycle + fine < MAX_CYCLE_INDEX)) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: a step of %g s to %g s holds more than 2^53 cycles "
                         "of 1 us (the finest cycle time SetSampleTime can choose), or ends beyond 2^53 cycles of the "
                         "grid: not run", fn, h, t + h);
        return PMD_ERROR;
    }
    end = pmd_cycles_before(&g, t + h);
    if (inst->s.recordEnabled && end - inst->s.nextCycle > (int64_t)inst->recordCapacity) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: recording a step of %lld cycles, but record.capacity "
                         "is %u: not run", fn, (long long)(end - inst->s.nextCycle), (unsigned)inst->recordCapacity);
        return PMD_ERROR;
    }
    if (inst->s.recordEnabled && inst->recordLent) {
        if (end - inst->s.nextCycle > pmd_record_room(inst)) {
            pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: recording a step of %lld cycles, but the memory "
                             "lent by %s holds %lld rows of %u bytes: not run", fn,
                             (long long)(end - inst->s.nextCycle), inst->recordLender, (long long)pmd_record_room(inst),
                             (unsigned)inst->columns.rowBytes);
            return PMD_ERROR;
        }
        if (!inst->columns.count && (uintptr_t)inst->recordLent % sizeof(int32_t)) {
            pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: the memory lent by %s (%p) "
                             "is not aligned to 4 bytes, as the default rows of int32 words need: not run", fn,
                             inst->recordLender, (void *)inst->recordLent);
            return PMD_ERROR;
        }
    }
    pmd_commit_ports(inst);
    g = pmd_grid(&inst->s, &inst->chip.s);              /* the batch may have restarted the grid */
    end = pmd_cycles_before(&g, t + h);
    inst->recordCount = 0;
    /* script steps due at a cycle run just before it, inside the step that runs it */
    while (inst->s.nextCycle < end) {
        if (run_script(inst)) {                    /* at the next cycle's time on the grid it ran on */
            restart_grid(inst, g.anchorTime + (double)(inst->s.nextCycle - g.anchorCycle) * g.cycleTime);
            g = pmd_grid(&inst->s, &inst->chip.s);
            end = pmd_cycles_before(&g, t + h);
            continue;
        }
        k = cycles_to_skip(inst, end);
        if (inst->s.recordEnabled) {               /* every cycle recorded: no fast-forward */
            /* Rows past the room (record.capacity, or the memory lent) are not recorded: the grid may have
             * restarted finer inside the step, up to 65 535 cycles for each one the room was checked for.
             * Those cycles record nothing, so they run as an unrecorded step runs them, fast-forwarded where
             * that pays: one by one, a step that passed the check could run for days. */
            int64_t room = pmd_record_room(inst) - recorded, r = k < room ? k : room;
            inst->recordRowBytes = inst->columns.rowBytes;
            if (inst->columns.count) {             /* record.columns: a row after each cycle (record.c) */
                PmdGrid now = pmd_grid(&inst->s, &inst->chip.s);
                pmd_record_cycles(inst, &now, r, recorded);
            } else {
                /* the rows are int32 words: record.data's buffer is aligned, lent memory was checked above */
                int32_t *rows = (int32_t *)(void *)pmd_record_rows(inst) + (size_t)recorded * PMD_RECORD_WORDS;
                pmd_chip_run_every_cycle(&inst->chip, r, rows);
            }
            pmd_chip_run_fast_forwarding(&inst->chip, k - r);
            recorded += r;
            ran += k;
        } else {                                   /* nothing recorded: fast-forward where it pays */
            pmd_chip_run_fast_forwarding(&inst->chip, k);
        }
        inst->s.nextCycle += k;                    /* the grid is the instance's: it alone advances it */
    }
    inst->s.time = t + h;
    inst->recordCount = (uint32_t)recorded;
    if (ran > recorded) {
        pmd_instance_log(inst, PMD_WARNING, PMD_LOG_WARNINGS, "%s: SetSampleTime restarted the cycle grid during a "
                         "recording step: it ran %lld cycles, record.data holds the first %lld (%s%s)", fn,
                         (long long)ran, (long long)recorded, inst->recordLent ? "the memory lent by " : "",
                         inst->recordLent ? inst->recordLender : "record.capacity");
        return PMD_WARNING;
    }
    return PMD_OK;
}

/* ---- ports ---------------------------------------------------------------- */

void pmd_model_set_begin(PmdInstance *inst)
{
    free(inst->staged.memory);                      /* left by a call that was refused after its check */
    inst->staged.memory = NULL;
    inst->staged.memorySize = inst->s.memorySize;
    inst->staged.memoryAddress = inst->s.memoryAddress;
    inst->staged.memoryCount = inst->s.memoryCount;
    inst->staged.memoryStrobe = inst->s.memoryStrobe;
}

/* What the staged values ask for together: a new memory.strobe a write that
 * fits the memory (as it will be), a new memorySize room for every buffer the
 * host has set up and for a pending write. The new memory block is allocated
 * last, so that nothing can fail once values are applied. */
PmdStatus pmd_model_set_check(PmdInstance *inst, const char *fn)
{
    uint32_t size = (uint32_t)inst->staged.memorySize;
    int id;
    if (inst->staged.memoryStrobe != inst->s.memoryStrobeSeen &&
        ((uint32_t)inst->staged.memoryAddress > size ||
         (uint32_t)inst->staged.memoryCount > size - (uint32_t)inst->staged.memoryAddress)) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: memory.strobe %d: writing %u words at address %u "
                         "leaves the %u-word memory: write refused, nothing set", fn, inst->staged.memoryStrobe,
                         (unsigned)inst->staged.memoryCount, (unsigned)inst->staged.memoryAddress, (unsigned)size);
        return PMD_ERROR;
    }
    if (size == (uint32_t)inst->s.memorySize)
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
    if (inst->s.hostStrobe != inst->s.hostAck) {
        uint16_t words[PMD_BATCH_WORDS], reply[PMD_BATCH_WORDS];
        int count = 0, gridChanged;
        for (i = 0; i < inst->s.hostWordCount; i++)
            words[i] = (uint16_t)(inst->s.hostWord[i] & 0xFFFF);
        inst->s.hostError = pmd_host_batch(&inst->chip, words, inst->s.hostWordCount, reply, &count, &gridChanged);
        for (i = 0; i < PMD_BATCH_WORDS; i++)
            inst->s.hostReply[i] = i < count ? reply[i] : 0;
        inst->s.hostReplyCount = count;
        inst->s.hostAck = inst->s.hostStrobe;
        if (gridChanged)
            restart_grid(inst, inst->s.time);
    }
    if (inst->s.memoryStrobe != inst->s.memoryStrobeSeen) {
        uint32_t data[PMD_BATCH_WORDS];
        for (i = 0; i < inst->s.memoryCount; i++)
            data[i] = (uint32_t)inst->s.memoryData[i];
        pmd_memory_write(&inst->chip, (uint32_t)inst->s.memoryAddress, (uint32_t)inst->s.memoryCount, data);
        inst->s.memoryStrobeSeen = inst->s.memoryStrobe;
    }
}

/* Gets see pending port writes executed first: a host reads its replies at the
 * time it wrote the batch (CONTRACT 2.2). In Initialization Mode a get executes
 * nothing: the ports' writes wait for the first get or doStep after it, at the
 * start time before cycle 0, so that the initial values depend on the
 * parameters and the start time alone (the InitialUnknowns say so, and FMI 2's
 * stay small: docs/performance.md, "Model description"). */
void pmd_model_commit(PmdInstance *inst)
{
    if (inst->s.state == PMD_STEP_MODE)
        pmd_commit_ports(inst);
}

/* ---- variables ------------------------------------------------------------- */

static const char *const type_names[] = {"Real", "Integer", "Boolean", "String", "Binary"};
static const PmdVariable *lookup(PmdInstance *inst, const char *fn, unsigned vr, PmdType type);

int pmd_model2_given(PmdInstance *inst, const char *fn, unsigned vr, PmdFmi2Type type)
{
    static const PmdType types[] = {[PMD_FMI2_REAL] = PMD_REAL, [PMD_FMI2_INTEGER] = PMD_INTEGER,
                                    [PMD_FMI2_BOOLEAN] = PMD_BOOLEAN};
    return lookup(inst, fn, vr, types[type]) != NULL;
}

int pmd_variable_row(const PmdInstance *inst, const char *fn, unsigned vr, const short *of_vr, unsigned max)
{
    if (vr > max || of_vr[vr] < 0) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: no variable has value reference %u", fn, vr);
        return -1;
    }
    return of_vr[vr];
}

static const PmdVariable *lookup(PmdInstance *inst, const char *fn, unsigned vr, PmdType type)
{
    int row = pmd_variable_row(inst, fn, vr, pmd_variable_of_vr, PMD_VR_MAX);
    const PmdVariable *v = row < 0 ? NULL : &pmd_variables[row];
    if (v && v->type != type) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: value reference %u (%s) is a %s, not %s", fn, vr,
                         v->name, type_names[v->type], type_names[type]);
        return NULL;
    }
    return v;
}

/* Parameters are fixed: settable before the end of initialization only;
 * outputs and time never. */
static int settable(PmdInstance *inst, const char *fn, const PmdVariable *v)
{
    if (v->causality == PMD_OUTPUT || v->causality == PMD_INDEPENDENT) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: value reference %u (%s) is an %s and cannot be set",
                         fn, v->vr, v->name, v->causality == PMD_OUTPUT ? "output" : "independent variable");
        return 0;
    }
    if (v->causality == PMD_PARAMETER && !(inst->s.state & (PMD_INSTANTIATED | PMD_INITIALIZATION_MODE))) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: value reference %u (%s) is a fixed parameter and "
                         "cannot be set after initialization", fn, v->vr, v->name);
        return 0;
    }
    return 1;
}

/* A variable of the right type that a get or set below has no case for: a
 * row of variables.csv without its code. Refused, never answered with
 * another variable's value or applied to another variable. */
static PmdStatus unhandled(PmdInstance *inst, const char *fn, const PmdVariable *v, const char *what)
{
    pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: value reference %u (%s): this FMU has no %s for it", fn,
                     v->vr, v->name, what);
    return PMD_ERROR;
}

/* The axis of a per-axis variable (index 0..3); only per-axis cases use it:
 * for other variables index is an array element and no axis exists. */
#define AXIS_OF(v) (&inst->chip.s.axis[(v)->index])

/* Each case is a row of values.h's tables (PMD_REAL_VALUES, ...), the values record.columns records. */
#define VALUE_CASE(family, expression) case family: *value = (expression); break;

PmdStatus pmd_model2_get_real(PmdInstance *inst, const char *fn, unsigned vr, double *value)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_REAL);
    PmdGrid grid;
    const PmdGrid *g = &grid;
    PmdCommandedReals all;
    const PmdCommandedReals *reals = &all;
    unsigned i;
    if (!v)
        return PMD_ERROR;
    grid = pmd_grid(&inst->s, &inst->chip.s);
    if (PMD_READS_REALS(v->family))
        pmd_commanded_reals(&inst->chip, g->cycleTime, &all);
    i = v->index;
    switch (v->family) {
    PMD_REAL_VALUES(VALUE_CASE)
    default: return unhandled(inst, fn, v, "Real getter");
    }
    return PMD_OK;
}

PmdStatus pmd_model2_get_integer(PmdInstance *inst, const char *fn, unsigned vr, int32_t *value)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_INTEGER);
    unsigned i;
    if (!v)
        return PMD_ERROR;
    i = v->index;
    switch (v->family) {
    PMD_INTEGER_VALUES(VALUE_CASE)
    default: return unhandled(inst, fn, v, "Integer getter");
    }
    return PMD_OK;
}

PmdStatus pmd_model2_get_boolean(PmdInstance *inst, const char *fn, unsigned vr, int *value)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_BOOLEAN);
    unsigned i;
    if (!v)
        return PMD_ERROR;
    i = v->index;
    switch (v->family) {
    PMD_BOOLEAN_VALUES(VALUE_CASE)
    default: return unhandled(inst, fn, v, "Boolean getter");
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

PmdStatus pmd_model2_set_real(PmdInstance *inst, const char *fn, unsigned vr, double value, int apply)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_REAL);
    if (!v || !settable(inst, fn, v))
        return PMD_ERROR;
    switch (v->family) {
    case VAR_cycleTime:
        /* The chip's sample time register (GetSampleTime) holds whole
         * microseconds, 1..65535: a cycle time it cannot hold is refused
         * rather than rounded. */
        if (!pmd_cycle_time_valid(value)) {
            /* say which of the two it is: 1.5e-6 is inside the range, just not whole */
            int inside = value * 1e6 >= 0.5 && value * 1e6 < 65535.5;
            pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: cycleTime = %.17g s is %s: the sample time "
                             "register (GetSampleTime) holds a whole number of microseconds, 1 .. 65535: not set",
                             fn, value, isnan(value) ? "not a number" : inside ? "not a whole number of microseconds"
                             : "outside 1 us .. 65535 us");
            return PMD_ERROR;
        }
        if (apply)
            inst->s.cycleTime = value;
        return PMD_OK;
    default:
        return unhandled(inst, fn, v, "Real setter");
    }
}

/* A new memory size keeps the words both sizes have and every register
 * (pmd_model_set_check made sure the buffers fit and allocated the block). */
static void set_memory_size(PmdInstance *inst, int32_t words)
{
    uint32_t *memory = inst->staged.memory;
    int32_t kept = words < inst->s.memorySize ? words : inst->s.memorySize;
    if (!memory)
        return;                                     /* the same size: nothing to do */
    memcpy(memory, inst->chip.memory, (size_t)kept * sizeof *memory);
    free(inst->chip.memory);
    inst->staged.memory = NULL;
    inst->chip.memory = memory;
    inst->chip.memorySize = (uint32_t)words;
    inst->s.memorySize = words;
}

/* memory.data's range, one check for pmd_set_integer and pmd_set_memory_data alike */
#define MEMORY_WORD_RANGE "a 32-bit word"
static int memory_word_fits(int64_t value)
{
    return value >= INT32_MIN && value <= UINT32_MAX;     /* FMI 2 Integer or FMI 3 UInt32: the word's 32 bits */
}

/* host.word's range, one check for pmd_set_integer and pmd_set_host_words alike */
#define HOST_WORD_RANGE "a 16-bit word, -32768 .. 65535"
static int host_word_fits(int64_t value)
{
    return value >= -32768 && value <= 65535;             /* FMI 2 Integer or FMI 3 UInt16: the word's bits */
}

PmdStatus pmd_set_integer(PmdInstance *inst, const char *fn, unsigned vr, int64_t value, int apply)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_INTEGER);
    if (!v || !settable(inst, fn, v))
        return PMD_ERROR;
    switch (v->family) {                                    /* the value's range */
    case VAR_memorySize:
        if (value < 1 || value > PMD_MAX_MEMORY_WORDS)
            return out_of_range(inst, fn, v, (double)value, "1 .. 2^26 words");
        break;
    case VAR_host_word:
        if (!host_word_fits(value))
            return out_of_range(inst, fn, v, (double)value, HOST_WORD_RANGE);
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
        if (!memory_word_fits(value))
            return out_of_range(inst, fn, v, (double)value, MEMORY_WORD_RANGE);
        break;
    case VAR_analog:
    case VAR_io_input:                                      /* UInt16 wires: FMI 2 Integer can go beyond them */
        if (value < 0 || value > UINT16_MAX)
            return out_of_range(inst, fn, v, (double)value, "a 16-bit unsigned value, 0 .. 65535");
        break;
    case VAR_axis_actualPosition:
    case VAR_host_strobe:
    case VAR_memory_strobe:                                 /* Int32 variables: FMI already bounds them */
        if (value < INT32_MIN || value > INT32_MAX)
            return out_of_range(inst, fn, v, (double)value, "a 32-bit signed integer");
        break;
    default:
        return unhandled(inst, fn, v, "Integer setter");
    }
    if (!apply) {
        switch (v->family) {                                /* what pmd_model_set_check looks at */
        case VAR_memorySize: inst->staged.memorySize = (int32_t)value; break;
        case VAR_memory_address: inst->staged.memoryAddress = (int32_t)value; break;
        case VAR_memory_count: inst->staged.memoryCount = (int32_t)value; break;
        case VAR_memory_strobe: inst->staged.memoryStrobe = (int32_t)value; break;
        default: break;                                     /* checked above; nothing to stage */
        }
        return PMD_OK;
    }
    switch (v->family) {
    case VAR_memorySize: set_memory_size(inst, inst->staged.memorySize); break;   /* the call's last value */
    case VAR_axis_actualPosition: AXIS_OF(v)->actualPositionInput = (int32_t)value; break;
    case VAR_host_word: inst->s.hostWord[v->index] = (int32_t)value; break;
    case VAR_host_wordCount: inst->s.hostWordCount = (int32_t)value; break;
    case VAR_host_strobe: inst->s.hostStrobe = (int32_t)value; break;
    case VAR_memory_address: inst->s.memoryAddress = (int32_t)value; break;
    case VAR_memory_count: inst->s.memoryCount = (int32_t)value; break;
    case VAR_memory_strobe: inst->s.memoryStrobe = (int32_t)value; break;
    case VAR_memory_data: inst->s.memoryData[v->index] = pmd_int32((uint32_t)value); break;
    /* the plant's wires, read by ReadAnalog and ReadIO when a batch executes */
    case VAR_analog: inst->chip.s.analogInput[v->index] = (uint16_t)value; break;
    case VAR_io_input: inst->chip.s.ioInput[v->index] = (uint16_t)value; break;
    case VAR_record_capacity: inst->recordCapacity = (uint32_t)value; break;
    default: return unhandled(inst, fn, v, "Integer setter");   /* the check pass refused it already */
    }
    return PMD_OK;
}

size_t pmd_memory_data_span(unsigned vr, size_t n)
{
    const PmdVariable *v;
    size_t left;
    if (vr > PMD_VR_MAX || pmd_variable_of_vr[vr] < 0)
        return 0;
    v = &pmd_variables[pmd_variable_of_vr[vr]];
    if (v->family != VAR_memory_data)
        return 0;
    left = (size_t)(PMD_BATCH_WORDS - v->index);     /* memory.data[index + 1] .. [64] */
    return n < left ? n : left;
}

/* What pmd_set_integer does for each of the n elements in turn, at once: the
 * elements are one variable row (variables.csv, memory.data[64]), so the
 * first's type and causality are every one's (a refusal names the first, as
 * the per-value path would), each word passes the same range check (which no
 * 32-bit value fails: the compiler may drop the loop), and applying stores the
 * words' 32 bits, as pmd_int32 does one by one. */
PmdStatus pmd_set_memory_data(PmdInstance *inst, const char *fn, unsigned vr, const void *words, int isSigned,
                              size_t n, int apply)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_INTEGER);
    size_t k;
    if (!v || !settable(inst, fn, v))
        return PMD_ERROR;
    if (v->family != VAR_memory_data || n > (size_t)(PMD_BATCH_WORDS - v->index))
        return unhandled(inst, fn, v, "block setter");     /* a caller that did not ask pmd_memory_data_span */
    if (!apply) {
        for (k = 0; k < n; k++) {
            int64_t value = isSigned ? (int64_t)((const int32_t *)words)[k] : (int64_t)((const uint32_t *)words)[k];
            if (!memory_word_fits(value))
                return out_of_range(inst, fn, &pmd_variables[pmd_variable_of_vr[vr + k]], (double)value,
                                    MEMORY_WORD_RANGE);
        }
        return PMD_OK;
    }
    memcpy(&inst->s.memoryData[v->index], words, n * sizeof *inst->s.memoryData);
    return PMD_OK;
}

/* FMI 3's host.word array, set whole by every host command (native/host_port.c), as one block:
 * what pmd_set_integer does for each of the n elements in turn, as pmd_set_memory_data does for
 * memory.data (the first's type and causality are every one's, each word passes the same range
 * check, which no UInt16 fails, and applying stores it), without a lookup and two switches per
 * word and pass: most of the FMU's share of an FMI 3 command before. */
PmdStatus pmd_set_host_words(PmdInstance *inst, const char *fn, unsigned vr, const uint16_t *words, size_t n,
                             int apply)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_INTEGER);
    size_t k;
    if (!v || !settable(inst, fn, v))
        return PMD_ERROR;
    if (v->family != VAR_host_word || n > (size_t)(PMD_BATCH_WORDS - v->index))
        return unhandled(inst, fn, v, "block setter");
    if (!apply) {
        for (k = 0; k < n; k++)
            if (!host_word_fits(words[k]))
                return out_of_range(inst, fn, &pmd_variables[pmd_variable_of_vr[vr + k]], (double)words[k],
                                    HOST_WORD_RANGE);
        return PMD_OK;
    }
    for (k = 0; k < n; k++)
        inst->s.hostWord[v->index + k] = words[k];
    return PMD_OK;
}

/* FMI 3's host.reply array, read whole by every host command that has a reply: the n words from
 * vr on as pmd_model2_get_integer reads them one by one (its 16 bits), with one lookup. */
PmdStatus pmd_get_host_reply(PmdInstance *inst, const char *fn, unsigned vr, uint16_t *words, size_t n)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_INTEGER);
    size_t k;
    if (!v)
        return PMD_ERROR;
    if (v->family != VAR_host_reply || n > (size_t)(PMD_BATCH_WORDS - v->index))
        return unhandled(inst, fn, v, "block getter");
    for (k = 0; k < n; k++)
        words[k] = (uint16_t)((uint32_t)inst->s.hostReply[v->index + k] & 0xFFFFu);
    return PMD_OK;
}

/* How many value references from vr[0] on are consecutive elements of
 * memory.data (at most n), a strobe's block (Chip.write_memory sets
 * memory.data[1..64] in one call); below 2 none: a lone element, and any
 * other order, takes the per-value path. */
static size_t memory_data_run(const unsigned vr[], size_t n)
{
    size_t span = pmd_memory_data_span(vr[0], n), run, k;
    unsigned differ = 0;
    if (span < 2)
        return span;
    for (k = 1; k < span; k++)          /* no early exit: a whole block compares in one vectorized pass */
        differ |= vr[k] ^ (unsigned)(vr[0] + k);
    if (!differ)
        return span;
    for (run = 1; vr[run] == vr[0] + run; run++)
        continue;                       /* ends before span: an element there differs */
    return run;
}

/* FMI 2's Integers from vr[0] on: a run of memory.data as one block
 * (pmd_set_memory_data: the same checks, messages and order as value by
 * value, without a lookup and two switches per word and pass), else one value. */
PmdStatus pmd_model2_set_integers(PmdInstance *inst, const char *fn, const unsigned vr[], size_t n,
                                  const int32_t value[], int apply, size_t *taken)
{
    size_t run = memory_data_run(vr, n);
    if (run > 1) {
        *taken = run;
        return pmd_set_memory_data(inst, fn, vr[0], value, 1, run, apply);
    }
    *taken = 1;
    return pmd_set_integer(inst, fn, vr[0], value[0], apply);
}

/* Whether an axis input may be set: not one the machine drives every cycle (docs/machine.md), which
 * would take the value back at the next cycle without a word. */
static int not_driven(PmdInstance *inst, const char *fn, const PmdVariable *v, unsigned signal)
{
    if (!inst->chip.machine || !(inst->chip.machine->axis[v->index].signals & signal))
        return 1;
    pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: value reference %u (%s) is driven every cycle by "
                     "the machine (its machine parameter) and cannot be set", fn, v->vr, v->name);
    return 0;
}

PmdStatus pmd_model2_set_boolean(PmdInstance *inst, const char *fn, unsigned vr, int value, int apply)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_BOOLEAN);
    if (!v || !settable(inst, fn, v))
        return PMD_ERROR;
    value = value != 0;
    switch (v->family) {
    case VAR_axis_positiveLimit:
    case VAR_axis_negativeLimit:
    case VAR_axis_home:
    case VAR_axis_index:
        if (!not_driven(inst, fn, v,
                        v->family == VAR_axis_positiveLimit   ? PMD_MACHINE_POSITIVE_LIMIT
                        : v->family == VAR_axis_negativeLimit ? PMD_MACHINE_NEGATIVE_LIMIT
                        : v->family == VAR_axis_home          ? PMD_MACHINE_HOME
                                                              : PMD_MACHINE_INDEX))
            return PMD_ERROR;
        break;
    default: break;
    }
    switch (v->family) {
    case VAR_loopback: if (apply) inst->chip.s.loopback = (uint8_t)value; break;
    case VAR_axis_positiveLimit: if (apply) AXIS_OF(v)->positiveLimitInput = (uint8_t)value; break;
    case VAR_axis_negativeLimit: if (apply) AXIS_OF(v)->negativeLimitInput = (uint8_t)value; break;
    case VAR_axis_home: if (apply) AXIS_OF(v)->homeInput = (uint8_t)value; break;
    case VAR_axis_index: if (apply) AXIS_OF(v)->indexInput = (uint8_t)value; break;
    case VAR_record_enabled:
        /* recording needs its buffer: allocated by the check, so that applying cannot fail */
        if (!apply)
            return value ? pmd_record_allocate(inst, fn) : PMD_OK;
        inst->s.recordEnabled = (uint8_t)value;
        break;
    default: return unhandled(inst, fn, v, "Boolean setter");
    }
    return PMD_OK;
}

PmdStatus pmd_model_get_string(PmdInstance *inst, const char *fn, unsigned vr, const char **value)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_STRING);
    if (!v)
        return PMD_ERROR;
    switch (v->family) {
    case VAR_script: *value = pmd_script_value(inst); break;
    case VAR_machine: *value = inst->machinePath ? inst->machinePath : ""; break;
    case VAR_record_columns: *value = inst->columns.text ? inst->columns.text : ""; break;
    default: return unhandled(inst, fn, v, "String getter");
    }
    return PMD_OK;
}

PmdStatus pmd_model_set_string(PmdInstance *inst, const char *fn, unsigned vr, const char *value, int apply)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_STRING);
    char *copy;
    if (!v || !settable(inst, fn, v))
        return PMD_ERROR;
    if (v->family != VAR_script && v->family != VAR_machine && v->family != VAR_record_columns)
        return unhandled(inst, fn, v, "String setter");
    if (!value) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: %s: the value is NULL", fn, v->name);
        return PMD_ERROR;
    }
    if (v->family == VAR_record_columns)
        return pmd_record_columns_set(inst, fn, value, apply);
    if (!apply)
        return PMD_OK;
    copy = (char *)malloc(strlen(value) + 1);
    if (!copy) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: out of host memory", fn);
        return PMD_ERROR;
    }
    strcpy(copy, value);
    if (v->family == VAR_machine) {
        free(inst->machinePath);
        inst->machinePath = copy;
        return PMD_OK;
    }
    free(inst->scriptPath);
    inst->scriptPath = copy;
    return PMD_OK;
}

PmdStatus pmd_model3_get_binary(PmdInstance *inst, const char *fn, unsigned vr, const unsigned char **value,
                                size_t *size)
{
    const PmdVariable *v = lookup(inst, fn, vr, PMD_BINARY);
    if (!v)
        return PMD_ERROR;
    switch (v->family) {
    case VAR_record_data:
        /* little-endian int32 words as this platform stores them */
        pmd_record_data(inst, value, size);
        break;
    default: return unhandled(inst, fn, v, "Binary getter");
    }
    return PMD_OK;
}
