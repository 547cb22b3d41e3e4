"""Construction lines' reasons keep apart (issue 17 item 4: "parallel to the path of E on 1" and "... of F on 1"
were written one each side of one line, and read as one text of two lines).

At the data level, on the velocity and acceleration polygons of generated mechanisms (tests/zoo.py) in both
styles and on Example 3.4's sheet: every two reasons' text rectangles (as drawn, rotated along their lines) are
at least an em (``ALONG_APART`` of the type size) apart, and lines drawn along one line carry one reason between
them, that names them all ("parallel to the path of E and F on 1").
"""
from __future__ import annotations

import itertools

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from shapely import affinity
from shapely.geometry import box

import sheets
import zoo
from velpoly.render import sheet
from velpoly.render.labels import ALONG_APART
from velpoly.render.polygon import _collinear, draw_polygon, joined_reasons
from velpoly.render.style import get_style, rc_context


def _rect(ax, t):
    """The text's rectangle on the canvas (pixels; 72 dpi: points), rotated along its line."""
    r = ax.figure.canvas.get_renderer()
    rot = t.get_rotation()
    t.set_rotation(0)
    bb = t.get_window_extent(r)
    t.set_rotation(rot)
    cx, cy = ax.transData.transform(t.get_position())
    return affinity.rotate(box(cx - bb.width / 2, cy - bb.height / 2, cx + bb.width / 2, cy + bb.height / 2), rot,
                           origin=(cx, cy))


def reasons_too_close(ax) -> list:
    """(reason, reason, gap in ems) of every two reasons nearer than ALONG_APART ems, and (reason, reason,
    'collinear') of two on lines along one line."""
    texts = [t for t in ax.texts if (t.get_gid() or "").endswith("-reason") and t.get_text()]
    out = []
    for a, b in itertools.combinations(texts, 2):
        em = min(a.get_fontsize(), b.get_fontsize()) * ax.figure.dpi / 72
        gap = _rect(ax, a).distance(_rect(ax, b))
        if gap < ALONG_APART * em * (1 - 1e-6):
            out.append((a.get_text(), b.get_text(), round(gap / em, 2)))
    lines = {ln.get_gid(): ln for ln in ax.lines if (ln.get_gid() or "").startswith("construction-")}
    for group in _collinear(list(lines.values())):
        named = [t for t in texts if t.get_gid()[:-len("-reason")] in {g.get_gid() for g in group}]
        if len(named) > 1:
            out.append((named[0].get_text(), named[1].get_text(), "collinear"))
    return out


def test_joined_reasons():
    assert joined_reasons(["parallel to the path of E on 1", "parallel to the path of F on 1"]) == \
        "parallel to the path of E and F on 1"
    assert joined_reasons(["perpendicular to DE", "perpendicular to GF", "perpendicular to HK"]) == \
        "perpendicular to DE, GF and HK"
    assert joined_reasons(["perpendicular to AB", "perpendicular to AB"]) == "perpendicular to AB"
    assert joined_reasons(["perpendicular to AB", "along the slot of 3 at A"]) == \
        "perpendicular to AB; along the slot of 3 at A"


@pytest.mark.parametrize("style", ["textbook", "slides"])
def test_reasons_keep_an_em_apart_on_generated_polygons(style):
    """Generated mechanisms, both polygons each: every tenth variant of the zoo (from the first in textbook, the
    sixth in slides: every kind over the two styles, six in textbook), six drawn in textbook, two in slides (the
    eight-bar, the one kind textbook has not, and the Watt I six-bar; the reasons' spacing is measured in the
    style's own em: the other four slides were cut by issue 19 item 7). Until the suite had to fit 2 minutes,
    the zoo's first twelve variants a style (four-bars and slider-cranks, one inverted slider-crank)."""
    st = get_style(style)
    rng = np.random.default_rng(1917 if style == "textbook" else 1918)
    specs = [zoo.specimen(rng, *pair) for pair in zoo.variants()[(0 if style == "textbook" else 5)::10]]
    assert len({sp.kind.split()[0] for sp in specs}) >= 5
    if style == "slides":
        specs = [sp for sp in specs if sp.kind.startswith(("eight-bar", "six-bar watt I"))]
        assert len(specs) == 2, [sp.kind for sp in specs]
    written = 0
    for sp in specs:
        sol = sp.drawn
        cons = sheet.constructions(sol, "full")
        for poly in (cons.velocity, cons.acceleration):
            if poly is None:
                continue
            with rc_context(st):
                fig = Figure(figsize=(6.0, 5.0), dpi=72)
                FigureCanvasAgg(fig)
                ax = fig.add_axes((0.02, 0.02, 0.96, 0.96))
                draw_polygon(poly, ax, mechanism=sol.mechanism, style=st)
            bad = reasons_too_close(ax)
            assert not bad, (sp.kind, bad)
            written += sum(1 for t in ax.texts if (t.get_gid() or "").endswith("-reason"))
    assert written >= 2 * len(specs), written   # (15 and 17 when measured)


@sheets.on("textbook")
def test_example_3_4_paths_of_e_and_f_share_one_reason():
    """Example 3.4's acceleration polygon: the paths of E and F lie along one line through O_a; one reason names
    both, and no two reasons of the sheet come within an em. The sheet is the gallery's page (tests/sheets.py,
    drawn once a worker for test_render_gallery too): read only."""
    fig = sheets.page("ex3_4_slotted_lever", "full", "textbook")
    with sheets.styled("textbook"):     # measured as it was drawn
        for ax in fig.axes:
            if ax.get_label() in ("velocity", "acceleration"):
                assert not reasons_too_close(ax), (ax.get_label(), reasons_too_close(ax))
        acc = next(ax for ax in fig.axes if ax.get_label() == "acceleration")
        texts = [t.get_text() for t in acc.texts if (t.get_gid() or "").endswith("-reason")]
        assert any("path of" in t and "E and F" in t for t in texts), texts
