"""The interactive page draws a polygon's vectors on one line apart, as the sheets do (issue 17, item 4).

``velpoly html`` draws its polygons in the browser (velpoly/html_assets/sheet.js), not through matplotlib: before
this, a swinging block's slip V_O4₃/O4₄ lay exactly over its absolute V_O4₄ there, one segment with an arrowhead at
each end, while the sheet (velpoly/render/polygon.py, ``Beside``) drew it beside. The page now plans the same rule
(``besideAll``): the later of two vectors on one line is drawn at right angles to it, 0.7 of the page's 13-px
arrowhead to one side (or twice that, ...), in its own style and sense, its true length; two of one kind from one
tail in one sense whose heads are two arrowheads apart stay on their ray. Planned over the whole construction: a
step draws each vector where the last step has it.

Checked in headless Chromium on generated mechanisms of the classes that always put two vectors on one line (a block
on a frame pivot, a guide through its pivot, a slotted lever), at the data level: the DOM's arrows against the
solution's vectors mapped by the panel's own scale. Fails on the page before the change (the slip along its
absolute over its whole length).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import velpoly
from velpoly.html import page
from velpoly.polygons import acceleration_polygon, velocity_polygon
from zoo import specimen

# generated classes that put two vectors on one line, crank-driven (a slider driver's stroke search costs seconds a
# page): a block on a frame pivot, a guide through both its pivots, a quick-return's slotted lever
CASES = (("inverted slider-crank", "swinging-block crank"), ("inverted slider-crank", "through both crank"),
         ("six-bar", "quick-return crank"))
HEAD = 13.0             # px: the page's arrowhead (sheet.js HEAD)
APART = 0.7 * HEAD      # px: the offset of a vector beside another
ROUND = 0.03            # px: the page writes coordinates to 0.01 px

# every drawn arrow of a panel: [tail x, tail y, tip x, tip y, class] (the shaft's start, the head's tip)
ARROWS = """Array.from(document.querySelectorAll('#%s line.vec')).map(function (l) {
  var h = l.parentNode.querySelector('path.head'), m = /^M([-0-9.e]+),([-0-9.e]+)/.exec(h.getAttribute('d'));
  return [+l.getAttribute('x1'), +l.getAttribute('y1'), +m[1], +m[2], l.getAttribute('class')]; })"""
# the panel's images: [x, y, sx, sy] (data and page coordinates)
IMAGES = """Array.from(document.querySelectorAll('#%s .hit.img')).map(function (c) {
  return [+c.dataset.x, +c.dataset.y, +c.dataset.sx, +c.dataset.sy]; })"""


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    """(mechanism, its page's path) for each case: a page every 30 degrees (or its stroke in steps of 30 units: a
    slider driver)."""
    rng = np.random.default_rng(1127)
    tmp = tmp_path_factory.mktemp("apart")
    out = []
    for i, (kind, variant) in enumerate(CASES):
        m = velpoly.load(specimen(rng, kind, variant).mech)
        path = tmp / f"case{i}.html"
        path.write_text(page(m, step=30.0), encoding="utf-8")
        out.append((m, path))
    return out


def _scale(images):
    """The panel's map: (k, offset) with page = k * (x, -y) + offset, fitted on its images."""
    pts = np.array(images, float)
    far = max(range(len(pts)), key=lambda i: math.hypot(*(pts[i, :2] - pts[0, :2])))
    k = math.hypot(*(pts[far, 2:] - pts[0, 2:])) / math.hypot(*(pts[far, :2] - pts[0, :2]))
    off = pts[0, 2:] - k * np.array([pts[0, 0], -pts[0, 1]])
    return k, off


def _along(a, b, near: float) -> float:
    """How far (px) segment b runs within ``near`` of segment a's line and over a, where the two are parallel
    within 1 degree (0 otherwise)."""
    u, v = a[1] - a[0], b[1] - b[0]
    if abs(u[0] * v[1] - u[1] * v[0]) > math.sin(math.radians(1.0)) * np.hypot(*u) * np.hypot(*v):
        return 0.0
    n = np.array([-u[1], u[0]]) / np.hypot(*u)
    if max(abs(np.dot(b[0] - a[0], n)), abs(np.dot(b[1] - a[0], n))) > near:
        return 0.0
    t = sorted(np.dot(p - a[0], u) / np.hypot(*u) for p in b)
    return max(0.0, min(t[1], np.hypot(*u)) - max(t[0], 0.0))


def _check_panel(arrows, vectors, k, off):
    """Every drawn arrow is one of ``vectors`` (data tail, head, kind), moved at right angles by a whole number of
    APART; no two drawn arrows on one line unless both of one kind from one tail in one sense, heads two arrowheads
    apart. Returns {vector index: shift} and how many were moved."""
    def px(p):
        return k * np.array([p[0], -p[1]]) + off
    want = [(px(t), px(h), kind) for t, h, kind in vectors]
    drawn, shifts, moved = [], {}, 0
    for x1, y1, x2, y2, cls in arrows:
        tail, tip = np.array([x1, y1]), np.array([x2, y2])
        kind = cls.split()[1]
        match = None      # the vector of its kind, length and direction it is nearest (parallel ones: the nearest)
        for i, (t, h, kd) in enumerate(want):
            s = tail - t
            if kd == kind and np.allclose(tip - s, h, atol=2 * ROUND) and \
                    (match is None or np.hypot(*s) < np.hypot(*(tail - want[match][0]))):
                match = i
        assert match is not None, f"an arrow {kind} {tail} -> {tip} that is no vector of the construction"
        t, h, _ = want[match]
        d = (h - t) / np.hypot(*(h - t))
        s = tail - t
        assert abs(np.dot(s, d)) <= 2 * ROUND                     # at right angles to itself
        steps = np.hypot(*s) / APART
        assert abs(steps - round(steps)) * APART <= 2 * ROUND     # a whole number of offsets
        moved += round(steps) > 0
        if match in shifts:
            assert np.allclose(shifts[match], s, atol=2 * ROUND)  # a vector drawn twice is drawn in one place
            continue
        shifts[match] = s
        drawn.append((np.array([tail, tip]), kind))
    for i, (a, ka) in enumerate(drawn):
        for b, kb in drawn[:i]:
            if _along(a, b, 0.5 * APART - 3 * ROUND) > 3.0 or _along(b, a, 0.5 * APART - 3 * ROUND) > 3.0:
                same_ray = ka == kb and np.hypot(*(a[0] - b[0])) <= 0.5 * APART and \
                    np.dot(a[1] - a[0], b[1] - b[0]) > 0 and np.hypot(*(a[1] - b[1])) >= 2 * HEAD - 4 * ROUND
                assert same_ray, f"{ka} {a.tolist()} drawn along {kb} {b.tolist()}"
    return shifts, moved


@pytest.mark.xdist_group("html-page")     # with test_html's browser tests: one Chromium (conftest's browser)
def test_the_page_draws_vectors_on_one_line_apart(browser, pages):
    moved_in_all = []
    for m, path in pages:
        moved_in_all.append(0)
        browser.open(path.resolve().as_uri() + "#step=999")     # the page opens at the drawn pose (a crank's nearest)
        shown = float(browser.js("document.body.dataset.rendered"))
        sol = velpoly.solve(m) if m.driver.is_slider else velpoly.solve(m, angle=shown)
        last_shifts = {}
        for level, make in (("velocity", velocity_polygon), ("acceleration", acceleration_polygon)):
            poly = make(sol)
            vectors = [(np.asarray(v.tail, float), np.asarray(v.head, float), v.kind)
                       for s in poly.steps for v in s.vectors]
            k, off = _scale(browser.js(IMAGES % level))
            shifts, moved = _check_panel(browser.js(ARROWS % level), vectors, k, off)
            # every vector drawn, once (one that is both absolute and relative: as absolute)
            assert len(shifts) == len({(tuple(np.round(t, 9)), tuple(np.round(h, 9))) for t, h, _ in vectors
                                       if np.hypot(*(h - t)) * k >= 0.5})
            last_shifts[level] = (shifts, vectors, k, off)
            moved_in_all[-1] += moved
        # an earlier step draws each of its vectors where the last step has it
        browser.open(path.resolve().as_uri() + "#step=3")
        for level in ("velocity", "acceleration"):
            shifts, vectors, k, off = last_shifts[level]
            early, _ = _check_panel(browser.js(ARROWS % level), vectors, k, off)
            for i, s in early.items():
                assert np.allclose(s, shifts[i], atol=2 * ROUND)
    assert not browser.errors(), browser.errors()
    # not vacuous: the swinging block's slip lies on its absolute's line, the quick-return's block too (measured: one
    # vector moved in each; none in the guide through both pivots at its drawn pose)
    assert moved_in_all[0] >= 1 and moved_in_all[2] >= 1, moved_in_all
