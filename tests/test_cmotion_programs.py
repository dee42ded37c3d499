# SPDX-License-Identifier: BSD-2-Clause
"""Host programs written the way public C-Motion programs of both generations are
(tests/c/cmotion5_host.c, cmotion5_engine.c, cmotion2_host.c, cmotion5_machine.c; docs/sources.md names the public
programs whose constructs they cover) compile unchanged against the library's headers, with the
project's warnings as errors, and run to completion against the twin; their outputs are pinned.
Around them: every vendor header name compiles alone in both generations, the vendor's types are
the vendor's (PMDint32 is a long), every Magellan-only call of cmotion_calls.csv reaches the chip
and gets a Navigator's answer, and PMDFMU_DEVICE's links that cannot be opened answer
PMD_ERR_OpeningPort (tests/test_cmotion_line.py runs the programs over a line)."""

import os
import re
import shutil
import subprocess
import sys

import pytest

import pmdfmu
from cmotion_build import HOST_C, ROOT, compile_program, generate

sys.path.insert(0, str(ROOT / "modelDescription"))
from generating import harness_tables  # noqa: E402
from generate_cmotion import VENDOR_HEADERS  # noqa: E402  (every vendor header name the generator writes)

pytestmark = [pytest.mark.skipif(not shutil.which("cc"), reason="no C compiler"), pytest.mark.slow]  # compiles programs

PROGRAMS = ("cmotion5_host", "cmotion5_engine", "cmotion2_host", "cmotion5_machine")


@pytest.fixture(scope="module")
def generated(tmp_path_factory):
    return generate(tmp_path_factory.mktemp("cmotion-programs") / "generated")


@pytest.fixture(scope="module")
def programs(generated):
    return {
        name: compile_program(ROOT / "tests" / "c" / f"{name}.c", generated.parent / name, generated, warnings=True)
        for name in PROGRAMS
    }


def run(exe, env=None):
    out = subprocess.run(
        [str(exe)],
        capture_output=True,
        text=True,
        timeout=300,
        env=dict(os.environ, PMDFMU_FMU=str(pmdfmu.default_fmu(2)), **(env or {})),
    )
    # PMD_RESULT prints the source's path: keep its name only
    return out.returncode, re.sub(r"in file: \S*/", "in file: ", out.stdout), out.stderr


def test_a_5x_host_program_opens_serial_mp_device_axis_and_polls_motion_complete(programs):
    """20000 counts at 4 counts/cycle with 1/16 count/cycle^2: 64 cycles of ramp each way and 4936
    at full speed, 5064 cycles; the serial link's polls (57600 baud) end it 38 cycles later. A
    Magellan call is refused as a Navigator refuses it: invalid instruction, the event bit set."""
    code, out, err = run(programs["cmotion5_host"])
    assert code == 0 and not err
    assert out.splitlines() == [
        "C-Motion Version 5.0",
        "Opening serial port COM1",
        "Motion processor version 1.0",
        "Instruction error at start: 0x1 Processor reset",
        "Motion complete after 5102 cycles, 364 polls, at 20000",
        "SetOperatingMode: 0x2 Invalid instruction",
        "Error: Invalid instruction, PMDGetCurrentLoopValue(&hAxis, PMDCurrentLoopPhaseA, "
        "PMDCurrentLoopValueNodeActualCurrent, &current) at line: 56 in file: cmotion5_host.c",
        "Instruction error event: 1",
        "Instruction error: 0x2 Invalid instruction",
        "Event status: 0x0001",
        "Done",
    ]


def test_c_motion_engine_user_code_runs_its_task_polls_gettime_and_downloads_a_trace(programs):
    """The task opens the engine's own axis (no device), runs a velocity move for 500 cycles of
    GetTime, stops smoothly and reads the trace: commanded position and velocity every 4 cycles from
    the Update, the velocity ramping by 4 x 0x800 a sample to 2 counts/cycle (0x20000), then the
    position gaining 8 counts a sample."""
    code, out, err = run(programs["cmotion5_engine"])
    assert code == 0 and not err
    lines = out.splitlines()
    assert lines[:3] == ["Ran 501 cycles", "Smooth stop: No error", "Trace: 128 words"]
    samples = [tuple(int(x) for x in line.split()) for line in lines[3:]]
    assert [s[0] for s in samples] == list(range(64))
    assert [s[2] for s in samples] == [min(0x800 * (1 + 4 * k), 0x20000) for k in range(64)]
    assert [s[1] for s in samples[:6]] == [0, 0, 1, 2, 4, 7]
    assert all(b[1] - a[1] == 8 for a, b in zip(samples[16:], samples[17:]))
    assert samples[-1] == (63, 443, 0x20000)


def test_a_2x_host_program_sets_up_copies_multiupdates_and_polls_activity(programs):
    """Two trapezoidal moves started together by MultiUpdate: 1000 counts at 2 counts/cycle with
    1/64 count/cycle^2 ends after 628 cycles, 2000 after 1128; GetSampleTime's 16-bit word; a
    profile mode the chip lacks (invalid parameter, 0x04 in 2.x) and an axis number passed for a
    handle (invalid handle, refused unsent: the chip's host I/O error is the parameter's)."""
    code, out, err = run(programs["cmotion2_host"])
    assert code == 0 and not err
    assert out.splitlines() == [
        "host I/O error at start 1",
        "sample time 100 us",
        "axis 1 at 1000, cycle 628, motion complete 1",
        "axis 2 at 2000, cycle 1128, motion complete 1",
        "18031 polls",
        "PMDSetProfileMode: 0x4 Invalid data parameter",
        "PMDUpdate: 0x1106 Invalid handle",
        "host I/O error 4",
    ]


def test_a_5x_program_homes_on_home_then_index_clears_a_limit_and_runs_20_moves_against_a_machine(programs):
    """examples/machine/stage.toml: the home flag from 12345 (hunting at 8 counts/cycle, the capture
    latches the first cycle inside it), the index every 2000 stage counts (1652 past the new origin),
    the positive limit at 40000 stage counts (27652 in the homed register, passed by up to 20 counts at
    20 counts/cycle), its event cleared and the axis moved out; axis 2 (no switches) ends its 20 moves
    exactly at the last target."""
    code, out, err = run(
        programs["cmotion5_machine"], {"PMDFMU_MACHINE": str(ROOT / "examples" / "machine" / "stage.toml")}
    )
    assert code == 0 and not err
    assert out.splitlines() == [
        "Home captured at 12348",
        "Back at 12348, made the origin",
        "Index captured at 1652",
        "Positive limit: event 0x0029 signals 0x002F at 27670",
        "Cleared: event 0x0009",
        "Moved out to 0: event 0x0009",
        "20 moves in 46489 cycles, at -50000, target -50000",
        "Done",
    ]


@pytest.mark.parametrize(
    "device,line",
    [
        (
            "serial:/nonexistent/ttyUSB0",
            "PMDFMU_DEVICE=serial:/nonexistent/ttyUSB0: /nonexistent/ttyUSB0: No such file",
        ),
        ("tcp:127.0.0.1:1", "PMDFMU_DEVICE=tcp:127.0.0.1:1: cannot connect: Connection refused"),
        ("usb", "PMDFMU_DEVICE=usb: expected serial:PATH or tcp:HOST:PORT"),
    ],
)
def test_pmdfmu_device_links_answer_opening_port_with_a_transport_line(programs, device, line):
    """The program's own PMD_ABORTONERROR ends it with the code (0x1205, exit status 5) after
    printing the vendor's text; the library's line says why, on stderr."""
    code, out, err = run(programs["cmotion5_host"], {"PMDFMU_DEVICE": device})
    assert code == 0x1205 & 0xFF
    assert "Error: Error opening port, PMDPeriphOpenDeviceMP(&hDevice, &hPeriph)" in out
    assert err.startswith("pmdfmu: " + line)


@pytest.mark.parametrize("generation", [2, 5])
@pytest.mark.parametrize("header", [*VENDOR_HEADERS, *(f"c-motion/{h}" for h in VENDOR_HEADERS)])
def test_every_vendor_header_name_alone_brings_the_api_with_the_vendors_types(generated, tmp_path, header, generation):
    """A program including any one of PMD's header names compiles: PMDint32 is a long (a long* takes
    its address, as C++ code passing &value to a long* API needs), the calls of both handle styles
    are declared, and GetSampleTime takes the generation's pointer."""
    source = tmp_path / "one_header.c"
    source.write_text(
        f'#include "{header}"\n'
        "int main(void)\n{\n"
        "    PMDint32 position = 0;\n    long *p = &position;\n"
        "    PMDuint32 u = 0;\n    unsigned long *q = &u;\n"
        f"    {'PMDuint16' if generation == 2 else 'PMDuint32'} sample = 0;\n"
        "    PMDAxisHandle hAxis;\n    PMDDeviceHandle hDevice = {0};\n    PMDPeriphHandle hPeriph = {0};\n"
        "    (void)p; (void)q; (void)hDevice; (void)hPeriph;\n"
        "    return PMDGetSampleTime(&hAxis, &sample) == PMD_ERR_OK && MAXINT32 > 0 && MININT16 < 0;\n}\n"
    )
    subprocess.run(
        [
            "cc",
            "-std=c99",
            "-Wall",
            "-Wextra",
            "-Wpedantic",
            "-Werror",
            f"-DPMD_CMOTION_GENERATION={generation}",
            f"-I{HOST_C}",
            f"-I{generated}",
            "-fsyntax-only",
            str(source),
        ],
        check=True,
    )


def test_every_call_of_cmotion_calls_csv_is_declared_and_defined(generated, tmp_path):
    """Both generations: a program taking every call's address (the generated ones, and the library
    calls of host/c/PMDlibrary.h and PMDfmu.h) compiles and links."""
    md = ROOT / "modelDescription"
    calls = harness_tables().read_cmotion_calls(md / "cmotion_calls.csv", md / "constants.csv")
    for generation in (2, 5):
        source = tmp_path / f"addresses{generation}.c"
        source.write_text(
            f"#define PMD_CMOTION_GENERATION {generation}\n"
            '#include "c-motion.h"\n'
            "typedef void (*any)(void);\n"
            "static const any calls[] = {\n" + "".join(f"    (any)PMD{c.name},\n" for c in calls) + "};\n"
            "int main(void) { return calls[0] == 0; }\n"
        )
        run(compile_program(source, tmp_path / f"addresses{generation}", generated, warnings=True))


def test_with_no_generation_named_a_gets_reply_pointer_picks_its_form_in_c11(generated, tmp_path):
    """A 2.x program (its GetGearMaster source a PMDuint8, its sample time a PMDuint16) and a 5.x one (both
    16 or 32 bits wide) built as C11 with no PMD_CMOTION_GENERATION, under ASan: neither variable is
    written wider than it is (the bytes beside it keep their canary), each gets the chip's value, and
    every call's address is still taken (the name's own function, 5.x's form)."""
    source = tmp_path / "pointers.c"
    source.write_text(
        r"""#include <stdio.h>
#include "c-motion.h"
typedef void (*any)(void);
static const any taken[] = {(any)PMDGetGearMaster, (any)PMDGetSampleTime};
int main(void)
{
    PMDAxisHandle h;
    PMDAxis master = 0;
    struct { PMDuint8 source, canary[7]; } g2 = {9, {0xAA, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA}};
    struct { PMDuint16 source, canary[3]; } g5 = {9, {0xBBBB, 0xBBBB, 0xBBBB}};
    struct { PMDuint16 time, canary[3]; } t2 = {0, {0xCCCC, 0xCCCC, 0xCCCC}};
    PMDuint32 t5 = 0;
    PMDresult r;
    if (PMDSetupAxisInterface_Serial(&h, PMDAxis2, 1) != PMD_ERR_OK)
        return 1;
    PMDSetGearMaster(&h, PMDAxis3, 1);
    r = PMDGetGearMaster(&h, &master, &g2.source);
    printf("%x %x\n", r, g2.source);
    r = PMDGetGearMaster(&h, &master, &g5.source);
    printf("%x %x\n", r, g5.source);
    r = PMDGetSampleTime(&h, &t2.time);
    printf("%x %x\n", r, t2.time);
    r = PMDGetSampleTime(&h, &t5);
    printf("%x %lx\n", r, t5);
    printf("%x %x %x %d\n", g2.canary[0], g5.canary[0], t2.canary[0], taken[0] != 0);
    return PMDCloseAxisInterface(&h);
}
"""
    )
    status, out, err = run(compile_program(source, tmp_path / "pointers", generated, "address,undefined", std="c11"))
    assert status == 0 and "Sanitizer" not in err, err
    # 2.x's forms: the gear source, the Navigator's GetSampleTime (100 us); 5.x's GetSampleTime is the
    # Magellan's opcode, refused by a Navigator as an invalid instruction, the variable left as it was
    assert out.splitlines() == ["0 1", "0 1", "0 64", "2 0", "aa bbbb cccc 1"]


def test_a_dual_port_word_wider_than_32_bits_is_refused_and_nothing_is_written(generated, tmp_path):
    """PMDuint32 is a long here: PMDFMU_WriteDPRAM refuses a block holding a word past 32 bits
    (PMD_ERR_ParameterOutOfRange) before writing any of it; -1 as a long is the word 0xFFFFFFFF."""
    source = tmp_path / "dpram.c"
    source.write_text(
        r"""#include <stdio.h>
#include "c-motion.h"
int main(void)
{
    PMDAxisHandle h;
    PMDuint32 bad[2] = {7, 0x100000005UL}, good[2] = {(PMDuint32)-1L, 9};
    PMDint32 word = 0;
    PMDresult r;
    if (PMDSetupAxisInterface_Serial(&h, PMDAxis1, 1) != PMD_ERR_OK)
        return 1;
    PMDSetBufferStart(&h, 0, 0x200);
    PMDSetBufferLength(&h, 0, 2);
    r = PMDFMU_WriteDPRAM(&h.transport_data, 0x200, 2, bad);
    PMDReadBuffer(&h, 0, &word);
    printf("%x %ld\n", r, word);
    r = PMDFMU_WriteDPRAM(&h.transport_data, 0x200, 2, good);
    PMDSetBufferReadIndex(&h, 0, 0);
    PMDReadBuffer(&h, 0, &word);
    printf("%x %ld\n", r, word);
    return PMDCloseAxisInterface(&h);
}
"""
    )
    status, out, err = run(compile_program(source, tmp_path / "dpram", generated, warnings=True))
    assert status == 0, err
    assert out.splitlines() == ["110a 0", "0 -1"]


def test_every_magellan_only_call_is_sent_and_answered_as_a_navigator_answers(generated, tmp_path):
    """Each call of cmotion_calls.csv whose opcode is out_of_scope.csv's goes to the chip: invalid
    instruction (0x02), the instruction-error event bit set on the instruction's axis (the handle's,
    axis 2 here; axis 1 for a chip-wide call, sent with axis field 0); nothing is refused unsent."""
    md = ROOT / "modelDescription"
    tables = harness_tables()
    commands = {c.name: c for c in tables.read_commands(md / "commands.csv")}
    navigator = {c.opcode for c in commands.values()}
    calls = [
        c
        for c in tables.read_cmotion_calls(md / "cmotion_calls.csv", md / "constants.csv")
        if c.opcode is not None and c.opcode not in navigator
    ]
    assert len(calls) > 60
    lines = [
        "#include <stdio.h>",
        '#include "c-motion.h"',
        "int main(void)",
        "{",
        "    PMDAxisHandle h, h1;",
        "    PMDuint16 status = 0, code = 0;",
        "    if (PMDSetupAxisInterface_Parallel(&h, PMDAxis2, 0)) return 1;",
        "    PMDCopyAxisInterface(&h1, &h, PMDAxis1);",
        "    PMDGetHostIOError(&h, &code);",
    ]
    for c in calls:
        symbol = f"PMD{c.name}_5" if c.name in commands else f"PMD{c.name}"
        arguments = ", ".join(["&h"] + ["0"] * len(c.args) + ["NULL"] * len(c.reply))
        lines += [
            f'    printf("{c.name} 0x%X", (unsigned){symbol}({arguments}));',
            f"    PMDGetEventStatus(&{'h1' if c.scope == 'chip' else 'h'}, &status); PMDGetHostIOError(&h, &code);",
            '    printf(" %d 0x%X\\n", (status & PMDEventInstructionErrorMask) != 0, (unsigned)code);',
            "    PMDResetEventStatus(&h, 0); PMDResetEventStatus(&h1, 0);",
        ]
    lines += ["    PMDCloseAxisInterface(&h1);", "    return PMDCloseAxisInterface(&h);", "}", ""]
    source = tmp_path / "magellan.c"
    source.write_text("\n".join(lines))
    code, out, err = run(compile_program(source, tmp_path / "magellan", generated, warnings=True))
    assert code == 0, err
    assert out.splitlines() == [f"{c.name} 0x2 1 0x2" for c in calls]


def test_the_docs_list_every_call_of_both_generations():
    """docs/c-motion.md's list is the tables' (python modelDescription/generate_cmotion.py --markdown)."""
    import generate_cmotion

    text = (ROOT / "docs" / "c-motion.md").read_text()
    assert generate_cmotion.calls_markdown() in text, "run: python modelDescription/generate_cmotion.py --markdown"
