# SPDX-License-Identifier: BSD-2-Clause
"""The FMU's block path for memory.data: fmi2SetInteger takes
a run of consecutive memory.data[k] value references, and fmi3SetUInt32 the
memory.data array, as one block (pmd_set_memory_data) instead of value by value.
It must leave the FMU exactly as the per-value path does: the same memory, the
same port variables, the same status, the same message for a refused call, and
nothing changed by a refused call.

FMI 2 pins it to the per-value path directly: a memory.data element can fail no
check of fmi2SetInteger (a 32-bit word, an input, settable in every state a set
is), and sets nothing any other value's check looks at, so a call's outcome does
not depend on where its memory.data elements stand. Each call below is therefore
also made, on a twin chip, with its other values in their order and its
memory.data elements after them, the last value of each element only, in
descending value references (no two consecutive: the per-value path), and both
chips must answer and end alike, FMU state byte for byte. FMI 3's array always
takes the block path: it is pinned to FMI 2's per-value path by its effect."""

import ctypes
from collections import defaultdict
from types import SimpleNamespace

import numpy as np
import pytest

import pmdfmu
from states import InitializationChip, snapshot
from stepwise import write_memory_stepwise

SIZE = 0x400  # memorySize of the chips below
WORDS = 64  # memory.data[1..64]


class _Names:
    """Stands for a chip where only the case names are wanted (parametrize, at collection)."""

    variables = defaultdict(lambda: SimpleNamespace(valueReference=0))


def chips(version):
    return pmdfmu.Chip(version, memorySize=SIZE), pmdfmu.Chip(version, memorySize=SIZE)


def vr(chip, name):
    return chip.variables[name].valueReference


def set_integer(chip, pairs):
    """One fmi2SetInteger of (value reference, value) pairs: its status and the messages it logged."""
    chip.messages.clear()
    vrs = (ctypes.c_uint * max(len(pairs), 1))(*[v for v, _ in pairs])
    values = (ctypes.c_int * max(len(pairs), 1))(*[x for _, x in pairs])
    status = chip.fmu._functions["fmi2SetInteger"](chip.fmu.component, vrs, len(pairs), values)
    return status, list(chip.messages)


def per_value_form(pairs, data):
    """The same call with its memory.data elements last, the last value of each, in descending value
    references: no run of two, every element through pmd_set_integer."""
    others = [(v, x) for v, x in pairs if v not in data]
    last = {v: x for v, x in pairs if v in data}
    return others + sorted(last.items(), reverse=True)


def assert_alike(fast, slow, pairs):
    data = range(vr(fast, "memory.data[1]"), vr(fast, "memory.data[1]") + WORDS)
    answer = set_integer(fast, pairs)
    assert answer == set_integer(slow, per_value_form(pairs, data)), pairs
    fast.get("host.ack"), slow.get("host.ack")  # a get executes a pending write: both alike
    assert snapshot(fast) == snapshot(slow)
    return answer


def strobe(chip, address, count, strobe_value):
    return [
        (vr(chip, "memory.address"), address),
        (vr(chip, "memory.count"), count),
        (vr(chip, "memory.strobe"), strobe_value),
    ]


def block(chip, first, values):
    """memory.data[first], [first + 1], .. set to values: a run of consecutive value references."""
    start = vr(chip, f"memory.data[{first}]")
    return [(start + k, int(x)) for k, x in enumerate(values)]


def test_memory_data_value_references_are_consecutive():
    """The block path's premise (pmd_memory_data_span): memory.data[k + 1] is memory.data[1] + k, in
    FMI 2, and FMI 3's array is the FMI 2 scalars from memory.data[1] on."""
    with pmdfmu.Chip(2) as two, pmdfmu.Chip(3) as three:
        first = vr(two, "memory.data[1]")
        assert [vr(two, f"memory.data[{k + 1}]") for k in range(WORDS)] == list(range(first, first + WORDS))
        assert vr(three, "memory.data") == first


def legal_calls(chip):
    rng = np.random.default_rng(5)
    words = [int(w) for w in rng.integers(-(2**31), 2**31, WORDS)]
    a, n = vr(chip, "memory.address"), vr(chip, "memory.count")
    word, count = vr(chip, "host.word[1]"), vr(chip, "host.wordCount")
    return {
        "the harness's strobe": block(chip, 1, words) + strobe(chip, 0x10, WORDS, 1),
        "a short block": block(chip, 1, words[:5]) + strobe(chip, SIZE - 5, 5, 2),
        "a block from the middle": block(chip, 10, words[:31]) + strobe(chip, 0x20, 40, 3),
        "a block up to memory.data[64]": block(chip, 40, words[:25]) + strobe(chip, 0, WORDS, 4),
        "two elements": block(chip, 63, [-1, 7]),
        "one element": block(chip, 7, [-(2**31)]),
        "descending": list(reversed(block(chip, 1, words))),
        "overlapping runs: the later wins": block(chip, 1, words[:20]) + block(chip, 5, words[30:50]),
        "a run repeated": block(chip, 1, words) + block(chip, 1, words[::-1]),
        "runs broken by other variables": (
            block(chip, 1, words[:20])
            + [(n, 33)]
            + block(chip, 21, words[20:])
            + [(word, 0x1234), (a, 0x40)]
            + block(chip, 3, [5, 6, 7])
            + [(count, 0), (vr(chip, "memory.strobe"), 9)]
        ),
        "every other element": [p for k, p in enumerate(block(chip, 1, words)) if k % 2 == 0],
        "a run, a gap, a run": block(chip, 1, words[:10]) + block(chip, 12, words[11:20]),
        "nothing": [],
    }


@pytest.mark.parametrize("case", list(legal_calls(_Names)))
def test_a_legal_fmi2_call_ends_as_value_by_value(case):
    fast, slow = chips(2)
    with fast, slow:
        pairs = legal_calls(fast)[case]
        assert assert_alike(fast, slow, pairs) == (0, [])
        last = {v: x for v, x in pairs}
        for k in range(WORDS):  # and memory.data holds what the call's last value of each said
            v = vr(fast, f"memory.data[{k + 1}]")
            assert fast.get(f"memory.data[{k + 1}]") == last.get(v, 0)


def refused_calls(chip):
    words = list(range(1000, 1000 + WORDS))
    n, a = vr(chip, "memory.count"), vr(chip, "memory.address")
    real = vr(chip, "cycleTime")
    output = vr(chip, "host.ack")
    return {
        "a bad value after a block": block(chip, 1, words) + [(n, 65)],
        "a bad value between two runs": block(chip, 1, words[:32])
        + [(vr(chip, "host.word[3]"), 70000)]
        + block(chip, 33, words[32:]),
        "a bad value before a block": [(a, -1)] + block(chip, 1, words),
        "an unknown value reference after a block": block(chip, 1, words) + [(99999, 1)],
        "the value reference after memory.data[64]": block(chip, 61, words[:4])
        + [(vr(chip, "memory.data[64]") + 1, 1)],
        "the value reference before memory.data[1]": [(vr(chip, "memory.data[1]") - 1, 1)] + block(chip, 1, words),
        "a Real's value reference in a run": block(chip, 1, words[:3]) + [(real, 1)] + block(chip, 4, words[3:]),
        "an output": block(chip, 1, words) + [(output, 1)],
        "a fixed parameter": block(chip, 1, words) + [(vr(chip, "memorySize"), SIZE)],
        "a block on an address out of the memory": block(chip, 1, words) + strobe(chip, SIZE - 10, WORDS, 1),
        "an address past the end": block(chip, 1, words) + strobe(chip, SIZE + 1, 0, 1),
    }


@pytest.mark.parametrize("case", list(refused_calls(_Names)))
def test_a_refused_fmi2_call_answers_as_value_by_value_and_changes_nothing(case):
    fast, slow = chips(2)
    with fast, slow:
        set_integer(fast, block(fast, 1, range(7, 7 + WORDS)))  # something for a refusal to keep
        set_integer(slow, block(slow, 1, range(7, 7 + WORDS)))
        before = snapshot(fast)
        status, messages = assert_alike(fast, slow, refused_calls(fast)[case])
        assert status == 3 and len(messages) == 1 and messages[0].message.startswith("fmi2SetInteger: ")
        assert snapshot(fast) == before


def test_calls_in_initialization_mode_end_alike():
    """In initialization mode memorySize is settable: a block beside a new memorySize (a new memory
    allocated by the check), and beside one out of range."""
    fast, slow = InitializationChip(2), InitializationChip(2)
    try:
        size = vr(fast, "memorySize")
        for pairs, expected in [
            ([(size, 0x800)] + block(fast, 1, range(WORDS)) + strobe(fast, 0x7C0, WORDS, 1), 0),
            (block(fast, 1, range(WORDS)) + [(size, 2**27)], 3),
            ([(size, 0)] + block(fast, 1, range(WORDS, 0, -1)), 3),
        ]:
            assert assert_alike(fast, slow, pairs)[0] == expected
    finally:
        fast.free()
        slow.free()


@pytest.mark.parametrize("seed", range(6))
def test_random_fmi2_calls_end_as_value_by_value(seed):
    """Random calls mixing runs of memory.data (any start, length, repeats) with every other Integer
    variable (inputs, outputs, a parameter, values in and out of range, unknown value references),
    and strobes that may leave the memory: status, messages and FMU state as value by value."""
    rng = np.random.default_rng(seed)
    fast, slow = chips(2)
    with fast, slow:
        integers = [v.valueReference for v in fast.variables.values() if v.type == "Integer"]
        first = vr(fast, "memory.data[1]")
        statuses = set()
        for _ in range(150):
            pairs = []
            for _ in range(rng.integers(0, 5)):
                kind = rng.integers(0, 4)
                if kind == 0:  # a run of memory.data
                    start = int(rng.integers(1, WORDS + 1))
                    length = int(rng.integers(1, WORDS - start + 2))
                    pairs += block(fast, start, rng.integers(-(2**31), 2**31, length))
                elif kind == 1:  # a port variable, in or out of range
                    name = ["memory.address", "memory.count", "memory.strobe"][rng.integers(0, 3)]
                    value = int(rng.choice([rng.integers(0, SIZE + 2), rng.integers(0, 66), -1, 2**26 + 1]))
                    pairs.append((vr(fast, name), value))
                elif kind == 2:  # any Integer variable
                    pairs.append((int(rng.choice(integers)), int(rng.integers(-70000, 70000))))
                else:  # near memory.data, or nothing
                    pairs.append((first + int(rng.integers(-3, WORDS + 3)), int(rng.integers(-(2**31), 2**31))))
            status, _ = assert_alike(fast, slow, pairs)
            statuses.add(status)
        assert statuses == {0, 3}  # both kinds of call were made


# ---- FMI 3: the memory.data array, always one block ----


def set3(chip, function, pairs, n_values=None):
    """One fmi3Set<function> of (value reference, values) pairs: its status and messages."""
    chip.messages.clear()
    ctype = {"UInt32": ctypes.c_uint32, "Int32": ctypes.c_int32}[function]
    values = [x for _, xs in pairs for x in xs]
    vrs = (ctypes.c_uint32 * max(len(pairs), 1))(*[v for v, _ in pairs])
    array = (ctype * max(len(values), 1))(*values)
    status = chip.fmu._functions["fmi3Set" + function](
        chip.fmu.component, vrs, len(pairs), array, len(values) if n_values is None else n_values
    )
    return status, [m.message for m in chip.messages]


def fmi2_messages(chip, pairs):
    _status, messages = set_integer(chip, pairs)
    return [m.message for m in messages]


@pytest.mark.parametrize("n", [1, 5, 63, 64])
def test_fmi3_blocks_write_what_fmi2_writes(n):
    """Strobes through the array (its tail 0 past count) and through FMI 2's scalars leave the same
    memory and port variables; the array set twice in one call: the second wins; the address first."""
    rng = np.random.default_rng(n)
    with pmdfmu.Chip(3, memorySize=SIZE) as three, pmdfmu.Chip(2, memorySize=SIZE) as two:
        data3, address = vr(three, "memory.data"), vr(three, "memory.address")
        for k in range(3):
            words = [int(w) for w in rng.integers(0, 2**32, WORDS)]
            words[n:] = [0] * (WORDS - n)
            other = [int(w) for w in rng.integers(0, 2**32, WORDS)]
            where = int(rng.integers(0, SIZE - n + 1))
            pairs = (
                [(data3, other), (data3, words), (address, [where])] if k == 0 else [(address, [where]), (data3, words)]
            )
            assert set3(three, "UInt32", pairs) == (0, [])
            assert set3(three, "Int32", [(vr(three, "memory.count"), [n]), (vr(three, "memory.strobe"), [k + 1])]) == (
                0,
                [],
            )
            signed = [w - 2**32 if w >> 31 else w for w in words]
            assert set_integer(two, block(two, 1, signed) + strobe(two, where, n, k + 1)) == (0, [])
            assert three.get("memory.data") == words
            assert [two.get(f"memory.data[{i + 1}]") & 0xFFFFFFFF for i in range(WORDS)] == words
            for chip in (three, two):
                chip.get("host.ack")
            for name in ("memory.address", "memory.count", "memory.strobe"):
                assert three.get(name) == two.get(name)
            m3 = np.frombuffer(snapshot(three)[-4 * SIZE :], dtype=np.uint32)
            m2 = np.frombuffer(snapshot(two)[-4 * SIZE :], dtype=np.uint32)
            assert np.array_equal(m3, m2) and list(m3[where : where + n]) == words[:n]


def test_fmi3_refused_calls_with_the_array_change_nothing_and_say_what_fmi2_says():
    with pmdfmu.Chip(3, memorySize=SIZE) as three, pmdfmu.Chip(2, memorySize=SIZE) as two:
        data3 = vr(three, "memory.data")
        words = list(range(500, 500 + WORDS))
        assert set3(three, "UInt32", [(data3, list(range(WORDS)))]) == (0, [])
        before = snapshot(three)
        a3, a2 = vr(three, "memory.address"), vr(two, "memory.address")
        for pairs3, pairs2 in [
            ([(data3, words), (a3, [2**26 + 1])], block(two, 1, words) + [(a2, 2**26 + 1)]),
            ([(a3, [2**26 + 1]), (data3, words)], [(a2, 2**26 + 1)] + block(two, 1, words)),
        ]:
            status, messages = set3(three, "UInt32", pairs3)
            assert status == 3
            assert messages == [m.replace("fmi2SetInteger", "fmi3SetUInt32") for m in fmi2_messages(two, pairs2)]
            assert snapshot(three) == before
        # a strobe on an address its block leaves the memory from: refused by the strobe's call
        assert set3(three, "UInt32", [(data3, words), (a3, [SIZE - 10])]) == (0, [])
        before = snapshot(three)
        status, messages = set3(
            three, "Int32", [(vr(three, "memory.count"), [WORDS]), (vr(three, "memory.strobe"), [1])]
        )
        assert status == 3 and messages == [
            f"fmi3SetInt32: memory.strobe 1: writing {WORDS} words at address "
            f"{SIZE - 10} leaves the {SIZE}-word memory: write refused, nothing set"
        ]
        assert snapshot(three) == before
        # the array by the wrong type, or short of values: refused before any value
        status, messages = set3(three, "Int32", [(data3, words)])
        assert status == 3 and messages == [
            f"fmi3SetInt32: value reference {data3} (memory.data) is a UInt32, not Int32"
        ]
        status, messages = set3(three, "UInt32", [(data3, words)], n_values=WORDS - 1)
        assert status == 3 and "nValues is 63 but the value references hold 64 values" in messages[0]
        assert snapshot(three) == before
        three.fmu.terminate()
        status, messages = set3(three, "UInt32", [(data3, words)])
        assert status == 3 and messages == ["fmi3SetUInt32: not allowed in terminated"]
        three.fmu.freeInstance()  # close() would terminate it again
        three.fmu = None


# ---- Chip.write_memory: every kind of array reaches the same strobes ----


@pytest.mark.parametrize("version", [2, 3])
def test_write_memory_takes_any_array_as_the_python_loop_does(version):
    """A read-only array (its address through numpy), a strided view (copied), int32, int64 and
    uint32 arrays, a list, an empty array: the same FMU state as stepwise.write_memory_stepwise."""
    rng = np.random.default_rng(9)
    words = rng.integers(0, 2**32, 300, dtype=np.uint64).astype(np.uint32)
    frozen = words.copy()
    frozen.flags.writeable = False
    native, python = chips(version)
    with native, python:
        for address, given in [
            (0, frozen),
            (7, words[::3]),
            (SIZE - 100, words[:100].view(np.int32)),
            (0x80, words.astype(np.int64)),
            (1, words[:70]),
            (SIZE, words[:0]),
            (3, [int(w) for w in words[:65]]),
        ]:
            native.write_memory(address, given)
            write_memory_stepwise(python, address, given)
            assert snapshot(native) == snapshot(python)
        assert native.messages == python.messages


@pytest.mark.parametrize("version", [2, 3])
def test_write_memory_refuses_any_address_its_words_leave_the_memory_from(version):
    with pmdfmu.Chip(version, memorySize=SIZE) as chip:
        before = snapshot(chip)
        for address, n in [(2**40, 1), (2**64 + 5, 0), (-(2**63), 1), (SIZE + 1, 0), (SIZE - 1, 2)]:
            with pytest.raises(
                ValueError, match=f"write_memory: {n} words at address {address} leave the {SIZE}-word memory"
            ):
                chip.write_memory(address, np.zeros(n, dtype=np.uint32))
            assert snapshot(chip) == before
