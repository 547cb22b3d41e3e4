"""Output files: a failed run leaves no partial file, and no output replaces an input or a special file.

A regular output file (or a missing one) is written first to a temporary file in
the same folder, renamed over the target only when complete (``os.replace`` is
atomic on one file system). On any failure -- an error, Ctrl-C, SIGTERM turned into
an exception by the command line -- the temporary file is removed and an existing
target is left untouched. The new file gets the permissions an ordinary new file
would (``0o666`` less the umask), not the private ``0o600`` of a temporary file.
A symbolic link is followed: the file it names is replaced, the link stays.

Anything else that already exists at the target -- a FIFO, a device such as
``/dev/null``, a terminal -- is written straight through, never replaced (a
rename would turn a FIFO into a regular file, and, run as root, replace a device
for the whole machine). So is a path under ``/dev`` or ``/proc`` (``/dev/stdout``).

Input files are never written: the command line registers its input with
:func:`protect_input`, and a target that is the same file (a hard link or a
symbolic link to it, too) is an :class:`~velpoly.errors.InputError`. A write
that fails (no space, no permission) is an InputError ``cannot write OUT: REASON``.

Interruptions: :func:`note_interrupt` records a Ctrl-C or SIGTERM, and which, even
where Python could not raise it (inside a callback whose exceptions are ignored);
an output is then never committed (:func:`raise_if_interrupted` raises it again).
"""
from __future__ import annotations

import contextlib
import os
import shutil
import secrets
import stat
import tempfile
from pathlib import Path

from .errors import InputError

__all__ = ["atomic_path", "atomic_write_text", "atomic_write_bytes", "committed_together", "check_output", "protect_input", "forget_inputs",
           "same_file", "check_not_input", "cannot_write", "note_interrupt", "forget_interrupt", "interrupted", "interruption", "raise_if_interrupted"]

_INPUTS: dict[tuple[int, int], str] = {}   # (device, inode) of each input file -> its name as given
_INTERRUPTED: list[type[BaseException] | None] = [None]   # the recorded interruption's kind
# committed_together(): (pid, [(temporary file, target)]) while a group of outputs is being written
_GROUP: list = [None]


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


# -- inputs are never outputs ---------------------------------------------------------------------
def _identity(path) -> tuple[int, int] | None:
    try:
        st = os.stat(path)
    except (OSError, ValueError):
        return None
    return st.st_dev, st.st_ino


def protect_input(path) -> None:
    """Register ``path`` as an input of this run: no output may be written over it."""
    ident = _identity(path)
    if ident is not None:
        _INPUTS[ident] = str(path)


def forget_inputs() -> None:
    """Forget every registered input (a new run starts)."""
    _INPUTS.clear()
    _INTERRUPTED[0] = None


def same_file(a, b) -> bool:
    """``a`` and ``b`` are one existing file (the same path, a hard link or a symbolic link to it)."""
    ia = _identity(a)
    return ia is not None and ia == _identity(b)


def check_not_input(out, inp, option: str, default: bool = False) -> None:
    """Refuse an output ``out`` (given by ``option``, or its ``default`` name) that is the input file
    ``inp``: an InputError naming the option (exit 2)."""
    if out is not None and inp is not None and same_file(out, inp):
        what = "the default output" if default else "the output"
        raise InputError(f"{what} {str(out)!r} is the input file: an output never replaces its input",
                         where=option, file=str(inp), hint=f"give {option} another file name"
                         if not default else f"give the output's name with {option} OUT")


def cannot_write(target, e: BaseException) -> InputError:
    """The error of a failed write: ``cannot write OUT: REASON``."""
    reason = getattr(e, "strerror", None) or str(e) or type(e).__name__
    return InputError(f"cannot write {target}: {reason}",
                      hint="check the output's folder is writable and the disk has room")


# -- interruptions ---------------------------------------------------------------------------------
def note_interrupt(kind: type[BaseException] = KeyboardInterrupt) -> None:
    """Record that the run was interrupted, and how: ``kind`` is the exception its signal raises
    (KeyboardInterrupt for Ctrl-C, the command line's Terminated for SIGTERM); the first one recorded is kept,
    so that the exit status says which signal stopped the run even where its exception was swallowed. No
    output is committed after it."""
    if _INTERRUPTED[0] is None:
        _INTERRUPTED[0] = kind


def forget_interrupt() -> None:
    """Forget a recorded interruption: the run it stopped is over (its caller has handled it)."""
    _INTERRUPTED[0] = None


def interrupted() -> bool:
    """Whether the run was interrupted (Ctrl-C, SIGTERM), even where the interrupt was swallowed."""
    return _INTERRUPTED[0] is not None


def interruption() -> BaseException | None:
    """The exception of the recorded interruption (a new one, of the kind :func:`note_interrupt` recorded),
    None if the run was not interrupted."""
    return None if _INTERRUPTED[0] is None else _INTERRUPTED[0]()


def raise_if_interrupted() -> None:
    """Raise the recorded interruption (KeyboardInterrupt, or SIGTERM's exception) if the run was interrupted,
    even where the interrupt itself was swallowed."""
    if _INTERRUPTED[0] is not None:
        raise _INTERRUPTED[0]


def _special(target: Path, st) -> bool:
    """A target written straight through: an existing non-regular file, or a path under /dev or /proc."""
    if st is not None and not stat.S_ISREG(st.st_mode):
        return True
    return os.path.abspath(target).startswith(("/dev/", "/proc/"))


def is_special(target) -> bool:
    """Whether ``target`` is a special file (a FIFO, a device, a terminal; a path under /dev or /proc), written
    straight through, never replaced."""
    try:
        st = os.stat(target)
    except OSError:
        st = None
    return _special(Path(target), st)


def _check_folder(target: Path, folder: Path) -> None:
    blocker = next((p for p in (folder, *folder.parents) if p.exists()), None)
    if blocker is not None and not blocker.is_dir():   # a file where the output's folder should be
        raise InputError(f"cannot write: {str(blocker)!r} is a file, not a folder", file=str(target),
                         hint="give an output path whose folders are folders")


def check_output(target, option: str = "") -> None:
    """Refuse an output path before any work, as :func:`atomic_path` would when writing it: an input
    file of this run (:func:`protect_input`), a folder, or a path below a file; the errors name ``option``,
    the command-line option that gave it, if any."""
    target = Path(target)
    ident = _identity(target)
    if ident is not None and ident in _INPUTS:
        raise InputError(f"the output {str(target)!r} is the input file: an output never replaces its input",
                         where=option, file=_INPUTS[ident],
                         hint=f"give the output another file name ({option or '-o'} OUT)")
    if target.is_dir():
        raise InputError("is a folder: cannot write a file there", where=option, file=str(target),
                         hint=f"give {option} the output file's name" if option else "give the output file's name")
    if not target.exists():
        _check_folder(target, target.parent if str(target.parent) else Path("."))


@contextlib.contextmanager
def atomic_path(target):
    """Yield the path to write ``target`` through: a temporary path beside it, renamed over it on success.

    A target that exists and is not a regular file (a FIFO, a device, a
    terminal) is yielded itself: written straight through, never replaced.
    On any exception the temporary file is removed and ``target`` is left as
    it was. Failing to create, write or rename the file is an
    :class:`~velpoly.errors.InputError` ``cannot write OUT: REASON``; a
    target that is an input file of this run (:func:`protect_input`) is
    refused before anything is written.
    """
    target = Path(target)
    check_output(target)
    try:
        st = os.stat(target)
    except (FileNotFoundError, NotADirectoryError):   # absent (a file where a folder should be: below)
        st = None
    except OSError as e:
        raise cannot_write(target, e) from None
    if _special(target, st):
        yield from _through(target)
        return
    if target.is_symlink():   # replace the file the link names, not the link
        target = Path(os.path.realpath(target))
    folder = target.parent if str(target.parent) else Path(".")
    _check_folder(target, folder)
    tmp = None
    try:
        try:
            folder.mkdir(parents=True, exist_ok=True)
            for tmp in _candidates(folder, f".{target.stem}.", target.suffix + ".part"):
                if _made(tmp):
                    break
                tmp = None   # another's file: never removed here
        except OSError as e:
            raise cannot_write(target, e) from None
        try:
            yield Path(tmp)
            raise_if_interrupted()
            mode = (st.st_mode & 0o7777) if st is not None else (0o666 & ~_umask())
            os.chmod(tmp, mode)
            group = _GROUP[0]
            if group is not None and group[0] == os.getpid():   # committed with the group's other outputs
                group[1].append((tmp, target))
                return
            os.replace(tmp, target)
        except OSError as e:
            raise cannot_write(target, e) from None
    except BaseException:
        if tmp is not None:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
        raise


def _candidates(folder: Path, prefix: str, suffix: str):
    """Names for a new temporary file in ``folder``, each bound by the caller (``for tmp in ...``) BEFORE
    :func:`_made` creates the file: an interruption (Ctrl-C, SIGTERM) at any moment then finds the caller's
    cleanup knowing the file it must remove. (``tempfile.mkstemp`` creates the file and only then returns its
    name: a signal in between left a ``.part`` behind.) Raises FileExistsError after 100 names all taken."""
    for _ in range(100):
        yield str(folder / f"{prefix}{secrets.token_hex(4)}{suffix}")
    raise FileExistsError(f"no free temporary name {prefix}*{suffix} in {str(folder)!r}")


def _made(tmp: str) -> bool:
    """Create the empty private file ``tmp`` (mode 0o600) if no file has that name; False if one has."""
    try:
        os.close(os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600))
    except FileExistsError:
        return False
    return True


def _through(target: Path):
    """:func:`atomic_path` for a FIFO, a device or a terminal: written straight through, never replaced, from
    a temporary file complete before the first byte goes out. A writer that seeks (a multi-page PDF: the
    ``--steps`` sheets', an animation's) cannot seek in a FIFO or a pipe, and a command that fails sends the
    reader nothing partial."""
    tmp = None
    try:
        try:
            for tmp in _candidates(Path(tempfile.gettempdir()), "velpoly-", target.suffix + ".part"):
                if _made(tmp):
                    break
                tmp = None   # another's file: never removed here
        except OSError as e:
            raise cannot_write(target, e) from None
        yield Path(tmp)
        raise_if_interrupted()
        with open(tmp, "rb") as src, open(target, "wb") as out:
            shutil.copyfileobj(src, out)
    except OSError as e:
        raise cannot_write(target, e) from None
    finally:
        if tmp is not None:
            with contextlib.suppress(OSError):
                os.unlink(tmp)


@contextlib.contextmanager
def committed_together():
    """Every output written through :func:`atomic_path` inside this block is committed together at its
    end: each stays a temporary file beside its target until the block completes, then all are renamed
    over their targets. A failure anywhere in the block (an error, Ctrl-C, an output refused as the
    input) removes them all, so a command that writes several files (a plot, a CSV and a GIF; the frames
    of ``--steps``) leaves none of them, and every existing output as it was. Nested blocks join the
    outermost: what a nested block wrote is committed with the outermost, but a failure inside it drops
    only its own outputs (the gallery leaves out an example that failed and builds the others); a FIFO or
    a device is written straight through as ever. Only this process takes part (a worker process commits
    its own outputs)."""
    outer = _GROUP[0]
    if outer is not None and outer[0] == os.getpid():
        mine = len(outer[1])   # the outputs written before this block: not its own
        try:
            yield
        except BaseException:
            _drop(outer[1][mine:])
            del outer[1][mine:]
            raise
        return
    _GROUP[0] = group = (os.getpid(), [])
    try:
        yield
        raise_if_interrupted()
    except BaseException:
        _GROUP[0] = outer
        _drop(group[1])
        raise
    _GROUP[0] = outer
    pending = group[1]
    try:
        while pending:
            tmp, target = pending[0]
            try:
                os.replace(tmp, target)
            except OSError as e:
                raise cannot_write(target, e) from None
            pending.pop(0)
    finally:
        _drop(pending)


def _drop(pending) -> None:
    """The temporary files of ``[(temporary file, target)]`` removed; their targets are left as they were."""
    for tmp, _ in pending:
        with contextlib.suppress(OSError):
            os.unlink(tmp)


def atomic_write_bytes(target, data: bytes) -> Path:
    """Write ``data`` to ``target`` (atomically where it is a regular file); returns the target's path."""
    with atomic_path(target) as tmp:
        tmp.write_bytes(data)
    return Path(target)


def atomic_write_text(target, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``target`` (atomically where it is a regular file); returns the target's path."""
    return atomic_write_bytes(target, text.encode("utf-8"))
