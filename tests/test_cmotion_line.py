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

import numpy as np
import pytest

import pmdfmu
from cmotion_build import ROOT, compile_program, generate

pytestmark = pytest.mark.skipif(not shutil.which("cc"), reason="no C compiler")

PMDFMU = Path(sys.executable).parent / "pmdfmu"
# the programs that open a serial port (so in-process they time their commands as a serial line)
# and use commands only
PROGRAMS = ("cmotion5_host",)
STAGE = ROOT / "examples" / "machine" / "stage.toml"
# every program of the in-process tests (test_cmotion.py, test_cmotion_programs.py) with its arguments and
# machine: over the line with the twin's monitor (PMDFMU_MONITOR) for what a chip has no packet for
MONITORED = [
    ("seed_1_1", ()),
    ("seed_1_2", ()),
    *[("seed_1_3", (mode,)) for mode in ("writebuffer", "dpram", "refill")],
    *[("seed_1_4", (mode,)) for mode in ("update", "multiupdate")],
    *[("seed_1_5", (mode,)) for mode in ("single", "multi")],
    *[("seed_1_6", mode) for mode in ((), ("poll",), ("meant",), ("meant", "poll"))],
    ("cmotion_example", ()),
    ("cmotion5_host", ()),
    ("cmotion5_engine", ()),
    ("cmotion2_host", ()),
    ("cmotion5_machine", (), STAGE),
]
CYCLE_LINE = re.compile(r"C \d")  # seed_support.h's line after every cycle, from the cycle callback


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
    """The server started, its first line (the endpoint); p.monitor: --monitor's HOST:PORT if asked."""
    p = subprocess.Popen([str(PMDFMU), "serve", *map(str, args)], stdout=subprocess.PIPE, text=True)
    first = p.stdout.readline()
    second = p.stdout.readline()
    p.monitor = second.split(";")[0].split()[-1] if second.startswith("monitor") else None
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


@pytest.fixture(scope="module")
def monitored(tmp_path_factory):
    out = tmp_path_factory.mktemp("cmotion-monitored")
    generated = generate(out / "generated")
    names = {m[0] for m in MONITORED}
    return {
        n: compile_program(
            ROOT / ("examples" if n == "cmotion_example" else "tests") / "c" / f"{n}.c", out / n, generated
        )
        for n in names
    }


@pytest.mark.slow  # compiles and runs fourteen programs twice
@pytest.mark.parametrize("run_", MONITORED, ids=lambda m: "-".join((m[0], *m[1])))
def test_every_in_process_program_runs_over_the_line_with_the_monitor_as_in_process(monitored, tmp_path, run_):
    """PMDFMU_MONITOR names `pmdfmu serve --monitor`: the program's cycles run (PMDFMU_RunCycles), sleeps
    (PMDTaskWait) pass chip time, PMDFMU_GetHostTime is the line's clock, the dual-port upload and FMU
    variables reach the chip; timed as a serial line in-process too (PMDFMU_HOST_INTERFACE=serial, whatever
    the program opens), it prints the same lines. The cycle callback's lines come from the server's
    recording instead: the same chip times and commanded values, cycle by cycle."""
    name, args, *machine = run_
    env = dict(os.environ, PMDFMU_FMU=str(pmdfmu.default_fmu(2)), PMDFMU_HOST_INTERFACE="serial")
    for v in ("PMDFMU_DEVICE", "PMDFMU_MONITOR", "PMDFMU_MACHINE"):
        env.pop(v, None)
    if machine:
        env["PMDFMU_MACHINE"] = str(machine[0])
    exe = [str(monitored[name]), *args]
    here = subprocess.run(exe, capture_output=True, text=True, timeout=300, env=env)
    assert here.returncode == 0, here.stderr
    printed = here.stdout.splitlines()
    cycles = [[int(x) for x in c.split()[1:]] for c in printed if CYCLE_LINE.match(c)]
    # the cycles compared where they are few enough: the server records a part after every packet, and 1.3's
    # refill (80 000 WriteBuffer packets, 1.7 million cycles) would take a minute
    record = tmp_path / "line.csv" if 0 < len(cycles) <= 200_000 else None
    p, first = serve(
        "--serial",
        tmp_path / "pmd",
        "--monitor",
        "127.0.0.1:0",
        *(["--record", record] if record else []),
        *(["--machine", machine[0]] if machine else []),
    )
    try:
        env.update(PMDFMU_DEVICE=f"serial:{tmp_path / 'pmd'}", PMDFMU_MONITOR="tcp:" + p.monitor)
        line = subprocess.run(exe, capture_output=True, text=True, timeout=300, env=env)
    finally:
        p.send_signal(signal.SIGINT)
        assert p.wait(timeout=60) == 0
    assert line.returncode == 0, line.stderr
    assert line.stdout.splitlines() == [c for c in printed if not CYCLE_LINE.match(c)]
    if record:  # chip time, then each axis's commanded position, velocity, acceleration
        rows = np.loadtxt(record, delimiter=",", skiprows=1, dtype=np.int64, ndmin=2)
        expected = [[c[0], *[c[1 + 5 * a + q] for a in range(4) for q in range(3)]] for c in cycles]
        assert rows.tolist() == expected


@pytest.mark.parametrize(
    "env,line",
    [
        (
            {"PMDFMU_DEVICE": "serial:/dev/null", "PMDFMU_MONITOR": "tcp:127.0.0.1:1"},
            "PMDFMU_MONITOR=tcp:127.0.0.1:1: cannot connect: Connection refused",
        ),
        (
            {"PMDFMU_DEVICE": "serial:/dev/null", "PMDFMU_MONITOR": "unix:/x"},
            "PMDFMU_MONITOR=unix:/x: expected tcp:HOST:PORT",
        ),
        ({"PMDFMU_HOST_INTERFACE": "warp"}, "PMDFMU_HOST_INTERFACE=warp: not a kind of host interface"),
    ],
)
def test_a_bad_monitor_or_host_interface_fails_the_opening_with_a_transport_line(programs, env, line):
    """PMD_ERR_OpeningPort (the program's PMD_ABORTONERROR: exit status 5), the library's line on stderr."""
    exe = programs["cmotion5_host"]
    out = subprocess.run(
        [str(exe)],
        capture_output=True,
        text=True,
        timeout=60,
        env={
            **{k: v for k, v in os.environ.items() if not k.startswith("PMDFMU_")},
            "PMDFMU_FMU": str(pmdfmu.default_fmu(2)),
            **env,
        },
    )
    assert out.returncode == 0x1205 & 0xFF
    assert out.stderr.startswith("pmdfmu: " + line)


def test_a_regular_file_named_as_the_serial_line_is_refused_and_left_as_it_was(programs, tmp_path):
    """The attacker's finding: PMDFMU_DEVICE=serial:FILE (and Chip(device="serial:FILE")) opened a regular
    file as the line and wrote the packets into it; a typo in the path overwrote the user's file."""
    victim = tmp_path / "notes.txt"
    victim.write_text("the user's notes\n")
    code, out, err = run(programs["cmotion5_host"], f"serial:{victim}")
    assert code == 0x1205 & 0xFF
    assert err.startswith(f"pmdfmu: PMDFMU_DEVICE=serial:{victim}: {victim}: a regular file, not a serial line")
    with pytest.raises(ValueError, match="a regular file, not a serial line: nothing was written"):
        pmdfmu.Chip(device=f"serial:{victim}")
    assert victim.read_text() == "the user's notes\n"


def test_a_tcp_port_past_65535_is_refused_not_wrapped(programs):
    """The attacker's finding: getaddrinfo took tcp:HOST:99999 as port 99999 mod 65536 = 34463, and the
    library and the harness connected there (to whatever listens on it)."""
    code, _out, err = run(programs["cmotion5_host"], "tcp:127.0.0.1:99999")
    assert code == 0x1205 & 0xFF
    assert err.startswith("pmdfmu: PMDFMU_DEVICE=tcp:127.0.0.1:99999: port 99999 is not 0 .. 65535"), err
    with pytest.raises(ValueError, match="port 99999 is not 0 .. 65535"):
        pmdfmu.Chip(device="tcp:127.0.0.1:99999")
    with pytest.raises(ValueError, match="port 70000 is not 0 .. 65535"):
        pmdfmu.Chip(device="serial:/dev/null", monitor="tcp:127.0.0.1:70000")
    code, _out, err = run(programs["cmotion5_host"], "tcp:127.0.0.1:0099999")
    assert code == 0x1205 & 0xFF and "port 0099999 is not 0 .. 65535" in err, err


def test_a_tcp_port_with_leading_zeros_is_its_number_in_the_library_and_the_harness(programs):
    """The port check refused a port of more than five digits: tcp:HOST:000001 was no port to the C
    library, port 1 to the harness (both now try port 1, where nothing listens)."""
    code, _out, err = run(programs["cmotion5_host"], "tcp:127.0.0.1:000001")
    assert code == 0x1205 & 0xFF and "Connection refused" in err and "is not 0 .. 65535" not in err, err
    with pytest.raises(ConnectionRefusedError):
        pmdfmu.Chip(device="tcp:127.0.0.1:000001")
