# SPDX-License-Identifier: BSD-2-Clause
"""An FMU's documentation/index.html (FMI 2.0.4 and FMI 3.0 name it the documentation's entry point),
written from its model description alone: the build writes it beside each model description
(modelDescription/generate.py, generate_plant.py) and `pmdfmu pack` writes it again for the packed
model. No third-party imports: the generators load this module by path."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from html import escape
from typing import Dict, List, Tuple

# the project's pages each FMU's page names, by its modelIdentifier: (path in pmdfmu's source, what it tells)
PAGES: Dict[str, List[Tuple[str, str]]] = {
    "PMDMotionProcessor": [
        ("README.md", "what the twin is, a first script, a first co-simulation with the plant"),
        ("docs/fmu.md", "the variables, the ports, timing, bad input, FMU states, logging"),
        ("docs/scripts.md", "the script parameter's language; a profile packed into the FMU (pmdfmu pack)"),
        ("docs/systems.md", "the chip with the plant FMU: wiring, the SSP, masters"),
        ("docs/tools.md", "the FMU in every FMI tool tested, with what to do in each"),
        ("docs/commands.md", "every chip command, register and constant"),
    ],
    "pmdplant": [
        ("docs/systems.md", "the plant's model, its parameters and the wiring to the chip FMU, the SSP, masters"),
        ("docs/tools.md", "the FMUs in every FMI tool tested, with what to do in each"),
        ("README.md", "pmdfmu: the motion processor's twin this plant closes the servo loop of"),
    ],
}

# FMI 2's type elements inside a ScalarVariable; FMI 3 names each variable's element by its type
FMI2_TYPES = ("Real", "Integer", "Boolean", "String", "Enumeration")

STYLE = (
    "body{font-family:sans-serif;max-width:80em;margin:1em auto;padding:0 1em}"
    "table{border-collapse:collapse}th,td{border:1px solid #ccc;padding:2px 6px;text-align:left;vertical-align:top}"
    "th{background:#eee}td.name{font-family:monospace;white-space:nowrap}"
)


def documentation_html(model_description: str) -> str:
    """The page of the FMU whose modelDescription.xml (FMI 2 or 3) is model_description: what the model is,
    its metadata, every variable with its value reference, causality, type (an FMI 3 array with its size),
    unit (its own or its declared type's) and description, in the description's order; then the project's
    pages (PAGES), named by their paths in pmdfmu's source (the FMU carries no copy of them). Well-formed
    XHTML written from the description alone: the same description gives the same page."""
    root = ET.fromstring(model_description)
    fmi3 = root.get("fmiVersion", "").startswith("3")
    identifier = root.find("CoSimulation").get("modelIdentifier")
    units = {}  # a declared type's unit by its name
    for t in root.iter():
        if t.tag == "SimpleType":  # FMI 2: <SimpleType name><Real unit/></SimpleType>
            units[t.get("name")] = next((e.get("unit") for e in t), None)
        elif fmi3 and t.tag.endswith("Type") and t.get("name"):
            units[t.get("name")] = t.get("unit")
    rows = []
    for v in root.find("ModelVariables"):
        element = v if fmi3 else next(e for e in v if e.tag in FMI2_TYPES)
        kind = element.tag + "".join(
            f"[{d.get('start') or 'size of ' + d.get('valueReference', '?')}]" for d in element if d.tag == "Dimension"
        )
        if element.get("declaredType"):
            kind += f" ({element.get('declaredType')})"
        unit = element.get("unit") or units.get(element.get("declaredType")) or ""
        cells = [v.get("valueReference"), v.get("causality", "local"), kind, unit, v.get("description", "")]
        rows.append(
            f'<tr><td class="name">{escape(v.get("name"))}</td>'
            + "".join(f"<td>{escape(c)}</td>" for c in cells)
            + "</tr>"
        )
    name = root.get("modelName")
    facts = [
        ("FMI", f"{root.get('fmiVersion')} Co-Simulation"),
        ("modelIdentifier", identifier),
        ("instantiation token" if fmi3 else "GUID", root.get("instantiationToken" if fmi3 else "guid")),
        ("version", root.get("version")),
        ("generationTool", root.get("generationTool")),
        ("author", root.get("author")),
        ("copyright", root.get("copyright")),
        ("license", root.get("license")),
    ]
    lines = [
        "<!DOCTYPE html>",
        '<html xmlns="http://www.w3.org/1999/xhtml" lang="en" xml:lang="en">',
        "<head>",
        '<meta charset="UTF-8"/>',
        f"<title>{escape(name)}</title>",
        f"<style>{STYLE}</style>",
        "</head>",
        "<body>",
        f"<h1>{escape(name)}</h1>",
        f"<p>{escape(root.get('description', ''))}</p>",
        "<table>",
        *(f"<tr><th>{escape(k)}</th><td>{escape(v)}</td></tr>" for k, v in facts if v),
        "</table>",
        f"<h2>Variables ({len(rows)})</h2>",
        "<table>",
        "<tr><th>name</th><th>value reference</th><th>causality</th><th>type</th><th>unit</th><th>description</th></tr>",
        *rows,
        "</table>",
        "<h2>Documentation</h2>",
        "<p>pmdfmu's documentation, in its source distribution:</p>",
        "<ul>",
        *(f"<li><code>{escape(path)}</code>: {escape(what)}</li>" for path, what in PAGES.get(identifier, [])),
        "</ul>",
        "</body>",
        "</html>",
        "",
    ]
    return "\n".join(lines)


__all__ = ["documentation_html", "PAGES"]
