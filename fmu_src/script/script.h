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

typedef struct {
    PmdScriptStep *steps;
    size_t count, capacity;
    uint32_t *pool;                  /* table words */
    size_t poolCount, poolCapacity;
    /* what a master may ask about the script without parsing it again */
    uint8_t axes;                    /* the axes its calls address: bit n for axis n + 1 */
    int64_t lastCycle;               /* the time of its last @ line (0: none), 0 .. 10^18 - 1 */
} PmdScript;

/* Compiles the script at path for a memory of memoryWords words. Returns 0,
 * or -1 with "file:line: reason" in error (and nothing allocated). */
int pmd_script_load(const char *path, uint32_t memoryWords, PmdScript *script, char *error, size_t errorSize);
void pmd_script_free(PmdScript *script);
/* The 64-bit FNV-1a hash of n bytes, continuing from h (start: PMD_FNV1A_BASIS):
 * the script digest and the FMU state checksum. */
#define PMD_FNV1A_BASIS UINT64_C(14695981039346656037)
uint64_t pmd_fnv1a(uint64_t h, const void *data, size_t n);

/* A digest of what the compiled script does (FNV-1a over its steps and table words,
 * 63 bits), or 0 for no script: FMU states name the script they run with it. */
uint64_t pmd_script_digest(const PmdScript *script);

#endif
