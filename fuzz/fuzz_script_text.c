/* SPDX-License-Identifier: BSD-2-Clause */
/* Fuzz target: a script given as text (the `script` parameter's
 * value is the script itself when it holds a line feed), compiled by
 * pmd_script_compile with a resources folder as the FMU gives it.
 *
 *   input = flags byte, then the script text, NUL, the table t.csv, NUL,
 *           the table "sub dir/u.csv" (the rest; each part may be empty or missing)
 *
 *   flags bits 0-1  the places: 0 a resources folder ending in '/', 1 the same
 *                   without the '/', 2 no resources folder with a reason (FMI 3's
 *                   NULL resourcePath), 3 none at all (a script outside an FMU)
 *         bits 2-3  memory words: 0x4000, 0x10000, 0x100, 0
 *         bits 4-5  size of the error buffer: 8192 (the FMU's), 256, 24, 1
 *
 * The text gets a line feed at its end if it holds none (else it would be a
 * path). "{res}" in the text stands for the resources folder's absolute path
 * (no '/' at its end), so that absolute table paths are reached too. The
 * tables are written into the resources folder, a temporary folder of this
 * process, before every run (relative paths not found there are looked for in
 * the working directory, as the FMU does).
 *
 * Properties (abort() on a violation, after "property violated: ..."):
 *   - no sanitizer report (ASan, UBSan; the error buffer is a heap block of
 *     exactly its size, so a write past it shows);
 *   - a refusal says why ("name:line: reason", within the buffer), names
 *     "(script text)" at a line the text has or a table's path, and leaves
 *     the script empty;
 *   - a compiled script is consistent: named "(script text)", steps in time
 *     order at lines of the text, at most PMD_SCRIPT_WORDS words, memory blocks
 *     inside the memory and the pool, axes 1..4, every table's path a file;
 *   - text and file agree: with a resources folder, the same bytes compiled as
 *     a file in that folder (its tables then looked for in the script's folder,
 *     which is the resources folder) give the same steps, pool and tables, or
 *     the same refusal at the same line; they may differ only where the text
 *     found a table in the working directory.
 *
 * FUZZ_TEXT_TRACE=1 prints what each input compiled to, or why it was refused. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fuzz_property.h"
#include "script.h"

static char root[64], res[96];       /* the temporary folder and its resources folder (no '/' at the end) */

static void put_file(const char *name, const uint8_t *data, size_t n)
{
    char path[256];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", res, name);
    if (!(f = fopen(path, "wb")) || fwrite(data, 1, n, f) != n || fclose(f) != 0)
        violated("cannot write %s", path);
}

static void remove_files(void)
{
    static const char *const names[] = {"t.csv", "sub dir/u.csv", "s.script"};
    char path[256];
    size_t i;
    for (i = 0; i < sizeof names / sizeof *names; i++) {
        snprintf(path, sizeof path, "%s/%s", res, names[i]);
        unlink(path);
    }
    snprintf(path, sizeof path, "%s/sub dir", res);
    rmdir(path);
    rmdir(res);
    rmdir(root);
}

static void make_folders(void)
{
    char path[256];
    snprintf(root, sizeof root, "/tmp/pmdfuzz-text-%d", (int)getpid());
    snprintf(res, sizeof res, "%s/resources", root);
    snprintf(path, sizeof path, "%s/sub dir", res);
    mkdir(root, 0700);
    mkdir(res, 0700);
    mkdir(path, 0700);
    atexit(remove_files);
}

/* The part of data up to the next NUL (or the end); *at moves past the NUL. */
static size_t part(const uint8_t *data, size_t size, size_t *at, const uint8_t **start)
{
    const uint8_t *nul;
    size_t n;
    *start = data + *at;
    nul = *at < size ? (const uint8_t *)memchr(*start, 0, size - *at) : NULL;
    n = nul ? (size_t)(nul - *start) : size - *at;
    *at += n + (nul != NULL);
    return n;
}

/* The script text: the bytes with "{res}" replaced, a line feed at the end if there is none. */
static char *script_text(const uint8_t *data, size_t n)
{
    size_t resLength = strlen(res), i, used = 0, room = n + 2;
    char *text;
    for (i = 0; i + 5 <= n; i++)
        if (memcmp(data + i, "{res}", 5) == 0)
            room += resLength;
    if (!(text = (char *)malloc(room)))
        abort();
    for (i = 0; i < n;) {
        if (i + 5 <= n && memcmp(data + i, "{res}", 5) == 0) {
            memcpy(text + used, res, resLength);
            used += resLength;
            i += 5;
        } else {
            text[used++] = (char)data[i++];
        }
    }
    if (!memchr(text, '\n', used))
        text[used++] = '\n';
    text[used] = '\0';
    return text;
}

static int lines_of(const char *text)
{
    int n = 0;
    for (; *text; text++)
        if (*text == '\n' || !text[1])
            n++;
    return n;
}

static int is_empty(const PmdScript *s)
{
    return !s->steps && !s->count && !s->capacity && !s->pool && !s->poolCount && !s->poolCapacity && !s->axes &&
           !s->lastCycle && !s->name && !s->tables && !s->tableCount;
}

/* The line a message "name:line: reason" gives for name, or -1 if it does not start so. */
static long line_of(const char *error, const char *name)
{
    size_t n = strlen(name);
    char *end;
    long line;
    if (strncmp(error, name, n) != 0 || error[n] != ':' || !(error[n + 1] >= '0' && error[n + 1] <= '9'))
        return -1;
    line = strtol(error + n + 1, &end, 10);
    return strncmp(end, ": ", 2) == 0 ? line : -1;
}

/* Whether the message holds ":line: " (a table's path may hold anything before it). */
static int names_a_line(const char *error)
{
    const char *p;
    for (p = strchr(error, ':'); p; p = strchr(p + 1, ':')) {
        const char *q = p + 1;
        while (*q >= '0' && *q <= '9')
            q++;
        if (q > p + 1 && q[0] == ':' && q[1] == ' ')
            return 1;
    }
    return 0;
}

/* A refusal: a message of the form "name:line: reason" within the buffer, the script left empty. */
static void check_refusal(const char *text, const PmdScript *s, const char *error, size_t errorSize)
{
    long line;
    if (!is_empty(s))
        violated("a refused script is not left empty");
    if (strlen(error) >= errorSize)
        violated("the message overflows its buffer");
    if (errorSize < 8192)
        return;                                   /* cut short: nothing more to look at */
    if (!error[0])
        violated("a refusal says nothing");
    if ((line = line_of(error, PMD_SCRIPT_TEXT_NAME)) >= 0) {
        if (line < 1 || line > lines_of(text))
            violated("'%s' names line %ld of a text of %d lines", error, line, lines_of(text));
    } else if (!names_a_line(error)) {
        violated("'%s' names no table's line", error);
    }
}

static void check_compiled(const char *text, const PmdScript *s, uint32_t memoryWords)
{
    size_t i;
    int64_t cycle = 0;
    int lines = lines_of(text);
    if (!s->name || strcmp(s->name, PMD_SCRIPT_TEXT_NAME) != 0)
        violated("a script given as text is named '%s'", s->name ? s->name : "(null)");
    if (s->count > s->capacity || s->poolCount > s->poolCapacity || (s->tableCount && !s->tables))
        violated("counts beyond capacities");
    if (s->axes & ~0xF)
        violated("axes 0x%X beyond Axis4", s->axes);
    if (s->lastCycle < 0 || s->lastCycle > INT64_C(999999999999999999))
        violated("lastCycle %lld out of 0 .. 10^18 - 1", (long long)s->lastCycle);
    for (i = 0; i < s->count; i++) {
        const PmdScriptStep *step = &s->steps[i];
        if (step->cycle < cycle || step->cycle > s->lastCycle)
            violated("step %zu at cycle %lld: out of order or after the last time", i, (long long)step->cycle);
        cycle = step->cycle;
        if (step->line < 1 || step->line > lines)
            violated("step %zu names line %d of a text of %d lines", i, step->line, lines);
        if (step->nWords > PMD_SCRIPT_WORDS)
            violated("step %zu has %u words", i, step->nWords);
        if (!step->nWords && ((uint64_t)step->address + step->count > memoryWords || step->first > s->poolCount ||
                              step->count > s->poolCount - step->first))
            violated("memory block %zu (0x%X + %u words, pool %zu) leaves the memory or the pool", i,
                     step->address, step->count, step->first);
    }
    for (i = 0; i < s->tableCount; i++) {
        struct stat st;
        if (!s->tables[i].name || !s->tables[i].path || stat(s->tables[i].path, &st) != 0 || !S_ISREG(st.st_mode))
            violated("table %zu was read from '%s', not a file", i, s->tables[i].path ? s->tables[i].path : "");
        if (s->tables[i].line < 1 || s->tables[i].line > lines)
            violated("table %zu at line %d of %d", i, s->tables[i].line, lines);
    }
}

/* Whether every table the text compiled read lies in the resources folder. */
static int tables_in_resources(const PmdScript *s)
{
    size_t i, n = strlen(res);
    for (i = 0; i < s->tableCount; i++)
        if (strncmp(s->tables[i].path, res, n) != 0 || s->tables[i].path[n] != '/')
            return 0;
    return 1;
}

/* What follows "name:line" (the same reason at the same line), or the whole message. */
static const char *after_name(const char *error, const char *name)
{
    size_t n = strlen(name);
    return line_of(error, name) >= 0 ? error + n : error;
}

static void check_same_as_file(const char *text, const PmdScript *asText, int textResult, const char *textError,
                               const PmdScriptPlaces *places, uint32_t memoryWords)
{
    char path[256], error[8192];
    PmdScript asFile;
    int result;
    size_t i;
    put_file("s.script", (const uint8_t *)text, strlen(text));
    snprintf(path, sizeof path, "%s/s.script", res);
    result = pmd_script_compile(path, places, memoryWords, &asFile, error, sizeof error);
    if (textResult == 0 && result == 0) {
        if (asFile.count != asText->count || asFile.poolCount != asText->poolCount ||
            asFile.tableCount != asText->tableCount || asFile.axes != asText->axes ||
            asFile.lastCycle != asText->lastCycle ||
            (asFile.count && memcmp(asFile.steps, asText->steps, asFile.count * sizeof *asFile.steps) != 0) ||
            (asFile.poolCount && memcmp(asFile.pool, asText->pool, asFile.poolCount * sizeof *asFile.pool) != 0))
            violated("the text and the same bytes as a file compile differently");
        for (i = 0; i < asFile.tableCount; i++)
            if (strcmp(asFile.tables[i].name, asText->tables[i].name) != 0 ||
                strcmp(asFile.tables[i].path, asText->tables[i].path) != 0)
                violated("table %zu: '%s' from the text, '%s' from the file", i, asText->tables[i].path,
                         asFile.tables[i].path);
    } else if (textResult == 0) {
        /* only a table the text found in the working directory */
        if (tables_in_resources(asText) || !strstr(error, "not found in"))
            violated("the text compiles, the same bytes as a file not: %s", error);
    } else if (result == 0) {
        violated("the file compiles, the same bytes as text not: %s", textError);
    } else if (!strstr(error, "not found in") && !strstr(textError, "not found in") &&
               strcmp(after_name(error, path), after_name(textError, PMD_SCRIPT_TEXT_NAME)) != 0) {
        violated("refused differently: text '%s', file '%s'", textError, error);
    }
    if (result == 0)
        pmd_script_free(&asFile);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const uint32_t memoryWordsOf[4] = {0x4000, 0x10000, 0x100, 0};
    static const size_t errorSizeOf[4] = {8192, 256, 24, 1};
    const uint8_t *script, *table;
    size_t at = 1, n, errorSize;
    unsigned flags;
    uint32_t memoryWords;
    char resources[128], *text, *error;
    PmdScriptPlaces places;
    PmdScript compiled;
    int result;

    if (size == 0)
        return 0;
    if (!root[0])
        make_folders();
    flags = data[0];
    memoryWords = memoryWordsOf[flags >> 2 & 3];
    errorSize = errorSizeOf[flags >> 4 & 3];
    n = part(data, size, &at, &script);
    text = script_text(script, n);
    n = part(data, size, &at, &table);
    put_file("t.csv", table, n);
    put_file("sub dir/u.csv", data + at, at < size ? size - at : 0);     /* the rest, NUL bytes and all */
    snprintf(resources, sizeof resources, "%s%s", res, (flags & 3) == 0 ? "/" : "");
    places.resources = (flags & 3) < 2 ? resources : NULL;
    places.noResources = (flags & 3) == 2 ? "the importer gave no resourcePath (NULL)" : NULL;

    if (!pmd_script_is_text(text))
        violated("a value holding a line feed is not text");
    if (!(error = (char *)malloc(errorSize)))
        abort();
    memset(&compiled, 0x5A, sizeof compiled);     /* the compiler must set every field */
    result = pmd_script_compile(text, &places, memoryWords, &compiled, error, errorSize);
    if (getenv("FUZZ_TEXT_TRACE"))
        fprintf(stderr, "  places %u, memory 0x%X: %s\n", flags & 3, (unsigned)memoryWords,
                result == 0 ? "compiled" : error);
    if (result != 0 && result != -1)
        violated("pmd_script_compile returned %d", result);
    if (result == 0)
        check_compiled(text, &compiled, memoryWords);
    else
        check_refusal(text, &compiled, error, errorSize);
    if (places.resources && errorSize == 8192)
        check_same_as_file(text, &compiled, result, error, &places, memoryWords);
    if (result == 0)
        pmd_script_free(&compiled);
    free(error);
    free(text);
    return 0;
}
