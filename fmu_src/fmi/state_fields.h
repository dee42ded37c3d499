/* SPDX-License-Identifier: BSD-2-Clause */
/* The declared state: every field of the structs an FMU state holds (the
 * instance's PmdInstanceState and the chip's PmdChipState), what each may
 * hold (state_fields.c). QEMU's VMStateDescription is the model: a snapshot
 * is refused, naming the field, when a field holds a value the model never
 * gives it, so a forged or corrupted state cannot reach the engine. */
#ifndef PMD_STATE_FIELDS_H
#define PMD_STATE_FIELDS_H

#include <stddef.h>
#include <stdint.h>

#include "instance.h"

/* Bumped whenever a field is added, removed or changes meaning. */
#define PMD_STATE_VERSION 7u

/* The declared state as a snapshot holds it: the instance's, then the chip's.
 * Its fields are named as the instance reaches them (hostWordCount,
 * chip.s.trace.period). */
typedef struct {
    PmdInstanceState instance;
    PmdChipState chip;
} PmdStateImage;

/* A snapshot (state.c): this header, the state image, the memory words. */
#define PMD_STATE_MAGIC "PMDFMUST"
typedef struct {
    char magic[8];
    uint32_t formatVersion;      /* PMD_STATE_VERSION */
    uint32_t instanceSize;       /* sizeof(PmdStateImage): the layout of this build */
    char token[48];              /* PMD_INSTANTIATION_TOKEN, zero-padded */
    uint64_t totalSize;
    uint64_t memoryWords;
    uint64_t checksum;           /* FNV-1a (64-bit) over everything after the header */
} PmdStateHeader;

typedef enum {
    PMD_SF_UNSIGNED,     /* an unsigned integer of 1, 2, 4 or 8 bytes, within [min, max] */
    PMD_SF_SIGNED,       /* a signed integer, within [min, max] */
    PMD_SF_REAL,         /* a double: finite */
    PMD_SF_STRUCT        /* a nested struct (sub); named "": its fields are named as if they were this struct's */
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

/* The image's two parts; their fields, and those of the structs in them, are
 * every member (tests/test_state_forgery.py checks it). */
extern const PmdStateStruct pmd_state_image;

/* One scalar of the flattened list: an element of an array, a field of a nested struct. */
typedef struct {
    char path[96];                /* e.g. "chip.s.axis[2].trajectory.fraction" */
    size_t offset, size;          /* in PmdStateImage */
    unsigned char kind;           /* PMD_SF_UNSIGNED, _SIGNED or _REAL */
    int64_t min, max;
} PmdStateLeaf;

/* Calls visit for every leaf in declaration order (with its path if named);
 * stops and returns its non-zero result. */
int pmd_state_walk(int named, int (*visit)(const PmdStateLeaf *leaf, void *context), void *context);

/* Checks every field of the state image against its declared range; on the
 * first that is out of it, writes "path = value is not in min..max" into why
 * and returns -1. */
int pmd_state_check_ranges(const void *image, char *why, size_t whySize);

#endif
