"""Fuzzing: whatever the file, velpoly solves it or says in one line what is wrong.

Hypothesis generates mechanisms (random four-bars, slider-cranks, inverted
slider-cranks, six-bars and the textbook examples), mutates them (deleted
keys, wrong types, random values, swapped names, renamed keys) and feeds them
to ``velpoly.load`` + ``velpoly.solve`` in-process, both as dicts and as TOML
text, along with corrupted and random TOML text. Every example either solves
(with a JSON-serialisable result) or raises a :class:`velpoly.VelpolyError`
whose message is one line naming the file: no other exception, ever. A
sample also goes through the command line (velpoly.cli.main in-process: its exit codes and messages).

The examples add up to about 500 a run (``EXAMPLES``): most of them mutated files, whose errors
only this module explores (150: each is loaded and solved twice, as a dict and as TOML text; the
mutations were 500, then 250, until the suite had to fit 2 minutes on 2 cores; half of a run's time is
hypothesis drawing and mutating these nested dicts; ``VELPOLY_FUZZ_SCALE=3`` runs 450); valid mechanisms
of every kind are also solved and checked by the seeded zoo (tests/test_zoo.py), so fewer of them are
generated here (80: each of the five kinds about 16 times, a tenth at another driver angle).
"""
from __future__ import annotations

import copy
import json
import math
import os
import tomllib

import numpy as np
import pytest
from hypothesis import HealthCheck, given, note, settings, strategies as st

import texts
import velpoly
from mechanisms import (CAM_FLAT, CAM_ROLLER, EXAMPLE_3_6, SIXBAR_1_4_4, SLOTTED_LEVER, WHEEL_ROLLING, fourbar,
                        in_process, inverted_slider_crank, ranges_by_dyads_only, slider_crank)
from mechanisms import drop_tiny

SCALE = float(os.environ.get("VELPOLY_FUZZ_SCALE", "1"))   # e.g. 20 for a long hunt; CI runs 1
EXAMPLES = {k: int(n * SCALE) for k, n in {"valid": 80, "mutated": 150, "corrupted": 200, "random": 150}.items()}
FUZZ = settings(deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                                      HealthCheck.filter_too_much])
NAME = "fuzz.toml"


# -- a small TOML writer (tomllib only reads) ----------------------------------------------------------
class Unwritable(Exception):
    """A value TOML cannot hold (None)."""


def toml_key(k) -> str:
    return toml_string(str(k))


def toml_string(s: str) -> str:
    return json.dumps(s).replace("\x7f", "\\u007f")


def toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf") if math.isinf(v) else repr(v)
    if isinstance(v, str):
        return toml_string(v)
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{toml_key(k)} = {toml_value(x)}" for k, x in v.items()) + " }" if v else "{}"
    raise Unwritable(type(v).__name__)


def to_toml(d: dict) -> str:
    """``d`` as a TOML document: scalars first, then [tables] and [[arrays of tables]]."""
    def is_tables(v):
        return isinstance(v, list) and v and all(isinstance(x, dict) for x in v)
    head, body = [], []
    for k, v in d.items():
        if isinstance(v, dict):
            body.append(f"[{toml_key(k)}]")
            body.extend(f"{toml_key(kk)} = {toml_value(vv)}" for kk, vv in v.items())
        elif is_tables(v):
            for item in v:
                body.append(f"[[{toml_key(k)}]]")
                body.extend(f"{toml_key(kk)} = {toml_value(vv)}" for kk, vv in item.items())
        else:
            head.append(f"{toml_key(k)} = {toml_value(v)}")
    return "\n".join(head + body) + "\n"


def test_the_writer_round_trips():
    for text in (SIXBAR_1_4_4, EXAMPLE_3_6, WHEEL_ROLLING, CAM_FLAT, CAM_ROLLER, SLOTTED_LEVER):
        d = tomllib.loads(text)
        assert tomllib.loads(to_toml(d)) == d
    d = {"a": [1.5, float("inf"), "x\x7f\n\"y"], "t": {"k": {"n": True}}}
    assert tomllib.loads(to_toml(d)) == d


@pytest.fixture(scope="module", autouse=True)
def _ranges_by_dyads_only():
    """A generated file asking for an angle beyond a toggle is refused with the reachable range in its
    message: by a dyad walk where the mechanism has one, else (0, 0) (tests/mechanisms.py): the contact
    examples took one to nine seconds a run, as many as hypothesis happened to send past a toggle."""
    with pytest.MonkeyPatch.context() as mp:
        ranges_by_dyads_only(mp)
        yield


# -- the property --------------------------------------------------------------------------------------
def check(source, file=NAME):
    """Solve ``source`` or fail with a VelpolyError of one line naming ``file``."""
    m = None
    try:
        m = velpoly.load(source, name=file)
        s = velpoly.solve(m)
        data = json.dumps(s.to_dict(), allow_nan=False)   # what `velpoly solve --json` prints
    except velpoly.VelpolyError as e:
        msg, hint = e.line(), e.hint_line()
        note(f"error: {msg}\nhint: {hint}")
        assert "\n" not in msg and "\r" not in msg and "\n" not in hint
        assert msg.startswith(file + ": "), msg
        assert e.exit_code == (3 if isinstance(e, velpoly.PoseError) else 2)
        assert "malformed entry" not in msg, msg      # the loader's last line of defence never fires
        assert e.hint, msg
        return e
    assert json.loads(data)["format"] == 1
    for key, p in s.position.items():
        assert np.all(np.isfinite(p)), key
    return s


# -- mechanisms -----------------------------------------------------------------------------------------
OMEGAS = st.one_of(st.floats(-50, 50).filter(lambda x: abs(x) > 0.01),
                   st.sampled_from(["60 rpm", "10 rad/s cw", "-10 rad/s cw", "2 Hz", "90 deg/s ccw", "1 rev/s"]))
ALPHAS = st.one_of(st.floats(-50, 50).map(drop_tiny), st.sampled_from(["5 rad/s^2 cw", "0 rad/s^2", "3 rad/s^2 ccw"]))
LENGTH = st.floats(0.5, 20)
ANGLE = st.floats(-180, 180)


def sixbar(a, b, c, d, e, g, r5, r6, theta, side_c, side_f, omega):
    """A Watt six-bar written with constructions only (it may not assemble: that is an input error)."""
    return {
        "title": "six-bar", "units": "mm",
        "points": {"A": [0, 0], "D": [d, 0], "G": [d, -g],
                   "B": {"from": "A", "length": a, "angle": theta},
                   "C": {"circles": [["B", b], ["D", c]], "side": side_c},
                   "E": {"from": "D", "length": e, "along": ["C", "D"]},
                   "F": {"circles": [["E", r5], ["G", r6]], "side": side_f}},
        "links": {"1": {"points": ["A", "D", "G"], "frame": True}, "2": {"points": ["A", "B"]},
                  "3": {"points": ["B", "C"]}, "4": {"points": ["D", "C", "E"]}, "5": {"points": ["E", "F"]},
                  "6": {"points": ["G", "F"]}},
        "driver": {"link": "2", "omega": omega},
    }


SIDES = st.sampled_from(["left", "right"])
fourbars = st.builds(fourbar, LENGTH, LENGTH, LENGTH, LENGTH, ANGLE, OMEGAS, ALPHAS, SIDES,
                     st.none() | st.tuples(LENGTH, ANGLE))
slider_cranks = st.builds(slider_crank, LENGTH, LENGTH, st.floats(-5, 5), ANGLE, OMEGAS, ALPHAS, st.floats(-90, 90))
inverted = st.builds(inverted_slider_crank, LENGTH, LENGTH, ANGLE, OMEGAS, ALPHAS)
sixbars = st.builds(sixbar, LENGTH, LENGTH, LENGTH, LENGTH, LENGTH, LENGTH, LENGTH, LENGTH, ANGLE, SIDES, SIDES,
                    OMEGAS)
TEXTBOOK = [tomllib.loads(t) for t in (SIXBAR_1_4_4, EXAMPLE_3_6, WHEEL_ROLLING, CAM_FLAT, CAM_ROLLER, SLOTTED_LEVER)]
textbook = st.sampled_from(TEXTBOOK).map(copy.deepcopy)
mechanisms = st.one_of(fourbars, slider_cranks, inverted, sixbars, textbook)


@st.composite
def with_angle(draw, mech):
    """Sometimes ask for another driver angle (a re-assembly along the branch)."""
    d = draw(mech)
    if "link" in d.get("driver", {}) and draw(st.integers(0, 9)) == 0:
        d["driver"]["angle"] = draw(ANGLE)
    return d


@settings(FUZZ, max_examples=EXAMPLES["valid"])
@given(with_angle(mechanisms), st.booleans())
def test_valid_mechanisms_solve_or_say_why(d, as_text):
    r = check(to_toml(d) if as_text else d)
    if isinstance(r, velpoly.InputError):   # a random mechanism may not close: only its points are wrong
        assert r.where.startswith("points."), r


def test_most_generated_mechanisms_solve():
    # the generators are not a trick: most of what they make is a working mechanism
    ok = 0
    for i in range(40):
        d = fourbar(a=2 + i % 3, b=8, c=7, d=9, theta=9.0 * i, branch=("left", "right")[i % 2])
        ok += isinstance(check(d), velpoly.Solution)
    assert ok == 40


# -- mutations ---------------------------------------------------------------------------------------------
WORDS = ["A", "B", "C", "D", "E", "F", "O2", "O4", "P", "K", "0", "1", "2", "3", "4", "5", "left", "right", "flat",
         "rolling", "sliding", "60 rpm", "10 rad/s cw", "5 rad/s^2", "a-b", "B@3", "", " ", "points", "links",
         "frame", "near", "side", "from", "to", "along", "circles", "circle", "line", "through"]
scalars = st.one_of(st.booleans(), st.integers(-10 ** 6, 10 ** 6), st.floats(), st.floats(-100, 100),
                    texts.text(max_size=8), st.sampled_from(WORDS))
junk = st.recursive(scalars, lambda inner: st.lists(inner, max_size=3) |
                    st.dictionaries(st.one_of(st.sampled_from(WORDS), texts.text(max_size=5)), inner, max_size=3),
                    max_leaves=6)


def places(d, out=None):
    """Every (container, key) in the nested structure."""
    out = [] if out is None else out
    items = d.items() if isinstance(d, dict) else enumerate(d)
    for k, v in list(items):
        out.append((d, k))
        if isinstance(v, (dict, list)):
            places(v, out)
    return out


def names_in(d) -> list:
    found = set()
    for c, k in places(d):
        if isinstance(c, dict):
            found.add(k)
        if isinstance(c[k], str):
            found.add(c[k])
    return sorted(map(str, found))


@st.composite
def mutated(draw, mech):
    d = draw(mech)
    for _ in range(draw(st.integers(1, 3))):
        spots = places(d)
        if not spots:
            break
        c, k = draw(st.sampled_from(spots))
        op = draw(st.sampled_from(["delete", "junk", "swap", "rename", "add", "number", "list"]))
        note(f"{op} at {k!r}")
        if op == "delete":
            del c[k]
        elif op == "junk":
            c[k] = draw(junk)
        elif op == "swap":   # another name from the file where a name (or anything) was
            c[k] = draw(st.sampled_from(names_in(d) or WORDS))
        elif op == "rename" and isinstance(c, dict):
            new = draw(st.sampled_from(names_in(d) + WORDS))
            c[new] = c.pop(k)
        elif op == "add":
            target = c[k] if isinstance(c[k], dict) else (c if isinstance(c, dict) else d)
            target[draw(st.sampled_from(WORDS + ["angle", "omega", "length", "speed", "slip", "centre"]))] = draw(junk)
        elif op == "number" and isinstance(c[k], (int, float)) and not isinstance(c[k], bool):
            c[k] = c[k] * draw(st.sampled_from([-1, 0, 1e-12, 1e-6, 1e6, 1e12, 1e300])) + draw(st.sampled_from([0, 1]))
        elif op == "list" and isinstance(c[k], list):
            lst = c[k]
            which = draw(st.integers(0, 2))
            if which == 0 and lst:
                lst.pop(draw(st.integers(0, len(lst) - 1)))
            elif which == 1 and lst:
                lst.append(copy.deepcopy(lst[0]))
            else:
                lst.append(draw(junk))
    return d


@settings(FUZZ, max_examples=EXAMPLES["mutated"])
@given(mutated(with_angle(mechanisms)))
def test_mutated_mechanisms(d):
    check(d)
    try:
        text = to_toml(d)
    except Unwritable:
        return
    check(text)


# -- TOML text --------------------------------------------------------------------------------------------
TOKENS = ["[", "]", "[[", "]]", "{", "}", "=", '"', "'", ",", ".", "\n", "#", "nan", "inf", "-inf", "true", "1e999",
          "[points]", "[links]", "[driver]", "[[sliders]]", "[[contacts]]", "[reference]", "A = [0, 0]",
          'link = "2"', "omega = ", "points = [", '"""', "\\u00", "\t", "\r\n", "é"]


@st.composite
def corrupted(draw):
    text = to_toml(draw(mechanisms))
    lines = text.split("\n")
    for _ in range(draw(st.integers(1, 4))):
        op = draw(st.integers(0, 4))
        if op == 0 and len(text) > 1:      # cut a slice
            i = draw(st.integers(0, len(text) - 1))
            text = text[:i] + text[i + draw(st.integers(1, 12)):]
        elif op == 1:                      # insert a token
            i = draw(st.integers(0, len(text)))
            text = text[:i] + draw(st.sampled_from(TOKENS) | texts.text(max_size=4)) + text[i:]
        elif op == 2:                      # drop, duplicate or swap lines
            lines = text.split("\n")
            i, j = draw(st.integers(0, len(lines) - 1)), draw(st.integers(0, len(lines) - 1))
            how = draw(st.integers(0, 2))
            if how == 0:
                lines.pop(i)
            elif how == 1:
                lines.insert(j, lines[i])
            else:
                lines[i], lines[j] = lines[j], lines[i]
            text = "\n".join(lines)
        elif op == 3:                      # cut the file short
            text = text[:draw(st.integers(0, len(text)))]
        else:                              # change a digit
            digits = [i for i, ch in enumerate(text) if ch.isdigit()]
            if digits:
                i = draw(st.sampled_from(digits))
                text = text[:i] + draw(st.sampled_from("0123456789-.e")) + text[i + 1:]
    return text + "\n"


@settings(FUZZ, max_examples=EXAMPLES["corrupted"])
@given(corrupted())
def test_corrupted_toml_text(text):
    check(text)


@settings(FUZZ, max_examples=EXAMPLES["random"])
@given(st.one_of(texts.text(max_size=200), st.lists(st.sampled_from(TOKENS + WORDS), max_size=40).map(" ".join)))
def test_random_text(text):
    check(text + "\n")   # a newline: always TOML text, never taken for a path


# -- the command line, for a sample -------------------------------------------------------------------------
@settings(FUZZ, max_examples=6)
@given(st.one_of(mutated(mechanisms), mechanisms).filter(lambda d: _writable(d)), st.sampled_from(["solve", "draw"]))
def test_command_line_sample(tmp_path_factory, d, command):
    folder = tmp_path_factory.mktemp("cli")
    f = folder / "mech.toml"
    f.write_text(to_toml(d), encoding="utf-8")
    args = ["solve", str(f), "--json"]
    if command == "draw":   # a wrong output type is refused before any work
        args = ["draw", str(f), "-o", str(folder / "out.txt")]
    r = in_process(args)
    assert "Traceback" not in r.stderr
    if command == "draw":
        assert r.returncode == 2 and r.stderr.splitlines()[0].endswith("unknown figure type '.txt'")
        assert list(folder.iterdir()) == [f]
        return
    assert r.returncode in (0, 2, 3), r.stderr
    if r.returncode == 0:
        assert json.loads(r.stdout)["format"] == 1
        assert all(line.startswith("warning: ") for line in r.stderr.splitlines())
    else:
        err = r.stderr.splitlines()
        assert r.stdout == "" and len(err) == 2, r.stderr
        assert err[0].startswith(f"error: {f}: ") and err[1].startswith("hint: ")


def _writable(d) -> bool:
    try:
        to_toml(d)
        return True
    except Unwritable:
        return False
