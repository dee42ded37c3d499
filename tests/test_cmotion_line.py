# SPDX-License-Identifier: BSD-2-Clause
"""The C library's line transport (host/c/PMDline.c): the same unchanged C program, run in-process and
with PMDFMU_DEVICE=serial:PATH (or tcp:HOST:PORT) against `pmdfmu serve`, prints the same lines,
chip times included: the server's virtual time is the in-process host timing model's."""

import os
import re
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import pytest

import pmdfmu
from cmotion_build import ROOT, compile_program, generate

pytestmark = pytest.mark.skipif(not shutil.which("cc"), reason="no C compiler")

PMDFMU = Path(sys.executable).parent / "pmdfmu"
# the programs that open a serial port (so in-process they time their commands as a serial line)
# and use commands only: the seed's programs read FMU variables through the library
# (PMDFMU_GetInteger, a cycle callback), which only the twin in-process has
PROGRAMS = ("cmotion5_host",)


@pytest.fixture(scope="module")
def programs(tmp_path_factory):
    out = tmp_path_factory.mktemp("cmotion-line")
    generated = generate(out / "generated")
    return {n: compile_program(ROOT / "tests" / "c" / f"{n}.c", out / n, generated, warnings=True) for n in PROGRAMS}


def run(exe, device=None):
    env = dict(os.environ, PMDFMU_FMU=str(pmdfmu.default_fmu(2)))
    env.pop("PMDFMU_DEVICE", None)
    if device:
        env["PMDFMU_DEVICE"] = device
    out = subprocess.run([str(exe)], capture_output=True, text=True, timeout=300, env=env)
    return out.returncode, re.sub(r"in file: \S*/", "in file: ", out.stdout), out.stderr


def serve(*args):
    p = subprocess.Popen([str(PMDFMU), "serve", *map(str, args)], stdout=subprocess.PIPE, text=True)
    first = p.stdout.readline()
    p.stdout.readline()
    return p, first


@pytest.mark.parametrize("name", PROGRAMS)
@pytest.mark.parametrize("kind", ["serial", "tcp"])
def test_a_c_program_prints_the_same_over_the_line_as_in_process(programs, tmp_path, name, kind):
    in_process = run(programs[name])
    assert in_process[0] == 0
    p, first = serve(*(["--serial", tmp_path / "pmd"] if kind == "serial" else ["--tcp", "127.0.0.1:0"]))
    try:
        device = f"serial:{tmp_path / 'pmd'}" if kind == "serial" else "tcp:" + first.split()[3].rstrip(",")
        assert run(programs[name], device) == in_process
    finally:
        p.send_signal(signal.SIGINT)
        assert p.wait(timeout=60) == 0


def test_what_needs_the_twin_in_process_answers_not_supported_over_a_line(tmp_path):
    """A program that reads an FMU variable over a line gets PMD_ERR_NotSupported and the library's
    line saying why; its commands still work."""
    source = tmp_path / "fmu_only.c"
    source.write_text(
        '#include "c-motion.h"\n#include <stdio.h>\n'
        "int main(void) { PMDAxisHandle h; PMDint32 t = 0; PMDuint16 e = 0; PMDresult r;\n"
        "  if (PMDSetupAxisInterface_Serial(&h, PMDAxis1, 0)) return 1;\n"
        '  r = PMDFMU_GetInteger(&h, "chipTime", &t); printf("GetInteger 0x%X\\n", (unsigned)r);\n'
        '  r = PMDGetHostIOError(&h, &e); printf("GetHostIOError 0x%X %u\\n", (unsigned)r, (unsigned)e);\n'
        "  return PMDCloseAxisInterface(&h); }\n"
    )
    exe = compile_program(source, tmp_path / "fmu_only", generate(tmp_path / "generated"), warnings=True)
    p, _first = serve("--serial", tmp_path / "pmd")
    try:
        code, out, err = run(exe, f"serial:{tmp_path / 'pmd'}")
    finally:
        p.send_signal(signal.SIGTERM)
        assert p.wait(timeout=60) == 0
    assert code == 0
    assert out.splitlines() == ["GetInteger 0x1101", "GetHostIOError 0x0 1"]  # PMD_ERR_NotSupported
    assert "PMDFMU_GetInteger needs the twin in-process" in err


def test_a_5x_program_addresses_each_chip_of_a_multi_drop_line(tmp_path):
    """pmdfmu serve --chips 2: PMDPeriphOpenPeriphMultiDrop's address goes into every packet of the
    device opened on it, so each chip (addresses 0 and 1) keeps the position written to it."""
    source = tmp_path / "multidrop.c"
    source.write_text(
        '#include "c-motion.h"\n#include <stdio.h>\n'
        "int main(void) { PMDPeriphHandle line = {0}, drop[2]; PMDDeviceHandle dev[2]; PMDAxisHandle ax[2];\n"
        "  PMDint32 p = 0; int i;\n"
        "  if (PMDPeriphOpenCOM(&line, NULL, PMDSerialPort1, PMDSerialBaud57600, PMDSerialParityNone, PMDSerialStopBits1)) return 1;\n"
        "  for (i = 0; i < 2; i++) {\n"
        "    if (PMDPeriphOpenPeriphMultiDrop(&drop[i], &line, (PMDparam)i)) return 2;\n"
        "    if (PMDPeriphOpenDeviceMP(&dev[i], &drop[i])) return 3;\n"
        "    if (PMDAxisOpen(&ax[i], &dev[i], PMDAxis1)) return 4;\n"
        "    PMDSetPosition(&ax[i], 1000 * (i + 1)); }\n"
        "  for (i = 0; i < 2; i++) { PMDresult r = PMDGetPosition(&ax[i], &p);\n"
        '    printf("chip %d: 0x%X %ld\\n", i, (unsigned)r, (long)p); PMDDeviceClose(&dev[i]); }\n'
        "  return 0; }\n"
    )
    exe = compile_program(source, tmp_path / "multidrop", generate(tmp_path / "generated"), warnings=True)
    p, _first = serve("--serial", tmp_path / "pmd", "--chips", 2)
    try:
        code, out, err = run(exe, f"serial:{tmp_path / 'pmd'}")
    finally:
        p.send_signal(signal.SIGTERM)
        assert p.wait(timeout=60) == 0
    assert code == 0, err
    assert out.splitlines() == ["chip 0: 0x0 1000", "chip 1: 0x0 2000"]
