"""Where a mechanism comes from: a file's path, TOML text or a dict, read into plain TOML values
(nesting at most MAX_DEPTH levels) and built into a Mechanism; every failure an InputError."""
from __future__ import annotations

import os
import re
import stat
import tomllib
from pathlib import Path
from typing import Mapping

import numpy as np

from ..errors import ArgumentTypeError, InputError, VelpolyError
from ..model import Mechanism
from .build import build
from .context import Ctx, toml_float
from .toml_positions import deep_entry, unclosed

__all__ = ["load", "loads", "MAX_DEPTH"]

MAX_DEPTH = 32   # levels of tables and lists: a mechanism file nests 4 or 5 at most
MAX_BYTES = 16 * 2 ** 20   # a mechanism file is a few kB: a larger one (or a device without end) is none


def load(source, *, name: str | None = None) -> Mechanism:
    """Read a mechanism from a file path, a dict, or TOML text with a newline in it (FORMAT.md section 4).

    A string on one line is a file's path (TOML text on one line, such as
    ``"[points]"``, is refused with a pointer to :func:`loads`); a string with
    a newline is TOML text. A dict's values may be tuples, numpy scalars or
    1-D arrays where the file has lists and numbers. Input files are only
    read, never written. Raises :class:`~velpoly.errors.InputError` (a
    :class:`VelpolyError`) naming the file, the entry and what is wrong.
    """
    _check_name(name)
    text = None
    if isinstance(source, Mapping):
        file = name or "<dict>"
        data = _plain(source, file)
        title = name
    elif isinstance(source, os.PathLike) or (isinstance(source, str) and source.strip() and "\n" not in source):
        path = Path(source)
        file = name or str(source)
        text = _read_file(path, source, file)
        data = _parse_toml(text, file)
        title = path.name   # the default title is the file's name, however errors call the file
    elif isinstance(source, str):
        return loads(source, name=name)
    else:
        raise ArgumentTypeError(f"cannot load {_a(type(source).__name__)}: give a path, a dict or TOML text",
                                where="source", file=name or "",
                                hint="velpoly.load(\"fourbar.toml\"), or velpoly.loads(text) for TOML text")
    return _load_data(data, file, text, title)


def _read_file(path: Path, source, file: str) -> str:
    """The file's text (without a byte-order mark); an InputError if it cannot be read as UTF-8 text, or if it
    is larger than MAX_BYTES (read no further: ``velpoly solve /dev/zero`` read without end until the system
    killed it)."""
    try:
        st = path.stat()
        if stat.S_ISREG(st.st_mode) and st.st_size <= MAX_BYTES:
            text = path.read_text(encoding="utf-8")
        else:   # a FIFO, a device, a large file: read no more than the bound
            with open(path, "rb") as f:
                data = f.read(MAX_BYTES + 1)
            if len(data) > MAX_BYTES:
                raise InputError(f"larger than {MAX_BYTES // 2 ** 20} MB: not a mechanism file", file=file,
                                 hint="a mechanism file is TOML text of a few kB: check the path")
            text = data.decode("utf-8").replace("\r\n", "\n").replace("\r", "\n")   # newlines as read_text's
    except FileNotFoundError:
        if isinstance(source, str) and _looks_like_toml(source):
            raise InputError("no such file: this is TOML text, not a file's name", file=file,
                             hint="read TOML text with velpoly.loads(text) (velpoly.load reads text "
                                  "only with a newline in it)") from None
        raise InputError("no such file", file=file, hint="check the path") from None
    except IsADirectoryError:
        raise InputError("is a directory, not a mechanism file", file=file,
                         hint="give the path of a .toml file") from None
    except UnicodeDecodeError:
        raise InputError("not a text (UTF-8) file", file=file,
                         hint="a mechanism file is TOML text in UTF-8") from None
    except (OSError, ValueError) as e:   # ValueError: a NUL character in the path
        raise InputError(f"cannot read: {getattr(e, 'strerror', None) or e}", file=file,
                         hint="check the path and its permissions") from None
    return text[1:] if text.startswith("\ufeff") else text   # a byte-order mark, as some editors write


def loads(text: str, *, name: str | None = None) -> Mechanism:
    """Read a mechanism from TOML text (one line or many): ``velpoly.loads('format = 1\\n[points]...')``.

    ``name`` is what errors call it (default ``<text>``). Raises
    :class:`~velpoly.errors.InputError` naming the entry and what is wrong.
    """
    _check_name(name)
    if isinstance(text, (bytes, bytearray)):
        try:
            text = bytes(text).decode("utf-8")
        except UnicodeDecodeError:
            raise InputError("not UTF-8 text", where="text", file=name or "<text>",
                             hint="TOML text is UTF-8") from None
    if not isinstance(text, str):
        raise ArgumentTypeError(f"expected TOML text (a string), got {_a(type(text).__name__)}", where="text",
                                file=name or "", hint="velpoly.load(path) reads a file, velpoly.load(d) a dict")
    file = name or "<text>"
    if text.startswith("\ufeff"):
        text = text[1:]
    return _load_data(_parse_toml(text, file), file, text, name)


def _check_name(name) -> None:
    """``name`` (what errors call the source) must be None or a string: an ArgumentTypeError naming it."""
    if name is not None and not isinstance(name, str):
        raise ArgumentTypeError(f"expected a string, got {_a(type(name).__name__)}", where="name",
                                hint='name is what errors call the source, e.g. name="fourbar.toml"')


def _a(noun: str) -> str:
    return ("an " if noun[:1].lower() in "aeiou" else "a ") + noun


def _looks_like_toml(s: str) -> bool:
    """A one-line string that is TOML rather than a path: a [table] header or a key = value."""
    t = s.strip()
    return t.startswith("[") or "=" in t or t.startswith("#")


def _load_data(data: dict, file: str, text: str | None, name: str | None) -> Mechanism:
    ctx = Ctx(file, text)
    try:
        return build(ctx, data, default_title=name or file)
    except VelpolyError as e:
        raise e.with_file(file)
    except RecursionError:   # pragma: no cover (nesting is limited by _plain first)
        raise InputError(f"nested too deeply (more than {MAX_DEPTH} levels)", file=file,
                         hint="a mechanism file's entries nest a few levels at most") from None
    except (TypeError, ValueError, KeyError, IndexError, AttributeError) as e:  # pragma: no cover
        # every input is checked above; this is a last line of defence, never a traceback
        raise InputError(f"malformed entry ({type(e).__name__}: {e})", file=file,
                         hint="please report this file: velpoly should have named the entry") from None


def _plain(data, file: str) -> dict:
    """``data`` (a dict, or what TOML gave) as plain TOML values: tuples and 1-D arrays become lists,
    numpy scalars Python numbers, and no entry nested deeper than MAX_DEPTH (an InputError naming it,
    never a RecursionError). The caller's dict is not changed."""
    def where_of(path):
        out = ""
        for k in path:
            out += f"[{k}]" if isinstance(k, int) else (f".{k}" if out else str(k))
        return out

    def conv(v, path):
        if isinstance(v, Mapping) or isinstance(v, (list, tuple)) or (isinstance(v, np.ndarray) and v.ndim):
            if len(path) >= MAX_DEPTH:
                shown = where_of(path[:6]) + ("..." if len(path) > 6 else "")
                raise InputError(f"nested more than {MAX_DEPTH} levels deep", where=shown, file=file,
                                 hint="a mechanism file's entries nest a few levels at most: "
                                      "check the brackets and table headers")
            if isinstance(v, Mapping):
                return {key(k): conv(x, path + [key(k)]) for k, x in v.items()}
            return [conv(x, path + [i]) for i, x in enumerate(v)]
        if isinstance(v, (np.generic, np.ndarray)):   # a numpy scalar or 0-d array
            return v.item() if isinstance(v, np.generic) or v.ndim == 0 else v
        return v

    def key(k):
        return k.item() if isinstance(k, np.generic) else k
    return conv(data, [])


def _parse_toml(text: str, file: str) -> dict:
    """The TOML text's values; bad TOML is an InputError at its line (or where a bracket opened)."""
    if not text.strip():
        raise InputError("the file is empty", file=file,
                         hint="a mechanism file has [points], [links] and [driver] tables (see the README)")
    try:
        return _plain(tomllib.loads(text, parse_float=toml_float), file)
    except RecursionError:   # tomllib reads nested brackets recursively
        entry, line = deep_entry(text, MAX_DEPTH)
        raise InputError(f"nested more than {MAX_DEPTH} levels deep", file=file,
                         where=f"{entry} (line {line})" if entry and line else (f"line {line}" if line else entry),
                         hint="a mechanism file's entries nest a few levels at most: "
                              "check the brackets") from None
    except tomllib.TOMLDecodeError as e:
        msg = str(e)
        m = re.search(r"\s*\(at line (\d+), column (\d+)\)\s*$", msg)
        where = ""
        if m:
            where = f"line {m.group(1)}"
            msg = msg[:m.start()] + f" at column {m.group(2)}"
        else:
            msg = re.sub(r"\s*\(at end of document\)\s*$", " at the end of the file", msg)
            opened = unclosed(text)
            if opened:
                where = f"line {opened}"
                msg += " (opened here)"
        raise InputError(f"bad TOML: {msg[:1].lower() + msg[1:]}", where=where, file=file,
                         hint="check the syntax there (quotes around names, = between key and value, "
                              "one key per line)") from None
