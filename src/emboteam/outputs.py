"""Checking an ``--out`` before a command spends time on a run, and turning a failed write
into a typed error.

A run or a benchmark that plans for minutes and then cannot save is the worst way to learn
that ``--out`` pointed at a file or a read-only disk, so the commands check it first; a
write that still fails (a disk that fills up) becomes an :class:`OutputPathError`, which
the CLI reports as bad input (exit 2), not as an internal error.
"""

from __future__ import annotations

import errno
import os
import tempfile
from pathlib import Path

from emboteam.errors import OutputPathError


def _reason(exc: OSError) -> str:
    if exc.errno == errno.EROFS:
        return "the file system is read-only"
    if exc.errno in (errno.EACCES, errno.EPERM):
        return "permission denied"
    if exc.errno == errno.ENOSPC:
        return "no space left on the device"
    return exc.strerror or str(exc)


def write_error(path: Path, exc: OSError, option: str = "--out") -> OutputPathError:
    """The typed error of a write to ``path`` that failed with ``exc``."""
    where = exc.filename if exc.filename else path
    return OutputPathError(f"cannot write {option} {path}: {_reason(exc)} ({where})")


def _check_writable_dir(folder: Path, path: Path, option: str) -> None:
    try:
        # creating a file is the only check that also catches read-only mounts and ACLs
        fd, probe = tempfile.mkstemp(prefix=".emboteam-probe-", dir=folder)
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        raise write_error(path, exc, option) from None


def ensure_out_dir(path: Path, option: str = "--out") -> Path:
    """Create the output folder ``path`` (its parent must exist) and check it is writable."""
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise OutputPathError(f"{option} {path} is an existing file, not a folder: choose another {option}")
    if not path.exists():
        parent = path.parent if str(path.parent) else Path(".")
        if not parent.is_dir():
            raise OutputPathError(f"{option} {path}: its parent folder {parent} does not exist")
        try:
            path.mkdir()
        except FileExistsError:
            pass  # made meanwhile by someone else: fine if it is a folder
        except OSError as exc:
            raise write_error(path, exc, option) from None
    _check_writable_dir(path, path, option)
    return path


def check_out_file(path: Path, option: str = "--out") -> Path:
    """Check that the file ``path`` can be written (its folder exists and is writable)."""
    path = Path(path)
    if path.is_dir():
        raise OutputPathError(f"{option} {path} is a folder, not a file: name the file to write")
    parent = path.parent if str(path.parent) else Path(".")
    if not parent.is_dir():
        raise OutputPathError(f"{option} {path}: its folder {parent} does not exist")
    _check_writable_dir(parent, path, option)
    return path
