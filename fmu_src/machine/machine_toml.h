/* SPDX-License-Identifier: BSD-2-Clause */
/* The machine file (docs/machine.md): a small, strict subset of TOML that
 * says, per axis, where its switches and index pulses are. Parsed into the
 * chip's PmdMachine (chip_types.h), which the chip applies every cycle
 * (fmu_src/chip/machine.c). Plain C, no FMI inside: the FMU parses its
 * `machine` parameter with it; the fuzzer parses text with it. */
#ifndef PMD_MACHINE_TOML_H
#define PMD_MACHINE_TOML_H

#include <stddef.h>
#include <stdint.h>

#include "chip_types.h"
#include "script.h"

#define PMD_MACHINE_TEXT_NAME "(machine text)"

/* Parses machine text; messages name it `name`. Returns 0 with *machine
 * filled, or -1 with "name:line: reason" in error and *machine all zero. */
int pmd_machine_parse_text(const char *text, const char *name, PmdMachine *machine, char *error, size_t errorSize);

/* Parses the `machine` parameter's value as the `script` parameter's is taken:
 * "" no machine; text when it holds a line feed; else a file's path
 * (absolute, or found in the resources folder, then the working directory).
 * *name (unless NULL) gets what messages call it (at most nameSize bytes). */
int pmd_machine_parse(const char *value, const PmdScriptPlaces *places, PmdMachine *machine, char *name,
                      size_t nameSize, char *error, size_t errorSize);

/* What the machine means, one line per axis it drives, into out (NUL-terminated). */
void pmd_machine_describe(const PmdMachine *machine, char *out, size_t outSize);

/* A digest of what the machine means (0: no machine), for the FMU state. */
uint64_t pmd_machine_digest(const PmdMachine *machine);

#endif
