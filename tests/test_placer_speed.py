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


def test_placements_of_generated_drawings_are_the_reference_ones(compared, monkeypatch):
    """A dense generated six-bar's poles drawing (fifteen poles, Kennedy lines, leaders, labels pushed to last
    resorts on a small page) and a generated four-bar's displacement diagram: each search and last resort the
    drawings made equals the reference's, bit for bit. The six-bar drawn again with every slow path of the
    fourteenth session (:func:`_slow_paths`) places the same texts, sizes, leaders and boxes, bit for bit; and
    ``clear_places`` of four of its pole labels (its own box lifted, at its size and smaller, as the Kennedy passes
    ask) answers as the old one."""
    rng = np.random.default_rng(29)
    variants = [v for k, v in zoo.variants() if k == "six-bar"]
    six = zoo.specimen(rng, "six-bar", variants[int(rng.integers(len(variants)))]).drawn
    four = zoo.specimen(rng, "four-bar").drawn
    st = get_style("textbook")
    with rc_context(st):
        art = draw_poles(six, fast := _axes((4.5, 4.2)), style=st)
        draw_mechanism(four, _axes((5.0, 4.0)), style=st)
    assert compared["search"] > 40 and compared["kept"] > 5, compared
    monkeypatch.undo()
    with rc_context(st), monkeypatch.context() as m:
        _slow_paths(m)
        draw_poles(six, slow := _axes((4.5, 4.2)), style=st)
    assert _placements(fast) == _placements(slow)
    pl, found = L.placer(fast), 0
    for t, f in zip(list(art.labels.values())[:4], (1.0, 0.8, 1.0, 0.8)):   # (30 ms a search)
        own = pl.of(t)
        k = pl.labels.index(own)
        del pl.labels[k]
        w, h = pl.text_size(t)
        new = pl.clear_places(own.anchor, w * f, h * f, -45.0)
        assert _same_places(new, _old_clear_places(pl, own.anchor, w * f, h * f, -45.0))
        found += len(new["boxes"])
        pl.labels.insert(k, own)
    assert found > 100, found


# -- the fourteenth session's shortcuts against their slow paths (issue 19 item 7) ----------------------------------
# The envelope prefilter (_Row.meets: GEOS asked only where the envelopes meet; prepared copies for leaders), the
# scenes a placer keeps while nothing changed (_scene, and the last resort's answers in it), the leaders of a
# ring in one shapely call (_leader_segments, clear_places), a pole label's ring test asking GEOS only of the rings
# near enough (kennedy._nearer_own) and the tries that keep only a free place (place's last_resort=False).
from hypothesis import HealthCheck, given, settings, strategies as st   # noqa: E402

from velpoly.render import kennedy as K   # noqa: E402


def _grid_geoms(draw, n):
    """``n`` geometries on a coarse grid (shared edges, corners, collinear runs): boxes, segments (some of zero
    length), two-segment polylines, circles and buffered segments (a leader's obstacle), an empty one."""
    pt = st.tuples(st.integers(-4, 4), st.integers(-4, 4)).map(lambda p: (float(p[0]), float(p[1])))
    out = []
    for _ in range(n):
        kind = draw(st.sampled_from(["box", "seg", "seg", "poly", "circle", "leader", "empty"]))
        a, b = draw(pt), draw(pt)
        if kind == "box":
            out.append(box(min(a[0], b[0]), min(a[1], b[1]), max(a[0], b[0]) + 1, max(a[1], b[1]) + 0.5))
        elif kind == "seg":
            out.append(LineString([a, b]))
        elif kind == "poly":
            out.append(LineString([a, b, draw(pt)]))
        elif kind == "circle":
            out.append(Point(a).buffer(draw(st.sampled_from([0.5, 1.0, 1.5]))))
        elif kind == "leader":
            out.append(LineString([a, b]).buffer(0.25))
        else:
            out.append(LineString())
    return out


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.data())
def test_rows_meet_as_shapely_pair_for_pair(data):
    """``_Row.meets`` (envelopes first; leaders against prepared copies) is ``shapely.intersects(row, column)`` of the
    plain geometries, pair for pair, on grid geometry that touches at edges and corners: boxes given with their
    bounds (a ring's), leaders without; ``count`` and ``any`` its sums."""
    obstacles = _grid_geoms(data.draw, data.draw(st.integers(0, 9)))
    cands = _grid_geoms(data.draw, data.draw(st.integers(1, 6)))
    row = L._Row(obstacles, lambda gs: [shapely.from_wkb(shapely.to_wkb(g)) for g in gs])
    column = np.array(cands, dtype=object)
    want = shapely.intersects(np.array(obstacles, dtype=object).reshape(-1)[None, :], column[:, None])
    for lines in (False, True):
        got = row.meets(column, lines=lines)
        assert np.array_equal(got, want)
        assert np.array_equal(row.count(column, lines=lines), want.sum(axis=1))
        assert np.array_equal(row.any(column, lines=lines), want.any(axis=1))
    rects = np.array([g for g in cands if g.geom_type == "Polygon" and shapely.equals(g, shapely.envelope(g))],
                     dtype=object)
    if len(rects):
        assert np.array_equal(row.meets(rects, shapely.bounds(rects)),
                              shapely.intersects(np.array(obstacles, dtype=object).reshape(-1)[None, :], rects[:, None]))


def test_leader_segments_are_leader_segment_bit_for_bit():
    """``_leader_segments`` of a ring's boxes (their nearest edge points from ``_towards``) is ``_leader_segment`` of
    each box, coordinate for coordinate: anchors outside, on an edge, at a corner and inside boxes of every shape."""
    rng = np.random.default_rng(14)
    checked = 0
    for _ in range(40):
        anchor = rng.normal(0, 30, 2) if rng.random() < 0.8 else np.round(rng.normal(0, 3, 2))
        w, h = (float(x) for x in rng.choice([rng.uniform(0.01, 20), 1.0, 2.0], 2))
        ring = L._Ring(anchor, w, h, float(rng.uniform(-180, 180)), float(rng.choice([0.0, 3.0, rng.uniform(0, 40)])),
                       int(rng.choice([8, 16, 24])))
        pp = float(rng.choice([0.35, 0.01, 2.0]))
        edges = L._towards(ring.geoms, anchor)
        got = L._leader_segments(anchor, edges, pp)
        for i, b in enumerate(ring.geoms):
            want = L._leader_segment(anchor, b, pp)
            assert np.array_equal(shapely.get_coordinates(got[i]), shapely.get_coordinates(want))
            checked += 1
    assert len(L._leader_segments(np.zeros(2), np.empty((0, 2)), 0.35)) == 0
    assert checked > 300


def _slow_nearer_own(own, rings):
    """kennedy._nearer_own as it was: every other ring's distance asked of GEOS."""
    others = np.array([g for g in rings if not g.equals(own)], dtype=object)

    def accept(b) -> bool:
        return bool(np.all(b.distance(own) < shapely.distance(b, others)))
    return accept


def test_nearer_own_ring_answers_as_every_distance():
    """``kennedy._nearer_own``'s test (GEOS asked only of the rings whose envelopes lie near) answers as the test that
    asks every ring, box for box: rings in a crowd and apart, boxes touching a ring, between two rings at equal
    distance, over a ring, far off."""
    rng = np.random.default_rng(41)
    checked = 0
    for _ in range(8):
        centres = np.round(rng.uniform(-5, 5, (int(rng.integers(2, 9)), 2)) * 2) / 2
        rings = [Point(*c).buffer(0.25, quad_segs=10) for c in centres]
        for own in rings[:3]:
            fast, slow = K._nearer_own(own, rings), _slow_nearer_own(own, rings)
            x0, y0, x1, y1 = own.bounds
            boxes = [box(x1, y0, x1 + 1.0, y1), box(x0 - 0.5, y0 - 0.5, x1 + 0.5, y1 + 0.5)]
            for _ in range(25):
                c = np.round(rng.uniform(-6, 6, 2) * 4) / 4
                w, h = rng.choice([0.25, 0.5, 1.0, 2.0], 2)
                boxes.append(box(c[0] - w / 2, c[1] - h / 2, c[0] + w / 2, c[1] + h / 2))
            for b in boxes:
                assert fast(b) == slow(b), (own, b)
                checked += 1
    assert checked > 500


def test_a_scene_is_kept_while_every_geometry_is_the_same_object():
    """``LabelPlacer._scene`` gives the scene made before from the same anchor while the view, the scale and every
    label's box, obstacle and leader are the very same objects (after a trial undone, too); a label placed, an
    obstacle added or one exchanged for an equal copy, another anchor: a new scene."""
    ax = _axes((4, 4))
    ax.set_xlim(-8, 8)
    ax.set_ylim(-8, 8)
    pl = L.LabelPlacer(ax)
    pl.add_obstacle(Point(0.0, 3.0).buffer(0.5))
    line = LineString([(-8, 0.5), (8, 0.5)])
    pl.add_obstacle(line, hard=False)
    pp, anchor = per_point(ax), np.array([1.0, 1.0])
    first = pl._scene(anchor, pp)
    assert pl._scene(anchor.copy(), pp) is first
    with pl.trial():
        pl.place((2.0, 2.0), "x", fontsize=9)
    assert pl._scene(anchor, pp) is first
    pl.place((2.0, 2.0), "x", fontsize=9)
    second = pl._scene(anchor, pp)
    assert second is not first and len(second.state[0]) == 1
    pl.soft[0] = LineString([(-8, 0.5), (8, 0.5)])   # an equal copy: not the same object
    assert pl._scene(anchor, pp) is not second
    assert pl._scene(anchor + 1e-9, pp) is not pl._scene(anchor, pp)


def _old_clear_places(pl, anchor, w, h, prefer=None, gap=2.5):
    """LabelPlacer.clear_places as it was (one box, one leader at a time)."""
    pp, view, anchor = per_point(pl.ax), view_box(pl.ax), np.asarray(anchor, float)
    keep_off = np.array(pl.boxes + pl.leaders, dtype=object)[None, :]
    hard = np.array(pl._hard, dtype=object)[None, :]
    soft = np.array(pl.prepared_soft(), dtype=object)[None, :]
    at_anchor = shapely.intersects(soft[0], Point(*anchor).buffer(2.0 * pp)) if soft.size else None

    def n_of(obstacles, geoms, n):
        return np.zeros(n, int) if not obstacles.size else shapely.intersects(obstacles, geoms).sum(axis=1)
    got = []
    for ring in sorted({gap, *(r for r in L.RINGS if r > gap), *L.FAR_RINGS, *L.REACH_RINGS}):
        cands = L._Ring(anchor, w, h, prefer, ring * pp, 48 if ring in L.REACH_RINGS else 24)
        ok = shapely.contains(view, cands.geoms)
        if keep_off.size:
            ok &= ~shapely.intersects(keep_off, cands.geoms[:, None]).any(axis=1)
        idx = np.flatnonzero(ok)
        edges = L._towards(cands.geoms[idx], anchor)
        far = np.hypot(*(edges - anchor).T)
        lines = np.array([None if d < 8.0 * pp else L._leader_segment(anchor, b, pp)
                          for d, b in zip(far, cands.geoms[idx])], dtype=object)
        has = np.array([ln is not None for ln in lines], bool)
        if keep_off.size and has.any():
            crossing = shapely.intersects(keep_off, lines[:, None]).any(axis=1)
            idx, lines, far, has = idx[~crossing], lines[~crossing], far[~crossing], has[~crossing]
        g = cands.geoms[idx][:, None]
        across = np.zeros(len(idx), int)
        if soft.size and has.any():
            across[has] = (shapely.intersects(soft, lines[has][:, None]) & ~at_anchor).sum(axis=1)
        got.append((cands.centres[idx], cands.geoms[idx], lines, n_of(hard, g, len(idx)), n_of(soft, g, len(idx)),
                    across, np.where(has, far, 0.0)))
    keys = ("centres", "boxes", "leaders", "hard", "soft", "across", "reach")
    return {k: np.concatenate([x[n] for x in got]) for n, k in enumerate(keys)}


def _same_places(new: dict, old: dict) -> bool:
    """Two clear_places answers alike bit for bit."""
    if new.keys() != old.keys() or len(new["boxes"]) != len(old["boxes"]):
        return False
    geoms = [(a, b) for k in ("boxes", "leaders") for a, b in zip(new[k], old[k])]
    return (all(np.array_equal(new[k], old[k]) for k in ("centres", "hard", "soft", "across", "reach"))
            and all((a is None and b is None) or (a is not None and b is not None and
                                                  shapely.equals_exact(a, b, tolerance=0.0)) for a, b in geoms))


def _slow_paths(monkeypatch):
    """Every shortcut of the fourteenth session replaced by its slow path: every pair asked of GEOS on the plain
    geometries, a new scene for every search, each ring's distance asked, a try placed and undone."""
    def meets(self, geoms, bounds=None, lines=False):
        if not len(geoms) or not self.size:
            return np.zeros((len(geoms), self.size), bool)
        return shapely.intersects(self.geoms[None, :], np.asarray(geoms, dtype=object)[:, None])
    place = L.LabelPlacer.place

    def tried(self, *args, last_resort=True, **kw):
        if last_resort:
            return place(self, *args, **kw)
        with self.trial():
            n = len(self.overlapping)
            t = place(self, *args, **kw)
            self.keep = len(self.overlapping) == n
        return t if self.of(t) is not None else None
    monkeypatch.setattr(L._Row, "meets", meets)
    monkeypatch.setattr(L.LabelPlacer, "_scene", lambda self, anchor, pp: L._Scene(self, anchor, pp))
    monkeypatch.setattr(L.LabelPlacer, "place", tried)
    monkeypatch.setattr(K, "_nearer_own", _slow_nearer_own)


def _placements(ax) -> list:
    """Everything placed on ``ax``, as numbers: each text's gid, string, position and size, each line's data, each
    placed label's box."""
    return ([(t.get_gid(), t.get_text(), tuple(map(float, t.get_position())), t.get_fontsize()) for t in ax.texts]
            + [(ln.get_gid(), np.asarray(ln.get_xydata()).tobytes()) for ln in ax.lines]
            + [p.box.wkb for p in L.placer(ax).labels])
