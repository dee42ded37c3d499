/* SPDX-License-Identifier: BSD-2-Clause */
/* Fuzz target: sequences of legal operations.
 *
 * The other targets feed random words and random FMI calls, and mostly meet
 * refusals. The bugs found by review were reached by short sequences of legal
 * calls, so this target decodes its input as such a sequence:
 *
 *   input     = version byte (bit 0: FMI 3, else FMI 2), then operations
 *   operation = one byte choosing a row of OPS[] below, then that row's
 *               arguments, each read by the byte reader (byte, below, value)
 *
 * Chip commands go through the FMU's host port (host.word, host.wordCount, a new
 * host.strobe, then a get executes the batch, unless the operation leaves it
 * pending for the next doStep); their arguments come from the command table
 * (pmd_commands[]: field kinds and widths), with a bias to boundary values
 * (value()). The instance starts initialized with the default parameters.
 *
 * Properties, checked after every call (property_*() below; abort() on a
 * violation, so that libFuzzer reports it):
 *   - no sanitizer report: the build uses ASan, UBSan (float-cast-overflow
 *     too) and -DPMD_CHECK_INVARIANTS (pmd_memory_store aborts on a write
 *     outside the memory);
 *   - a legal call succeeds, an illegal one returns Error;
 *   - a call that returned Error changed nothing: the serialized FMU state
 *     before and after it are equal, byte for byte;
 *   - a restored state replays identically: save, run k cycles and read every
 *     output, restore (the state is then the saved one, byte for byte), run
 *     the same steps: the same outputs and the same serialized state
 *     (op_replay). The stack is painted anew before every call (paint_stack),
 *     so that uninitialized bytes in the state show as a difference;
 *   - recording (op_columns, op_lend, op_record_data): record.columns and
 *     record.rowSize read back as set, a refused value leaves both as they
 *     were; memory lent by pmdfmu_fmi2/3SetRecordBuffer is written only
 *     inside the bytes lent, and only while lent (the rest of the fuzzer's
 *     area, guard bytes, is checked after every call); record.data holds
 *     whole rows of the last step that ran, of consecutive chip times, in the
 *     memory lent if it was lent then;
 *   - memory.data set as a block (op_memory_block) reads back as set, word by
 *     word, as a master setting it value by value would leave it.
 *
 * fuzz/sequence_inputs.py encodes the hand-built seeds and regression inputs
 * in this format (it reads OPS[] from this file; tests/test_determinism.py checks
 * that every operation has its encoder and a saved input). FUZZ_SEQUENCE_TRACE=1 prints every
 * call as it runs (to turn a crash file into a reproduction). To look past a
 * known finding while it is being fixed: FUZZ_SEQUENCE_SKIP lists operation
 * names to leave out (comma-separated), FUZZ_SEQUENCE_KNOWN text that a
 * violation's message or the FMU's last error contains ('|'-separated): such an
 * input ends quietly instead of aborting. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fmi2Functions.h"
#include "fmi3Functions.h"
#include "command_table.h"
#include "instance.h"
#include "plant_variables.h"
#include "state_fields.h"
#include "variables.h"
#include "variables3.h"

enum { OK = 0, ERROR = 3 };          /* fmi2Status and fmi3Status agree on these */

#define CYCLE_BUDGET 1500000         /* chip cycles (estimated) one input may run outside fast-forward: a replay
                                        runs them twice, ~4 s under ASan, well inside run.py's timeout */
#define MAX_MEMORY 0x10000           /* memorySize the fuzzer sets: every call may snapshot the memory */
#define MAX_CAPACITY (1 << 17)       /* record.capacity it sets: ASan poisons a new record.data block whole */
#define LEND_AREA 0x8000             /* bytes of the memory it may lend (op_lend), guard bytes around the loan */
#define PAINT 0xA5                   /* what the lend area holds where the FMU has no loan */
#define MAX_COLUMNS 8                /* names of a record.columns value it sets */
#define DEFAULT_ROW_BYTES (4 * PMD_RECORD_WORDS)     /* a row of record.columns "" */

/* pmdfmu's extensions (fmi/record_fmi2.c, record_fmi3.c, docs/performance.md "Recording"): no header declares them */
fmi2Status pmdfmu_fmi2GetRecordData(fmi2Component c, const void **data, size_t *size);
fmi2Status pmdfmu_fmi2SetRecordBuffer(fmi2Component c, void *rows, size_t size);
fmi3Status pmdfmu_fmi3SetRecordBuffer(fmi3Instance c, void *rows, size_t size);

static int tracing;                  /* FUZZ_SEQUENCE_TRACE */
static const char *known;            /* FUZZ_SEQUENCE_KNOWN */
static char last_error[1024];        /* the FMU's last error message */
static jmp_buf known_finding;        /* where a known finding ends the input */

static void say(const char *format, ...)
{
    va_list args;
    if (!tracing)
        return;
    va_start(args, format);
    vfprintf(stderr, format, args);
    va_end(args);
}

/* Whether text contains one of the '|'-separated parts of FUZZ_SEQUENCE_KNOWN. */
static int is_known(const char *text)
{
    const char *part = known;
    while (part && *part) {
        const char *end = strchr(part, '|');
        size_t n = end ? (size_t)(end - part) : strlen(part);
        char needle[256];
        if (n && n < sizeof needle) {
            memcpy(needle, part, n);
            needle[n] = '\0';
            if (strstr(text, needle))
                return 1;
        }
        part = end ? end + 1 : NULL;
    }
    return 0;
}

static void fail(const char *format, ...)
{
    char message[1024];
    va_list args;
    va_start(args, format);
    vsnprintf(message, sizeof message, format, args);
    va_end(args);
    if (is_known(message) || is_known(last_error)) {
        say("known finding: %s (%s)\n", message, last_error);
        longjmp(known_finding, 1);
    }
    fprintf(stderr, "\nfuzz_sequence: property violated: %s\n", message);
    if (last_error[0])
        fprintf(stderr, "fuzz_sequence: the FMU's last error: %s\n", last_error);
    abort();
}

/* ---- the byte reader ------------------------------------------------------- */

typedef struct {
    const uint8_t *p;
    size_t n;
} Reader;

static unsigned byte(Reader *r)       /* 0 once the input is used up */
{
    if (!r->n)
        return 0;
    r->n--;
    return *r->p++;
}

static unsigned below(Reader *r, unsigned n) { return byte(r) % n; }

static uint32_t bytes(Reader *r, int count)   /* big-endian */
{
    uint32_t v = 0;
    while (count--)
        v = v << 8 | byte(r);
    return v;
}

/* ---- the FMU under test ------------------------------------------------------ */

typedef struct {
    uint8_t *p;
    size_t n, capacity;
} Bytes;

typedef struct {
    void *state;          /* an fmi2FMUstate or fmi3FMUState */
    double t;
} Slot;

typedef struct {
    int fmi3;
    void *c;              /* fmi2Component or fmi3Instance */
    double t;             /* the current communication point, as a master tracks it */
    int64_t budget;       /* CYCLE_BUDGET minus the cycles run so far */
    Slot slot[2];         /* states saved by op_save */
    void *probe;          /* the state object the properties snapshot into */
    void *saved, *restored;   /* op_replay's and op_restore's states (here: freed after a known finding) */
    /* recording as the sequence set it up (the FMU's getters are checked against it) */
    int lending;          /* lendArea[lentAt, lentAt + lentSize) is lent to the FMU */
    size_t lentAt, lentSize;
    char columns[MAX_COLUMNS * 64];   /* record.columns as last set ("" after a reset) */
    uint32_t rowBytes;    /* record.rowSize it makes */
    uint32_t stepRowBytes;    /* record.rowSize at the last step that ran: record.data's rows */
    int scripted;         /* a script runs (its Reset or SetTime may make record.data's chip times jump) */
} Fuzz;

static unsigned char lendArea[LEND_AREA];

static Bytes before, after;          /* serialized states around a call that may fail */

static void reserve(Bytes *b, size_t n)
{
    if (b->capacity < n) {
        b->p = (uint8_t *)realloc(b->p, n);
        if (!b->p)
            abort();
        b->capacity = n;
    }
}

static void append(Bytes *b, const void *data, size_t n)
{
    reserve(b, b->n + n);
    memcpy(b->p + b->n, data, n);
    b->n += n;
}

/* The instance behind the FMI handle (the shells fmi2.c and fmi3.c both keep it first).
 * The fuzzer reads it only to size its steps (memory size, cycle time, whether
 * the chip idles) and to name a changed field, never to decide a property. */
static const PmdInstance *instance(const Fuzz *f) { return *(PmdInstance *const *)f->c; }
static double cycle_time(const PmdInstance *inst) { return pmd_grid(&inst->s, &inst->chip.s).cycleTime; }

/* Value references by name, from the generated variable table. */
static unsigned vr(const char *name)
{
    int i;
    for (i = 0; i < PMD_VARIABLE_COUNT; i++)
        if (strcmp(pmd_variables[i].name, name) == 0)
            return pmd_variables[i].vr;
    fail("no variable %s", name);
    return 0;
}

static const char *vr_name(unsigned v)
{
    return v <= PMD_VR_MAX && pmd_variable_of_vr[v] >= 0 ? pmd_variables[pmd_variable_of_vr[v]].name : "?";
}

static struct {
    unsigned time, cycleTime, memorySize, loopback, script, machine, recordEnabled, recordCapacity;
    unsigned recordData, recordColumns, recordRowSize;
    unsigned hostWord, hostWordCount, hostStrobe, hostReply, hostReplyCount, hostError;
    unsigned memoryAddress, memoryCount, memoryStrobe, memoryData, chipTime;
    unsigned actualPosition, positiveLimit, negativeLimit, home;   /* of axis 1; + 100 per axis */
} VR;

static void find_value_references(void)
{
    VR.time = vr("time");
    VR.cycleTime = vr("cycleTime");
    VR.memorySize = vr("memorySize");
    VR.loopback = vr("loopback");
    VR.script = vr("script");
    VR.machine = vr("machine");
    VR.recordEnabled = vr("record.enabled");
    VR.recordCapacity = vr("record.capacity");
    VR.recordData = vr("record.data");
    VR.recordColumns = vr("record.columns");
    VR.recordRowSize = vr("record.rowSize");
    VR.hostWord = vr("host.word[1]");
    VR.hostWordCount = vr("host.wordCount");
    VR.hostStrobe = vr("host.strobe");
    VR.hostReply = vr("host.reply[1]");
    VR.hostReplyCount = vr("host.replyCount");
    VR.hostError = vr("host.error");
    VR.memoryAddress = vr("memory.address");
    VR.memoryCount = vr("memory.count");
    VR.memoryStrobe = vr("memory.strobe");
    VR.memoryData = vr("memory.data[1]");
    VR.chipTime = vr("chipTime");
    VR.actualPosition = vr("axis1.actualPosition");
    VR.positiveLimit = vr("axis1.positiveLimit");
    VR.negativeLimit = vr("axis1.negativeLimit");
    VR.home = vr("axis1.home");
}

/* ---- FMI 2 and FMI 3 behind one set of calls ---------------------------------- */

static void logger2(fmi2ComponentEnvironment e, fmi2String name, fmi2Status s, fmi2String category,
                    fmi2String message, ...)
{
    (void)e; (void)name;
    if (s == fmi2Error)
        snprintf(last_error, sizeof last_error, "%s", message);
    if (tracing)
        fprintf(stderr, "    log %d [%s] %s\n", (int)s, category, message);   /* '%' arrives doubled */
}

static void logger3(fmi3InstanceEnvironment e, fmi3Status s, fmi3String category, fmi3String message)
{
    (void)e;
    if (s == fmi3Error)
        snprintf(last_error, sizeof last_error, "%s", message);
    if (tracing)
        fprintf(stderr, "    log %d [%s] %s\n", (int)s, category, message);
}

static const fmi2CallbackFunctions callbacks2 = {logger2, NULL, NULL, NULL, NULL};

static const PmdVariable3 *variable3(unsigned v)
{
    if (v > PMD_VR3_MAX || pmd_variable3_of_vr[v] < 0)
        fail("value reference %u is no FMI 3 variable", v);
    return &pmd_variables3[pmd_variable3_of_vr[v]];
}

/* n values from value reference v on (FMI 2: the scalars v .. v+n-1; FMI 3:
 * the variable v, whose other array elements are set to 0). */
static int set_ints(Fuzz *f, unsigned v, size_t n, const int64_t *x)
{
    size_t i;
    say("  set %s", vr_name(v));
    for (i = 0; i < n && i < 8; i++)
        say(" %lld", (long long)x[i]);
    say("%s\n", n > 8 ? " ..." : "");
    if (!f->fmi3) {
        fmi2ValueReference vrs[PMD_BATCH_WORDS];
        fmi2Integer values[PMD_BATCH_WORDS];
        for (i = 0; i < n; i++) {
            vrs[i] = v + (unsigned)i;
            values[i] = pmd_int32((uint32_t)x[i]);
        }
        return fmi2SetInteger(f->c, vrs, n, values);
    } else {
        const PmdVariable3 *var = variable3(v);
        fmi3ValueReference ref = v;
        union { fmi3Int32 i32[PMD_BATCH_WORDS]; fmi3UInt32 u32[PMD_BATCH_WORDS]; fmi3UInt16 u16[PMD_BATCH_WORDS]; } u;
        memset(&u, 0, sizeof u);
        for (i = 0; i < n && i < var->count; i++) {
            u.i32[i] = pmd_int32((uint32_t)x[i]);     /* overwritten below for the other types */
            if (var->type == PMD3_UINT32)
                u.u32[i] = (uint32_t)x[i];
        }
        if (var->type == PMD3_UINT16) {
            memset(&u, 0, sizeof u);
            for (i = 0; i < n && i < var->count; i++)
                u.u16[i] = (uint16_t)x[i];
            return fmi3SetUInt16(f->c, &ref, 1, u.u16, var->count);
        }
        return var->type == PMD3_UINT32 ? fmi3SetUInt32(f->c, &ref, 1, u.u32, var->count)
                                        : fmi3SetInt32(f->c, &ref, 1, u.i32, var->count);
    }
}

static int set_int(Fuzz *f, unsigned v, int64_t x) { return set_ints(f, v, 1, &x); }

/* Reads n values from v on (FMI 3: all of variable v's elements, n of them kept). */
static int get_ints(Fuzz *f, unsigned v, size_t n, int64_t *x)
{
    size_t i;
    int s;
    say("  get %s\n", vr_name(v));
    if (!f->fmi3) {
        fmi2ValueReference vrs[PMD_BATCH_WORDS];
        fmi2Integer values[PMD_BATCH_WORDS];
        for (i = 0; i < n; i++)
            vrs[i] = v + (unsigned)i;
        s = fmi2GetInteger(f->c, vrs, n, values);
        for (i = 0; i < n; i++)
            x[i] = values[i];
    } else {
        const PmdVariable3 *var = variable3(v);
        fmi3ValueReference ref = v;
        union { fmi3Int32 i32[PMD_BATCH_WORDS]; fmi3UInt32 u32[PMD_BATCH_WORDS]; fmi3UInt16 u16[PMD_BATCH_WORDS]; } u;
        memset(&u, 0, sizeof u);
        s = var->type == PMD3_UINT16   ? fmi3GetUInt16(f->c, &ref, 1, u.u16, var->count)
            : var->type == PMD3_UINT32 ? fmi3GetUInt32(f->c, &ref, 1, u.u32, var->count)
                                       : fmi3GetInt32(f->c, &ref, 1, u.i32, var->count);
        for (i = 0; i < n; i++)
            x[i] = var->type == PMD3_UINT16 ? (int64_t)u.u16[i]
                   : var->type == PMD3_UINT32 ? (int64_t)u.u32[i] : (int64_t)u.i32[i];
    }
    return s;
}

static int set_bool(Fuzz *f, unsigned v, int x)
{
    say("  set %s %d\n", vr_name(v), x);
    if (!f->fmi3) {
        fmi2Boolean b = x;
        return fmi2SetBoolean(f->c, &v, 1, &b);
    } else {
        fmi3Boolean b = x != 0;
        return fmi3SetBoolean(f->c, &v, 1, &b, 1);
    }
}

static int set_real(Fuzz *f, unsigned v, double x)
{
    say("  set %s %.17g\n", vr_name(v), x);
    if (!f->fmi3)
        return fmi2SetReal(f->c, &v, 1, &x);
    return fmi3SetFloat64(f->c, &v, 1, &x, 1);
}

static int do_step(Fuzz *f, double t, double h)
{
    say("  doStep(%.17g, %.17g)\n", t, h);
    if (!f->fmi3)
        return fmi2DoStep(f->c, t, h, fmi2False);
    {
        fmi3Boolean event, terminate, early;
        fmi3Float64 last;
        return fmi3DoStep(f->c, t, h, fmi3False, &event, &terminate, &early, &last);
    }
}

/* The instance as instantiated: nothing lent (the FMU forgets the loan), record.columns "". */
static void forget_recording(Fuzz *f)
{
    f->lending = 0;
    memset(lendArea, PAINT, sizeof lendArea);
    f->columns[0] = '\0';
    f->rowBytes = DEFAULT_ROW_BYTES;
    f->scripted = 0;
}

static int reset(Fuzz *f)
{
    int s;
    say("  reset\n");
    s = f->fmi3 ? fmi3Reset(f->c) : fmi2Reset(f->c);
    if (s == OK)
        forget_recording(f);
    return s;
}
static int terminate(Fuzz *f) { say("  terminate\n"); return f->fmi3 ? fmi3Terminate(f->c) : fmi2Terminate(f->c); }
static int exit_initialization(Fuzz *f)
{
    say("  exitInitializationMode\n");
    return f->fmi3 ? fmi3ExitInitializationMode(f->c) : fmi2ExitInitializationMode(f->c);
}

static int enter_initialization(Fuzz *f, double start)
{
    say("  enterInitializationMode(start %.17g)\n", start);
    if (f->fmi3)
        return fmi3EnterInitializationMode(f->c, fmi3False, 0, start, fmi3False, 0);
    if (fmi2SetupExperiment(f->c, fmi2False, 0, start, fmi2False, 0) != fmi2OK)
        return ERROR;
    return fmi2EnterInitializationMode(f->c);
}

static int get_state(Fuzz *f, void **state)
{
    return f->fmi3 ? fmi3GetFMUState(f->c, state) : fmi2GetFMUstate(f->c, state);
}

static int set_state(Fuzz *f, void *state)
{
    say("  setFMUState\n");
    return f->fmi3 ? fmi3SetFMUState(f->c, state) : fmi2SetFMUstate(f->c, state);
}

static void free_state(Fuzz *f, void **state)
{
    if (*state && (f->fmi3 ? fmi3FreeFMUState(f->c, state) : fmi2FreeFMUstate(f->c, state)) != OK)
        fail("freeing an FMU state failed");
    *state = NULL;
}

/* The serialized bytes of a state object. */
static int serialize(Fuzz *f, void *state, Bytes *out)
{
    size_t size = 0;
    int s = f->fmi3 ? fmi3SerializedFMUStateSize(f->c, state, &size) : fmi2SerializedFMUstateSize(f->c, state, &size);
    if (s != OK)
        return s;
    reserve(out, size);
    out->n = size;
    return f->fmi3 ? fmi3SerializeFMUState(f->c, state, out->p, size)
                   : fmi2SerializeFMUstate(f->c, state, (fmi2Byte *)out->p, size);
}

static int deserialize(Fuzz *f, const Bytes *in, void **state)
{
    say("  deserializeFMUState(%zu bytes)\n", in->n);
    return f->fmi3 ? fmi3DeserializeFMUState(f->c, in->p, in->n, state)
                   : fmi2DeSerializeFMUstate(f->c, (const fmi2Byte *)in->p, in->n, state);
}

/* ---- the properties, in one place -------------------------------------------- */

/* The whole FMU state as bytes, through the FMU's own API. */
static void snapshot(Fuzz *f, Bytes *out)
{
    if (get_state(f, &f->probe) != OK || serialize(f, f->probe, out) != OK)
        fail("getting and serializing the FMU state failed");
}

/* The declared field whose bytes hold image offset `at`, named by the walk. */
typedef struct {
    size_t at;
    char path[sizeof(((PmdStateLeaf *)0)->path)];
    size_t offset;
} FieldAt;

static int field_at(const PmdStateLeaf *leaf, void *context)
{
    FieldAt *w = (FieldAt *)context;
    if (w->at < leaf->offset || w->at >= leaf->offset + leaf->size)
        return 0;
    memcpy(w->path, leaf->path, sizeof w->path);
    w->offset = leaf->offset;
    return 1;
}

/* NULL if two snapshots are equal, else where they first differ (a declared
 * field, a memory word, the size or the header). */
static const char *difference(const Fuzz *f, const Bytes *a, const Bytes *b)
{
    static char where[160];
    size_t header = a->n - sizeof(PmdStateImage) - (size_t)instance(f)->s.memorySize * sizeof(uint32_t), i, at;
    FieldAt w;
    if (a->n == b->n && memcmp(a->p, b->p, a->n) == 0)
        return NULL;
    if (a->n != b->n) {
        snprintf(where, sizeof where, "the sizes, %zu and %zu bytes", a->n, b->n);
        return where;
    }
    for (i = header; i < a->n && a->p[i] == b->p[i]; i++)
        ;
    if (i == a->n)
        return "the header only";
    at = i - header;
    if (at >= sizeof(PmdStateImage)) {
        snprintf(where, sizeof where, "memory word 0x%zX", (at - sizeof(PmdStateImage)) / 4);
        return where;
    }
    w.at = at;
    if (pmd_state_walk(1, field_at, &w))
        snprintf(where, sizeof where, "%s + %zu: 0x%02X, then 0x%02X", w.path, at - w.offset, a->p[i], b->p[i]);
    else
        snprintf(where, sizeof where, "padding at image offset %zu: 0x%02X, then 0x%02X", at, a->p[i], b->p[i]);
    return where;
}

typedef enum { MUST_SUCCEED, MAY_FAIL, MUST_FAIL } Expect;

/* Fills the stack below the caller with a new byte each call: uninitialized
 * stack bytes that reach the FMU state (struct padding of a local copied in)
 * then differ between a run and its replay, and the properties see them. */
static void paint_stack(void)
{
    static unsigned char paint;
    volatile unsigned char area[16384];
    memset((void *)area, ++paint, sizeof area);
}

static Expect property_before(Fuzz *f, Expect expect)
{
    if (expect != MUST_SUCCEED)
        snapshot(f, &before);
    paint_stack();
    return expect;
}

/* The lend area as the FMU must leave it outside a loan: PAINT throughout. */
static unsigned char painted[LEND_AREA];

/* The FMU wrote into the lend area only inside the loan (the memory it may write into). */
static void property_lent(const Fuzz *f, const char *call)
{
    size_t from = f->lending ? f->lentAt : LEND_AREA, to = f->lending ? f->lentAt + f->lentSize : LEND_AREA, i;
    if (memcmp(lendArea, painted, from) == 0 && memcmp(lendArea + to, painted, LEND_AREA - to) == 0)
        return;
    for (i = 0; i < LEND_AREA && ((i >= from && i < to) || lendArea[i] == PAINT); i++)
        ;
    fail("%s wrote byte %zu of the lend area (0x%02X), outside the %zu bytes lent at %zu%s", call, i, lendArea[i],
         to - from, from, f->lending ? "" : " (nothing is lent)");
}

/* A legal call succeeds; an illegal one fails; a failed one changed nothing. */
static int property_after(Fuzz *f, Expect expect, const char *call, int status)
{
    say("    -> %d\n", status);
    property_lent(f, call);
    if (expect == MUST_SUCCEED && status != OK)
        fail("%s returned %d, but the call is legal", call, status);
    if (expect == MUST_FAIL && status != ERROR)
        fail("%s returned %d, but the call is illegal", call, status);
    if (status == ERROR) {
        const char *where;
        snapshot(f, &after);
        if ((where = difference(f, &before, &after)) != NULL)
            fail("%s returned Error but changed the FMU state (first in %s)", call, where);
    }
    return status;
}

/* Every FMI call of the operations goes through CALL; expect is evaluated
 * once, before the call (it may look at the instance). */
static Expect expecting;
#define CALL(f, expect, call) \
    (expecting = property_before(f, expect), property_after(f, expecting, #call, (call)))

/* Every output as bytes; record.data (FMI 3) only with record: it is not part
 * of the FMU state (a restore empties it), so it is compared only after a
 * step that ran. */
static void read_outputs(Fuzz *f, Bytes *out, int record)
{
    int i;
    if (!f->fmi3) {
        fmi2ValueReference ints[PMD_VARIABLE_COUNT], reals[PMD_VARIABLE_COUNT], bools[PMD_VARIABLE_COUNT];
        fmi2Integer iv[PMD_VARIABLE_COUNT];
        fmi2Real rv[PMD_VARIABLE_COUNT];
        fmi2Boolean bv[PMD_VARIABLE_COUNT];
        size_t ni = 0, nr = 0, nb = 0;
        for (i = 0; i < PMD_VARIABLE_COUNT; i++) {
            const PmdVariable *v = &pmd_variables[i];
            if (v->causality != PMD_OUTPUT)
                continue;
            if (v->type == PMD_INTEGER)
                ints[ni++] = v->vr;
            else if (v->type == PMD_REAL)
                reals[nr++] = v->vr;
            else if (v->type == PMD_BOOLEAN)
                bools[nb++] = v->vr;
        }
        if (fmi2GetInteger(f->c, ints, ni, iv) != fmi2OK || fmi2GetReal(f->c, reals, nr, rv) != fmi2OK ||
            fmi2GetBoolean(f->c, bools, nb, bv) != fmi2OK)
            fail("reading the outputs failed");
        append(out, iv, ni * sizeof *iv);
        append(out, rv, nr * sizeof *rv);
        append(out, bv, nb * sizeof *bv);
        return;
    }
    for (i = 0; i < PMD_VARIABLE3_COUNT; i++) {
        const PmdVariable3 *v = &pmd_variables3[i];
        fmi3ValueReference ref = v->vr;
        union {
            fmi3Float64 d[64]; fmi3Int32 i32[64]; fmi3UInt32 u32[64]; fmi3UInt16 u16[64]; fmi3Int16 i16[64];
            fmi3Boolean b[64];
        } u;
        size_t size = 0;
        fmi3Binary binary = NULL;
        int s;
        if (pmd_variables[pmd_variable_of_vr[v->vr]].causality != PMD_OUTPUT || (v->type == PMD3_BINARY && !record))
            continue;
        memset(&u, 0, sizeof u);
        switch (v->type) {
        case PMD3_FLOAT64: s = fmi3GetFloat64(f->c, &ref, 1, u.d, v->count); break;
        case PMD3_INT32: s = fmi3GetInt32(f->c, &ref, 1, u.i32, v->count); break;
        case PMD3_UINT32: s = fmi3GetUInt32(f->c, &ref, 1, u.u32, v->count); break;
        case PMD3_UINT16: s = fmi3GetUInt16(f->c, &ref, 1, u.u16, v->count); break;
        case PMD3_INT16: s = fmi3GetInt16(f->c, &ref, 1, u.i16, v->count); break;
        case PMD3_BOOLEAN: s = fmi3GetBoolean(f->c, &ref, 1, u.b, v->count); break;
        default: s = fmi3GetBinary(f->c, &ref, 1, &size, &binary, 1); break;
        }
        if (s != OK)
            fail("reading output %s failed", v->name);
        append(out, &u, sizeof u);
        append(out, &size, sizeof size);
        if (size)
            append(out, binary, size);
    }
}

/* ---- stepping within the budget ------------------------------------------------ */

/* Whether fast-forward skips any number of cycles in O(1): every axis idles,
 * nothing per-cycle is armed, no script step is due. */
static int chip_quiet(const PmdInstance *inst)
{
    const PmdChipState *s = &inst->chip.s;
    int n;
    if (inst->s.scriptNext < inst->script.count || s->trace.active || s->trace.start)
        return 0;
    if (inst->chip.machine)                  /* a machine's axes run every cycle (PmdRunFacts) */
        return 0;
    for (n = 0; n < PMD_AXES; n++) {
        const PmdAxis *ax = &s->axis[n];
        if (ax->motion != PMD_MOTION_IDLE || ax->motionCompletePending || ax->breakpoint[0].trigger ||
            ax->breakpoint[1].trigger)
            return 0;
    }
    return 1;
}

/* Whether doStep may run any number of cycles in O(1): the chip is quiet and nothing records. */
static int chip_idle(const PmdInstance *inst)
{
    return !inst->s.recordEnabled && chip_quiet(inst);
}

/* The pending host batch (written, not yet executed): the smallest
 * SetSampleTime in it (microseconds, 0 if none), and whether every command
 * in it leaves an idle chip idle. */
static int pending_batch(const PmdInstance *inst, int *harmless)
{
    int i = 0, smallest = 0;
    *harmless = 1;
    if (inst->s.hostStrobe == inst->s.hostAck)
        return 0;
    while (i < inst->s.hostWordCount) {
        int index = pmd_command_of_opcode[inst->s.hostWord[i] & 0xFF];
        const PmdCommand *c = index >= 0 ? &pmd_commands[index] : NULL;
        if (!c)
            break;
        if (strcmp(c->name, "SetSampleTime") == 0 && i + 1 < inst->s.hostWordCount) {
            int us = inst->s.hostWord[i + 1] & 0xFFFF;
            if (us && (!smallest || us < smallest))
                smallest = us;
        } else if (strncmp(c->name, "Get", 3) != 0 && strcmp(c->name, "NoOperation") != 0) {
            *harmless = 0;
        }
        i += 1 + c->argWords;
    }
    return smallest;
}

/* A step size, in cycles of the current grid (a kind byte and a 2-byte
 * payload p): 1, 2 + p % 8, 10 + p % 990, 1000 + 2p, p % 8 + 1/2,
 * record.capacity - 1 + p % 3, 2^e (e = 52 or 53 around doStep's limit of
 * 2^53 cycles for odd p, else 40 + p/2 % 24; only when the chip idles: else a
 * legal step could run for hours, and it is 1 cycle), (p % 256 + 1) / 256. */
static double step_cycles(Fuzz *f, Reader *r, int allow_huge)
{
    const PmdInstance *inst = instance(f);
    unsigned kind = below(r, 8), p = bytes(r, 2);
    int harmless;
    switch (kind) {
    case 0: return 1;
    case 1: return 2 + p % 8;
    case 2: return 10 + p % 990;
    case 3: return 1000 + 2.0 * p;
    case 4: return p % 8 + 0.5;
    case 5: return (double)inst->recordCapacity - 1 + p % 3;
    case 6: {
        int e = p & 1 ? 53 - (int)(p >> 1 & 1) : 40 + (int)(p >> 1) % 24;
        pending_batch(inst, &harmless);
        return allow_huge && harmless && chip_idle(inst) ? ldexp(1, e) : 1;
    }
    default: return (p % 256 + 1) / 256.0;
    }
}

/* A machine's motors' internal steps per second, in the budget's units: 8 internal steps (a division
 * each) cost about a chip cycle. Whatever the sample time, a motor takes 1 / internalStep of them a
 * second. */
static double plant_rate(const PmdInstance *inst)
{
    double rate = 0;
    int n;
    for (n = 0; n < PMD_AXES; n++)
        if (inst->chip.machine && (inst->chip.machine->plantAxes & (1u << n)))
            rate += 1 / inst->chip.machine->axis[n].plant.internalStep / 8;
    return rate;
}

/* A doStep of `cycles` cycles of the current grid, made smaller if the cycles
 * it may run (at the smallest sample time a pending batch sets), and a machine's
 * motors' internal steps, exceed the budget. Returns the status; t advances unless it failed. */
static int step(Fuzz *f, double cycles)
{
    const PmdInstance *inst = instance(f);
    int harmless, pending = pending_batch(inst, &harmless);
    double h = cycles * cycle_time(inst), fastest = cycle_time(inst), estimate, motors = plant_rate(inst);
    int status;
    if (pending && pending * 1e-6 < fastest)
        fastest = pending * 1e-6;
    if (inst->s.scriptNext < inst->script.count)     /* the script may set any sample time */
        fastest = 1e-6;
    estimate = h / fastest + h * motors;
    /* a recording step of a quiet chip runs its rows one by one, the cycles past their room (a grid made
     * finer inside the step) as an unrecorded step runs them: fast-forwarded */
    if (inst->s.recordEnabled && harmless && chip_quiet(inst) && estimate > (double)inst->recordCapacity)
        estimate = inst->recordCapacity;
    if (estimate > (double)f->budget && !(harmless && chip_idle(inst))) {
        estimate = f->budget > 1 ? (double)f->budget : 1;
        h = motors > 0 ? estimate / (1 / fastest + motors) : estimate * fastest;
    }
    if (!(h > 0))
        h = fastest;
    f->budget -= estimate < (double)f->budget ? (int64_t)estimate : f->budget;
    status = CALL(f, MAY_FAIL, do_step(f, f->t, h));
    if (status < ERROR) {                            /* OK, or a Warning: the step ran */
        f->t += h;
        f->stepRowBytes = f->rowBytes;
    }
    return status;
}

/* ---- the host port -------------------------------------------------------------- */

typedef struct {
    uint16_t word[PMD_BATCH_WORDS];
    int n, replies;
} Batch;

static const PmdCommand *command(const char *name)
{
    int i;
    for (i = 0; i < PMD_COMMAND_COUNT; i++)
        if (strcmp(pmd_commands[i].name, name) == 0)
            return &pmd_commands[i];
    fail("no command %s in the table", name);
    return NULL;
}

/* Executes the pending port writes and reads the batch's answer. */
static void execute(Fuzz *f)
{
    int64_t count = 0, error = 0, reply[PMD_BATCH_WORDS];
    CALL(f, MUST_SUCCEED, get_ints(f, VR.hostError, 1, &error));
    CALL(f, MUST_SUCCEED, get_ints(f, VR.hostReplyCount, 1, &count));
    CALL(f, MUST_SUCCEED, get_ints(f, VR.hostReply, PMD_BATCH_WORDS, reply));
    say("    host.error 0x%02llX, %lld reply words\n", (long long)error, (long long)count);
    if (count < 0 || count > PMD_BATCH_WORDS)
        fail("host.replyCount %lld", (long long)count);
}

/* Writes the batch to the host port as a host does: read the strobe (which
 * executes a batch still pending, as the protocol asks), the words, the count,
 * a new strobe; then reads the answer, unless the batch is left pending for
 * the next doStep or get. */
static void send(Fuzz *f, Batch *b, int pending)
{
    int64_t strobe = 0, words[PMD_BATCH_WORDS];
    int i;
    if (b->n == 0)
        return;
    CALL(f, MUST_SUCCEED, get_ints(f, VR.hostStrobe, 1, &strobe));
    for (i = 0; i < b->n; i++)
        words[i] = b->word[i];
    CALL(f, MUST_SUCCEED, set_ints(f, VR.hostWord, (size_t)b->n, words));
    CALL(f, MUST_SUCCEED, set_int(f, VR.hostWordCount, b->n));
    CALL(f, MUST_SUCCEED, set_int(f, VR.hostStrobe, strobe == INT32_MAX ? 0 : strobe + 1));
    if (!pending)
        execute(f);
    b->n = b->replies = 0;
}

/* Appends one command (arguments as the table's fields decode them); a full
 * batch is sent first. */
static void add(Fuzz *f, Batch *b, int axis, const PmdCommand *c, const int64_t *arg)
{
    uint16_t *w;
    int k;
    if (b->n + 1 + c->argWords > PMD_BATCH_WORDS || b->replies + c->replyWords > PMD_BATCH_WORDS)
        send(f, b, 0);
    w = &b->word[b->n];
    memset(w, 0, (size_t)(1 + c->argWords) * sizeof *w);
    w[0] = (uint16_t)(axis << 8 | c->opcode);
    for (k = 0; k < c->nArgs; k++)
        pmd_encode_field(&c->args[k], arg[k], w + 1);
    b->n += 1 + c->argWords;
    b->replies += c->replyWords;
    say("  cmd axis %d %s(", axis + 1, c->name);
    for (k = 0; k < c->nArgs; k++)
        say("%s%lld", k ? ", " : "", (long long)arg[k]);
    say(")\n");
}

#define CMD(f, b, axis, name, ...) add(f, b, axis, command(name), (const int64_t[PMD_MAX_FIELDS]){__VA_ARGS__})

/* ---- argument values ------------------------------------------------------------- */

/* A value in [lo, hi], biased to boundaries. Always 5 bytes, so that a
 * mutation of one value leaves the following ones in place: a selector byte,
 * then a 4-byte big-endian payload that some selectors use. The selector picks
 * lo, lo+1, hi, hi-1, 0, 1, the memory size M, M-1, M+1, M - (the payload's low
 * byte), a small value (the low byte, signed if lo < 0), or the payload (two's
 * complement if lo < 0). A value outside [lo, hi] wraps into it. */
static int64_t value(Fuzz *f, Reader *r, int64_t lo, int64_t hi)
{
    int64_t m = instance(f)->s.memorySize, v;
    unsigned selector = below(r, 16);
    uint32_t u = bytes(r, 4);
    switch (selector) {
    case 0: v = lo; break;
    case 1: v = lo + 1; break;
    case 2: v = hi; break;
    case 3: v = hi - 1; break;
    case 4: v = 0; break;
    case 5: v = 1; break;
    case 6: v = m; break;
    case 7: v = m - 1; break;
    case 8: v = m + 1; break;
    case 9: v = m - (u & 0xFF); break;
    case 10: v = lo < 0 ? (int8_t)(u & 0xFF) : (int64_t)(u & 0xFF); break;
    default: v = lo < 0 ? (int64_t)pmd_int32(u) : (int64_t)u; break;
    }
    if (v < lo || v > hi)
        v = lo + (int64_t)((uint64_t)(v - lo) % (uint64_t)(hi - lo + 1));
    return v;
}

/* The range a field of the command table can carry. */
static int64_t field_value(Fuzz *f, Reader *r, const PmdField *field)
{
    switch (field->kind) {
    case PMD_U16: return value(f, r, 0, 0xFFFF);
    case PMD_I16: return value(f, r, -0x8000, 0x7FFF);
    case PMD_U32: return value(f, r, 0, 0xFFFFFFFFLL);
    case PMD_I32: return value(f, r, INT32_MIN, INT32_MAX);
    default: return value(f, r, 0, (1 << field->width) - 1);
    }
}

#define I32(f, r) value(f, r, INT32_MIN, INT32_MAX)
#define POSITIVE31(f, r) value(f, r, 0, INT32_MAX)                  /* acceleration, jerk, ... */
#define ADDRESS(f, r) value(f, r, 0, instance(f)->s.memorySize)
#define BUFFER_ID(f, r) value(f, r, 0, PMD_BUFFERS - 1)

/* The flags byte every host operation starts with: bits 0-1 axis, bit 2
 * leave the (last) batch pending, bits 3-7 the operation's own. */
typedef struct {
    int axis, pending, bits;
} Flags;

static Flags flags(Reader *r)
{
    unsigned b = byte(r);
    Flags fl = {(int)(b & 3), (int)(b >> 2 & 1), (int)(b >> 3)};
    return fl;
}

/* ---- the operations --------------------------------------------------------------- */

/* Any command of the table, on any axis, with any arguments its fields carry. */
static void op_command(Fuzz *f, Reader *r)
{
    Flags fl = flags(r);
    const PmdCommand *c = &pmd_commands[below(r, PMD_COMMAND_COUNT)];
    int64_t arg[PMD_MAX_FIELDS] = {0};
    Batch b = {{0}, 0, 0};
    int k;
    for (k = 0; k < c->nArgs; k++)
        arg[k] = field_value(f, r, &c->args[k]);
    add(f, &b, fl.axis, c, arg);
    send(f, &b, fl.pending);
}

/* A buffer's start and length (in either order), and maybe a trajectory
 * function of the axis assigned to it. */
static void op_buffer(Fuzz *f, Reader *r)
{
    Flags fl = flags(r);
    int64_t id = BUFFER_ID(f, r), start = ADDRESS(f, r), length = ADDRESS(f, r);
    unsigned function = below(r, PMD_FUNCTIONS + 1);
    Batch b = {{0}, 0, 0};
    if (fl.bits & 1) {
        CMD(f, &b, fl.axis, "SetBufferLength", id, length);
        CMD(f, &b, fl.axis, "SetBufferStart", id, start);
    } else {
        CMD(f, &b, fl.axis, "SetBufferStart", id, start);
        CMD(f, &b, fl.axis, "SetBufferLength", id, length);
    }
    if (function < PMD_FUNCTIONS)
        CMD(f, &b, fl.axis, "SetBufferFunction", function, fl.bits & 2 ? -1 : id);
    send(f, &b, fl.pending);
}

/* WriteBuffer, n times. */
static void op_write_buffer(Fuzz *f, Reader *r)
{
    Flags fl = flags(r);
    int64_t id = BUFFER_ID(f, r);
    unsigned n = 1 + below(r, 32), i;
    Batch b = {{0}, 0, 0};
    for (i = 0; i < n; i++)
        CMD(f, &b, fl.axis, "WriteBuffer", id, I32(f, r));
    send(f, &b, fl.pending);
}

/* A read or write index, or ReadBuffer n times. */
static void op_buffer_index(Fuzz *f, Reader *r)
{
    Flags fl = flags(r);
    int64_t id = BUFFER_ID(f, r), index = ADDRESS(f, r);
    unsigned n, i;
    Batch b = {{0}, 0, 0};
    switch (fl.bits % 3) {
    case 0: CMD(f, &b, fl.axis, "SetBufferWriteIndex", id, index); break;
    case 1: CMD(f, &b, fl.axis, "SetBufferReadIndex", id, index); break;
    default:
        for (n = 1 + (unsigned)(index % 8), i = 0; i < n; i++)
            CMD(f, &b, fl.axis, "ReadBuffer", id);
    }
    send(f, &b, fl.pending);
}

/* A whole external profile: buffer 2 + f for each function f in the mask
 * (flags bits 3-7; position always), of length L at start + f L, filled with
 * L segments, then SetProfileMode(4) and Update. */
static void op_external_profile(Fuzz *f, Reader *r)
{
    Flags fl = flags(r);
    unsigned mask = 1u | (unsigned)fl.bits, length = 1 + below(r, 8), fn, i;
    int64_t start = ADDRESS(f, r);
    Batch b = {{0}, 0, 0};
    for (fn = 0; fn < PMD_FUNCTIONS; fn++) {
        int64_t id = PMD_FIRST_PROFILE_BUFFER + fn;
        if (!(mask >> fn & 1))
            continue;
        CMD(f, &b, fl.axis, "SetBufferStart", id, start + fn * length);
        CMD(f, &b, fl.axis, "SetBufferLength", id, length);
        CMD(f, &b, fl.axis, "SetBufferFunction", fn, id);
        for (i = 0; i < length; i++)          /* times 0..16, positions any, the rest moderate */
            CMD(f, &b, fl.axis, "WriteBuffer", id, fn == PMDBufferFunctionTime ? value(f, r, 0, 16)
                                                   : fn == 0 ? I32(f, r) : value(f, r, -0x40000, 0x40000));
    }
    CMD(f, &b, fl.axis, "SetProfileMode", PMDExternalProfile);
    CMD(f, &b, fl.axis, "Update", 0);
    send(f, &b, fl.pending);
}

/* A trapezoidal, velocity, S-curve or gear move (or an external Update
 * without set-up): the buffered registers in their legal ranges, then Update. */
static void op_move(Fuzz *f, Reader *r)
{
    Flags fl = flags(r);
    unsigned mode = below(r, 5);
    Batch b = {{0}, 0, 0};
    CMD(f, &b, fl.axis, "SetProfileMode", mode);
    CMD(f, &b, fl.axis, "SetPosition", I32(f, r));
    CMD(f, &b, fl.axis, "SetVelocity", mode == 1 || mode == 3 ? I32(f, r) : POSITIVE31(f, r));
    CMD(f, &b, fl.axis, "SetAcceleration", POSITIVE31(f, r));
    CMD(f, &b, fl.axis, "SetDeceleration", POSITIVE31(f, r));
    if (mode == 2)
        CMD(f, &b, fl.axis, "SetJerk", POSITIVE31(f, r));
    if (mode == 3) {
        int64_t master = below(r, PMD_AXES), source;
        CMD(f, &b, fl.axis, "SetGearRatio", I32(f, r));
        source = below(r, 2);
        CMD(f, &b, fl.axis, "SetGearMaster", master, source);
    }
    if (fl.bits & 1)
        CMD(f, &b, fl.axis, "MultiUpdate", value(f, r, 0, 15));
    else
        CMD(f, &b, fl.axis, "Update", 0);
    send(f, &b, fl.pending);
}

/* The trace: buffer 0, up to four variables, mode, period, a stop and a start
 * condition (every condition 0..4, any bit and state), in either order. */
static void op_trace(Fuzz *f, Reader *r)
{
    Flags fl = flags(r);
    unsigned slots = below(r, PMD_TRACE_SLOTS + 1), k;
    Batch b = {{0}, 0, 0};
    int64_t start = ADDRESS(f, r), length = ADDRESS(f, r);
    CMD(f, &b, fl.axis, "SetBufferStart", 0, start);
    CMD(f, &b, fl.axis, "SetBufferLength", 0, length);
    for (k = 0; k < slots; k++) {
        int64_t axis = below(r, PMD_AXES), variable = below(r, 15);
        CMD(f, &b, fl.axis, "SetTraceVariable", k, axis, variable);
    }
    CMD(f, &b, fl.axis, "SetTraceMode", below(r, 2));
    CMD(f, &b, fl.axis, "SetTracePeriod", value(f, r, 1, 0xFFFF));
    {
        int64_t sa = below(r, PMD_AXES), sc = below(r, 5), sb = below(r, 16), ss = below(r, 2);
        int64_t ea = below(r, PMD_AXES), ec = below(r, 5), eb = below(r, 16), es = below(r, 2);
        if (fl.bits & 1) {
            CMD(f, &b, fl.axis, "SetTraceStart", sa, sc, sb, ss);
            if (fl.bits & 2)
                CMD(f, &b, fl.axis, "SetTraceStop", ea, ec, eb, es);
        } else {
            if (fl.bits & 2)
                CMD(f, &b, fl.axis, "SetTraceStop", ea, ec, eb, es);
            CMD(f, &b, fl.axis, "SetTraceStart", sa, sc, sb, ss);
        }
    }
    send(f, &b, fl.pending);
}

/* A breakpoint with every trigger (0..10) and action (0..4). */
static void op_breakpoint(Fuzz *f, Reader *r)
{
    Flags fl = flags(r);
    int64_t bp = below(r, 2), source = below(r, PMD_AXES), action = below(r, 5), trigger = below(r, 11);
    Batch b = {{0}, 0, 0};
    CMD(f, &b, fl.axis, "SetBreakpointValue", bp, I32(f, r));
    CMD(f, &b, fl.axis, "SetBreakpoint", bp, source, action, trigger);
    send(f, &b, fl.pending);
}

static void op_sample_time(Fuzz *f, Reader *r)
{
    Flags fl = flags(r);
    Batch b = {{0}, 0, 0};
    CMD(f, &b, fl.axis, "SetSampleTime", value(f, r, 1, 0xFFFF));
    send(f, &b, fl.pending);
}

/* An abrupt or smooth stop: SetStopMode, then Update or MultiUpdate. */
static void op_stop(Fuzz *f, Reader *r)
{
    Flags fl = flags(r);
    Batch b = {{0}, 0, 0};
    CMD(f, &b, fl.axis, "SetStopMode", 1 + (fl.bits & 1));
    if (fl.bits & 2)
        CMD(f, &b, fl.axis, "MultiUpdate", 1 << fl.axis);
    else
        CMD(f, &b, fl.axis, "Update", 0);
    send(f, &b, fl.pending);
}

static void op_chip_reset(Fuzz *f, Reader *r)
{
    Flags fl = flags(r);
    Batch b = {{0}, 0, 0};
    CMD(f, &b, fl.axis, "Reset", 0);
    if (fl.bits & 1)
        CMD(f, &b, fl.axis, "GetHostIOError", 0);
    send(f, &b, fl.pending);
}

/* A dual-port memory write: address, count, data, a new strobe (then a get
 * executes it, unless it stays pending); or one of address, count, strobe
 * alone (a pending write may be waiting). Addresses run past the memory. */
static void op_memory(Fuzz *f, Reader *r)
{
    unsigned kind = byte(r);
    int64_t address = value(f, r, 0, instance(f)->s.memorySize + 64), count = value(f, r, 0, PMD_BATCH_WORDS);
    int64_t strobe = 0, data[PMD_BATCH_WORDS], seed = value(f, r, 0, 0xFFFFFFFFLL);
    int i;
    for (i = 0; i < PMD_BATCH_WORDS; i++)
        data[i] = (uint32_t)(seed + i);
    /* a get executes a pending write, except in Initialization Mode, where a write waits for the first get
       or doStep after it (docs/fmu.md): there a new address or count it would no longer fit is refused */
    Expect placed = instance(f)->s.state & PMD_INITIALIZATION_MODE ? MAY_FAIL : MUST_SUCCEED;
    switch (kind % 4) {
    case 0:
        CALL(f, MUST_SUCCEED, get_ints(f, VR.memoryStrobe, 1, &strobe));   /* executes a pending write */
        CALL(f, placed, set_int(f, VR.memoryAddress, address));             /* nothing pending: legal */
        CALL(f, placed, set_int(f, VR.memoryCount, count));
        CALL(f, MUST_SUCCEED, set_ints(f, VR.memoryData, PMD_BATCH_WORDS, data));
        CALL(f, MAY_FAIL, set_int(f, VR.memoryStrobe, strobe == INT32_MAX ? 0 : strobe + 1));
        if (!(kind & 4))
            execute(f);
        break;
    case 1: CALL(f, MAY_FAIL, set_int(f, VR.memoryAddress, address)); break;
    case 2: CALL(f, MAY_FAIL, set_int(f, VR.memoryCount, count)); break;
    default:
        CALL(f, MUST_SUCCEED, get_ints(f, VR.memoryStrobe, 1, &strobe));
        CALL(f, MAY_FAIL, set_int(f, VR.memoryStrobe, strobe == INT32_MAX ? 0 : strobe + 1));
        break;
    }
}

static void op_step(Fuzz *f, Reader *r)
{
    step(f, step_cycles(f, r, 1));
}

/* Property: a restored state is the saved one, byte for byte, and replays
 * identically. Saves the state, runs 1..4 steps reading every output after
 * each, restores (directly, or through serialize and deserialize), runs the
 * same steps again. */
static void op_replay(Fuzz *f, Reader *r)
{
    static Bytes outputs[2], states[2], blob;
    unsigned n = 1 + below(r, 4), via_bytes = byte(r) & 1, i, run;
    double cycles[4], t0 = f->t;
    int64_t budget = f->budget;
    const char *where;
    for (i = 0; i < n; i++) {
        cycles[i] = step_cycles(f, r, 0);
        if (cycles[i] > 2000)
            cycles[i] = 2000;
    }
    say("  getFMUState (replay)\n");
    CALL(f, MUST_SUCCEED, get_state(f, &f->saved));
    for (run = 0; run < 2; run++) {
        outputs[run].n = 0;
        if (run == 1) {
            if (via_bytes) {
                say("  serializeFMUState\n");
                CALL(f, MUST_SUCCEED, serialize(f, f->saved, &blob));
                CALL(f, MUST_SUCCEED, deserialize(f, &blob, &f->restored));
                CALL(f, MUST_SUCCEED, set_state(f, f->restored));
                free_state(f, &f->restored);
            } else {
                CALL(f, MUST_SUCCEED, set_state(f, f->saved));
            }
            f->t = t0;
            f->budget = budget;
            if (serialize(f, f->saved, &blob) != OK)
                fail("serializing a saved state failed");
            snapshot(f, &states[1]);
            if ((where = difference(f, &blob, &states[1])) != NULL)
                fail("SetFMUState did not restore the saved state byte for byte (first in %s)", where);
        }
        for (i = 0; i < n; i++) {
            int status = step(f, cycles[i]);
            append(&outputs[run], &status, sizeof status);
            read_outputs(f, &outputs[run], status != ERROR);
        }
        snapshot(f, &states[run]);
    }
    free_state(f, &f->saved);
    if (outputs[0].n != outputs[1].n || memcmp(outputs[0].p, outputs[1].p, outputs[0].n) != 0)
        fail("a restored state replayed with other outputs");
    if ((where = difference(f, &states[0], &states[1])) != NULL)
        fail("a restored state replayed into another state (first in %s)", where);
}

static void op_save(Fuzz *f, Reader *r)
{
    Slot *s = &f->slot[below(r, 2)];
    say("  getFMUState (slot %d)\n", (int)(s - f->slot));
    CALL(f, MUST_SUCCEED, get_state(f, &s->state));
    s->t = f->t;
}

/* Restores a saved state (directly, or through serialize and deserialize):
 * it may be from before a reset, with other parameters (the instance may
 * refuse it: a script position its script does not have). */
static void op_restore(Fuzz *f, Reader *r)
{
    static Bytes bytes_;
    Slot *s = &f->slot[below(r, 2)];
    int via_bytes = byte(r) & 1, status;
    if (!s->state)
        return;
    if (via_bytes) {
        say("  serializeFMUState\n");
        CALL(f, MUST_SUCCEED, serialize(f, s->state, &bytes_));
        status = CALL(f, MAY_FAIL, deserialize(f, &bytes_, &f->restored));
        if (status == OK)
            status = CALL(f, MAY_FAIL, set_state(f, f->restored));
        free_state(f, &f->restored);
    } else {
        status = CALL(f, MAY_FAIL, set_state(f, s->state));
    }
    if (status == OK)
        f->t = s->t;
}

/* cycleTime: whole microseconds, 1 .. 65535 (the sample time register); then some it cannot hold */
static const double cycle_times[] = {1e-4, 1e-6, 0.065535, 1e-3, 2.5e-5, 3e-4, 0.065534, 2e-6};
static const double bad_cycle_times[] = {0.065536, 5e-7, 1.5e-6, 0};
static const double start_times[] = {0, 1, 0.5, -1, 1e3, 1e-4};

/* Initialization with the default parameters (a failed re-initialization
 * falls back to it). */
static void initialize_defaults(Fuzz *f)
{
    CALL(f, MUST_SUCCEED, enter_initialization(f, 0));
    CALL(f, MUST_SUCCEED, exit_initialization(f));
    f->t = 0;
}

/* Reset (after Terminate, maybe) and initialization with other parameters,
 * set before or in initialization mode: memorySize, cycleTime, loopback,
 * record.capacity, record.enabled, and the start time. */
static void op_reinitialize(Fuzz *f, Reader *r)
{
    unsigned bits = byte(r);
    int64_t memory = value(f, r, 1, MAX_MEMORY), capacity = value(f, r, 0, MAX_CAPACITY);
    double cycle = cycle_times[below(r, sizeof cycle_times / sizeof cycle_times[0])];
    double start = start_times[below(r, sizeof start_times / sizeof start_times[0])] * (bits & 32 ? cycle : 1);
    int early = bits & 2, status;
    if (bits & 1)
        CALL(f, MUST_SUCCEED, terminate(f));
    CALL(f, MUST_SUCCEED, reset(f));
    if (!early)
        CALL(f, MUST_SUCCEED, enter_initialization(f, start));
    CALL(f, MUST_SUCCEED, set_int(f, VR.memorySize, memory));
    if (bits & 16)
        CALL(f, MUST_FAIL, set_real(f, VR.cycleTime, bad_cycle_times[bits >> 6 & 3]));
    CALL(f, MUST_SUCCEED, set_real(f, VR.cycleTime, cycle));
    CALL(f, MUST_SUCCEED, set_bool(f, VR.loopback, !(bits & 4)));
    CALL(f, MUST_SUCCEED, set_int(f, VR.recordCapacity, capacity));
    if (bits & 8)
        CALL(f, capacity ? MUST_SUCCEED : MUST_FAIL, set_bool(f, VR.recordEnabled, 1));
    if (early)
        CALL(f, MUST_SUCCEED, enter_initialization(f, start));
    status = CALL(f, MAY_FAIL, exit_initialization(f));
    f->t = start;
    if (status != OK) {
        CALL(f, MUST_SUCCEED, reset(f));
        initialize_defaults(f);
    }
}

/* Reset (after Terminate, maybe) and initialization mode, where the sequence
 * stays until op_exit_initialization: host commands, memory writes, inputs
 * and parameters (op_parameter) then act in initialization mode. */
static void op_enter_initialization(Fuzz *f, Reader *r)
{
    unsigned bits = byte(r);
    double start = start_times[below(r, sizeof start_times / sizeof start_times[0])];
    if (bits & 1)
        CALL(f, instance(f)->s.state & (PMD_INITIALIZATION_MODE | PMD_STEP_MODE) ? MUST_SUCCEED : MUST_FAIL,
             terminate(f));
    CALL(f, MUST_SUCCEED, reset(f));
    CALL(f, MUST_SUCCEED, enter_initialization(f, start * (bits & 2 ? instance(f)->s.cycleTime : 1)));
    f->t = start * (bits & 2 ? instance(f)->s.cycleTime : 1);
}

/* A parameter: settable before the end of initialization, refused after. A
 * memorySize may be refused in initialization too: a buffer or a pending
 * memory write that would leave the new size. */
static void op_parameter(Fuzz *f, Reader *r)
{
    int settable = instance(f)->s.state & (PMD_INSTANTIATED | PMD_INITIALIZATION_MODE);
    switch (below(r, 5)) {
    case 0: CALL(f, settable ? MAY_FAIL : MUST_FAIL, set_int(f, VR.memorySize, value(f, r, 1, MAX_MEMORY))); break;
    case 1: {
        double cycle = cycle_times[below(r, sizeof cycle_times / sizeof cycle_times[0])];
        CALL(f, settable ? MUST_SUCCEED : MUST_FAIL, set_real(f, VR.cycleTime, cycle));
        break;
    }
    case 2: CALL(f, MUST_FAIL, set_real(f, VR.cycleTime, bad_cycle_times[below(r, 4)])); break;
    case 3: CALL(f, settable ? MUST_SUCCEED : MUST_FAIL, set_bool(f, VR.loopback, byte(r) & 1)); break;
    default:
        CALL(f, settable ? MUST_SUCCEED : MUST_FAIL, set_int(f, VR.recordCapacity, value(f, r, 0, MAX_CAPACITY)));
        break;
    }
}

/* The end of initialization (refused outside initialization mode). */
static void op_exit_initialization(Fuzz *f, Reader *r)
{
    (void)r;
    CALL(f, instance(f)->s.state == PMD_INITIALIZATION_MODE ? MAY_FAIL : MUST_FAIL, exit_initialization(f));
}

/* The axis registers that decide events: position error limit, auto stop,
 * motion complete mode, settle time and window, tracking window, limit-switch
 * mode, signal sense, capture source, interrupt mask, motor mode. */
static void op_axis_setup(Fuzz *f, Reader *r)
{
    Flags fl = flags(r);
    Batch b = {{0}, 0, 0};
    CMD(f, &b, fl.axis, "SetPositionErrorLimit", value(f, r, 0, INT32_MAX));
    CMD(f, &b, fl.axis, "SetAutoStopMode", fl.bits & 1);
    CMD(f, &b, fl.axis, "SetMotionCompleteMode", fl.bits >> 1 & 1);
    CMD(f, &b, fl.axis, "SetSettleTime", value(f, r, 0, 0xFFFF));
    CMD(f, &b, fl.axis, "SetSettleWindow", value(f, r, 0, 0xFFFF));
    CMD(f, &b, fl.axis, "SetTrackingWindow", value(f, r, 0, 0xFFFF));
    CMD(f, &b, fl.axis, "SetLimitSwitchMode", fl.bits >> 2 & 1);
    CMD(f, &b, fl.axis, "SetSignalSense", value(f, r, 0, 0x1FFF));
    CMD(f, &b, fl.axis, "SetCaptureSource", fl.bits >> 3 & 1);
    CMD(f, &b, fl.axis, "SetInterruptMask", value(f, r, 0, 0xFFFF));
    CMD(f, &b, fl.axis, "SetMotorMode", !(fl.bits >> 4 & 1));
    send(f, &b, fl.pending);
}

/* A script (the script parameter): 1..8 lines of commands of the table, at
 * chip cycles 0, +0..255 each, with any arguments their fields carry; a new
 * initialization runs it (with cycleTime, record.capacity, record.enabled). */
static void op_script(Fuzz *f, Reader *r)
{
    static char path[64];
    unsigned bits = byte(r), lines = 1 + below(r, 8), i;
    int64_t capacity = value(f, r, 0, MAX_CAPACITY), cycle = 0, k;
    double cycle_time = cycle_times[below(r, sizeof cycle_times / sizeof cycle_times[0])];
    const char *text = path;
    FILE *file;
    int status;
    if (!path[0])
        snprintf(path, sizeof path, "/tmp/pmd-sequence-%ld.script", (long)getpid());
    if (!(file = fopen(path, "w")))
        fail("cannot write %s", path);
    for (i = 0; i < lines; i++) {
        unsigned delta = byte(r), axis = below(r, PMD_AXES);
        const PmdCommand *c = &pmd_commands[below(r, PMD_COMMAND_COUNT)];
        if (delta || i == 0)
            fprintf(file, "@ %lld\n", (long long)(cycle += delta));
        fprintf(file, "%s(Axis%u", c->name, axis + 1);
        for (k = 0; k < c->nArgs; k++) {              /* hex: the raw word, also for 16.16 and 0.32 values */
            int64_t v = field_value(f, r, &c->args[k]);
            fprintf(file, ", %s0x%llX", v < 0 ? "-" : "", (unsigned long long)(v < 0 ? -v : v));
        }
        fprintf(file, ");\n");
    }
    fclose(file);
    if (tracing) {
        char line[256];
        say("  script:\n");
        for (file = fopen(path, "r"); file && fgets(line, sizeof line, file);)
            say("    %s", line);
        if (file)
            fclose(file);
    }
    CALL(f, MUST_SUCCEED, reset(f));
    CALL(f, MUST_SUCCEED, enter_initialization(f, 0));
    CALL(f, MUST_SUCCEED, set_real(f, VR.cycleTime, cycle_time));
    CALL(f, MUST_SUCCEED, set_int(f, VR.recordCapacity, capacity));
    say("  set script %s\n", path);
    CALL(f, MUST_SUCCEED, f->fmi3 ? fmi3SetString(f->c, &VR.script, 1, &text, 1)
                                  : fmi2SetString(f->c, &VR.script, 1, &text));
    if (bits & 1)
        CALL(f, capacity ? MUST_SUCCEED : MUST_FAIL, set_bool(f, VR.recordEnabled, 1));
    status = CALL(f, MAY_FAIL, exit_initialization(f));     /* a script the parser refuses */
    f->t = 0;
    if (status != OK) {
        CALL(f, MUST_SUCCEED, reset(f));
        initialize_defaults(f);
    }
    f->scripted = status == OK;
}

/* The plant's inputs: an encoder position, or a limit or home switch. */
/* Whether the machine drives this input of the axis every cycle: then setting it is refused. */
static int driven(Fuzz *f, unsigned axis, unsigned signal)
{
    const PmdMachine *machine = instance(f)->chip.machine;
    return machine && (machine->axis[axis].signals & signal);
}

static void op_input(Fuzz *f, Reader *r)
{
    unsigned axis = below(r, PMD_AXES), kind = below(r, 4);
    switch (kind) {
    case 0: CALL(f, MUST_SUCCEED, set_int(f, VR.actualPosition + 100 * axis, I32(f, r))); break;
    case 1:
        CALL(f, driven(f, axis, PMD_MACHINE_POSITIVE_LIMIT) ? MUST_FAIL : MUST_SUCCEED,
             set_bool(f, VR.positiveLimit + 100 * axis, byte(r) & 1));
        break;
    case 2:
        CALL(f, driven(f, axis, PMD_MACHINE_NEGATIVE_LIMIT) ? MUST_FAIL : MUST_SUCCEED,
             set_bool(f, VR.negativeLimit + 100 * axis, byte(r) & 1));
        break;
    default:
        CALL(f, driven(f, axis, PMD_MACHINE_HOME) ? MUST_FAIL : MUST_SUCCEED,
             set_bool(f, VR.home + 100 * axis, byte(r) & 1));
        break;
    }
}

/* record.enabled on or off (a recording step runs cycle by cycle and, in
 * FMI 3, leaves record.data, which op_replay compares). */
static void op_record(Fuzz *f, Reader *r)
{
    int on = byte(r) & 1;
    CALL(f, on && instance(f)->recordCapacity == 0 ? MUST_FAIL : MUST_SUCCEED, set_bool(f, VR.recordEnabled, on));
}

static void op_logging(Fuzz *f, Reader *r)
{
    int on = byte(r) & 1;
    say("  setDebugLogging(%d)\n", on);
    CALL(f, MUST_SUCCEED, f->fmi3 ? fmi3SetDebugLogging(f->c, on, 0, NULL) : fmi2SetDebugLogging(f->c, on, 0, NULL));
}

/* Illegal calls, in whatever state the sequence left (a batch or a memory
 * write may be pending): each must return Error and change nothing. */
static void op_refused(Fuzz *f, Reader *r)
{
    const PmdInstance *inst = instance(f);
    unsigned kind = below(r, 11);
    int stepping = inst->s.state == PMD_STEP_MODE;
    double d = 0;
    switch (kind) {
    case 0: {                                                                        /* no such variable */
        fmi3ValueReference none = 9999;
        fmi2Integer i2;
        fmi3Int32 i3;
        say("  get value reference %u\n", none);
        CALL(f, MUST_FAIL, f->fmi3 ? fmi3GetInt32(f->c, &none, 1, &i3, 1) : fmi2GetInteger(f->c, &none, 1, &i2));
        break;
    }
    case 1:
        say("  get %s as a Real\n", vr_name(VR.chipTime));
        CALL(f, MUST_FAIL, f->fmi3 ? fmi3GetFloat64(f->c, &VR.chipTime, 1, &d, 1)
                                   : fmi2GetReal(f->c, &VR.chipTime, 1, &d));
        break;
    case 2:                                                                          /* a fixed parameter */
        if (stepping)
            CALL(f, MUST_FAIL, set_int(f, VR.memorySize, 64));
        break;
    case 3:
        if (stepping)
            CALL(f, MUST_FAIL, set_real(f, VR.cycleTime, 1e-4));
        break;
    case 9:                                                                          /* the wrong FMI state */
        if (inst->s.state != PMD_INSTANTIATED)
            CALL(f, MUST_FAIL, enter_initialization(f, f->t));
        break;
    case 10:
        if (inst->s.state != PMD_INITIALIZATION_MODE)
            CALL(f, MUST_FAIL, exit_initialization(f));
        break;
    case 4:                                  /* not at the current time (beyond the rounding tolerance) */
        CALL(f, MUST_FAIL, do_step(f, f->t + fmax(cycle_time(inst), 64 * DBL_EPSILON * fabs(f->t)),
                                   cycle_time(inst)));
        break;
    case 5: {
        static const double sizes[] = {0, -1, NAN, INFINITY};
        CALL(f, MUST_FAIL, do_step(f, f->t, sizes[below(r, 4)]));
        break;
    }
    case 6: CALL(f, MUST_FAIL, set_int(f, VR.hostWordCount, PMD_BATCH_WORDS + 1)); break;
    case 7: CALL(f, MUST_FAIL, set_int(f, VR.memoryCount, byte(r) & 1 ? -1 : PMD_BATCH_WORDS + 1)); break;
    default: {
        static Bytes corrupt;
        size_t body = sizeof(PmdStateImage) + (size_t)inst->s.memorySize * sizeof(uint32_t), at = bytes(r, 4) % body;
        snapshot(f, &corrupt);                        /* a byte of the body: the checksum must catch it */
        corrupt.p[corrupt.n - body + at] ^= (uint8_t)(1 + below(r, 255));
        CALL(f, MUST_FAIL, deserialize(f, &corrupt, &f->restored));
        free_state(f, &f->restored);
        break;
    }
    }
}

/* ---- recording ----------------------------------------------------------------------- */

/* The variables a record.columns column may name: numbers, but not the independent variable (record.c). */
static short recordable[PMD_VARIABLE_COUNT];
static size_t recordables;

/* Names that record.columns refuses: unknown, a prefix or an extension of a name, of the wrong type, the
 * independent variable, an array without its element or past its end, an empty column. */
static const char *const bad_columns[] = {
    "axis1.nothing", "axis1.commandedPositio", "axis1.commandedPositionX", "AXIS1.commandedPosition",
    "axis5.commandedPosition", "script", "record.columns", "record.data", "time", "memory.data",
    "io.output[0]", "io.output[17]", "host.word[65]", "axis1.commandedPosition[1]", "", " ",
};

static int set_strings(Fuzz *f, unsigned v, size_t n, const char *const *text)
{
    fmi2ValueReference vrs[2] = {v, v};
    size_t i;
    say("  set %s", vr_name(v));
    for (i = 0; i < n; i++)
        say(" \"%.80s%s\"", text[i], strlen(text[i]) > 80 ? "..." : "");
    say("\n");
    return f->fmi3 ? fmi3SetString(f->c, vrs, n, text, n) : fmi2SetString(f->c, vrs, n, text);
}

static int get_string(Fuzz *f, unsigned v, const char **text)
{
    say("  get %s\n", vr_name(v));
    return f->fmi3 ? fmi3GetString(f->c, &v, 1, text, 1) : fmi2GetString(f->c, &v, 1, text);
}

/* A value of 1..MAX_COLUMNS names of recordable[], some with blanks around them, and the row it makes;
 * with bad, one name of bad_columns[] in place of one of them. */
static uint32_t column_list(Reader *r, char *text, size_t size, int bad)
{
    unsigned n = 1 + below(r, MAX_COLUMNS), at = below(r, n), k;
    const char *wrong = bad_columns[below(r, sizeof bad_columns / sizeof bad_columns[0])];
    uint32_t row = sizeof(uint32_t);                       /* the chip time */
    size_t used = 0;
    text[0] = '\0';
    for (k = 0; k < n; k++) {
        const PmdVariable *v = &pmd_variables[recordable[bytes(r, 2) % recordables]];
        unsigned blanks = byte(r);
        used += (size_t)snprintf(text + used, size - used, "%s%s%s%s", k ? "," : "", blanks & 1 ? " " : "",
                                 bad && k == at ? wrong : v->name, blanks & 2 ? "  " : "");
        row += v->bytes;
    }
    return row;
}

/* Property: record.columns and record.rowSize read back as the sequence set them (not in Instantiated, where
 * gets are refused; a get executes what is pending on the ports, hence only when the operation asks). */
static void property_columns(Fuzz *f, const char *after)
{
    const char *text = "";
    int64_t row = 0;
    if (instance(f)->s.state == PMD_INSTANTIATED)
        return;
    CALL(f, MUST_SUCCEED, get_string(f, VR.recordColumns, &text));
    CALL(f, MUST_SUCCEED, get_ints(f, VR.recordRowSize, 1, &row));
    if (strcmp(text, f->columns) != 0 || row != (int64_t)f->rowBytes)
        fail("after %s, record.columns reads \"%.100s\" (record.rowSize %lld) where \"%.100s\" (%u) was set", after,
             text, (long long)row, f->columns, (unsigned)f->rowBytes);
}

/* record.columns: a valid list, the empty one, a list with a refused name, two values in one set call (the
 * last counts; one refused refuses both), or 4097 empty columns (more than a row may hold); flags bit 0:
 * read record.columns and record.rowSize back. A refused value must leave both as they were. */
static void op_columns(Fuzz *f, Reader *r)
{
    static char text[2][sizeof f->columns];
    static char many[4097 + 1];
    unsigned kind = below(r, 5), check = byte(r) & 1;
    int settable = instance(f)->s.state & (PMD_INSTANTIATED | PMD_INITIALIZATION_MODE | PMD_STEP_MODE), ok = 1;
    const char *values[2];
    uint32_t row[2];
    size_t n = 1, k;
    switch (kind) {
    case 0: row[0] = column_list(r, text[0], sizeof text[0], 0); break;
    case 1: text[0][0] = '\0'; row[0] = DEFAULT_ROW_BYTES; break;
    case 2: row[0] = column_list(r, text[0], sizeof text[0], 1); ok = 0; break;
    case 3:
        n = 2;
        for (k = 0; k < 2; k++) {
            unsigned which = below(r, 3);               /* valid, empty, refused */
            text[k][0] = '\0';
            row[k] = which == 1 ? DEFAULT_ROW_BYTES : column_list(r, text[k], sizeof text[k], which == 2);
            ok &= which != 2;
        }
        break;
    default:
        memset(many, ',', sizeof many - 1);
        many[sizeof many - 2] = '\0';                   /* 4096 commas: 4097 columns */
        values[0] = many;
        if (CALL(f, MUST_FAIL, set_strings(f, VR.recordColumns, 1, values)) == OK)
            return;
        if (check)
            property_columns(f, "a refused record.columns of 4097 columns");
        return;
    }
    values[0] = text[0];
    values[1] = text[1];
    if (CALL(f, !settable || !ok ? MUST_FAIL : MUST_SUCCEED, set_strings(f, VR.recordColumns, n, values)) == OK) {
        snprintf(f->columns, sizeof f->columns, "%s", values[n - 1]);
        f->rowBytes = row[n - 1];
    }
    if (check)
        property_columns(f, "setting record.columns");
}

static int lend(Fuzz *f, void *rows, size_t size)
{
    say("  pmdfmu_fmi%dSetRecordBuffer(%s + %zu, %zu bytes)\n", f->fmi3 ? 3 : 2, rows ? "area" : "NULL",
        rows ? (size_t)((unsigned char *)rows - lendArea) : 0, size);
    return f->fmi3 ? pmdfmu_fmi3SetRecordBuffer(f->c, rows, size) : pmdfmu_fmi2SetRecordBuffer(f->c, rows, size);
}

/* Memory of the fuzzer's lend area lent for the rows (pmdfmu_fmi2/3SetRecordBuffer): whole rows of
 * record.columns as they stand (at any byte offset: the default rows need 4-byte alignment, a step refuses
 * others), any number of bytes, NULL (record.data's own buffer again), or 0 bytes. The area outside the loan
 * holds PAINT, checked after every call (property_lent). */
static void op_lend(Fuzz *f, Reader *r)
{
    unsigned kind = below(r, 4);
    size_t at = below(r, 8), p = bytes(r, 2), size;
    size = kind == 0 ? p % 512 * f->rowBytes : kind == 1 ? p : 0;
    if (size > LEND_AREA - at)
        size = LEND_AREA - at;
    memset(lendArea, PAINT, sizeof lendArea);          /* the rows of an earlier loan are no longer lent */
    f->lending = kind != 2;
    f->lentAt = at;
    f->lentSize = size;
    CALL(f, MUST_SUCCEED, lend(f, kind == 2 ? NULL : lendArea + at, size));
}

static int record_data(Fuzz *f, const unsigned char **data, size_t *size)
{
    say("  get record.data\n");
    if (!f->fmi3)
        return pmdfmu_fmi2GetRecordData(f->c, (const void **)data, size);
    {
        fmi3ValueReference ref = VR.recordData;
        fmi3Binary binary = NULL;
        int s = fmi3GetBinary(f->c, &ref, 1, size, &binary, 1);
        *data = binary;
        return s;
    }
}

/* record.data (FMI 2: pmdfmu_fmi2GetRecordData). Property: it holds whole rows of the last step that ran
 * (record.rowSize as it stood then), of consecutive chip times (unless a script runs: its Reset may restart
 * the time), and lies in the memory lent if something is lent, else outside the lend area. */
static void op_record_data(Fuzz *f, Reader *r)
{
    const unsigned char *data = NULL;
    size_t size = 0, rows, k;
    int legal = instance(f)->s.state != PMD_INSTANTIATED;
    uint32_t first, time;
    (void)r;
    if (CALL(f, legal ? MUST_SUCCEED : MUST_FAIL, record_data(f, &data, &size)) != OK || size == 0)
        return;
    say("    %zu bytes\n", size);
    if (f->lending ? data != lendArea + f->lentAt || size > f->lentSize
                   : data + size > lendArea && data < lendArea + LEND_AREA)
        fail("record.data's %zu bytes at area + %td are not %s", size, data - lendArea,
             f->lending ? "the memory lent" : "outside the lend area (nothing is lent)");
    if (size % f->stepRowBytes)
        fail("record.data holds %zu bytes: not whole rows of %u bytes", size, (unsigned)f->stepRowBytes);
    rows = size / f->stepRowBytes;
    memcpy(&first, data, sizeof first);
    for (k = 1; k < rows && !f->scripted; k++) {
        memcpy(&time, data + k * f->stepRowBytes, sizeof time);
        if (time != first + (uint32_t)k)
            fail("record.data's row %zu has chip time %u, row 0 %u", k, (unsigned)time, (unsigned)first);
    }
}

/* ---- memory.data as a block ------------------------------------------------------------ */

/* memory.data set in one call as a block (pmd_set_memory_data). FMI 2: a run of consecutive memory.data[k]
 * value references from any element, maybe past memory.data[64] (refused), maybe split by a missing element,
 * maybe with an element again after it (the last value counts), maybe after memory.address or memory.count
 * in the same call. FMI 3: the memory.data array, maybe after memory.address, maybe twice, maybe with a
 * wrong nValues (refused). Flags bit 0: read memory.data back before and after (a get executes what is
 * pending on the ports) and compare with the words as set. */
static void op_memory_block(Fuzz *f, Reader *r)
{
    unsigned bits = byte(r), first = below(r, PMD_BATCH_WORDS), n = 1 + below(r, PMD_BATCH_WORDS + 2), i;
    uint32_t seed = bytes(r, 4), word[2 * PMD_BATCH_WORDS + 2], expected[PMD_BATCH_WORDS];
    int64_t prefix = bits & 4 ? value(f, r, 0, PMD_BATCH_WORDS) : ADDRESS(f, r), read[PMD_BATCH_WORDS];
    int check = bits & 1 && instance(f)->s.state != PMD_INSTANTIATED, status;
    int settable = instance(f)->s.state & (PMD_INSTANTIATED | PMD_INITIALIZATION_MODE | PMD_STEP_MODE);
    Expect expect = settable ? MUST_SUCCEED : MUST_FAIL;
    size_t count = 0;
    for (i = 0; i < sizeof word / sizeof word[0]; i++)
        word[i] = seed + 0x9E3779B9u * i;
    if (check) {
        CALL(f, MUST_SUCCEED, get_ints(f, VR.memoryData, PMD_BATCH_WORDS, read));
        for (i = 0; i < PMD_BATCH_WORDS; i++)
            expected[i] = (uint32_t)read[i];
    }
    if (!f->fmi3) {
        fmi2ValueReference vrs[2 * PMD_BATCH_WORDS + 2];
        fmi2Integer values[2 * PMD_BATCH_WORDS + 2];
        unsigned gap = bits & 8 && n > 2 ? first + n / 2 : PMD_BATCH_WORDS + 2;
        if (bits & 2) {                                   /* memory.count or memory.address first */
            vrs[count] = bits & 4 ? VR.memoryCount : VR.memoryAddress;
            values[count++] = (fmi2Integer)prefix;
            expect = MAY_FAIL;                            /* refused with a pending write it would not fit */
        }
        for (i = first; i < first + n; i++) {
            if (i == gap)
                continue;
            vrs[count] = VR.memoryData + i;
            values[count] = pmd_int32(word[count]);
            if (i < PMD_BATCH_WORDS)
                expected[i] = word[count];
            count++;
        }
        if (bits & 16) {                                  /* the run's first element again */
            vrs[count] = VR.memoryData + first;
            values[count] = pmd_int32(word[count]);
            expected[first] = word[count];
            count++;
        }
        if (first + n > PMD_BATCH_WORDS + (gap == PMD_BATCH_WORDS))   /* value reference 1565 on: none */
            expect = MUST_FAIL;
        say("  set memory.data block: %zu values from %s, memory.data[%u] .. [%u]%s\n", count, vr_name(vrs[0]),
            first + 1, first + n, bits & 16 ? " and its first again" : "");
        status = CALL(f, expect, fmi2SetInteger(f->c, vrs, count, values));
    } else {
        fmi3ValueReference vrs[3];
        fmi3UInt32 values[2 * PMD_BATCH_WORDS + 2];
        size_t nvr = 0, nValues;
        unsigned kind = bits >> 1 & 3, copies = kind == 2 ? 2 : 1, c;
        if (kind == 1) {
            vrs[nvr++] = VR.memoryAddress;
            values[count++] = (fmi3UInt32)prefix;
            expect = MAY_FAIL;
        }
        for (c = 0; c < copies; c++) {
            vrs[nvr++] = VR.memoryData;
            for (i = 0; i < PMD_BATCH_WORDS; i++, count++) {
                values[count] = word[count];
                expected[i] = word[count];
            }
        }
        nValues = count;
        if (kind == 3) {                                  /* 63 or 65 values for the array's 64 */
            nValues = bits & 32 ? count + 1 : count - 1;
            expect = MUST_FAIL;
        }
        say("  fmi3SetUInt32 %zu value references, %zu values%s\n", nvr, nValues,
            kind == 1 ? " (memory.address first)" : "");
        status = CALL(f, expect, fmi3SetUInt32(f->c, vrs, nvr, values, nValues));
    }
    if (check && status == OK) {
        CALL(f, MUST_SUCCEED, get_ints(f, VR.memoryData, PMD_BATCH_WORDS, read));
        for (i = 0; i < PMD_BATCH_WORDS; i++)
            if ((uint32_t)read[i] != expected[i])
                fail("memory.data[%u] reads 0x%08X after a block set, 0x%08X was set", i + 1, (unsigned)read[i],
                     (unsigned)expected[i]);
    }
}

/* A machine (the machine parameter, given as text): for each axis a byte of
 * which keys its table gives - servo = "plant" (bit 0), home (1), positive
 * limit (2), negative limit (3), index every K counts (4), index at listed
 * positions (5), signal_sense (6), an [axisN.plant] table of 1..4 motor
 * parameters (7) - their values from value() (the parser refuses what it
 * refuses: the fallback is the defaults), the motor's from MACHINE_NUMBERS;
 * then a new initialization with a cycle time and loopback. */
static const char *const MACHINE_NUMBERS[] = {"0", "1", "24", "2e-6", "1e-5", "1e-6", "7.2e-6", "0.03",
                                              "4000", "1048576", "-3.5", "1e300", "65535", "1E-3", "0.004", "50.0"};
static void op_machine(Fuzz *f, Reader *r)
{
    char text[4096];
    size_t used = 0;
    unsigned bits = byte(r), n, k;
    double cycle = cycle_times[below(r, sizeof cycle_times / sizeof cycle_times[0])];
    const char *value_text = text;
    int status;
#define PUT(...) (used += (size_t)snprintf(text + used, sizeof text - used, __VA_ARGS__))
    for (n = 0; n < PMD_AXES; n++) {
        unsigned keys = byte(r);
        if (!keys)
            continue;
        PUT("[axis%u]\n", n + 1);
        if (keys & 1)
            PUT("servo = \"plant\"\n");
        if (keys & 2) {
            long long lo = (long long)value(f, r, INT32_MIN, INT32_MAX);
            PUT("home = [%lld, %lld]\n", lo, lo + (long long)value(f, r, 0, 100000));
        }
        if (keys & 4)
            PUT("positive_limit = %lld\n", (long long)value(f, r, INT32_MIN, INT32_MAX));
        if (keys & 8)
            PUT("negative_limit = %lld\n", (long long)value(f, r, INT32_MIN, INT32_MAX));
        if (keys & 16)
            PUT("index = %lld\n", (long long)value(f, r, 1, INT32_MAX));
        else if (keys & 32) {
            unsigned count = 1 + below(r, 4);
            PUT("index = [");
            for (k = 0; k < count; k++)
                PUT("%s%lld", k ? ", " : "", (long long)value(f, r, INT32_MIN, INT32_MAX));
            PUT("]\n");
        }
        if (keys & 64)
            PUT("signal_sense = 0x%llX\n", (unsigned long long)value(f, r, 0, 0x3C));
        if (keys & 128) {
            unsigned count = 1 + below(r, 4);
            PUT("[axis%u.plant]\n", n + 1);
            for (k = 0; k < count; k++) {
                const char *name = plant_variables[below(r, PLANT_VARIABLE_COUNT)].name;   /* read in this order */
                PUT("%s = %s\n", name, MACHINE_NUMBERS[below(r, sizeof MACHINE_NUMBERS / sizeof MACHINE_NUMBERS[0])]);
            }
        }
    }
#undef PUT
    if (used == 0)
        snprintf(text, sizeof text, "# no axis\n");
    say("  machine:\n%s", text);
    CALL(f, MUST_SUCCEED, reset(f));
    CALL(f, MUST_SUCCEED, enter_initialization(f, 0));
    CALL(f, MUST_SUCCEED, set_real(f, VR.cycleTime, cycle));
    CALL(f, MUST_SUCCEED, set_bool(f, VR.loopback, !(bits & 1)));
    CALL(f, MUST_SUCCEED, f->fmi3 ? fmi3SetString(f->c, &VR.machine, 1, &value_text, 1)
                                  : fmi2SetString(f->c, &VR.machine, 1, &value_text));
    status = CALL(f, MAY_FAIL, exit_initialization(f));     /* a machine the parser refuses */
    f->t = 0;
    if (status != OK) {
        CALL(f, MUST_SUCCEED, reset(f));
        initialize_defaults(f);
    }
}

typedef struct {
    const char *name;
    void (*run)(Fuzz *f, Reader *r);
} Operation;

static const Operation OPS[] = {
    {"command", op_command},                  /* 0 */
    {"buffer", op_buffer},                    /* 1 */
    {"write_buffer", op_write_buffer},        /* 2 */
    {"buffer_index", op_buffer_index},        /* 3 */
    {"external_profile", op_external_profile},/* 4 */
    {"move", op_move},                        /* 5 */
    {"trace", op_trace},                      /* 6 */
    {"breakpoint", op_breakpoint},            /* 7 */
    {"sample_time", op_sample_time},          /* 8 */
    {"stop", op_stop},                        /* 9 */
    {"chip_reset", op_chip_reset},            /* 10 */
    {"memory", op_memory},                    /* 11 */
    {"step", op_step},                        /* 12 */
    {"replay", op_replay},                    /* 13 */
    {"save", op_save},                        /* 14 */
    {"restore", op_restore},                  /* 15 */
    {"reinitialize", op_reinitialize},        /* 16 */
    {"input", op_input},                      /* 17 */
    {"record", op_record},                    /* 18 */
    {"logging", op_logging},                  /* 19 */
    {"refused", op_refused},                  /* 20 */
    {"script", op_script},                    /* 21 */
    {"enter_initialization", op_enter_initialization}, /* 22 */
    {"parameter", op_parameter},              /* 23 */
    {"exit_initialization", op_exit_initialization},   /* 24 */
    {"axis_setup", op_axis_setup},            /* 25 */
    {"columns", op_columns},                  /* 26 */
    {"lend", op_lend},                        /* 27 */
    {"record_data", op_record_data},          /* 28 */
    {"memory_block", op_memory_block},        /* 29 */
    {"machine", op_machine},                  /* 30 */
};
#define N_OPS (sizeof OPS / sizeof OPS[0])

static int skipped[N_OPS];

static void configure(void)
{
    const char *skip = getenv("FUZZ_SEQUENCE_SKIP");
    size_t k;
    tracing = getenv("FUZZ_SEQUENCE_TRACE") != NULL;
    known = getenv("FUZZ_SEQUENCE_KNOWN");
    for (k = 0; skip && k < N_OPS; k++) {
        const char *at = strstr(skip, OPS[k].name);
        size_t n = strlen(OPS[k].name);
        skipped[k] = at && (at == skip || at[-1] == ',') && (at[n] == '\0' || at[n] == ',');
    }
    find_value_references();
    memset(painted, PAINT, sizeof painted);
    for (k = 0; k < PMD_VARIABLE_COUNT; k++) {
        const PmdVariable *v = &pmd_variables[k];
        if (v->type != PMD_STRING && v->type != PMD_BINARY && v->family != VAR_time)
            recordable[recordables++] = (short)k;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int configured;
    static Fuzz f;                               /* static: longjmp from a known finding keeps it */
    Reader r = {data, size};
    int k;
    if (!configured) {
        configure();
        configured = 1;
    }
    memset(&f, 0, sizeof f);
    forget_recording(&f);
    f.stepRowBytes = DEFAULT_ROW_BYTES;
    f.fmi3 = byte(&r) & 1;
    f.budget = CYCLE_BUDGET;
    say("== FMI %d\n", f.fmi3 ? 3 : 2);
    f.c = f.fmi3 ? (void *)fmi3InstantiateCoSimulation("sequence", PMD_INSTANTIATION_TOKEN, NULL, fmi3False,
                                                       fmi3False, fmi3False, fmi3False, NULL, 0, NULL, logger3, NULL)
                 : (void *)fmi2Instantiate("sequence", fmi2CoSimulation, PMD_INSTANTIATION_TOKEN, "", &callbacks2,
                                           fmi2False, fmi2False);
    last_error[0] = '\0';
    if (!f.c)
        fail("instantiation failed");
    if (setjmp(known_finding) == 0) {
        initialize_defaults(&f);
        while (r.n) {
            const Operation *op = &OPS[byte(&r) % N_OPS];
            if (skipped[op - OPS])
                continue;
            say("== %s\n", op->name);
            op->run(&f, &r);
        }
    }
    for (k = 0; k < 2; k++)
        free_state(&f, &f.slot[k].state);
    free_state(&f, &f.probe);
    free_state(&f, &f.saved);
    free_state(&f, &f.restored);
    if (f.fmi3)
        fmi3FreeInstance(f.c);
    else
        fmi2FreeInstance(f.c);
    return 0;
}
