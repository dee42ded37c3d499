# SPDX-License-Identifier: BSD-2-Clause
"""Every FMU carries documentation/index.html (FMI 2.0.4 and FMI 3.0: the documentation's entry point),
written at build time from its model description: well-formed, naming every variable with its causality,
type, unit and description, and the project's pages; a packed FMU's names the packed model."""

import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path

import fmpy
import pytest

import pmdfmu
from pmdfmu.documentation import PAGES, documentation_html
from pmdfmu.pack import pack

REPO = Path(__file__).resolve().parent.parent
XHTML = "{http://www.w3.org/1999/xhtml}"
FMUS = [(model, version) for model in ("chip", "plant") for version in (2, 3)]


def fmu_path(model, version):
    chip = pmdfmu.default_fmu(version)
    return chip if model == "chip" else chip.with_name(f"pmdplant-fmi{version}.fmu")


def page(fmu):
    """(the page's text, the model description's text) of the FMU."""
    with zipfile.ZipFile(fmu) as z:
        return z.read("documentation/index.html").decode("utf-8"), z.read("modelDescription.xml").decode("utf-8")


def variable_rows(html):
    """{name: [value reference, causality, type, unit, description]} of the page's variable table."""
    root = ET.fromstring(html)  # well-formed: an XML parser reads it
    rows = {}
    for tr in root.iter(f"{XHTML}tr"):
        cells = ["".join(td.itertext()) for td in tr.findall(f"{XHTML}td")]
        if len(cells) == 6:
            rows[cells[0]] = cells[1:]
    return rows


@pytest.mark.parametrize("model,version", FMUS)
def test_the_page_names_every_variable_with_causality_type_unit_and_description(model, version):
    html, xml = page(fmu_path(model, version))
    assert html == documentation_html(xml)  # what the build wrote is the description's page
    md = fmpy.read_model_description(str(fmu_path(model, version)))
    rows = variable_rows(html)
    assert list(rows) == [v.name for v in md.modelVariables]
    for v in md.modelVariables:
        reference, causality, kind, unit, description = rows[v.name]
        assert reference == str(v.valueReference) and causality == v.causality, v.name
        assert kind.startswith(v.type) and description == (v.description or ""), v.name
        if v.dimensions:
            assert f"[{v.dimensions[0].start}]" in kind, v.name
        declared = v.declaredType.unit if v.declaredType is not None and hasattr(v.declaredType, "unit") else None
        assert unit == (v.unit or declared or ""), v.name
    units = {rows[n][3] for n in rows}
    assert "s" in units and ("counts" in units if model == "chip" else len(units) > 2)
    root = ET.fromstring(html)
    assert "".join(root.find(f"{XHTML}head/{XHTML}title").itertext()) == md.modelName
    pages = ["".join(c.itertext()) for c in root.iter(f"{XHTML}code")]
    assert pages == [path for path, _ in PAGES[md.coSimulation.modelIdentifier]]


def test_the_pages_named_exist_in_the_project():
    for pages in PAGES.values():
        for path, _ in pages:
            assert (REPO / path).is_file(), path


@pytest.mark.parametrize("version", [2, 3])
def test_a_packed_fmus_page_is_the_packed_models(tmp_path, version):
    packed = pack(REPO / "examples" / "two_axis.script", tmp_path / "p.fmu", version)
    html, xml = page(packed.fmu)
    assert html == documentation_html(xml)
    assert f"<title>{packed.model_name}</title>" in html and packed.token in html
    assert not fmpy.validation.validate_fmu(str(packed.fmu))
