# SPDX-License-Identifier: BSD-2-Clause
"""pmdfmu pack: a copy of the FMU that runs a script profile with no parameter set.

The copy carries the script and every segment table it loads under
resources/profile/, in their relative layout, and the `script` parameter starts
at the script's path there (docs/scripts.md): modelDescription.xml's start
value says so, and resources/script.start holds the same value for the binary,
which reads it at instantiation (fmu_src/script/script.h, PMD_SCRIPT_START), so
an importer that sets no start values runs the profile too.

The copy is a model of its own, so that two packed profiles in one system are
told apart: its `modelName` and `description` name the profile, and its GUID /
instantiation token is the base FMU's, '+', and a fingerprint of its contents
(the same inputs give the same token). resources/instantiation.token holds that
token for the binary, which accepts it beside its own
(fmu_src/fmi_common/token.h); documentation/index.html is written again from
the new model description. The modelIdentifier, the variables and every other
file are the base FMU's, byte for byte.

Which tables a script loads is the FMU's answer, not a second parser's: pack
compiles the script in the FMU and reads the files it names in its log.
"""

from __future__ import annotations

import hashlib
import os
import re
import tempfile
import uuid
import xml.etree.ElementTree as ET
import xml.parsers.expat
import zipfile
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path, PurePosixPath
from typing import Dict, Iterator, List, Optional, Tuple, Union

from .files import replaced, resolved, shown_path
from .chip import Chip, FMUError, default_fmu
from .documentation import documentation_html

PROFILE = "profile"  # resources/profile/: the script and its tables
START_FILE = "script.start"  # resources/script.start: PMD_SCRIPT_START in fmu_src/script/script.h
TOKEN_FILE = "instantiation.token"  # resources/instantiation.token: PMD_TOKEN_FILE in fmu_src/fmi_common/token.h
MODEL_DESCRIPTION = "modelDescription.xml"
DOCUMENTATION = "documentation/index.html"  # written from the model description (documentation.py)

# what the FMU logs (category "buffers") at the end of initialization about the files it read (instance.c)
_SCRIPT_READ = re.compile(r"ExitInitializationMode: script read from (.*)$")
_TABLE_READ = re.compile(r"ExitInitializationMode: .*:(\d+): segment table \"([^\"]*)\" read from (.*)$")


class PackError(ValueError):
    """The script cannot be packed (a table named by an absolute path, a packed base FMU...)."""


@dataclass
class Packed:
    """What pack wrote: the FMU, the `script` start value, the files under resources/ and its identity."""

    fmu: Path
    start: str
    files: List[str]
    model_name: str = ""
    token: str = ""


@dataclass
class _Read:
    script: Path
    tables: List[Tuple[int, str, Path]]  # (line, name as the script gives it, file read)
    state: bytes  # the FMU state right after initialization
    axes: int
    last_cycle: float


def _compile(fmi_version: int, fmu: Path, script: Optional[Path]) -> Tuple[_Read, Path]:
    """Initializes the FMU (with the script, or with its own start value) and reads what it compiled;
    also returns the folder the FMU was unpacked in, as the FMU saw it, while it existed."""
    parameters = {"script": script} if script is not None else {}
    with Chip(fmi_version, fmu, log_categories=["buffers"], **parameters) as chip:
        read_from, tables = None, []
        for m in chip.messages:
            if found := _SCRIPT_READ.search(m.message):
                read_from = Path(found.group(1))
            elif found := _TABLE_READ.search(m.message):
                tables.append((int(found.group(1)), found.group(2), Path(found.group(3))))
        if read_from is None:
            raise PackError(f"{fmu}: the FMU compiled no script file (script = {chip.get('script')!r})")
        read = _Read(read_from, tables, chip.get_state(), chip.get("script.axes"), chip.get("script.lastCycle"))
        return read, Path(chip._unzipdir)


def tables_loaded(script: Path, fmi_version: int = 2, fmu: Optional[Path] = None) -> List[Path]:
    """The files of the segment tables the script loads, as the FMU read them (pack's compile); none for a
    script the FMU refuses, whose run then says why."""
    try:
        read, _ = _compile(fmi_version, fmu, script)
    except (FMUError, PackError):
        return []
    return [path for _, _, path in read.tables]


def _escape_attribute(value: str) -> str:
    """value as an XML attribute between double quotes; line feeds and tabs as references,
    which attribute-value normalization keeps."""
    if any(ord(c) < 0x20 and c not in "\t\n\r" for c in value):
        raise PackError(f"{value!r}: a control character XML 1.0 cannot carry")
    for plain, escaped in (
        ("&", "&amp;"),
        ("<", "&lt;"),
        (">", "&gt;"),
        ('"', "&quot;"),
        ("\n", "&#10;"),
        ("\r", "&#13;"),
        ("\t", "&#9;"),
    ):
        value = value.replace(plain, escaped)
    return value


def _start_tag(xml_bytes: bytes) -> Tuple[int, str, str]:
    """Where the element holding the `script` start value begins (byte offset), its tag and the
    attribute: FMI 2 <ScalarVariable name="script"><String start=...>, FMI 3 <String name="script">
    <Start value=...>. Found by an XML parser, not by a pattern."""
    parser = xml.parsers.expat.ParserCreate()
    stack: List[Tuple[str, dict]] = []
    found: List[Tuple[int, str, str]] = []

    def start(tag, attributes):
        parent = stack[-1] if stack else ("", {})
        if tag == "String" and parent[0] == "ScalarVariable" and parent[1].get("name") == "script":
            found.append((parser.CurrentByteIndex, tag, "start"))
        elif tag == "Start" and parent[0] == "String" and parent[1].get("name") == "script":
            found.append((parser.CurrentByteIndex, tag, "value"))
        stack.append((tag, attributes))

    parser.StartElementHandler = start
    parser.EndElementHandler = lambda tag: stack.pop()
    parser.Parse(xml_bytes, True)
    if len(found) != 1:
        raise PackError(f"{MODEL_DESCRIPTION}: {len(found)} start elements of the script variable, not 1")
    return found[0]


_ATTRIBUTE = r"""\s+([\w:.-]+)\s*=\s*("[^"]*"|'[^']*')"""


def _set_attributes(xml_bytes: bytes, offset: int, tag: str, values: Dict[str, str]) -> bytes:
    """xml_bytes with the attributes of the <tag> element that begins at byte offset set to values (replaced
    in place, or appended), every other byte as it was."""
    text = xml_bytes.decode("utf-8")
    at = len(xml_bytes[:offset].decode("utf-8"))
    element = re.compile(rf"<{tag}((?:{_ATTRIBUTE})*)\s*/?>").match(text, at)
    if not element:
        raise PackError(f"{MODEL_DESCRIPTION}: cannot read the <{tag}> element at byte {offset}")
    attributes = element.group(1)
    for name, value in values.items():
        new_attribute = f'{name}="{_escape_attribute(value)}"'
        existing = [m for m in re.finditer(_ATTRIBUTE, attributes) if m.group(1) == name]
        if existing:
            m = existing[0]
            attributes = (
                attributes[: m.start()] + m.group(0)[: m.start(1) - m.start()] + new_attribute + attributes[m.end() :]
            )
        else:
            attributes += " " + new_attribute
    return (text[: element.start(1)] + attributes + text[element.end(1) :]).encode("utf-8")


def set_script_start(xml_bytes: bytes, value: str) -> bytes:
    """modelDescription.xml (FMI 2 or 3) with the `script` variable's start value set to value,
    every other byte as it was; checked by parsing both and comparing them element by element."""
    offset, tag, name = _start_tag(xml_bytes)
    result = _set_attributes(xml_bytes, offset, tag, {name: value})
    _check_only_changed(xml_bytes, result, lambda e: e.tag == tag and e.get(name) == value, {name})
    return result


def set_identity(xml_bytes: bytes, values: Dict[str, str]) -> bytes:
    """modelDescription.xml with the root element's attributes (modelName, description, guid or
    instantiationToken) set to values, every other byte as it was; checked as set_script_start is."""
    parser = xml.parsers.expat.ParserCreate()
    roots: List[int] = []
    parser.StartElementHandler = lambda tag, attributes: roots.append(parser.CurrentByteIndex) if not roots else None
    parser.Parse(xml_bytes, True)
    result = _set_attributes(xml_bytes, roots[0], "fmiModelDescription", values)
    _check_only_changed(xml_bytes, result, lambda e: e.tag == "fmiModelDescription", set(values))
    return result


def _check_only_changed(before: bytes, after: bytes, is_edited, names) -> None:
    """after is before but for the attributes names of one element, which is_edited(element) recognizes."""
    old, new = list(ET.fromstring(before).iter()), list(ET.fromstring(after).iter())
    if len(old) != len(new):
        raise PackError(f"{MODEL_DESCRIPTION}: the edit changed the elements")
    changed = 0
    for a, b in zip(old, new):
        others = [{k: v for k, v in e.attrib.items() if k not in names} for e in (a, b)]
        if (a.tag, a.text, a.tail) != (b.tag, b.text, b.tail) or (
            a.attrib != b.attrib and (not is_edited(b) or others[0] != others[1])
        ):
            raise PackError(f"{MODEL_DESCRIPTION}: the edit changed <{a.tag}> {a.attrib}")
        changed += a.attrib != b.attrib
    if changed > 1:
        raise PackError(f"{MODEL_DESCRIPTION}: the edit changed {changed} elements")


def profile_name(script: Path) -> str:
    """The name a packed FMU gives its profile by default: the script's file name without its extension, as
    a name of letters, digits and '_' (another character as '_')."""
    name = re.sub(r"\W", "_", script.stem, flags=re.ASCII)
    return name if re.match(r"[A-Za-z_]", name) else "_" + name


def packed_token(base_token: str, members: Dict[str, bytes]) -> str:
    """The packed FMU's GUID / instantiation token: the base FMU's (which names the variables and so the
    binary, fmu_src/fmi_common/token.h), '+', and a fingerprint of the packed FMU's files, members (not the
    token's file, nor documentation/index.html, which is written from the model description; the model
    description counts with the base token in it), as a braced UUID."""
    digest = hashlib.sha256()
    for name in sorted(members):
        digest.update(b"%d:%s%d:" % (len(name.encode()), name.encode(), len(members[name])) + members[name])
    return f"{base_token}+{{{uuid.UUID(bytes=digest.digest()[:16])}}}"


def _layout(read: _Read, unzipdir: Path) -> Tuple[Path, List[Tuple[Path, str]]]:
    """The folder the packed files are relative to, and each file to pack with its path under it."""
    folder = read.script.parent
    files = [read.script]
    inside = unzipdir / "resources"
    for line, name, path in read.tables:
        if os.path.isabs(name):
            raise PackError(
                f"{read.script}:{line}: the table {name} is named by an absolute path: a packed FMU "
                "must find it inside itself; name it relative to the script's folder"
            )
        if Path(os.path.normpath(path)).is_relative_to(inside):
            continue  # in the base FMU's resources folder: packed already
        if (file := Path(os.path.normpath(path))) not in files:  # a table loaded twice is packed once
            files.append(file)
    root = Path(os.path.commonpath([folder] + [f.parent for f in files]))
    return root, [(f, PurePosixPath(*f.relative_to(root).parts).as_posix()) for f in files]


def _refuse_overwriting(out: Path, inputs: List[Tuple[Path, str]]) -> None:
    """out must be none of the files pack reads (by identity: a symlink or a hard link to one is one)."""
    if not os.path.lexists(out):
        return
    if out.is_dir():
        raise PackError(f"{out} is a folder: --out names the FMU file to write")
    for path, what in inputs:
        try:
            same = os.path.samefile(out, path)
        except OSError:  # a dangling link: replacing it overwrites nothing
            continue
        if same:
            raise PackError(f"{out}: the packed FMU must not overwrite {what}, {shown_path(path)}")


@contextmanager
def _by_a_name_the_fmu_reads_as_a_path(script: Path) -> Iterator[Path]:
    """script as a path the FMU can be given: a `script` value holding a line feed is the script's text
    (docs/scripts.md), so a script whose path holds one is compiled through a temporary folder that
    mirrors the script's folder by symbolic links, the script itself under its name with each line
    feed as "_". A table beside the script or below its folder is found as from the script itself; one
    outside it (`../t.csv`) would be looked for beside the mirror, so pack refuses it (_refuse_outside)."""
    if "\n" not in str(script):
        yield script
        return
    folder = script.parent
    name = script.name.replace("\n", "_")
    if name != script.name and (folder / name).exists():
        raise PackError(f"{shown_path(script)}: its name holds a line feed and {name} is beside it: rename the script")
    with tempfile.TemporaryDirectory(prefix="pmdfmu-pack-") as mirror:
        for entry in os.listdir(folder):
            if "\n" not in entry and entry != name:
                os.symlink(folder / entry, Path(mirror, entry))
        os.symlink(script, Path(mirror, name))
        yield Path(mirror, name)


def _refuse_outside(script: Path, tables) -> None:
    """A script compiled through the mirror of its folder: every table it loads must be the folder's (a
    relative name reaching out of it would have been looked for beside the mirror, in a shared folder)."""
    folder = resolved(script.parent)
    for line, name, path in tables:
        table = resolved(path)
        if table != folder and folder not in table.parents:
            raise PackError(
                f"{shown_path(script)}:{line}: the table {name} lies outside the script's folder, which "
                "pack cannot reach for a script whose name holds a line feed: rename the script"
            )


def pack(
    script: Union[str, Path],
    out: Union[str, Path],
    fmi_version: int = 2,
    fmu: Union[str, Path, None] = None,
    name: Optional[str] = None,
) -> Packed:
    """Writes out: a copy of fmu (default: the built FMU of fmi_version) with script and every
    table it loads under resources/profile/ and `script` starting at it, a model of its own named
    after the profile (name, default: profile_name(script)); then initializes the copy without
    parameters and checks that it compiled the same script from inside itself.
    out is never one of these inputs; it is written whole or not at all (files.replaced)."""
    script, out = resolved(script), Path(out)
    name = profile_name(script) if name is None else name
    if not re.fullmatch(r"[A-Za-z_]\w*", name, flags=re.ASCII):
        raise PackError(f"{name!r}: a profile's name is letters, digits and '_', not beginning with a digit")
    base = Path(fmu) if fmu else default_fmu(fmi_version)
    _refuse_overwriting(out, [(base, "the FMU it copies"), (script, "the script")])
    with zipfile.ZipFile(base) as z:
        names = z.namelist()
    if f"resources/{START_FILE}" in names or f"resources/{TOKEN_FILE}" in names:
        raise PackError(f"{base} is a packed FMU already: pack onto the built FMU")
    with _by_a_name_the_fmu_reads_as_a_path(script) as given:
        try:
            read, unzipdir = _compile(fmi_version, base, given)
        except FMUError as e:
            raise PackError(
                f"{shown_path(script)}: the FMU refuses the script: {str(e).replace(str(given), shown_path(script))}"
            ) from None
        if given != script:
            _refuse_outside(script, read.tables)
        _refuse_overwriting(
            out, [(path, f"the table {table} the script loads (line {line})") for line, table, path in read.tables]
        )
        root, files = _layout(read, unzipdir)
        start = f"{PROFILE}/{files[0][1]}"

        with zipfile.ZipFile(base) as zin:
            infos = zin.infolist()
            members = {info.filename: zin.read(info) for info in infos}
        md = members[MODEL_DESCRIPTION]
        attributes = ET.fromstring(md).attrib
        token_attribute = "guid" if fmi_version == 2 else "instantiationToken"
        model_name = f"{attributes['modelName']}.{name}"
        md = set_identity(
            set_script_start(md, start),
            {
                "modelName": model_name,
                "description": f"{attributes.get('description', attributes['modelName'])}; runs the profile "
                f"{name}, packed in resources/{start}",
            },
        )
        added = {f"resources/{PROFILE}/{relative}": path.read_bytes() for path, relative in files}
        added[f"resources/{START_FILE}"] = start.encode("utf-8")
        contents = {**members, MODEL_DESCRIPTION: md, **added}
        contents.pop(DOCUMENTATION, None)  # the page says the token: it is the description's, written again
        token = packed_token(attributes[token_attribute], contents)
        members[MODEL_DESCRIPTION] = set_identity(md, {token_attribute: token})
        if DOCUMENTATION in members:
            members[DOCUMENTATION] = documentation_html(members[MODEL_DESCRIPTION].decode("utf-8")).encode("utf-8")
        added[f"resources/{TOKEN_FILE}"] = token.encode("ascii")

        out.parent.mkdir(parents=True, exist_ok=True)
        with replaced(out) as partial:
            with _archive(partial) as zout:
                for info in infos:
                    zout.writestr(info, members[info.filename])
                for member, data in added.items():
                    zout.writestr(
                        zipfile.ZipInfo(member, date_time=(1980, 1, 1, 0, 0, 0)),
                        data,
                        compress_type=zipfile.ZIP_DEFLATED,
                    )
            partial.flush()
            _verify(Path(partial.name), fmi_version, start, read, token)
    return Packed(out, start, list(added), model_name, token)


@contextmanager
def _archive(partial) -> Iterator[zipfile.ZipFile]:
    """The packed FMU's zip, written into the partial file. On an exception the partial file is removed
    (files.replaced), so the archive is let go of, not closed: after a Ctrl-C inside a member's write,
    closing it raises ("Can't close the ZIP file while there is an open writing handle", then "seek of
    closed file" from its finalizer), which must not replace the interrupt."""
    archive = zipfile.ZipFile(partial, "w")
    try:
        yield archive
    except BaseException:
        archive.fp = None  # closed as a file only: nor will the archive's finalizer try its end record
        raise
    archive.close()


def _verify(packed: Path, fmi_version: int, start: str, original: _Read, token: str) -> None:
    """The packed FMU, initialized with no parameter: its script is the start value, read from
    inside it, its tables too, and it compiled what the script by path compiles (same FMU state);
    the binary took its token (the harness instantiates with the model description's)."""
    try:
        read, unzipdir = _compile(fmi_version, packed, None)
    except FMUError as e:
        raise PackError(f"the packed FMU refuses its own profile: {e}") from None
    inside = unzipdir / "resources"
    for path in [read.script] + [p for _, _, p in read.tables]:
        if not Path(os.path.normpath(path)).is_relative_to(inside):
            raise PackError(f"the packed FMU reads {path}, outside itself")
    if (read.state, read.axes, read.last_cycle) != (original.state, original.axes, original.last_cycle):
        raise PackError("the packed FMU compiles another script than the script by path")
    md = ET.fromstring(zipfile.ZipFile(packed).read(MODEL_DESCRIPTION))
    starts = [
        e.get("start", e.get("value"))
        for v in md.iter()
        if v.get("name") == "script"
        for e in v
        if e.tag in ("String", "Start")
    ]
    if starts != [start]:
        raise PackError(f"{MODEL_DESCRIPTION} gives the script the start value {starts}, not {start!r}")
    if md.get("guid", md.get("instantiationToken")) != token:
        raise PackError(f"{MODEL_DESCRIPTION} does not give the packed FMU's token {token}")


__all__ = [
    "pack",
    "Packed",
    "PackError",
    "set_script_start",
    "set_identity",
    "packed_token",
    "profile_name",
    "PROFILE",
    "START_FILE",
    "TOKEN_FILE",
]
