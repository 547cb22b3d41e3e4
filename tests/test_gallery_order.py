"""The gallery hands its workers the longest examples first (by file size) and writes them in name order."""
from __future__ import annotations

from concurrent.futures import Future
from pathlib import Path

from velpoly import gallery


class _Pool:
    """A pool that records what it was given, in order, and has every result at once."""

    def __init__(self):
        self.order = []

    def submit(self, fn, path, out, style, copy):
        self.order.append(Path(path).name)
        f = Future()
        f.set_result(((path.stem, f"text of {path.stem}", [], path), None))
        return f


def test_longest_first_written_in_order(tmp_path):
    sizes = {"a.toml": 10, "b.toml": 300, "c.toml": 50, "d.toml": 300, "e.toml": 1}
    files = []
    for name, n in sizes.items():
        (tmp_path / name).write_text("#" * n)
        files.append(tmp_path / name)
    pool = _Pool()
    written, built, failed, sections = gallery._build_examples(files, pool, tmp_path / "out", "textbook", False,
                                                               None, None)
    assert pool.order == ["b.toml", "d.toml", "c.toml", "a.toml", "e.toml"]   # largest first, ties in name order
    assert [s[0] for s in sections] == ["a", "b", "c", "d", "e"] and not failed
    assert built == files
