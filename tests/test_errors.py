"""Every input error and singular pose: exit status, the entry named, the gist, the line.

Most cases run the command in-process (``velpoly.cli.main``) on a small file
written to tmp_path and read stderr with capsys: the first line is
``error: FILE: WHERE (line N): WHAT``, the second ``hint: ...``, and there is
no traceback. The file is tests/data/fourbar.toml with one edit.
"""
from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

import velpoly
from velpoly.cli import main
from velpoly.loader import locate, parse_alpha, parse_omega

DATA = Path(__file__).parent / "data"
FOURBAR = (DATA / "fourbar.toml").read_text()
SLIDER = """
title = "slider-crank"
units = "mm"
[points]
A = [0, 0]
B = { from = "A", length = 30, angle = 40 }
C = { circle = ["B", 100], line = { through = [0, 10], angle = 0 }, near = [120, 10] }
[links]
0 = { points = ["A"], frame = true }
1 = { points = ["A", "B"] }
2 = { points = ["B", "C"] }
3 = { points = ["C"] }
[[sliders]]
block = "3"
guide = "0"
point = "C"
angle = 0
[driver]
link = "1"
omega = 10
"""
# a gear pair: wheels 2 and 3 turn about frame pivots O2, O3 and roll at P on the line of centres
GEARS = """
units = "mm"
[points]
O2 = [0, 0]
O3 = [100, 0]
P = [40, 0]
Q = [0, 40]
R = [100, 60]
K = [0, 10]
[links]
1 = { points = ["O2", "O3", "K"], frame = true }
2 = { points = ["O2", "Q"] }
3 = { points = ["O3", "R"] }
[[contacts]]
links = ["2", "3"]
point = "P"
kind = "rolling"
centres = ["O2", "O3"]
[driver]
link = "2"
omega = 10
"""


def edit(text: str, old: str, new: str) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


def run(capsys, tmp_path, text, *args, command="solve"):
    """Run the command on ``text``; returns (exit status, stdout, first stderr line, hint)."""
    f = tmp_path / "mech.toml"
    f.write_text(text, encoding="utf-8")
    code = main([command, str(f), *args])
    out, err = capsys.readouterr()
    assert "Traceback" not in err
    lines = err.splitlines()
    if code == 0:
        return code, out, "", ""
    assert len(lines) == 2, err
    assert lines[0].startswith(f"error: {f}: "), lines[0]
    assert lines[1].startswith("hint: ") and len(lines[1]) > len("hint: "), lines[1]
    return code, out, lines[0][len(f"error: {f}: "):], lines[1][len("hint: "):]


def fails(capsys, tmp_path, text, where, gist, code=2, *args):
    """The command exits ``code`` naming ``where`` (``points.C (line 9)``) and saying ``gist``."""
    got, _, msg, hint = run(capsys, tmp_path, text, *args)
    assert got == code, msg
    assert msg.startswith(where + ": "), msg
    assert re.search(gist, msg[len(where) + 2:]), msg
    return msg, hint


# -- files -------------------------------------------------------------------------------------
def test_missing_file(capsys, tmp_path):
    code = main(["solve", str(tmp_path / "nope.toml")])
    err = capsys.readouterr().err.splitlines()
    assert code == 2
    assert err == [f"error: {tmp_path / 'nope.toml'}: no such file", "hint: check the path"]


def test_directory(capsys, tmp_path):
    assert main(["solve", str(tmp_path)]) == 2
    err = capsys.readouterr().err.splitlines()
    assert err[0] == f"error: {tmp_path}: is a directory, not a mechanism file" and err[1].startswith("hint: ")


def test_bad_toml_names_the_line(capsys, tmp_path):
    msg, _ = fails(capsys, tmp_path, edit(FOURBAR, 'B = { from = "A", length = 40, angle = 60 }',
                                          'B = { from = "A", length = 40, angle = }'), "line 8", "bad TOML")
    assert "column" in msg


def test_duplicate_point_is_bad_toml(capsys, tmp_path):
    fails(capsys, tmp_path, edit(FOURBAR, "D = [100, 0]", "D = [100, 0]\nA = [1, 1]"), "line 8", "bad TOML")


@pytest.mark.parametrize("text", ["", "  \n\n"])
def test_empty_file(capsys, tmp_path, text):
    code, _, msg, _ = run(capsys, tmp_path, text)
    assert (code, msg) == (2, "the file is empty")


def test_comments_only(capsys, tmp_path):
    code, _, msg, hint = run(capsys, tmp_path, "# a mechanism, some day\n")
    assert (code, msg) == (2, "points: missing table [points]") and "[points]" in hint


def test_not_utf8(capsys, tmp_path):
    f = tmp_path / "latin1.toml"
    f.write_bytes(FOURBAR.replace("Crank-rocker", "Kurbelschwinge \xe4").encode("latin-1"))
    assert main(["solve", str(f)]) == 2
    assert "not a text (UTF-8) file" in capsys.readouterr().err


def test_load_api_errors_and_empty_text():
    with pytest.raises(velpoly.InputError, match="the file is empty"):
        velpoly.load("")
    with pytest.raises(velpoly.InputError, match="cannot load an int"):
        velpoly.load(3)


# -- keys ---------------------------------------------------------------------------------------
def test_unknown_top_level_key_lists_the_valid_ones(capsys, tmp_path):
    msg, hint = fails(capsys, tmp_path, edit(FOURBAR, "units", "unit"), "unit (line 3)", "unknown key 'unit'")
    assert hint.startswith("valid keys: format, title, units, points, links")


def test_unknown_table(capsys, tmp_path):
    fails(capsys, tmp_path, edit(FOURBAR, "[driver]", "[drivers]"), "drivers (line 17)", "unknown key 'drivers'")


@pytest.mark.parametrize("old, new, where, key", [
    ('angle = 60 }', 'angel = 60 }', "points.B.angel (line 8)", "angel"),
    ('near = [90, 80] }', 'near = [90, 80], sde = "left" }', "points.C.sde (line 9)", "sde"),
    ("A = [0, 0]", "A = { x = 0, y = 0 }", "points.A.x (line 6)", "x"),
    ('3 = { points = ["B", "C"] }', '3 = { points = ["B", "C"], colour = "red" }', "links.3.colour (line 14)",
     "colour"),
    ('omega = "10 rad/s"', 'omgea = "10 rad/s"', "driver.omgea (line 19)", "omgea"),
    ("alpha = 0", "alpha = 0\n\n[reference]\nsorce = \"book\"", "reference.sorce (line 23)", "sorce"),
])
def test_unknown_keys_inside_tables(capsys, tmp_path, old, new, where, key):
    _, hint = fails(capsys, tmp_path, edit(FOURBAR, old, new), where, f"unknown key '{key}'")
    assert "valid keys" in hint or "a point is" in hint


@pytest.mark.parametrize("table, entry, key", [
    ("sliders", SLIDER, "guid"), ("contacts", GEARS, "knd"), ("slots", None, "slott")])
def test_unknown_keys_in_arrays_of_tables(capsys, tmp_path, table, entry, key):
    if table == "sliders":
        text = edit(SLIDER, 'guide = "0"', f'{key} = "0"')
        where = "sliders[0].guid (line 15)"
    elif table == "contacts":
        text = edit(GEARS, 'kind = "rolling"', f'{key} = "rolling"')
        where = "contacts[0].knd (line 17)"
    else:
        text = FOURBAR + '\n[[slots]]\npin = "C"\nlink = "3"\nslott = "4"\nangle = 0\n'
        where = "slots[0].slott (line 25)"
    _, hint = fails(capsys, tmp_path, text, where, f"unknown key '{key}'")
    assert hint.startswith("valid keys: ")


def test_unknown_key_in_reference_values(capsys, tmp_path):
    text = FOURBAR + '\n[reference]\nsource = "book"\nvalues = { V_C = 1.0, W_Z = 2.0 }\n'
    fails(capsys, tmp_path, text, "reference.values.W_Z (line 24)", "unknown quantity 'W_Z'")


def test_unknown_link_and_point_in_reference(capsys, tmp_path):
    text = FOURBAR + '\n[reference]\nomega = { "7" = 1.0 }\n'
    fails(capsys, tmp_path, text, "reference.omega.7 (line 23)", "unknown link '7'")
    text = FOURBAR + '\n[reference]\n[reference.speed]\nB = 400\nZ = 1.0\n'
    fails(capsys, tmp_path, text, "reference.speed.Z (line 25)", "unknown point 'Z'")


# -- points --------------------------------------------------------------------------------------
def test_unknown_point_in_a_construction(capsys, tmp_path):
    _, hint = fails(capsys, tmp_path, edit(FOURBAR, '["D", 80]', '["Q", 80]'), r"points.C.circles (line 9)",
                    "refers to unknown point 'Q'")
    assert hint == "points defined above it: A, D, B"


def test_later_defined_point(capsys, tmp_path):
    text = edit(FOURBAR, 'B = { from = "A", length = 40, angle = 60 }\n', "")
    text = edit(text, "\n[links]", 'B = { from = "A", length = 40, angle = 60 }\n\n[links]')
    _, hint = fails(capsys, tmp_path, text, "points.C.circles (line 8)",
                    r"refers to point 'B', which is defined later \(line 9\)")
    assert hint == "points are evaluated in file order: define 'B' above 'C'"


def test_circular_references_are_later_definitions(capsys, tmp_path):
    # B from C and C from B: impossible in file order; the first one names the other as later
    text = edit(FOURBAR, 'B = { from = "A", length = 40, angle = 60 }', 'B = { from = "C", length = 40, angle = 60 }')
    text = edit(text, 'C = { circles = [["B", 120], ["D", 80]], near = [90, 80] }',
                'C = { from = "B", length = 120, angle = 10 }')
    fails(capsys, tmp_path, text, "points.B.from (line 8)", r"refers to point 'C', which is defined later \(line 9\)")


def test_self_reference(capsys, tmp_path):
    fails(capsys, tmp_path, edit(FOURBAR, '"A", length = 40', '"B", length = 40'), "points.B.from (line 8)",
          "point 'B' refers to itself")


def test_point_listed_in_no_link(capsys, tmp_path):
    _, hint = fails(capsys, tmp_path, edit(FOURBAR, "D = [100, 0]", "D = [100, 0]\nE = [50, 50]"),
                    "points.E (line 8)", "point 'E' is listed in no link")
    assert hint == "list it in the link that carries it"


def test_point_listed_twice_in_a_link(capsys, tmp_path):
    fails(capsys, tmp_path, edit(FOURBAR, '["B", "C"]', '["B", "C", "B"]'), "links.3.points (line 14)",
          "point 'B' is listed twice")


def test_unknown_point_in_a_link(capsys, tmp_path):
    _, hint = fails(capsys, tmp_path, edit(FOURBAR, '["B", "C"]', '["B", "X"]'), "links.3.points (line 14)",
                    "unknown point 'X'")
    assert "A, D, B, C" in hint


def test_name_used_for_a_point_and_a_link(capsys, tmp_path):
    text = edit(edit(FOURBAR, "D = [100, 0]", 'D = [100, 0]\n2 = { from = "A", length = 5, angle = 0 }'),
                '1 = { points = ["A", "D"]', '1 = { points = ["A", "D", "2"]')
    fails(capsys, tmp_path, text, "links.2 (line 14)", "'2' names both a point and a link")


def test_duplicate_names_in_a_dict():
    d = {"points": {"A": [0, 0], "B": [1, 0]}, "links": {1: {"points": ["A", "B"], "frame": True},
                                                       "1": {"points": ["A"]}}, "driver": {"link": 1, "omega": 1}}
    with pytest.raises(velpoly.InputError, match=r"links\.1: link '1' is defined twice"):
        velpoly.load(d)


@pytest.mark.parametrize("frames, where, gist", [
    ((), "links (line 11)", "no link is the frame"),
    (("1", "2"), "links.2 (line 13)", "two or more links are the frame: 1, 2")])
def test_frames(capsys, tmp_path, frames, where, gist):
    text = edit(FOURBAR, ", frame = true", "")
    for k in frames:
        text = edit(text, f'{k} = {{ points = [', f'{k} = {{ frame = true, points = [')
    _, hint = fails(capsys, tmp_path, text, where, gist)
    assert hint == "mark exactly one link with frame = true"


def test_circles_that_do_not_meet_say_by_how_much(capsys, tmp_path):
    gap = math.hypot(100 - 20, 40 * math.sin(math.radians(60))) - 75
    msg, hint = fails(capsys, tmp_path, edit(FOURBAR, '[["B", 120], ["D", 80]]', '[["B", 50], ["D", 25]]'),
                      "points.C (line 9)", "circles do not meet")
    assert msg.endswith(f"circles do not meet (gap {gap:.6g} mm)")
    assert "add up to 75" in hint


def test_circle_inside_circle(capsys, tmp_path):
    _, hint = fails(capsys, tmp_path, edit(FOURBAR, '[["B", 120], ["D", 80]]', '[["B", 300], ["D", 80]]'),
                    "points.C (line 9)", r"circles do not meet \(gap [\d.]+ mm\)")
    assert "inside the other" in hint


def test_line_that_misses_the_circle(capsys, tmp_path):
    fails(capsys, tmp_path, edit(SLIDER, "through = [0, 10]", "through = [0, 250]"), "points.C (line 7)",
          r"the line misses the circle \(gap [\d.]+ mm\)")


def test_concentric_circles(capsys, tmp_path):
    fails(capsys, tmp_path, edit(FOURBAR, '["D", 80]', '["B", 80]'), "points.C.circles (line 9)",
          "centres 'B' and 'B' coincide")


@pytest.mark.parametrize("old, new, gist", [
    ('near = [90, 80] }', 'near = [90, 80], side = "left" }', r"exactly one of 'near' and 'side' \(both are given\)"),
    (', near = [90, 80] }', ' }', "exactly one of 'near' and 'side'$")])
def test_near_and_side(capsys, tmp_path, old, new, gist):
    fails(capsys, tmp_path, edit(FOURBAR, old, new), "points.C (line 9)", gist)


def test_circle_line_needs_near(capsys, tmp_path):
    fails(capsys, tmp_path, edit(SLIDER, ", near = [120, 10] }", " }"), "points.C (line 7)", "needs 'near'")


def test_side_value(capsys, tmp_path):
    fails(capsys, tmp_path, edit(FOURBAR, "near = [90, 80]", 'side = "up"'), "points.C.side (line 9)",
          'expected "left" or "right", got "up"')


# -- mobility and driver --------------------------------------------------------------------------------
def test_mobility_zero(capsys, tmp_path):
    fails(capsys, tmp_path, edit(FOURBAR, '3 = { points = ["B", "C"] }', '3 = { points = ["B", "C", "D"] }'),
          "links (line 11)", r"^mobility is 0 ")


def test_mobility_two(capsys, tmp_path):
    text = edit(FOURBAR, "D = [100, 0]", "D = [100, 0]\nE = [130, 60]")
    text = edit(text, '4 = { points = ["D", "C"] }', '4 = { points = ["D", "E"] }\n5 = { points = ["E", "C"] }')
    _, hint = fails(capsys, tmp_path, text, "links (line 12)", r"^mobility is 2 .*must be 1")
    assert "missing" in hint


@pytest.mark.parametrize("old, new, where, gist", [
    ('link = "2"', 'link = "3"', "driver.link (line 18)", "link '3' is not pinned to the frame '1'"),
    ('link = "2"', 'link = "9"', "driver.link (line 18)", "unknown link '9'"),
    ('link = "2"', 'link = "1"', "driver.link (line 18)", "the driver cannot be the frame '1'"),
    ('link = "2"', 'slider = "C"\nspeed = 1', "driver.slider (line 18)", "no slider has the point 'C'"),
    ('link = "2"\n', '', "driver (line 17)", "give exactly one of 'link'"),
    ('omega = "10 rad/s"', 'omega = "60 rmp"', "driver.omega (line 19)", 'cannot read "60 rmp" as an angular velocity'),
    ('omega = "10 rad/s"', 'omega = "5 rad/s^2"', "driver.omega (line 19)", "cannot read"),
    ('omega = "10 rad/s"', 'omega = "10 rad/s sideways"', "driver.omega (line 19)", "cannot read"),
    ('omega = "10 rad/s"', 'omega = "fast"', "driver.omega (line 19)", "cannot read"),
    ('omega = "10 rad/s"', 'omega = ""', "driver.omega (line 19)", "cannot read"),
    ('omega = "10 rad/s"', 'omega = "1e999 rpm"', "driver.omega (line 19)", "is too large: beyond any floating-point number"),
    ('alpha = 0', 'alpha = "5 rpm"', "driver.alpha (line 20)", 'cannot read "5 rpm" as an angular acceleration'),
    ('omega = "10 rad/s"\n', '', "driver (line 17)", "missing 'omega'"),
    ('alpha = 0', 'speed = 3', "driver.speed (line 20)", "'speed' belongs to a slider driver"),
])
def test_driver(capsys, tmp_path, old, new, where, gist):
    fails(capsys, tmp_path, edit(FOURBAR, old, new), where, gist)


def test_missing_driver_table(capsys, tmp_path):
    text = FOURBAR[:FOURBAR.index("[driver]")]
    _, hint = fails(capsys, tmp_path, text, "driver", r"missing table \[driver\]")
    assert "omega" in hint


@pytest.mark.parametrize("text, value", [
    ("-10 rad/s cw", 10.0), ("10 rad/s cw", -10.0), ("10 rad/s ccw", 10.0), ("60 rpm", 2 * math.pi),
    ("60 RPM", 2 * math.pi), ("30 r/min cw", -math.pi), ("30 rev/min", math.pi), ("2 Hz", 4 * math.pi),
    ("2 rps", 4 * math.pi), ("1 rev/s CW", -2 * math.pi), ("90 deg/s ccw", math.pi / 2),
    ("  1.5e1 rad/s  ", 15.0), ("10rad/s", 10.0), ("+.5 rad/s", 0.5), (7, 7.0), (-2.5, -2.5)])
def test_omega_strings(text, value):
    assert parse_omega(text) == pytest.approx(value, rel=1e-15)


@pytest.mark.parametrize("text, value", [
    ("5 rad/s^2 cw", -5.0), ("5 rad/s^2", 5.0), ("-5 rad/s^2 cw", 5.0), ("5 RAD/S^2 CCW", 5.0), (0, 0.0)])
def test_alpha_strings(text, value):
    assert parse_alpha(text) == pytest.approx(value)


@pytest.mark.parametrize("bad", ["60 rmp", "10", "cw", "10 cw", "10 rad/s^2", "1 rad/s cw ccw", True, [1], {}, None])
def test_omega_strings_rejected(bad):
    with pytest.raises(ValueError):
        parse_omega(bad)


def test_omega_and_alpha_strings_in_a_file():
    m = velpoly.load(edit(edit(FOURBAR, '"10 rad/s"', '"-10 rad/s cw"'), "alpha = 0", 'alpha = "5 rad/s^2 cw"'))
    assert (m.driver.omega, m.driver.alpha) == (10.0, -5.0)
    # alpha's sign is its own: counter-clockwise positive whatever omega's sense
    m = velpoly.load(edit(edit(FOURBAR, '"10 rad/s"', '"60 rpm cw"'), "alpha = 0", 'alpha = "5 rad/s^2"'))
    assert m.driver.omega == pytest.approx(-2 * math.pi) and m.driver.alpha == 5.0


# -- types and values ---------------------------------------------------------------------------------
@pytest.mark.parametrize("old, new, where, gist", [
    ("length = 40", "length = -40", "points.B.length (line 8)", "must be positive, got -40"),
    ('["B", 120]', '["B", 0]', "points.C.circles (line 9)", "must be positive, got 0"),
    ("length = 40", 'length = "40"', "points.B.length (line 8)", 'expected a number, got the string "40"'),
    ("angle = 60", 'angle = "60 deg"', "points.B.angle (line 8)", "expected a number, got the string"),
    ("length = 40", "length = true", "points.B.length (line 8)", "expected a number, got true"),
    ("A = [0, 0]", "A = [false, 0]", "points.A (line 6)", "expected a number, got false"),
    ("A = [0, 0]", "A = [0, 0, 0]", "points.A (line 6)", r"expected \[x, y\], got a list of 3 items"),
    ("A = [0, 0]", 'A = "origin"', "points.A (line 6)", "expected .x, y. or a construction table"),
    ("A = [0, 0]", "A = [[0], [0]]", "points.A (line 6)", "expected a number, got a list"),
    ('[["B", 120], ["D", 80]]', '{ B = 120, D = 80 }', "points.C.circles (line 9)", "expected"),
    ('[["B", 120], ["D", 80]]', '[["B", "120"], ["D", 80]]', "points.C.circles (line 9)", "got the string"),
    ('near = [90, 80]', 'near = 90', "points.C.near (line 9)", "refers to unknown point '90'"),
    ('near = [90, 80]', 'near = true', "points.C.near (line 9)", "got true"),
    ('points = ["A", "B"]', 'points = "AB"', "links.2.points (line 13)", 'got "AB"'),
    ('points = ["A", "B"]', 'points = { A = 1 }', "links.2.points (line 13)", "got a table"),
    ('points = ["A", "B"]', 'points = []', "links.2.points (line 13)", "a non-empty list"),
    ('points = ["A", "B"]', 'points = ["A", 2.5]', "links.2.points (line 13)", "expected a point's name, got 2.5"),
    ("frame = true", 'frame = "yes"', "links.1.frame (line 12)", 'expected true or false, got "yes"'),
    ("frame = true", "frame = 1", "links.1.frame (line 12)", "expected true or false, got 1"),
    ('2 = { points = ["A", "B"] }', '2 = ["A", "B"]', "links.2 (line 13)", "got a list"),
    ('title = "Crank-rocker four-bar"', "title = 3", "title (line 2)", "expected a string, got 3"),
    ('units = "mm"', "units = 1", "units (line 3)", "expected a string"),
    ("format = 1", "format = 2", "format (line 1)", "unsupported format 2"),
    ("format = 1", 'format = "1"', "format (line 1)", 'unsupported format "1"'),
    ("format = 1", "format = true", "format (line 1)", "unsupported format true"),
    ('link = "2"', "link = 2.0", "driver.link (line 18)", "expected a link's name, got 2"),
    ('link = "2"', "link = true", "driver.link (line 18)", "expected a link's name, got true"),
    ('omega = "10 rad/s"', "omega = true", "driver.omega (line 19)", "cannot read true"),
    ('omega = "10 rad/s"', "omega = [10]", "driver.omega (line 19)", "cannot read a list"),
    ("alpha = 0", "alpha = 0\nangle = \"30\"", "driver.angle (line 21)", "got the string"),
    (FOURBAR[FOURBAR.index("[points]"):FOURBAR.index("[links]")], 'points = "ABCD"\n', "points (line 5)",
     'expected a table \\[points\\], got "ABCD"'),
])
def test_wrong_types(capsys, tmp_path, old, new, where, gist):
    fails(capsys, tmp_path, edit(FOURBAR, old, new), where, gist)


@pytest.mark.parametrize("old, new, where", [
    ("length = 40", "length = nan", "points.B.length (line 8)"),
    ("length = 40", "length = inf", "points.B.length (line 8)"),
    ("D = [100, 0]", "D = [inf, 0]", "points.D (line 7)"),
    ("D = [100, 0]", "D = [-inf, 0]", "points.D (line 7)"),
    ("angle = 60", "angle = nan", "points.B.angle (line 8)"),
    ("near = [90, 80]", "near = [nan, 80]", "points.C.near (line 9)"),
    ('["D", 80]', '["D", inf]', "points.C.circles (line 9)"),
    ('omega = "10 rad/s"', "omega = nan", "driver.omega (line 19)"),
    ('omega = "10 rad/s"', "omega = -inf", "driver.omega (line 19)"),
    ("alpha = 0", "alpha = nan", "driver.alpha (line 20)"),
    ("alpha = 0", "alpha = 0\nangle = inf", "driver.angle (line 21)"),
])
def test_nan_and_inf(capsys, tmp_path, old, new, where):
    msg, _ = fails(capsys, tmp_path, edit(FOURBAR, old, new), where, "finite")
    assert re.search(r"\b(-?inf|nan)\b", msg)


def test_huge_lengths_give_no_finite_position(capsys, tmp_path):
    text = edit(FOURBAR, "length = 40, angle = 60 }", 'length = 1.5e308, angle = 0 }\n'
                'B2 = { from = "B", length = 1.5e308, angle = 0 }')
    fails(capsys, tmp_path, text, "points.B2 (line 9)", "no finite position")


def test_link_names_must_not_contain_a_dash(capsys, tmp_path):
    text = edit(edit(FOURBAR, '3 = { points', '"3-a" = { points'), "", "")
    fails(capsys, tmp_path, text, "links.3-a (line 14)", "must not contain '-'")


def test_names_must_not_contain_at(capsys, tmp_path):
    text = edit(edit(FOURBAR, "D = [100, 0]", '"D@1" = [100, 0]'), '["A", "D"]', '["A", "D@1"]')
    text = edit(edit(text, '["D", 80]', '["D@1", 80]'), '["D", "C"]', '["D@1", "C"]')
    fails(capsys, tmp_path, text, "points.D@1 (line 7)", "must not contain '@'")


def test_control_characters_stay_on_one_line(capsys, tmp_path):
    text = edit(FOURBAR, 'link = "2"', 'link = "2\\nsecond line"')
    msg, _ = fails(capsys, tmp_path, text, "driver.link (line 18)", r"unknown link '2\\nsecond line'")


# -- sliders, contacts, slots ---------------------------------------------------------------------------
@pytest.mark.parametrize("old, new, where, gist", [
    ('block = "3"', 'block = "7"', "sliders[0].block (line 14)", "unknown link '7'"),
    ('guide = "0"', 'guide = "3"', "sliders[0].guide (line 15)", "block and guide are the same link '3'"),
    ('point = "C"', 'point = "B"', "sliders[0].point (line 16)", "point 'B' is not a point of the block '3'"),
    ('point = "C"', 'point = "Z"', "sliders[0].point (line 16)", "unknown point 'Z'"),
    ('angle = 0\n[driver]', 'angle = 0\ncentre = "A"\n[driver]', "sliders[0] (line 13)",
     r"exactly one of 'angle', 'along' and 'centre' \(angle and centre are given\)"),
    ('guide = "0"\n', '', "sliders[0] (line 13)", "missing 'guide'"),
    ('angle = 0\n[driver]', 'angle = "east"\n[driver]', "sliders[0].angle (line 17)", "got the string"),
])
def test_sliders(capsys, tmp_path, old, new, where, gist):
    fails(capsys, tmp_path, edit(SLIDER, old, new), where, gist)


def test_sliders_as_a_table(capsys, tmp_path):
    text = edit(SLIDER, "[[sliders]]", "[sliders]")
    _, hint = fails(capsys, tmp_path, text, "sliders (line 13)", r"expected \[\[sliders\]\] entries")
    assert "[[sliders]]" in hint


def test_the_line_of_the_second_slider(capsys, tmp_path):
    text = SLIDER + '[[sliders]]\nblock = "3"\nguide = "0"\npoint = "C"\nangel = 0\n'
    fails(capsys, tmp_path, text, "sliders[1].angel (line 25)", "unknown key 'angel'")


@pytest.mark.parametrize("old, new, where, gist", [
    ('links = ["2", "3"]', 'links = ["2", "8"]', "contacts[0].links (line 15)", "unknown link '8'"),
    ('links = ["2", "3"]', 'links = ["2", "2"]', "contacts[0].links (line 15)", "two different links"),
    ('links = ["2", "3"]', 'links = "2"', "contacts[0].links (line 15)", "expected links"),
    ('point = "P"', 'point = "W"', "contacts[0].point (line 16)", "unknown point 'W'"),
    ("P = [40, 0]", "P = [40, 3]", "contacts[0].point (line 16)", "off the line of centres by 3 mm"),
    ('centres = ["O2", "O3"]', 'centres = ["P", "O3"]', "contacts[0].centres (line 18)",
     "centre 'P' is at the contact point: the profile has no radius"),
    ('centres = ["O2", "O3"]', 'centres = ["flat", "flat"]', "contacts[0].centres (line 18)", "both profiles are flat"),
    ('centres = ["O2", "O3"]', 'centres = ["O3", "O2"]', "contacts[0].centres (line 18)",
     "centre 'O3' is not a point of link '2'"),
    ('centres = ["O2", "O3"]', 'centres = ["O2", "O2"]', "contacts[0].centres (line 18)",
     "centre 'O2' is not a point of link '3'"),
    ('kind = "rolling"', 'kind = "rolling"\nslip = 2', "contacts[0].slip (line 18)",
     'a prescribed slip needs kind = "sliding"'),
    ('kind = "rolling"', 'kind = "gliding"', "contacts[0].kind (line 17)", 'expected "rolling" or "sliding", got "gliding"'),
    ('kind = "rolling"\n', '', "contacts[0].kind (line 14)", r"kind is missing"),
    ('centres = ["O2", "O3"]', 'centres = ["O2", "O3"]\nnormal = 0', "contacts[0] (line 14)",
     r"exactly one of 'centres' and 'normal' \(both are given\)"),
])
def test_contacts(capsys, tmp_path, old, new, where, gist):
    fails(capsys, tmp_path, edit(GEARS, old, new), where, gist)


def test_gears_solve():
    s = velpoly.solve(velpoly.load(GEARS))
    assert s.omega["3"] == pytest.approx(-10 * 40 / 60)


@pytest.mark.parametrize("entry, where, gist", [
    ('pin = "C"\nlink = "3"\nslot = "9"\nangle = 0', "slots[0].slot (line 25)", "unknown link '9'"),
    ('pin = "C"\nlink = "3"\nslot = "3"\nangle = 0', "slots[0].slot (line 25)", "same link '3'"),
    ('pin = "B"\nlink = "3"\nslot = "2"\nangle = 0\ncentre = "A"', "slots[0] (line 22)", "exactly one of"),
    ('pin = "D"\nlink = "3"\nslot = "4"\nangle = 0', "slots[0].pin (line 23)", "point 'D' is not a point of link '3'"),
    ('pin = "Y"\nlink = "3"\nslot = "4"\nangle = 0', "slots[0].pin (line 23)", "unknown point 'Y'"),
])
def test_slots(capsys, tmp_path, entry, where, gist):
    fails(capsys, tmp_path, FOURBAR + "\n[[slots]]\n" + entry + "\n", where, gist)


# -- line numbers in other layouts ------------------------------------------------------------------------
def test_line_numbers_in_sub_tables_and_dotted_keys():
    text = ('title = "x"\n'            # 1
            "[points]\n"               # 2
            "A = [0, 0]\n"             # 3
            "[points.B]\n"             # 4
            'from = "A"\n'             # 5
            "length = 3\n"             # 6
            "[links.2]\n"              # 7
            "points = [\n"             # 8
            '  "A",\n'                 # 9
            '  "B" ]\n'                # 10
            "[[sliders]]\n"            # 11
            'block = "2"\n'            # 12
            "[[sliders]]\n"            # 13
            'block = "3"\n'            # 14
            "[reference]\n"            # 15
            "values.V_B = 3\n"         # 16
            "[reference.note]\n"       # 17
            "'V_B3/B4' = \"misprint\"\n")  # 18
    assert locate(text, "points.A") == 3
    assert locate(text, "points.B") == 4
    assert locate(text, "points.B.length") == 6
    assert locate(text, "points.B.angle") == 4
    assert locate(text, "links.2.points") == 8
    assert locate(text, "links") == 7
    assert locate(text, "sliders[0].block") == 12
    assert locate(text, "sliders[1].block") == 14
    assert locate(text, "sliders[1].guide") == 13
    assert locate(text, "reference.values.V_B") == 16
    assert locate(text, "reference.note.V_B3/B4") == 18
    assert locate(text, "title") == 1
    assert locate(text, "driver") is None
    assert locate(text, "pose") is None


def test_line_of_a_construction_table():
    text = edit(FOURBAR, "[links]", '[points.E]\nfrom = "A"\nlength = -40\nangle = 60\n\n[links]')
    with pytest.raises(velpoly.InputError) as e:
        velpoly.load(text)
    assert e.value.where == "points.E.length (line 13)"


def test_dict_input_names_the_entry_without_a_line():
    d = {"points": {"A": [0, 0], "B": {"from": "A", "length": -1, "angle": 0}}}
    with pytest.raises(velpoly.InputError) as e:
        velpoly.load(d)
    assert str(e.value) == "<dict>: points.B.length: must be positive, got -1"


# -- singular and near-singular poses -----------------------------------------------------------------------
def data_file(capsys, name, *args):
    code = main(["solve", str(DATA / name), *args])
    out, err = capsys.readouterr()
    assert "Traceback" not in err
    return code, out, err.splitlines()


@pytest.mark.parametrize("name, links", [
    ("toggle_fourbar.toml", "links 3, 4"),        # coupler and rocker in line
    ("tangent_toggle.toml", "links 3, 4"),        # the same, drawn with tangent circles
    ("dead_centre.toml", "links 1, 2"),           # crank and rod in line, the slider drives
    ("coincident_pins.toml", "links 3, 4"),       # crank pin on the rocker's pivot
])
def test_singular_poses_exit_3_naming_the_links(capsys, name, links):
    code, out, err = data_file(capsys, name, "--json")
    assert code == 3 and out == ""
    assert len(err) == 2 and err[0].startswith(f"error: {DATA / name}: ") and "singular" in err[0]
    assert err[0].endswith(f"({links})"), err[0]
    with pytest.raises(velpoly.SingularPoseError) as e:
        velpoly.solve(velpoly.load(DATA / name))
    assert ", ".join(e.value.links) == links.split(" ", 1)[1]


def test_parallel_construction_lines_exit_3(capsys):
    code, out, err = data_file(capsys, "parallel_lines.toml")
    assert code == 3 and out == ""
    assert "singular pose" in err[0] and re.search(r"\(links [\d, ]*2[\d, ]*\)$", err[0]), err[0]


def test_exact_toggle_by_tangent_circles_is_on_the_line_of_centres():
    m = velpoly.load(DATA / "tangent_toggle.toml")
    b, c, d = (m.position(p) for p in "BCD")
    u, v = c - b, d - b
    assert abs(u[0] * v[1] - u[1] * v[0]) <= 1e-12 * 130 ** 2


def test_near_singular_pose_warns(capsys):
    code, out, err = data_file(capsys, "near_toggle.toml", "--json")
    assert code == 0
    data = json.loads(out)
    assert len(data["warnings"]) == 1 and "near-singular" in data["warnings"][0]
    assert err == [f"warning: {DATA / 'near_toggle.toml'}: {data['warnings'][0]}"]
    s = velpoly.solve(velpoly.load(DATA / "near_toggle.toml"))
    assert 1e6 < s.condition < 1e10
    # the numbers are still right: omega_3 and omega_4 from the loop equation
    # omega_2 x AB + omega_3 x BC = omega_4 x DC, solved in closed form with exact trigonometry
    a, b, c, d = (np.array(s.position[p]) for p in "ABCD")
    ab, bc, dc = b - a, c - b, c - d
    cross = lambda u, v: u[0] * v[1] - u[1] * v[0]   # noqa: E731
    w2 = 10.0
    w4 = w2 * cross(ab, bc) / cross(dc, bc)
    w3 = -w2 * cross(ab, dc) / cross(bc, dc)
    assert s.omega["4"] == pytest.approx(w4, rel=1e-5)
    assert s.omega["3"] == pytest.approx(w3, rel=1e-5)


def test_no_warning_away_from_toggles(capsys):
    code, out, err = data_file(capsys, "fourbar.toml", "--json")
    assert code == 0 and err == [] and "warnings" not in json.loads(out)


# -- the rest of docs/errors.md, one case each ------------------------------------------------------------
B_LINE = 'B = { from = "A", length = 40, angle = 60 }'
C_LINE = 'C = { circles = [["B", 120], ["D", 80]], near = [90, 80] }'
C_ON_LINE = 'C = { circle = ["B", 120], line = LINE, near = [90, 80] }'
REF = "alpha = 0\n[reference]\n"


@pytest.mark.parametrize("base, old, new, where, gist", [
    ("f", B_LINE, 'B = { from = "A", to = "D", length = 40, angle = 60 }', "points.B (line 8)",
     "give one of 'from' and 'to', not both"),
    ("f", B_LINE, 'B = { from = "A", length = 40, angle = 60, along = ["A", "D"] }', "points.B (line 8)",
     "give one of 'angle' and 'along', not both"),
    ("f", B_LINE, 'B = { from = "A", length = 40, along = "AD" }', "points.B.along (line 8)",
     r'expected \["Q", "R"\], got "AD"'),
    ("f", "[points]\nA = [0, 0]\nD = [100, 0]\n" + B_LINE + "\n" + C_LINE + "\n", "[points]\n", "points (line 5)",
     "^no points$"),
    ("f", C_LINE, C_ON_LINE.replace("LINE", "5"), "points.C.line (line 9)", "expected a line, got 5"),
    ("f", C_LINE, C_ON_LINE.replace("LINE", '{ through = "D" }'), "points.C.line (line 9)",
     "a line needs 'through' and 'angle'"),
    ("f", C_LINE, C_ON_LINE.replace("LINE", '["D", "D"]'), "points.C.line (line 9)", "the line's two points coincide"),
    ("f", C_LINE, C_ON_LINE.replace("LINE", '["A", "D"]').replace('["B", 120]', '"B"'), "points.C.circle (line 9)",
     r'expected \["P", r\], got "B"'),
    ("f", "near = [90, 80]", 'near = { from = "B" }', "points.C.near (line 9)", r'expected \{from = "P", angle = deg\}'),
    ("s", 'angle = 0\n[driver]', 'centre = "C"\n[driver]', "sliders[0].centre (line 17)",
     "the path's centre is the point 'C' itself"),
    ("s", 'link = "1"\nomega = 10', 'slider = "C"', "driver (line 18)", "a slider driver needs 'speed'"),
    ("g", 'links = ["2", "3"]', 'links = ["2", "3", "1"]', "contacts[0].links (line 15)",
     r'expected links = \["a", "b"\], got a list'),
    ("g", 'centres = ["O2", "O3"]', 'centres = "O2"', "contacts[0].centres (line 18)",
     r'expected \["Ca", "Cb"\], got "O2"'),
    ("f", "alpha = 0", REF + 'velocity = { "B" = [400] }', "reference.velocity.B (line 22)",
     r"expected a magnitude or \[magnitude, direction\], got a list of 1"),
    ("f", "alpha = 0", REF + 'acceleration = { "B" = "400" }', "reference.acceleration.B (line 22)",
     r'expected a number, got the string "400"'),
    ("f", "alpha = 0", REF + 'values = { V_B = [400, 30, 2] }', "reference.values.V_B (line 22)",
     r"expected a magnitude or \[magnitude, direction\], got a list of 3"),
    ("f", "alpha = 0", REF + "values = [1, 2]", "reference.values (line 22)", "expected a table, got a list"),
])
def test_more_input_errors(capsys, tmp_path, base, old, new, where, gist):
    text = {"f": FOURBAR, "s": SLIDER, "g": GEARS}[base]
    fails(capsys, tmp_path, edit(text, old, new), where, gist)


def test_a_note_must_explain_a_printed_value(capsys, tmp_path):
    # a note for V_B where no V_B is printed: a slip of the pen (the note would never be shown)
    _, hint = fails(capsys, tmp_path, edit(FOURBAR, "alpha = 0", REF + 'note = { V_B = "misprint" }'),
                    "reference.note.V_B (line 22)", "a note for 'V_B', which is no reference value")
    assert "no printed values" in hint
    _, hint = fails(capsys, tmp_path, edit(FOURBAR, "alpha = 0", REF + 'omega = { "3" = 1.0 }\nnote = { V_B = "x" }'),
                    "reference.note.V_B (line 23)", "no reference value")
    assert "omega_3" in hint
    # a note keyed like its value, in each of the ways compare() reads it, is fine
    for table, note in (('omega = { "3" = 1.0 }', "omega_3"), ('omega = { "3" = 1.0 }', '"3"'),
                        ('velocity = { B = [400, 60] }', "V_B"), ('velocity = { B = [400, 60] }', "B"),
                        ('acceleration = { C = [1, 2] }', "A_C"), ('speed = { C = 3 }', "V_C"),
                        ('values = { V_CB = 3 }', "V_CB")):
        velpoly.load(edit(FOURBAR, "alpha = 0", REF + f'{table}\nnote = {{ {note} = "x" }}'))


def test_a_slot_of_no_radius(capsys, tmp_path):
    fails(capsys, tmp_path, FOURBAR + '\n[[slots]]\npin = "C"\nlink = "3"\nslot = "4"\ncentre = "C"\n',
          "slots[0].centre (line 26)", "the slot's centre is the point 'C' itself")


@pytest.mark.parametrize("base, old, new, where, gist", [
    ("f", B_LINE, 'B = { length = 40, angle = 60 }', "points.B (line 8)", "incomplete construction: length, angle"),
    ("f", B_LINE, 'B = { from = "A", length = 40, along = ["D", "D"] }', "points.B.along (line 8)",
     "'D' and 'D' coincide: no direction"),
    ("f", "length = 40", "length = 0", "links.2.points (line 13)",
     "its first two points 'A' and 'B' coincide, so the link's angle is undefined"),
    ("f", "A = [0, 0]", '"" = [0, 0]\nA = [0, 0]', 'points."" (line 6)', "a point's name is empty"),
    ("f", "D = [100, 0]", 'D = [100, 0]\n"E\\tF" = [5, 5]', r"points.E\tF (line 8)",
     "a point's name must not contain control characters"),
    ("g", "K = [0, 10]", "K = [0, 10]\nZ = [0, 0]", "contacts[0].centres (line 19)",
     "the two centres of curvature coincide"),
    ("g", "omega = 10", 'omega = 10\n[reference]\nvelocity = { P = [1, 0] }', "reference.velocity.P (line 23)",
     "point 'P' moves differently on links 2, 3: say which"),
])
def test_the_remaining_input_errors(capsys, tmp_path, base, old, new, where, gist):
    text = edit({"f": FOURBAR, "g": GEARS}[base], old, new)
    if "Z = [0, 0]" in text:   # a centre of link 3 at O2's place
        text = edit(edit(text, '3 = { points = ["O3", "R"] }', '3 = { points = ["O3", "R", "Z"] }'),
                    'centres = ["O2", "O3"]', 'centres = ["O2", "Z"]')
    fails(capsys, tmp_path, text, where, gist)


def test_a_driver_the_joints_hold_still(capsys, tmp_path):
    # the crank 5 is pinned to the frame at A and at E: it cannot turn, though the four-bar can
    text = edit(edit(FOURBAR, "D = [100, 0]", "D = [100, 0]\nE = [0, -30]"), '1 = { points = ["A", "D"]',
                '1 = { points = ["A", "D", "E"]')
    text = edit(edit(text, '4 = { points = ["D", "C"] }', '4 = { points = ["D", "C"] }\n5 = { points = ["A", "E"] }'),
                'link = "2"', 'link = "5"')
    fails(capsys, tmp_path, text, "driver (line 19)", "the driver's motion is fixed by the joints")


def test_a_file_that_cannot_be_read(capsys, tmp_path, monkeypatch):
    f = tmp_path / "locked.toml"
    f.write_text(FOURBAR)

    def denied(self, *a, **kw):
        raise PermissionError(13, "Permission denied")
    monkeypatch.setattr(Path, "read_text", denied)
    assert main(["solve", str(f)]) == 2
    assert capsys.readouterr().err.splitlines() == [f"error: {f}: cannot read: Permission denied",
                                                    "hint: check the path and its permissions"]


def test_one_error_hierarchy():
    """velpoly.VelpolyError is the root; input errors exit 2, pose errors 3 and name their links."""
    assert issubclass(velpoly.InputError, velpoly.VelpolyError) and issubclass(velpoly.PoseError, velpoly.VelpolyError)
    assert issubclass(velpoly.AssemblyError, velpoly.PoseError) and issubclass(velpoly.SingularPoseError, velpoly.PoseError)
    assert not issubclass(velpoly.PoseError, velpoly.InputError)
    assert (velpoly.InputError("x").exit_code, velpoly.AssemblyError("x").exit_code,
            velpoly.SingularPoseError("x").exit_code) == (2, 3, 3)
    e = velpoly.SingularPoseError("singular pose", where="reference pose", file="f.toml", hint="h", links=(3, "4"))
    assert (e.what, e.where, e.file, e.hint, e.links) == ("singular pose", "reference pose", "f.toml", "h", ("3", "4"))
    assert str(e) == e.line() == "f.toml: reference pose: singular pose (links 3, 4)"
    assert velpoly.PoseError("toggle of links 2, 3", links=("2", "3")).line() == "toggle of links 2, 3"
    assert velpoly.InputError("a\nb", where="points.A").line() == "points.A: a\\nb"


@pytest.mark.parametrize("base, old, new, where, gist", [
    ("f", 'omega = "10 rad/s"', "omega = 1e200", "driver.omega (line 19)",
     r"1e\+200 rad/s is too large: speeds of 1.52e\+202 mm/s \(at most 1e\+100\)"),
    ("f", "alpha = 0", "alpha = 1e300", "driver.alpha (line 20)", r"1e\+300 rad/s\^2 is too large: accelerations"),
    ("f", "alpha = 0", "alpha = 1.7e308", "driver.alpha (line 20)", r"accelerations of beyond 1e\+308"),
    ("f", "D = [100, 0]", "D = [100, 0]\nZ = [1e120, 0]", "points (line 5)",
     r"the mechanism's size 1e\+120 mm is out of range \(1e-100 to 1e\+100\)"),
    ("s", 'link = "1"\nomega = 10', 'slider = "C"\nspeed = 1e150', "driver.speed (line 20)", "too large: speeds of 1e"),
])
def test_numbers_beyond_what_the_arithmetic_holds(capsys, tmp_path, base, old, new, where, gist):
    """A size or a driver motion whose speeds or accelerations would overflow (or vanish) is an input
    error, never an internal error or a silently NaN result."""
    text = edit({"f": FOURBAR, "s": SLIDER}[base], old, new)
    if "Z = " in text:
        text = edit(text, '1 = { points = ["A", "D"]', '1 = { points = ["A", "D", "Z"]')
    fails(capsys, tmp_path, text, where, gist)


def test_tiny_mechanisms_are_out_of_range_too(capsys, tmp_path):
    text = FOURBAR.replace("[100, 0]", "[1e-118, 0]").replace("length = 40", "length = 4e-119")
    text = text.replace('[["B", 120], ["D", 80]], near = [90, 80]', '[["B", 1.2e-118], ["D", 8e-119]], near = [9e-119, 8e-119]')
    fails(capsys, tmp_path, text, "points (line 5)", "the mechanism's size .* mm is out of range")
