"""``velpoly gallery`` is whole or nothing (FORMAT.md section 3: "Ctrl-C stops any command with exit 130 ...
nothing partial or temporary stays behind"): a build stopped half-way leaves its folder byte for byte as it
was, with no temporary file and no folder it made; an example that fails leaves none of its own files while
the others are built. The drawings are stand-ins that write small files (the drawing itself is tested
elsewhere): what is tested is which files reach the folder."""
from __future__ import annotations

from pathlib import Path

import pytest

from velpoly import gallery
from velpoly.fileio import atomic_write_bytes
from velpoly.gallery import build_gallery

EXAMPLES = Path(gallery.__file__).parent / "examples"
NAMES = ("crank_slider", "ex3_6_fourbar", "ex3_5_slider_crank", "stephenson_sixbar")


def _source(tmp_path) -> Path:
    src = tmp_path / "src"
    src.mkdir()
    for n in NAMES:
        (src / f"{n}.toml").write_text((EXAMPLES / f"{n}.toml").read_text())
    return src


def _draw(fail=None, table_page=False, build="new"):
    """A stand-in for draw_to_file: the sheet (and a table page) as small files that name the ``build``;
    ``fail(title)`` raises."""
    def draw(sol, out, sheet="full", style="textbook", steps=False):
        out = Path(out)
        files = [atomic_write_bytes(out, f"{build} sheet of {sol.mechanism.title}".encode())]
        if table_page:
            files.append(atomic_write_bytes(out.with_name(out.stem + "-table.png"), b"table"))
        if fail is not None:
            fail(sol.mechanism.title)
        return files
    return draw


def _snapshot(folder: Path) -> dict:
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in folder.rglob("*") if p.is_file()}


def _titles():
    import velpoly
    return [velpoly.load(EXAMPLES / f"{n}.toml").title for n in NAMES]


@pytest.mark.parametrize("error", [KeyboardInterrupt, RuntimeError])
def test_a_stopped_build_leaves_the_previous_gallery_as_it_was(tmp_path, error):
    """A previous gallery, then a build stopped at each example in turn (the last one too): every file
    as it was, nothing added, no temporary file."""
    src, out = _source(tmp_path), tmp_path / "site"
    build_gallery(src, out, draw=_draw(build="old"))
    before = _snapshot(out)
    assert "README.md" in before and len([k for k in before if k.startswith("figures/")]) == len(NAMES)
    for stop in _titles():
        def fail(title, stop=stop):
            if title == stop:
                raise error("stopped")
        with pytest.raises(error):   # a RuntimeError out of the build, not out of one example's drawing:
            build_gallery(src, out, draw=_draw(fail), log=_raise_runtime if error is RuntimeError else None)
        assert _snapshot(out) == before, stop


def _raise_runtime(line):
    raise RuntimeError(line)


def test_a_stopped_build_into_a_new_folder_leaves_no_folder(tmp_path):
    src, out = _source(tmp_path), tmp_path / "new" / "site"
    (tmp_path / "new").mkdir()

    def fail(title):
        if title == _titles()[-1]:
            raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        build_gallery(src, out, draw=_draw(fail))
    assert list((tmp_path / "new").iterdir()) == []


def test_a_failing_example_leaves_none_of_its_files(tmp_path):
    """The second example fails after its sheet was written, before its table page: neither file is left;
    the others' sheets and table pages are written, and the README lists the failure."""
    src, out = _source(tmp_path), tmp_path / "site"
    bad = _titles()[1]

    def fail(title):
        if title == bad:
            raise RuntimeError("renderer crashed half-way")
    logged = []
    result = build_gallery(src, out, draw=_draw(fail, table_page=True), log=logged.append)
    assert [p.name for p, _ in result.failed] == [f"{NAMES[1]}.toml"] and len(logged) == 1
    files = set(_snapshot(out))
    for n in NAMES:
        shown = {f"figures/{n}.png", f"figures/{n}-table.png"}
        assert (shown & files == set()) if n == NAMES[1] else shown <= files, n
    assert not [f for f in files if f.endswith(".part")]


def _example_in_worker(path, out, style, copy):
    """The worker's task with the stand-in drawing (module level, so the pool can pickle it by name)."""
    return gallery._example(path, out, style, copy, _draw(), keep=True), None


def test_a_build_in_worker_processes_stopped_half_way_writes_nothing(tmp_path, monkeypatch):
    """The pool's workers draw into memory and this process writes their files: Ctrl-C after the first
    example's files were written leaves the folder as it was."""
    src, out = _source(tmp_path), tmp_path / "site"
    build_gallery(src, out, draw=_draw(build="old"))
    before = _snapshot(out)
    monkeypatch.setattr(gallery, "_example_in_worker", _example_in_worker)
    real, seen = gallery._example_result, []

    def result(*a, **kw):
        seen.append(a[0])
        if len(seen) == 3:
            raise KeyboardInterrupt
        return real(*a, **kw)
    monkeypatch.setattr(gallery, "_example_result", result)
    with pytest.raises(KeyboardInterrupt):
        build_gallery(src, out, jobs=2)
    assert len(seen) == 3 and _snapshot(out) == before


def _deaf_to_sigterm():
    import signal
    signal.signal(signal.SIGTERM, signal.SIG_IGN)


def _wait_long(seconds):
    import time
    time.sleep(seconds)
    return seconds


def test_a_worker_that_does_not_leave_on_sigterm_is_killed():
    """A worker still there after its SIGTERM (as one is that waits for the task queue's lock a sibling left
    taken when it left idle: the pool's shutdown then waited for ever, seen as a hung Ctrl-C test) is killed
    after the grace, so that the pool's shutdown returns."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor
    from multiprocessing.connection import wait
    pool = ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("fork"), initializer=_deaf_to_sigterm)
    futures = [pool.submit(_wait_long, 60) for _ in range(2)]
    procs = list(pool._processes.values())
    try:
        while not all(f.running() for f in futures):
            pass
        gallery._stop_workers(pool, grace=0.2)
        # each worker's end read from its sentinel (ready once the process has ended; is_alive() may say True
        # of a process the pool's own thread reaped first); 10 s a bound, not a timing: a live worker sleeps 60 s
        assert [bool(wait([p.sentinel], 10)) for p in procs] == [True, True]
    finally:
        for proc in procs:
            proc.kill()
        pool.shutdown(wait=True, cancel_futures=True)
