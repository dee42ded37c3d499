#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-2-Clause
"""Generates, from plant.csv and units.csv beside this file, everything of
the plant FMU (pmdplant: a DC motor, its amplifier and a quadrature encoder)
that must agree with them:

  fmi2/modelDescription.xml   the FMI 2.0 Co-Simulation interface
  fmi3/modelDescription.xml   the FMI 3.0 Co-Simulation interface
  fmi3/buildDescription.xml   the FMI 3.0 source-FMU build description
  fmi2/documentation/index.html, fmi3/...   the FMUs' documentation: the variables, from the descriptions
  plant_variables.h, .c       the variable table of the C code: value reference,
                              FMI 2 and 3 types, causality, the member of
                              PlantModel (fmu_src/plant/plant.h) it lives in,
                              range and start value

plant.csv has one row per variable; its name is also the PlantModel member. An
empty `type` (FMI 2) leaves the variable out of FMI 2 (`time`: FMI 3 needs an
independent variable, FMI 2 has an implicit one). `dependencies` lists the
inputs an output depends on without a step (none: every output changes only in
doStep), `initialDependencies` the parameters it depends on in initialization.

Usage: generate_plant.py OUTDIR [C source file names of the FMU's sources/ ...]
"""

import csv
import hashlib
import sys
import uuid
from pathlib import Path
from xml.sax.saxutils import quoteattr

from generate import METADATA, VERSION, build_description, unit_definitions  # the chip's generator, beside this one
from generating import harness_module, write_files

HERE = Path(__file__).resolve().parent
MODEL_IDENTIFIER = "pmdplant"
DESCRIPTION = (
    "DC motor with amplifier, armature resistance, back-EMF, inertia, viscous and Coulomb friction, "
    "and a quadrature encoder: a plant for the PMD motion processor's servo loop"
)
GENERATION_TOOL = f"pmdfmu {VERSION}"
# (name, description): errors are always logged, whatever SetDebugLogging says
LOG_CATEGORIES = [("errors", "Refused calls and values, with the function, the variable and the reason")]
C_TYPES = {"Real": "double", "Integer": "int32_t"}
FMI2_OF_FMI3 = {"Float64": "Real", "Int32": "Integer", "Int16": "Integer"}


def read_variables():
    with open(HERE / "plant.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    vrs = [int(r["vr"]) for r in rows]
    if len(set(vrs)) != len(vrs):
        sys.exit("plant.csv: duplicate value references")
    names = {r["name"] for r in rows}
    for r in rows:
        r["vr"] = int(r["vr"])
        if r["type"] and FMI2_OF_FMI3[r["fmi3Type"]] != r["type"]:
            sys.exit(f"plant.csv: {r['name']}: FMI 2 type {r['type']} does not hold FMI 3 {r['fmi3Type']}")
        for column in ("dependencies", "initialDependencies"):
            r[column] = r[column].split()
            unknown = set(r[column]) - names
            if unknown:
                sys.exit(f"plant.csv: {r['name']}: {column} names no variable {sorted(unknown)}")
    return rows


def read_units():
    with open(HERE / "units.csv", newline="") as f:
        return list(csv.DictReader(f))


def instantiation_token() -> str:
    """Changes whenever a table changes, so the FMU never runs with a foreign XML."""
    digest = hashlib.sha256((HERE / "plant.csv").read_bytes() + (HERE / "units.csv").read_bytes())
    return "{" + str(uuid.UUID(bytes=digest.digest()[:16])) + "}"


def chip_cycle_time() -> str:
    """The DefaultExperiment's stepSize: the chip's cycle (variables.csv's cycleTime start), the
    servo loop's sample time the plant is stepped at beside the chip; internalStep stays the
    integration step inside (FMI 3's fixedInternalStepSize)."""
    with open(HERE / "variables.csv", newline="") as f:
        return next(r["start"] for r in csv.DictReader(f) if r["name"] == "cycleTime")


def internal_step(variables) -> str:
    """internalStep's start value: also FMI 3's fixedInternalStepSize."""
    return next(v["start"] for v in variables if v["name"] == "internalStep")


def log_categories():
    return [
        "  <LogCategories>",
        *(f'    <Category name="{n}" description={quoteattr(d)}/>' for n, d in LOG_CATEGORIES),
        "  </LogCategories>",
    ]


def attributes(v) -> str:
    """unit (Reals only), min, max and start: what the variable's type element carries."""
    out = ""
    if v["unit"]:
        out += f' unit="{v["unit"]}"'
    for a in ("min", "max", "start"):
        if v[a]:
            out += f' {a}="{v[a]}"'
    return out


def fmi2_xml(variables, units, token: str, sources) -> str:
    variables = [v for v in variables if v["type"]]
    index = {v["name"]: i for i, v in enumerate(variables, start=1)}
    lines = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<fmiModelDescription fmiVersion="2.0" modelName="{MODEL_IDENTIFIER}" guid="{token}"',
        f"  description={quoteattr(DESCRIPTION)}",
        f'  {METADATA} generationTool="{GENERATION_TOOL}" variableNamingConvention="flat" numberOfEventIndicators="0">',
        f'  <CoSimulation modelIdentifier="{MODEL_IDENTIFIER}" canHandleVariableCommunicationStepSize="true"'
        ' canNotUseMemoryManagementFunctions="true" canGetAndSetFMUstate="true" canSerializeFMUstate="true">',
        "    <SourceFiles>",
        *(f'      <File name="{name}"/>' for name in sources),
        "    </SourceFiles>",
        "  </CoSimulation>",
        *unit_definitions({v["unit"] for v in variables if v["unit"]}),
        *log_categories(),
        f'  <DefaultExperiment startTime="0" stopTime="0.2" stepSize="{chip_cycle_time()}"/>',
        "  <ModelVariables>",
    ]
    for v in variables:
        initial = ' initial="exact"' if v["causality"] == "parameter" else ""
        lines += [
            f'    <ScalarVariable name="{v["name"]}" valueReference="{v["vr"]}" causality="{v["causality"]}"'
            f' variability="{v["variability"]}"{initial} description={quoteattr(v["description"])}>',
            f"      <{v['type']}{attributes(v)}/>",
            "    </ScalarVariable>",
        ]
    outputs = [v for v in variables if v["causality"] == "output"]

    def unknown(v, column):
        deps = " ".join(str(i) for i in sorted(index[n] for n in v[column]))
        return f'      <Unknown index="{index[v["name"]]}" dependencies="{deps}"/>'

    lines += [
        "  </ModelVariables>",
        "  <ModelStructure>",
        "    <Outputs>",
        *(unknown(v, "dependencies") for v in outputs),
        "    </Outputs>",
        "    <InitialUnknowns>",
        *(unknown(v, "initialDependencies") for v in outputs),
        "    </InitialUnknowns>",
        "  </ModelStructure>",
        "</fmiModelDescription>",
        "",
    ]
    return "\n".join(lines)


def fmi3_xml(variables, units, token: str) -> str:
    vr = {v["name"]: v["vr"] for v in variables}
    lines = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<fmiModelDescription fmiVersion="3.0" modelName="{MODEL_IDENTIFIER}" instantiationToken="{token}"',
        f"  description={quoteattr(DESCRIPTION)}",
        f'  {METADATA} generationTool="{GENERATION_TOOL}" variableNamingConvention="flat">',
        f'  <CoSimulation modelIdentifier="{MODEL_IDENTIFIER}" canHandleVariableCommunicationStepSize="true"'
        f' fixedInternalStepSize="{internal_step(variables)}" canGetAndSetFMUState="true"'
        ' canSerializeFMUState="true" hasEventMode="false" providesIntermediateUpdate="false"/>',
        *unit_definitions({v["unit"] for v in variables if v["unit"]}),
        *log_categories(),
        f'  <DefaultExperiment startTime="0" stopTime="0.2" stepSize="{chip_cycle_time()}"/>',
        "  <ModelVariables>",
    ]
    for v in variables:
        initial = ' initial="exact"' if v["causality"] == "parameter" else ""
        lines.append(
            f'    <{v["fmi3Type"]} name="{v["name"]}" valueReference="{v["vr"]}"'
            f' causality="{v["causality"]}" variability="{v["variability"]}"{initial}'
            f"{attributes(v)} description={quoteattr(v['description'])}/>"
        )
    outputs = [v for v in variables if v["causality"] == "output"]

    def unknown(element, v, column):
        deps = " ".join(str(vr[n]) for n in v[column])
        return f'    <{element} valueReference="{v["vr"]}" dependencies="{deps}"/>'

    lines += [
        "  </ModelVariables>",
        "  <ModelStructure>",
        *(unknown("Output", v, "dependencies") for v in outputs),
        *(unknown("InitialUnknown", v, "initialDependencies") for v in outputs),
        "  </ModelStructure>",
        "</fmiModelDescription>",
        "",
    ]
    return "\n".join(lines)


def c_double(text: str, default: str) -> str:
    return repr(float(text)) if text else default


def variables_c(variables, token: str):
    h = [
        "/* Generated by modelDescription/generate_plant.py from plant.csv: do not edit. */",
        "#ifndef PLANT_VARIABLES_H",
        "#define PLANT_VARIABLES_H",
        "",
        "#include <stddef.h>",
        "",
        f'#define PLANT_MODEL_IDENTIFIER "{MODEL_IDENTIFIER}"',
        f'#define PLANT_INSTANTIATION_TOKEN "{token}"',
        f"#define PLANT_VARIABLE_COUNT {len(variables)}",
        f"#define PLANT_LOG_CATEGORY_COUNT {len(LOG_CATEGORIES)}",
        "",
        "typedef enum {",
        *(f"    PLANT_LOG_{n.upper()}," for n, _ in LOG_CATEGORIES),
        "} PlantLogCategory;",
        "extern const char *const plant_log_category_names[PLANT_LOG_CATEGORY_COUNT];",
        "",
        "/* FMI 2 types (PLANT_NONE: not an FMI 2 variable) and FMI 3 types. */",
        "typedef enum { PLANT_NONE, PLANT_REAL, PLANT_INTEGER } PlantType;",
        "typedef enum { PLANT3_FLOAT64, PLANT3_INT32, PLANT3_INT16 } PlantType3;",
        "typedef enum { PLANT_PARAMETER, PLANT_INPUT, PLANT_OUTPUT, PLANT_INDEPENDENT } PlantCausality;",
        "",
        "/* One row of plant.csv. The value lives in the PlantModel member at offset,",
        " * a double for FMI 3 Float64, else an int32_t; min and max bound what a set",
        " * call (and a restored FMU state) may write there. */",
        "typedef struct {",
        "    unsigned vr;",
        "    unsigned char type;          /* PlantType */",
        "    unsigned char type3;         /* PlantType3 */",
        "    unsigned char causality;     /* PlantCausality */",
        "    size_t offset;",
        "    double min, max, start;",
        "    const char *name;",
        "} PlantVariable;",
        "",
        "extern const PlantVariable plant_variables[PLANT_VARIABLE_COUNT];",
        "",
        "#endif",
        "",
    ]
    types = {"": "PLANT_NONE", "Real": "PLANT_REAL", "Integer": "PLANT_INTEGER"}
    types3 = {"Float64": "PLANT3_FLOAT64", "Int32": "PLANT3_INT32", "Int16": "PLANT3_INT16"}
    member_type = {"Float64": "double", "Int32": "int32_t", "Int16": "int32_t"}
    c = [
        "/* Generated by modelDescription/generate_plant.py from plant.csv: do not edit. */",
        "#include <math.h>",
        "#include <stddef.h>",
        "#include <stdint.h>",
        "",
        '#include "plant.h"',
        '#include "plant_variables.h"',
        "",
        "const char *const plant_log_category_names[PLANT_LOG_CATEGORY_COUNT] = {",
        *(f'    "{n}",' for n, _ in LOG_CATEGORIES),
        "};",
        "",
        "/* Each variable's member has the size its type says (the negative array size stops the build otherwise). */",
        *(
            f"typedef char plant_member_{v['name']}[sizeof(((const PlantModel *)0)->{v['name']}) == "
            f"sizeof({member_type[v['fmi3Type']]}) ? 1 : -1];"
            for v in variables
        ),
        "",
        "const PlantVariable plant_variables[PLANT_VARIABLE_COUNT] = {",
    ]
    for v in variables:
        low = "INT16_MIN" if v["fmi3Type"] == "Int16" else "INT32_MIN" if v["fmi3Type"] == "Int32" else "-HUGE_VAL"
        high = "INT16_MAX" if v["fmi3Type"] == "Int16" else "INT32_MAX" if v["fmi3Type"] == "Int32" else "HUGE_VAL"
        c.append(
            f"    {{{v['vr']}, {types[v['type']]}, {types3[v['fmi3Type']]}, "
            f"PLANT_{v['causality'].upper()}, offsetof(PlantModel, {v['name']}), "
            f"{c_double(v['min'], low)}, {c_double(v['max'], high)}, {c_double(v['start'], '0.0')}, "
            f'"{v["name"]}"}},'
        )
    c += ["};", ""]
    return "\n".join(h), "\n".join(c)


def main(outdir: Path, sources) -> None:
    variables = read_variables()
    units = read_units()
    used = {v["unit"] for v in variables if v["unit"]}
    missing = used - {u["name"] for u in units}
    if missing:
        sys.exit(f"plant.csv: units not defined in units.csv: {sorted(missing)}")
    token = instantiation_token()
    files = {
        "fmi2/modelDescription.xml": fmi2_xml(variables, units, token, [n for n in sources if n not in FMI3_ONLY]),
        "fmi3/modelDescription.xml": fmi3_xml(variables, units, token),
        "fmi3/buildDescription.xml": build_description([n for n in sources if n not in FMI2_ONLY], MODEL_IDENTIFIER),
    }
    for version in (2, 3):
        files[f"fmi{version}/documentation/index.html"] = harness_module("documentation").documentation_html(
            files[f"fmi{version}/modelDescription.xml"]
        )
    files["plant_variables.h"], files["plant_variables.c"] = variables_c(variables, token)
    write_files(outdir, files)


FMI2_ONLY = {"fmi2.c", "fmi2_not_provided.c"}
FMI3_ONLY = {"fmi3.c", "fmi3_not_provided.c"}

if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    # a file of both shells (token.c) is named once
    main(Path(sys.argv[1]), list(dict.fromkeys(Path(a).name for a in sys.argv[2:])))
