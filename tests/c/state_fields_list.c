/* SPDX-License-Identifier: BSD-2-Clause */
/* Prints the declared state (fmu_src/fmi/state_fields.c) for
 * tests/test_state_forgery.py, which forges snapshots from it:
 *   header SIZE CHECKSUM                         bytes before the state image, checksum offset
 *   leaf PATH OFFSET SIZE KIND MIN MAX           one per scalar of the image
 *   member STRUCT NAME                           one per declared field of each struct in the image
 * (the image itself, PmdStateImage, only puts the instance's and the chip's
 * state side by side: its parts are the structs the instance holds) */
#include <stdio.h>

#include <stddef.h>

#include "instance.h"
#include "state_fields.h"

static int print_leaf(const PmdStateLeaf *leaf, void *context)
{
    (void)context;
    printf("leaf %s %zu %zu %u %lld %lld\n", leaf->path, leaf->offset, leaf->size, (unsigned)leaf->kind,
           (long long)leaf->min, (long long)leaf->max);
    return 0;
}

/* Each struct once, however many fields have its type. */
static void print_members(const PmdStateStruct *s)
{
    static const PmdStateStruct *printed[64];
    static size_t nPrinted;
    size_t f, i;
    for (i = 0; i < nPrinted; i++)
        if (printed[i] == s)
            return;
    if (nPrinted < sizeof printed / sizeof printed[0])
        printed[nPrinted++] = s;
    for (f = 0; f < s->nFields; f++)
        printf("member %s %s\n", s->name, s->fields[f].name);
    for (f = 0; f < s->nFields; f++)
        if (s->fields[f].kind == PMD_SF_STRUCT)
            print_members(s->fields[f].sub);
}

int main(void)
{
    size_t part;
    printf("header %zu %zu\n", sizeof(PmdStateHeader), offsetof(PmdStateHeader, checksum));
    pmd_state_walk(1, print_leaf, NULL);
    for (part = 0; part < pmd_state_image.nFields; part++)
        print_members(pmd_state_image.fields[part].sub);
    return 0;
}
