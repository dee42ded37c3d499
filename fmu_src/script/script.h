/* SPDX-License-Identifier: BSD-2-Clause */
/* Command scripts: the FMU used stand-alone, without a host model (script.c).
 * Plain C over the chip's command table; no FMI inside (the instance runs them). */
#ifndef PMD_SCRIPT_H
#define PMD_SCRIPT_H

#include <stddef.h>
#include <stdint.h>

#define PMD_SCRIPT_WORDS 8           /* the longest command: instruction + 4 data words */

/* One thing a script does at a chip cycle: a host command, or a block of
 * words written straight into memory (a segment table's column). */
typedef struct {
    int64_t cycle;                   /* it runs before this cycle (grid index) */
    int line;                        /* script line, for messages */
    uint16_t nWords;                 /* host command words, or 0 for a memory block */
    uint16_t words[PMD_SCRIPT_WORDS];
    uint32_t address, count;         /* memory block: count words of the pool at `first` */
    size_t first;
} PmdScriptStep;

/* A segment table the script loaded: the name its line gives and the file read. */
typedef struct {
    int line;
    char *name, *path;
} PmdScriptTable;

typedef struct {
    PmdScriptStep *steps;
    size_t count, capacity;
    uint32_t *pool;                  /* table words */
    size_t poolCount, poolCapacity;
    /* what a master may ask about the script without parsing it again */
    uint8_t axes;                    /* the axes its calls address: bit n for axis n + 1 */
    int64_t lastCycle;               /* the time of its last @ line (0: none), 0 .. 10^18 - 1 */
    /* what it read: messages name the script by name ("file:line: reason") */
    char *name;                      /* the path it was read from, or PMD_SCRIPT_TEXT_NAME */
    PmdScriptTable *tables;          /* every LoadSegmentTable, in script order */
    size_t tableCount;
} PmdScript;

/* The `script` parameter's value is the script's text itself when it holds a
 * line feed, else the path of a script file (docs/scripts.md): a path never
 * holds one, and a one-line script is that line and its line feed. */
int pmd_script_is_text(const char *value);
#define PMD_SCRIPT_TEXT_NAME "(script text)"

/* Where relative paths are looked for besides the script's own folder: the
 * FMU's resources folder (ending in a separator), or NULL with why (NULL too:
 * no resources folder to speak of, as for a script compiled outside an FMU). */
typedef struct {
    const char *resources;
    const char *noResources;
} PmdScriptPlaces;

/* Compiles the `script` parameter's value for a memory of memoryWords words.
 * A path: absolute as is; relative, the first that exists of the resources
 * folder's and the working directory's. Its tables (LoadSegmentTable): absolute
 * as is; relative, from the script's folder, else the resources folder; for a
 * script given as text, the resources folder, else the working directory.
 * Returns 0, or -1 with "file:line: reason" in error (and nothing allocated);
 * a file not found names each place it was looked for. */
int pmd_script_compile(const char *value, const PmdScriptPlaces *places, uint32_t memoryWords, PmdScript *script,
                       char *error, size_t errorSize);
/* Compiles the script file at path (relative: from the working directory), its
 * tables relative to its folder: pmd_script_compile without a resources folder. */
int pmd_script_load(const char *path, uint32_t memoryWords, PmdScript *script, char *error, size_t errorSize);
/* A packed FMU (pmdfmu pack) carries the `script` parameter's start value, as
 * its modelDescription.xml gives it, byte for byte in this file of its
 * resources folder: the start value an importer that sets no start values
 * runs with. Reads it: 1 with *value allocated, 0 if the FMU has none, -1 with
 * the reason in error. */
#define PMD_SCRIPT_START "script.start"
int pmd_script_read_start(const char *resources, char **value, char *error, size_t errorSize);
void pmd_script_free(PmdScript *script);
/* Reads the file a parameter names as the script's path is found (absolute as
 * is; relative, the resources folder's, then the working directory's): 0 with
 * *text (NUL-terminated) and *name (the path read) allocated, or -1 with
 * "value: cannot open the <what>: why" in error. The machine parameter's file. */
int pmd_parameter_file(const char *value, const PmdScriptPlaces *places, const char *what, char **text, char **name,
                       char *error, size_t errorSize);
/* The 64-bit FNV-1a hash of n bytes, continuing from h (start: PMD_FNV1A_BASIS):
 * the script digest and the FMU state checksum. */
#define PMD_FNV1A_BASIS UINT64_C(14695981039346656037)
uint64_t pmd_fnv1a(uint64_t h, const void *data, size_t n);

/* A digest of what the compiled script does (FNV-1a over its steps and table words,
 * 63 bits), or 0 for no script: FMU states name the script they run with it. */
uint64_t pmd_script_digest(const PmdScript *script);

#endif
