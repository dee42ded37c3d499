#!/usr/bin/env python3
"""Generates, from the tables beside this file, everything that must agree with them:

  fmi2/modelDescription.xml   the FMI 2.0 Co-Simulation interface
  fmi3/modelDescription.xml   the FMI 3.0 Co-Simulation interface (arrays kept whole)
  variables3.h, variables3.c  the FMI 3 types and array sizes for the C wrapper
  variables.h, variables.c    value references and the variable table for the C wrapper
  command_table.h, .c         the command table that drives the chip's dispatcher
  pmd_constants.h, .c         the C-Motion constants as C macros, and by name for scripts;
                              each *Mask constant's register field as NAME_SHIFT, NAME_LENGTH
                              with PMD_FIELD_EX / PMD_FIELD_DP

  fmi3/buildDescription.xml   the FMI 3.0 source-FMU build description

Usage: generate.py OUTDIR [C source file names of the FMUs' sources/ ...]
"""
import hashlib
import importlib.util
import sys
import uuid
from pathlib import Path
from xml.sax.saxutils import quoteattr

HERE = Path(__file__).resolve().parent
_spec = importlib.util.spec_from_file_location("tables", HERE.parent / "python" / "pmdfmu" / "tables.py")
tables = importlib.util.module_from_spec(_spec)
sys.modules["tables"] = tables
_spec.loader.exec_module(tables)

MODEL_IDENTIFIER = "PMDMotionProcessor"


def cycle_time(variables) -> str:
    """The cycleTime parameter's start value: the default step and the FMI 3 fixed internal step."""
    return next(v.start for v in variables if v.name == "cycleTime")
LOG_CATEGORIES = [
    ("errors", "Refused commands and bad FMI calls"),
    ("warnings", "Suspicious but legal situations, e.g. a buffer read index overtaking its write index"),
    ("commands", "Every host command executed"),
    ("buffers", "Buffer set-up and dual-port memory writes"),
    ("segments", "External profile segments read from memory"),
    ("events", "Event status bits set by the chip, breakpoints firing"),
]


def instantiation_token() -> str:
    """Changes whenever an interface table changes, so an FMU never runs with a foreign XML."""
    digest = hashlib.sha256()
    for name in ("variables.csv", "commands.csv", "constants.csv"):
        digest.update((HERE / name).read_bytes())
    return "{" + str(uuid.UUID(bytes=digest.digest()[:16])) + "}"


def index_array(declaration: str, keys, size: int):
    """C lines of an array that maps each key (a value reference, an opcode) to
    its row in the table, and every other index to -1."""
    index_of = [-1] * size
    for row, key in enumerate(keys):
        index_of[key] = row
    lines = [f"{declaration} = {{"]
    lines += ["    " + ", ".join(str(x) for x in index_of[i:i + 16]) + "," for i in range(0, size, 16)]
    return lines + ["};", ""]


def fmi2_xml(variables, token: str, sources=()) -> str:
    lines = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<fmiModelDescription fmiVersion="2.0" modelName="{MODEL_IDENTIFIER}" guid="{token}"',
        '  description="PMD Navigator/Pilot-class motion processor: external profile engine, buffer memory, host interface"',
        '  generationTool="pmdfmu modelDescription/generate.py" variableNamingConvention="structured"',
        '  numberOfEventIndicators="0">',
        f'  <CoSimulation modelIdentifier="{MODEL_IDENTIFIER}" canHandleVariableCommunicationStepSize="true"'
        ' canNotUseMemoryManagementFunctions="true" canGetAndSetFMUstate="true" canSerializeFMUstate="true">',
        "    <SourceFiles>",
        *(f'      <File name="{name}"/>' for name in sources),
        "    </SourceFiles>",
        "  </CoSimulation>",
        "  <LogCategories>",
        *(f'    <Category name="{n}" description={quoteattr(d)}/>' for n, d in LOG_CATEGORIES),
        "  </LogCategories>",
        f'  <DefaultExperiment startTime="0" stopTime="0.1" stepSize="{cycle_time(variables)}"/>',
        "  <ModelVariables>",
    ]
    outputs = []
    variables = [v for v in variables if v.type != "Binary"]     # FMI 2 has no Binary type
    for i, v in enumerate(variables, start=1):
        initial = ' initial="exact"' if v.causality == "parameter" else ""
        lines.append(f'    <ScalarVariable name="{v.name}" valueReference="{v.vr}" causality="{v.causality}"'
                     f' variability="{v.variability}"{initial} description={quoteattr(v.description)}>')
        start = f' start="{v.start}"' if v.start != "" or v.causality == "parameter" else ""
        lines.append(f"      <{v.type}{start}/>")
        lines.append("    </ScalarVariable>")
        if v.causality == "output":
            outputs.append(i)
    lines += ["  </ModelVariables>", "  <ModelStructure>", "    <Outputs>"]
    lines += [f'      <Unknown index="{i}"/>' for i in outputs]
    lines += ["    </Outputs>", "    <InitialUnknowns>"]
    lines += [f'      <Unknown index="{i}"/>' for i in outputs]
    lines += ["    </InitialUnknowns>", "  </ModelStructure>", "</fmiModelDescription>", ""]
    return "\n".join(lines)


def build_description(sources) -> str:
    """FMI 3.0 source FMU: sources/ is flat and holds every header it needs."""
    return "\n".join([
        '<?xml version="1.0" encoding="UTF-8"?>',
        '<fmiBuildDescription fmiVersion="3.0">',
        f'  <BuildConfiguration modelIdentifier="{MODEL_IDENTIFIER}">',
        '    <SourceFileSet language="C99">',
        *(f'      <SourceFile name="{name}"/>' for name in sources),
        "    </SourceFileSet>",
        "  </BuildConfiguration>",
        "</fmiBuildDescription>", ""])


def fmi3_xml(variables3, token: str) -> str:
    """FMI 3.0 Co-Simulation: native types, arrays kept whole, the same names
    and value references as FMI 2 (an array's is that of its first element)."""
    lines = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<fmiModelDescription fmiVersion="3.0" modelName="{MODEL_IDENTIFIER}" instantiationToken="{token}"',
        '  description="PMD Navigator/Pilot-class motion processor: external profile engine, buffer memory, host interface"',
        '  generationTool="pmdfmu modelDescription/generate.py" variableNamingConvention="structured">',
        f'  <CoSimulation modelIdentifier="{MODEL_IDENTIFIER}" canHandleVariableCommunicationStepSize="true"'
        f' fixedInternalStepSize="{cycle_time(variables3)}" canGetAndSetFMUState="true" canSerializeFMUState="true"'
        ' hasEventMode="false" providesIntermediateUpdate="false"/>',
        "  <LogCategories>",
        *(f'    <Category name="{n}" description={quoteattr(d)}/>' for n, d in LOG_CATEGORIES),
        "  </LogCategories>",
        f'  <DefaultExperiment startTime="0" stopTime="0.1" stepSize="{cycle_time(variables3)}"/>',
        "  <ModelVariables>",
    ]
    for v in variables3:
        initial = ' initial="exact"' if v.causality == "parameter" else ""
        start = f' start="{" ".join([v.start] * v.count)}"' if v.start != "" and v.type != "String" else ""
        head = (f'    <{v.type} name="{v.name}" valueReference="{v.vr}" causality="{v.causality}"'
                f' variability="{v.variability}"{initial}{start} description={quoteattr(v.description)}')
        if v.type == "String":                    # FMI 3 writes String start values as elements
            lines += [head + ">", f"      <Start value={quoteattr(v.start)}/>", f"    </{v.type}>"]
        elif v.count > 1:
            lines += [head + ">", f'      <Dimension start="{v.count}"/>', f"    </{v.type}>"]
        else:
            lines.append(head + "/>")
    outputs = [v.vr for v in variables3 if v.causality == "output"]
    lines += ["  </ModelVariables>", "  <ModelStructure>"]
    lines += [f'    <Output valueReference="{vr}"/>' for vr in outputs]
    lines += [f'    <InitialUnknown valueReference="{vr}"/>' for vr in outputs]
    lines += ["  </ModelStructure>", "</fmiModelDescription>", ""]
    return "\n".join(lines)


def variables3_c(variables3):
    """The FMI 3 view for fmi3.c: each variable's type and element count."""
    vr_max = max(v.vr for v in variables3)
    c = ["/* Generated by modelDescription/generate.py from variables.csv: do not edit. */",
         '#include "variables3.h"', "",
         "const PmdVariable3 pmd_variables3[PMD_VARIABLE3_COUNT] = {",
         *(f'    {{{v.vr}, {v.count}, PMD3_{v.type.upper()}, "{v.name}"}},' for v in variables3),
         "};", "",
         *index_array("const short pmd_variable3_of_vr[PMD_VR3_MAX + 1]", (v.vr for v in variables3), vr_max + 1)]
    h = ["/* Generated by modelDescription/generate.py from variables.csv: do not edit. */",
         "#ifndef PMD_VARIABLES3_H", "#define PMD_VARIABLES3_H", "",
         f"#define PMD_VR3_MAX {vr_max}", f"#define PMD_VARIABLE3_COUNT {len(variables3)}", "",
         "/* FMI 3 types, in the order of the fmi3 get/set functions that use them. */",
         "typedef enum { PMD3_FLOAT64, PMD3_INT32, PMD3_UINT32, PMD3_UINT16, PMD3_BOOLEAN, PMD3_STRING, PMD3_BINARY }"
         " PmdType3;",
         "",
         "typedef struct {",
         "    unsigned vr;             /* also the FMI 2 value reference of element 1 */",
         "    unsigned short count;    /* elements: element i has FMI 2 value reference vr + i */",
         "    unsigned char type;      /* PmdType3 */",
         "    const char *name;",
         "} PmdVariable3;", "",
         "extern const PmdVariable3 pmd_variables3[PMD_VARIABLE3_COUNT];",
         "extern const short pmd_variable3_of_vr[PMD_VR3_MAX + 1];", "", "#endif", ""]
    return "\n".join(h), "\n".join(c)


def variables_c(variables, token: str):
    families = list(dict.fromkeys(v.family for v in variables))
    vr_max = max(v.vr for v in variables)
    h = [
        "/* Generated by modelDescription/generate.py from variables.csv: do not edit. */",
        "#ifndef PMD_VARIABLES_H", "#define PMD_VARIABLES_H", "",
        f'#define PMD_MODEL_IDENTIFIER "{MODEL_IDENTIFIER}"',
        f'#define PMD_INSTANTIATION_TOKEN "{token}"',
        f"#define PMD_VR_MAX {vr_max}",
        f"#define PMD_VARIABLE_COUNT {len(variables)}", "",
        "typedef enum { PMD_REAL, PMD_INTEGER, PMD_BOOLEAN, PMD_STRING, PMD_BINARY } PmdType;",
        "typedef enum { PMD_PARAMETER, PMD_INPUT, PMD_OUTPUT, PMD_INDEPENDENT } PmdCausality;", "",
        "/* One per row of variables.csv; index tells the axis or array element. */",
        "typedef enum {",
        *(f"    VAR_{f}," for f in families),
        "    VAR_FAMILY_COUNT",
        "} PmdFamily;", "",
        "typedef struct {",
        "    unsigned vr;",
        "    PmdFamily family;",
        "    unsigned short index;",
        "    unsigned char type;",
        "    unsigned char causality;",
        "    const char *name;",
        "} PmdVariable;", "",
        "extern const PmdVariable pmd_variables[PMD_VARIABLE_COUNT];",
        "/* pmd_variable_of_vr[vr] is the index into pmd_variables, or -1. */",
        "extern const short pmd_variable_of_vr[PMD_VR_MAX + 1];", "",
        "#endif", "",
    ]
    types = {"Real": "PMD_REAL", "Integer": "PMD_INTEGER", "Boolean": "PMD_BOOLEAN", "String": "PMD_STRING",
             "Binary": "PMD_BINARY"}
    caus = {"parameter": "PMD_PARAMETER", "input": "PMD_INPUT", "output": "PMD_OUTPUT",
            "independent": "PMD_INDEPENDENT"}
    c = [
        "/* Generated by modelDescription/generate.py from variables.csv: do not edit. */",
        '#include "variables.h"', "",
        "const PmdVariable pmd_variables[PMD_VARIABLE_COUNT] = {",
        *(f'    {{{v.vr}, VAR_{v.family}, {v.index}, {types[v.type]}, {caus[v.causality]}, "{v.name}"}},'
          for v in variables),
        "};", "",
        *index_array("const short pmd_variable_of_vr[PMD_VR_MAX + 1]", (v.vr for v in variables), vr_max + 1),
    ]
    return "\n".join(h), "\n".join(c)


def commands_c(commands):
    def fields(fs):
        kinds = {"u16": "PMD_U16", "i16": "PMD_I16", "u32": "PMD_U32", "i32": "PMD_I32", "bits": "PMD_BITS"}
        fixed = {"": 0, "16.16": 16, "0.32": 32}
        def place(f):       # a packed value by its register field's name (pmd_constants.h)
            return f"{f.register_field}_SHIFT, {f.register_field}_LENGTH" if f.register_field else f"{f.shift}, {f.width}"
        return "{" + ", ".join(f"{{{kinds[f.kind]}, {f.word}, {place(f)}, {fixed[f.fixed]}}}"
                               for f in fs) + "}" if fs else "{{0}}"

    h = [
        "/* Generated by modelDescription/generate.py from commands.csv: do not edit. */",
        "#ifndef PMD_COMMAND_TABLE_H", "#define PMD_COMMAND_TABLE_H", "",
        '#include "chip_types.h"', "",
        *(f"int cmd_{c.name}(PmdChip *chip, int axis, const int64_t *arg, int64_t *reply);" for c in commands),
        "",
        "extern const PmdCommand pmd_commands[];",
        f"#define PMD_COMMAND_COUNT {len(commands)}",
        "/* pmd_command_of_opcode[opcode] is the index into pmd_commands, or -1 (invalid instruction). */",
        "extern const signed char pmd_command_of_opcode[256];", "",
        "#endif", "",
    ]
    c = [
        "/* Generated by modelDescription/generate.py from commands.csv: do not edit. */",
        '#include "command_table.h"', '#include "pmd_constants.h"', "",
        "const PmdCommand pmd_commands[] = {",
    ]
    for cmd in commands:
        c.append(f'    {{0x{cmd.opcode:02X}, "{cmd.name}", {int(cmd.scope == "chip")}, {cmd.arg_words}, '
                 f'{cmd.reply_words}, {len(cmd.args)}, {len(cmd.reply)}, {fields(cmd.args)}, '
                 f'{fields(cmd.reply)}, cmd_{cmd.name}}},')
    c += ["};", "", *index_array("const signed char pmd_command_of_opcode[256]", (c.opcode for c in commands), 256)]
    return "\n".join(h), "\n".join(c)


def constants_c(constants) -> str:
    """The constants by name, for the script parser."""
    return "\n".join(["/* Generated by modelDescription/generate.py from constants.csv: do not edit. */",
                      '#include "pmd_constants.h"', "",
                      "const PmdConstant pmd_constants[PMD_CONSTANT_COUNT] = {",
                      *(f'    {{"{name}", {value}}},' for _, name, value in constants),
                      "};", ""])


def constants_h(constants, fields) -> str:
    """The constants as macros; after each field mask (tables.read_fields) its
    NAME_SHIFT and NAME_LENGTH, for PMD_FIELD_EX / PMD_FIELD_DP."""
    lines = ["/* Generated by modelDescription/generate.py from constants.csv: do not edit. */",
             "#ifndef PMD_CONSTANTS_H", "#define PMD_CONSTANTS_H", "", "#include <stdint.h>", "",
             "/* Register fields, as QEMU's include/hw/registerfields.h has them: a field F is",
             " * declared once, as the mask FMask (a C-Motion-style constant of constants.csv);",
             " * F_SHIFT and F_LENGTH derive from it. PMD_FIELD_EX reads F from a register",
             " * word, PMD_FIELD_DP returns the word with F replaced by x (cut to F's width). */",
             "#define PMD_FIELD_EX(value, F) ((uint32_t)(((uint32_t)(value) & (uint32_t)(F##Mask)) >> F##_SHIFT))",
             "#define PMD_FIELD_DP(value, F, x) \\",
             "    (((uint32_t)(value) & ~(uint32_t)(F##Mask)) | (((uint32_t)(x) << F##_SHIFT) & (uint32_t)(F##Mask)))",
             ""]
    group = None
    names = {name for _, name, _ in constants}
    for g, name, value in constants:
        if g != group:
            lines.append(f"\n/* {g} */")
            group = g
        field = name[:-len("Mask")] if name.endswith("Mask") else None
        if field is None:
            lines.append(f"#define {name} ({value})")
            continue
        f = fields[field]
        for derived in (f"{field}_SHIFT", f"{field}_LENGTH"):
            if derived in names:
                sys.exit(f"constants.csv: {derived} is both a constant and derived from {name}")
        lines += [f"#define {name} (0x{value:04X})",
                  f"#define {field}_SHIFT {f.shift}", f"#define {field}_LENGTH {f.length}"]
    lines += ["", "typedef struct {", "    const char *name;", "    long value;", "} PmdConstant;", "",
              f"#define PMD_CONSTANT_COUNT {len(constants)}",
              "extern const PmdConstant pmd_constants[PMD_CONSTANT_COUNT];", "", "#endif", ""]
    return "\n".join(lines)


def main(outdir: Path, sources) -> None:
    variables = tables.read_variables(HERE / "variables.csv")
    variables3 = tables.read_variables3(HERE / "variables.csv")
    commands = tables.read_commands(HERE / "commands.csv")
    constants = tables.read_constants(HERE / "constants.csv")
    try:
        fields = tables.read_fields(HERE / "constants.csv")      # refuses a mask that is no field
    except ValueError as e:
        sys.exit(f"constants.csv: {e}")
    token = instantiation_token()
    files = {
        "fmi2/modelDescription.xml": fmi2_xml(variables, token, [n for n in sources if n not in FMI3_ONLY]),
        "fmi3/modelDescription.xml": fmi3_xml(variables3, token),
        "fmi3/buildDescription.xml": build_description([n for n in sources if n not in FMI2_ONLY]),
        "pmd_constants.h": constants_h(constants, fields),
        "pmd_constants.c": constants_c(constants),
    }
    files["variables.h"], files["variables.c"] = variables_c(variables, token)
    files["variables3.h"], files["variables3.c"] = variables3_c(variables3)
    files["command_table.h"], files["command_table.c"] = commands_c(commands)
    for name, text in files.items():
        path = outdir / name
        path.parent.mkdir(parents=True, exist_ok=True)
        if not path.exists() or path.read_text() != text:   # keep timestamps: no needless rebuilds
            path.write_text(text)


FMI2_ONLY = {"fmi2.c"}
FMI3_ONLY = {"fmi3.c", "variables3.c"}

if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(Path(sys.argv[1]), [Path(a).name for a in sys.argv[2:]])
