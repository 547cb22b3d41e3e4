"""Outside checks of the command line's messages (FORMAT.md section 3: one line naming the file and the
entry, exit 2 for a wrong input, 3 for a pose that cannot be assembled). Found by the audit, on generated
mechanisms:

- ``velpoly sweep FILE --step 37`` of a double rocker drawn 14.6 deg short of its toggle (in omega's sense,
  the way its cycle runs) exited 3 with the hint "draw the mechanism in a pose away from the toggle" alone:
  the hint now names the step that reaches the toggle (``give a --step under 14.6 deg``);
- ``--step 1e400`` said "got inf", ``--step 1e-400`` "got 0" (sweep, animate, html): now too large / too
  small, as ``--angle 1e400`` is;
- ``--csv -`` wrote a file named "-" (FORMAT.md makes no option's "-" standard output; ``-o -`` was refused as
  an unknown figure type): every output option refuses "-", naming the option;
- ``-o DIR`` (a folder) said "error: d.svg: is a folder" naming no option: now ``-o``, ``--gif``, ``--csv``;
- ``omega = "1e400 rpm"`` said "cannot read": now too large.
"""
from __future__ import annotations

import copy
import re

import velpoly
from velpoly.solution import reachable_range
from velpoly.sweeps import run_cycle

from mechanisms import in_process
from test_fuzz import to_toml
from zoo import zoo


def _rockers(seed, n):
    """Generated crank-driven mechanisms whose reachable range is short ahead of the drawn pose (a toggle
    within 40 deg in omega's sense), with that reach."""
    out = []
    for sp in zoo(seed, n):
        if "link" not in sp.mech["driver"]:
            continue
        m = velpoly.load(sp.mech)
        lo, hi = reachable_range(velpoly.solve(m).kinematics)
        ahead = -lo if m.driver.omega < 0 else hi
        if 1.0 < ahead < 40.0:
            out.append((sp, ahead))
    return out


def test_a_step_past_the_toggle_ahead_is_named_in_the_hint(tmp_path):
    found = _rockers(20271201, 12)
    assert len(found) >= 2, [a for _, a in found]
    for i, (sp, ahead) in enumerate(found[:3]):
        f = tmp_path / f"r{i}.toml"
        f.write_text(to_toml(sp.mech))
        r = in_process(["sweep", f, "--step", repr(min(ahead + 5.0, 180.0)), "-o", tmp_path / "s.svg"])
        assert r.returncode == 3, (sp.kind, ahead, r.stderr)
        hint = r.stderr.splitlines()[1]
        said = float(re.search(r"give a --step under ([0-9.e+-]+) deg", hint).group(1))
        assert ahead - 0.011 <= said <= ahead, (ahead, hint)
        assert len(run_cycle(velpoly.load(sp.mech), said * 0.999).angles) >= 2, (sp.kind, said)


def test_steps_beyond_any_float_are_too_large_or_too_small(tmp_path):
    sp = zoo(20271201, 2)[1]
    f = tmp_path / "m.toml"
    f.write_text(to_toml(sp.mech))
    for command, out, most, least in (("sweep", "s.svg", "180", "0.001"), ("animate", "a.gif", "90", "0.05"),
                                      ("html", "h.html", "180", "0.1")):
        for step, said in (("1e400", f"the step 1e+400 deg is too large (at most {most} deg)"),
                           ("1e-400", f"the step 1e-400 deg is too small (at least {least} deg)"),
                           ("-1e400", "the step must be a number of degrees above 0, got -1e+400")):
            r = in_process([command, f, f"--step={step}", "-o", tmp_path / out])
            assert r.returncode == 2, r.stderr
            assert r.stderr.splitlines()[0] == f"error: {f}: --step: {said}", r.stderr


def test_output_options_name_themselves_for_a_folder_or_a_dash(tmp_path, monkeypatch):
    sp = zoo(20271202, 1)[0]
    f = tmp_path / "m.toml"
    f.write_text(to_toml(sp.mech))
    (tmp_path / "d.svg").mkdir()
    (tmp_path / "g.gif").mkdir()
    monkeypatch.chdir(tmp_path)
    for args, option, folder in ((["draw", f, "-o", "d.svg"], "-o", "d.svg"),
                                 (["sweep", f, "--gif", "g.gif"], "--gif", "g.gif"),
                                 (["sweep", f, "--csv", "d.svg"], "--csv", "d.svg"),
                                 (["animate", f, "-o", "g.gif"], "-o", "g.gif")):
        r = in_process(args)
        assert r.returncode == 2, (args, r.stderr)
        assert r.stderr.startswith(f"error: {folder}: {option}: is a folder"), (args, r.stderr)
    for args, option in ((["sweep", f, "--csv", "-"], "--csv"), (["draw", f, "-o", "-"], "-o"),
                         (["sweep", f, "--gif", "-"], "--gif"), (["html", f, "-o", "-"], "-o")):
        r = in_process(args)
        assert r.returncode == 2, (args, r.stderr)
        assert r.stderr.startswith(f"error: {f}: {option}: '-' is not standard output here"), (args, r.stderr)
    assert not (tmp_path / "-").exists()


def test_a_rate_beyond_any_float_is_too_large(tmp_path):
    for i, sp in enumerate(zoo(20271204, 3)):
        if "link" not in sp.mech["driver"]:
            continue
        for key, text in (("omega", "1e400 rpm"), ("omega", "-2e999 rad/s cw"), ("alpha", "1e400 rad/s^2")):
            mech = copy.deepcopy(sp.mech)
            mech["driver"][key] = text
            f = tmp_path / f"m{i}.toml"
            f.write_text(to_toml(mech))
            r = in_process(["solve", f])
            assert r.returncode == 2, r.stderr
            assert re.match(rf'error: {re.escape(str(f))}: driver\.{key} \(line \d+\): "{re.escape(text)}" is too '
                            r"large: beyond any floating-point number$", r.stderr.splitlines()[0]), r.stderr
