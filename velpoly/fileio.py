"""Atomic output files: a failed run leaves no partial file.

Every file velpoly writes goes first to a temporary file in the same
folder, which is renamed over the target only when complete (``os.replace``
is atomic on one file system). On any failure the temporary file is
removed and an existing target is left untouched. The new file gets the
permissions an ordinary new file would (``0o666`` less the umask), not the
private ``0o600`` of a temporary file. Input files are never written.
"""
from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path

from .errors import InputError

__all__ = ["atomic_path", "atomic_write_text", "atomic_write_bytes"]


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


@contextlib.contextmanager
def atomic_path(target):
    """Yield a temporary path beside ``target``; rename it over ``target`` on success.

    On any exception the temporary file is removed and ``target`` is left
    as it was. Failing to create or rename the file is an
    :class:`~velpoly.errors.InputError` naming the target.
    """
    target = Path(target)
    folder = target.parent if str(target.parent) else Path(".")
    if target.is_dir():
        raise InputError("is a folder: cannot write a file there", file=str(target),
                         hint="give the output file's name")
    blocker = next((p for p in (folder, *folder.parents) if p.exists()), None)
    if blocker is not None and not blocker.is_dir():   # a file where the output's folder should be
        raise InputError(f"cannot write: {str(blocker)!r} is a file, not a folder", file=str(target),
                         hint="give an output path whose folders are folders")
    try:
        folder.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{target.stem}.", suffix=target.suffix + ".part", dir=folder)
    except OSError as e:
        raise InputError(f"cannot write: {e.strerror or e}", file=str(target),
                         hint="check the output folder exists and is writable") from None
    os.close(fd)
    try:
        yield Path(tmp)
        try:
            mode = (target.stat().st_mode & 0o7777) if target.exists() else (0o666 & ~_umask())
            os.chmod(tmp, mode)
            os.replace(tmp, target)
        except OSError as e:
            raise InputError(f"cannot write: {e.strerror or e}", file=str(target),
                             hint="check the output is writable") from None
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def atomic_write_bytes(target, data: bytes) -> Path:
    """Write ``data`` to ``target`` atomically; returns the target's path."""
    with atomic_path(target) as tmp:
        tmp.write_bytes(data)
    return Path(target)


def atomic_write_text(target, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``target`` atomically; returns the target's path."""
    return atomic_write_bytes(target, text.encode("utf-8"))
