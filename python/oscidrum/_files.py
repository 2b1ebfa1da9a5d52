"""Every file the package writes goes through the library's output file (oscidrum_io's
``OutputFile``), as the command-line tool's do: a regular file is written beside its target and
renamed over it only when complete (an interrupted write leaves the old file), a symbolic link
is written through (it keeps pointing where it did), a FIFO or character device is written in
place, and a directory, block device or socket is refused with ``oscidrum.Error``."""

from __future__ import annotations

import contextlib
import os
from typing import Iterator, Union

from . import _core

PathLike = Union[str, "os.PathLike[str]"]


def write_file(path: PathLike, data: Union[bytes, str]) -> None:
    """Write `data` (bytes, or str as UTF-8) to `path` atomically."""
    if isinstance(data, str):
        data = data.encode("utf-8")
    _core._write_file(os.fsencode(path), data)


@contextlib.contextmanager
def output_path(path: PathLike, regular_only: bool = False) -> Iterator[str]:
    """The name to write `path` under, for writers that take a file name (matplotlib, netCDF):
    a temporary file beside the target, renamed over it when the block ends without an
    exception (deleted otherwise); or the FIFO or device itself. `regular_only` refuses those
    (a format that seeks)."""
    out = _core._OutputFile(os.fsencode(path), regular_only)
    try:
        yield os.fsdecode(out.write_path)
        out.commit()
    finally:
        out.discard()
