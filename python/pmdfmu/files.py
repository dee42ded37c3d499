"""A user's files as the harness reads and writes them.

Reading: only a regular file is read; a FIFO, a device or a folder is refused at
once, never waited on -- as the FMU refuses them for a script or a table (README,
"Scripts").

Writing: a file the harness writes (a recording, a plot, a report, a packed FMU)
is written whole into a new file beside it and renamed over it when complete, so
an interrupted or failed write leaves the old file as it was and no partial one.
The new file is created with O_CREAT|O_EXCL under a random name: a name someone
planted (a symlink to another file) is never written through.
"""
from __future__ import annotations

import os
import secrets
import stat
from contextlib import contextmanager, suppress
from pathlib import Path
from typing import IO, Iterator, Union

PathLike = Union[str, Path]
PARTIAL = ".partial"                # the suffix of a file being written (.NAME.RANDOM.partial beside NAME)


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
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0))
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            raise NotRegularFile(path, mode)
        if hasattr(os, "O_NONBLOCK"):
            os.set_blocking(fd, True)
        with os.fdopen(fd, "rb") as f:
            fd = -1
            return f.read()
    finally:
        if fd >= 0:
            os.close(fd)


def read_text(path: PathLike) -> str:
    """read_bytes as UTF-8 text, line ends as they are (a UnicodeDecodeError for other bytes)."""
    return read_bytes(path).decode("utf-8")


def check_regular(path: PathLike) -> None:
    """Raises NotRegularFile (or open's OSError) unless path is a regular file, without reading it."""
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            raise NotRegularFile(path, mode)
    finally:
        os.close(fd)


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
    """A new file (binary, or text with newline="") that becomes path when the block ends without an
    exception; on any exception, KeyboardInterrupt included, it is removed and path is untouched.
    Its name while it is written is .NAME.RANDOM.partial beside path (f.name)."""
    path = Path(path)
    temp = None
    try:
        while temp is None:
            candidate = path.with_name(f".{path.name}.{secrets.token_hex(4)}{PARTIAL}")
            try:
                f = open(candidate, "x", newline="") if text else open(candidate, "xb")
            except FileExistsError:
                continue
            temp = candidate
        with f:
            yield f
        os.replace(temp, path)
    except BaseException:
        if temp is not None:
            with suppress(FileNotFoundError):
                os.unlink(temp)
        raise


__all__ = ["read_bytes", "read_text", "check_regular", "replaced", "shown", "shown_path", "NotRegularFile", "PARTIAL"]
