/* SPDX-License-Identifier: BSD-2-Clause */
/* The plain stored registers of modelDescription/registers.csv: their Set and
 * Get commands have no handler of their own. A Set passes the register's guard
 * and range check (the refusal and its host I/O error code come from the
 * table) and stores; a Get reads back; Reset writes the reset values. This is
 * QEMU's register API (include/hw/register.h, RegisterAccessInfo with .reset
 * and .ro), with the table generated instead of written by hand. */
#include <stdio.h>
#include <string.h>

#include "events.h"
#include "register_table.h"
#include "registers.h"

/* Where the register lives: in the chip state, in the axis, or in the axis's
 * buffered (host-written) or active profile or filter registers. */
static unsigned char *storage(PmdChip *chip, const PmdRegister *r, int axis, int active)
{
    PmdAxis *ax = &chip->s.axis[axis];
    unsigned char *base;
    if (r->chipWide)
        base = (unsigned char *)&chip->s;
    else if (r->buffered == PMD_BUFFERED_PROFILE)
        base = (unsigned char *)(active ? &ax->active : &ax->buffered);
    else if (r->buffered == PMD_BUFFERED_FILTER)
        base = (unsigned char *)(active ? &ax->filter.active : &ax->filter.buffered);
    else
        base = (unsigned char *)ax;
    return base + r->offset;
}

/* The member holds the value's low size bytes (it is a uintN_t or intN_t of that size). */
static void store(unsigned char *at, const PmdRegister *r, int64_t value)
{
    uint32_t u = (uint32_t)(uint64_t)value;
    uint16_t h = (uint16_t)u;
    uint8_t b = (uint8_t)u;
    memcpy(at, r->size == 4 ? (const void *)&u : r->size == 2 ? (const void *)&h : (const void *)&b, r->size);
}

static int64_t load(const unsigned char *at, const PmdRegister *r)
{
    uint32_t u;
    uint16_t h;
    uint8_t b;
    int bits = 8 * r->size;
    if (r->size == 4) {
        memcpy(&u, at, 4);
    } else if (r->size == 2) {
        memcpy(&h, at, 2);
        u = h;
    } else {
        memcpy(&b, at, 1);
        u = b;
    }
    return r->isSigned && (u >> (bits - 1)) ? (int64_t)u - ((int64_t)1 << bits) : (int64_t)u;
}

int pmd_register_command(PmdChip *chip, const PmdCommand *c, int axis, const int64_t *arg, int64_t *reply)
{
    const PmdRegister *r = c->reg;
    int err;
    if (c->nArgs == 0) {
        reply[0] = load(storage(chip, r, axis, 0), r);      /* a buffered register reads its buffered set (4.1) */
        return 0;
    }
    if (r->guard && (err = r->guard(chip, c->name)) != 0)
        return err;
    if (arg[0] < r->min || arg[0] > r->max) {
        if (PMD_LOGGING(chip, PMD_LOG_ERRORS)) {
            char value[24], where[24] = "";
            /* a "negative" 32-bit value shows as the word the host sent */
            if (r->error == PMD_ERR_InvalidNegativeValue)
                snprintf(value, sizeof value, "0x%08llX", (unsigned long long)arg[0]);
            else
                snprintf(value, sizeof value, "%lld", (long long)arg[0]);
            if (!r->chipWide)
                snprintf(where, sizeof where, "axis %d: ", axis + 1);
            pmd_log(chip, PMD_LOG_ERRORS, "%s%s(%s): %s", where, c->name, value, r->refusal);
        }
        return r->error;
    }
    store(storage(chip, r, axis, 0), r, arg[0]);
    return 0;
}

/* The registers whose commands take packed or paired words, so that their
 * handlers serve them (commands_hardware.c): their reset values other than 0. */
static void reset_packed_registers(PmdChip *chip)
{
    int n;
    /* 57600 baud, 8N1, point-to-point: the Magellan's reset value (reference 3.3); [L] for the Navigator */
    chip->s.serialPortMode = (uint16_t)PMD_FIELD_DP(0, PMDSerialPortBaud, PMDSerialBaud57600);
    for (n = 0; n < PMD_AXES; n++) {
        chip->s.axis[n].encoderCounts = 1;          /* the ratio 0x00010001, 1:1 (reference 4.2) */
        chip->s.axis[n].encoderSteps = 1;
    }
}

void pmd_registers_reset(PmdChip *chip)
{
    int i, n;
    reset_packed_registers(chip);
    for (i = 0; i < PMD_REGISTER_COUNT; i++) {
        const PmdRegister *r = &pmd_registers[i];
        if (!r->hasReset)
            continue;
        if (r->chipWide) {
            store(storage(chip, r, 0, 0), r, r->reset);
            continue;
        }
        for (n = 0; n < PMD_AXES; n++) {
            store(storage(chip, r, n, 0), r, r->reset);
            if (r->buffered != PMD_NOT_BUFFERED)
                store(storage(chip, r, n, 1), r, r->reset);
        }
    }
}
