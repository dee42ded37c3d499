/* SPDX-License-Identifier: BSD-2-Clause */
/* Bulk recording: record.data's buffer and record.columns, the values a
 * recording doStep writes per cycle (docs/performance.md, "Recording").
 *
 * A row is little-endian and packed: the chip time (uint32, GetTime), then
 * each column in record.columns' order as the FMU's getter returns it at the
 * end of the cycle, in its FMI 3 type (variables.csv): Float64 8 bytes, Int32
 * and UInt32 4, Int16 and UInt16 2, Boolean 1 (0 or 1) - the layout of the
 * harness's rows, which it copies whole. "" (the default) is the row of chip.c's
 * pmd_chip_record: the chip time and the commanded position, velocity and
 * acceleration of the four axes. */
#include <stdlib.h>
#include <string.h>

#include "messages.h"
#include "record.h"
#include "values.h"

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "record.data's rows are little-endian as the platform stores them"
#endif

/* Columns of one row at most: a row of every variable of variables.csv twice over fits. */
#define MAX_COLUMNS 4096

static PmdStatus record_reserve(PmdInstance *inst, const char *fn, uint32_t rowBytes)
{
    size_t bytes = (size_t)inst->recordCapacity * rowBytes;
    int32_t *record;
    if (inst->record && inst->recordRows == inst->recordCapacity && inst->recordBytes >= bytes)
        return PMD_OK;
    if (inst->recordCapacity == 0) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: record.enabled: record.capacity is 0", fn);
        return PMD_ERROR;
    }
    /* a larger block of the same capacity keeps the rows of the last doStep (record.data) */
    record = (int32_t *)realloc(inst->record, bytes);
    if (!record) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: record.enabled: no host memory for record.capacity %u",
                         fn, (unsigned)inst->recordCapacity);
        return PMD_ERROR;
    }
    if (inst->recordRows != inst->recordCapacity)     /* sized for another record.capacity */
        inst->recordCount = 0;
    inst->record = record;
    inst->recordRows = inst->recordCapacity;
    inst->recordBytes = bytes;
    return PMD_OK;
}

/* The record.data buffer, allocated when recording is enabled: an instance
 * that never records does not carry it, and doStep never allocates. */
PmdStatus pmd_record_allocate(PmdInstance *inst, const char *fn)
{
    return record_reserve(inst, fn, inst->columns.rowBytes);
}

void pmd_record_data(const PmdInstance *inst, const unsigned char **data, size_t *size)
{
    *data = pmd_record_rows(inst);
    *size = (size_t)inst->recordCount * inst->recordRowBytes;
}

unsigned char *pmd_record_rows(const PmdInstance *inst)
{
    return inst->recordLent ? inst->recordLent : (unsigned char *)inst->record;
}

int64_t pmd_record_room(const PmdInstance *inst)
{
    int64_t lent = (int64_t)(inst->recordLentBytes / inst->columns.rowBytes);
    return inst->recordLent && lent < (int64_t)inst->recordRows ? lent : (int64_t)inst->recordRows;
}

/* The rows go straight into the caller's memory, which spares it a copy of
 * record.data's (docs/performance.md, "Recording"). The rows recorded so far
 * are in the other memory: record.data holds none until the next doStep. */
void pmd_record_lend(PmdInstance *inst, const char *fn, void *rows, size_t bytes)
{
    /* any memory may be lent: doStep checks that its rows fit */
    inst->recordLender = fn;
    inst->recordLent = (unsigned char *)rows;
    inst->recordLentBytes = rows ? bytes : 0;
    inst->recordCount = 0;
}

void pmd_record_columns_free(PmdRecordColumns *columns)
{
    free(columns->text);
    free(columns->column);
    memset(columns, 0, sizeof *columns);
    columns->rowBytes = PMD_RECORD_WORDS * sizeof(int32_t);
}

/* The variable of this name (length characters, not NUL-terminated), by bisection of
 * pmd_variable_by_name: a row's 28 names are resolved in microseconds, not tens of them. */
static const PmdVariable *variable_named(const char *name, size_t length)
{
    size_t low = 0, high = PMD_VARIABLE_COUNT;
    while (low < high) {
        size_t middle = low + (high - low) / 2;
        const PmdVariable *v = &pmd_variables[pmd_variable_by_name[middle]];
        int order = strncmp(name, v->name, length);
        if (order == 0)
            order = v->name[length] == '\0' ? 0 : -1;      /* name is a prefix of v's: it sorts first */
        if (order == 0)
            return v;
        if (order < 0)
            high = middle;
        else
            low = middle + 1;
    }
    return NULL;
}

static PmdStatus refused(PmdInstance *inst, const char *fn, const char *text, const char *name, size_t length,
                         const char *why, PmdRecordColumn *column)
{
    free(column);
    pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: record.columns = \"%s\": \"%.*s\" %s: not set", fn, text,
                     (int)length, name, why);
    return PMD_ERROR;
}

/* Families in order, a family's columns in row order (offsets differ: the order is total). */
static int by_family(const void *a, const void *b)
{
    const PmdRecordColumn *x = (const PmdRecordColumn *)a, *y = (const PmdRecordColumn *)b;
    if (x->family != y->family)
        return x->family < y->family ? -1 : 1;
    return x->offset < y->offset ? -1 : x->offset > y->offset;
}

PmdStatus pmd_record_columns_compile(PmdInstance *inst, const char *fn, const char *text, PmdRecordColumns *out)
{
    PmdRecordColumns c;
    const char *p = text;
    size_t n = 1, k = 0;
    memset(&c, 0, sizeof c);
    c.rowBytes = sizeof(int32_t);                   /* the chip time */
    if (!*text) {
        pmd_record_columns_free(out);
        return PMD_OK;
    }
    for (; *p; p++)
        n += *p == ',';
    if (n > MAX_COLUMNS) {
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: record.columns: %zu columns, more than %d: not set", fn,
                         n, MAX_COLUMNS);
        return PMD_ERROR;
    }
    c.column = (PmdRecordColumn *)malloc(n * sizeof *c.column);
    c.text = (char *)malloc(strlen(text) + 1);
    if (!c.column || !c.text) {
        free(c.text);
        free(c.column);
        pmd_instance_log(inst, PMD_ERROR, PMD_LOG_ERRORS, "%s: record.columns: out of host memory: not set", fn);
        return PMD_ERROR;
    }
    strcpy(c.text, text);
    for (p = text;; p++) {
        /* one name: FMI 2's (an array's element as "io.output[3]"), spaces around it ignored */
        const char *end = p + strcspn(p, ",");
        const PmdVariable *v;
        while (p < end && *p == ' ')
            p++;
        while (end > p && end[-1] == ' ')
            end--;
        v = variable_named(p, (size_t)(end - p));
        /* a row stores an Integer in 2 or 4 bytes, a Real in 8, a Boolean in 1 (record_row): a variable of
         * another width would need a row writer that stores it (tests/test_record_columns.py checks the table) */
        if (end == p || !v || v->type == PMD_STRING || v->type == PMD_BINARY || v->family == VAR_time) {
            free(c.text);
            return refused(inst, fn, text, p, (size_t)(end - p),
                           end == p ? "is no name (an empty column)"
                           : !v ? "is not a variable of the FMU (FMI 2 names: an array's element as name[i])"
                           : v->family == VAR_time ? "is the independent variable, the same for every cycle of a "
                                                     "doStep (each cycle's time: nextCycleTime before it)"
                           : "is not a number (String or Binary)", c.column);
        }
        c.column[k].family = (unsigned short)v->family;
        c.column[k].index = v->index;
        c.column[k].bytes = v->bytes;
        c.column[k].offset = c.rowBytes;
        c.readsReals |= PMD_READS_REALS(v->family);
        c.rowBytes += v->bytes;
        k++;
        p += strcspn(p, ",");
        if (!*p)
            break;
    }
    c.count = k;
    qsort(c.column, k, sizeof *c.column, by_family);
    pmd_record_columns_free(out);
    *out = c;
    return PMD_OK;
}

PmdStatus pmd_record_columns_set(PmdInstance *inst, const char *fn, const char *text, int apply)
{
    const char *staged;
    if (!apply) {
        PmdRecordColumns c;
        memset(&c, 0, sizeof c);
        if (pmd_record_columns_compile(inst, fn, text, &c) != PMD_OK)
            return PMD_ERROR;
        /* recording goes on with the new rows: the buffer grows now, so that applying cannot fail; before
         * step mode nothing records until the end of initialization sizes the buffer for the columns and the
         * record.capacity then (which may still be 0 now) */
        if (inst->s.recordEnabled && inst->s.state == PMD_STEP_MODE &&
            record_reserve(inst, fn, c.rowBytes) != PMD_OK) {
            pmd_record_columns_free(&c);
            return PMD_ERROR;
        }
        pmd_record_columns_free(&inst->stagedColumns);
        inst->stagedColumns = c;
        return PMD_OK;
    }
    /* the call's last value was compiled last: an earlier one of the same call is overwritten anyway */
    staged = inst->stagedColumns.text ? inst->stagedColumns.text : "";
    if (strcmp(staged, text) == 0) {
        pmd_record_columns_free(&inst->columns);
        inst->columns = inst->stagedColumns;
        memset(&inst->stagedColumns, 0, sizeof inst->stagedColumns);
        pmd_record_columns_free(&inst->stagedColumns);
    }
    return PMD_OK;
}

/* Each case is a row of values.h's tables, the getters' (instance.c): the
 * value as its getter returns it, stored at each of the family's columns in
 * its width (a family has one type, hence one width), the columns of a family
 * one after the other (record.columns is kept in that order): one switch per
 * family and row. */
#define FAMILY_COLUMNS(F, store)                                                                                      \
    case F:                                                                                                           \
        do {                                                                                                          \
            unsigned i = c->index;                                                                                    \
            (void)i;                                                                                                  \
            store;                                                                                                    \
        } while (++c < last && c->family == F);                                                                       \
        break;
#define REAL_COLUMN(F, expression)                                                                                    \
    FAMILY_COLUMNS(F, double x = (expression); memcpy(row + c->offset, &x, sizeof x))
#define INTEGER_COLUMN(F, expression)                                                                                 \
    FAMILY_COLUMNS(F, int32_t n = (expression); uint16_t low = (uint16_t)(uint32_t)n;                                 \
                   if (c->bytes == 2) memcpy(row + c->offset, &low, sizeof low);                                      \
                   else memcpy(row + c->offset, &n, sizeof n))   /* 4: an Integer is 16 or 32 bits (compile) */
#define BOOLEAN_COLUMN(F, expression) FAMILY_COLUMNS(F, row[c->offset] = (expression) != 0)

/* A row: the chip time, then each column (checked when set: its family is
 * one of the tables', of the column's type). g: the grid as it stands. */
static inline void record_row(PmdInstance *inst, const PmdGrid *g, unsigned char *row)
{
    const PmdRecordColumn *c = inst->columns.column, *last = c + inst->columns.count;
    int32_t time = pmd_int32(inst->chip.s.time);
    PmdCommandedReals all;
    const PmdCommandedReals *reals = &all;
    if (inst->columns.readsReals)
        pmd_commanded_reals(&inst->chip, g->cycleTime, &all);
    memcpy(row, &time, sizeof time);
    while (c < last) {
        switch ((PmdFamily)c->family) {         /* every family: a new one is a build error here */
        PMD_REAL_VALUES(REAL_COLUMN)
        PMD_INTEGER_VALUES(INTEGER_COLUMN)
        PMD_BOOLEAN_VALUES(BOOLEAN_COLUMN)
        case VAR_script:
        case VAR_machine:
        case VAR_record_columns:
        case VAR_record_data:
        case VAR_FAMILY_COUNT:
            /* no number: pmd_record_columns_compile refuses such a column, and were one here, it would
             * keep the bytes it has (the row's layout stays that of record.columns) */
            c++;
            break;
        }
    }
}

/* A row per cycle of a chip run (pmd_chip_run_every_cycle_with_rows): where it
 * goes, and the grid as the row reads it (its own copy: the instance's
 * nextCycle is the instance's to advance). */
typedef struct {
    PmdInstance *inst;
    PmdGrid grid;
    unsigned char *row;
} Rows;

static void next_row(void *context)
{
    Rows *r = (Rows *)context;
    r->grid.nextCycle++;
    record_row(r->inst, &r->grid, r->row);
    r->row += r->inst->columns.rowBytes;
}

/* Whether a column reads the servo filter of an axis whose filter a run leaves to its end. */
static int reads_deferred(const PmdInstance *inst, unsigned deferred)
{
    const PmdRecordColumn *c = inst->columns.column, *last = c + inst->columns.count;
    for (; c < last; c++)
        if ((c->family == VAR_axis_motorCommand || c->family == VAR_axis_motorOutput) &&
            (deferred & (1u << c->index)))
            return 1;
    return 0;
}

/* The cycles as one chip run with a row after each cycle
 * (pmd_chip_run_every_cycle_with_rows) unless a column shows an ideal servo's
 * filter, which such a run brings up to date at its end (chip.c): then each
 * cycle alone (pmd_chip_run_every_cycle of one cycle). The grid stays as it
 * is: a cycle changes no part of it (only a host batch or a script step
 * changes the sample time, and they run between calls); each row has its own
 * next cycle. */
void pmd_record_cycles(PmdInstance *inst, const PmdGrid *grid, int64_t cycles, int64_t first)
{
    Rows r;
    int64_t i;
    r.inst = inst;
    r.grid = *grid;
    r.row = pmd_record_rows(inst) + (size_t)first * inst->columns.rowBytes;
    if (!reads_deferred(inst, pmd_chip_deferred_axes(&inst->chip))) {
        pmd_chip_run_every_cycle_with_rows(&inst->chip, cycles, next_row, &r);
        return;
    }
    for (i = 0; i < cycles; i++) {
        pmd_chip_run_every_cycle(&inst->chip, 1, NULL);
        next_row(&r);
    }
}
