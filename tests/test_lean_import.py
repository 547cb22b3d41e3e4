"""velpoly.render.lean: the velpoly program imports matplotlib without set()'s help text and the 3-D axes;
its drawing is the same bytes as velpoly's called from Python, and matplotlib's set() still works there."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from velpoly.cli import main

EXAMPLE = Path(__file__).resolve().parent.parent / "velpoly" / "examples" / "crank_slider.toml"

PROBE = r'''
import sys
from velpoly.cli import main
status = main()   # as the program: argv None
from matplotlib.lines import Line2D
line = Line2D([0], [1])
line.set(color="red", lw=2.5)   # set() made without its help text takes the same keywords
assert (line.get_color(), line.get_linewidth()) == ("red", 2.5)
assert "mpl_toolkits.mplot3d" not in sys.modules
assert "Supported properties" not in (Line2D.set.__doc__ or "")   # the lean import did run
import gc
assert gc.isenabled() and gc.get_freeze_count() > 0   # the imports frozen, the collector on again
sys.exit(status)
'''


def test_program_draws_the_same_bytes_as_python(tmp_path):
    lean, full = tmp_path / "lean.svg", tmp_path / "full.svg"
    env = dict(os.environ, PYTHONPATH=str(EXAMPLE.parents[2]) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    proc = subprocess.run([sys.executable, "-c", PROBE, "draw", str(EXAMPLE), "--sheet", "poles", "-o", str(lean)],
                          capture_output=True, text=True, env=env, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert main(["draw", str(EXAMPLE), "--sheet", "poles", "-o", str(full)]) == 0
    assert lean.read_bytes() == full.read_bytes()


class _Leaned(BaseException):
    """Raised by the stand-in for the lean import: the command has asked for it, and stops there."""


def test_every_command_that_draws_imports_matplotlib_lean_as_the_program(tmp_path, monkeypatch):
    """Each command line of the program that draws with matplotlib asks for the lean import before it
    draws (``sweep``'s plot and GIF, ``animate`` and ``demo`` imported it in full: 0.4 CPU s more a run).
    In this process, as the program (``main()``, its arguments from sys.argv); the stand-in stops the
    command where it asks, so nothing is drawn."""
    import velpoly.render.lean as lean

    def stand_in(freeze=False):
        raise _Leaned(freeze)
    monkeypatch.setattr(lean, "import_matplotlib", stand_in)
    monkeypatch.chdir(tmp_path)
    f = str(EXAMPLE)
    lines = [["draw", f, "-o", "s.svg"], ["sweep", f, "--step", "60", "-o", "c.svg"],
             ["sweep", f, "--step", "60", "--gif", "c.gif"], ["animate", f, "--step", "60", "-o", "a.gif"],
             ["demo", "-o", "d"], ["gallery", "-o", "g", "crank_slider"]]
    asked = []
    for line in lines:
        monkeypatch.setattr(sys, "argv", ["velpoly", *line])
        try:
            main()
        except _Leaned as e:
            asked.append((line[0], e.args))
        else:
            asked.append((line[0], "drawn in full"))
    assert asked == [(line[0], (True,)) for line in lines]
    assert list(tmp_path.iterdir()) == []
