# SPDX-License-Identifier: BSD-2-Clause
"""C-Motion's calls as the host sends them, whatever carries them (the FMU in-process, chip.py; a
serial line, line.py): the command table, the words of a call and of its reply, the register
fields and constants, the axis handle whose methods are the calls."""

from __future__ import annotations

import inspect
import textwrap
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import tables
from .fixed import integer, to_word
from .tables import Command, Field

PACKAGE = Path(__file__).resolve().parent
REPO = PACKAGE.parent.parent


def tables_dir() -> Path:
    """The interface tables: installed with the package, or the source tree's."""
    installed = PACKAGE / "tables"
    return installed if installed.is_dir() else REPO / "modelDescription"


COMMANDS: Dict[str, Command] = {c.name: c for c in tables.read_commands(tables_dir() / "commands.csv")}
_CONSTANT_ROWS = tables.read_constants(tables_dir() / "constants.csv")
# every C-Motion constant of constants.csv by name (pmdfmu exports them as module attributes)
CONSTANTS: Dict[str, int] = {name: value for _group, name, value in _CONSTANT_ROWS}
ERROR_NAMES: Dict[int, str] = {v: n for g, n, v in _CONSTANT_ROWS if g == "Error"}
# PMDAxis1Mask .. PMDAxis4Mask: axis n's bit in MultiUpdate's mask, GetInterruptAxis and script.axes
AXIS_MASKS: Tuple[int, ...] = tuple(v for g, _n, v in _CONSTANT_ROWS if g == "AxisMask")
# the register fields: every *Mask constant as a field, by its name without "Mask" (QEMU's FIELD())
FIELDS: Dict[str, tables.BitField] = tables.read_fields(tables_dir() / "constants.csv")


def field_ex(value, field: str):
    """The value of a register field in a word (QEMU's FIELD_EX, the C side's
    PMD_FIELD_EX): field_ex(status, "PMDActivityProfileSegment") is the profile
    segment number. value may be a numpy array of words (a recorded column)."""
    return FIELDS[field].ex(value)


def field_dp(value: int, field: str, x: int) -> int:
    """value with a register field replaced by x (QEMU's FIELD_DP, PMD_FIELD_DP)."""
    return FIELDS[field].dp(value, x)


def instruction_word(opcode: int, axis: int) -> int:
    """A host instruction word: the opcode and the axis field (pmd-reference 2.1)."""
    return field_dp(field_dp(0, "PMDInstructionOpcode", opcode), "PMDInstructionAxis", axis)


# the commands by opcode: a timed batch is split into its commands as the FMU's dispatcher splits it
OPCODES: Dict[int, Command] = {c.opcode: c for c in COMMANDS.values()}
# the host port's batch: host.word[1..BATCH_WORDS] (variables.csv), the C side's PMD_BATCH_WORDS
BATCH_WORDS = sum(1 for v in tables.read_variables(tables_dir() / "variables.csv") if v.family == "host_word")


class PMDError(Exception):
    """A command the chip refused, with its host I/O error code (pmd-reference 2.4)."""

    def __init__(self, code: int, command: str = ""):
        self.code = code
        self.command = command
        super().__init__(f"{command}: host I/O error 0x{code:02X} ({ERROR_NAMES.get(code, 'unknown')})")


def sent_words(instruction, data: Sequence) -> Tuple[List[int], Optional[Command]]:
    """chip.send's words checked, and the command its instruction word names (None: an opcode no command has,
    sent as it is for the chip to refuse): each word 0 .. 0xFFFF, or -32768 .. -1 for its two's complement, and
    as many data words as the command takes. ValueError naming the word otherwise; nothing is sent."""
    try:
        words = [
            to_word(w, 16, "send: " + (f"data word {i}" if i else "the instruction word"))
            for i, w in enumerate((instruction, *data))
        ]
    except ValueError as e:
        raise ValueError(f"{e}; nothing was sent") from None
    command = OPCODES.get(FIELDS["PMDInstructionOpcode"].ex(words[0]))
    if command is not None and len(data) != command.arg_words:
        raise ValueError(
            f"send: {command.name} (opcode 0x{command.opcode:02X}) takes {command.arg_words} data words, "
            f"not {len(data)}; nothing was sent"
        )
    if len(words) > BATCH_WORDS:
        raise ValueError(f"send: a command holds at most {BATCH_WORDS} words, not {len(words)}; nothing was sent")
    return words, command


# chip.send's native path: the instruction word of a command on axis 0..3 -> (its data words, the native
# call's shape (words | reply words << 8), the result's high bits when it succeeds (no error, its reply
# words: host_port.h), the command); any other word goes the checked path (sent_words)
SEND_SHAPES: Dict[int, Tuple[int, int, int, Command]] = {
    instruction_word(c.opcode, a): (c.arg_words, (1 + c.arg_words) | c.reply_words << 8, c.reply_words << 16, c)
    for c in COMMANDS.values()
    if c.arg_words <= 3
    for a in range(4)
}


def sent_name(command: Optional[Command], instruction: int) -> str:
    """What a refused send names: its command, or the instruction word that names none."""
    return command.name if command is not None else f"instruction word 0x{instruction:04X}"


def encode(command: Command, values: Sequence[int]) -> List[int]:
    """The data words of a command, as C-Motion packs them.

    An argument is an integer (Python or numpy); a float is refused, even 2.0: a
    16.16 or 0.32 argument takes the word (pmdfmu.fixed_16_16(2.75)), a count takes
    whole counts. A 16- or 32-bit argument takes -2^(w-1) .. 2^w-1, its signed or its
    unsigned reading of the same bits (SetVelocity(-1) and SetVelocity(0xFFFFFFFF)
    send the same words); a packed field (a register field of constants.csv) takes
    0 .. 2^width-1.
    Anything else raises ValueError naming the command, the argument and the range:
    nothing is masked."""
    if len(values) != len(command.args):
        names = ", ".join(f.name for f in command.args)
        raise TypeError(f"{command.name}({names}) takes {len(command.args)} arguments, {len(values)} given")
    words = [0] * command.arg_words
    for f, v in zip(command.args, values):
        what = f"{command.name}: {f.name}"
        if f.fixed and not isinstance(v, (int, np.integer)):
            raise ValueError(
                f"{what} = {v!r} is not an integer: the argument is the {f.fixed} word, "
                f"e.g. pmdfmu.fixed_{f.fixed.replace('.', '_')}({v!r})"
            )
        if f.kind == "bits":
            v = integer(v, what)
            if not 0 <= v < (1 << f.width):
                raise ValueError(f"{what} = {v} does not fit its {f.width}-bit field: 0 .. {(1 << f.width) - 1}")
            words[f.word] |= v << f.shift
        else:
            v = to_word(v, f.width, what)
            if f.width == 32:
                words[f.word], words[f.word + 1] = v >> 16, v & 0xFFFF
            else:
                words[f.word] = v
    return words


def decode(fields: Tuple[Field, ...], words: Sequence[int]) -> List[int]:
    out = []
    for f in fields:
        if f.kind == "bits":
            out.append((words[f.word] >> f.shift) & ((1 << f.width) - 1))
            continue
        v = (words[f.word] << 16) | words[f.word + 1] if f.width == 32 else words[f.word]
        if f.signed and v >> (f.width - 1):
            v -= 1 << f.width
        out.append(v)
    return out


def axis_number(number) -> int:
    """An axis number 0..3 (PMDAxis1..PMDAxis4); anything else raises ValueError."""
    n = integer(number, "axis")
    if not 0 <= n < 4:
        raise ValueError(f"axis {n}: the chip has axes 0..3 (PMDAxis1..PMDAxis4)")
    return n


class Axis:
    """An axis handle: C-Motion's PMDAxisHandle, made by chip.axis(n).

    Its methods are the C-Motion calls of modelDescription/commands.csv without
    the PMD prefix and the handle, with C-Motion's arguments in C-Motion's order:
    PMDSetBufferStart(&hAxis1, 2, 0x200) is ax.SetBufferStart(2, 0x200).
    help(ax.SetVelocity) gives a call's argument formats and what it returns."""

    def __init__(self, chip, number: int):
        self.chip = chip  # a Chip (chip.py) or a LineChip (line.py): anything with command()
        self.number = axis_number(number)

    def __getattr__(self, name: str):
        # only for names that are not attributes: every command is a method of the class
        raise AttributeError(f"{name} is not a command of this chip (see pmdfmu info)")

    def __repr__(self):
        return f"<PMDAxis{self.number + 1}>"


def _bits_doc(f: Field, word: str) -> str:
    return (
        f"packed field {f.register_field}: bits {f.shift}..{f.shift + f.width - 1} of {word} {f.word + 1}, "
        f"0 .. {(1 << f.width) - 1}"
    )


def _field_doc(f: Field) -> str:
    """What an argument is, as C-Motion's manual gives it: the word it occupies,
    its format and the integers it takes (encode's checks)."""
    if f.kind == "bits":
        return _bits_doc(f, "word")
    words = "two words, high word first" if f.width == 32 else "one word"
    if f.fixed:
        scale = 16 if f.fixed == "16.16" else 32
        return (
            f"{f.fixed} fixed point ({'signed' if f.signed else 'unsigned'} 32-bit word = value * 2^{scale}, "
            f"{words}): pass the word, e.g. pmdfmu.fixed_{f.fixed.replace('.', '_')}(x); "
            f"-2^31 .. 2^32-1"
        )
    reading = "signed" if f.signed else "unsigned"
    lo, hi = -(1 << (f.width - 1)), (1 << f.width) - 1
    return f"{f.width}-bit {reading} integer ({words}); {lo} .. {hi}, either reading of the same bits"


def _reply_doc(command: Command, f: Field) -> str:
    """What a reply value is (decode's reading of it)."""
    if f.kind == "bits":
        return _bits_doc(f, "reply word")
    lo, hi = (-(1 << (f.width - 1)), (1 << (f.width - 1)) - 1) if f.signed else (0, (1 << f.width) - 1)
    text = f"{f.width}-bit {'signed' if f.signed else 'unsigned'} integer, {lo} .. {hi}"
    # a Get's value is the word its Set takes: the same format (GetVelocity reads SetVelocity's 16.16 word)
    setter = COMMANDS.get("Set" + command.name[3:]) if command.name.startswith("Get") else None
    fixed = next((a.fixed for a in setter.args if a.name == f.name and a.fixed), "") if setter else ""
    if fixed:
        text += f': the {fixed} word {setter.name} takes (pmdfmu.from_fixed(word, "{fixed}"))'
    return text


def _item(name: str, text: str) -> str:
    return textwrap.fill(f"{name}: {text}", 96, initial_indent="    ", subsequent_indent="        ")


def _method_doc(command: Command) -> str:
    lines = [
        command.summary + ".",
        "",
        f"C-Motion PMD{command.name}, opcode 0x{command.opcode:02X}; "
        + (
            "chip-wide: sent with axis field 0, whatever the handle's axis."
            if command.scope == "chip"
            else "acts on this handle's axis."
        ),
    ]
    if command.args:
        lines += ["", "Arguments (integers; nothing is rounded or masked):"]
        lines += [_item(f.name, _field_doc(f)) for f in command.args]
    lines += [""]
    if not command.reply:
        lines += ["Returns None."]
    elif len(command.reply) == 1:
        lines += [textwrap.fill(f"Returns {command.reply[0].name}: {_reply_doc(command, command.reply[0])}.", 96)]
    else:
        lines += [f"Returns the tuple ({', '.join(f.name for f in command.reply)}):"]
        lines += [_item(f.name, _reply_doc(command, f)) for f in command.reply]
    lines += [
        "",
        "Raises PMDError (.code: the host I/O error) if the chip refuses the call; TypeError for a",
        "wrong number of arguments; ValueError for a value that is not an integer or does not fit.",
    ]
    return "\n".join(lines)


def _slow_method(command: Command, signature: inspect.Signature, public: inspect.Signature):
    """A call the native path leaves (keywords, a wrong number of arguments, an argument not a plain int
    in range, a chip without it): Chip.command's checks, encoding and errors."""

    def slow(self, *args, **kwargs):
        try:
            bound = signature.bind(self, *args, **kwargs)
        except TypeError as e:
            raise TypeError(f"{command.name}{public}: {e}") from None
        return self.chip.command(self.number, command, bound.args[1:])

    return slow


def _fast_source(command: Command) -> str:
    """The source of an Axis method's native path (host_port.py): the arguments checked and packed into
    one 64-bit word as encode() packs them (the instruction word in the low 16 bits), one native call,
    the reply decoded from the result word as decode() reads it. Whatever it does not take goes to the
    slow path, which raises as Chip.command does."""
    # the arguments by name (a missing one _MISSING), the rest caught for the slow path's messages: a call with
    # positional arguments past the named ones gave them all positionally, else the named ones go by name
    names = [f.name for f in command.args]
    given = "".join(f" or {n} is _MISSING" for n in names)
    lines = [
        f"def {command.name}(self{''.join(f', {n}=_MISSING' for n in names)}, *rest, **keywords):",
        "    chip = self.chip",
        "    port = chip._fast",
        f"    if port is None or rest or keywords or chip._recording{given}:",
        f"        if rest:\n            return _slow_{command.name}(self, {''.join(f'{n}, ' for n in names)}*rest, **keywords)",
        f"        named = {{{', '.join(f'{n!r}: {n}' for n in names)}}}",
        f"        return _slow_{command.name}(self, **{{k: v for k, v in named.items() if v is not _MISSING}}, **keywords)",
        f"    words = _INSTRUCTION_{command.name}[self.number]",
    ]
    for f in command.args:
        place = 16 * (1 + f.word)
        if f.kind == "bits":
            lo, hi = 0, (1 << f.width) - 1
            pack = f"{f.name} << {place + f.shift}"
        elif f.width == 32:
            lo, hi = -(1 << 31), (1 << 32) - 1
            pack = f"((({f.name} & 0xFFFFFFFF) >> 16) << {place}) | (({f.name} & 0xFFFF) << {place + 16})"
        else:
            lo, hi = -(1 << (f.width - 1)), (1 << f.width) - 1
            pack = f"(({f.name} & 0xFFFF) << {place})"
        lines += [
            f"    if type({f.name}) is not int or not {lo} <= {f.name} <= {hi}:",
            f"        return _slow_{command.name}(self, {', '.join(names)})",
            f"    words |= {pack}",
        ]
    expect = command.reply_words
    lines += [
        "    logged = len(chip.messages)",
        f"    r = _COMMAND(port, {(1 + command.arg_words) | expect << 8}, words, words >> 32)",
        f"    if r >> 32 != {expect << 16}:",
        f"        return chip._fast_trouble(r, _COMMANDS[{command.name!r}], logged)",
    ]
    values = []
    for f in command.reply:
        if expect > 2:
            values.append(f"_decode_one(_COMMANDS[{command.name!r}].reply[{len(values)}], port.out)")
            continue
        if f.kind == "bits":
            word = "(r >> 16)" if f.word == 0 else "r"
            values.append(f"(({word} >> {f.shift}) & {(1 << f.width) - 1})")
            continue
        v = "(r & 0xFFFFFFFF)" if f.width == 32 else "((r >> 16) & 0xFFFF)" if f.word == 0 else "(r & 0xFFFF)"
        if f.signed:
            v = f"(({v} ^ {1 << (f.width - 1)}) - {1 << (f.width - 1)})"
        values.append(v)
    if not values:
        lines.append("    return None")
    elif len(values) == 1:
        lines.append(f"    return {values[0]}")
    else:
        lines.append(f"    return ({', '.join(values)})")
    return "\n".join(lines) + "\n"


_MISSING = object()  # an Axis method's argument not given (_fast_source)


def _decode_one(f: Field, words) -> int:
    return decode((f,), list(words))[0]


# the generated Axis methods' globals, shared: each command's slow path and instruction words by name,
# and _COMMAND, the native call, set when the first Chip makes its host port (Chip.__init__, chip.py):
# importing pmdfmu loads no library, and no method reaches _COMMAND before a Chip has a port (chip._fast);
# a chip over a line (line.py) has none
_FAST_GLOBALS: dict = {"_MISSING": _MISSING, "_decode_one": _decode_one, "_COMMANDS": COMMANDS, "_COMMAND": None}


def _c_motion_method(command: Command):
    """The Axis method of one command: a real function with the command's
    signature, name and docstring (inspect, help(), dir() and tab completion
    see it as written by hand), through the native host port (_fast_source)
    where the chip has one."""
    parameters = [inspect.Parameter(f.name, inspect.Parameter.POSITIONAL_OR_KEYWORD) for f in command.args]
    public = inspect.Signature(parameters)
    signature = inspect.Signature([inspect.Parameter("self", inspect.Parameter.POSITIONAL_OR_KEYWORD)] + parameters)
    scope = _FAST_GLOBALS
    scope[f"_slow_{command.name}"] = _slow_method(command, signature, public)
    scope[f"_INSTRUCTION_{command.name}"] = tuple(
        instruction_word(command.opcode, 0 if command.scope == "chip" else a) for a in range(4)
    )
    exec(compile(_fast_source(command), f"<pmdfmu Axis.{command.name}>", "exec"), scope)
    method = scope.pop(command.name)

    method.__name__ = command.name
    method.__qualname__ = f"Axis.{command.name}"
    method.__module__ = __name__
    method.__doc__ = _method_doc(command)
    method.__signature__ = signature
    return method


for _command in COMMANDS.values():
    if hasattr(Axis, _command.name):
        raise ValueError(f"command {_command.name} clashes with an attribute of Axis")
    setattr(Axis, _command.name, _c_motion_method(_command))
del _command
