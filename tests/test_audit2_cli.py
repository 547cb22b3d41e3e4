"""Outside checks of the command line's words (FORMAT.md section 3: exit 2 "with one line ``error:
FILE: WHERE: WHAT`` and a hint"; section 1, Drawing options). Found by the audit:
- ``--angle 1e400`` said "the driver angle must be finite, got inf", where the API says of
  ``solve(m, angle=10**400)`` "the driver angle 1e+400 deg is too large": the number the user typed is
  finite, only too large for a float. The option now keeps such a number exact, and says so;
- ``[drawing] label_points = true`` was refused "expected a list of point names, got True": the option
  takes TOML's booleans (true: every point, as without it; false: none), and the ``[drawing]`` errors
  show a value as the file has it (``true``, not Python's ``True``);
- ``velpoly gallery --source DIR nosuch`` hinted at the built-in examples (``velpoly examples``), not at
  the files in DIR, which are the names it takes.
On generated mechanisms (the zoo's first crank-driven specimens).
"""
from __future__ import annotations

import copy

import pytest

import velpoly

from mechanisms import in_process
from test_fuzz import to_toml
from zoo import zoo


def cranks(n: int) -> list[dict]:
    return [sp.mech for sp in zoo(20261125, 12) if "link" in sp.mech["driver"]][:n]


def test_an_angle_beyond_any_float_is_too_large_not_infinite(tmp_path):
    for k, mech in enumerate(cranks(4)):
        f = tmp_path / f"m{k}.toml"
        f.write_text(to_toml(mech))
        for args, shown in ((["solve", f, "--angle", "1e400"], "1e+400"),
                            (["draw", f, "--angle=-2.5e999", "-o", tmp_path / "x.svg"], "-2.5e+999")):
            r = in_process(args)
            lines = r.stderr.splitlines()
            assert r.returncode == 2 and len(lines) == 2, r.stderr
            assert lines[0] == f"error: {f}: --angle: the driver angle {shown} deg is too large (at most 1e+06 deg " \
                               "either way)", r.stderr
        assert not (tmp_path / "x.svg").exists()
        r = in_process(["solve", f, "--angle=-inf"])   # an infinity typed as one stays "not finite"
        assert r.returncode == 2 and "must be finite, got -inf" in r.stderr, r.stderr


def with_drawing(mech: dict, drawing: dict) -> dict:
    m = copy.deepcopy(mech)
    m["drawing"] = drawing
    return m


def test_label_points_takes_true_and_false_and_errors_show_values_as_typed():
    from velpoly.render.options import drawing_options
    for mech in cranks(3):
        every = drawing_options(velpoly.load(with_drawing(mech, {"label_points": True})))
        none = drawing_options(velpoly.load(with_drawing(mech, {"label_points": False})))
        assert every.label_points is None and none.label_points == ()
        for drawing, where, said in (({"label_points": 3}, "label_points", "true or false, got 3"),
                                     ({"label_points": ["A", True]}, "label_points", "got true in the list"),
                                     ({"scale": True}, "scale", "expected a positive number, got true"),
                                     ({"reasons": "yes"}, "reasons", "expected true or false, got 'yes'"),
                                     ({"link_numbers": False}, "link_numbers", "got false")):
            with pytest.raises(velpoly.InputError) as e:
                drawing_options(velpoly.load(with_drawing(mech, drawing)))
            assert e.value.where == f"drawing.{where}" and said in str(e.value), e.value


def test_gallery_of_a_source_folder_hints_at_its_own_files(tmp_path):
    src = tmp_path / "mine"
    src.mkdir()
    for k, mech in enumerate(cranks(2)):
        (src / f"lever_{k}.toml").write_text(to_toml(mech))
    r = in_process(["gallery", "--source", src, "-o", tmp_path / "out", "nosuch"])
    lines = r.stderr.splitlines()
    assert r.returncode == 2 and len(lines) == 2, r.stderr
    assert lines[0] == f"error: gallery: no example 'nosuch' in {src}"
    assert lines[1] == f"hint: the examples in {src} (name them without .toml): lever_0, lever_1"
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())
