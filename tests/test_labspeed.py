"""A label's second search finds its rings and their tests made (render/labels.py, ``_Scene.ring``/``tests``).

:meth:`LabelPlacer.place` with ``accept`` (a pole's label nearer its own ring) searches twice on one scene when
the first answer is not the first ring's preferred place: the second search walks the same rings, and the
scene now keeps each ring (``_Scene.ring``) with the tests of its candidates (``_Scene.tests``) instead of
making and testing them again. Checked here: a kept ring is the very ring ``_Ring`` makes (a numpy float kept
apart from a Python one: its arithmetic is its own), the kept tests are the scene's own answers, and every
search of a generated poles drawing gives, bit for bit, what the same search gives on a fresh scene (where
nothing is kept)."""
from __future__ import annotations

import numpy as np
import pytest
import shapely
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from shapely.geometry import LineString, Point

import zoo
from velpoly.render import labels as L
from velpoly.render.canvas import box, per_point
from velpoly.render.kennedy import draw_poles
from velpoly.render.style import get_style, rc_context


def _same(new, old) -> bool:
    """Two search results alike bit for bit: score, centre, box, ring."""
    if new is None or old is None:
        return new is None and old is None
    return (new[0] == old[0] and np.array_equal(new[1], old[1]) and new[3] == old[3]
            and shapely.equals_exact(new[2], old[2], tolerance=0.0))


def _axes(size):
    fig = Figure(figsize=size, dpi=72)
    FigureCanvasAgg(fig)
    return fig.add_axes((0.02, 0.02, 0.96, 0.96))


def test_kept_rings_and_tests_are_the_made_ones():
    """``_Scene.ring`` gives one ring per exact arguments (a numpy float prefer apart from a Python one), equal
    bit for bit to ``_Ring``'s; ``_Scene.tests`` gives the scene's free, soft and leader answers, the same object
    when asked again; on touching boxes and a zero-length segment."""
    ax = _axes((4, 4))
    ax.set_xlim(-8, 8)
    ax.set_ylim(-8, 8)
    pl = L.LabelPlacer(ax)
    pl.labels = [L.Placed(None, box(1.0, 1.0, 2.0, 2.0)), L.Placed(None, box(-3.0, 0.0, -2.0, 1.0))]
    pl.add_obstacle(Point(0.0, 3.0).buffer(0.5))
    for g in (LineString([(-8, 0.5), (8, 0.5)]), LineString([(1.0, 1.0), (1.0, 1.0)]), box(-1, -6, 1, -5)):
        pl.add_obstacle(g, hard=False)
    anchor = np.array([0.0, 0.0])
    scene = L._Scene(pl, anchor, per_point(ax))
    made = 0
    for prefer in (90.0, np.float64(90.0), None):
        for ring, k, within in ((0.0, 8, None), (2.0 / scene.pp, 16, None), (3.0 / scene.pp, 24, 60.0)):
            cands = scene.ring(anchor, 1.0, 1.0, prefer, ring, k, within)
            assert scene.ring(anchor, 1.0, 1.0, prefer, ring, k, within) is cands
            fresh = L._Ring(anchor, 1.0, 1.0, prefer, ring * scene.pp, k, within)
            assert np.array_equal(cands.centres, fresh.centres) and np.array_equal(cands.bounds, fresh.bounds)
            part = np.arange(len(cands))
            free, soft, crosses, on = scene.tests(cands, part, True)
            assert scene.tests(cands, part, True)[0] is free
            assert np.array_equal(free, scene.free(cands, part))
            if len(free):
                assert np.array_equal(soft, scene.soft_hits(cands, free))
                want = scene.leader_tests(cands, free)
                assert np.array_equal(crosses, want[0]) and np.array_equal(on, want[1])
                made += 1
    assert scene.ring(anchor, 1.0, 1.0, 90.0, 0.0, 8, None) is not scene.ring(anchor, 1.0, 1.0, np.float64(90.0),
                                                                               0.0, 8, None)
    assert made >= 6, made


@pytest.fixture
def fresh_compared(monkeypatch):
    """Every search made inside checked against the same search on a fresh scene (nothing kept); counts."""
    seen = {"search": 0, "again": 0}
    search = L.LabelPlacer._search
    scenes: set = set()

    def checked(self, anchor, w, h, prefer, gap, leader, within, accept, clear=False, reach=False, scene=None,
                crossing=L.LEADER_MOST):
        new = search(self, anchor, w, h, prefer, gap, leader, within, accept, clear, reach, scene, crossing)
        old = search(self, anchor, w, h, prefer, gap, leader, within, accept, clear, reach, None, crossing)
        assert _same(new, old), (anchor, prefer, new, old)
        seen["search"] += 1
        seen["again"] += scene is not None and id(scene) in scenes
        if scene is not None:
            scenes.add(id(scene))
        return new
    monkeypatch.setattr(L.LabelPlacer, "_search", checked)
    return seen


def test_second_searches_of_a_generated_poles_drawing_are_the_fresh_ones(fresh_compared):
    """A generated four-bar's poles drawing on a small page (pole labels placed with ``accept``, so that some
    search twice): each search equals the search on a fresh scene, bit for bit, the second ones included."""
    rng = np.random.default_rng(3)
    four = zoo.specimen(rng, "four-bar").drawn
    st = get_style("textbook")
    with rc_context(st):
        draw_poles(four, _axes((3.0, 2.8)), style=st)
    assert fresh_compared["search"] > 8 and fresh_compared["again"] > 0, fresh_compared
