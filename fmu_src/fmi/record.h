/* record.columns: which values a recording doStep writes into record.data
 * besides the chip time (record.c). Independent of the FMI version. */
#ifndef PMD_RECORD_H
#define PMD_RECORD_H

#include <stddef.h>
#include <stdint.h>

/* One column: a variable of variables.csv (its FMI 2 scalar), read through
 * the instance's own getter (pmd_get_real, _integer, _boolean). */
typedef struct {
    unsigned vr;
    unsigned char type;              /* PMD_REAL, PMD_INTEGER, PMD_BOOLEAN */
    unsigned char bytes;             /* of its FMI 3 type: 8, 4, 2 (the low bits), 1 (a Boolean: 0 or 1) */
} PmdRecordColumn;

/* record.columns compiled: count 0 is "" (the default row of PMD_RECORD_WORDS int32). */
typedef struct {
    char *text;                      /* the value as set; NULL: "" */
    PmdRecordColumn *column;
    size_t count;
    uint32_t rowBytes;               /* of one row of record.data */
} PmdRecordColumns;

#endif
