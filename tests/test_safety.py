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
import threading
import time
from pathlib import Path

import pytest

import velpoly
from velpoly.cli import main
from velpoly.fileio import atomic_write_text

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
    """SIGTERM or Ctrl-C while the GIF writer works in its temporary folder: exit 130/143, one line, no
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
        while not list(tmp.iterdir()) and p.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)
        assert list(tmp.iterdir()), "the GIF writer's temporary folder never appeared"
        time.sleep(0.3)
        p.send_signal(sig)
        _, err = p.communicate(timeout=60)
    finally:
        if p.poll() is None:
            p.kill()
    err = err.decode()
    assert p.returncode == code and err.strip().splitlines()[-1] == f"error: {word}", err
    assert "Traceback" not in err and "Exception ignored" not in err
    assert list(tmp.iterdir()) == [] and list(out.iterdir()) == []


class _InterruptOnCollect:
    """Raises KeyboardInterrupt where Python can only ignore it (as in a matplotlib weakref callback)."""

    def __del__(self):
        raise KeyboardInterrupt


def test_a_ctrl_c_swallowed_in_a_callback_still_stops_the_run(tmp_path, capsys, monkeypatch):
    out = tmp_path / "c.csv"

    def command(args):
        _InterruptOnCollect()   # its __del__ runs now: the interrupt is "ignored" by Python
        gc.collect()
        atomic_write_text(out, "a table")   # the run must not commit its output after that
        return 0
    monkeypatch.setitem(velpoly.cli.COMMANDS, "solve", command)
    assert main(["solve", str(FOURBAR)]) == 130
    err = capsys.readouterr().err
    assert err.splitlines() == ["error: interrupted"] and "Exception ignored" not in err
    assert list(tmp_path.iterdir()) == []
