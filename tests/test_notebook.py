# SPDX-License-Identifier: BSD-2-Clause
"""examples/notebooks/pmdfmu.ipynb runs from top to bottom in a fresh kernel (nbclient), every cell without
an error, its plots drawn inline, and its gate passes: the notebook never goes stale."""

from pathlib import Path

import nbclient
import nbformat
import pytest

pytestmark = pytest.mark.slow  # tests/README.md: starts a kernel, runs chip and plant for seconds

NOTEBOOK = Path(__file__).resolve().parent.parent / "examples" / "notebooks" / "pmdfmu.ipynb"


def test_the_notebook_runs_and_its_gate_passes():
    nb = nbformat.read(NOTEBOOK, as_version=4)
    nbclient.NotebookClient(
        nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(NOTEBOOK.parent)}}
    ).execute()
    outputs = [o for cell in nb.cells if cell.cell_type == "code" for o in cell.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    images = [o for o in outputs if "image/png" in o.get("data", {})]
    assert len(images) == 3  # the profile, the trace scope, the closed loop
    text = "".join(o.get("text", "") for o in outputs)
    assert "pmdfmu verify: 1 of 1 case passed" in text and "150 samples of time" in text


def test_the_notebook_is_stored_without_outputs():
    nb = nbformat.read(NOTEBOOK, as_version=4)
    assert all(not cell.get("outputs") for cell in nb.cells if cell.cell_type == "code")
