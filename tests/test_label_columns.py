"""Boundary labelling: a crowd's pole labels whose leaders cross set in a column along a free side of the panel
(issue 17 item 4: "leader lines of pole labels cross so that one cannot tell which ring is which";
``kennedy._in_columns``, ``velpoly/render/columns.py``).

Generated crowds (seeded: four clusters of 5 to 8 poles within 1.2 cm, three lines through each as the
Kennedy lines are, on a 12 x 9 cm panel): each pole labelled by the placer, then the labels' places dealt out
among them at random, as a crowd's last-resort places taken one at a time leave them (leaders crossing).
Checked at the data level: each leader as drawn (its Line2D, display coordinates) against every other leader
and every other label's box (its window extent). With ``kennedy._in_columns`` answering False by hand (the
drawing left as dealt, as on main 9945c0a) every crowd keeps its crossings.
"""
from __future__ import annotations

import itertools
from types import SimpleNamespace

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from shapely.geometry import LineString, Point, box  # noqa: E402

from velpoly.render import kennedy  # noqa: E402
from velpoly.render.canvas import renderer_of  # noqa: E402
from velpoly.render.columns import _least_matching  # noqa: E402
from velpoly.render.labels import placer, segment  # noqa: E402

CROWDS = range(4)
SIZE = 10.0


def crowd(seed: int):
    """A seeded crowd on a bare 12 x 9 cm axes (data in cm): its poles' labels placed, then their places dealt out
    at random (each box centred where another stood). Returns the axes and ``art`` (``labels``, ``rings``)."""
    rng = np.random.default_rng(seed)
    fig = plt.figure(figsize=(12 / 2.54, 9 / 2.54))
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, 12)
    ax.set_ylim(0, 9)
    ax.set_aspect("equal")
    ax.set_axis_off()
    pl = placer(ax)
    n = int(rng.integers(5, 9))
    c = np.array([6.0, 4.5]) + rng.uniform(-1, 1, 2)
    at = c + rng.uniform(-1.2, 1.2, (n, 2))
    for a in rng.uniform(0, np.pi, 3):   # lines through the crowd, as Kennedy lines are: hard for labels
        d = np.array([np.cos(a), np.sin(a)]) * 20
        g = segment(c - d, c + d)
        ax.plot(*np.column_stack([c - d, c + d]), lw=0.5, color="0.5")
        pl.add_obstacle(g)
        pl.add_obstacle(g, hard=False)
    art = SimpleNamespace(labels={}, rings={})
    for k, q in enumerate(at):
        key = f"{k}-9"
        art.rings[key] = Point(*q).buffer(0.085)
        pl.add_obstacle(art.rings[key])
        art.labels[key] = pl.place(q, f"$P_{{{k}9}}$", fontsize=SIZE, gap=20.0, reach=True, gid=f"label-pole-{key}")
    old = list(pl.labels)
    deal = rng.permutation(len(old))
    new = []
    for p, q in zip(old, (old[i] for i in deal)):
        (x0, y0, x1, y1), (u0, v0, u1, v1) = p.box.bounds, q.box.bounds
        cx, cy = (u0 + u1) / 2, (v0 + v1) / 2
        b = box(cx - (x1 - x0) / 2, cy - (y1 - y0) / 2, cx + (x1 - x0) / 2, cy + (y1 - y0) / 2)
        new.append(pl._moved(p, b, pl._leader_line(p.anchor, b)))
    pl._commit(new, range(len(new)))
    return ax, art


def crossings(ax) -> int:
    """Pairs of drawn leaders that cross, and leaders across another label's box (display coordinates)."""
    r = renderer_of(ax.figure)
    lines = {ln.get_gid()[:-len("-leader")]: LineString(ax.transData.transform(np.column_stack(ln.get_data())))
             for ln in ax.lines if (ln.get_gid() or "").endswith("-leader")}
    boxes = {t.get_gid(): box(*t.get_window_extent(r).extents) for t in ax.texts}
    return (sum(lines[a].intersects(lines[b]) for a, b in itertools.combinations(sorted(lines), 2))
            + sum(line.intersects(b) for g, line in lines.items() for h, b in boxes.items() if h != g))


@pytest.mark.parametrize("seed", CROWDS)
def test_a_crowds_crossing_leaders_set_in_a_column_cross_none(seed):
    """A crowd dealt with crossing leaders: after ``_in_columns`` no leader crosses another leader or a label, every
    label has a leader from its own pole, and the labels moved stand in view, aligned in a column (their boxes
    flush on one line) or a row."""
    ax, art = crowd(seed)
    ax.figure.draw_without_rendering()
    assert crossings(ax) > 0   # (the generated crowd is crossed)
    moved_before = {k: t.get_position() for k, t in art.labels.items()}
    kennedy._in_columns(placer(ax), art, SIZE)
    ax.figure.draw_without_rendering()
    assert crossings(ax) == 0
    pl = placer(ax)
    moved = [pl.of(t) for k, t in art.labels.items() if t.get_position() != moved_before[k]]
    view = box(0, 0, 12, 9)
    assert moved and all(view.contains(p.box) for p in moved)
    for p in pl.labels:   # each leader starts at its own pole (1.5 pt off it)
        if p.leader is not None:
            assert Point(p.leader.get_xydata()[0]).distance(Point(*p.anchor)) < 0.06
    edges = np.array([p.box.bounds for p in moved])
    side = np.argmin(np.column_stack([12 - edges[:, 0], 9 - edges[:, 1], edges[:, 2], edges[:, 3]]), axis=1)
    for s in set(side.tolist()):   # a column's boxes flush on the drawing's side (right: their left edges), a row's too
        assert np.ptp(edges[side == s, s]) < 1e-9, edges
    plt.close(ax.figure)


def test_least_matching_is_the_least_total():
    """The Hungarian method against every assignment of seeded price tables, 1 to 4 rows, up to 6 places."""
    rng = np.random.default_rng(3)
    for _ in range(200):
        n = int(rng.integers(1, 5))
        m = int(rng.integers(n, 7))
        cost = rng.random((n, m)) * rng.choice([1.0, 1e6], (n, m))
        at = _least_matching(cost)
        least = min(sum(cost[i, p[i]] for i in range(n)) for p in itertools.permutations(range(m), n))
        assert len(set(at.tolist())) == n
        assert sum(cost[i, at[i]] for i in range(n)) == pytest.approx(least, rel=1e-9, abs=1e-12)


def test_a_crowd_with_no_free_column_is_left_as_it_was():
    """A panel whose every place is covered (an outline over it all): no column, the labels where they stood."""
    ax, art = crowd(0)
    pl = placer(ax)
    pl.add_obstacle(box(-1, -1, 13, 10), hard=False)
    at = [p.box.bounds for p in pl.labels]
    assert not kennedy._in_columns(pl, art, SIZE)
    assert [p.box.bounds for p in pl.labels] == at
    plt.close(ax.figure)
