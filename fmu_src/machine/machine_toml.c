/* SPDX-License-Identifier: BSD-2-Clause */
/* The machine file's parser (machine_toml.h). The TOML subset: comments,
 * [axis1] .. [axis4] tables and their [axisN.plant] sub-tables, `key = value`
 * with a bare key, and values that are integers (decimal, 0x hex, 0o octal,
 * 0b binary, underscores between digits), "strings" without escapes, or
 * [arrays, of, integers] on one line; in a plant table, decimal floats too
 * (the motor's parameters are physical quantities). Anything
 * else TOML allows is refused with the line and the reason, never guessed at:
 * a machine file that means something other than its author thinks would
 * make a homing routine find its switch somewhere else. */
#include <ctype.h>
#include <locale.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "machine_toml.h"
#include "plant_variables.h"
#include "pmd_constants.h"

#define SENSE_BITS (PMDSignalEncoderIndexMask | PMDSignalEncoderHomeMask | PMDSignalPositiveLimitMask | \
                    PMDSignalNegativeLimitMask)
#define MAX_ARRAY PMD_MACHINE_INDEX_POSITIONS
/* The machine steps its motor every chip cycle, up to 65535 us: an internal step of 1 us or longer keeps
 * that below 65536 internal steps (a finer one is the plant FMU's business, beside the chip in a tool). */
#define FINEST_INTERNAL_STEP 1e-6

typedef struct {
    const char *name;
    int line;
    char *error;
    size_t errorSize;
} Where;

static int fail(const Where *w, const char *format, ...)
{
    char reason[512];
    va_list args;
    va_start(args, format);
    vsnprintf(reason, sizeof reason, format, args);
    va_end(args);
    snprintf(w->error, w->errorSize, "%s:%d: %s", w->name, w->line, reason);
    return -1;
}

/* A value: an integer, a float (plant tables only), a string or an array of integers. */
typedef struct {
    enum { INTEGER, REAL, STRING, ARRAY } kind;
    int64_t integer;
    double real;
    char string[64];
    int count;
    int64_t item[MAX_ARRAY];
} Value;

static const char *skip_blanks(const char *p)
{
    while (*p == ' ' || *p == '\t')
        p++;
    return p;
}

/* An integer at *p (TOML's forms), moved past; values beyond 2^40 in size are refused
 * (no position needs more, and the arithmetic stays far from overflow). */
static int parse_integer(const Where *w, const char **p, int64_t *value)
{
    const char *s = *p;
    int negative = 0, base = 10, digits = 0, lastUnderscore = 0;
    int64_t v = 0;
    if (*s == '+' || *s == '-') {
        negative = *s == '-';
        s++;
    }
    if (s[0] == '0' && (s[1] == 'x' || s[1] == 'o' || s[1] == 'b')) {
        if (s != *p)
            return fail(w, "a sign before a 0%c number (TOML allows none)", s[1]);
        base = s[1] == 'x' ? 16 : s[1] == 'o' ? 8 : 2;
        s += 2;
    } else if (s[0] == '0' && isdigit((unsigned char)s[1])) {
        return fail(w, "a decimal integer with a leading zero (TOML allows none; hex is 0x...)");
    }
    for (;; s++) {
        int d;
        if (*s == '_') {
            if (digits == 0 || lastUnderscore)
                return fail(w, "an underscore must stand between two digits");
            lastUnderscore = 1;
            continue;
        }
        if (isdigit((unsigned char)*s))
            d = *s - '0';
        else if (isxdigit((unsigned char)*s))
            d = tolower((unsigned char)*s) - 'a' + 10;
        else
            break;
        if (d >= base)
            return fail(w, "'%c' is not a digit of a base-%d number", *s, base);
        v = v * base + d;
        if (v > ((int64_t)1 << 40))
            return fail(w, "integer out of range");
        digits++;
        lastUnderscore = 0;
    }
    if (digits == 0 || lastUnderscore)
        return fail(w, "a number without digits, or ending in an underscore");
    if (*s == '.' || *s == 'e' || *s == 'E')
        return fail(w, "a floating-point number: positions are whole counts");
    *value = negative ? -v : v;
    *p = s;
    return 0;
}

/* Digits with underscores between them, copied without the underscores to *out; how many digits. */
static int digits_of(const char **p, char **out)
{
    const char *s = *p;
    int n = 0;
    while (isdigit((unsigned char)*s) || (*s == '_' && n > 0 && isdigit((unsigned char)s[1]))) {
        if (*s != '_') {
            *(*out)++ = *s;
            n++;
        }
        s++;
    }
    *p = s;
    return n;
}

/* A TOML float at *p (a decimal with a fraction, an exponent or both), moved past. Converted by
 * strtod with the C locale's decimal point in place of the process's (a host program may have set
 * another), so the same text means the same double everywhere. */
static int parse_real(const Where *w, const char **p, double *value)
{
    char text[96], *out = text, *end;
    const char *s = *p, *point = localeconv()->decimal_point;
    int integerDigits;
    if (*s == '+' || *s == '-')
        *out++ = *s++;
    if (strncmp(s, "inf", 3) == 0 || strncmp(s, "nan", 3) == 0)
        return fail(w, "%.3s: a motor's parameter is a finite number", s);
    if (strspn(s, "0123456789_.eE+-") > sizeof text - 16)
        return fail(w, "a number longer than %d characters", (int)sizeof text - 16);
    if (s[0] == '0' && (isdigit((unsigned char)s[1]) || s[1] == '_'))
        return fail(w, "a decimal number with a leading zero (TOML allows none)");
    integerDigits = digits_of(&s, &out);
    if (integerDigits == 0)
        return fail(w, "a number without digits before its point or exponent");
    if (*s == '.') {
        s++;
        strcpy(out, point);
        out += strlen(point);
        if (digits_of(&s, &out) == 0)
            return fail(w, "a decimal point must have digits on both sides (TOML)");
    }
    if (*s == 'e' || *s == 'E') {
        *out++ = *s++;
        if (*s == '+' || *s == '-')
            *out++ = *s++;
        if (digits_of(&s, &out) == 0)
            return fail(w, "an exponent without digits");
    }
    if (*s == '_')
        return fail(w, "an underscore must stand between two digits");
    *out = '\0';
    *value = strtod(text, &end);
    if (*end != '\0' || !isfinite(*value))
        return fail(w, "%s is not a finite double", text);
    *p = s;
    return 0;
}

/* Whether the number at p is a float: a point or an exponent before its end (0x... never is). */
static int is_real(const char *p)
{
    if (*p == '+' || *p == '-')
        p++;
    if (p[0] == '0' && (p[1] == 'x' || p[1] == 'o' || p[1] == 'b'))
        return 0;
    if (strncmp(p, "inf", 3) == 0 || strncmp(p, "nan", 3) == 0)
        return 1;
    p += strspn(p, "0123456789_");
    return *p == '.' || *p == 'e' || *p == 'E';
}

/* The value at p, to the end of the line (comments already removed); floats only when reals. */
static int parse_value(const Where *w, const char *p, Value *v, int reals)
{
    memset(v, 0, sizeof *v);
    if (reals && (*p == '+' || *p == '-' || isdigit((unsigned char)*p) || *p == 'i' || *p == 'n') && is_real(p)) {
        v->kind = REAL;
        if (parse_real(w, &p, &v->real))
            return -1;
    } else if (*p == '"') {
        const char *end = strchr(p + 1, '"');
        if (p[1] == '"' && p[2] == '"')
            return fail(w, "a multi-line string (not part of the machine file's TOML)");
        if (!end)
            return fail(w, "a string without its closing quote");
        if (memchr(p + 1, '\\', (size_t)(end - p - 1)))
            return fail(w, "an escape in a string (not part of the machine file's TOML)");
        if ((size_t)(end - p - 1) >= sizeof v->string)
            return fail(w, "a string longer than %d characters", (int)sizeof v->string - 1);
        v->kind = STRING;
        memcpy(v->string, p + 1, (size_t)(end - p - 1));
        p = end + 1;
    } else if (*p == '\'') {
        return fail(w, "a literal 'string': write it in double quotes");
    } else if (*p == '[') {
        v->kind = ARRAY;
        p = skip_blanks(p + 1);
        while (*p != ']') {
            if (*p == '\0')
                return fail(w, "an array must close on its line");
            if (v->count == MAX_ARRAY)
                return fail(w, "an array of more than %d values", MAX_ARRAY);
            if (!(*p == '+' || *p == '-' || isdigit((unsigned char)*p)))
                return fail(w, "an array holds integers only");
            if (parse_integer(w, &p, &v->item[v->count++]))
                return -1;
            p = skip_blanks(p);
            if (*p == ',')
                p = skip_blanks(p + 1);
            else if (*p != ']' && *p != '\0')
                return fail(w, "expected ',' or ']' in the array");
        }
        p++;
    } else if (*p == '+' || *p == '-' || isdigit((unsigned char)*p)) {
        v->kind = INTEGER;
        if (parse_integer(w, &p, &v->integer))
            return -1;
    } else if (*p == '{') {
        return fail(w, "an inline table (not part of the machine file's TOML)");
    } else if (*p == '\0') {
        return fail(w, "a key without a value");
    } else {
        return fail(w, "a value is an integer, a \"string\" or an array of integers");
    }
    p = skip_blanks(p);
    if (*p != '\0')
        return fail(w, "text after the value: '%s'", p);
    return 0;
}

static int int32_value(const Where *w, const char *key, int64_t x, int32_t *out)
{
    if (x < INT32_MIN || x > INT32_MAX)
        return fail(w, "%s = %lld is not a position (-2^31 .. 2^31-1 counts)", key, (long long)x);
    *out = (int32_t)x;
    return 0;
}

/* Where each key of an axis was given (0: not), for duplicates and cross checks. */
enum { KEY_SERVO, KEY_HOME, KEY_POSITIVE, KEY_NEGATIVE, KEY_INDEX, KEY_SENSE, KEYS };
static const char *const key_names[KEYS] = {"servo", "home", "positive_limit", "negative_limit", "index",
                                            "signal_sense"};

static int set_key(const Where *w, PmdMachineAxis *a, int key, const Value *v)
{
    const char *k = key_names[key];
    switch (key) {
    case KEY_SERVO:
        if (v->kind != STRING)
            return fail(w, "servo is a string: \"ideal\" or \"plant\"");
        if (strcmp(v->string, "plant") == 0)
            a->servo = PMD_MACHINE_SERVO_PLANT;
        else if (strcmp(v->string, "ideal") == 0)
            a->servo = PMD_MACHINE_SERVO_IDEAL;
        else
            return fail(w, "servo = \"%s\": the servo is \"ideal\" (the commanded position) or \"plant\" "
                           "(the pmdplant motor in the loop)", v->string);
        return 0;
    case KEY_HOME:
        if (v->kind != ARRAY || v->count != 2)
            return fail(w, "home = [lo, hi]: two positions, active from lo to hi");
        if (int32_value(w, k, v->item[0], &a->homeLow) || int32_value(w, k, v->item[1], &a->homeHigh))
            return -1;
        if (a->homeLow > a->homeHigh)
            return fail(w, "home = [%d, %d]: lo is above hi", (int)a->homeLow, (int)a->homeHigh);
        a->signals |= PMD_MACHINE_HOME;
        return 0;
    case KEY_POSITIVE:
    case KEY_NEGATIVE:
        if (v->kind != INTEGER)
            return fail(w, "%s is one position, in counts", k);
        if (int32_value(w, k, v->integer, key == KEY_POSITIVE ? &a->positiveLimit : &a->negativeLimit))
            return -1;
        a->signals |= key == KEY_POSITIVE ? PMD_MACHINE_POSITIVE_LIMIT : PMD_MACHINE_NEGATIVE_LIMIT;
        return 0;
    case KEY_INDEX:
        if (v->kind == INTEGER) {
            if (v->integer < 1 || v->integer > INT32_MAX)
                return fail(w, "index = %lld: the counts between pulses are 1 .. 2^31-1", (long long)v->integer);
            a->indexPeriod = (uint32_t)v->integer;
        } else if (v->kind == ARRAY && v->count > 0) {
            int i;
            for (i = 0; i < v->count; i++)
                if (int32_value(w, k, v->item[i], &a->indexPosition[i]))
                    return -1;
            a->indexCount = (uint8_t)v->count;
        } else {
            return fail(w, "index = K (a pulse every K counts) or [p1, p2, ...] (pulses at these positions)");
        }
        a->signals |= PMD_MACHINE_INDEX;
        return 0;
    default:
        if (v->kind != INTEGER || v->integer < 0 || (v->integer & ~(int64_t)SENSE_BITS))
            return fail(w, "signal_sense is a SignalSense mask of the index (0x%04X), home (0x%04X), positive "
                           "limit (0x%04X) and negative limit (0x%04X) bits", PMDSignalEncoderIndexMask,
                        PMDSignalEncoderHomeMask, PMDSignalPositiveLimitMask, PMDSignalNegativeLimitMask);
        a->signalSense = (uint16_t)v->integer;
        return 0;
    }
}

/* x in the fewest digits that read back as x (7.2e-06, not 7.1999999999999997e-06). */
static const char *shortest(double x, char text[32])
{
    int precision;
    for (precision = 1; precision < 17; precision++) {
        snprintf(text, 32, "%.*g", precision, x);
        if (strtod(text, NULL) == x)
            return text;
    }
    snprintf(text, 32, "%.17g", x);
    return text;
}

/* ---- [axisN.plant]: the motor's parameters, named and bounded as the plant FMU's (plant.csv) ---- */

static double *real_member(PlantModel *m, const PlantVariable *p)
{
    return (double *)(void *)((char *)m + p->offset);
}

static int32_t *int_member(PlantModel *m, const PlantVariable *p)
{
    return (int32_t *)(void *)((char *)m + p->offset);
}

/* Every parameter at the plant FMU's start value. */
static void plant_defaults(PlantModel *m)
{
    size_t i;
    memset(m, 0, sizeof *m);
    for (i = 0; i < PLANT_VARIABLE_COUNT; i++) {
        const PlantVariable *p = &plant_variables[i];
        if (p->causality != PLANT_PARAMETER)
            continue;
        if (p->type3 == PLANT3_FLOAT64)
            *real_member(m, p) = p->start;
        else
            *int_member(m, p) = (int32_t)p->start;
    }
}

/* The parameter called name, or -1. */
static int plant_parameter(const char *name)
{
    size_t i;
    for (i = 0; i < PLANT_VARIABLE_COUNT; i++)
        if (plant_variables[i].causality == PLANT_PARAMETER && strcmp(plant_variables[i].name, name) == 0)
            return (int)i;
    return -1;
}

static int set_plant_key(const Where *w, PmdMachineAxis *a, int index, const Value *v)
{
    const PlantVariable *p = &plant_variables[index];
    double x = v->kind == REAL ? v->real : (double)v->integer;
    double min = p->min;
    if (v->kind != REAL && v->kind != INTEGER)
        return fail(w, "%s is a number", p->name);
    if (p->type3 != PLANT3_FLOAT64 && v->kind != INTEGER)
        return fail(w, "%s is a whole number", p->name);
    if (strcmp(p->name, "internalStep") == 0 && min < FINEST_INTERNAL_STEP)
        min = FINEST_INTERNAL_STEP;
    if (x < min || x > p->max) {
        char a[32], b[32], c[32];
        return fail(w, "%s = %s is outside %s .. %s", p->name, shortest(x, a), shortest(min, b), shortest(p->max, c));
    }
    if (p->type3 == PLANT3_FLOAT64)
        *real_member(&a->plant, p) = x;
    else
        *int_member(&a->plant, p) = (int32_t)x;
    return 0;
}

/* The parameters' names, for a message. */
static void plant_names(char *out, size_t size)
{
    size_t i, used = 0;
    out[0] = '\0';
    for (i = 0; i < PLANT_VARIABLE_COUNT && used < size; i++)
        if (plant_variables[i].causality == PLANT_PARAMETER) {
            int n = snprintf(out + used, size - used, "%s%s", used ? ", " : "", plant_variables[i].name);
            used += n > 0 ? (size_t)n : 0;
        }
}

/* Removes a comment (a # outside a string) and the line's end blanks. */
static void strip_comment(char *line)
{
    int quoted = 0;
    char *p, *end;
    for (p = line; *p; p++) {
        if (*p == '"')
            quoted = !quoted;
        else if (*p == '#' && !quoted) {
            *p = '\0';
            break;
        }
    }
    end = line + strlen(line);
    while (end > line && (end[-1] == ' ' || end[-1] == '\t' || end[-1] == '\r'))
        *--end = '\0';
}

/* Where the parser is and what it has seen, by line (0: not yet), for duplicates and cross checks. */
typedef struct {
    int axis;                              /* the table's axis, -1 before the first */
    int plant;                             /* in [axisN.plant] */
    int given[PMD_AXES][KEYS];
    int plantGiven[PMD_AXES][PLANT_VARIABLE_COUNT];
    int tables[PMD_AXES], plantTables[PMD_AXES];
} Seen;

static int parse_line(const Where *w, char *line, Seen *seen, PmdMachine *m)
{
    int *axis = &seen->axis;
    char *p = (char *)skip_blanks(line), *key, *end;
    Value v;
    int k;
    strip_comment(p);
    if (*p == '\0')
        return 0;
    if (*p == '[') {
        int n;
        if (p[1] == '[')
            return fail(w, "an array of tables (not part of the machine file's TOML)");
        end = strchr(p, ']');
        if (!end || end[1] != '\0')
            return fail(w, "a table header is [axis1] .. [axis4] alone on its line");
        *end = '\0';
        p = (char *)skip_blanks(p + 1);
        for (end = p + strlen(p); end > p && (end[-1] == ' ' || end[-1] == '\t');)
            *--end = '\0';
        if (strncmp(p, "axis", 4) != 0 || p[4] < '1' || p[4] > '4' ||
            (p[5] != '\0' && strcmp(p + 5, ".plant") != 0))
            return fail(w, "[%s]: the tables are [axis1] .. [axis4] and their motors, [axis1.plant] .. "
                           "[axis4.plant]", p);
        n = p[4] - '1';
        seen->plant = p[5] != '\0';
        if ((seen->plant ? seen->plantTables : seen->tables)[n])
            return fail(w, "[%s] is given twice (first at line %d)", p,
                        (seen->plant ? seen->plantTables : seen->tables)[n]);
        (seen->plant ? seen->plantTables : seen->tables)[n] = w->line;
        *axis = n;
        return 0;
    }
    key = p;
    while (isalnum((unsigned char)*p) || *p == '_' || *p == '-')
        p++;
    end = p;
    p = (char *)skip_blanks(p);
    if (end == key)
        return fail(w, "expected a key, a [table] or a comment");
    if (*p == '.')
        return fail(w, "a dotted key (not part of the machine file's TOML)");
    if (*p != '=')
        return fail(w, "expected '=' after the key");
    *end = '\0';
    if (*axis >= 0 && seen->plant) {
        char names[512];
        k = plant_parameter(key);
        plant_names(names, sizeof names);
        if (k < 0)
            return fail(w, "unknown key '%s' in [axis%d.plant] (the motor's parameters, as the plant FMU's: %s)",
                        key, *axis + 1, names);
        if (seen->plantGiven[*axis][k])
            return fail(w, "'%s' is given twice in [axis%d.plant] (first at line %d)", key, *axis + 1,
                        seen->plantGiven[*axis][k]);
        seen->plantGiven[*axis][k] = w->line;
        if (parse_value(w, skip_blanks(p + 1), &v, 1))
            return -1;
        return set_plant_key(w, &m->axis[*axis], k, &v);
    }
    for (k = 0; k < KEYS && strcmp(key, key_names[k]) != 0; k++)
        ;
    if (k == KEYS)
        return fail(w, "unknown key '%s' (an axis has servo, home, positive_limit, negative_limit, index, "
                       "signal_sense)", key);
    if (*axis < 0)
        return fail(w, "'%s' outside a table: put it under [axis1] .. [axis4]", key);
    if (seen->given[*axis][k])
        return fail(w, "'%s' is given twice in [axis%d] (first at line %d)", key, *axis + 1, seen->given[*axis][k]);
    seen->given[*axis][k] = w->line;
    if (parse_value(w, skip_blanks(p + 1), &v, 0))
        return -1;
    return set_key(w, &m->axis[*axis], k, &v);
}

int pmd_machine_parse_text(const char *text, const char *name, PmdMachine *machine, char *error, size_t errorSize)
{
    static const Seen nothing = {-1, 0, {{0}}, {{0}}, {0}, {0}};
    Seen seen = nothing;
    int n;
    char line[1024];
    const char *p = text;
    Where w;
    w.name = name;
    w.line = 0;
    w.error = error;
    w.errorSize = errorSize;
    memset(machine, 0, sizeof *machine);
    for (n = 0; n < PMD_AXES; n++)
        plant_defaults(&machine->axis[n].plant);
    while (*p) {
        const char *end = strchr(p, '\n');
        size_t length = end ? (size_t)(end - p) : strlen(p);
        w.line++;
        if (length >= sizeof line) {
            fail(&w, "a line longer than %d characters", (int)sizeof line - 1);
            memset(machine, 0, sizeof *machine);
            return -1;
        }
        memcpy(line, p, length);
        line[length] = '\0';
        if (parse_line(&w, line, &seen, machine)) {
            memset(machine, 0, sizeof *machine);
            return -1;
        }
        p += length + (end != NULL);
    }
    for (n = 0; n < PMD_AXES; n++) {
        const PmdMachineAxis *a = &machine->axis[n];
        if ((a->signals & PMD_MACHINE_POSITIVE_LIMIT) && (a->signals & PMD_MACHINE_NEGATIVE_LIMIT) &&
            a->positiveLimit <= a->negativeLimit) {
            w.line = seen.given[n][KEY_POSITIVE] > seen.given[n][KEY_NEGATIVE] ? seen.given[n][KEY_POSITIVE]
                                                                              : seen.given[n][KEY_NEGATIVE];
            fail(&w, "[axis%d]: positive_limit %d is not above negative_limit %d: the axis could never move", n + 1,
                 (int)a->positiveLimit, (int)a->negativeLimit);
            memset(machine, 0, sizeof *machine);
            return -1;
        }
        if (seen.plantTables[n] && a->servo != PMD_MACHINE_SERVO_PLANT) {
            w.line = seen.plantTables[n];
            fail(&w, "[axis%d.plant] gives a motor, but [axis%d] does not say servo = \"plant\": the motor would "
                 "not be in the loop", n + 1, n + 1);
            memset(machine, 0, sizeof *machine);
            return -1;
        }
        if (a->servo == PMD_MACHINE_SERVO_PLANT)
            machine->plantAxes |= 1u << n;
        if (a->signals || a->servo == PMD_MACHINE_SERVO_PLANT)
            machine->axes |= 1u << n;
    }
    return 0;
}

int pmd_machine_parse(const char *value, const PmdScriptPlaces *places, PmdMachine *machine, char *name,
                      size_t nameSize, char *error, size_t errorSize)
{
    char *text = NULL, *path = NULL;
    int result;
    memset(machine, 0, sizeof *machine);
    if (name && nameSize)
        snprintf(name, nameSize, "%s", PMD_MACHINE_TEXT_NAME);
    if (*value == '\0')
        return 0;
    if (pmd_script_is_text(value))
        return pmd_machine_parse_text(value, PMD_MACHINE_TEXT_NAME, machine, error, errorSize);
    if (pmd_parameter_file(value, places, "machine file", &text, &path, error, errorSize))
        return -1;
    if (name && nameSize)
        snprintf(name, nameSize, "%s", path);
    result = pmd_machine_parse_text(text, path, machine, error, errorSize);
    free(text);
    free(path);
    return result;
}

static size_t append(char *out, size_t size, size_t used, const char *format, ...)
{
    va_list args;
    int n;
    if (used >= size)
        return used;
    va_start(args, format);
    n = vsnprintf(out + used, size - used, format, args);
    va_end(args);
    return n < 0 ? size : used + (size_t)n;
}

void pmd_machine_describe(const PmdMachine *machine, char *out, size_t outSize)
{
    size_t used = 0;
    int n, i;
    if (outSize)
        out[0] = '\0';
    if (!machine->axes)
        used = append(out, outSize, used, "no axis has a switch or an index: every input is the FMU's\n");
    for (n = 0; n < PMD_AXES; n++) {
        const PmdMachineAxis *a = &machine->axis[n];
        if (!(machine->axes & (1u << n)))
            continue;
        used = append(out, outSize, used, "axis%d (PMDAxis%d): ", n + 1, n + 1);
        if (a->servo == PMD_MACHINE_SERVO_PLANT) {
            PlantModel m = a->plant;
            used = append(out, outSize, used, "plant servo (the pmdplant motor:");
            for (i = 0; i < PLANT_VARIABLE_COUNT; i++) {
                const PlantVariable *p = &plant_variables[i];
                if (p->causality != PLANT_PARAMETER)
                    continue;
                char text[32];
                if (p->type3 == PLANT3_FLOAT64)
                    used = append(out, outSize, used, " %s %s", p->name, shortest(*real_member(&m, p), text));
                else
                    used = append(out, outSize, used, " %s %d", p->name,
                                  (int)*int_member(&m, p));
            }
            used = append(out, outSize, used, ")");
        } else {
            used = append(out, outSize, used, "ideal servo");
        }
        if (a->signals & PMD_MACHINE_HOME)
            used = append(out, outSize, used, "; home active at %d .. %d", (int)a->homeLow, (int)a->homeHigh);
        if (a->signals & PMD_MACHINE_POSITIVE_LIMIT)
            used = append(out, outSize, used, "; positive limit active at >= %d", (int)a->positiveLimit);
        if (a->signals & PMD_MACHINE_NEGATIVE_LIMIT)
            used = append(out, outSize, used, "; negative limit active at <= %d", (int)a->negativeLimit);
        if (a->indexPeriod)
            used = append(out, outSize, used, "; index pulse every %u counts (at multiples of %u)",
                          (unsigned)a->indexPeriod, (unsigned)a->indexPeriod);
        else if (a->indexCount) {
            used = append(out, outSize, used, "; index pulse at");
            for (i = 0; i < a->indexCount; i++)
                used = append(out, outSize, used, "%s %d", i ? "," : "", (int)a->indexPosition[i]);
        }
        used = append(out, outSize, used, "; signal sense 0x%04X (%s)\n", (unsigned)a->signalSense,
                      a->signalSense ? "the bits set are wired active high: SetSignalSense with them"
                                     : "every switch active low, as the chip's reset sense expects");
    }
}

uint64_t pmd_machine_digest(const PmdMachine *machine)
{
    uint64_t h = PMD_FNV1A_BASIS;
    int n, i;
    if (!machine->axes)
        return 0;
    /* field by field: the struct's padding is not part of what it means */
    for (n = 0; n < PMD_AXES; n++) {
        const PmdMachineAxis *a = &machine->axis[n];
        int64_t f[8];
        f[0] = a->signals, f[1] = a->signalSense, f[2] = a->homeLow, f[3] = a->homeHigh;
        f[4] = a->positiveLimit, f[5] = a->negativeLimit, f[6] = a->indexPeriod, f[7] = a->indexCount;
        h = pmd_fnv1a(h, f, sizeof f);
        if (a->servo == PMD_MACHINE_SERVO_PLANT) {
            PlantModel m = a->plant;
            for (i = 0; i < PLANT_VARIABLE_COUNT; i++) {
                const PlantVariable *p = &plant_variables[i];
                double x;
                if (p->causality != PLANT_PARAMETER)
                    continue;
                x = p->type3 == PLANT3_FLOAT64 ? *real_member(&m, p) : (double)*int_member(&m, p);
                h = pmd_fnv1a(h, &x, sizeof x);
            }
        }
        for (i = 0; i < a->indexCount; i++) {
            int64_t p = a->indexPosition[i];
            h = pmd_fnv1a(h, &p, sizeof p);
        }
    }
    return (h & (uint64_t)INT64_MAX) | 1u;          /* never 0: that means no machine */
}
