"""Where an entry is in a TOML text: the line of ``points.C`` or ``sliders[1].guide``, for error messages.

The scanner reads table headers, ``key =`` lines and bracket depth (skipping strings and comments);
it never parses values, so it also finds the line of an entry in a file ``tomllib`` refuses.
"""
from __future__ import annotations

import re
import tomllib

__all__ = ["locate", "unclosed", "deep_entry"]

_BARE = r"[A-Za-z0-9_-]+"
_QUOTED = r'"(?:[^"\\]|\\.)*"|' + r"'[^']*'"
_KEYPART = rf"(?:{_BARE}|{_QUOTED})"
_DOTTED = rf"{_KEYPART}(?:\s*\.\s*{_KEYPART})*"
_HEADER_RE = re.compile(rf"^\s*(\[\[|\[)\s*({_DOTTED})\s*(\]\]|\])\s*(?:#.*)?$")
_ASSIGN_RE = re.compile(rf"^\s*({_DOTTED})\s*=")
_PART_RE = re.compile(_KEYPART)
_TRIPLE = ('"' * 3, "'" * 3)


def _key_parts(dotted: str) -> list[str]:
    out = []
    for m in _PART_RE.finditer(dotted):
        k = m.group(0)
        if k[:1] == '"' and "\\" in k:   # a basic string's escapes, as TOML reads them ("E\tF")
            try:
                k = tomllib.loads("k = " + k)["k"]
            except tomllib.TOMLDecodeError:
                k = k[1:-1]
        elif k[:1] in "\"'":
            k = k[1:-1]
        out.append(k)
    return out


def _where_parts(where: str) -> list:
    """``sliders[0].guide`` -> ['sliders', 0, 'guide']."""
    out: list = []
    for piece in where.split("."):
        m = re.fullmatch(r"(.*?)((?:\[\d+\])*)", piece, flags=re.DOTALL)
        if m.group(1) in ('""', "''"):   # an empty name, written as TOML writes it
            out.append("")
        elif m.group(1):
            out.append(m.group(1))
        out.extend(int(i) for i in re.findall(r"\[(\d+)\]", m.group(2)))
    return out


def _scan_brackets(line: str, depth: int, in_ml: str | None, peak: list | None = None) -> tuple[int, str | None]:
    """Bracket depth and open multi-line string after ``line`` (strings and comments skipped); the
    deepest depth inside the line is kept in ``peak[0]`` if given."""
    i, n = 0, len(line)
    while i < n:
        if in_ml:
            j = line.find(in_ml, i)
            if j < 0:
                return depth, in_ml
            i, in_ml = j + 3, None
            continue
        c = line[i]
        if c == "#":
            break
        if line[i:i + 3] in _TRIPLE:
            in_ml = line[i:i + 3]
            i += 3
            continue
        if c in "\"'":
            j = i + 1
            while j < n and line[j] != c:
                j += 2 if (c == '"' and line[j] == "\\") else 1
            i = j + 1
            continue
        if c in "[{":
            depth += 1
            if peak is not None and depth > peak[0]:
                peak[0] = depth
        elif c in "]}":
            depth = max(depth - 1, 0)
        i += 1
    return depth, in_ml


def _header_path(h: re.Match, counts: dict[tuple, int]) -> list[str]:
    """The key path a table header opens: ``[[sliders]]`` -> ['sliders', '1'] (its count so far, kept in
    ``counts``); ``[sliders.x]`` after ``[[sliders]]`` is a sub-table of that entry."""
    table = _key_parts(h.group(2))
    if h.group(1) == "[[":
        key = tuple(table)
        counts[key] = counts.get(key, -1) + 1
        return table + [str(counts[key])]
    for key, i in counts.items():   # a sub-table of the latest array-of-tables entry: [[a]] then [a.b]
        if tuple(table[:len(key)]) == key and len(table) > len(key):
            return list(key) + [str(i)] + table[len(key):]
    return table


def locate(text: str | None, where: str) -> int | None:
    """The line (1-based) of the TOML text that defines the entry ``where``.

    ``where`` is written ``table.key`` (``points.C``, ``sliders[1].guide``,
    ``reference.values.V_B``); the line is the one whose key path is the
    longest prefix of it: the key's own line, or else its table's header.
    None when the entry is not in the text (a default, or a dict input).

    >>> locate("[points]\\nA = [0, 0]\\nB = [1, 0]\\n", "points.B")
    3
    >>> locate("[[sliders]]\\nblock = 1\\n[[sliders]]\\nblock = 2\\n", "sliders[1].block")
    4
    """
    if not text or not where or "(line " in where:
        return None
    target = [str(t) for t in _where_parts(where)]
    best, best_len = None, 0
    table: list = []
    counts: dict[tuple, int] = {}
    depth, in_ml = 0, None
    for no, line in enumerate(text.splitlines(), start=1):
        if depth == 0 and not in_ml:
            path = None
            h = _HEADER_RE.match(line)
            if h:
                path = table = _header_path(h, counts)
            else:
                a = _ASSIGN_RE.match(line)
                if a:
                    path = table + _key_parts(a.group(1))
            if path is not None:
                k = 0
                while k < min(len(path), len(target)) and path[k] == target[k]:
                    k += 1
                if (k == len(path) or (h and k == len(target))) and k > best_len:
                    best, best_len = no, k
            if h:
                continue
        depth, in_ml = _scan_brackets(line, depth, in_ml)
    return best


def deep_entry(text: str, max_depth: int) -> tuple[str, int | None]:
    """The entry (``table.key``) and line where the text's brackets nest deeper than ``max_depth``."""
    table, key, depth, in_ml = "", "", 0, None
    for no, line in enumerate(text.splitlines(), start=1):
        if depth == 0 and not in_ml:
            h = _HEADER_RE.match(line)
            if h:
                table, key = ".".join(_key_parts(h.group(2))), ""
                if len(_key_parts(h.group(2))) > max_depth:
                    return table[:60], no
                continue
            a = _ASSIGN_RE.match(line)
            if a:
                key = ".".join(_key_parts(a.group(1)))
        peak = [depth]
        depth, in_ml = _scan_brackets(line, depth, in_ml, peak)
        if peak[0] > max_depth:
            return ".".join(p for p in (table, key) if p)[:60], no
    return "", None


def unclosed(text: str) -> int | None:
    """The line where a bracket or multi-line string opens that the text never closes."""
    depth, in_ml, opened = 0, None, None
    for no, line in enumerate(text.splitlines(), start=1):
        was_open = depth > 0 or in_ml
        depth, in_ml = _scan_brackets(line, depth, in_ml)
        if (depth > 0 or in_ml) and not was_open:
            opened = no
    return opened if (depth > 0 or in_ml) else None
