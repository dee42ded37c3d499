# SPDX-License-Identifier: BSD-2-Clause
"""The FMU's block path for FMI 3's host port arrays: fmi3SetUInt16 takes `host.word` and
fmi3GetUInt16 gives `host.reply` as one block each (pmd_set_host_words, pmd_get_host_reply in
instance.c) instead of element by element, since every FMI 3 host command sets the one whole and
reads the other whole. The words and replies are the ones FMI 2's scalars hold, every element of
the 64 (trailing zeros too); a call that also names a variable it may not set sets nothing and
names that variable, as the per-element path did."""

import pytest
from fmpy.fmi1 import FMICallException

import pmdfmu
from states import command, snapshot

WORDS = [0, 1, 0x7FFF, 0x8000, 0xFFFF] + [(k * 0x9E37) & 0xFFFF for k in range(59)]


def vr(chip, name):
    return chip.variables[name].valueReference


def test_fmi3_host_word_array_holds_the_words_fmi2s_elements_hold():
    with pmdfmu.Chip(2) as two, pmdfmu.Chip(3) as three:
        two.set("host.word", WORDS)
        three.fmu.setUInt16([vr(three, "host.word")], WORDS)
        assert list(three.fmu.getUInt16([vr(three, "host.word")], nValues=64)) == WORDS
        assert two.get("host.word") == WORDS


def test_fmi3_host_reply_array_reads_every_element_fmi2_reads():
    batch = command("GetPosition") + command("GetTime") + command("GetVersion") + command("GetEventStatus", axis=1)
    replies = []
    for version in (2, 3):
        with pmdfmu.Chip(version) as chip:
            chip.axis(0).SetPosition(-123456)
            chip.run(7)
            chip.batch(batch)
            replies.append(list(chip.get("host.reply")))
    assert replies[0] == replies[1]
    assert replies[0][:2] == [0xFFFE, 0x1DC0] and replies[0][7:] == [0] * 57


@pytest.mark.parametrize("output", ["host.reply", "io.output"])
def test_a_call_setting_host_word_and_an_output_sets_nothing_and_names_the_output(output):
    with pmdfmu.Chip(3) as chip:
        before = snapshot(chip)
        chip.messages.clear()
        n = len(chip.get(output))
        with pytest.raises(FMICallException):
            chip.fmu.setUInt16([vr(chip, "host.word"), vr(chip, output)], WORDS + [1] * n)
        assert snapshot(chip) == before
        assert any(f"({output}[1]) is an output and cannot be set" in m.message for m in chip.messages)
