"""The command line's contract: exit codes, one-line errors, --debug, atomic outputs, scale.

A few cases run the real ``python -m velpoly`` in a subprocess (what users
see, tracebacks included); the rest call ``velpoly.cli.main`` in-process.
"""
from __future__ import annotations

import hashlib
import json
import os
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest

import velpoly
import velpoly.cli
from velpoly.cli import main
from velpoly.fileio import atomic_path, atomic_write_bytes, atomic_write_text

DATA = Path(__file__).parent / "data"
FOURBAR = DATA / "fourbar.toml"


def velpoly_cmd(*args, cwd=None):
    """``python -m velpoly ARGS`` in a subprocess: for what only the real process shows (its exit status as the
    shell sees it, a traceback, a broken pipe, the entry point)."""
    return subprocess.run([sys.executable, "-m", "velpoly", *map(str, args)], capture_output=True, text=True,
                          timeout=120, cwd=cwd)


@pytest.fixture
def cli(capsys, monkeypatch):
    """``velpoly ARGS`` run in this process (``velpoly.cli.main``, what ``python -m velpoly`` runs), as a
    CompletedProcess (returncode, stdout, stderr): the same exit codes and text without a second of imports a
    subprocess pays."""
    def run(*args, cwd=None):
        if cwd is not None:
            monkeypatch.chdir(cwd)
        capsys.readouterr()
        rc = main([str(a) for a in args])
        out = capsys.readouterr()
        return subprocess.CompletedProcess(args, rc, out.out, out.err)
    return run


# -- exit codes and messages, as a user sees them ------------------------------------------------------
def test_solve_exit_0(cli):
    # in this process (a second process until the suite had to fit 2 minutes: 0.4 CPU s); the real process's
    # exit 0 on this very command is test_broken_pipe_is_quiet's
    r = cli("solve", FOURBAR, "--json")
    assert r.returncode == 0 and r.stderr == ""
    assert json.loads(r.stdout)["links"]["2"]["omega"] == 10.0


def test_missing_file_exit_2_one_line_and_a_hint(tmp_path, cli):
    # in this process (a second process until the suite had to fit 2 minutes: 0.4 CPU s); the real process's
    # exit 2 as the shell sees it is test_safety's test_standard_output_that_cannot_be_written_is_exit_2
    r = cli("solve", tmp_path / "fourbar.toml")
    assert r.returncode == 2 and r.stdout == ""
    assert r.stderr.splitlines() == [f"error: {tmp_path / 'fourbar.toml'}: no such file", "hint: check the path"]


def test_bad_toml_exit_2(tmp_path, cli):
    f = tmp_path / "bad.toml"
    f.write_text("[points]\nA = [0, 0\n")
    r = cli("solve", f)
    err = r.stderr.splitlines()
    assert r.returncode == 2 and len(err) == 2 and "Traceback" not in r.stderr
    assert err[0].startswith(f"error: {f}: line 2: bad TOML: ")


def test_singular_pose_exit_3(cli):
    r = cli("solve", DATA / "toggle_fourbar.toml")
    err = r.stderr.splitlines()
    assert r.returncode == 3 and r.stdout == "" and len(err) == 2
    assert "singular" in err[0] and err[0].endswith("(links 3, 4)") and err[1].startswith("hint: ")


def test_near_singular_warning_on_stderr_and_in_the_json(cli):
    r = cli("solve", DATA / "near_toggle.toml", "--json")
    assert r.returncode == 0
    w = json.loads(r.stdout)["warnings"]
    assert r.stderr.splitlines() == [f"warning: {DATA / 'near_toggle.toml'}: {w[0]}"]


def test_debug_shows_the_traceback():
    """The real process prints the traceback and exits 1 (``--debug`` after the command, the other place it is
    read, is test_debug_in_process_raises's: the same parse, in this process; it ran a second process here until
    issue 19 item 7)."""
    r = velpoly_cmd("--debug", "solve", DATA / "toggle_fourbar.toml")
    assert r.returncode == 1
    assert "Traceback (most recent call last)" in r.stderr
    assert "velpoly.errors.SingularPoseError" in r.stderr


def test_debug_in_process_raises(tmp_path):
    with pytest.raises(velpoly.InputError, match="no such file"):
        main(["solve", str(tmp_path / "x.toml"), "--debug"])
    with pytest.raises(velpoly.SingularPoseError):
        main(["--debug", "solve", str(DATA / "dead_centre.toml")])


def test_no_command_exit_2(capsys):
    assert main([]) == 2
    assert "usage: velpoly" in capsys.readouterr().out


def test_unknown_option_is_an_argparse_error(capsys):
    with pytest.raises(SystemExit) as e:
        main(["solve", str(FOURBAR), "--angel", "3"])
    assert e.value.code == 2
    assert "unrecognized arguments: --angel" in capsys.readouterr().err


@pytest.mark.parametrize("value", ["nan", "inf", "-inf"])
def test_a_non_finite_angle_is_an_input_error_about_the_option(capsys, value):
    assert main(["solve", str(FOURBAR), f"--angle={value}"]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2 and err[0].startswith(f"error: {FOURBAR}: --angle: ") and "finite" in err[0]
    assert err[1].startswith("hint: --angle DEG turns a crank driver")   # about the option, not the file


def test_angle_for_a_slider_driver(capsys):
    assert main(["solve", str(DATA / "dead_centre.toml"), "--angle", "10"]) == 2
    err = capsys.readouterr().err.splitlines()
    assert err[0].endswith("--angle: a slider driver has no angle") and err[1] == "hint: a slider driver is placed where the file draws it: leave out the angle"


def test_a_step_too_fine_for_the_memory_is_an_input_error(capsys, tmp_path):
    out = tmp_path / "cycle.csv"
    assert main(["sweep", str(FOURBAR), "--step", "1e-9", "--csv", str(out)]) == 2
    err = capsys.readouterr().err.splitlines()
    assert err == [f"error: {FOURBAR}: --step: the step 1e-09 deg is too fine: 3.6e+11 poses a turn",
                   "hint: use a step of at least 0.001 deg (e.g. --step 0.1)"]
    assert not out.exists()


@pytest.mark.parametrize("exc", [RuntimeError("boom"), ZeroDivisionError("float division by zero"),
                                 KeyError("B"), ValueError("two\nlines")])
def test_unexpected_exceptions_are_one_line_without_traceback(capsys, monkeypatch, exc):
    def broken(*a, **k):
        raise exc
    monkeypatch.setattr(velpoly, "solve", broken)
    assert main(["solve", str(FOURBAR)]) == 1
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2 and "Traceback" not in "".join(err)
    assert err[0].startswith(f"error: {FOURBAR}: internal error: {type(exc).__name__}: ")
    assert err[1] == "hint: this is a bug in velpoly: run again with --debug and report the traceback"
    with pytest.raises(type(exc)):
        main(["solve", str(FOURBAR), "--debug"])


def test_keyboard_interrupt(capsys, monkeypatch):
    def interrupted(*a, **k):
        raise KeyboardInterrupt
    monkeypatch.setattr(velpoly, "load", interrupted)
    assert main(["solve", str(FOURBAR)]) == 130
    assert capsys.readouterr().err == "error: interrupted\n"


def test_kernel_errors_get_their_line(capsys, tmp_path):
    # mobility is the kernel's to find; the command line adds the [links] line to its message
    f = tmp_path / "locked.toml"
    f.write_text(FOURBAR.read_text().replace('3 = { points = ["B", "C"] }', '3 = { points = ["B", "C", "D"] }'))
    assert main(["solve", str(f)]) == 2
    assert capsys.readouterr().err.startswith(f"error: {f}: links (line 11): mobility is 0 ")


def test_output_is_not_read_as_a_figure(capsys, tmp_path):
    out = tmp_path / "fig.txt"
    assert main(["draw", str(FOURBAR), "-o", str(out)]) == 2
    assert capsys.readouterr().err.splitlines()[0] == f"error: {out}: -o: unknown figure type '.txt'"
    assert not out.exists()


def test_a_failed_draw_writes_nothing(capsys, tmp_path):
    out = tmp_path / "figs" / "toggle.svg"
    assert main(["draw", str(DATA / "toggle_fourbar.toml"), "-o", str(out)]) == 3
    assert not out.parent.exists() or list(out.parent.iterdir()) == []


def test_a_failed_sweep_writes_nothing(capsys, tmp_path):
    csv = tmp_path / "cycle.csv"
    code = main(["sweep", str(DATA / "dead_centre.toml"), "--csv", str(csv)])
    assert code == 3, capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("how", ["singular", "crash", "interrupt"])
def test_a_failed_command_leaves_an_existing_output_as_it_was(capsys, tmp_path, monkeypatch, how):
    """An output that exists already is untouched when the command fails, however it fails: a
    singular pose (exit 3), a crash half-way through the drawing (exit 1), Ctrl-C (exit 130)."""
    pytest.importorskip("matplotlib")
    from velpoly.render import sheet
    out, csv = tmp_path / "fig.svg", tmp_path / "cycle.csv"
    out.write_text("the previous figure")
    csv.write_text("the previous table")
    src = DATA / ("toggle_fourbar.toml" if how == "singular" else "fourbar.toml")
    if how != "singular":
        def fail(*a, **kw):
            raise KeyboardInterrupt if how == "interrupt" else RuntimeError("renderer crashed half-way")
        monkeypatch.setattr(sheet, "draw_results_table", fail)
    code = main(["draw", str(src), "-o", str(out), "--sheet", "velocity"])
    assert code == {"singular": 3, "crash": 1, "interrupt": 130}[how]
    if how == "singular":
        assert main(["sweep", str(DATA / "dead_centre.toml"), "--csv", str(csv)]) == 3
    assert "Traceback" not in capsys.readouterr().err
    assert out.read_text() == "the previous figure" and csv.read_text() == "the previous table"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cycle.csv", "fig.svg"]   # no temporary left


def test_broken_pipe_is_quiet():
    p = subprocess.Popen([sys.executable, "-m", "velpoly", "solve", str(DATA / "fourbar.toml"), "--json"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    p.stdout.readline()
    p.stdout.close()
    err = p.stderr.read().decode()
    assert p.wait(timeout=60) == 0 and "Traceback" not in err and "BrokenPipe" not in err


# -- reading never writes ------------------------------------------------------------------------------
def snapshot(folder: Path):
    return {p.name: (hashlib.sha256(p.read_bytes()).hexdigest(), p.stat().st_mtime_ns, stat.S_IMODE(p.stat().st_mode))
            for p in sorted(folder.iterdir())}


@pytest.mark.parametrize("name", ["fourbar.toml", "toggle_fourbar.toml"])
def test_reading_never_modifies_the_input(tmp_path, name, cli):
    f = tmp_path / name
    f.write_bytes((DATA / name).read_bytes())
    os.chmod(f, 0o444)
    before = snapshot(tmp_path)
    velpoly.load(f)
    velpoly.load(str(f))
    r = cli("solve", f, "--json", cwd=tmp_path)
    assert r.returncode in (0, 3)
    assert snapshot(tmp_path) == before
    if name == "fourbar.toml":   # drawing and sweeping read it too, writing elsewhere only
        other = tmp_path.parent / (tmp_path.name + "-out")
        assert main(["sweep", str(f), "--step", "10", "--csv", str(other / "c.csv")]) == 0
        if __import__("importlib").util.find_spec("matplotlib"):   # (drawing itself is test_render's)
            main(["draw", str(f), "-o", str(other / "f.svg"), "--sheet", "velocity"])
        assert snapshot(tmp_path) == before


# -- atomic outputs ---------------------------------------------------------------------------------------
def test_atomic_write_creates_an_ordinary_file(tmp_path):
    out = atomic_write_text(tmp_path / "sub" / "table.txt", "ω = 10 rad/s\n")
    assert out.read_text(encoding="utf-8") == "ω = 10 rad/s\n"
    mask = os.umask(0)
    os.umask(mask)
    assert stat.S_IMODE(out.stat().st_mode) == 0o666 & ~mask
    assert [p.name for p in out.parent.iterdir()] == ["table.txt"]


def test_atomic_write_keeps_an_existing_files_permissions(tmp_path):
    out = tmp_path / "f.svg"
    out.write_text("old")
    os.chmod(out, 0o640)
    atomic_write_bytes(out, b"new")
    assert out.read_bytes() == b"new" and stat.S_IMODE(out.stat().st_mode) == 0o640


@pytest.mark.parametrize("existing", [False, True])
def test_a_failure_while_writing_leaves_no_partial_file(tmp_path, existing):
    out = tmp_path / "figure.svg"
    if existing:
        out.write_text("the previous figure")
    with pytest.raises(RuntimeError, match="renderer crashed"):
        with atomic_path(out) as tmp:
            with open(tmp, "w") as fh:
                fh.write("<svg>half a figure")
            raise RuntimeError("renderer crashed")
    if existing:
        assert out.read_text() == "the previous figure"
        assert [p.name for p in tmp_path.iterdir()] == ["figure.svg"]
    else:
        assert list(tmp_path.iterdir()) == []


def test_a_failure_in_the_rename_leaves_no_temporary_file(tmp_path, monkeypatch):
    out = tmp_path / "data.csv"
    out.write_text("old")

    def full_disk(src, dst):
        raise OSError(28, "No space left on device")
    monkeypatch.setattr(os, "replace", full_disk)
    with pytest.raises(velpoly.InputError, match=f"cannot write {out}: No space left on device"):
        atomic_write_text(out, "new")
    assert [p.name for p in tmp_path.iterdir()] == ["data.csv"] and out.read_text() == "old"


def test_writing_over_a_folder_is_an_input_error(tmp_path):
    (tmp_path / "out.svg").mkdir()
    with pytest.raises(velpoly.InputError, match="is a folder"):
        atomic_write_text(tmp_path / "out.svg", "x")
    assert [p.name for p in tmp_path.iterdir()] == ["out.svg"]


def test_writing_under_a_file_is_an_input_error_naming_it(tmp_path):
    (tmp_path / "out").write_text("a file")
    for target in (tmp_path / "out" / "x.svg", tmp_path / "out" / "sub" / "x.svg"):
        with pytest.raises(velpoly.InputError, match=f"cannot write: '{tmp_path / 'out'}' is a file, not a folder"):
            atomic_write_text(target, "x")
    assert [p.name for p in tmp_path.iterdir()] == ["out"] and (tmp_path / "out").read_text() == "a file"


@pytest.mark.skipif(hasattr(os, "geteuid") and os.geteuid() == 0, reason="root writes anywhere")
def test_an_unwritable_folder_is_an_input_error(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    os.chmod(ro, 0o555)
    try:
        with pytest.raises(velpoly.InputError, match="cannot write"):
            atomic_write_text(ro / "x.txt", "x")
    finally:
        os.chmod(ro, 0o755)


# -- scale --------------------------------------------------------------------------------------------------
def many_points(folder: Path) -> Path:
    """The four-bar with 496 more points on its coupler (500 in all), written to ``folder/many.toml``."""
    extra = [f'P{i} = {{ from = "B", length = {10 + 0.1 * i:.1f}, along = ["B", "C"], turn = {0.7 * i:.1f} }}'
             for i in range(496)]
    text = FOURBAR.read_text().replace("\n[links]", "\n" + "\n".join(extra) + "\n\n[links]")
    text = text.replace('3 = { points = ["B", "C"] }',
                        '3 = { points = ["B", "C", ' + ", ".join(f'"P{i}"' for i in range(496)) + "] }")
    f = folder / "many.toml"
    f.write_text(text)
    return f


def test_a_file_with_500_points(tmp_path, cli):
    f = many_points(tmp_path)
    t0 = time.perf_counter()
    s = velpoly.solve(velpoly.load(f))
    assert time.perf_counter() - t0 < 5.0
    assert len(s.position) == 500
    t0 = time.perf_counter()
    r = cli("solve", f, "--json")
    assert time.perf_counter() - t0 < 10.0
    assert r.returncode == 0, r.stderr
    points = json.loads(r.stdout)["points"]
    assert len(points) == 500
    # a point of the coupler moves with it: V_P = V_B + omega_3 x (P - B)
    w3 = s.omega["3"]
    p, b = s.position["P123"], s.position["B"]
    expected = s.velocity["B"] + w3 * __import__("numpy").array([-(p - b)[1], (p - b)[0]])
    assert points["P123"]["velocity"] == pytest.approx(expected.tolist(), rel=1e-12, abs=1e-9)


# `velpoly solve` importing no matplotlib: test_render's test_kernel_and_solve_do_not_import_matplotlib (a process
# of its own; this file's copy of it, on the four-bar, went in issue 19 item 7)


# -- what `velpoly solve` prints ----------------------------------------------------------------------------
from paths import SIXBAR  # noqa: E402  FORMAT.md section 1's file


def test_json_is_format_section_2(cli):
    """The example of FORMAT.md section 2, value by value, on the file of section 1."""
    r = cli("solve", SIXBAR, "--json")
    assert r.returncode == 0 and r.stderr == ""
    d = json.loads(r.stdout)
    assert list(d)[:4] == ["format", "title", "units", "driver"]
    assert {"links", "points", "sliders", "contacts", "poles", "graphical"} <= set(d)
    assert "slots" not in d and "warnings" not in d        # only for files with slots / poses with warnings
    assert d["format"] == 1 and d["title"] == velpoly.load(SIXBAR).title
    assert d["units"] == {"length": "m"}
    assert d["driver"] == {"link": "1", "angle": pytest.approx(30.0), "omega": pytest.approx(6.283185, abs=1e-6),
                           "alpha": 0.0}
    assert list(d["links"]) == ["0", "1", "2", "3", "4", "5"]
    assert d["links"]["0"]["omega"] == 0.0 and d["links"]["0"]["alpha"] == 0.0
    two = d["links"]["2"]
    assert (two["angle"], two["omega"], two["alpha"]) == (pytest.approx(119.81, abs=5e-3),
                                                          pytest.approx(-1.1307, abs=5e-5), pytest.approx(-22.33, abs=5e-3))
    assert all(-180 < v["angle"] <= 180 for v in d["links"].values())
    assert list(d["points"]) == ["A", "D", "B", "C", "E", "F"]
    c = d["points"]["C"]
    assert c["position"] == pytest.approx([-0.0689445, 0.422073], abs=5e-7)
    assert c["velocity"] == pytest.approx([-0.0788, 1.0410], abs=5e-5)
    assert c["acceleration"] == pytest.approx([2.8760, 1.0357], abs=5e-5)
    (sl,) = d["sliders"]
    assert (sl["block"], sl["guide"], sl["point"]) == ("5", "0", "F")
    assert sl["slip_velocity"] == pytest.approx(1.64625, abs=5e-6)
    assert sl["slip_acceleration"] == pytest.approx(3.29262, abs=5e-6)
    assert sl["coriolis"] == pytest.approx([0.0, 0.0], abs=1e-12)
    assert d["contacts"] == []
    names = list(d["links"])
    assert list(d["poles"]) == [f"{a}-{b}" for i, a in enumerate(names) for b in names[i + 1:]]
    assert d["poles"]["0-1"]["position"] == pytest.approx([0.0, 0.0], abs=1e-12)
    assert d["poles"]["0-5"]["position"] is None and d["poles"]["0-5"]["direction"] == pytest.approx(0.0, abs=1e-9)
    assert set(d["graphical"]["max_error"]) == {"velocity", "acceleration"}
    assert max(d["graphical"]["max_error"].values()) < 1e-9


def test_the_table_shows_each_printed_value_beside_the_computed_one_and_the_deviation(tmp_path, cli):
    r = cli("solve", SIXBAR)
    assert r.returncode == 0 and r.stderr == ""
    part = r.stdout.split("Reference values (Problem 1.4.4 (Fig. 3.19)", 1)[1].split("\n", 1)[1]
    header, rule, *rows = part.strip().splitlines()
    assert header.split()[:4] == ["quantity", "printed", "analytic", "deviation"]
    row = {line.split()[0]: line.split() for line in rows}
    assert row["omega_3"][1:3] == ["-2.82169", "-2.82169"] and row["omega_3"][3].endswith("%")
    assert float(row["omega_3"][3].rstrip("%")) < 1e-3
    assert row["V_F"][1:4] == ["1.64625", "∠", "90.000°"]
    assert "modulo 180" in " ".join(row["theta_2"])          # a note beside its value
    # a wrong printed value shows as a large deviation (6.3 % off)
    f = tmp_path / "wrong.toml"
    f.write_text(SIXBAR.read_text().replace('"3" = -2.82169', '"3" = -3.0'))
    r = cli("solve", f)
    line = next(x for x in r.stdout.split("Reference values")[1].splitlines() if x.startswith("omega_3 "))
    assert line.split()[1:3] == ["-3", "-2.82169"] and float(line.split()[3].rstrip("%")) == pytest.approx(5.94, abs=0.01)


def test_at_another_angle_the_printed_values_are_listed_not_compared(cli):
    """The book's answers belong to the file's pose: at --angle 40 they would be 50 % "off"."""
    r = cli("solve", SIXBAR, "--angle", "40")
    assert r.returncode == 0
    part = r.stdout.split("Reference values (Problem 1.4.4 (Fig. 3.19)", 1)[1].split("\n", 1)[1]
    header, _, first = part.splitlines()[:3]
    assert r.stdout.split("Reference values (", 1)[1].split("\n", 1)[0].endswith(
        ": printed for the file's pose (driver at 30 deg), not compared at 40 deg")
    assert header.split() == ["quantity", "printed", "note"] and first.split() == ["omega_1", "6.28319"]
    assert "%" not in part


def test_an_error_without_a_hint_gets_one_for_what_it_is_about(capsys, monkeypatch):
    cases = [(velpoly.InputError("not a folder", where="--source", file="g"),
              "check the option --source (velpoly solve --help lists the options)"),
             (velpoly.InputError("bad", where="points.B", file="f"), "check the file against the format in the README"),
             (velpoly.SingularPoseError("singular", where="reference pose", file="f", links=("3", "4")),
              "choose another driver angle, or draw the mechanism in another pose")]
    for err, hint in cases:
        def raise_it(args, err=err):
            raise err
        monkeypatch.setitem(velpoly.cli.COMMANDS, "solve", raise_it)
        assert main(["solve", "f"]) == err.exit_code
        assert capsys.readouterr().err.splitlines() == [f"error: {err.line()}", f"hint: {hint}"]


def test_the_package_metadata():
    """PEP 621 metadata as installed: the console script, the dependencies and the test extra."""
    import importlib.metadata as md
    import re as re_
    import shutil
    import tomllib
    project = tomllib.loads((Path(__file__).resolve().parent.parent / "pyproject.toml").read_text())["project"]
    assert project["name"] == "velpoly" and project["scripts"] == {"velpoly": "velpoly.cli:main"}
    dist = md.distribution("velpoly")
    assert [(e.name, e.value) for e in dist.entry_points if e.group == "console_scripts"] == \
        [("velpoly", "velpoly.cli:main")]
    names = {re_.split(r"[<>=;\s\[]", r, maxsplit=1)[0]: r for r in dist.requires}
    assert {"numpy", "matplotlib", "shapely"} <= {n for n, r in names.items() if "extra ==" not in r}
    assert {"pytest", "hypothesis"} <= {n for n, r in names.items() if 'extra == "test"' in r}
    exe = shutil.which("velpoly")
    if exe:   # the installed script runs the same main
        r = subprocess.run([exe, "--version"], capture_output=True, text=True, timeout=60)
        assert r.returncode == 0 and r.stdout.startswith("velpoly ")
