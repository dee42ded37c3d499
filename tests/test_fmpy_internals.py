# SPDX-License-Identifier: BSD-2-Clause
"""The FMPy internals the harness uses for speed (docs/architecture.md): FMPy's slaves declare their FMI
functions' prototypes in _loadFunctions() into _functions (chip._SharedPrototypes replaces that with the
prototypes of the FMU file's first slave), and keep the loaded library in .dll (recording.extension
looks the FMU's extension functions up there). pyproject.toml pins fmpy below 0.4; this fails with a
clear message when a version changes those names."""

import inspect

import fmpy
import pytest
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave

import pmdfmu


def changed(what: str) -> str:
    return (
        f"FMPy {fmpy.__version__} changed {what}, which pmdfmu's harness relies on for speed: pin the "
        "last FMPy that has it (pyproject.toml) or update python/pmdfmu/chip.py (_SharedPrototypes)"
    )


@pytest.mark.parametrize("slave", [FMU2Slave, FMU3Slave])
def test_fmpy_still_declares_its_prototypes_in_load_functions(slave):
    constructors = [inspect.getsource(c.__init__) for c in slave.__mro__ if "__init__" in vars(c) and c is not object]
    assert hasattr(slave, "_loadFunctions") and any("self._loadFunctions()" in source for source in constructors), (
        changed(f"{slave.__name__}._loadFunctions")
    )


@pytest.mark.parametrize("version", [2, 3])
def test_a_chip_uses_the_shared_prototypes_and_library(version):
    with pmdfmu.Chip(fmi_version=version) as chip:
        functions = getattr(chip.fmu, "_functions", None)
        assert isinstance(functions, dict), changed("the slaves' _functions dict")
        name = f"fmi{version}DoStep"
        assert name in functions and hasattr(functions[name], "argtypes"), changed(f"_functions[{name!r}]")
        assert functions is chip.fmu._shared_functions, changed("the call of _loadFunctions in the constructor")
        assert hasattr(chip._library, name), changed("the slaves' .dll (the loaded library)")


def test_a_call_that_needs_a_missing_extra_says_which_to_install(monkeypatch, tmp_path):
    """Dask and matplotlib are extras (pmdfmu[sweep], pmdfmu[plot]): without them, the call that needs one
    raises ImportError naming the extra."""
    import sys
    from pmdfmu import extras
    from pmdfmu.sweep import Case

    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed raises ImportError
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    with pytest.raises(
        ImportError,
        match=r"a sweep on a local cluster .* needs distributed, which comes with "
        r"pmdfmu's 'sweep' extra: pip install 'pmdfmu\[sweep\]'",
    ):
        pmdfmu.sweep([Case("c")])
    with pytest.raises(ImportError, match=r"pip install 'pmdfmu\[plot\]'"):
        extras.pyplot("a plot")
    script = tmp_path / "s.pmd"
    script.write_text(
        "@0\nSetPosition(Axis1, 100);\nSetVelocity(Axis1, 0x10000);\nSetAcceleration(Axis1, 0x1000);\nUpdate(Axis1);\n"
    )
    assert pmdfmu.sweep([Case("c", script=str(script))], scheduler="serial").rows[0]["status"] == "ok"
