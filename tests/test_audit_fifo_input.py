"""Outside check, FORMAT.md section 3 (exit 2 or 3 with one line, never a hang): a mechanism read from a FIFO (a
pipe a script feeds, ``velpoly solve <(make_mechanism)``) whose error is found after loading (a pose beyond a
toggle, an acceleration sheet of a contact given by its normal) is reported like a file's, only without the
entry's line.

Found by the audit: velpoly read the input again to give the entry's line, and a FIFO read again waits for a
writer that never comes: ``velpoly solve FIFO --angle A`` beyond a toggle hung for ever (every exit-3 error from a
FIFO, and exit-2 errors found after loading).
"""
from __future__ import annotations

import os
import threading

import mechanisms
from test_fuzz import to_toml
from zoo import each


def run_on_fifo(tmp_path, text: str, args) -> tuple:
    """``velpoly ARGS`` with the mechanism ``text`` fed through a FIFO: (exit code, stderr), or None if it hung."""
    fifo = tmp_path / "m.toml"
    if fifo.exists():
        fifo.unlink()
    os.mkfifo(fifo)
    feeder = threading.Thread(target=lambda: fifo.write_text(text), daemon=True)
    feeder.start()
    done = []
    run = threading.Thread(target=lambda: done.append(mechanisms.in_process([args[0], fifo, *args[1:]])), daemon=True)
    run.start()
    run.join(timeout=30)
    if run.is_alive():   # waiting for a writer: give it one, so that the thread ends
        fifo.write_text("")
        run.join(timeout=30)
        return None
    return done[0].returncode, done[0].stderr


def test_an_error_found_after_loading_a_fifo_is_reported(tmp_path):
    cases = 0
    for sp in each(20271127, 24):
        kind = sp.kind
        if kind.startswith("four-bar") and "rocker" in kind and not sp.mech["driver"].get("slider"):
            args = ["solve", "--angle", str(sp.drawn.driver_angle + 180.0)]   # past a rocker's toggle, or solved
        elif "by its normal" in kind:
            args = ["draw", "--sheet", "acceleration", "-o", str(tmp_path / "a.svg")]
        else:
            continue
        got = run_on_fifo(tmp_path, to_toml(sp.mech), args)
        assert got is not None, (kind, "hung")
        rc, err = got
        if rc:
            assert rc in (2, 3) and err.startswith("error: ") and len(err.splitlines()) == 2, (kind, err)
            cases += 1
    assert cases >= 2
