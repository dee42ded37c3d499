/* The declared instance state: every field of PmdInstance, what it may hold,
 * and whether it belongs to the FMU state or to this process (state_fields.c).
 * QEMU's VMStateDescription is the model: a snapshot is refused, naming the
 * field, when a field holds a value the model never gives it, so a forged or
 * corrupted state cannot reach the engine. */
#ifndef PMD_STATE_FIELDS_H
#define PMD_STATE_FIELDS_H

#include <stddef.h>
#include <stdint.h>

/* Bumped whenever a field is added, removed or changes meaning. */
#define PMD_STATE_VERSION 3u

/* A snapshot (state.c): this header, the instance image, the memory words. */
#define PMD_STATE_MAGIC "PMDFMUST"
typedef struct {
    char magic[8];
    uint32_t formatVersion;      /* PMD_STATE_VERSION */
    uint32_t instanceSize;       /* sizeof(PmdInstance): the layout of this build */
    char token[48];              /* PMD_INSTANTIATION_TOKEN, zero-padded */
    uint64_t totalSize;
    uint64_t memoryWords;
    uint64_t checksum;           /* FNV-1a (64-bit) over everything after the header */
} PmdStateHeader;

typedef enum {
    PMD_SF_UNSIGNED,     /* an unsigned integer of 1, 2, 4 or 8 bytes, within [min, max] */
    PMD_SF_SIGNED,       /* a signed integer, within [min, max] */
    PMD_SF_REAL,         /* a double: finite */
    PMD_SF_STRUCT,       /* a nested struct (sub) */
    PMD_SF_PROCESS       /* this process's, not the state's (pointers, hooks, logging): kept on restore */
} PmdStateFieldKind;

typedef struct PmdStateStruct PmdStateStruct;

typedef struct {
    const char *name;
    size_t offset, size;          /* of one element */
    unsigned count;               /* 1, or the array's length */
    unsigned char kind;           /* PmdStateFieldKind */
    int64_t min, max;
    const PmdStateStruct *sub;
} PmdStateField;

struct PmdStateStruct {
    const char *name;
    size_t size;
    size_t nFields;
    const PmdStateField *fields;
};

extern const PmdStateStruct pmd_instance_state;

/* One scalar of the flattened list: an element of an array, a field of a nested struct. */
typedef struct {
    char path[96];                /* e.g. "chip.s.axis[2].trajectory.fraction" */
    size_t offset, size;          /* in PmdInstance */
    unsigned char kind;           /* PMD_SF_UNSIGNED, _SIGNED, _REAL or _PROCESS */
    int64_t min, max;
} PmdStateLeaf;

/* Calls visit for every leaf in declaration order (with its path if named);
 * stops and returns its non-zero result. */
int pmd_state_walk(int named, int (*visit)(const PmdStateLeaf *leaf, void *context), void *context);

/* Checks every field of the instance image against its declared range; on the
 * first that is out of it, writes "path = value is not in min..max" into why
 * and returns -1. */
int pmd_state_check_ranges(const void *instance, char *why, size_t whySize);

#endif
