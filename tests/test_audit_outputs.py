"""Outside check, outputs (FORMAT.md section 3): "A failed command leaves no partial output file" and
"an existing output is left as it was", for the commands that write several files.

Found by the audit: ``velpoly draw IN --steps -o st.svg`` where a numbered frame (``st-03.svg``) is the
input wrote ``st-01.svg`` and ``st-02.svg`` over existing files and then, refusing the third, deleted
them (the user's old files lost); ``velpoly sweep -o p.png --csv c.csv --gif G`` whose GIF could not be
written (a folder) exited 2 but left the plot and the CSV behind. Now every output of a command is
committed together at its end (``fileio.committed_together``), and each is checked before any work.
"""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from velpoly.cli import main
from velpoly.fileio import atomic_path, atomic_write_text, committed_together

import mechanisms
from test_fuzz import to_toml


def generated(seed: int) -> dict:
    """A four-bar or slider-crank of random proportions, pose and rates (a regular drawn pose)."""
    rng = np.random.default_rng(seed)
    if seed % 2:
        return mechanisms.slider_crank(r=rng.uniform(2, 4), l=rng.uniform(9, 14), e=rng.uniform(-1, 1),
                                       theta=rng.uniform(20, 160), omega=rng.uniform(-20, 20),
                                       alpha=rng.uniform(-50, 50))
    return mechanisms.fourbar(a=rng.uniform(3, 5), b=rng.uniform(8, 10), c=rng.uniform(8, 10), d=8.0,
                              theta=rng.uniform(20, 160), omega=rng.uniform(-20, 20), alpha=rng.uniform(-50, 50))


def old_files(folder: Path, names) -> dict:
    for i, n in enumerate(names):
        (folder / n).write_text(f"the user's own {n} ({i})\n")
    return {n: (folder / n).read_text() for n in names}


def listing(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir())


@pytest.mark.parametrize("seed", range(3))
def test_steps_whose_frame_is_the_input_leave_every_existing_frame(tmp_path, capsys, seed):
    old = old_files(tmp_path, [f"st-0{i}.svg" for i in (1, 2, 4)])
    src = tmp_path / "st-03.svg"          # the mechanism file, named as the third frame will be
    src.write_text(to_toml(generated(seed)))
    text = src.read_text()
    assert main(["draw", str(src), "--steps", "-o", str(tmp_path / "st.svg")]) == 2
    err = capsys.readouterr().err.splitlines()
    assert err[0] == f"error: {src}: the output '{src}' is the input file: an output never replaces its input"
    assert src.read_text() == text
    assert {n: (tmp_path / n).read_text() for n in old} == old      # the user's files, as they were
    assert listing(tmp_path) == sorted([*old, src.name])           # nothing new, no temporary file


@pytest.mark.parametrize("seed", range(2))
def test_a_sweep_whose_last_output_is_refused_writes_none(tmp_path, capsys, seed):
    src = tmp_path / "m.toml"
    src.write_text(to_toml(generated(seed)))
    old = old_files(tmp_path, ["c.csv"])
    (tmp_path / "g.gif").mkdir()           # the GIF cannot be written: a folder stands there
    assert main(["sweep", str(src), "--step", "30", "--csv", str(tmp_path / "c.csv"), "-o",
                 str(tmp_path / "p.png"), "--gif", str(tmp_path / "g.gif")]) == 2
    assert "g.gif: --gif: is a folder" in capsys.readouterr().err
    assert (tmp_path / "c.csv").read_text() == old["c.csv"]
    assert listing(tmp_path) == ["c.csv", "g.gif", "m.toml"]


@pytest.mark.parametrize("failure, code", [(OSError(28, "No space left on device"), 2), (KeyboardInterrupt(), 130)])
def test_a_sweep_failing_in_its_last_output_commits_none(tmp_path, capsys, monkeypatch, failure, code):
    """A failure found only while writing (a full disk, Ctrl-C in the GIF writer) after the CSV is
    complete: it is not committed, the existing CSV stays, no temporary file is left."""
    import velpoly.render.sweep as render_sweep
    src = tmp_path / "m.toml"
    src.write_text(to_toml(generated(3)))
    old = old_files(tmp_path, ["c.csv"])

    def broken(sw, out, *args, **kw):   # the GIF fails half-written
        with atomic_path(out) as tmp:
            tmp.write_bytes(b"GIF89a")
            raise failure
    monkeypatch.setattr(render_sweep, "write_gif", broken)
    assert main(["sweep", str(src), "--step", "45", "--csv", str(tmp_path / "c.csv"),
                 "--gif", str(tmp_path / "g.gif")]) == code
    assert (tmp_path / "c.csv").read_text() == old["c.csv"]
    assert listing(tmp_path) == ["c.csv", "m.toml"]


def test_committed_together_renames_at_the_end_or_removes_all(tmp_path):
    a, b = tmp_path / "a.txt", tmp_path / "sub" / "b.txt"
    a.write_text("old a")
    with committed_together():
        atomic_write_text(a, "new a")
        with committed_together():            # a nested block joins the outer one
            atomic_write_text(b, "new b")
        assert a.read_text() == "old a" and not b.exists()   # nothing committed before the end
    assert a.read_text() == "new a" and b.read_text() == "new b"
    with pytest.raises(RuntimeError):
        with committed_together():
            atomic_write_text(a, "newer a")
            atomic_write_text(tmp_path / "c.txt", "c")
            raise RuntimeError("late failure")
    assert a.read_text() == "new a"
    assert sorted(p.name for p in tmp_path.rglob("*")) == ["a.txt", "b.txt", "sub"]
    assert os.listdir(tmp_path / "sub") == ["b.txt"]


def test_a_demo_that_cannot_write_one_file_writes_none(tmp_path, capsys):
    (tmp_path / "sixbar-results.md").mkdir()      # a folder where the demo's Markdown table goes
    assert main(["demo", "-o", str(tmp_path)]) == 2
    assert "sixbar-results.md: is a folder" in capsys.readouterr().err
    assert listing(tmp_path) == ["sixbar-results.md"]


def test_a_demo_failing_late_commits_none(tmp_path, capsys, monkeypatch):
    """The figures and the text table written, the Markdown table failing: none of them stays."""
    import velpoly.gallery as gallery

    def fast_draw(sol, out, **kw):   # the figures (slow to draw) as small files, written the same way
        with atomic_path(out) as tmp:
            tmp.write_text("figure")
        return [out]
    real = gallery.comparison_text

    def markdown_fails(sol, fmt):
        if fmt == "markdown":
            raise OSError(28, "No space left on device")
        return real(sol, fmt)
    monkeypatch.setattr(gallery, "_draw_to_file", lambda: fast_draw)
    monkeypatch.setattr(gallery, "comparison_text", markdown_fails)
    old = old_files(tmp_path, ["sixbar.svg"])
    assert main(["demo", "-o", str(tmp_path)]) != 0
    assert listing(tmp_path) == ["sixbar.svg"] and (tmp_path / "sixbar.svg").read_text() == old["sixbar.svg"]
