"""Never lose a file, never crash on a name (issue 14): outputs that are inputs, special files, write
errors, signals, the gallery's folder, names drawn as mathtext, memory and nesting, API arguments.

The file-safety cases run on real FIFOs, /dev/full, a read-only folder (as root: in a subprocess without
the capability that lets root write anywhere) and subprocesses receiving SIGINT and SIGTERM.
"""
from __future__ import annotations

import gc
import os
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import pytest

import velpoly
from velpoly.cli import main
from velpoly.fileio import atomic_write_text
from paths import example

DATA = Path(__file__).parent / "data"
FOURBAR = DATA / "fourbar.toml"
ROOT = Path(__file__).resolve().parents[1]


def velpoly_cmd(*args, cwd=None, env=None, **kw):
    e = dict(os.environ, PYTHONPATH=str(ROOT), **(env or {}))
    return subprocess.run([sys.executable, "-m", "velpoly", *map(str, args)], text=True, timeout=120, cwd=cwd,
                          env=e, **({"stdout": subprocess.PIPE, "stderr": subprocess.PIPE} | kw))


def copy_fourbar(folder: Path, name="m.toml") -> Path:
    f = folder / name
    f.write_bytes(FOURBAR.read_bytes())
    return f


# -- 1. an output is never its own input ----------------------------------------------------------------
@pytest.mark.parametrize("how", ["same", "hard link", "symlink", "relative"])
@pytest.mark.parametrize("option", ["--csv", "-o", "--gif"])
def test_an_output_that_is_the_input_is_exit_2_naming_the_option(tmp_path, capsys, monkeypatch, how, option):
    f = copy_fourbar(tmp_path, "m.gif" if option == "--gif" else "m.svg" if option == "-o" else "m.toml")
    before = f.read_bytes()
    out = {"same": f, "relative": Path(f.name)}.get(how)
    monkeypatch.chdir(tmp_path)
    if how == "hard link":
        out = tmp_path / ("h" + f.suffix)
        os.link(f, out)
    elif how == "symlink":
        out = tmp_path / ("s" + f.suffix)
        out.symlink_to(f)
    assert main(["sweep", str(f), option, str(out)]) == 2
    err = capsys.readouterr().err.splitlines()
    assert err[0] == (f"error: {f}: {option}: the output {str(out)!r} is the input file: "
                      "an output never replaces its input")
    assert err[1] == f"hint: give {option} another file name"
    assert f.read_bytes() == before and sorted(p.name for p in tmp_path.iterdir()) == sorted(
        {f.name} | ({out.name} if how in ("hard link", "symlink") else set()))


def test_draw_s_default_output_that_is_the_input_is_exit_2(tmp_path, capsys, monkeypatch):
    f = copy_fourbar(tmp_path, "mech.svg")      # a mechanism file whose name ends in .svg
    monkeypatch.chdir(tmp_path)
    assert main(["draw", "mech.svg"]) == 2
    err = capsys.readouterr().err.splitlines()
    assert err[0] == "error: mech.svg: -o: the default output 'mech.svg' is the input file: an output never replaces its input"
    assert err[1] == "hint: give the output's name with -o OUT"
    assert f.read_bytes() == FOURBAR.read_bytes()


def test_no_writer_replaces_an_input_of_the_run(tmp_path, capsys, monkeypatch):
    """The backstop in the writer itself: a derived name (a numbered step frame) that is the input."""
    f = copy_fourbar(tmp_path, "frame-01.svg")
    from velpoly.fileio import protect_input, forget_inputs
    protect_input(f)
    try:
        with pytest.raises(velpoly.InputError, match="is the input file"):
            atomic_write_text(tmp_path / "frame-01.svg", "<svg/>")
    finally:
        forget_inputs()
    assert f.read_bytes() == FOURBAR.read_bytes()


# -- 2. special files are written through, never replaced; write errors are exit 2 ---------------------
def test_a_fifo_output_is_written_into_not_replaced(tmp_path, capsys):
    fifo = tmp_path / "cycle.csv"
    os.mkfifo(fifo)
    got = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_bytes()), daemon=True)
    reader.start()
    assert main(["sweep", str(FOURBAR), "--step", "10", "--csv", str(fifo)]) == 0
    reader.join(timeout=60)
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)                       # still a FIFO
    assert got and got[0].decode().startswith("driver,") and len(got[0].decode().splitlines()) == 37
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cycle.csv"]   # no temporary file beside it


def test_a_device_output_is_written_into(tmp_path, capsys):
    assert main(["sweep", str(FOURBAR), "--step", "30", "--csv", "/dev/null"]) == 0
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)
    assert not list(Path("/dev").glob(".null.*.part"))


def test_no_space_on_a_device_is_exit_2_cannot_write(capsys):
    assert main(["sweep", str(FOURBAR), "--step", "30", "--csv", "/dev/full"]) == 2
    err = capsys.readouterr().err.splitlines()
    assert err[0] == f"error: {FOURBAR}: cannot write /dev/full: No space left on device"
    assert stat.S_ISCHR(os.stat("/dev/full").st_mode)


def test_standard_output_that_cannot_be_written_is_exit_2():
    with open("/dev/full", "w") as full:
        r = velpoly_cmd("solve", FOURBAR, "--json", stdout=full, stderr=subprocess.PIPE)
    assert r.returncode == 2
    assert r.stderr.splitlines() == [
        f"error: {FOURBAR}: cannot write standard output: No space left on device",
        "hint: check where the output is redirected (a full disk, a read-only file)"]


def _without_root_s_override():
    """A prefix running a command subject to file permissions, even as root."""
    if os.geteuid() != 0:
        return []
    if shutil.which("setpriv") is None:
        pytest.skip("root writes anywhere, and setpriv is not there to drop that")
    return ["setpriv", "--bounding-set=-dac_override,-dac_read_search"]


def test_a_read_only_folder_is_exit_2_cannot_write(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    f = copy_fourbar(tmp_path)
    os.chmod(ro, 0o555)
    try:
        r = subprocess.run([*_without_root_s_override(), sys.executable, "-m", "velpoly", "sweep", str(f),
                            "--step", "30", "--csv", str(ro / "c.csv")], capture_output=True, text=True,
                           timeout=120, env=dict(os.environ, PYTHONPATH=str(ROOT)))
    finally:
        os.chmod(ro, 0o755)
    assert r.returncode == 2, r.stderr
    assert r.stderr.splitlines()[0] == f"error: {f}: cannot write {ro / 'c.csv'}: Permission denied"
    assert list(ro.iterdir()) == []


def test_a_symlink_output_replaces_the_file_it_names_and_stays_a_link(tmp_path, capsys):
    real = tmp_path / "real.csv"
    real.write_text("old")
    link = tmp_path / "link.csv"
    link.symlink_to(real)
    assert main(["sweep", str(FOURBAR), "--step", "30", "--csv", str(link)]) == 0
    assert link.is_symlink() and real.read_text().startswith("driver,")


# -- 7. signals --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("sig, code, word", [(signal.SIGTERM, 143, "terminated"), (signal.SIGINT, 130, "interrupted")])
def test_a_signal_during_the_gif_leaves_nothing_behind(tmp_path, sig, code, word):
    """SIGTERM or Ctrl-C while the GIF writer works in its temporary file: exit 130/143, one line, no
    traceback, no temporary folder or file, no output."""
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    out = tmp_path / "out"
    out.mkdir()
    env = dict(os.environ, PYTHONPATH=str(ROOT), TMPDIR=str(tmp))
    p = subprocess.Popen([sys.executable, "-m", "velpoly", "sweep", str(FOURBAR), "--step", "5", "--gif",
                          str(out / "cycle.gif")], stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    try:
        deadline = time.monotonic() + 90
        def writing():   # the GIF's temporary file (beside the output) or folder (in TMPDIR) is there
            return list(tmp.iterdir()) or list(out.iterdir())
        while not writing() and p.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)
        assert writing(), "the GIF writer's temporary file never appeared"
        time.sleep(0.05)     # at its first frames (0.3 s until the suite had to fit 2 minutes); a signal as the
        p.send_signal(sig)   # temporary file is made: test_a_signal_as_the_temporary_file_is_made_leaves_nothing
        _, err = p.communicate(timeout=60)
    finally:
        if p.poll() is None:
            p.kill()
    err = err.decode()
    assert p.returncode == code and err.strip().splitlines()[-1] == f"error: {word}", err
    assert "Traceback" not in err and "Exception ignored" not in err
    assert list(tmp.iterdir()) == [] and list(out.iterdir()) == []


@pytest.mark.parametrize("special", [False, True], ids=["beside-the-output", "straight-through"])
def test_a_signal_as_the_temporary_file_is_made_leaves_nothing(tmp_path, monkeypatch, special):
    """Ctrl-C arriving just as an output's temporary file is made (the moment the file exists, before the call
    that made it returns) leaves no file: ``os.open`` here sends SIGINT to this process itself right after it
    creates a ``.part`` file, and gives Python time to run the handler before it returns. With
    ``tempfile.mkstemp``, which returns the name only after the file exists, the .part file stayed (both cases
    fail so). A special target (/dev/null) is written through a temporary file of its own, in the temporary
    folder."""
    made = []
    real = os.open

    def open_(path, flags, *mode, **kw):
        fd = real(path, flags, *mode, **kw)
        if str(path).endswith(".part"):
            made.append(str(path))
            os.kill(os.getpid(), signal.SIGINT)
            for _ in range(10_000):   # the handler runs here
                pass
        return fd

    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    monkeypatch.setattr(os, "open", open_)
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt):
            atomic_write_text("/dev/null" if special else tmp_path / "out" / "a.txt", "x")
    finally:
        signal.signal(signal.SIGINT, old)
    assert len(made) == 1 and not os.path.exists(made[0])
    assert [p.name for p in tmp_path.rglob("*") if p.is_file()] == []


@pytest.fixture
def heap_frozen():
    """The objects the worker holds before the test (the shared pages, specimens and sweeps of the tests before it)
    frozen for the test (:func:`gc.freeze`), so that its ``gc.collect()`` walks only what the test makes: the
    swallowed-interrupt tests below took 1.2-2.2 CPU s each in the suite, walking the heap the others left, 0.1
    alone. What they check (an interrupt raised in a ``__del__`` of an object made in the test) is the same.
    They stay frozen after it, as what the collection left does (tests/conftest.py): ``gc.unfreeze`` here put
    the worker's whole heap back, conftest's frozen 150 000 objects with it, for every later full collection
    to walk again (test_suite_rules checks that no test unfreezes)."""
    gc.freeze()
    yield


class _InterruptOnCollect:
    """Raises KeyboardInterrupt where Python can only ignore it (as in a matplotlib weakref callback)."""

    def __del__(self):
        raise KeyboardInterrupt


def test_a_ctrl_c_swallowed_in_a_callback_still_stops_the_run(tmp_path, capsys, monkeypatch, heap_frozen):
    out = tmp_path / "c.csv"

    def command(args):
        _InterruptOnCollect()   # its __del__ runs now: the interrupt is "ignored" by Python
        gc.collect()
        atomic_write_text(out, "a table")   # the run must not commit its output after that
        return 0
    _stops(monkeypatch, capsys, tmp_path, command, 130, "interrupted")


def _stops(monkeypatch, capsys, tmp_path, command, code, word):
    """``velpoly solve`` running ``command`` returns ``code`` with the one line "error: WORD" and writes nothing."""
    monkeypatch.setitem(velpoly.cli.COMMANDS, "solve", command)
    assert main(["solve", str(FOURBAR)]) == code
    err = capsys.readouterr().err
    assert err.splitlines() == [f"error: {word}"] and "Exception ignored" not in err
    assert list(tmp_path.iterdir()) == []


class _TerminateOnCollect:
    """Raises SIGTERM's exception where Python can only ignore it (the GIF writer's callbacks under load)."""

    def __del__(self):
        raise velpoly.cli.Terminated


@pytest.mark.parametrize("late", [False, True])
def test_a_sigterm_swallowed_in_a_callback_is_still_a_termination(tmp_path, capsys, monkeypatch, late,
                                                                   heap_frozen):
    """SIGTERM whose exception a callback swallowed: exit 143 and "error: terminated", not Ctrl-C's 130 (a
    run terminated under load once reported "interrupted"), whether the run ends by raising the recorded
    interruption or by an error raised while unwinding from it (``late``); a Ctrl-C after it does not
    change which signal stopped the run."""
    out = tmp_path / "c.csv"

    def command(args):
        _TerminateOnCollect()
        gc.collect()
        if late:
            _InterruptOnCollect()
            gc.collect()
            raise RuntimeError("a library's cleanup failing on its half-done work")
        atomic_write_text(out, "a table")
        return 0
    _stops(monkeypatch, capsys, tmp_path, command, 143, "terminated")


@pytest.mark.parametrize("how", ["raised", "swallowed"])
def test_after_an_interrupted_run_python_goes_on_writing(tmp_path, capsys, monkeypatch, how, heap_frozen):
    """``cli.main([...])`` called from Python and interrupted returns 130; the interruption belongs to that
    run only: the caller's next file written through the API is written (it raised KeyboardInterrupt, a
    worker of the test suite was stopped by it)."""
    def command(args):
        if how == "raised":
            raise KeyboardInterrupt
        _InterruptOnCollect()
        gc.collect()
        return 0
    monkeypatch.setitem(velpoly.cli.COMMANDS, "solve", command)
    assert main(["solve", str(FOURBAR)]) == 130
    capsys.readouterr()
    atomic_write_text(tmp_path / "after.txt", "written")
    assert (tmp_path / "after.txt").read_text() == "written"


# -- 8. the Python API: every wrong argument is a VelpolyError that is a TypeError or ValueError ------------
import numpy as np
from hypothesis import HealthCheck, given, settings, strategies as st

import texts

M = velpoly.load(FOURBAR)


def _api_error(fn, *a, **k) -> velpoly.VelpolyError:
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")          # no numpy warning leaks
        try:
            fn(*a, **k)
        except velpoly.VelpolyError as e:
            assert isinstance(e, (TypeError, ValueError)), type(e)
            return e
    raise AssertionError(f"no error for {a} {k}")


@pytest.mark.parametrize("call, where, gist", [
    (lambda: velpoly.solve(None), "m", "expected a velpoly.Mechanism, got None"),
    (lambda: velpoly.solve("f.toml"), "m", "got the string 'f.toml'"),
    (lambda: velpoly.solve({"points": {}}), "m", "got a dict"),
    (lambda: velpoly.sweep(None, [30.0]), "m", "got None"),
    (lambda: velpoly.solve(M, angle="30"), "angle", "got the string '30'"),
    (lambda: velpoly.solve(M, angle=[30]), "angle", "got a list"),
    (lambda: velpoly.solve(M, angle=True), "angle", "got the boolean True"),
    (lambda: velpoly.solve(M, angle=1 + 0j), "angle", "got a complex number"),
    (lambda: velpoly.solve(M, angle=np.array([30.0])), "angle", "got an array of shape (1,)"),
    (lambda: velpoly.solve(M, angle=float("nan")), "angle", "must be finite"),
    # an int beyond any float is too large, written as %g writes a float (main b313165: its 401 digits)
    (lambda: velpoly.solve(M, angle=10 ** 400), "angle", "the driver angle 1e+400 deg is too large (at most 1e+06"),
    (lambda: velpoly.solve(M, angle=-(10 ** 400) // 3), "angle", "the driver angle -3.33333e+399 deg is too large"),
    (lambda: velpoly.solve(M, angle=10 ** 6 + 1), "angle", "the driver angle 1000001 deg is too large (at most 1e+06"),
    (lambda: velpoly.sweep(M, "abc"), "angles", "got the string 'abc'"),
    (lambda: velpoly.sweep(M, [[60, 61], [62]]), "angles", "rows of different lengths"),
    (lambda: velpoly.sweep(M, (a for a in (60.0, 61.0))), "angles", "got a generator"),
    (lambda: velpoly.sweep(M, 60.0), "angles", "got a float"),
    (lambda: velpoly.sweep(M, np.ones((2, 3))), "angles", "got shape (2, 3)"),
    (lambda: velpoly.sweep(M, np.array([60 + 1j, 61])), "angles", "got complex numbers"),
    (lambda: velpoly.sweep(M, [True, False]), "angles", "got booleans"),
    (lambda: velpoly.sweep(M, [60, "61"]), "angles", "got strings"),
    (lambda: velpoly.sweep(M, [60, None]), "angles", "got None"),
    (lambda: velpoly.sweep(M, [60, float("inf")]), "angles", "finite"),
    (lambda: velpoly.load(None), "source", "cannot load a NoneType"),
    (lambda: velpoly.loads(3), "text", "expected TOML text"),
])
def test_a_wrong_api_argument_is_a_velpoly_error_naming_it(call, where, gist):
    e = _api_error(call)
    assert e.where == where and gist in e.what, (e.where, e.what)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.one_of(st.booleans(), texts.text(max_size=5), st.complex_numbers(), st.binary(max_size=3),
                 st.lists(st.floats(), max_size=3), st.dictionaries(texts.text(max_size=2), st.integers(), max_size=2),
                 st.floats(allow_nan=True, allow_infinity=True).filter(lambda x: not np.isfinite(x))))
def test_fuzz_solve_s_angle(angle):
    e = _api_error(velpoly.solve, M, angle=angle)
    assert e.where == "angle"


_reals = st.one_of(st.floats(-720, 720), st.integers(-720, 720))
_bad_element = st.one_of(st.none(), st.booleans(), texts.text(min_size=1, max_size=3), st.complex_numbers(),
                         st.floats(allow_nan=True, allow_infinity=True).filter(lambda x: not np.isfinite(x)),
                         st.lists(_reals, min_size=2, max_size=2))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(_reals, max_size=4), _bad_element, st.integers(0, 4),
       st.sampled_from(["list", "tuple", "array"]))
def test_fuzz_sweep_s_angles(good, bad, at, container):
    angles = list(good)
    angles.insert(min(at, len(angles)), bad)
    if container == "tuple":
        angles = tuple(angles)
    elif container == "array":
        try:
            angles = np.array(angles, dtype=object)
        except ValueError:
            return
    e = _api_error(velpoly.sweep, M, angles)
    assert e.where == "angles"


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.floats(0.0, 30.0), min_size=1, max_size=5), st.sampled_from(["list", "tuple", "array", "f32"]))
def test_fuzz_good_angles_sweep_as_floats_do(offsets, container):
    angles = [60.0 + x for x in offsets]
    given_ = {"list": angles, "tuple": tuple(angles), "array": np.array(angles),
              "f32": [np.float32(a) for a in angles]}[container]
    w, ref = velpoly.sweep(M, given_), velpoly.sweep(M, np.array(angles, dtype=np.float32 if container == "f32" else float))
    assert np.array_equal(w.angles, ref.angles) and np.array_equal(w.omega["3"], ref.omega["3"])


def test_numpy_scalar_angles_are_numbers():
    for a in (np.float64(70), np.float32(70), np.int64(70), np.array(70.0), 70):
        assert velpoly.solve(M, angle=a).driver_angle == 70.0


def _fourbar_dict():
    import tomllib
    return tomllib.loads(FOURBAR.read_text())


def test_load_accepts_tuples_and_numpy_scalars_and_leaves_the_dict_alone():
    d = _fourbar_dict()
    d["points"] = {"A": (np.float64(0), np.int64(0)), "D": np.array([100.0, 0.0]),
                   "B": {"from": "A", "length": np.float32(40), "angle": np.int32(60)},
                   "C": {"circles": (("B", 120), ("D", np.float64(80))), "near": (90, 80)}}
    d["links"] = {np.int64(1): {"points": ("A", "D"), "frame": np.bool_(True)}, "2": {"points": ["A", "B"]},
                  "3": {"points": ("B", "C")}, "4": {"points": ["D", "C"]}}
    before = repr(d)
    s, ref = velpoly.solve(velpoly.load(d)), velpoly.solve(velpoly.load(_fourbar_dict()))
    assert s.to_dict() == {**ref.to_dict(), "source": "<dict>"} or s.omega == ref.omega
    assert s.omega == ref.omega and repr(d) == before


def test_loads_and_load_of_text():
    text = FOURBAR.read_text()
    assert velpoly.loads(text).title == velpoly.load(text).title == "Crank-rocker four-bar"   # a newline: text
    with pytest.raises(velpoly.InputError) as e:
        velpoly.load("[points]")                          # one line: a file's name, and not one
    assert e.value.what == "no such file: this is TOML text, not a file's name" and "velpoly.loads(text)" in e.value.hint
    with pytest.raises(velpoly.InputError, match=r"points \(line 1\): no points"):
        velpoly.loads("[points]")                         # loads reads it as text
    assert velpoly.loads(text.encode()).title == "Crank-rocker four-bar"


# -- 6. nesting and memory ---------------------------------------------------------------------------------
@pytest.mark.parametrize("text, where", [
    ("format = 1\n[points]\nA = " + "[" * 3000 + "0" + "]" * 3000 + "\n", "points.A (line 3)"),
    ("[points]\nA = " + "{b = " * 3000 + "1" + "}" * 3000 + "\n", "points.A (line 2)"),
    ("[" + ".".join(["points"] + ["x"] * 5000) + "]\n", "points.x.x.x.x.x..."),
    ("[drawing]\nq = " + "[" * 40 + "]" * 40 + "\n", "drawing.q[0][0][0][0]..."),
])
def test_deep_nesting_is_exit_2_naming_the_entry(tmp_path, capsys, text, where):
    f = tmp_path / "deep.toml"
    f.write_text(text)
    assert main(["solve", str(f)]) == 2
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith(f"error: {f}: {where}") and err[0].endswith("nested more than 32 levels deep"), err


def test_a_deep_dict_is_an_input_error():
    deep = cur = {}
    for _ in range(5000):
        cur["a"] = cur = {}
    with pytest.raises(velpoly.InputError, match=r"points\.a\.a\.a\.a\.a\.\.\.: nested more than 32 levels deep"):
        velpoly.load({"points": deep})


# -- 5 and 9. names and [drawing] checked on load -------------------------------------------------------------
@pytest.mark.parametrize("name", ["A\nx", "A\tB", "A\x7f", "A\x85", "A\u2028B", "\x00"])
def test_a_name_with_a_control_character_is_exit_2(tmp_path, capsys, name):
    import json
    f = tmp_path / "c.toml"
    f.write_text(FOURBAR.read_text().replace('"C"', json.dumps(name)).replace("\nC = ", f"\n{json.dumps(name)} = "))
    assert main(["solve", str(f)]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2 and err[0].endswith("a point's name must not contain control characters") and "(line 9)" in err[0]


@pytest.mark.parametrize("drawing, gist", [("scal = 1", "unknown drawing option 'scal'"),
                                           ("scale = -1", "expected a positive number"),
                                           ('label_points = ["Z"]', "unknown point 'Z'"),
                                           ('link_numbers = "roman"', "expected one of circled, plain, none")])
def test_drawing_keys_are_checked_on_load(tmp_path, capsys, drawing, gist):
    f = tmp_path / "d.toml"
    f.write_text(FOURBAR.read_text() + f"\n[drawing]\n{drawing}\n")
    for command in ("solve", "draw"):
        assert main([command, str(f), *(["-o", str(tmp_path / "x.svg")] if command == "draw" else [])]) == 2
        err = capsys.readouterr().err.splitlines()
        assert gist in err[0] and "(line 23)" in err[0], err
    assert not (tmp_path / "x.svg").exists()


# -- 6. memory: a sweep's estimate is checked before anything is allocated ---------------------------------
def _many_points(tmp_path) -> Path:
    sys.path.insert(0, str(Path(__file__).parent))
    from test_cli import many_points
    return many_points(tmp_path)


def test_a_sweep_beyond_the_memory_budget_is_exit_2_naming_step_and_poses(tmp_path, capsys):
    f = _many_points(tmp_path)
    out = tmp_path / "c.csv"
    t0 = time.perf_counter()
    assert main(["sweep", str(f), "--step", "0.001", "--csv", str(out)]) == 2
    assert time.perf_counter() - t0 < 10        # refused before the work, not after
    err = capsys.readouterr().err.splitlines()
    assert err[0] == "velpoly sweep: --step 0.001 deg computes up to 360000 poses"
    assert err[1].startswith(f"error: {f}: --step: 360000 poses would need about ")
    assert err[1].endswith("GB, beyond the sweep's memory budget of 2 GB")
    assert err[2].startswith("hint: use a coarser --step: ") and not out.exists()


def test_the_memory_estimate_bounds_the_measured_peak():
    """The estimate is at least the peak tracemalloc measures, and not wildly above it."""
    import tracemalloc
    from velpoly.sweeps import memory_estimate
    sys.path.insert(0, str(Path(__file__).parent))
    from test_branch import chain
    m = velpoly.load(chain(6))
    n = 2000
    tracemalloc.start()
    try:
        w = velpoly.sweep(m, 70 + np.arange(n) * 360 / n)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    est = memory_estimate(m, w.kinematics, n)
    assert len(w.angles) == n and peak <= est <= 1.6 * peak, (peak, est)


def test_the_api_sweep_checks_its_budget(monkeypatch):
    import velpoly.sweeps
    monkeypatch.setattr(velpoly.sweeps, "MEMORY_BUDGET", 100_000)
    with pytest.raises(velpoly.InputError, match=r"^.*angles: 1000 poses would need about .* GB, beyond"):
        velpoly.sweep(M, 60 + np.arange(1000) * 0.1)
    assert len(velpoly.sweep(M, 60 + np.arange(10) * 0.1).angles) == 10


# -- 3. the gallery writes only into its own folder ------------------------------------------------------
def _gallery_source(tmp_path) -> Path:
    src = tmp_path / "mine"
    src.mkdir()
    shutil.copy(example("ex3_6_fourbar"), src / "ex3_6_fourbar.toml")
    return src


def _fake_draw(monkeypatch):
    import velpoly.gallery
    from velpoly.fileio import atomic_write_bytes

    def draw(sol, out, sheet="full", style="textbook", steps=False):
        return [atomic_write_bytes(out, b"x")]
    monkeypatch.setattr(velpoly.gallery, "_draw_to_file", lambda: draw)


@pytest.mark.parametrize("where", ["source", "-o"])
def test_the_gallery_never_writes_over_a_user_s_readme(tmp_path, capsys, monkeypatch, where):
    _fake_draw(monkeypatch)
    src = _gallery_source(tmp_path)
    target = src if where == "source" else tmp_path / "site"
    target.mkdir(exist_ok=True)
    (target / "README.md").write_text("# My notes\n")
    (target / "figures").mkdir()
    (target / "figures" / "ex3_6_fourbar.png").write_bytes(b"my own figure")
    argv = ["gallery", "--source", str(src)] + (["-o", str(target)] if where == "-o" else [])
    assert main(argv) == 2
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith(f"error: {target}: the folder is not velpoly's gallery")
    assert err[1] == "hint: give -o a new or empty folder (velpoly gallery --source DIR -o OUT)"
    assert (target / "README.md").read_text() == "# My notes\n"
    assert (target / "figures" / "ex3_6_fourbar.png").read_bytes() == b"my own figure"


def test_a_folder_of_examples_alone_needs_o(tmp_path, capsys, monkeypatch):
    _fake_draw(monkeypatch)
    src = _gallery_source(tmp_path)
    assert main(["gallery", "--source", str(src)]) == 2
    assert sorted(p.name for p in src.iterdir()) == ["ex3_6_fourbar.toml"]
    assert main(["gallery", "--source", str(src), "-o", str(tmp_path / "new")]) == 0   # a new folder: built
    readme = (tmp_path / "new" / "README.md").read_text()
    assert readme.splitlines()[0] == "<!-- generated by velpoly gallery -->"
    # velpoly's own gallery folder is rebuilt in place, again and again
    shutil.copy(src / "ex3_6_fourbar.toml", tmp_path / "new")
    assert main(["gallery", "--source", str(tmp_path / "new")]) == 0
    empty = tmp_path / "empty"
    empty.mkdir()
    assert main(["gallery", "--source", str(src), "-o", str(empty)]) == 0
    assert (empty / "figures" / "ex3_6_fourbar.png").read_bytes() == b"x"


def test_the_repository_gallery_readme_carries_the_mark():
    assert (ROOT / "gallery" / "README.md").read_text().splitlines()[0] == "<!-- generated by velpoly gallery -->"


# -- 5. every user string is drawn as written, never read as mathtext -----------------------------------------
NASTY_POINTS = ["$B$", "\\frac{a}", "x_{y}^z\\", "$\\sqrt{$"]     # for A, D, B, C of the four-bar
NASTY_LINKS = ["$3$", "\\", "{", "%#&~ 1"]                         # for links 1, 2, 3, 4
NASTY_TITLE = "$\\sqrt{$ title \\frac{a} $x$"
NASTY_UNITS = "$\\sqrt{$"


def _nasty_text() -> str:
    import json
    t = FOURBAR.read_text()
    for old, new in zip(["A", "D", "B", "C"] + ["1", "2", "3", "4"], NASTY_POINTS + NASTY_LINKS):
        t = t.replace(f'"{old}"', json.dumps(new)).replace(f"\n{old} = ", f"\n{json.dumps(new)} = ")
    return (t.replace('title = "Crank-rocker four-bar"', f"title = {json.dumps(NASTY_TITLE)}")
             .replace('units = "mm"', f"units = {json.dumps(NASTY_UNITS)}"))


def _shown(fig) -> list[str]:
    """What every Text of the figure shows: mathtext parsed to its glyphs (spaces are not glyphs), plain
    text with its escaped dollars. A text mathtext cannot parse fails here, as it would in savefig."""
    from matplotlib import cbook
    from matplotlib.mathtext import MathTextParser
    from matplotlib.text import Text
    parser = MathTextParser("path")
    out = []
    for t in fig.findobj(Text):
        s = t.get_text()
        for line in s.split("\n"):
            if cbook.is_math_text(line):
                out.append("".join(chr(g[2]) for g in parser.parse(line, dpi=72).glyphs))
            else:
                out.append(line.replace(r"\$", "$"))
    return out


def _appears(name: str, shown: list[str]) -> bool:
    squeeze = name.replace(" ", "")
    return any(name in s or squeeze in s.replace(" ", "") for s in shown)


def test_names_titles_and_units_are_drawn_as_written():
    from velpoly.render.sheet import render_sheet
    from velpoly.render.style import get_style, rc_context
    m = velpoly.loads(_nasty_text())
    sol = velpoly.solve(m)
    with rc_context(get_style("textbook")):
        for sheet in ("full", "poles"):
            shown = _shown(render_sheet(sol, sheet))
            for name in NASTY_POINTS + [NASTY_TITLE, NASTY_UNITS, "\\", "%#&~ 1"]:
                assert _appears(name, shown), (sheet, name)
            assert sheet != "full" or _appears("$\\sqrt{$/s", shown)      # a unit of velocity


def test_names_are_drawn_as_written_in_the_cycle_plots():
    from velpoly.centrodes import centrodes
    from velpoly.render.sweep import cycle_figure
    from velpoly.sweeps import run_cycle
    m = velpoly.loads(_nasty_text())
    sw = run_cycle(m, 15.0)
    shown = _shown(cycle_figure(sw, cen=centrodes(sw, "{")))
    # a curve's label is typeset (velpoly.names): V or omega with the user's name, as written, as its subscript
    for name in NASTY_POINTS + [NASTY_TITLE, "x ($\\sqrt{$)", "|Vx_{y}^z\\|", "ω%#&~ 1", "link {"]:
        assert _appears(name, shown), name


def test_angles_beyond_reason_are_refused_before_any_walk():
    e = _api_error(velpoly.sweep, M, [60.0, 1e20])
    assert e.where == "angles" and "too large (at most 1e+06 deg either way)" in e.what
    e = _api_error(velpoly.solve, M, angle=1e308)
    assert e.where == "angle" and "too large" in e.what
    e = _api_error(velpoly.sweep, M, [0.0, 9e5] * 3000)     # each gap walked: about 9e8 poses
    assert e.what.startswith("6000 poses (and ") and "more walked between them" in e.what


def test_a_terminal_output_is_written_into(capsys):
    """A pseudo-terminal given as an output (its path is under /dev): written through, never replaced."""
    master, slave = os.openpty()
    try:
        name = os.ttyname(slave)
        got = []

        def read():
            data = b""
            while b"\n60," not in data and len(data) < 10 ** 6:
                data += os.read(master, 65536)
            got.append(data)
        reader = threading.Thread(target=read, daemon=True)
        reader.start()
        assert main(["sweep", str(FOURBAR), "--step", "30", "--csv", name]) == 0
        reader.join(timeout=30)
        assert stat.S_ISCHR(os.stat(name).st_mode) and got and got[0].startswith(b"driver,")
    finally:
        os.close(master)
        os.close(slave)


def test_ctrl_c_during_draw_is_exit_130_and_leaves_nothing(tmp_path):
    f = copy_fourbar(tmp_path)
    p = subprocess.Popen([sys.executable, "-m", "velpoly", "draw", str(f), "--steps", "-o", str(tmp_path / "s.pdf")],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=dict(os.environ, PYTHONPATH=str(ROOT)))
    time.sleep(1.0)   # importing, solving or drawing: wherever it is, Ctrl-C stops it
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=60)
    assert p.returncode == 130, err
    assert err.decode().splitlines() == ["error: interrupted"]
    assert sorted(x.name for x in tmp_path.iterdir()) == ["m.toml"]


def test_ctrl_c_inside_code_compiled_from_text_still_exits_130(tmp_path):
    """A Ctrl-C that leaves code Python compiled from text (a dataclass's ``__init__`` being made, as in
    any import) is noted by CPython as unhandled even when velpoly handles it; without clearing that note
    the program is killed by SIGINT at exit (status -2, seen under load) instead of exiting 130."""
    f = copy_fourbar(tmp_path)
    (tmp_path / "ctrl_c_in_text.py").write_text(   # run as `python -m velpoly` runs (runpy)
        "import sys, velpoly.cli as cli\n"
        "cli.COMMANDS['solve'] = lambda args: exec('raise KeyboardInterrupt')\n"
        f"sys.exit(cli.main(['solve', {str(f)!r}]))\n")
    p = subprocess.run([sys.executable, "-m", "ctrl_c_in_text"], capture_output=True, timeout=60,
                       env=dict(os.environ, PYTHONPATH=os.pathsep.join((str(ROOT), str(tmp_path)))))
    assert p.returncode == 130 and p.stderr.decode().splitlines() == ["error: interrupted"], p.stderr


def test_ctrl_c_leaves_no_noise_of_objects_half_built_when_it_came(tmp_path):
    """An object whose ``__init__`` Ctrl-C stopped (pyparsing's ``Forward`` while matplotlib imports, seen
    in CI) fails in its ``__del__`` when the interrupted frames are freed, after velpoly has printed its
    one line: the run is stopping, and that failure is no news to the user (no 'Exception ignored in')."""
    f = copy_fourbar(tmp_path)
    (tmp_path / "half_built.py").write_text(
        "import os, signal, sys, time, velpoly.cli as cli\n"
        "class Forward:\n"
        "    def __init__(self):\n"
        "        os.kill(os.getpid(), signal.SIGINT)\n"
        "        time.sleep(30)\n"
        "        self.expr = None\n"
        "    def __del__(self):\n"
        "        self.expr\n"
        "def solve(args):\n"
        "    Forward()\n"
        "cli.COMMANDS['solve'] = solve\n"
        f"sys.argv = ['velpoly', 'solve', {str(f)!r}]\n"
        "sys.exit(cli.main())\n")
    p = subprocess.run([sys.executable, "-m", "half_built"], capture_output=True, timeout=60,
                       env=dict(os.environ, PYTHONPATH=os.pathsep.join((str(ROOT), str(tmp_path)))))
    assert p.returncode == 130 and p.stderr.decode().splitlines() == ["error: interrupted"], p.stderr


_USER_TEXT = st.text(alphabet=st.sampled_from([chr(c) for c in range(32, 127)] + list("éü∠ω°")), max_size=12)


def _glyphs(s: str) -> str:
    from matplotlib import cbook
    from matplotlib.mathtext import MathTextParser
    if not cbook.is_math_text(s):
        return s.replace(r"\$", "$")
    return "".join(chr(g[2]) for g in MathTextParser("path").parse(s, dpi=72).glyphs)


@settings(max_examples=75, deadline=None)   # 150 until the suite had to fit 2 minutes
@given(_USER_TEXT)
def test_fuzz_literal_and_math_literal_draw_any_text_as_written(s):
    """Any text, alone, beside velpoly's own mathtext, or inside a subscript, shows exactly its
    characters (mathtext sets no glyph for a space, so spaces are left out of the comparison)."""
    from velpoly.render.canvas import literal, math_literal
    bare = s.replace(" ", "")
    assert _glyphs(literal(s)).replace(" ", "") == bare
    assert _glyphs(literal(s) + r"$\omega_{2}$" + literal(s)).replace(" ", "") == bare + "ω2" + bare
    assert _glyphs(r"$\omega_{" + math_literal(s) + "}$").replace(" ", "") == "ω" + bare
