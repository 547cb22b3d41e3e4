"""Two vectors of a polygon on one line are drawn apart (issue 17, item 4: every drawn thing is what its label says).

Where two vectors of a velocity or acceleration polygon lie along one line and overlap (a block's slip V_O4₃/O4₄ from
o₄,₄ back to O_v over the absolute V_O4₄ when the block pivots on the frame; a normal component nearly the whole
acceleration; a Coriolis component collinear with a tangential one on a guide through its pivot; the images of two
points of a slotted lever on one line from the origin), one was drawn over the other: one segment with an arrowhead
at each end, a dashed component hidden under a solid line that the legend lists. Now the later of the two is drawn
beside the other, offset at right angles by a small paper distance (0.7 of the style's arrowhead length: 1.5 mm on a
textbook page), in its own line style, with its own arrowhead at its own (offset) head, its true length and
direction. Checked at the data level on generated mechanisms of the classes that always produce such overlaps (both
polygons, textbook; one of them in the slides style), and the placing rule itself on random segments (hypothesis).
On the code before the change the drawn checks fail: the slip of the swinging block lies 100 mm along its absolute.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from shapely.geometry import LineString

from velpoly.polygons import acceleration_polygon, velocity_polygon
from velpoly.render import polygon as P
from velpoly.render.canvas import per_point
from velpoly.render.style import get_style, rc_context
from zoo import specimen

MM = 25.4 / 72          # mm per point
LONG = 1.5              # mm: two strokes on one line over more than this read as one line
PARALLEL = 1.0          # degrees
# (kind, variant): blocks on a frame pivot (the slip equal to an absolute), guides through their pivot (Coriolis along
# the tangential component), a slotted lever (two points' images on one line from the origin)
CASES = (("inverted slider-crank", "swinging-block slider"), ("inverted slider-crank", "through block slider"),
         ("six-bar", "quick-return slider"))


@pytest.fixture(scope="module")
def specimens():
    rng = np.random.default_rng(1127)
    return [specimen(rng, kind, variant) for kind, variant in CASES]


def _drawn(poly, sol, style):
    """The polygon drawn into a bare axes: (axes, its Artists)."""
    with rc_context(get_style(style)):
        fig = Figure(figsize=(5, 4), dpi=72)
        FigureCanvasAgg(fig)
        ax = fig.add_axes((0.02, 0.02, 0.96, 0.96))
        return ax, P.draw_polygon(poly, ax, mechanism=sol.mechanism, style=style)


def _paper(ax, sh, patch) -> np.ndarray:
    """The drawn vector's tail (its shaft's start) and head (its arrowhead's tip) in mm of paper."""
    x, y = sh.get_data()
    return ax.transData.transform([[x[0], y[0]], patch.get_xy()[0]]) * MM


def _one_line(a, b, width: float) -> float:
    """How far (mm) the paper segment ``b`` runs within ``width`` of ``a``, where the two are parallel within
    PARALLEL degrees (0 otherwise)."""
    u, v = a[1] - a[0], b[1] - b[0]
    if abs(u[0] * v[1] - u[1] * v[0]) > math.sin(math.radians(PARALLEL)) * np.hypot(*u) * np.hypot(*v):
        return 0.0
    return LineString(a).buffer(width, cap_style="flat").intersection(LineString(b)).length


def _check(ax, art, style):
    """Every pair of drawn vectors apart on paper, or two images on one ray from one tail; every vector drawn where
    it is, or as its offset copy. Returns how many are offset and how many pairs stay on one ray."""
    s = get_style(style)
    width = s.arrow_lw * s.kind_styles["absolute"][2] * MM       # an absolute vector's stroke
    pp = per_point(ax)
    assert len(art["shafts"]) == len(art.arrows)
    drawn, moved, on_ray = [], 0, 0
    for (kind, tail, head, patch), sh in zip(art.arrows, art["shafts"]):
        shift = np.asarray(getattr(patch, "_velpoly_shift", np.zeros(2)), float)
        x, y = sh.get_data()
        d, size = head - tail, float(np.hypot(*(head - tail)))
        # the head's tip at the head (moved by the shift), the shaft from the tail (moved by it): the copy is
        # exactly parallel to the vector and as long
        assert np.hypot(*(patch.get_xy()[0] - shift - head)) <= 1e-9 * size, (kind, patch.get_gid())
        assert np.hypot(*(np.array([x[0], y[0]]) - shift - tail)) <= 1e-9 * size, (kind, patch.get_gid())
        tip, start = patch.get_xy()[0], np.array([x[0], y[0]])
        assert abs((tip - start)[0] * d[1] - (tip - start)[1] * d[0]) <= 1e-9 * size ** 2
        assert abs(float(np.hypot(*(tip - start))) - size) <= 1e-9 * size
        if np.hypot(*shift) > 0:
            moved += 1
            assert abs(float(np.dot(shift, d))) <= 1e-9 * size * float(np.hypot(*shift))    # at right angles
            apart = P.APART * s.head_length                                               # pt
            k = float(np.hypot(*shift)) / pp / apart                                      # whole offsets, on paper
            assert k >= 1 - 1e-9 and abs(k - round(k)) <= 1e-9, k
            if style == "textbook" and round(k) == 1:
                assert 1.0 <= apart * MM <= 1.6
        drawn.append((kind, patch.get_gid(), _paper(ax, sh, patch)))
    head_mm = s.head_length * MM
    for i, (ki, gi, a) in enumerate(drawn):
        for kj, gj, b in drawn[i + 1:]:
            if _one_line(a, b, width) <= LONG and _one_line(b, a, width) <= LONG:
                continue
            # on one line only as books draw two images on one ray: one kind, one tail, one sense, both arrowheads
            # seen (the heads P.HEADS_APART arrowheads apart)
            assert ki == kj and np.hypot(*(a[0] - b[0])) <= 0.1 and np.dot(a[1] - a[0], b[1] - b[0]) > 0, (gi, gj)
            assert np.hypot(*(a[1] - b[1])) >= P.HEADS_APART * head_mm - 1e-6, (gi, gj)
            on_ray += 1
    return moved, on_ray


@pytest.mark.parametrize("build", [velocity_polygon, acceleration_polygon], ids=["velocity", "acceleration"])
def test_vectors_on_one_line_are_drawn_apart(specimens, build):
    moved = np.zeros(2, int)
    for sp in specimens:
        ax, art = _drawn(build(sp.drawn), sp.drawn, "textbook")
        moved += _check(ax, art, "textbook")
        if art.detail is not None:
            moved += _check(art.detail.ax, art.detail.art, "textbook")
    assert moved[0] >= 1 and moved.sum() >= 2     # each polygon of these classes had vectors on one line


def test_slides_draw_the_swinging_blocks_slip_apart(specimens):
    """The slip of a block pivoted on the frame, beside its absolute velocity in the slides style (thicker lines,
    a larger offset), and listed in the legend, whose long dashes now show."""
    sp = specimens[0]
    ax, art = _drawn(velocity_polygon(sp.drawn), sp.drawn, "slides")
    assert _check(ax, art, "slides")[0] >= 1
    assert "slip" in {kind for kind, *_ in art.arrows}
    assert "slip along the path" in [t.get_text() for t in ax.get_legend().get_texts()]


@settings(max_examples=25, deadline=None)
@given(st.lists(st.tuples(st.floats(-5, 5), st.floats(-5, 5), st.sampled_from([0.0, 0.3, 1.0]),
                          st.booleans()), min_size=2, max_size=6),
       st.floats(0, 180))
def test_beside_puts_no_vector_along_another(segments, angle):
    """Random vectors, most of them on one line (the same direction or reversed, overlapping), placed one after the
    other: none lies along another as placed, each moved at right angles by a whole number of offsets."""
    u = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
    n = np.array([-u[1], u[0]])
    b = P.Beside(apart=1.0, along=0.4)
    placed = []
    for a0, a1, off, back in segments:
        if abs(a1 - a0) < 0.5:
            continue
        tail, head = a0 * u + off * n, a1 * u + off * n
        if back:
            tail, head = head, tail
        s = b.add(tail, head, np.zeros(2))
        assert abs(float(np.dot(s, head - tail))) <= 1e-9 * float(np.hypot(*(head - tail)))
        k = float(np.hypot(*s))
        assert abs(k - round(k)) <= 1e-9 and round(k) <= 4
        placed.append((tail + s, head + s))
    for i, a in enumerate(placed):
        for c in placed[i + 1:]:
            assert _one_line(np.array(a), np.array(c), 0.2) <= 0.4 + 1e-9


def test_step_frames_draw_each_vector_where_the_last_frame_does(specimens):
    """The offsets are planned on the finished construction: a ``--steps`` frame draws each of its vectors where the
    finished polygon has it (nothing jumps from frame to frame), moved ones included."""
    sp = specimens[2]
    poly = acceleration_polygon(sp.drawn)

    def shifts(upto):
        with rc_context(get_style("textbook")):
            fig = Figure(figsize=(5, 4), dpi=72)
            FigureCanvasAgg(fig)
            ax = fig.add_axes((0.02, 0.02, 0.96, 0.96))
            art = P.draw_polygon(poly, ax, mechanism=sp.drawn.mechanism, style="textbook", upto=upto)
        return {(tuple(np.round(t, 9)), tuple(np.round(h, 9))): np.asarray(hd._velpoly_shift) / per_point(ax)
                for _, t, h, hd in art.arrows}

    final = shifts(None)
    assert any(np.any(s) for s in final.values())
    for upto in (len(poly.steps) - 1,):
        frame = shifts(upto)
        assert frame
        for key, s in frame.items():
            assert np.allclose(s, final[key], rtol=0, atol=1e-9), key


def test_two_images_on_one_ray_from_the_origin_stay_on_it():
    """Two absolute vectors from the origin along one ray (O-a' and O-b', as books draw them) stay on their line
    where both arrowheads are seen; the same vector drawn back, another kind along it, or a head within
    HEADS_APART arrowheads of the other's is moved beside it."""
    apart = 1.0
    head = apart / P.APART                                   # an arrowhead's length, in the same units
    u = np.array([0.6, 0.8])
    o = np.zeros(2)

    def shifts(*vectors):
        b = P.Beside(apart=apart, along=0.4)
        return [float(np.hypot(*b.add(t, h, np.array([5.0, -5.0]), kind))) for kind, t, h in vectors]

    far, short = 10 * u, 10 * u - (P.HEADS_APART + 0.5) * head * u
    assert shifts(("absolute", o, far), ("absolute", o, short)) == [0.0, 0.0]
    assert shifts(("absolute", o, far), ("absolute", o, 10 * u - 0.5 * head * u))[1] > 0     # heads too near
    assert shifts(("absolute", o, far), ("slip", o, short))[1] > 0                            # another kind
    assert shifts(("absolute", o, far), ("absolute", far, o))[1] > 0                          # drawn back
    assert shifts(("absolute", o, far), ("relative", 2 * u, short))[1] > 0                    # another tail


def test_animation_frames_draw_vectors_on_one_line_apart(specimens):
    """An animation's polygon panels (velpoly animate) draw vectors on one line apart as a sheet does: in every frame
    drawn, no two visible arrows lie along each other (but two images on one ray from one tail), and each arrow is
    one of the frame's vectors moved at right angles (its true length and direction)."""
    from velpoly.render.animate import Animator, plan_frames
    anim = Animator(plan_frames(specimens[0].drawn.mechanism, 60.0), "full", "textbook", (480, 270))
    moved = 0
    for k in range(0, len(anim.plan), max(1, len(anim.plan) // 3)):
        anim.update(k)
        for kind in anim.polys:
            art, poly = anim._poly_art[kind], anim.polys[kind][k]
            truth = [(np.zeros(2), np.asarray(p, float)) for p in poly.images.values()]
            truth += [(np.asarray(v.tail, float), np.asarray(v.head, float)) for s in poly.steps for v in s.vectors]
            ax, drawn = art["ax"], []
            for key, (shaft, tip) in art["arrows"].items():
                if not shaft.get_visible():
                    continue
                x, y = shaft.get_data()
                start, end = np.array([x[0], y[0]]), tip.get_xy()[0]
                fits = [float(np.hypot(*((end - start) - (h - t)))) for t, h in truth]
                i = int(np.argmin(fits))
                t, h = truth[i]
                size = float(np.hypot(*(h - t)))
                assert fits[i] <= 1e-9 * size, key                     # its true length and direction
                shift = start - t
                assert abs(float(np.dot(shift, h - t))) <= 1e-9 * size * max(float(np.hypot(*shift)), 1e-300)
                moved += bool(np.hypot(*shift) > 1e-9 * size)
                kind_of = "absolute" if key.startswith("abs-") else key.split("-")[0]
                drawn.append((kind_of, key, ax.transData.transform([start, end]) * 25.4 / anim.dpi))
            for i, (ki, gi, a) in enumerate(drawn):
                for kj, gj, b in drawn[i + 1:]:
                    if _one_line(a, b, 0.3) <= LONG and _one_line(b, a, 0.3) <= LONG:
                        continue
                    assert ki == kj and np.hypot(*(a[0] - b[0])) <= 0.1 and np.dot(a[1] - a[0], b[1] - b[0]) > 0, \
                        (k, gi, gj)
    assert moved >= 1      # the swinging block's slip beside its absolute velocity
