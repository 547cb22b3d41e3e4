"""The --steps captions in the textbook's words (issue 17 item 8a), checked at the data level on
generated mechanisms of every kind (tests/zoo.py) and on the gallery.

Every step of both polygons has a caption (``Step.caption``) that names what the step locates (each
point key found, as ``V_B`` / ``A_B``), the links whose rates it fixes (``omega_3`` / ``alpha_3``)
and, for a link's image, the link; it carries no debugging words ("scale", "turned", degrees), no
raw point key ("P@cam") and no underscore outside a textbook quantity (``V_B``, ``A^n_BA``,
``omega_3``, ``O_v``). Typeset for a figure (``render.sheet.equation_tex``), no underscore is left
outside mathtext. Every pole found has its caption (``poles.pole_caption``) naming it and its lines.
"""
from __future__ import annotations

import re

import pytest

import velpoly
from paths import EXAMPLES
from velpoly.errors import VelpolyError
from velpoly.poles import locate_poles, pole_caption, pole_label
from velpoly.polygons import acceleration_polygon, point_text, velocity_polygon
from zoo import zoo

# a textbook quantity: V_B, A^n_BA, A^t_B3O4, V_A3/A4, omega_3, alpha_cam, R_AO2, P_13, P_{2-10}, O_v
QUANTITY = re.compile(r"(?<![A-Za-z])(?:omega|alpha|theta|[VARP])(?:\^[nt])?_(?:\{[^}]*\}|[A-Za-z0-9]+(?:/[A-Za-z0-9]+)?)"
                      r"|(?<![A-Za-z])O_[av]\b")
DEBUG = re.compile(r"(?i:\bscale\b|\bturned\b|\bdeg\b|\bnan\b)|°|@|\bNone\b|\bTrue\b|\bFalse\b|[\[\]]")


def _solves():
    """(name, how to solve it) of every gallery file (loaded here: a file that stops loading fails the test) and
    90 zoo specimens (solved at their drawn pose already, as ``velpoly.solve(velpoly.load(mech))``: their
    solutions)."""
    out = [(p.stem, lambda m=velpoly.load(p): velpoly.solve(m)) for p in sorted(EXAMPLES.glob("*.toml"))]
    out += [(f"zoo {i} {s.kind}", lambda s=s: s.drawn) for i, s in enumerate(zoo(20261125, 90))]
    return out


def _name_of(poly, key) -> str:
    """The textbook name a polygon gives a point key: B for key B, B4 for key B@4 (its label, upper)."""
    label = poly.labels[key].rstrip("'")
    return label


def check_caption(text: str, where: str) -> None:
    assert text and text == text.strip(), where
    assert not DEBUG.search(text), f"{where}: debugging text in {text!r}"
    rest = QUANTITY.sub("Q", text)
    assert "_" not in rest, f"{where}: an underscore outside a quantity in {text!r}"


def check_typeset(text: str, where: str) -> None:
    from velpoly.render.sheet import equation_tex
    tex = equation_tex(text)
    outside = "".join(tex.split("$")[0::2])
    assert "_" not in outside, f"{where}: {tex!r}"


def check_step(poly, step, where: str) -> None:
    X, rate = ("V", "omega") if poly.kind == "velocity" else ("A", "alpha")
    text = step.caption
    check_caption(text, where)
    # each point located is named as the quantity the step finds (a trial step: the one assumed)
    found = step.found if not text.startswith("Trial solution") else ()
    for key in found:
        name = _name_of(poly, key)
        assert re.search(rf"(?<![A-Za-z]){X}_{re.escape(name)}(?![A-Za-z0-9])", text, re.I), \
            f"{where}: {key} ({X}_{name}) not named in {text!r}"
    for lk in step.omegas:
        assert f"{rate}_{lk}" in text, f"{where}: {rate}_{lk} not named in {text!r}"
    if step.kind in ("image", "driver") and step.link is not None:
        assert f"link {step.link}" in text or f"{rate}_{step.link}" in text or f"{X}_" in text, where
    if step.kind == "intersection":
        assert text.count("the line through") == 2, f"{where}: {text!r}"
    if step.kind == "image":
        level = "velocity" if X == "V" else "acceleration"
        assert f"from the {level} image of link {step.link}" in text, f"{where}: {text!r}"
    if step.kind == "instant-centre":
        assert f"the instant centre of link" in text and "O_v" in text, where


@pytest.mark.xdist_group("zoo")   # on test_zoo's worker: its first 90 specimens are made once there (tests/zoo.py)
def test_captions_of_generated_mechanisms():
    """Every step of both polygons and every pole found, over the gallery and 90 zoo mechanisms of
    every kind (one pass: the solves are the cost)."""
    kinds = set()
    checked = 0
    for n, (name, solved) in enumerate(_solves()):
        try:
            sol = solved()
            polys = [velocity_polygon(sol)] + ([acceleration_polygon(sol)] if sol.has_accelerations else [])
        except VelpolyError:
            continue
        for poly in polys:
            for step in poly.steps:
                where = f"{name} {poly.kind} step {step.index + 1} ({step.kind})"
                check_step(poly, step, where)
                if n % 3 == 0:
                    check_typeset(step.caption, where)
                kinds.add((poly.kind, step.kind))
                checked += 1
        if n % 2 == 0:
            check_pole_captions(name, sol)
    # every kind of step was seen, at both levels
    for level in ("velocity", "acceleration"):
        for kind in ("known", "driver", "intersection", "image", "auxiliary"):
            assert (level, kind) in kinds, (level, kind)
    assert ("velocity", "instant-centre") in kinds
    assert checked > 800


def check_pole_captions(name, sol) -> None:
    ps = locate_poles(sol)
    compact = all(len(lk) == 1 for lk in ps.links)
    for p in ps.poles.values():
        if p.order == 0:
            continue
        text = pole_caption(p, lambda key: pole_label(key, compact))
        check_caption(text, f"{name} pole {p.key}")
        assert text.startswith(pole_label(p.key, compact)), text
        if p.how == "kennedy":
            for ln in p.lines:
                if ln[0] not in ("normal", "slot normal"):
                    assert pole_label(ln[0], compact) in text and pole_label(ln[1], compact) in text, text
            assert "Aronhold-Kennedy" in text


def test_textbook_captions_of_a_four_bar():
    """Example 3.6 (four-bar with a coupler plate): the captions as the book words them."""
    sol = velpoly.solve(velpoly.load(EXAMPLES / "ex3_6_fourbar.toml"))
    caps = [s.caption for s in velocity_polygon(sol).steps]
    assert caps[1] == "V_A = omega_2 x R_AO2, ⊥ O₂A"
    assert caps[2] == ("V_B = V_A + V_BA = V_O4 + V_BO4: b on the line through a ⊥ AB and the line through "
                       "O_v ⊥ O₄B; omega_3 = V_BA / AB; omega_4 = V_BO4 / O₄B")
    assert caps[3].endswith("e, f from the velocity image of link 3, abef similar to ABEF")
    acc = [s.caption for s in acceleration_polygon(sol).steps]
    assert "b' on the line through a' + A^n_BA ⊥ AB" in acc[2]


def test_coriolis_and_coincident_points_in_words():
    """An inverted slider-crank: the guide's point under the block is named a₄ and the Coriolis
    term appears in the line it offsets."""
    sol = velpoly.solve(velpoly.load(EXAMPLES / "ex3_3_inverted_slider.toml"))
    acc = [s.caption for s in acceleration_polygon(sol).steps]
    step = next(c for c in acc if c.startswith("A_A₄ ="))   # a point of link 4 named as velpoly.names names it
    assert "a₄' on the line through" in step and "- 2 omega_4 x V_A₃/A₄ ∥ the path of B on link 4" in step
    assert "alpha_3 = alpha_4 (block and straight guide turn together)" in step


def test_point_text():
    assert point_text("O2") == "O₂" and point_text("B", "4") == "B₄" and point_text("P@cam") == "P(cam)"
    assert point_text("A") == "A" and point_text("12") == "12"


def test_steps_frames_show_the_captions():
    """draw --steps captions each frame with its step's caption (the polygons' steps in order, then
    on the poles sheet the poles in their order of discovery), typeset with no stray underscore."""
    from velpoly.render.sheet import Constructions, equation_tex, frames
    sol = velpoly.solve(velpoly.load(EXAMPLES / "ex3_3_inverted_slider.toml"))
    v, a, ps = velocity_polygon(sol), acceleration_polygon(sol), locate_poles(sol)
    cons = Constructions(v, a, ps)
    full = frames("full", cons, True)
    want = [s.caption for s in v.steps] + [s.caption for s in a.steps]
    assert [f.caption for f in full] == [f"Step {k}: " + equation_tex(c) for k, c in enumerate(want, 1)]
    poles = frames("poles", cons, True)
    found = sorted((p for p in ps.poles.values() if p.order > 0), key=lambda p: p.order)
    assert len(poles) == len(found) + 1
    for f, p in zip(poles[1:], found):
        assert f.caption.startswith(f"Step {p.order}: $P_{{{p.links[0]}{p.links[1]}}}$ on the line ")
        assert "_" not in "".join(f.caption.split("$")[0::2])
