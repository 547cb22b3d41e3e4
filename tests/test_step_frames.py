"""In ``--steps`` frames, labels do not jump between frames (issue 17, item 8; render/sheet.py,
LabelPlacer.settle in render/labels.py).

Every frame is drawn with the pins of the finished construction (each label's place, ring and font size
there, each arrow to a pole at infinity's tip, the driver's layout of arcs, each reason's place along its
line); a label whose pinned box is free in a frame stands at it, at the pinned size, even where another
label, leader or driver's value stood on it when it was placed (the labels off their pins are lifted
together and moved; a reason the finished construction has no place for keeps off the others' places).
Checked at the data level: every text with a gid (pole and point labels, link numbers, the driver's values,
image labels, reasons, scale bars' numbers) present in two consecutive frames has the same position and font
size, on Problem 1.4.4 and generated six-bars (test_pole_labels' seeded ``sixbars``), slides style, on the
consecutive frames where main moved some: the poles sheet's frames 5-6 of Problem 1.4.4 (1 pole label) and 1-2
of six-bar 1 of seed 7 (4, on 464fb66); the velocity sheet's frames 4-5 of six-bar 2 (the driver's arcs laid
out anew with its values at their pins: a link number and two point names moved, on e730b9f) and Example
3.8's frames 3-4 (a reason moved along its line: its place was taken by a reason the finished construction
does not write, on e730b9f).

Measured over every frame change (too slow for the suite): no label of those kinds moves on Example 3.4,
Problem 1.4.4 and the four six-bars ``sixbars(7, 4)`` (main: 42, 1 and 48 pole labels, 13 others), nor on the
velocity and acceleration sheets' frames of every gallery example, ``sixbars(7, 4)`` and 24 generated
mechanisms of ``zoo.zoo(4, 24)``, both styles (e730b9f: 4 reasons on 4 examples, 3 labels on one six-bar)."""
from __future__ import annotations

import functools
from pathlib import Path

import pytest

import velpoly
from test_pole_labels import sixbars
from velpoly.render import sheet
from velpoly.render.constructions import constructions
from velpoly.render.style import get_style, rc_context

EXAMPLES = Path(velpoly.__file__).parent / "examples"


@functools.cache
def _sixbars():
    return tuple(sixbars(7, 3))


def _labels(fig) -> dict:
    """gid -> (position, font size) of every text with a gid on the figure's panels (the table's aside)."""
    return {(ax.get_label(), t.get_gid()): (tuple(map(float, t.get_position())), t.get_fontsize())
            for ax in fig.axes if ax.get_label() != "table" for t in ax.texts if t.get_gid() and t.get_text()}


def _moved(sol, first: int, name: str = "poles") -> list:
    """The labels that move or change size between frames ``first`` and ``first + 1`` of the sheet ``name``'s
    steps (slides), each frame drawn with the finished construction's pins, as draw_to_file does (the last frame
    is the finished construction itself)."""
    st = get_style("slides")
    with rc_context(st):
        cons = constructions(sol, name)
        frames = sheet.frames(name, cons, True)
        done = sheet.render(sol, name, st, cons=cons, frame=frames[-1]).figure
        a, b = (_labels(done if k == len(frames) - 1 else
                        sheet.render(sol, name, st, cons=cons, frame=frames[k], pins=done._velpoly_pins).figure)
                for k in (first, first + 1))
    assert a and b
    return [(g, a[g], b[g]) for g in a if g in b and a[g] != b[g]]


@pytest.mark.parametrize("case, first, name", [("problem_1_4_4", 4, "poles"), ("sixbar-1", 0, "poles"),
                                               ("sixbar-2", 3, "velocity"), ("ex3_8", 2, "velocity")])
def test_labels_keep_their_place_and_size(case, first, name):
    sol = (velpoly.solve(velpoly.load(EXAMPLES / "problem_1_4_4_sixbar.toml")) if case.startswith("problem") else
           velpoly.solve(velpoly.load(EXAMPLES / "ex3_8_instant_centres_cw.toml")) if case == "ex3_8"
           else _sixbars()[int(case[-1])].drawn)
    assert _moved(sol, first, name) == []
