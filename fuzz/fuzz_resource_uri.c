/* SPDX-License-Identifier: BSD-2-Clause */
/* Fuzz target: FMI 2's fmuResourceLocation, a file URI decoded into the
 * resources folder where relative script and table paths are looked for.
 * The decoder, resources_of, is static in the FMI 2 shell,
 * fmu_src/fmi_common/fmi2.c: this file includes fmi2.c so that it can call it
 * as well as fmi2Instantiate (run.py then leaves fmi2.c out of the target's
 * sources).
 *
 *   input = the URI, up to the first NUL; an empty input passes NULL
 *
 * "{res}" in the input stands for the absolute path of a resources folder of
 * this process, "/tmp/pmdfuzz-uri-PID/res dir" (a space, so that encodings
 * matter), and "{res%}" for the same path with the space written %20. That
 * folder holds script.start (a packed FMU's script text, which loads t.csv),
 * t.csv and s.script (which loads t.csv too, at another address).
 *
 * Properties (abort() on a violation, after "property violated: ..."):
 *   - no sanitizer report (the URI is a heap block of exactly its length);
 *   - never accepted unless well-formed and local: resources_of accepts only
 *     what an independent reading of RFC 8089 and RFC 3986 (ref_decode, with
 *     the scheme and "localhost" in any case) accepts, and gives the same
 *     folder: the path's percent-decoding up to '?' or '#', absolute, ending
 *     in '/', no %00; a refusal says why;
 *   - never refused when well-formed in the forms it documents ("file:" or
 *     "FILE:", no authority, an empty one or "localhost"; ref_decode strict);
 *   - fmi2Instantiate keeps that folder, or that reason, in the instance; every
 *     message it logs is a printf format without arguments ('%' doubled);
 *   - a URI that decodes to the resources folder above (by any spelling whose
 *     files' paths fit script.c's 1024 bytes) works end to end: the
 *     instance reads script.start from it, initializes with its tables found
 *     there, and after fmi2Reset the relative script "s.script" is found there. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fmi2.c"
#include "fuzz_property.h"
#include "instance.h"
#include "variables.h"

static const char START[] = "@ 0\nLoadSegmentTable(Axis1, \"t.csv\", 0x200, 2);\n"
                            "@ 10\nSetProfileMode(Axis1, PMDExternalProfile);\nUpdate(Axis1);\n";
static const char SCRIPT[] = "LoadSegmentTable(Axis2, \"t.csv\", 0x400, 4);\n";
static const char TABLE[] = "position, time\n0, 0x10\n5, 0x10\n";

static char root[64], res[96], resEncoded[128];

/* script.c looks for a file by a path of fewer than MAX_PATH (1024) bytes, script.start too: a
 * resources folder longer than that leaves files there unread, and fmi2Instantiate refuses
 * (the script parameter's start value cannot be looked for). */
#define SCRIPT_PATH_LIMIT 1024
#define FITS(folder, name) (strlen(folder) + strlen(name) < SCRIPT_PATH_LIMIT)

/* ---- the resources folder ---- */

static void put_file(const char *name, const char *text)
{
    char path[256];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", res, name);
    if (!(f = fopen(path, "wb")) || fputs(text, f) < 0 || fclose(f) != 0)
        violated("cannot write %s", path);
}

static void remove_files(void)
{
    static const char *const names[] = {PMD_SCRIPT_START, "t.csv", "s.script"};
    char path[256];
    size_t i;
    for (i = 0; i < sizeof names / sizeof *names; i++) {
        snprintf(path, sizeof path, "%s/%s", res, names[i]);
        unlink(path);
    }
    rmdir(res);
    rmdir(root);
}

static void make_folder(void)
{
    snprintf(root, sizeof root, "/tmp/pmdfuzz-uri-%d", (int)getpid());
    snprintf(res, sizeof res, "%s/res dir", root);
    snprintf(resEncoded, sizeof resEncoded, "%s/res%%20dir", root);
    mkdir(root, 0700);
    mkdir(res, 0700);
    put_file(PMD_SCRIPT_START, START);
    put_file("t.csv", TABLE);
    put_file("s.script", SCRIPT);
    atexit(remove_files);
}

/* The URI: the input up to its first NUL with "{res}" and "{res%}" replaced, in a block of its size. */
static char *uri_of(const uint8_t *data, size_t size)
{
    const uint8_t *nul = (const uint8_t *)memchr(data, 0, size);
    size_t n = nul ? (size_t)(nul - data) : size, i, used = 0, room = 1;
    char *uri;
    for (i = 0; i < n;) {                         /* pass 0 measures, pass 1 copies */
        if (i + 6 <= n && memcmp(data + i, "{res%}", 6) == 0)
            room += strlen(resEncoded), i += 6;
        else if (i + 5 <= n && memcmp(data + i, "{res}", 5) == 0)
            room += strlen(res), i += 5;
        else
            room++, i++;
    }
    if (!(uri = (char *)malloc(room)))
        abort();
    for (i = 0; i < n;) {
        if (i + 6 <= n && memcmp(data + i, "{res%}", 6) == 0) {
            memcpy(uri + used, resEncoded, strlen(resEncoded));
            used += strlen(resEncoded);
            i += 6;
        } else if (i + 5 <= n && memcmp(data + i, "{res}", 5) == 0) {
            memcpy(uri + used, res, strlen(res));
            used += strlen(res);
            i += 5;
        } else {
            uri[used++] = (char)data[i++];
        }
    }
    uri[used] = '\0';
    return uri;
}

/* ---- the reference reading of a file URI ---- */

static int same_letters(const char *a, const char *b, size_t n, int anyCase)
{
    size_t i;
    for (i = 0; i < n; i++) {
        char x = a[i], y = b[i];
        if (anyCase) {
            x = (char)(x >= 'A' && x <= 'Z' ? x - 'A' + 'a' : x);
            y = (char)(y >= 'A' && y <= 'Z' ? y - 'A' + 'a' : y);
        }
        if (x != y)
            return 0;
    }
    return 1;
}

static int hex_digit(char c)
{
    return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
}

/* RFC 8089 (file URI) over RFC 3986: "file:" path-absolute, or "file://" authority path-absolute
 * with the authority empty or "localhost" (this machine); the path ends at '?' or '#'; each '%'
 * starts two hex digits, not %00 (no path holds a NUL). Lenient: "file" and "localhost" in any case
 * (RFC 3986 sections 3.1 and 3.2.2: both are case-insensitive); strict: the forms resources_of
 * documents ("file:" or "FILE:", "localhost"). Into out[strlen(uri) + 2] the decoded path, ending in
 * '/'; 1 if accepted. */
static int ref_decode(const char *uri, int lenient, char *out)
{
    const char *p, *authority, *end;
    size_t n = 0;
    if (!uri || strlen(uri) < 5)
        return 0;
    if (!(lenient ? same_letters(uri, "file:", 5, 1) : strncmp(uri, "file:", 5) == 0 || strncmp(uri, "FILE:", 5) == 0))
        return 0;
    p = uri + 5;
    if (p[0] == '/' && p[1] == '/') {
        authority = p + 2;
        for (end = authority; *end && *end != '/' && *end != '?' && *end != '#'; end++)
            ;
        if (end != authority && !(end - authority == 9 && same_letters(authority, "localhost", 9, lenient)))
            return 0;
        p = end;
    }
    if (*p != '/')
        return 0;
    for (; *p && *p != '?' && *p != '#'; p++) {
        if (*p != '%') {
            out[n++] = *p;
            continue;
        }
        if (hex_digit(p[1]) < 0 || hex_digit(p[2]) < 0 || (p[1] == '0' && p[2] == '0'))
            return 0;
        out[n++] = (char)(hex_digit(p[1]) * 16 + hex_digit(p[2]));
        p += 2;
    }
    if (out[n - 1] != '/')
        out[n++] = '/';
    out[n] = '\0';
    return 1;
}

/* ---- the instance ---- */

/* Every message goes out as a printf format without arguments: each '%' doubled. */
static void logger(fmi2ComponentEnvironment e, fmi2String name, fmi2Status status, fmi2String category,
                   fmi2String message, ...)
{
    const char *p;
    (void)e; (void)status;
    if (!name || !category || !message)
        violated("a log message with a NULL string");
    for (p = message; *p; p++)
        if (*p == '%' && *++p != '%')
            violated("a logged message has a lone '%%': %s", message);
    if (getenv("FUZZ_URI_TRACE"))
        fprintf(stderr, "  log %s: %s\n", category, message);
}

static const fmi2CallbackFunctions callbacks = {logger, NULL, NULL, NULL, NULL};

static PmdInstance *instance_of(fmi2Component c)
{
    return ((Component *)c)->inst;
}

static void must(fmi2Status status, const char *call, const char *uri)
{
    if (status != fmi2OK)
        violated("%s refused with fmuResourceLocation '%s'", call, uri);
}

static void initialize(fmi2Component c, const char *uri)
{
    must(fmi2SetupExperiment(c, 0, 0, 0, 0, 0), "fmi2SetupExperiment", uri);
    must(fmi2EnterInitializationMode(c), "fmi2EnterInitializationMode", uri);
    must(fmi2ExitInitializationMode(c), "fmi2ExitInitializationMode", uri);
}

static int same_file(const char *a, const char *b)
{
    char x[4096], y[4096];
    return strlen(a) < sizeof x && strlen(b) < sizeof y && realpath(a, x) && realpath(b, y) && strcmp(x, y) == 0;
}

/* The URI names the resources folder made above: script.start, its table, and a relative script all found there. */
static void check_end_to_end(fmi2Component c, const char *uri, const char *folder)
{
    PmdInstance *inst = instance_of(c);
    fmi2ValueReference script = pmd_variables[VAR_script].vr;
    fmi2String relative = "s.script";
    char expected[SCRIPT_PATH_LIMIT + 16];
    if (!inst->scriptStart || strcmp(inst->scriptStart, START) != 0)
        violated("'%s': script.start not read from %s", uri, folder);
    initialize(c, uri);
    snprintf(expected, sizeof expected, "%st.csv", folder);
    if (inst->script.tableCount != 1 || strcmp(inst->script.tables[0].path, expected) != 0)
        violated("'%s': script.start's table read from '%s', not %s", uri,
                 inst->script.tableCount ? inst->script.tables[0].path : "(none)", expected);
    must(fmi2Reset(c), "fmi2Reset", uri);
    must(fmi2SetString(c, &script, 1, &relative), "fmi2SetString", uri);
    initialize(c, uri);
    snprintf(expected, sizeof expected, "%ss.script", folder);
    if (!inst->script.name || strcmp(inst->script.name, expected) != 0)
        violated("'%s': s.script read from '%s', not %s", uri, inst->script.name ? inst->script.name : "(none)",
                 expected);
    /* its table from its own folder, the name up to its last '/' ("res dir//s.script": "res dir/") */
    snprintf(expected, sizeof expected, "%st.csv", folder);
    if (inst->script.tableCount != 1 || !same_file(inst->script.tables[0].path, expected))
        violated("'%s': s.script's table read from '%s', not %s", uri,
                 inst->script.tableCount ? inst->script.tables[0].path : "(none)", expected);
}

/* Whether folder is the resources folder made above, by another spelling too ("//", "/./", "%2F"). */
static int is_our_folder(const char *folder)
{
    static char ours[4096];
    char theirs[4096];
    if (!ours[0] && !realpath(res, ours))
        violated("the resources folder %s is gone", res);
    return strlen(folder) < sizeof theirs && realpath(folder, theirs) && strcmp(theirs, ours) == 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *uri, *folder, *lenient = NULL, *strict = NULL;
    const char *why = NULL;
    fmi2Component c;
    int ours;

    if (!root[0])
        make_folder();
    uri = size ? uri_of(data, size) : NULL;
    if (uri) {
        lenient = (char *)malloc(strlen(uri) + 2);
        strict = (char *)malloc(strlen(uri) + 2);
        if (!lenient || !strict)
            abort();
    }

    folder = resources_of(uri, &why);
    if (folder) {
        if (!uri || !ref_decode(uri, 1, lenient))
            violated("fmuResourceLocation '%s' accepted as %s: not a well-formed local file URI", uri ? uri : "(NULL)",
                     folder);
        if (strcmp(folder, lenient) != 0)
            violated("fmuResourceLocation '%s' decoded as '%s', not '%s'", uri, folder, lenient);
    } else {
        if (!why || !*why)
            violated("fmuResourceLocation '%s' refused without a reason", uri ? uri : "(NULL)");
        if (uri && ref_decode(uri, 0, strict))
            violated("fmuResourceLocation '%s' refused (%s), though a local file URI for %s", uri, why, strict);
    }

    /* the same through fmi2Instantiate: the folder, or the reason, kept in the instance */
    ours = folder && is_our_folder(folder);
    c = fmi2Instantiate("uri", fmi2CoSimulation, PMD_INSTANTIATION_TOKEN, uri, &callbacks, 0, 1);
    if (c) {
        PmdInstance *inst = instance_of(c);
        if (folder ? !inst->resources || strcmp(inst->resources, folder) != 0
                   : inst->resources || !inst->noResources || strcmp(inst->noResources, why) != 0)
            violated("fmi2Instantiate keeps resources '%s' (%s) for '%s'", inst->resources ? inst->resources : "NULL",
                     inst->noResources ? inst->noResources : "NULL", uri ? uri : "(NULL)");
        if (ours && FITS(folder, PMD_SCRIPT_START))
            check_end_to_end(c, uri, folder);
        fmi2FreeInstance(c);
    } else if (!folder || (ours && FITS(folder, PMD_SCRIPT_START))) {
        /* only a script.start it cannot read, or look for, refuses an instance (any folder of this machine) */
        violated("fmi2Instantiate refused fmuResourceLocation '%s'", uri ? uri : "(NULL)");
    }
    free(folder);
    free(lenient);
    free(strict);
    free(uri);
    return 0;
}
