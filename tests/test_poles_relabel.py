"""A poles drawing's labels placed again in another order on the drawing made once (``kennedy._least_tangled``)
are the drawing made anew in that order, artist for artist.

A crowd of poles whose leaders cross is labelled again in the reverse order, then the most crowded first. The
mechanism, the Kennedy lines and the poles' marks are drawn once: for each order the drawing comes back to where it
stood before the labels (``LabelPlacer.moment``/``back_to``: what the mechanism's labels moved for the poles' put
back), the things drawn pole by pole put in that order (``kennedy._in_order``), and only the labels are placed
again; the order kept is put back as it stood. Checked at the data level on generated mechanisms (each artist on
the axes in drawing order: its kind, gid, zorder, place, size, points; the placer's labels, obstacles and pins).
"""
from __future__ import annotations

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.text import Text
from shapely.geometry import LineString

import zoo
from velpoly.poles import locate_poles
from velpoly.render import kennedy
from velpoly.render.canvas import Artists, box, fit_view
from velpoly.render.labels import Placed, placer
from velpoly.render.options import drawing_options
from velpoly.render.style import get_style, rc_context

# of zoo(2026)'s first specimens, a double-rocker four-bar and an offset slider-crank (each 0.1-0.2 CPU s a drawing;
# two poles found by Kennedy's theorem, their lines and the six marks drawn pole by pole)
SPECIMENS = (2, 7)


def drawn(ax, art) -> tuple:
    """What is drawn on ``ax`` and what its placer holds, as plain data (an artist named by its place in the drawing
    order): each artist in drawing order (kind, gid, zorder, visible; a text's string, place, size and colour; a
    line's points, width and style; a patch's outline), the placer's labels (text, box, leader, anchor), hard and
    soft obstacles, texts along lines, labels on a crowd's last resort, where each label went, and the drawing's
    roles, pole labels and rings in their order."""
    children = list(ax._children)
    at = {id(a): n for n, a in enumerate(children)}

    def ref(a):
        return None if a is None else at.get(id(a), "off the axes")

    def one(a):
        head = (type(a).__name__, a.get_gid(), a.get_zorder(), a.get_visible())
        if isinstance(a, Text):
            return head + (a.get_text(), tuple(map(float, a.get_position())), a.get_fontsize(), a.get_color())
        if isinstance(a, Line2D):
            return head + (np.asarray(a.get_xydata(), float).tobytes(), a.get_linewidth(), str(a.get_linestyle()))
        if isinstance(a, Patch):
            return head + (np.asarray(a.get_path().vertices, float).tobytes(), a.get_transform().get_matrix().tobytes())
        return head
    pl = placer(ax)
    return ([one(a) for a in children],
            [(ref(p.text), p.box.wkb, ref(p.leader), None if p.leader_geom is None else p.leader_geom.wkb,
              None if p.anchor is None else tuple(p.anchor)) for p in pl.labels],
            [[g.wkb for g in lst] for lst in (pl._hard, pl.soft, pl.along)],
            [ref(t) for t in pl.overlapping], sorted(repr(kv) for kv in pl.placed.items()),
            [(role, [ref(a) for a in v]) for role, v in art.items()], [(k, ref(t)) for k, t in art.labels.items()],
            list(art.rings))


def blank(bounds, scale=None, margin: float = 0.0, size=(4.0, 4.0)):
    """An empty axes on a page of its own (``size``, inches) whose view holds ``bounds`` (``fit_view``'s)."""
    fig = Figure(figsize=size, dpi=72)
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0.02, 0.02, 0.96, 0.96))
    fit_view(ax, bounds, scale=scale, margin=margin)
    ax.set_axis_off()
    return ax


def page(sol, st):
    """A poles page's axes for ``sol``, its view fitted as ``draw_poles`` fits it; with its poles and options."""
    ps, opts = locate_poles(sol), drawing_options(sol.mechanism)
    return blank(kennedy.poles_bounds(sol, ps), opts.scale, 0.1, (5.5, 5.0)), ps, opts


def test_labels_placed_again_in_another_order_are_the_drawing_made_in_that_order():
    """On generated mechanisms: the drawing made in the listed order, its labels then placed again in the reverse
    order on it, is the drawing made anew in the reverse order; and the listed order's drawing, taken as it stood
    and put back after the other order was placed, is the listed order's again."""
    st = get_style("textbook")
    specimens = list(zoo.each(2026, max(SPECIMENS) + 1))
    checked = 0
    with rc_context(st):
        for i in SPECIMENS:
            sol = specimens[i].drawn
            shown = kennedy.shown_poles(locate_poles(sol))
            order = shown[::-1]
            assert [p.key for p in order] != [p.key for p in shown]
            # made anew in the reverse order
            ax, ps, opts = page(sol, st)
            art, lines, _ = kennedy._poles_drawn(sol, ax, st, opts, ps, order, None, True)
            kennedy._poles_labelled(sol, ax, ps, order, lines, st, art, None)
            anew = drawn(ax, art)
            # made in the listed order, its labels placed again in the reverse order
            ax, ps, opts = page(sol, st)
            art, lines, own = kennedy._poles_drawn(sol, ax, st, opts, ps, shown, None, True)
            base = kennedy._Drawn.of(art)
            kennedy._poles_labelled(sol, ax, ps, shown, lines, st, art, None)
            first, kept = drawn(ax, art), kennedy._Drawn.of(art)
            base.in_order(own, order).restore(art)
            kennedy._poles_labelled(sol, ax, ps, order, lines, st, art, None)
            assert drawn(ax, art) == anew, specimens[i].kind
            kept.restore(art)   # the listed order's, put back
            assert drawn(ax, art) == first, specimens[i].kind
            checked += first != anew
    assert checked == len(SPECIMENS)   # each order draws another drawing (else nothing was put in order)


def test_a_placer_and_its_axes_come_back_to_a_moment():
    """``LabelPlacer.back_to``: after labels were placed, one taken off with its leader, one moved and set smaller,
    an obstacle added, the placer and its axes are as they were at the moment taken (the labels taken off put back in
    their places in the drawing order, each text at its place and size)."""
    ax = blank((0.0, 0.0, 10.0, 10.0))
    fig, pl = ax.figure, placer(ax)
    pl.add_obstacle(box(4.0, 4.0, 6.0, 6.0))
    texts = [pl.place(xy, s, leader=True, gid=s) for xy, s in (((5.0, 5.0), "A"), ((5.2, 5.1), "B"), ((5.1, 4.9), "C"),
                                                               ((2.0, 8.0), "D"))]
    ax.add_line(Line2D([0, 1], [0, 1], gid="after"))
    art = Artists(ax)
    art.add("labels", *texts)
    art.rings = {}
    before, m = drawn(ax, art), pl.moment()
    assert any(p.leader is not None for p in pl.labels)
    with_leader = next(p.text for p in pl.labels if p.leader is not None)
    pl.remove(with_leader)
    pl.move(texts[3], (0.5, 0.5), box(2.0, 8.0, 3.0, 9.0))
    texts[3].set_fontsize(5.0)
    pl.add_obstacle(box(0.0, 0.0, 1.0, 1.0))
    pl.place((8.0, 2.0), "E", gid="E")
    assert drawn(ax, art) != before
    pl.back_to(m)
    assert drawn(ax, art) == before
    assert all(t.axes is ax and t.get_figure(root=False) is fig for t in texts)


def one_at_a_time(labels) -> list:
    """``LabelPlacer._crossings`` as it was written: each leader against each other label's box, else against each
    later leader, one pair at a time."""
    lines = [None if p.leader is None else LineString(np.column_stack(p.leader.get_data())) for p in labels]
    out = []
    for i, ln in enumerate(lines):
        if ln is None:
            continue
        for j, q in enumerate(labels):
            if j != i and q.box.intersects(ln):
                out.append((i, j, "box"))
            elif j > i and lines[j] is not None and lines[j].intersects(ln):
                out.append((i, j, "leader"))
    return out


def test_crossings_listed_at_once_are_those_listed_one_at_a_time():
    """The crossings a crowd's untangling counts for each swap it weighs (``LabelPlacer._crossings``: every leader
    against every box and every later leader in one shapely call) are, pair for pair and in order, those found one
    pair at a time: on 300 seeded scenes of up to 12 labels, most with leaders, many crossing (boxes and leaders
    touching at an end or a corner among them)."""
    rng = np.random.default_rng(20261128)
    pl = placer(blank((0.0, 0.0, 10.0, 10.0)))
    kinds = set()
    for _ in range(300):
        labels = []
        for _ in range(int(rng.integers(0, 13))):
            c = rng.integers(0, 21, 2) / 2.0   # on a half grid: ends and corners meet exactly
            w, h = rng.integers(1, 5, 2) / 2.0
            leader = None
            if rng.random() < 0.6:
                a = rng.integers(0, 21, 2) / 2.0
                leader = Line2D([a[0], c[0] - w / 2], [a[1], c[1]])
            labels.append(Placed(None, box(c[0] - w / 2, c[1] - h / 2, c[0] + w / 2, c[1] + h / 2), leader))
        got = pl._crossings(labels)
        assert got == one_at_a_time(labels)
        kinds.update(k for _, _, k in got)
    assert kinds == {"box", "leader"}
