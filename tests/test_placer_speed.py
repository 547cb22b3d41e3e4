"""The label placer's ring-at-a-time search gives the very placements of the box-at-a-time one (issue 20; render/labels.py).

:meth:`LabelPlacer._search` and ``_least_bad`` test a ring's candidate boxes together, one shapely call per test
(``_Scene``, ``_Ring``, ``_leaders``); before, each box was made and tested on its own. The reference below is that
old path, kept small: the candidates as ``_candidates`` made them (``half_extent``, ``_box``), the leader's end as
``_toward`` finds it, each predicate asked of shapely per box. Checked bit for bit: the candidates and leader ends
on random anchors, sizes, directions and boxes (touching, degenerate); the predicates on random boxes and lines
(shared edges, corners, zero-length lines); every search and last resort of generated drawings (a dense six-bar's
poles, a four-bar's displacement diagram) against the reference on the same placer state."""
from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
import shapely
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from shapely.geometry import LineString, Point

import zoo
from velpoly.render import labels as L
from velpoly.render.canvas import box, per_point, view_box
from velpoly.render.displacement import draw_mechanism
from velpoly.render.kennedy import draw_poles
from velpoly.render.style import get_style, rc_context


# -- the reference: the box-at-a-time path as it was -------------------------------------------------------
def ref_candidates(anchor, w, h, prefer, ring, k, within, pp):
    for ang in L._directions(prefer, k):
        if within is not None and abs((ang - (prefer or 45.0) + 180.0) % 360.0 - 180.0) > within + 1e-9:
            continue
        u = np.array([math.cos(math.radians(ang)), math.sin(math.radians(ang))])
        c = anchor + u * (ring * pp + L.half_extent(w, h, u))
        yield c, box(c[0] - w / 2, c[1] - h / 2, c[0] + w / 2, c[1] + h / 2)


def ref_toward(b, p):
    from shapely.ops import nearest_points
    q = nearest_points(b.exterior, Point(p))[0]
    return np.array([q.x, q.y])


def count(geoms, g) -> int:
    return int(np.count_nonzero(shapely.intersects(np.array(geoms, dtype=object), g))) if geoms else 0


def ref_search(pl, anchor, w, h, prefer, gap, leader, within, accept, clear=False, reach=False,
               crossing=L.LEADER_MOST):
    view, pp = view_box(pl.ax), per_point(pl.ax)
    taken, soft, crossed = pl.boxes + pl.hard, pl.soft, pl.boxes + pl.leaders
    near = np.array([g.intersects(Point(*anchor).buffer(2.0 * pp)) for g in soft], bool)
    rings = (gap,) + tuple(r for r in L.RINGS if r > gap)
    best = None
    for ring_i, ring in enumerate(rings + L.FAR_RINGS + (L.REACH_RINGS if reach and leader else ())):
        seeking = ring_i >= len(rings) and best is not None
        if seeking and not (clear and leader and best[0][0] > 0):
            break
        k = 48 if ring in L.REACH_RINGS else 24 if ring_i >= len(rings) else 16 if ring_i >= 2 else 8
        for c, b in ref_candidates(anchor, w, h, prefer, ring, k, within, pp):
            if not view.contains(b) or count(taken, b) or (accept is not None and not accept(b)):
                continue
            hits = (count(soft, b), 0)
            if seeking and hits[0]:
                continue
            if leader and ring >= 9.0:
                line = LineString([tuple(anchor), tuple(ref_toward(b, anchor))])
                if count(crossed, line):
                    continue
                on = shapely.intersects(np.array(soft, dtype=object), line) if soft else np.zeros(0, bool)
                hits = (hits[0], int(np.count_nonzero(on & ~near)))
                if seeking and hits[1] > crossing:
                    continue
            if best is None or hits < best[0]:
                best = (hits, c, b, ring)
            if hits == (0, 0):
                return best
    return best


def ref_least_bad(pl, anchor, w, h, prefer, gap, leader, reach=False):
    view, pp = view_box(pl.ax), per_point(pl.ax)
    best = None
    far = L.REACH_RINGS if reach and leader else ()
    for ring in sorted({gap, *(r for r in L.RINGS if r > gap), *L.FAR_RINGS, 135.0, *far}):
        if ring in far and best is not None and best[0][1:3] == (0, 0):
            break
        k = 48 if ring in far else 24 if ring in L.FAR_RINGS else 16
        for c, b in ref_candidates(anchor, w, h, prefer, ring, k, None, pp):
            if not view.contains(b) or count(pl.boxes + pl.leaders, b):
                continue
            line = LineString([tuple(anchor), tuple(ref_toward(b, anchor))])
            drawn = leader and ring >= 9.0
            score = (count(pl.boxes, line) if drawn else 0, count(pl.hard, b), count(pl.leaders, line) if drawn else 0,
                     count(pl.soft, b))
            if best is None or score < best[0]:
                best = (score, c, b, ring)
    if best is None:
        c, b = next(ref_candidates(anchor, w, h, prefer, gap, 1, None, pp))
        best = (math.inf, c, b, gap)
    return best


def same(new, old) -> bool:
    """Two search results alike bit for bit: score, centre, box, ring."""
    if new is None or old is None:
        return new is None and old is None
    return (new[0] == old[0] and np.array_equal(new[1], old[1]) and new[3] == old[3]
            and shapely.equals_exact(new[2], old[2], tolerance=0.0))


# -- the pieces, on random input -----------------------------------------------------------------------------
def test_candidates_and_leader_ends_are_the_old_ones_bit_for_bit():
    """``_Ring``'s centres and boxes are ``_candidates``'; ``_towards`` is ``_toward`` (anchors outside, on an
    edge, at a corner, inside; boxes of every shape), over random sizes, preferred directions and ``within``."""
    rng = np.random.default_rng(20)
    for _ in range(60):
        anchor = rng.normal(0, 50, 2)
        w, h = (float(x) for x in rng.choice([rng.uniform(0.01, 30), 0.5, 2.0], 2))
        prefer = rng.choice([None, 0.0, float(rng.uniform(-180, 180)), 90.0, -45.0])
        within = rng.choice([None, None, 30.0, 90.0])
        k, reach = int(rng.choice([1, 8, 16, 24, 48])), float(rng.uniform(0, 40))
        ring = L._Ring(anchor, w, h, prefer, reach * 0.35, k, within)
        old = list(ref_candidates(anchor, w, h, prefer, reach, k, within, 0.35))
        assert len(old) == len(ring)
        for i, (c, b) in enumerate(old):
            assert np.array_equal(c, ring.centres[i])
            assert shapely.equals_exact(b, ring.geom(i), tolerance=0.0)
        if not len(ring):
            continue   # (one direction, outside ``within``)
        # leader ends from points around and on the boxes: the anchor, a corner, an edge's midpoint, inside
        x0, y0, x1, y1 = ring.bounds[0]
        for p in (anchor, (x0, y0), ((x0 + x1) / 2, y1), ((x0 + x1) / 2, (y0 + y1) / 2), (x1, y0 - 1.0)):
            p = np.asarray(p, float)
            ends = L._towards(ring.geoms, p)
            assert all(np.array_equal(ends[i], ref_toward(ring.geom(i), p)) for i in range(len(ring)))


def test_view_containment_is_shapely_on_touching_degenerate_and_nan_boxes():
    """``_Scene.in_view`` (bounds compared, for boxes of some width and height) is ``view.contains(b)`` box for box:
    boxes on a grid inside, across and along the view's edges, boxes of no width or height, views with an axis
    inverted; a NaN corner answers (or fails) alike."""
    rng = np.random.default_rng(3)
    fig = Figure(figsize=(3, 3), dpi=72)
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0, 0, 1, 1))
    pl = L.LabelPlacer(ax)
    for lims in (((-4, 4), (-3, 3)), ((4, -4), (-3, 3)), ((-4, 4), (3, -3))):
        ax.set_xlim(*lims[0])
        ax.set_ylim(*lims[1])
        scene = L._Scene(pl, np.zeros(2), per_point(ax))
        cands = L._Ring(np.zeros(2), 1.0, 1.0, 0.0, 0.0, 8)
        x0, y0 = rng.integers(-6, 6, (2, 300)).astype(float)
        x1, y1 = x0 + rng.integers(0, 4, 300), y0 + rng.integers(0, 4, 300)
        cands.bounds, cands.centres = np.column_stack([x0, y0, x1, y1]), np.zeros((300, 2))
        cands._geoms = None
        inside = scene.in_view(cands)
        view = view_box(ax)
        assert [bool(x) for x in inside] == [view.contains(cands.geom(i)) for i in range(len(cands))]
        assert inside.any() and not inside.all()
        cands.bounds[0, 0], cands._geoms = np.nan, None   # a NaN corner: the same answer, or refused alike
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)   # (shapely's, on the NaN)
            assert outcome(lambda: view.contains(cands.geom(0))) == outcome(lambda: scene.in_view(cands)[0])


def outcome(f):
    """f()'s answer, or that shapely refused."""
    try:
        return bool(f())
    except shapely.errors.GEOSException:
        return "refused"


def _grid_scene(rng):
    """Obstacles on a coarse grid, so that boxes share edges and corners with them: boxes, circles, segments
    (some of zero length), a polyline."""
    def pt():
        return rng.integers(-6, 7, 2).astype(float)
    boxes = [box(*pt(), *(pt() + rng.integers(1, 4, 2))) for _ in range(6)]
    hard = [Point(*pt()).buffer(float(rng.choice([0.5, 1.0]))) for _ in range(3)]
    segs = [LineString([tuple(pt()), tuple(pt())]) for _ in range(5)]
    segs += [LineString([(1.0, 1.0), (1.0, 1.0)]), LineString([tuple(pt()), tuple(pt()), tuple(pt())])]
    return boxes, hard, segs


def test_ring_predicates_are_shapely_per_box_on_touching_and_degenerate_geometry():
    """``_Scene.free``, ``soft_hits`` and ``leader_tests`` give, candidate for candidate, what shapely gives box by
    box (touching counts as meeting; zero-length lines; a view the boxes touch)."""
    rng = np.random.default_rng(7)
    fig = Figure(figsize=(4, 4), dpi=72)
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0, 0, 1, 1))
    checked = 0
    for _ in range(20):
        ax.set_xlim(-8, 8)
        ax.set_ylim(-8, 8)
        pl = L.LabelPlacer(ax)
        boxes, hard, segs = _grid_scene(rng)
        pl.labels = [L.Placed(None, b) for b in boxes]
        for g in hard:
            pl.add_obstacle(g)
        for g in segs:
            pl.add_obstacle(g, hard=False)
        anchor = rng.integers(-5, 6, 2).astype(float)
        pp = per_point(ax)
        scene = L._Scene(pl, anchor, pp)
        # sizes and reaches in whole grid steps: candidates that land on the grid, edge to edge with obstacles
        w, h = (float(x) for x in rng.integers(1, 4, 2))
        for ring_units in (0.0, 1.0, 2.0, 3.5):
            cands = L._Ring(anchor, w, h, float(rng.choice([0.0, 90.0, 45.0])), ring_units, 8)
            free = scene.free(cands, np.arange(len(cands)))
            view = view_box(ax)
            want = [i for i in range(len(cands)) if view.contains(cands.geom(i)) and not count(pl.boxes + pl.hard,
                                                                                               cands.geom(i))]
            assert list(free) == want
            soft = scene.soft_hits(cands, free)
            assert [int(x) for x in soft] == [count(pl.soft, cands.geom(i)) for i in free]
            crosses, on = scene.leader_tests(cands, free)
            near = np.array([g.intersects(Point(*anchor).buffer(2.0 * pp)) for g in pl.soft], bool)
            for n, i in enumerate(free):
                line = LineString([tuple(anchor), tuple(ref_toward(cands.geom(i), anchor))])
                assert bool(crosses[n]) == bool(count(pl.boxes + pl.leaders, line))
                assert int(on[n]) == int(np.count_nonzero(shapely.intersects(np.array(pl.soft, dtype=object), line)
                                                          & ~near))
                checked += 1
    assert checked > 50, checked


# -- whole drawings ------------------------------------------------------------------------------------------
@pytest.fixture
def compared(monkeypatch):
    """Every search and last resort of the drawings made inside checked against the reference, on the placer's
    state at that moment (the reference runs first: it changes nothing); returns the counts."""
    seen = {"search": 0, "least_bad": 0, "kept": 0}
    search, least_bad = L.LabelPlacer._search, L.LabelPlacer._least_bad

    def checked_search(self, anchor, w, h, prefer, gap, leader, within, accept, clear=False, reach=False, scene=None,
                       crossing=L.LEADER_MOST):
        old = ref_search(self, anchor, w, h, prefer, gap, leader, within, accept, clear, reach, crossing)
        new = search(self, anchor, w, h, prefer, gap, leader, within, accept, clear, reach, scene, crossing)
        assert same(new, old), (anchor, prefer, new, old)
        seen["search"] += 1
        seen["kept"] += new is not None and new[3] >= 9.0
        return new

    def checked_least_bad(self, anchor, w, h, prefer, gap, leader, reach=False):
        old = ref_least_bad(self, anchor, w, h, prefer, gap, leader, reach)
        new = least_bad(self, anchor, w, h, prefer, gap, leader, reach)
        assert same(new, old), (anchor, prefer, new, old)
        seen["least_bad"] += 1
        return new
    monkeypatch.setattr(L.LabelPlacer, "_search", checked_search)
    monkeypatch.setattr(L.LabelPlacer, "_least_bad", checked_least_bad)
    return seen


def _axes(size):
    fig = Figure(figsize=size, dpi=72)
    FigureCanvasAgg(fig)
    return fig.add_axes((0.02, 0.02, 0.96, 0.96))


def test_placements_of_generated_drawings_are_the_reference_ones(compared):
    """A dense generated six-bar's poles drawing (fifteen poles, Kennedy lines, leaders, labels pushed to last
    resorts on a small page) and a generated four-bar's displacement diagram: each search and last resort the
    drawings made equals the reference's, bit for bit."""
    rng = np.random.default_rng(29)
    variants = [v for k, v in zoo.variants() if k == "six-bar"]
    six = zoo.specimen(rng, "six-bar", variants[int(rng.integers(len(variants)))]).drawn
    four = zoo.specimen(rng, "four-bar").drawn
    st = get_style("textbook")
    with rc_context(st):
        draw_poles(six, _axes((4.5, 4.2)), style=st)
        draw_mechanism(four, _axes((5.0, 4.0)), style=st)
    assert compared["search"] > 40 and compared["kept"] > 5, compared
