"""`velpoly demo` and `velpoly gallery`: the built-in example, the comparison tables, the README."""
import re
import shutil
from pathlib import Path

import pytest

import velpoly
from velpoly.cli import main
from velpoly.fileio import atomic_write_bytes
from velpoly.compare import comparison
from velpoly.gallery import build_gallery, comparison_text, example_path, find_gallery, top_comments

REPO = Path(__file__).resolve().parent.parent
from paths import EXAMPLES, GALLERY  # noqa: E402
from paths import BOOK_FILES, GALLERY_FILES


def render_available():
    try:
        from velpoly.render import draw_to_file  # noqa: F401
    except ImportError:
        return False
    return True


needs_render = pytest.mark.skipif(not render_available(), reason="velpoly.render (the figures) is absent")


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def table_rows(markdown: str, section_title: str) -> list[list[str]]:
    """The rows of the first table in the README section whose heading contains ``section_title``."""
    part = markdown.split(f"## {section_title}", 1)[1].split("\n## ", 1)[0]
    rows = [line for line in part.splitlines() if line.startswith("| ")]
    return [[c.strip() for c in re.split(r"(?<!\\)\|", r)[1:-1]] for r in rows[1:]]   # without the header


# -- the demo ----------------------------------------------------------------------------------
def test_demo_example_is_problem_1_4_4_with_its_printed_answers():
    m = velpoly.load(example_path())
    assert m.reference.source.startswith("Problem 1.4.4")
    c = comparison(velpoly.solve(m))
    keys = [v[0] for v in c.values]
    assert keys[:8] == ["omega_1", "omega_2", "omega_3", "omega_4", "alpha_1", "alpha_2", "alpha_3", "alpha_4"]
    assert {"V_B", "V_C", "V_E", "V_F", "A_B", "A_C", "A_E", "A_F", "R_CA", "theta_3"} <= set(keys)
    noted = {key for _, key, _ in c.notes}
    assert noted == {"theta_2", "theta_3", "theta_4"}   # printed modulo 180 deg, as the notes say
    for key, printed, graphical, analytic in c.values:
        if key in noted or graphical is None:
            continue
        # the book prints 5 to 6 significant digits: it agrees to 5e-5 (directions to 1e-3 deg)
        p, a = (printed, analytic) if isinstance(printed, tuple) else ((printed, 0.0), (analytic, 0.0))
        assert a[0] == pytest.approx(p[0], rel=5e-5, abs=1e-9), key
        assert abs((a[1] - p[1] + 180) % 360 - 180) < 1e-3, key
        # the graphical construction is exact
        g = graphical if isinstance(graphical, tuple) else (graphical, 0.0)
        assert g[0] == pytest.approx(a[0], rel=1e-9, abs=1e-12), key
        assert abs((g[1] - a[1] + 180) % 360 - 180) < 1e-7, key


def test_comparison_text_and_markdown_hold_every_row_and_note():
    sol = velpoly.solve(velpoly.load(example_path()))
    text, md = comparison_text(sol, "text"), comparison_text(sol, "markdown")
    n = len(comparison(sol).values)
    assert md.startswith("# Problem 1.4.4: six-bar") and md.count("\n| ") == n + 1
    assert "| omega_2 | -1.1307 | -1.1307 | -1.1307 |" in md
    assert "1. theta_2: printed as phi2" in text and "1. theta\\_2: printed as phi2" in md
    assert "graphical vs analytic" in text


@needs_render
def test_demo_writes_the_sheet_and_the_tables(tmp_path, capsys):
    out = tmp_path / "out"
    code, stdout, err = run(capsys, "demo", "-o", out)
    assert code == 0, err
    names = ["sixbar.svg", "sixbar.png", "sixbar-results.txt", "sixbar-results.md"]
    for name in names:
        assert (out / name).stat().st_size > 0
        assert str(out / name) in stdout
    assert (out / "sixbar.png").read_bytes().startswith(b"\x89PNG")
    assert "<svg" in (out / "sixbar.svg").read_text()
    assert "omega_3   -2.82169" in (out / "sixbar-results.txt").read_text()
    assert not list(out.glob(".*part"))


def test_demo_without_the_figure_module_fails_clearly(tmp_path, capsys, monkeypatch):
    import velpoly.gallery as gallery

    def absent():
        raise gallery.FiguresUnavailable("the figure module velpoly.render is not available (test)",
                                         where="figures", hint="install velpoly completely")
    monkeypatch.setattr(gallery, "_draw_to_file", absent)
    code, stdout, err = run(capsys, "demo", "-o", tmp_path / "out")
    assert code == 1 and err.startswith("error: figures: the figure module") and "hint:" in err
    assert not (tmp_path / "out").exists()


# -- the gallery ---------------------------------------------------------------------------------
def two_examples(tmp_path) -> Path:
    src = tmp_path / "src"
    src.mkdir()
    for name in ("problem_1_4_4_sixbar.toml", "ex3_6_fourbar.toml"):
        shutil.copy(EXAMPLES / name, src / name)
    return src


def fake_draw(calls):
    """A stand-in for draw_to_file that records its calls and writes a one-byte file atomically."""
    def draw(sol, out, sheet="full", style="textbook", steps=False):
        calls.append((sol.mechanism.title, Path(out), sheet, style, steps))
        return [atomic_write_bytes(out, b"x")]
    return draw


def test_gallery_readme_has_a_row_per_reference_value(tmp_path):
    src = two_examples(tmp_path)
    calls = []
    result = build_gallery(src, draw=fake_draw(calls))
    assert not result.failed and len(result.built) == 2
    assert [c[1].name for c in calls] == ["ex3_6_fourbar.png", "problem_1_4_4_sixbar.png"]
    assert all(c[2] == "full" and c[4] is False for c in calls)
    readme = (src / "README.md").read_text()
    for name in ("ex3_6_fourbar", "problem_1_4_4_sixbar"):
        m = velpoly.load(src / f"{name}.toml")
        sol = velpoly.solve(m)
        rows = table_rows(readme, m.title.replace("_", "\\_"))
        expected = comparison(sol).values
        assert len(rows) == len(expected) > 10
        assert [r[0].replace("\\", "") for r in rows] == [v[0] for v in expected]
        assert f"![{m.title.replace('_', chr(92) + '_')}](figures/{name}.png)" in readme
        for r in rows:   # book, graphical, analytic and both deviations are shown
            assert r[1] != "" and r[3] != "" and r[4] != ""
    # the notes and the top comments explain the disagreements
    from velpoly.gallery import _md
    for name in ("ex3_6_fourbar", "problem_1_4_4_sixbar"):
        m = velpoly.load(src / f"{name}.toml")
        assert m.reference.note
        for note in m.reference.note.values():
            assert _md(note) in readme
        for kind, body in top_comments(src / f"{name}.toml"):
            assert (f"```text\n{body}\n```" if kind == "pre" else _md(body)) in readme


def test_a_sheet_with_a_table_page_links_it_from_the_readme(tmp_path):
    """A sheet whose table cannot show every book's row beside the drawings writes a table page beside
    its figure (FORMAT.md, draw); the gallery's README links it under the figure, and only then."""
    src = two_examples(tmp_path)

    def draw(sol, out, sheet="full", style="textbook", steps=False):
        written = [atomic_write_bytes(out, b"x")]
        if "sixbar" in out.name:
            written.append(atomic_write_bytes(out.with_name(f"{out.stem}-table{out.suffix}"), b"t"))
        return written
    result = build_gallery(src, draw=draw)
    assert not result.failed
    readme = (src / "README.md").read_text()
    link = "[the sheet's table page](figures/problem_1_4_4_sixbar-table.png)"
    assert readme.count("the sheet's table page") == 1 and link in readme
    assert (src / "figures" / "problem_1_4_4_sixbar-table.png").read_bytes() == b"t"
    assert readme.index(link) > readme.index("](figures/problem_1_4_4_sixbar.png)")


def test_one_failing_example_does_not_stop_the_others(tmp_path, capsys):
    src = two_examples(tmp_path)
    (src / "broken.toml").write_text('title = "broken"\n[points]\nA = [0, 0]\n')
    logged = []
    result = build_gallery(src, draw=fake_draw([]), log=logged.append)
    assert len(result.built) == 2 and [p.name for p, _ in result.failed] == ["broken.toml"]
    assert len(logged) == 1 and logged[0].startswith("broken.toml: ")
    readme = (src / "README.md").read_text()
    assert "## Not built" in readme and "broken.toml" in readme.split("## Not built")[1]
    assert readme.count("\n## ") == 3   # the two examples and the failures


@needs_render
def test_gallery_command_builds_figures_and_exits_2_on_a_bad_file(tmp_path, capsys, monkeypatch):
    """One example drawn (by a stand-in: the command's real drawing is test_wheel's gallery, through the
    installed program; the pool's drawing of several is the next test's) and one that fails: not TOML, the
    input's status 2 (the other statuses: test_audit3_gallery)."""
    import velpoly.gallery as gallery
    monkeypatch.setattr(gallery, "_draw_to_file", lambda: fake_draw([]))   # (it may draw in a forked worker)
    src = tmp_path / "src"
    src.mkdir()
    shutil.copy(EXAMPLES / "ex3_6_fourbar.toml", src / "ex3_6_fourbar.toml")
    (src / "zz_bad.toml").write_text("this is not toml = = \n")
    out = tmp_path / "site"
    code, stdout, err = run(capsys, "gallery", "--source", src, "-o", out)
    assert code == 2
    assert "error: zz_bad.toml" in err and "1 of 2 examples failed" in err
    assert (out / "figures" / "ex3_6_fourbar.png").read_bytes() == b"x"   # the stand-in's
    assert [p.name for p in (out / "figures").iterdir()] == ["ex3_6_fourbar.png"]
    readme = (out / "README.md").read_text()
    assert "](figures/ex3_6_fourbar.png)" in readme and "## Not built" in readme
    assert str(out / "README.md") in stdout


def test_gallery_without_examples_is_an_input_error(tmp_path, capsys):
    code, _, err = run(capsys, "gallery", "--source", tmp_path)
    assert code == 2 and "no *.toml files" in err


def test_find_gallery_from_inside_the_repository(tmp_path):
    assert find_gallery(REPO / "docs") == GALLERY
    assert find_gallery(REPO) == GALLERY


def test_top_comments_keep_paragraphs_items_and_formulas(tmp_path):
    f = tmp_path / "c.toml"
    f.write_text("# First line\n# goes on.\n#\n# Misprints:\n# - one item\n#   continued.\n# - two\n"
                 "#\n#   x = 1      y = 2\n#   z = 3\nformat = 1\n# not a top comment\n")
    assert top_comments(f) == [("text", "First line goes on."), ("text", "Misprints:"),
                               ("item", "one item continued."), ("item", "two"),
                               ("pre", "x = 1      y = 2\nz = 3")]


def test_a_file_without_reference_values_shows_graphical_against_analytic():
    from mechanisms import slider_crank
    m = velpoly.load(slider_crank())
    sol = velpoly.solve(m)
    c = comparison(sol)
    keys = [v[0] for v in c.values]
    assert keys == ["omega_2", "omega_3", "omega_4", "alpha_2", "alpha_3", "alpha_4", "V_A", "V_B", "A_A", "A_B"]
    for key, printed, graphical, analytic in c.values:
        assert printed is None
        if isinstance(analytic, tuple):
            assert graphical[0] == pytest.approx(analytic[0], rel=1e-9), key
            assert abs((graphical[1] - analytic[1] + 180) % 360 - 180) < 1e-7, key
        else:
            assert graphical == pytest.approx(analytic, rel=1e-9, abs=1e-9), key
    assert all(r[1] == "-" and r[4] == "-" for r in c.table.rows)


# -- the book's values, strictly -----------------------------------------------------------------
def _off_by_more_than_last_digit(r, units=1.0) -> bool:
    """Whether a printed value differs from velpoly's by more than ``units`` of its last printed digit
    (magnitude, direction or either coordinate); ``units=0.5``: whether it is not velpoly's value
    correctly rounded."""
    from test_kinematics import _printed_digits_unit as unit
    p, c = r.printed, r.computed
    if c is None:
        return True
    tol = lambda x: unit(x) * units * 1.0001 + 1e-12   # noqa: E731
    if isinstance(p, tuple) and r.angle_error is None and r.key.startswith("P"):     # a pole [x, y]
        return any(abs(a - b) > tol(a) for a, b in zip(p, c))
    if isinstance(p, tuple):
        return abs(p[0] - c[0]) > tol(p[0]) or (r.angle_error is not None and r.angle_error > tol(p[1]))
    if r.key.startswith("theta"):
        return r.angle_error > tol(p)
    return abs(p - c) > tol(p)


def test_the_files_without_the_book_s_answers_are_the_own_mechanisms():
    """The gallery files the book-comparing tests (here and test_kinematics) leave out, as having no printed
    answers: the seven mechanisms of our own (no [reference] table); a book example that
    lost its answers fails here (those tests skipped it, until issue 19 item 7)."""
    assert sorted(p.stem for p in GALLERY_FILES if p not in BOOK_FILES) == [
        "cam_flat_follower", "cam_roller_follower", "crank_shaper", "crank_slider", "stephenson_sixbar",
        "watt_sixbar", "wheel_rolling"]
    assert not any(velpoly.load(p).reference for p in GALLERY_FILES if p not in BOOK_FILES)


@pytest.mark.parametrize("path", BOOK_FILES, ids=lambda p: p.stem)
def test_every_disagreement_with_the_book_has_a_note_and_every_note_a_disagreement(path):
    """A gallery value the book prints either matches velpoly to its last printed digit, or a
    `[reference] note` says which side is wrong; a note on a value the book rounds correctly would
    be stale (one within a unit but not correctly rounded, e.g. truncated, may carry a note)."""
    from velpoly.reference import compare
    m = velpoly.load(path)
    assert m.reference, path
    rows = compare(velpoly.solve(m))
    unexplained = [r.key for r in rows if not r.note and _off_by_more_than_last_digit(r)]
    stale = [r.key for r in rows if r.note and not _off_by_more_than_last_digit(r, units=0.5)]
    assert not unexplained, f"book values off by more than their last digit, with no note: {unexplained}"
    assert not stale, f"notes on values that match: {stale}"


# -- the built-in examples (issue 18, item 6) ----------------------------------------------------
def test_examples_lists_and_prints_the_built_in_files(capsys):
    code, out, err = run(capsys, "examples")
    assert code == 0 and err == ""
    names = [line.split()[0] for line in out.splitlines()]
    assert names == [p.stem for p in sorted(GALLERY_FILES, key=lambda p: [
        (0, int(t), "") if t.isdigit() else (1, 0, t.lower()) for t in re.split(r"(\d+)", p.stem)])]
    for path in GALLERY_FILES:   # each with its title
        assert f"{path.stem}  " in out and velpoly.load(path).title in out
    code, out, _ = run(capsys, "examples", "ex3_6_fourbar.toml")
    assert code == 0 and out == (EXAMPLES / "ex3_6_fourbar.toml").read_text(encoding="utf-8")
    code, out, err = run(capsys, "examples", "fourbar")
    assert code == 2 and out == "" and "no built-in example 'fourbar'" in err
    assert "did you mean ex3_6_fourbar or " in err
    code, out, err = run(capsys, "examples", "ex3_4")   # (test_wheel's case: the wheel ships the listing)
    assert code == 2 and out == "" and "no built-in example 'ex3_4'" in err and "ex3_4_slotted_lever" in err


def test_a_gallery_of_the_built_in_examples_elsewhere_stands_alone(tmp_path, capsys):
    calls = []
    out = tmp_path / "site"
    result = build_gallery(out=out, draw=fake_draw(calls), names=["crank_slider", "ex3_5_slider_crank.toml"])
    assert [p.name for p in result.built] == ["crank_slider.toml", "ex3_5_slider_crank.toml"]
    for name in ("crank_slider", "ex3_5_slider_crank"):   # the files beside the README it links to
        assert (out / f"{name}.toml").read_bytes() == (EXAMPLES / f"{name}.toml").read_bytes()
        assert f"]({name}.toml)" in (out / "README.md").read_text()
    # a file of the user's by an example's name is never replaced: that example fails, the others build
    (out / "crank_slider.toml").write_text("# my own\n")
    logged = []
    result = build_gallery(out=out, draw=fake_draw([]), names=["crank_slider", "crank_shaper"], log=logged.append)
    assert [p.name for p in result.built] == ["crank_shaper.toml"] and (out / "crank_slider.toml").read_text() == "# my own\n"
    assert "crank_slider.toml: -o: " in logged[0] and "not replaced" in logged[0]
    with pytest.raises(velpoly.InputError, match="no example 'nope'"):
        build_gallery(out=out, draw=fake_draw([]), names=["nope"])
    # the checkout's own gallery links to the package's files and copies nothing
    assert find_gallery(REPO) == GALLERY and (REPO / "gallery" / "README.md").exists()
    assert "](../velpoly/examples/ex3_6_fourbar.toml)" in (GALLERY / "README.md").read_text()
    assert not list(GALLERY.glob("*.toml"))


def test_the_gallery_drawn_in_worker_processes_is_the_one_drawn_in_one(tmp_path):
    """The pool of workers (one a core) draws into memory and this process writes every file, in the
    order and with the bytes of a build one example after another (its README and figures)."""
    src = tmp_path / "src"
    src.mkdir()
    # each example's own sheet is its displacement diagram (drawn, text and all, in half a full sheet's time:
    # the test 1.8 CPU s alone, 3.2 with full sheets); the pool's order, bytes and failures are tested here
    for name in ("crank_slider.toml", "ex3_6_fourbar.toml", "nope.toml"):   # the third fails to load
        (src / name).write_text((EXAMPLES / name).read_text() + '\n[drawing]\nsheet = "displacement"\n'
                                if name != "nope.toml" else "[links\n")
    built = {}
    for jobs in (1, 2):
        out = tmp_path / f"jobs{jobs}" / "site"
        logged = []
        result = build_gallery(src, out, jobs=jobs, log=logged.append)
        files = {p.relative_to(out).as_posix(): p.read_bytes().replace(f"jobs{jobs}".encode(), b"jobsN")
                 for p in out.rglob("*") if p.is_file()}   # the README names its folder
        built[jobs] = ([Path(p).relative_to(out).as_posix() for p in result.written], files, logged,
                       [p.name for p in result.built], [(p.name, line) for p, line in result.failed])
    assert built[1] == built[2]
    written, files, logged, ok, failed = built[2]
    assert written == ["figures/crank_slider.png", "figures/ex3_6_fourbar.png", "README.md"]
    assert ok == ["crank_slider.toml", "ex3_6_fourbar.toml"] and [f for f, _ in failed] == ["nope.toml"]
    assert logged == [line for _, line in failed] and logged[0].startswith("nope.toml: ")
    assert all(files[f].startswith(b"\x89PNG") for f in written[:2])
    assert not [p for p in tmp_path.rglob("*.part")]


@pytest.mark.parametrize("sig, code, word", [("SIGINT", 130, "interrupted"), ("SIGTERM", 143, "terminated")])
def test_a_signal_while_the_workers_draw_leaves_nothing_behind(tmp_path, sig, code, word):
    """Ctrl-C or SIGTERM to the command while its workers draw: it stops at once (the workers
    abandon their drawings), exit 130/143 with one line, no traceback, no temporary folder, no
    README, nothing drawn after the signal."""
    import os
    import signal
    import subprocess
    import sys
    import time
    src = tmp_path / "src"
    src.mkdir()
    for name in ("crank_slider.toml", "ex3_6_fourbar.toml", "problem_1_4_4_sixbar.toml"):
        shutil.copy(EXAMPLES / name, src / name)
    tmp, out = tmp_path / "tmp", tmp_path / "out"
    tmp.mkdir()
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[1]), TMPDIR=str(tmp))
    p = subprocess.Popen([sys.executable, "-m", "velpoly", "gallery", "--source", str(src), "-o", str(out)],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    try:
        deadline = time.monotonic() + 90
        while not list(tmp.glob("*/*")) and p.poll() is None and time.monotonic() < deadline:
            time.sleep(0.02)     # a worker's temporary folder in the pool's: it draws
        assert list(tmp.glob("*/*")), "no worker began to draw"
        p.send_signal(getattr(signal, sig))
        sent = time.monotonic()
        lines = p.communicate(timeout=60)[1].decode().strip().splitlines()
        took = time.monotonic() - sent
    except BaseException:
        p.kill()
        raise
    assert (p.returncode, lines[-1]) == (code, f"error: {word}"), lines
    assert not [ln for ln in lines if ln.startswith(("Traceback", "Exception ignored"))], lines
    assert list(tmp.iterdir()) == []
    assert not (out / "README.md").exists() and not list(out.rglob("*.part"))
    assert took < 20, took      # not the rest of the build: the drawings under way are abandoned
