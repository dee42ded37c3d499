# SPDX-License-Identifier: BSD-2-Clause
"""A user's files as the harness reads and writes them.

Reading: only a regular file is read; a FIFO, a device or a folder is refused at
once, never waited on -- as the FMU refuses them for a script or a table
(docs/scripts.md).

Writing: a file the harness writes (a recording, a plot, a report, a packed FMU)
is written whole into a new file beside it and renamed over it when complete, so
an interrupted or failed write leaves the old file as it was and no partial one.
The new file is created with O_CREAT|O_EXCL under a random name: a name someone
planted (a symlink to another file) is never written through.
"""

from __future__ import annotations

import errno
import os
import secrets
import stat
from contextlib import contextmanager, suppress
from pathlib import Path
from typing import IO, Iterator, Union

PathLike = Union[str, Path]
PARTIAL = ".partial"  # the suffix of a file being written (.NAME.RANDOM.partial beside NAME)


class NotRegularFile(OSError):
    """A FIFO, a device or a folder named as a file to read; str() is the reason, filename the file."""

    def __init__(self, path: PathLike, mode: int):
        super().__init__(None, f"{_kind(mode)}, not a regular file", str(path))

    def __str__(self) -> str:
        return self.strerror


def _kind(mode: int) -> str:
    if stat.S_ISDIR(mode):
        return "a folder"
    if stat.S_ISFIFO(mode):
        return "a FIFO"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    return "a socket or another special file"


def read_bytes(path: PathLike) -> bytes:
    """The contents of the regular file path. A FIFO is opened without blocking (O_NONBLOCK) and
    refused, like a device or a folder (NotRegularFile); other OSErrors as open raises them."""
    fd = os.open(
        path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0) | getattr(os, "O_BINARY", 0)
    )
    try:  # the descriptor is this frame's alone: closed once, on every way out
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            raise NotRegularFile(path, mode)
        if hasattr(os, "O_NONBLOCK"):
            os.set_blocking(fd, True)
        chunks = []
        while True:
            chunk = os.read(fd, 1 << 20)
            if not chunk:
                return b"".join(chunks)
            chunks.append(chunk)
    finally:
        os.close(fd)


BOM = b"\xef\xbb\xbf"  # UTF-8's byte order mark: some editors and Excel's "CSV UTF-8" put it first


def read_text(path: PathLike) -> str:
    """read_bytes as UTF-8 text, line ends as they are (a UnicodeDecodeError for other bytes, and for a
    byte order mark first, which the FMU refuses too: read as text it was an invisible character in the
    first column's name)."""
    data = read_bytes(path)
    if data.startswith(BOM):
        raise UnicodeDecodeError(
            "utf-8",
            data,
            0,
            len(BOM),
            "the file begins with a UTF-8 byte order mark (BOM): save it as UTF-8 without one",
        )
    return data.decode("utf-8")


def check_regular(path: PathLike) -> None:
    """Raises NotRegularFile (or open's OSError) unless path is a regular file, without reading it."""
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0))
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            raise NotRegularFile(path, mode)
    finally:
        os.close(fd)


def resolved(path: PathLike) -> Path:
    """Path(path).resolve(); a symlink loop is an OSError (ELOOP), as opening the path raises it, not the
    RuntimeError of Pythons before 3.13, which no caller takes for a user's bad file (3.13 resolves a loop
    without an error, and the file's opening then says ELOOP)."""
    try:
        return Path(path).resolve()
    except RuntimeError:
        raise OSError(errno.ELOOP, os.strerror(errno.ELOOP), str(path)) from None


def shown(value, limit: int = 40) -> str:
    """repr(value) for a one-line message about a user's file, cut to about limit characters (a cell may
    be 100 000 characters long)."""
    text = repr(value)
    return text if len(text) <= limit else f"{text[:limit]}... ({len(text)} characters)"


def shown_path(path: PathLike) -> str:
    """A path for a one-line message: a line feed in a name written as \\n."""
    return str(path).replace("\n", "\\n")


@contextmanager
def replaced(path: PathLike, text: bool = False) -> Iterator[IO]:
    """A new file (binary, or UTF-8 text with newline="") that becomes path when the block ends without an
    exception; on any exception, KeyboardInterrupt included, it is removed and path is untouched.
    Its name while it is written is .NAME.RANDOM.partial beside path (f.name). A symbolic link keeps
    pointing where it did, at the new file (the file it named is replaced); an older file's permissions
    stay. A path that is no regular file but can be written (a FIFO, a device: /dev/stdout) is written
    through, as asked: there is nothing to rename over."""
    path = Path(path)
    try:
        old = os.stat(path)  # through a link: the file it names
    except (FileNotFoundError, NotADirectoryError):
        old = None
    if old is not None and stat.S_ISDIR(old.st_mode):
        raise IsADirectoryError(errno.EISDIR, "a folder, not a file to write", str(path))
    if old is not None and not stat.S_ISREG(old.st_mode):
        with open(path, "w", newline="", encoding="utf-8") if text else open(path, "wb") as f:
            yield f
        return
    target = Path(os.path.realpath(path)) if path.is_symlink() else path
    temp = None
    try:
        while True:
            # named before it is made: an interrupt as the file appears still finds it to remove
            temp = target.with_name(f".{target.name}.{secrets.token_hex(4)}{PARTIAL}")
            try:
                f = open(temp, "x", newline="", encoding="utf-8") if text else open(temp, "xb")
                break
            except FileExistsError:  # another file's name: never written through
                temp = None
            except OSError as e:  # a missing or unwritable folder, named as the user named it
                temp = None
                raise OSError(e.errno, e.strerror, str(path)) from None
        with f:
            yield f
        if old is not None:
            os.chmod(temp, stat.S_IMODE(old.st_mode))
        os.replace(temp, target)
    except BaseException:
        if temp is not None:
            with suppress(FileNotFoundError):
                os.unlink(temp)
        raise


__all__ = ["read_bytes", "read_text", "check_regular", "replaced", "shown", "shown_path", "NotRegularFile", "PARTIAL"]
