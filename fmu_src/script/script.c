/* SPDX-License-Identifier: BSD-2-Clause */
/* Command scripts (docs/scripts.md): C-Motion calls grouped by the chip
 * cycle at which they run, compiled at initialization into host-command
 * words and memory blocks.
 *
 *     # comment (also //)
 *     @ 0                                      the calls below run before cycle 0
 *     SetBufferStart(Axis1, 2, 0x200);         axis first, then C-Motion's arguments
 *     PMDSetVelocity(PMDAxis1, 2.5);           decimals for 16.16 and 0.32 values
 *     SetProfileMode(Axis1, PMDExternalProfile);
 *     LoadSegmentTable(Axis1, "table.csv", 0x200, 2);
 *
 * LoadSegmentTable reads a CSV segment table into buffers firstBuffer.. at
 * address, one per column, and assigns them to the columns' trajectory
 * variables. The script is a file or, given as text, a string in memory
 * (a profile that travels inside the FMU or its parameter set);
 * relative paths are looked for in a fixed order of places (pmd_script_compile). */
#if !defined(_WIN32) && !defined(_POSIX_C_SOURCE)
#define _POSIX_C_SOURCE 200809L      /* open, fstat, fdopen, O_CLOEXEC: the build is strict C99 */
#endif
#include <ctype.h>
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#ifdef _WIN32
#include <direct.h>                  /* _getcwd */
#define getcwd _getcwd
#else
#include <fcntl.h>
#include <unistd.h>
#endif

#include "chip.h"
#include "command_table.h"
#include "script.h"
#include "wide.h"

/* A UTF-8 byte order mark, which some editors and Excel's "CSV UTF-8" put first: refused by name, as the
 * harness's files.read_text refuses it; read as text it was an invisible character in the first
 * command, column or key ("expected a key, a [table] or a comment" of a comment line). */
#define UTF8_BOM "\xEF\xBB\xBF"
#define BOM_REASON "the file begins with a UTF-8 byte order mark (BOM): save it as UTF-8 without one"
#define MAX_LINE 4096                /* a line has at most MAX_LINE - 1 characters besides its newline */
#define MAX_FILE (1L << 30)          /* bytes in a script or table; also keeps line numbers within an int */
#define TOO_LARGE "larger than 1 GiB, the limit for a script or table"
#define MAX_ARGS 8
#define MAX_PATH 1024                /* a path as looked for, its NUL included */

typedef struct {
    const char *file;
    int line;
    char *error;
    size_t errorSize;
} Where;

static int fail(const Where *w, const char *format, ...)
{
    char reason[6144];               /* a file not found names each place looked in (locate) */
    va_list args;
    va_start(args, format);
    vsnprintf(reason, sizeof reason, format, args);
    va_end(args);
    snprintf(w->error, w->errorSize, "%s:%d: %s", w->file, w->line, reason);
    return -1;
}

/* ---- growing arrays ---- */

static PmdScriptStep *new_step(PmdScript *s, int64_t cycle, int line)
{
    PmdScriptStep *step;
    if (s->count == s->capacity) {
        size_t capacity = s->capacity ? 2 * s->capacity : 64;
        PmdScriptStep *grown = (PmdScriptStep *)realloc(s->steps, capacity * sizeof *grown);
        if (!grown)
            return NULL;
        s->steps = grown;
        s->capacity = capacity;
    }
    step = &s->steps[s->count++];
    memset(step, 0, sizeof *step);
    step->cycle = cycle;
    step->line = line;
    return step;
}

/* Makes room for n more words at the end of the pool. */
static int pool_grow(PmdScript *s, size_t n)
{
    size_t capacity = s->poolCapacity ? s->poolCapacity : 1024;
    uint32_t *grown;
    if (s->poolCount + n <= s->poolCapacity)
        return 0;
    while (capacity < s->poolCount + n)
        capacity *= 2;
    if (!(grown = (uint32_t *)realloc(s->pool, capacity * sizeof *grown)))
        return -1;
    s->pool = grown;
    s->poolCapacity = capacity;
    return 0;
}


/* ---- reading: scripts and tables alike ---- */

/* A script or table being read line by line from its text in memory: a script
 * given as text, or a file's bytes read at once (read_file; one read instead
 * of a call per character, and a table's second pass reads the same bytes);
 * w.line is the line last read. */
typedef struct {
    Where w;
    long bytes;
    const char *text;                /* the text, its length and where reading stands */
    size_t length, at;
    char *owned;                     /* a file's bytes (text), freed by close_reader */
    int readError;                   /* errno of the read that stopped after `length` bytes, or 0 */
} Reader;

static void close_reader(Reader *r)
{
    free(r->owned);
    r->owned = NULL;
}

/* Opens a regular file of at most MAX_FILE bytes, or returns NULL with the
 * reason in why: a FIFO, a device or a directory would block or never end.
 * *size is the size the file has now. */
static FILE *open_text(const char *path, const char **why, long *size)
{
    FILE *file;
#ifdef _WIN32
    struct _stat st;
    if (_stat(path, &st) != 0)
        return *why = strerror(errno), NULL;
    if ((st.st_mode & _S_IFMT) != _S_IFREG)
        return *why = "not a regular file", NULL;
    if (st.st_size > MAX_FILE)
        return *why = TOO_LARGE, NULL;
    *size = (long)st.st_size;
    if (!(file = fopen(path, "rb")))
        *why = strerror(errno);
#else
    struct stat st;
    /* O_NONBLOCK: opening a FIFO must not wait for a writer; fstat then refuses it */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC), flags;
    if (fd < 0)
        return *why = strerror(errno), NULL;
    if (fstat(fd, &st) != 0)
        *why = strerror(errno);
    else if (!S_ISREG(st.st_mode))
        *why = "not a regular file";
    else if (st.st_size > MAX_FILE)
        *why = TOO_LARGE;
    else if ((flags = fcntl(fd, F_GETFL)) < 0 || fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0 ||
             !(file = fdopen(fd, "rb"))) {           /* a regular file is then read as usual */
        *why = strerror(errno);
    } else {
        *size = (long)st.st_size;
        return file;
    }
    close(fd);
    file = NULL;
#endif
    return file;
}

/* The most of a file read: a file that grows while being read stops at
 * MAX_FILE plus a line, so read_line's count still finds the line that takes
 * it past MAX_FILE (or that line too long) as reading line by line did. */
#define MAX_READ ((size_t)MAX_FILE + MAX_LINE + 1)

/* Reads the file opened by open_text (size bytes when it was opened) into
 * r->owned and closes it. A read error keeps the bytes before it and its errno
 * (read_line reports it at the line it cuts short). -1 if out of memory. */
static int read_file(Reader *r, FILE *file, long size)
{
    size_t capacity = (size_t)size + 1, length = 0;    /* + 1: the end is seen without growing */
    char *bytes = (char *)malloc(capacity);
    while (bytes) {
        size_t n = fread(bytes + length, 1, capacity - length, file);
        length += n;
        if (n == 0 || length >= MAX_READ) {
            if (ferror(file))
                r->readError = errno ? errno : EIO;
            break;
        }
        if (length == capacity) {                  /* the file grew since it was opened */
            char *grown;
            capacity = capacity < MAX_READ / 2 ? 2 * capacity : MAX_READ;
            if (!(grown = (char *)realloc(bytes, capacity))) {
                free(bytes);
                bytes = NULL;
            } else {
                bytes = grown;
            }
        }
    }
    fclose(file);
    if (!bytes)
        return -1;
    r->owned = bytes;
    r->text = bytes;
    r->length = length < MAX_READ ? length : MAX_READ;
    r->at = 0;
    return 0;
}

/* Opens and reads the file at path into r; -1 with the reason in why. */
static int open_reader(Reader *r, const char *path, const char **why)
{
    long size = 0;
    FILE *file = open_text(path, why, &size);
    if (!file)
        return -1;
    if (read_file(r, file, size)) {
        *why = "out of memory";
        return -1;
    }
    return 0;
}

/* Reads the next line, without its newline, into line[MAX_LINE]: 1, or 0 at
 * the end, or -1 with "file:line: reason" (a line too long, a NUL byte, a
 * read error, a file grown past MAX_FILE while being read). A line's first
 * MAX_LINE characters are looked at in order: a NUL byte among them is
 * reported before the line's length. */
static int read_line(Reader *r, char *line)
{
    const char *start = r->text + r->at, *end;
    size_t left = r->length - r->at, n;
    r->w.line++;
    end = (const char *)memchr(start, '\n', left);
    n = end ? (size_t)(end - start) : left;
    if (memchr(start, '\0', n < MAX_LINE ? n : MAX_LINE))
        return fail(&r->w, "NUL byte in the line (a script or table is text)");
    if (r->w.line == 1 && n >= 3 && memcmp(start, UTF8_BOM, 3) == 0)
        return fail(&r->w, BOM_REASON);
    if (n > MAX_LINE - 1)
        return fail(&r->w, "line longer than %d characters", MAX_LINE - 1);
    if (!end && r->readError)
        return fail(&r->w, "cannot read: %s", strerror(r->readError));
    if (!end && n == 0) {
        r->w.line--;
        return 0;
    }
    r->at += n + (end != NULL);
    if ((r->bytes += (long)n + 1) > MAX_FILE)
        return fail(&r->w, "the file grew " TOO_LARGE);
    memcpy(line, start, n);
    line[n] = '\0';
    return 1;
}

/* ---- values ---- */

static char *trim(char *t)
{
    char *end;
    while (isspace((unsigned char)*t))
        t++;
    end = t + strlen(t);
    while (end > t && isspace((unsigned char)end[-1]))
        *--end = '\0';
    return t;
}

/* A number: decimal or 0x-hex integer, or a decimal fraction d.ddd taken
 * exactly and rounded (halves away from zero) to `fixed` fraction bits. */
static int parse_number(const Where *w, const char *text, int fixed, int64_t *value)
{
    const char *p = text;
    int negative = 0, digits = 0, scale = 0, seen_point = 0;
    uint64_t mantissa = 0, ten = 1, rem, q;

    if (!*p)
        return fail(w, "a value is missing");
    if (*p == '-' || *p == '+')
        negative = *p++ == '-';
    if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X')) {
        static const char hex[] = "0123456789abcdef";
        const char *first = p += 2;
        /* hex digits only (strtoull would take blanks and a sign after the 0x) */
        for (; isxdigit((unsigned char)*p) && mantissa <= 0xFFFFFFFF; p++)
            mantissa = mantissa * 16 + (uint64_t)(strchr(hex, tolower((unsigned char)*p)) - hex);
        if (p == first || *p || mantissa > 0xFFFFFFFF)
            return fail(w, "'%s' is not a 32-bit hexadecimal number", text);
        *value = negative ? -(int64_t)mantissa : (int64_t)mantissa;
        return 0;
    }
    for (; *p; p++) {
        if (*p == '.' && !seen_point) {
            seen_point = 1;
        } else if (isdigit((unsigned char)*p) && digits < 18) {
            mantissa = mantissa * 10 + (uint64_t)(*p - '0');
            digits++;
            scale += seen_point;
        } else {
            return fail(w, "'%s' is not a number (at most 18 digits)", text);
        }
    }
    if (digits == 0)
        return fail(w, "'%s' is not a number", text);
    if (seen_point && !fixed)
        return fail(w, "'%s': a decimal fraction is allowed only for 16.16 and 0.32 values", text);
    while (scale-- > 0)
        ten *= 10;
    if (fixed) {                                   /* mantissa * 2^fixed / 10^scale, rounded */
        q = pmd_muldiv(mantissa, (uint64_t)1 << fixed, ten, &rem);
        if (rem * 2 >= ten)
            q++;
        if (q > (negative ? 0x80000000ull : 0x7FFFFFFFull))    /* a signed 32-bit word */
            return fail(w, "'%s' does not fit a %s value", text, fixed == 16 ? "16.16" : "0.32");
        mantissa = q;
    }
    *value = negative ? -(int64_t)mantissa : (int64_t)mantissa;
    return 0;
}

/* A value: a C-Motion constant name, or a number. */
static int parse_value(const Where *w, const char *text, int fixed, int64_t *value)
{
    int i;
    if (isalpha((unsigned char)*text) || *text == '_') {
        for (i = 0; i < PMD_CONSTANT_COUNT; i++) {
            if (strcmp(pmd_constants[i].name, text) == 0) {
                *value = pmd_constants[i].value;
                return 0;
            }
        }
        return fail(w, "'%s' is not a C-Motion constant", text);
    }
    return parse_number(w, text, fixed, value);
}

static int parse_axis(const Where *w, const char *text, int *axis)
{
    const char *t = strncmp(text, "PMD", 3) == 0 ? text + 3 : text;
    if (strncmp(t, "Axis", 4) == 0 && t[4] >= '1' && t[4] <= '4' && t[5] == '\0') {
        *axis = t[4] - '1';
        return 0;
    }
    return fail(w, "'%s' is not an axis (Axis1..Axis4 or PMDAxis1..PMDAxis4)", text);
}

/* Range of a field as the host port carries it: unsigned words may also be
 * written as their two's-complement negative, signed ones as their raw word. */
static int check_range(const Where *w, const char *command, const PmdField *f, int64_t v)
{
    int64_t lo, hi;
    switch (f->kind) {
    case PMD_BITS: lo = 0; hi = (1 << f->width) - 1; break;
    case PMD_U16: case PMD_I16: lo = -32768; hi = 65535; break;
    default: lo = -(int64_t)0x80000000; hi = 0xFFFFFFFF; break;
    }
    if (v < lo || v > hi)
        return fail(w, "%s: %lld does not fit the argument", command, (long long)v);
    return 0;
}

/* ---- commands ---- */

static int add_command(PmdScript *s, const Where *w, int64_t cycle, const PmdCommand *c, int axis,
                       const int64_t *values)
{
    PmdScriptStep *step = new_step(s, cycle, w->line);
    int k;
    if (!step)
        return fail(w, "out of memory");
    step->words[0] = (uint16_t)PMD_FIELD_DP(PMD_FIELD_DP(0, PMDInstructionOpcode, c->opcode), PMDInstructionAxis,
                                           c->chipWide ? 0 : axis);
    for (k = 0; k < c->nArgs; k++)
        pmd_encode_field(&c->args[k], values[k], step->words + 1);
    step->nWords = (uint16_t)(1 + c->argWords);
    return 0;
}

static const PmdCommand *find_command(const char *name)
{
    int i;
    if (strncmp(name, "PMD", 3) == 0)
        name += 3;
    for (i = 0; i < PMD_COMMAND_COUNT; i++)
        if (strcmp(pmd_commands[i].name, name) == 0)
            return &pmd_commands[i];
    return NULL;
}

/* Splits "Name(a, b, c);" into name and trimmed arguments (quotes kept). */
static int split_call(const Where *w, char *text, char **name, char **args, int *nArgs)
{
    char *open = strchr(text, '('), *close = strrchr(text, ')'), *p, *rest;
    int quoted = 0;
    if (!open || !close || close < open)
        return fail(w, "expected Command(Axis, arguments...), got '%s'", text);
    rest = trim(close + 1);
    if (*rest && strcmp(rest, ";") != 0)
        return fail(w, "unexpected '%s' after the call", rest);
    *open = *close = '\0';
    *name = trim(text);
    *nArgs = 0;
    for (p = open + 1;;) {
        char *start = p;
        while (*p && (quoted || *p != ',')) {
            if (*p == '"')
                quoted = !quoted;
            p++;
        }
        if (*nArgs == MAX_ARGS)
            return fail(w, "too many arguments");
        args[(*nArgs)++] = start;
        if (!*p)
            break;
        *p++ = '\0';
    }
    for (quoted = 0; quoted < *nArgs; quoted++)
        args[quoted] = trim(args[quoted]);
    if (*nArgs == 1 && !*args[0])
        *nArgs = 0;
    return 0;
}

/* ---- segment tables ---- */

static const char *const columns[PMD_FUNCTIONS] = {"position", "velocity", "acceleration", "jerk", "time"};

/* Splits a CSV line into trimmed cells, keeping the first max; returns how
 * many there are. */
static int split_csv(char *line, char **cells, int max)
{
    int n = 0;
    char *p = line;
    for (;;) {
        char *comma = strchr(p, ',');
        if (comma)
            *comma = '\0';
        if (n < max)
            cells[n] = trim(p);
        n++;
        if (!comma)
            return n;
        p = comma + 1;
    }
}

/* The column a misspelt header cell was meant to be: the nearest by edit
 * distance (at most a third of its letters wrong), or NULL. */
static const char *nearest_column(const char *cell)
{
    const char *best = NULL;
    size_t n = strlen(cell), bestDistance = n / 3 + 1, row[16], i, j;
    int f;
    if (n >= sizeof row / sizeof row[0])
        return NULL;
    for (f = 0; f < PMD_FUNCTIONS; f++) {
        const char *c = columns[f];
        size_t m = strlen(c), diagonal;
        for (i = 0; i <= n; i++)
            row[i] = i;
        for (j = 1; j <= m; j++) {           /* Levenshtein, one row kept */
            diagonal = row[0];
            row[0] = j;
            for (i = 1; i <= n; i++) {
                size_t up = row[i], cost = tolower((unsigned char)cell[i - 1]) != c[j - 1];
                size_t best3 = diagonal + cost;
                if (up + 1 < best3)
                    best3 = up + 1;
                if (row[i - 1] + 1 < best3)
                    best3 = row[i - 1] + 1;
                diagonal = up;
                row[i] = best3;
            }
        }
        if (row[n] < bestDistance) {
            bestDistance = row[n];
            best = c;
        }
    }
    return best;
}

/* The header names the columns: each a trajectory variable, each at most
 * once. Returns the number of columns, or -1. */
static int read_header(const Where *w, char *text, int *columnOf)
{
    char *cells[PMD_FUNCTIONS];
    int n = split_csv(text, cells, PMD_FUNCTIONS), f, k;
    if (n > PMD_FUNCTIONS)
        return fail(w, "%d columns: a segment table has at most one each of position, velocity, acceleration, "
                       "jerk, time", n);
    for (k = 0; k < n; k++) {
        for (f = 0; f < PMD_FUNCTIONS && strcmp(cells[k], columns[f]) != 0; f++)
            ;
        if (f == PMD_FUNCTIONS) {
            const char *near = nearest_column(cells[k]);
            return fail(w, "column '%s' is not a segment column (position, velocity, acceleration, jerk, time)%s%s%s",
                        cells[k], near ? ": did you mean '" : "", near ? near : "", near ? "'?" : "");
        }
        if (columnOf[f] >= 0)
            return fail(w, "column '%s' named twice", cells[k]);
        columnOf[f] = k;
    }
    if (columnOf[0] < 0)
        return fail(w, "a segment table needs a position column");
    return n;
}

/* What a column's 32-bit words hold: a segment time is unsigned, the others either reading. */
static int fits_column(int f, int64_t v)
{
    return f == PMDBufferFunctionTime ? v >= 0 && v <= 0xFFFFFFFF : v >= -(int64_t)0x80000000 && v <= 0xFFFFFFFF;
}

/* A row read the common way, in place (a table of 10^5 rows spends its time
 * here): every cell a decimal integer of at most 18 digits, which parse_number
 * would read as the same value (scaled to the cell's fraction bits), as many
 * cells as columns, each value fitting its column. Returns 0 with values[f] for
 * each column's function f, or -1 for any other row, which load_table then
 * reads cell by cell: its first error is reported as it always was. */
static int plain_row(const char *p, int nColumns, const int *functionOfCell, const int *fixedOfCell, int64_t *values)
{
    int n;
    for (n = 0; n < nColumns; n++) {
        uint64_t mantissa = 0;
        int negative = 0, digits = 0;
        int64_t v;
        while (isspace((unsigned char)*p))
            p++;
        if (*p == '-' || *p == '+')
            negative = *p++ == '-';
        for (; *p >= '0' && *p <= '9' && digits < 18; p++, digits++)
            mantissa = mantissa * 10 + (uint64_t)(*p - '0');
        if (digits == 0 || (*p >= '0' && *p <= '9'))
            return -1;
        while (isspace((unsigned char)*p))
            p++;
        if (*p != ',' && *p != '\0')
            return -1;
        if (fixedOfCell[n]) {                      /* mantissa * 2^fixed, a signed 32-bit word (parse_number) */
            if (mantissa > (negative ? 0x80000000ull : 0x7FFFFFFFull) >> fixedOfCell[n])
                return -1;
            mantissa <<= fixedOfCell[n];
        }
        v = negative ? -(int64_t)mantissa : (int64_t)mantissa;
        if (!fits_column(functionOfCell[n], v))
            return -1;
        values[functionOfCell[n]] = v;
        if (*p++ == '\0')
            return n + 1 == nColumns ? 0 : -1;
    }
    return -1;                                     /* more cells than columns */
}

/* Reads the table; emits, at `cycle`, buffer set-up commands and one memory
 * block per column. Units: "# units: raw" (default: the chip's words) or
 * "# units: counts/cycle" (decimals for velocity, acceleration and jerk). */
static int load_table(PmdScript *s, const Where *at, int64_t cycle, int axis, const char *path, int64_t address,
                      int64_t firstBuffer, uint32_t memoryWords)
{
    static const int fixedOfColumn[PMD_FUNCTIONS] = {0, 16, 16, 32, 0};
    char line[MAX_LINE], *cells[PMD_FUNCTIONS];
    int columnOf[PMD_FUNCTIONS], functionOfCell[PMD_FUNCTIONS], fixedOfCell[PMD_FUNCTIONS];
    int nColumns = 0, present = 0, units = -1, header, got, f, k;
    int64_t values[PMD_FUNCTIONS];
    size_t rows = 0, row, base = s->poolCount;
    const char *why = "";
    Reader in;

    memset(&in, 0, sizeof in);
    in.w = *at;
    in.w.file = path;
    in.w.line = 0;
    if (open_reader(&in, path, &why))
        return fail(at, "cannot open segment table %s: %s", path, why);
    for (f = 0; f < PMD_FUNCTIONS; f++)
        columnOf[f] = -1;
    /* pass 1 reads the header and counts rows; pass 2 stores the columns one after another */
    while ((got = read_line(&in, line)) == 1) {
        char *t = line;
        while (isspace((unsigned char)*t))       /* a row is only counted: trimmed when it is read */
            t++;
        if (*t == '#') {
            char *text = strstr(trim(t), "units:");
            int counts;
            if (!text)
                continue;
            text = trim(text + 6);
            counts = strcmp(text, "counts/cycle") == 0;
            if (!counts && strcmp(text, "raw") != 0)
                return close_reader(&in), fail(&in.w, "units '%s': say raw or counts/cycle", text);
            if (units >= 0 && units != counts)
                return close_reader(&in), fail(&in.w, "units '%s' contradict the units stated before", text);
            units = counts;
            continue;
        }
        if (!*t)
            continue;
        if (!nColumns) {
            if ((nColumns = read_header(&in.w, trim(t), columnOf)) < 0)
                return close_reader(&in), -1;
            continue;
        }
        rows++;
    }
    if (got < 0)
        return close_reader(&in), -1;
    if (!nColumns || rows == 0)
        return close_reader(&in), fail(&in.w, "no header or no rows");
    for (f = 0; f < PMD_FUNCTIONS; f++)
        present += columnOf[f] >= 0;
    if (address < 0 || address + (int64_t)(present * rows) > (int64_t)memoryWords)
        return close_reader(&in), fail(at, "%zu rows x %d columns at 0x%llX leave the %u-word memory", rows, present,
                                     (long long)address, (unsigned)memoryWords);
    if (firstBuffer < PMD_FIRST_PROFILE_BUFFER || firstBuffer + present > PMD_BUFFERS)
        return close_reader(&in), fail(at, "buffers %lld.. do not fit IDs 2..31", (long long)firstBuffer);
    /* pass 2: every row once, each present column into its own block of the pool */
    if (pool_grow(s, (size_t)present * rows))
        return close_reader(&in), fail(at, "out of memory");
    for (f = 0; f < PMD_FUNCTIONS; f++) {
        if (columnOf[f] >= 0) {
            functionOfCell[columnOf[f]] = f;
            fixedOfCell[columnOf[f]] = units == 1 ? fixedOfColumn[f] : 0;
        }
    }
    in.at = 0;
    in.w.line = 0;
    in.bytes = 0;
    got = 1;
    for (row = 0, header = 0; row < rows && (got = read_line(&in, line)) == 1;) {
        char *t = line;
        int n;
        while (isspace((unsigned char)*t))
            t++;
        if (*t == '#' || !*t)
            continue;
        if (!header) {
            header = 1;
            continue;
        }
        if (plain_row(t, nColumns, functionOfCell, fixedOfCell, values) == 0) {
            for (f = 0, k = 0; f < PMD_FUNCTIONS; f++)
                if (columnOf[f] >= 0)
                    s->pool[base + (size_t)k++ * rows + row] = (uint32_t)(values[f] & 0xFFFFFFFF);
            row++;
            continue;
        }
        t = trim(t);
        if ((n = split_csv(t, cells, PMD_FUNCTIONS)) != nColumns)
            return close_reader(&in), fail(&in.w, "expected %d values (one per column), found %d", nColumns, n);
        for (f = 0, k = 0; f < PMD_FUNCTIONS; f++) {
            int64_t v;
            if (columnOf[f] < 0)
                continue;
            if (parse_number(&in.w, cells[columnOf[f]], units == 1 ? fixedOfColumn[f] : 0, &v))
                return close_reader(&in), -1;
            if (!fits_column(f, v))
                return close_reader(&in), fail(&in.w, "%s %s does not fit 32 bits", columns[f], cells[columnOf[f]]);
            s->pool[base + (size_t)k++ * rows + row] = (uint32_t)(v & 0xFFFFFFFF);
        }
        row++;
    }
    close_reader(&in);
    if (got < 0)
        return -1;
    s->poolCount = base + (size_t)present * rows;
    /* buffers firstBuffer.. at address.., one per present column, then the data */
    for (f = 0, k = 0; f < PMD_FUNCTIONS; f++) {
        int64_t id = firstBuffer + k, start = address + (int64_t)(k * rows);
        int64_t a[3];
        PmdScriptStep *block;
        if (columnOf[f] < 0)
            continue;
        a[0] = id; a[1] = start;
        if (add_command(s, at, cycle, find_command("SetBufferStart"), axis, a))
            return -1;
        a[1] = (int64_t)rows;
        if (add_command(s, at, cycle, find_command("SetBufferLength"), axis, a))
            return -1;
        a[0] = f; a[1] = id;
        if (add_command(s, at, cycle, find_command("SetBufferFunction"), axis, a))
            return -1;
        if (!(block = new_step(s, cycle, at->line)))
            return fail(at, "out of memory");
        block->address = (uint32_t)start;
        block->count = (uint32_t)rows;
        block->first = base + (size_t)k * rows;
        k++;
    }
    return 0;
}

/* ---- where files are: relative paths are looked for in places, in order ---- */

#ifdef _WIN32
#define IS_SEPARATOR(c) ((c) == '/' || (c) == '\\')
#else
#define IS_SEPARATOR(c) ((c) == '/')
#endif

int pmd_script_is_text(const char *value)
{
    return strchr(value, '\n') != NULL;
}

static int is_absolute(const char *path)
{
#ifdef _WIN32
    if (isalpha((unsigned char)path[0]) && path[1] == ':')
        return 1;                                   /* C:\x, and C:x, which names its drive too */
#endif
    return IS_SEPARATOR(path[0]);
}

/* A folder a relative path is looked for in: the first length bytes of folder,
 * or the working directory (folder NULL); missing says why it is unknown. */
typedef struct {
    const char *label;
    const char *folder;
    size_t length;
    const char *missing;
} Place;

#define MAX_PLACES 2

typedef struct {
    Place place[MAX_PLACES];
    int count;
} Places;

static void add_place(Places *p, const char *label, const char *folder, size_t length, const char *missing)
{
    Place *place = &p->place[p->count++];
    place->label = label;
    place->folder = folder;
    place->length = length;
    place->missing = missing;
}

/* The FMU's resources folder as a place, if there is one to speak of. */
static void add_resources(Places *p, const PmdScriptPlaces *places)
{
    if (places->resources)
        add_place(p, "the FMU's resources folder", places->resources, strlen(places->resources), NULL);
    else if (places->noResources)
        add_place(p, "the FMU's resources folder", NULL, 0, places->noResources);
}

/* path in place into out[MAX_PATH]; -1 if it does not fit. */
static int join(const Place *place, const char *path, char *out)
{
    int n;
    if (!place->folder)
        n = snprintf(out, MAX_PATH, "%s", path);
    else if (place->length && IS_SEPARATOR(place->folder[place->length - 1]))
        n = snprintf(out, MAX_PATH, "%.*s%s", (int)place->length, place->folder, path);
    else
        n = snprintf(out, MAX_PATH, "%.*s/%s", (int)place->length, place->folder, path);
    return n < 0 || n >= MAX_PATH ? -1 : 0;
}

static int exists(const char *path)
{
#ifdef _WIN32
    struct _stat st;
    return _stat(path, &st) == 0;
#else
    struct stat st;
    return stat(path, &st) == 0;
#endif
}

/* Puts path into out[MAX_PATH]: absolute as it is, relative joined to the first
 * place where it exists. Else -1 with, in why, each place looked in: the path
 * looked for there and why it is not (the working directory by its name). */
static int locate(const char *path, const Places *places, char *out, char *why, size_t whySize)
{
    size_t used = 0;
    int i;
    why[0] = '\0';
    if (is_absolute(path)) {
        if (strlen(path) < MAX_PATH) {
            strcpy(out, path);
            return 0;
        }
        snprintf(why, whySize, "the path is longer than %d characters", MAX_PATH - 1);
        return -1;
    }
    for (i = 0; i < places->count; i++) {
        const Place *place = &places->place[i];
        char cwd[MAX_PATH];
        const char *reason, *folder = "", *separator = "";
        int n;
        if (place->missing) {
            n = snprintf(why + used, whySize - used, "%s%s (none: %s)", i ? " nor in " : "not found in ", place->label,
                         place->missing);
        } else {
            if (join(place, path, out))
                reason = "the path is too long";
            else if (exists(out))
                return 0;
            else
                reason = strerror(errno);
            if (!place->folder && getcwd(cwd, sizeof cwd)) {
                folder = cwd;
                separator = "/";
            }
            n = snprintf(why + used, whySize - used, "%s%s (%s%s%s: %s)", i ? " nor in " : "not found in ",
                         place->label, folder, separator, place->folder ? out : path, reason);
        }
        if (n < 0 || (size_t)n >= whySize - used)
            break;                                  /* the message is cut short, nothing else */
        used += (size_t)n;
    }
    return -1;
}

/* Notes a table the script loads (pack and the log name them). */
static int note_table(PmdScript *s, int line, const char *name, const char *path)
{
    PmdScriptTable *grown = (PmdScriptTable *)realloc(s->tables, (s->tableCount + 1) * sizeof *grown);
    PmdScriptTable *t;
    if (!grown)
        return -1;
    s->tables = grown;
    t = &s->tables[s->tableCount];
    t->line = line;
    t->name = (char *)malloc(strlen(name) + 1);
    t->path = (char *)malloc(strlen(path) + 1);
    if (!t->name || !t->path) {
        free(t->name);
        free(t->path);
        return -1;
    }
    strcpy(t->name, name);
    strcpy(t->path, path);
    s->tableCount++;
    return 0;
}

/* ---- the script ---- */

static int compile_line(PmdScript *s, const Where *w, char *text, int64_t *cycle, uint32_t memoryWords,
                        const Places *tables)
{
    char *name = NULL, *args[MAX_ARGS] = {NULL};
    int nArgs = 0, axis = 0, k;
    int64_t values[MAX_ARGS];
    const PmdCommand *c;

    if (*text == '@') {
        int64_t next;
        if (parse_number(w, trim(text + 1), 0, &next))
            return -1;
        if (next < 0)
            return fail(w, "a time is a chip cycle >= 0");
        if (next < *cycle)
            return fail(w, "time %lld comes before %lld: times must not go back", (long long)next,
                        (long long)*cycle);
        *cycle = next;
        s->lastCycle = next;
        return 0;
    }
    if (split_call(w, text, &name, args, &nArgs))
        return -1;
    if (nArgs == 0)
        return fail(w, "%s: the first argument is the axis", name);
    if (parse_axis(w, args[0], &axis))
        return -1;
    s->axes |= (uint8_t)(PMDAxis1Mask << axis);
    if (strcmp(name, "LoadSegmentTable") == 0) {
        char path[MAX_PATH], why[4 * MAX_PATH];
        const char *table;
        size_t len;
        int64_t address, first;
        if (nArgs != 4)
            return fail(w, "LoadSegmentTable(Axis, \"file.csv\", address, firstBuffer)");
        len = strlen(args[1]);
        if (args[1][0] != '"' || len < 2 || args[1][len - 1] != '"')
            return fail(w, "LoadSegmentTable(Axis, \"file.csv\", address, firstBuffer)");
        table = args[1] + 1;                 /* only now: args[1] exists */
        args[1][len - 1] = '\0';
        if (strchr(table, '"'))
            return fail(w, "LoadSegmentTable: a quote inside the file name %s\"", args[1]);
        if (strlen(table) >= MAX_PATH)
            return fail(w, "LoadSegmentTable: the table's path is longer than %d characters", MAX_PATH - 1);
        if (parse_value(w, args[2], 0, &address) || parse_value(w, args[3], 0, &first))
            return -1;
        if (locate(table, tables, path, why, sizeof why))
            return fail(w, "cannot open segment table %s: %s", table, why);
        if (note_table(s, w->line, table, path))
            return fail(w, "out of memory");
        return load_table(s, w, *cycle, axis, path, address, first, memoryWords);
    }
    if (!(c = find_command(name)))
        return fail(w, "'%s' is not a command of this chip (see docs/commands.md)", name);
    if (nArgs - 1 != c->nArgs)
        return fail(w, "%s takes the axis and %d arguments, not %d", c->name, c->nArgs, nArgs - 1);
    for (k = 0; k < c->nArgs; k++)
        if (parse_value(w, args[k + 1], c->args[k].fixed, &values[k]) ||
            check_range(w, c->name, &c->args[k], values[k]))
            return -1;
    return add_command(s, w, *cycle, c, axis, values);
}

/* Compiles what in reads, line by line; 0, or -1 with the reason in in->w.error. */
static int compile(PmdScript *script, Reader *in, uint32_t memoryWords, const Places *tables)
{
    char line[MAX_LINE];
    int64_t cycle = 0;
    int got;
    while ((got = read_line(in, line)) == 1) {
        char *text, *comment;
        int quoted = 0;
        for (comment = line; *comment; comment++) {      /* '#' or '//' outside quotes */
            if (*comment == '"')
                quoted = !quoted;
            if (!quoted && (*comment == '#' || (comment[0] == '/' && comment[1] == '/'))) {
                *comment = '\0';
                break;
            }
        }
        text = trim(line);
        if (*text && compile_line(script, &in->w, text, &cycle, memoryWords, tables))
            return -1;
    }
    return got;
}

/* The script's value: text, or a file found in places; its tables are looked for in the places that
 * follow from where the script is. */
static int compile_value(const char *value, int isText, const PmdScriptPlaces *places, uint32_t memoryWords,
                         PmdScript *script, char *error, size_t errorSize)
{
    char path[MAX_PATH], why[4 * MAX_PATH];
    const char *name = PMD_SCRIPT_TEXT_NAME, *folderEnd = NULL, *p;
    Places scripts, tables;
    Reader in;
    int result;

    memset(script, 0, sizeof *script);
    memset(&in, 0, sizeof in);
    memset(&scripts, 0, sizeof scripts);
    memset(&tables, 0, sizeof tables);
    error[0] = '\0';
    if (isText) {
        if (strlen(value) > (size_t)MAX_FILE) {
            snprintf(error, errorSize, "%s: " TOO_LARGE, name);
            return -1;
        }
        in.text = value;
        in.length = strlen(value);
        add_resources(&tables, places);
        add_place(&tables, "the working directory", NULL, 0, NULL);
    } else {
        const char *reason = "";
        add_resources(&scripts, places);
        add_place(&scripts, "the working directory", NULL, 0, NULL);
        if (locate(value, &scripts, path, why, sizeof why)) {
            snprintf(error, errorSize, "%s: cannot open the script: %s", value, why);
            return -1;
        }
        if (open_reader(&in, path, &reason)) {
            snprintf(error, errorSize, "%s: cannot open the script: %s", path, reason);
            return -1;
        }
        name = path;
        for (p = path; *p; p++)
            if (IS_SEPARATOR(*p))
                folderEnd = p;
        if (folderEnd)
            add_place(&tables, "the script's folder", path, (size_t)(folderEnd - path), NULL);
        else
            add_place(&tables, "the script's folder", NULL, 0, NULL);
        add_resources(&tables, places);
    }
    if (!(script->name = (char *)malloc(strlen(name) + 1))) {
        close_reader(&in);
        snprintf(error, errorSize, "%s: out of memory", name);
        return -1;
    }
    strcpy(script->name, name);
    in.w.file = script->name;
    in.w.error = error;
    in.w.errorSize = errorSize;
    /* a table in the script's folder is looked for from the name kept, which outlives path */
    if (!isText && tables.place[0].folder)
        tables.place[0].folder = script->name;
    result = compile(script, &in, memoryWords, &tables);
    close_reader(&in);
    if (result != 0) {
        pmd_script_free(script);
        return -1;
    }
    return 0;
}

int pmd_script_compile(const char *value, const PmdScriptPlaces *places, uint32_t memoryWords, PmdScript *script,
                       char *error, size_t errorSize)
{
    return compile_value(value, pmd_script_is_text(value), places, memoryWords, script, error, errorSize);
}

int pmd_script_load(const char *path, uint32_t memoryWords, PmdScript *script, char *error, size_t errorSize)
{
    static const PmdScriptPlaces nowhere = {NULL, NULL};
    return compile_value(path, 0, &nowhere, memoryWords, script, error, errorSize);
}

int pmd_script_read_start(const char *resources, char **value, char *error, size_t errorSize)
{
    char path[MAX_PATH];
    const char *why = "";
    FILE *file;
    long n = 0, size;
    int c;
    *value = NULL;
    error[0] = '\0';
    if (snprintf(path, sizeof path, "%s%s" PMD_SCRIPT_START, resources,
                 *resources && IS_SEPARATOR(resources[strlen(resources) - 1]) ? "" : "/") >= (int)sizeof path) {
        snprintf(error, errorSize, "%s" PMD_SCRIPT_START ": the path is longer than %d characters", resources,
                 MAX_PATH - 1);
        return -1;
    }
    if (!exists(path))
        return 0;
    if (!(file = open_text(path, &why, &size))) {
        snprintf(error, errorSize, "%s: cannot open: %s", path, why);
        return -1;
    }
    while ((c = getc(file)) != EOF && c != '\0')
        n++;
    if (c == '\0' || ferror(file) || n > MAX_FILE || !(*value = (char *)malloc((size_t)n + 1))) {
        snprintf(error, errorSize, "%s: %s", path, c == '\0' ? "NUL byte (a String value is text)"
                                                   : ferror(file) ? strerror(errno) : "out of memory");
        fclose(file);
        return -1;
    }
    rewind(file);
    if (fread(*value, 1, (size_t)n, file) != (size_t)n) {
        snprintf(error, errorSize, "%s: the file changed while being read", path);
        free(*value);
        *value = NULL;
        fclose(file);
        return -1;
    }
    (*value)[n] = '\0';
    fclose(file);
    return 1;
}

void pmd_script_free(PmdScript *script)
{
    size_t i;
    for (i = 0; i < script->tableCount; i++) {
        free(script->tables[i].name);
        free(script->tables[i].path);
    }
    free(script->tables);
    free(script->name);
    free(script->steps);
    free(script->pool);
    memset(script, 0, sizeof *script);
}

uint64_t pmd_fnv1a(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = (const unsigned char *)data;
    size_t i;
    for (i = 0; i < n; i++) {
        h ^= p[i];
        h *= 1099511628211u;
    }
    return h;
}

/* The steps are zeroed before they are filled (new_step): no padding byte varies. */
uint64_t pmd_script_digest(const PmdScript *script)
{
    uint64_t h;
    if (script->count == 0)
        return 0;
    h = pmd_fnv1a(PMD_FNV1A_BASIS, script->steps, script->count * sizeof *script->steps);
    h = pmd_fnv1a(h, script->pool, script->poolCount * sizeof *script->pool);
    return (h & (uint64_t)INT64_MAX) | 1u;          /* never 0: that means no script */
}

int pmd_parameter_file(const char *value, const PmdScriptPlaces *places, const char *what, char **text, char **name,
                       char *error, size_t errorSize)
{
    char path[MAX_PATH], why[4 * MAX_PATH];
    const char *reason = "";
    Places files;
    Reader in;
    memset(&in, 0, sizeof in);
    memset(&files, 0, sizeof files);
    *text = *name = NULL;
    add_resources(&files, places);
    add_place(&files, "the working directory", NULL, 0, NULL);
    if (locate(value, &files, path, why, sizeof why)) {
        snprintf(error, errorSize, "%s: cannot open the %s: %s", value, what, why);
        return -1;
    }
    if (open_reader(&in, path, &reason)) {
        snprintf(error, errorSize, "%s: cannot open the %s: %s", path, what, reason);
        return -1;
    }
    if (memchr(in.text, '\0', in.length)) {
        close_reader(&in);
        snprintf(error, errorSize, "%s: NUL byte in the file (a %s is text)", path, what);
        return -1;
    }
    if (in.length >= 3 && memcmp(in.text, UTF8_BOM, 3) == 0) {
        close_reader(&in);
        snprintf(error, errorSize, "%s:1: %s", path, BOM_REASON);
        return -1;
    }
    if ((*text = (char *)malloc(in.length + 1)) != NULL && (*name = (char *)malloc(strlen(path) + 1)) != NULL) {
        memcpy(*text, in.text, in.length);
        (*text)[in.length] = '\0';
        strcpy(*name, path);
        close_reader(&in);
        return 0;
    }
    free(*text);
    *text = NULL;
    close_reader(&in);
    snprintf(error, errorSize, "%s: out of memory", path);
    return -1;
}
