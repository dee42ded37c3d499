/* SPDX-License-Identifier: BSD-2-Clause */
/* The host port: an instruction word (fields PMDInstructionAxis and
 * PMDInstructionOpcode), then the data words,
 * 32-bit values high word first (reference 1.1). The command table generated
 * from modelDescription/commands.csv says how many words each opcode takes and
 * how its values are packed. */
#include <stddef.h>

#include "chip.h"
#include "command_table.h"

#define SIGN16(x) ((x) >= 0x8000 ? (int64_t)(x) - 0x10000 : (int64_t)(x))

/* Decodes one argument value from the command's data words. */
static int64_t decode(const PmdField *f, const uint16_t *w)
{
    switch (f->kind) {
    case PMD_U16: return w[f->word];
    case PMD_I16: return SIGN16(w[f->word]);
    case PMD_U32: return pmd_word_pair(w[f->word], w[f->word + 1]);
    case PMD_I32: return pmd_int32(pmd_word_pair(w[f->word], w[f->word + 1]));
    default: return (w[f->word] >> f->shift) & ((1u << f->width) - 1u);
    }
}

void pmd_encode_field(const PmdField *f, int64_t value, uint16_t *w)
{
    uint32_t u = (uint32_t)(uint64_t)value;        /* modulo 2^32 */
    switch (f->kind) {
    case PMD_U32:
    case PMD_I32:
        w[f->word] = pmd_high_word(u);
        w[f->word + 1] = pmd_low_word(u);
        break;
    case PMD_BITS:
        w[f->word] |= (uint16_t)((u & ((1u << f->width) - 1u)) << f->shift);
        break;
    default:
        w[f->word] = pmd_low_word(u);
        break;
    }
}

/* Unused bits of packed words must be 0 (reference 1.1). */
static int packed_bits_clear(const PmdCommand *c, const uint16_t *w)
{
    uint16_t used[PMD_MAX_FIELDS] = {0};
    int i, packed = 0;
    for (i = 0; i < c->nArgs; i++) {
        if (c->args[i].kind == PMD_BITS) {
            used[c->args[i].word] |= (uint16_t)(((1u << c->args[i].width) - 1u) << c->args[i].shift);
            packed = 1;
        }
    }
    for (i = 0; packed && i < c->argWords; i++)
        if (used[i] && (w[i] & ~used[i]))
            return 0;
    return 1;
}

/* Records a refused command the way the chip does: the host I/O error
 * register keeps the first error since it was read, and the instruction-error
 * event bit is set (reference 2.4). */
static void refuse(PmdChip *chip, int axis, int code)
{
    if (chip->s.hostIOError == 0)
        chip->s.hostIOError = (uint16_t)code;
    pmd_set_event(chip, axis < PMD_AXES ? axis : 0, PMDEventInstructionErrorMask);
}

int pmd_host_batch(PmdChip *chip, const uint16_t *words, int count, uint16_t *reply, int *replyCount,
                   int *gridChanged)
{
    int first = 0, i = 0, changed = 0;
    *replyCount = 0;
    while (i < count) {
        uint16_t instruction = words[i++];
        int opcode = (int)PMD_FIELD_EX(instruction, PMDInstructionOpcode);
        int axis = (int)PMD_FIELD_EX(instruction, PMDInstructionAxis), err = 0, k;
        int index = pmd_command_of_opcode[opcode];
        const PmdCommand *c = index >= 0 ? &pmd_commands[index] : NULL;
        int64_t arg[PMD_MAX_FIELDS] = {0}, value[PMD_MAX_FIELDS] = {0};
        const uint16_t *data = words + i;

        if (!c) {
            /* Without the opcode the chip cannot know where the next command starts. */
            pmd_log(chip, PMD_LOG_ERRORS, "host: invalid instruction 0x%04X (opcode 0x%02X); %d following words "
                    "of the batch not executed", instruction, opcode, count - i);
            refuse(chip, axis, PMD_ERR_InvalidInstruction);
            if (!first)
                first = PMD_ERR_InvalidInstruction;
            break;
        }
        if (count - i < c->argWords) {
            pmd_log(chip, PMD_LOG_ERRORS, "host: %s needs %d data words, the batch ends after %d: not executed",
                    c->name, c->argWords, count - i);
            refuse(chip, axis, PMD_ERR_InvalidParameter);
            if (!first)
                first = PMD_ERR_InvalidParameter;
            break;
        }
        i += c->argWords;
        if (axis >= PMD_AXES) {
            pmd_log(chip, PMD_LOG_ERRORS, "host: %s: axis field %d (instruction 0x%04X) is not 0..3", c->name, axis,
                    instruction);
            err = PMD_ERR_InvalidAxis;
        } else if (*replyCount + c->replyWords > PMD_BATCH_WORDS) {
            pmd_log(chip, PMD_LOG_ERRORS, "host: %s: its reply would pass host.reply[%d]: not executed; split the "
                    "batch", c->name, PMD_BATCH_WORDS);
            err = PMD_ERR_InvalidParameter;
        } else if (!packed_bits_clear(c, data)) {
            pmd_log(chip, PMD_LOG_ERRORS, "host: %s: unused bits set in a packed argument word", c->name);
            err = PMD_ERR_InvalidParameter;
        } else {
            for (k = 0; k < c->nArgs; k++)
                arg[k] = decode(&c->args[k], data);
            if (PMD_LOGGING(chip, PMD_LOG_COMMANDS))
                pmd_log(chip, PMD_LOG_COMMANDS, "axis %d: %s(%lld, %lld, %lld, %lld)", axis + 1, c->name,
                        (long long)arg[0], (long long)arg[1], (long long)arg[2], (long long)arg[3]);
            err = c->reg ? pmd_register_command(chip, c, c->chipWide ? 0 : axis, arg, value)
                         : c->handler(chip, c->chipWide ? 0 : axis, arg, value);
            changed |= (err & PMD_GRID_CHANGED) != 0;
            err &= ~PMD_GRID_CHANGED;
        }
        if (err) {
            refuse(chip, axis, err);
            if (!first)
                first = err;
            continue;
        }
        /* only a successful Get returns data words, as in the serial protocol (reference 3.2) */
        for (k = 0; k < c->replyWords; k++)
            reply[*replyCount + k] = 0;
        for (k = 0; k < c->nReply; k++)
            pmd_encode_field(&c->reply[k], value[k], reply + *replyCount);
        *replyCount += c->replyWords;
    }
    if (gridChanged)
        *gridChanged = changed;
    return first;
}
