"""Labels that never overlap: placement with shapely, in data coordinates.

A :class:`LabelPlacer` belongs to one axes (:func:`placer`). Drawings
register what labels must not cover (arrowheads, pins, pivots: *hard*
obstacles) and what they should rather not cover (links, lines: *soft*).
:meth:`LabelPlacer.place` measures the text with the figure's renderer,
converts its box into data coordinates, and tries candidate positions around
the anchor, ring after ring, in a fixed order of directions (the preferred
one first): the first box that stays in view, meets no placed label and no
hard obstacle, and crosses the fewest soft ones, wins. Far from its anchor, a
label gets a thin leader line. Nothing is random: the same drawing gives
the same placement.
"""
from __future__ import annotations

import functools
import math
from contextlib import contextmanager
from dataclasses import dataclass, replace
from typing import Any, Callable

import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import LineString, Point

from .canvas import box, per_point, renderer_of, view_box
from .textcache import window_extent

__all__ = ["LabelPlacer", "Moment", "Placed", "placer", "segment", "half_extent", "ALONG_APART", "meets_any",
           "all_farther"]

# ring radii, in points of gap between the anchor and the box
RINGS = (2.5, 5.0, 9.0, 14.0, 21.0, 30.0, 42.0, 58.0)
FAR_RINGS = (9.0, 21.0, 42.0, 80.0, 105.0)   # finer directions, only when nothing above is free
REACH_RINGS = (135.0, 170.0, 220.0, 280.0)   # finer still, with ``reach`` only, when nothing above is free
ALONG_APART = 1.0   # of the type size: the gap two texts along lines keep between their boxes
LEADER_MOST = 0   # the most lines and outlines a far label's leader (see LabelPlacer.place's clear) may cross
SCENES_KEPT = 8   # the search scenes a placer keeps (LabelPlacer._scene)


@dataclass(frozen=True, eq=False)
class Placed:
    """One label the placer put down: its ``text`` (a matplotlib Text), its ``box`` (shapely, data
    coordinates, with the margin it keeps), its ``leader`` (the Line2D drawn from its anchor, or None) with
    ``leader_geom`` (that line as the obstacle later labels keep off), ``again``: how its drawing places
    it anew (a driver's value a later leader crosses), or None, the ``anchor`` it labels (placed by
    :meth:`LabelPlacer.place`; else None) and, for a text along a line, ``apart``: its box grown by the em the
    other such texts keep from it (in :attr:`LabelPlacer.along`)."""

    text: Any
    box: Any
    leader: Any = None
    leader_geom: Any = None
    again: Callable | None = None
    anchor: Any = None
    apart: Any = None


@dataclass(frozen=True, eq=False)
class Moment:
    """A placer and its axes as they stood (:meth:`LabelPlacer.moment`), to come back to (:meth:`LabelPlacer.back_to`):
    the axes' ``artists`` in their drawing order, each Text's place and type size (``texts``: ``(text, (x, y),
    size)``; the placer moves and resizes the labels it placed), each leader's points (``leaders``: ``(line, x,
    y)``), the placer's lists (``labels``, ``hard``, ``soft``, ``overlapping``, ``along``) and where each label
    went (``placed``)."""

    artists: list
    texts: list
    leaders: list
    labels: list
    hard: list
    soft: list
    overlapping: list
    along: list
    placed: dict


class LabelPlacer:
    """Place texts on an axes so that no two boxes intersect (see the module's docstring).

    What it placed is :attr:`labels`, a list of :class:`Placed` (:meth:`of` finds a Text's); the texts,
    their boxes and their leaders as obstacles are read from it (:attr:`texts`, :attr:`boxes`,
    :attr:`leaders`)."""

    def __init__(self, ax):
        self.ax = ax
        self.renderer = renderer_of(ax.figure)
        self._hard: list = []      # hard obstacles registered (the leaders are hard too: :attr:`hard`)
        self.soft: list = []
        self.labels: list[Placed] = []
        # where each label (by gid) went, and where it must go: the frames of a step sequence put every
        # label, scale bar and legend where the finished construction has it, so that nothing jumps
        self.placed: dict = {}
        self.pins: dict = {}
        self.along: list = []      # the boxes of the texts written along lines (a line's reason), each grown by
        #                            the em its neighbours keep from it
        self._prepared: dict = {}  # id(soft obstacle) -> (it, its prepared copy): see prepared_soft()
        self._scenes: dict = {}    # (anchor, scale, view) -> the last _Scene made there: see _scene()

    @property
    def boxes(self) -> list:
        """The shapely boxes of the placed labels."""
        return [p.box for p in self.labels]

    @property
    def texts(self) -> list:
        """The Text artists of the placed labels, in the same order."""
        return [p.text for p in self.labels]

    @property
    def leaders(self) -> list:
        """The leader lines drawn, as obstacles."""
        return [p.leader_geom for p in self.labels if p.leader_geom is not None]

    @property
    def hard(self) -> list:
        """Every hard obstacle: those registered and the leaders."""
        return self._hard + self.leaders

    def of(self, text) -> Placed | None:
        """The :class:`Placed` of a Text this placer put down (None if it did not)."""
        return next((p for p in self.labels if p.text is text), None)

    # -- obstacles ---------------------------------------------------------------------
    def add_obstacle(self, geom, hard: bool = True) -> None:
        """Register a shapely geometry (data coordinates) labels must avoid (hard) or should (soft)."""
        if geom is None or geom.is_empty:
            return
        (self._hard if hard else self.soft).append(geom)

    def add_box(self, text, box=None, anchor=None) -> Placed:
        """Register an already drawn Text as a placed label (its box: measured if not given; ``anchor``: what it
        labels, where a step frame may move it to its pin with a leader, :meth:`settle`)."""
        self.labels.append(Placed(text, self.box_of(text) if box is None else box,
                                  anchor=None if anchor is None else np.asarray(anchor, float)))
        return self.labels[-1]

    def move(self, text, by, box, leader_geom=None) -> None:
        """Move the placed ``text`` by ``by`` (data units) to ``box`` (its new box, margin kept), its leader now
        ``leader_geom`` (the leader line as an obstacle; None: it has none), and remember where it went."""
        own = self.of(text)
        x, y = text.get_position()
        at = (x + by[0], y + by[1])
        text.set_position(at)
        self.labels[self.labels.index(own)] = replace(own, box=box, leader_geom=leader_geom)
        gid = text.get_gid()
        if gid in self.placed and self.placed[gid][0] == "place":
            self.placed[gid] = ("place", at) + tuple(self.placed[gid][2:])

    def remove(self, text) -> None:
        """Take a placed label off the axes with its box and its leader (no longer an obstacle), so that it
        can be placed again."""
        own = self.of(text)
        self.labels.remove(own)
        if own.leader is not None:
            own.leader.remove()
        text.remove()

    @contextmanager
    def trial(self, aside: list | None = None):
        """Draw and place tentatively: on leaving, every label, obstacle, leader and artist added to the axes
        inside is gone again (to score a layout before choosing it), unless ``keep`` was set inside. With
        ``aside`` (a list), the trial's drawing as it stood at its end is appended to it as a :class:`Moment`, which
        :meth:`back_to` restores (a layout chosen after others were tried is not drawn again)."""
        sizes = [(lst, len(lst)) for lst in self._lists()]
        placed = dict(self.placed)
        before = {id(a) for a in self.ax.get_children()}
        self.keep = False   # set inside to keep what was placed
        try:
            yield self
        finally:
            if not self.keep:
                if aside is not None:
                    aside.append(self.moment())
                added = [a for a in self.ax.get_children() if id(a) not in before]
                for lst, n in sizes:
                    del lst[n:]
                self.placed.clear()
                self.placed.update(placed)
                for a in added:
                    a.remove()
            self.keep = False

    def moment(self) -> Moment:
        """What this placer and its axes hold now (:class:`Moment`): a drawing that places its labels in several
        orders comes back to it for each (:meth:`back_to`) instead of drawing everything again."""
        from matplotlib.text import Text
        artists = list(self.ax._children)   # (the axes' own list: its order is the drawing order of equal zorders)
        return Moment(artists, [(a, a.get_position(), a.get_fontsize()) for a in artists if isinstance(a, Text)],
                      [(p.leader, *p.leader.get_data()) for p in self.labels if p.leader is not None],
                      list(self.labels), list(self._hard), list(self.soft), list(self.overlapping), list(self.along),
                      dict(self.placed))

    def back_to(self, m: Moment) -> None:
        """This placer and its axes as they were at the moment ``m`` (:meth:`moment`): every artist added since
        taken off, every one taken off since put back (in its place in the drawing order), each Text at its place
        and size then and each leader through its points then, the placer's lists as they were."""
        fig, now = self.ax.get_figure(root=False), {id(a) for a in self.ax._children}
        keep = {id(a) for a in m.artists}
        for a in [a for a in self.ax._children if id(a) not in keep]:
            a.remove()
        for a in m.artists:
            if id(a) not in now:   # taken off (Artist.remove): attached again as Axes.add_* attaches it
                a.set_figure(fig)
                a.axes = self.ax
        self.ax._children[:] = m.artists
        for t, at, size in m.texts:
            if t.get_position() != at:
                t.set_position(at)
            if t.get_fontsize() != size:
                t.set_fontsize(size)
        for line, x, y in m.leaders:
            xs, ys = line.get_data()
            if xs is not x or ys is not y:
                line.set_data(x, y)
        for lst, was in ((self.labels, m.labels), (self._hard, m.hard), (self.soft, m.soft),
                         (self.overlapping, m.overlapping), (self.along, m.along)):
            lst[:] = was
        self.placed.clear()
        self.placed.update(m.placed)

    def _lists(self) -> tuple:
        """The lists a trial adds to: the labels, the obstacles, the labels placed overlapping, the texts along
        lines."""
        return self.labels, self._hard, self.soft, self.overlapping, self.along

    # -- measuring ---------------------------------------------------------------------
    def box_of(self, text, pad: float = 1.0, pp: float | None = None):
        """The Text's box in data coordinates, grown by ``pad`` points (a rotated text: its outline; ``pp``: the
        axes' :func:`per_point`, where known)."""
        return box(*self._bounds_of(text, pad, pp))

    def _bounds_of(self, text, pad: float, pp: float | None) -> tuple:
        """The corners ``(x0, y0, x1, y1)`` of :meth:`box_of`'s box (the very floats it is made of)."""
        bb = window_extent(text, self.renderer)
        inv = self.ax.transData.inverted()
        (x0, y0), (x1, y1) = inv.transform([[bb.x0, bb.y0], [bb.x1, bb.y1]])
        p = pad * (per_point(self.ax) if pp is None else pp)
        return min(x0, x1) - p, min(y0, y1) - p, max(x0, x1) + p, max(y0, y1) + p

    def text_size(self, text, pad: float = 1.0, pp: float | None = None) -> tuple[float, float]:
        """The width and height of the Text's unrotated :meth:`box_of` (data units). The box's bounds are the least
        and greatest of the corners it is made of, so they are taken from :meth:`_bounds_of` without the box where
        all four are finite; a text already unrotated is measured as it is (turning it to 0 and back changes
        nothing)."""
        rot = text.get_rotation()
        if rot != 0:
            text.set_rotation(0)
        bounds = self._bounds_of(text, pad, pp)
        if rot != 0:
            text.set_rotation(rot)
        if not all(map(math.isfinite, bounds)):
            bounds = box(*bounds).bounds   # (a NaN corner: the box canvas.box makes)
        x0, y0, x1, y1 = bounds
        return max(x0, x1) - min(x0, x1), max(y0, y1) - min(y0, y1)   # (a box's bounds: its least and greatest)

    def free(self, geom, soft: bool = False) -> bool:
        """Whether ``geom`` meets no placed label and no hard (or, with ``soft``, any) obstacle."""
        others = self.boxes + self.hard + (self.soft if soft else [])
        if not others:
            return True
        return not bool(np.any(shapely.intersects(np.array(others, dtype=object), geom)))

    def prepared_soft(self) -> list:
        """The soft obstacles as copies shapely has prepared (each indexed once: a search tests hundreds of boxes
        and leaders against the same lines and outlines; GEOS's prepared predicates answer as the plain ones
        do, faster), made once per obstacle while the placer lives. Copies: the registered geometries stay as
        they are for the drawings that share them."""
        return self.prepared(self.soft)

    def prepared(self, geoms) -> list:
        """Prepared copies of ``geoms`` (:meth:`prepared_soft`), each made once while the placer lives."""
        out = []
        for g in geoms:
            got = self._prepared.get(id(g))
            if got is None or got[0] is not g:
                copy = shapely.from_wkb(shapely.to_wkb(g))
                shapely.prepare(copy)
                got = self._prepared[id(g)] = (g, copy)
            out.append(got[1])
        return out

    def _state(self) -> tuple:
        """What a search tests against, as the geometries themselves: the labels' boxes, the hard obstacles
        registered, the leaders, the soft obstacles (lists)."""
        return self.boxes, list(self._hard), self.leaders, list(self.soft)

    def _scene(self, anchor, pp: float) -> _Scene:
        """The :class:`_Scene` of a search from ``anchor`` (``pp``: :func:`per_point`): the one last made there if
        the view and every geometry it was gathered from are the very same objects (shapely geometries do not
        change; each try a crowded label makes is undone by :meth:`trial`, which leaves these lists as they
        were), else a new one (kept in its place: one scene an anchor, at most :data:`SCENES_KEPT`)."""
        anchor = np.asarray(anchor, float)
        key = (anchor.tobytes(), pp, view_box(self.ax).bounds)
        state = self._state()
        got = self._scenes.get(key)
        if got is not None and all(len(a) == len(b) and all(x is y for x, y in zip(a, b))
                                   for a, b in zip(got.state, state)):
            return got
        if len(self._scenes) >= SCENES_KEPT:
            del self._scenes[next(iter(self._scenes))]
        got = self._scenes[key] = _Scene(self, anchor, pp, state)
        return got

    def soft_hits(self, geom) -> int:
        if not self.soft:
            return 0
        return int(np.count_nonzero(shapely.intersects(np.array(self.soft, dtype=object), geom)))

    # -- placing -----------------------------------------------------------------------
    def place(self, anchor, s: str, *, prefer: float | None = None, gap: float = 2.5, leader: bool = True,
              gid: str | None = None, obstacle: bool = True, pad: float = 1.0, within: float | None = None,
              accept=None, clear: bool = False, reach: bool = False, again: Callable | None = None, only: bool = False,
              crossing: int = LEADER_MOST, last_resort: bool = True, **text_kw):
        """Draw text ``s`` near ``anchor`` where it overlaps nothing; return the Text.

        ``prefer``: the preferred direction from the anchor (degrees), e.g.
        away from the link; the other directions follow alternately on either
        side of it. ``gap``: the smallest distance from the anchor (points);
        ``pad``: the margin kept around the text (points; more for a boxed text).
        A label that can find no free place in view is put at the candidate
        crossing the fewest obstacles (and the placement reports it through
        :attr:`overlapping`). ``within``: only directions within so many degrees
        of ``prefer`` (a label that must sit on one side of its anchor); if none
        of them is free, every direction. ``accept``: a test of a candidate box
        (data coordinates) it must pass where any free place does (a pole's label
        nearer its own ring than any other; ``only``: even where a place failing it
        crosses fewer lines). ``clear``: when every free place near
        the anchor lies on a line (a soft obstacle), look farther out (with a
        leader) for one on none. ``reach``: when nothing is free within the far
        rings, farther still (:data:`REACH_RINGS`: a long leader out of a crowd
        to a free place). A leader crosses no other label and no other leader.
        ``crossing``: with ``clear``, the most lines and outlines the leader of such a farther place may cross.
        ``again``: kept in the label's :class:`Placed` (how to place it anew). ``last_resort``: False where a
        label with no free place is of no use (a try that :meth:`trial` undoes unless one is free): the text is
        taken off again and None returned, its least bad place not sought.
        """
        anchor = np.asarray(anchor, float)
        t = self.ax.text(anchor[0], anchor[1], s, ha="center", va="center", **text_kw)
        if gid:
            t.set_gid(gid)
        pp = per_point(self.ax)   # (the axes' scale: placing a text changes neither its limits nor its size)
        w, h = self.text_size(t, pad, pp)
        best = self._pinned(gid, t, w, h, pad, pp)
        if best is None:
            scene = self._scene(anchor, pp)
            best = self._search(anchor, w, h, prefer, gap, leader, within, accept, clear, reach, scene, crossing)
            if accept is not None and not only and (best is None or best[0] != (0, 0)):   # a line under it is worse
                anywhere = self._search(anchor, w, h, prefer, gap, leader, within, None, clear, reach, scene, crossing)
                if anywhere is not None and (best is None or anywhere[0] < best[0]):
                    best = anywhere
        if best is None and within is not None:   # nothing free on that side: any side
            t.remove()
            return self.place(anchor, s, prefer=prefer, gap=gap, leader=leader, gid=gid, obstacle=obstacle, pad=pad,
                              clear=clear, reach=reach, again=again, crossing=crossing, last_resort=last_resort,
                              **text_kw)
        if best is None and not last_resort:
            t.remove()
            return None
        if best is None:
            best = self._least_bad(anchor, w, h, prefer, gap, leader, reach)   # (kept in its scene: see _least_bad)
            self.overlapping.append(t)
        self._put(t, anchor, best, gid, leader, obstacle, again, pp)
        return t

    def _pinned(self, gid, t, w: float, h: float, pad: float = 1.0, pp: float | None = None):
        """Where the finished construction put this label, at the size it has there, if that box is free here
        too (the Text then set to that size; else left as it was)."""
        pin = self.pins.get(gid) if gid else None
        if pin is None or pin[0] != "place":
            return None
        c = np.asarray(pin[1], float)
        size = t.get_fontsize()
        if len(pin) > 3 and pin[3] != size:   # set smaller there: measured at that size
            t.set_fontsize(pin[3])
            w, h = self.text_size(t, pad, pp)
        b = _box(c, w, h)
        if view_box(self.ax).contains(b) and self.free(b):
            return (0, c, b, pin[2])
        t.set_fontsize(size)
        return None

    def at_pin(self, t) -> bool:
        """Whether the Text stands where, and at the size, its pin (the finished construction) has it."""
        pin = self.pins.get(t.get_gid())
        if pin is None or pin[0] not in ("place", "at", "along"):
            return False
        return (tuple(map(float, t.get_position())) == tuple(map(float, _pinned_at(pin)))
                and (len(pin) < 4 or pin[3] == t.get_fontsize()))

    def settle(self) -> int:
        """A step frame's labels put at their pins: the labels placed elsewhere (each pinned box was taken when
        it was placed: by a label, leader or value that stands elsewhere in this frame, maybe by one another in
        a ring) lifted together, and each moved to the place and size the finished construction gives it where
        that box is free (in view, of the hard obstacles and of every label and leader that stays, its leader
        crossing no label); one whose box is not free stays where it is, and a label it would meet there keeps
        its place too. Repeated while one moves. Return the labels moved."""
        view, pp = view_box(self.ax), per_point(self.ax)
        moved = 0
        for _ in range(len(self.labels) + 1):
            lifted = [p for p in self.labels if self._movable(p)]
            kept = [p for p in self.labels if not any(p is q for q in lifted)]
            boxes = [q.box for q in kept]
            leaders = [q.leader_geom for q in kept if q.leader_geom is not None]
            crowded = self.pins.get("_crowded", ("crowded", frozenset()))[1]
            strays = [q for q in kept if not self.at_pin(q.text)]   # (a leader at its pin crosses what stands
            astray = [q.box for q in strays]                        # at its pin here as in the finished one)
            goals = {}
            for p in lifted:   # the lifted ones' pinned boxes free of what stays, in the order they were placed
                goal = self._goal(p, pp)
                b, line = goal[0], goal[1]
                # on a line or a leader there too: here as well (off the leaders of labels off their pins)
                hard = (self._hard + leaders if p.text.get_gid() not in crowded else
                        [q.leader_geom for q in strays if q.leader_geom is not None])
                apart = [q.apart for q in kept if q.apart is not None] if p.apart is not None else []
                if not view.contains(b) or any(g.intersects(b) for g in boxes + hard + apart) or (
                        line is not None and any(g.intersects(line) for g in astray)):
                    continue
                if any(b.intersects(g[0]) for g in goals.values()):
                    continue
                goals[id(p)] = goal
            while True:   # one that stays where it is keeps its place: a goal it meets is given up
                stay = [p for p in lifted if id(p) not in goals]
                clash = [k for k, g in goals.items()
                         if any(_meet(g[0], g[1], q.box, q.leader_geom) for q in stay)]
                if not clash:
                    break
                del goals[clash[0]]
            if not goals:
                break
            for p in [p for p in lifted if id(p) in goals]:
                self._to_pin(p, goals[id(p)], pp)
                moved += 1
        return moved

    def crowded(self) -> frozenset:
        """The gids of the placed labels whose boxes meet a hard obstacle or another label's leader (a crowd's
        last-resort places): a step frame puts them at their pins where no label is, whatever line or leader
        (of a label at its pin) runs there (:meth:`settle`)."""
        out = set()
        for p in self.labels:
            hard = np.array(self._hard + [q.leader_geom for q in self.labels
                                          if q is not p and q.leader_geom is not None], dtype=object)
            if p.text.get_gid() and hard.size and shapely.intersects(hard, p.box).any():
                out.add(p.text.get_gid())
        return frozenset(out)

    def _movable(self, p) -> bool:
        """Whether placed label ``p`` has a pin it does not stand at (a place, with its anchor known, or a mark
        on something)."""
        pin = self.pins.get(p.text.get_gid())
        return (pin is not None and pin[0] in ("place", "at", "along") and not (pin[0] == "place" and p.anchor is None)
                and not (pin[0] == "along" and (len(pin) < 3 or p.apart is None)) and not self.at_pin(p.text))

    def _goal(self, p, pp: float) -> tuple:
        """Placed label ``p``'s box at its pin, at the pinned size, with its margin (``(box, leader line or None,
        size)``)."""
        t = p.text
        pin = self.pins[t.get_gid()]
        size = t.get_fontsize()
        if pin[0] == "along":   # on the same line, at another place along it: the same (rotated) box moved there
            (x, y), (u, v) = t.get_position(), pin[2]
            return affinity.translate(p.box, float(u) - x, float(v) - y), None, size
        x0, y0, x1, y1 = p.box.bounds
        w0, h0 = self.text_size(t, 0.0, pp)
        if len(pin) > 3:
            t.set_fontsize(pin[3])
        w, h = self.text_size(t, 0.0, pp)
        t.set_fontsize(size)
        b = _box(np.asarray(pin[1], float), w + (x1 - x0) - w0, h + (y1 - y0) - h0)
        line = None
        if pin[0] == "place" and pin[2] >= 9.0:   # far from its anchor: a leader, as _put draws it
            line = _leader_segment(np.asarray(p.anchor, float), b, pp)
        return b, line, pin[3] if len(pin) > 3 else size

    def _to_pin(self, p, goal, pp: float) -> None:
        """Move placed label ``p`` to its pin (``goal``: :meth:`_goal`'s), its leader drawn anew."""
        t = p.text
        b, line, size = goal
        if p.leader is not None:
            p.leader.remove()
        ln, geom = (None, None) if line is None else self._draw_leader(t, line, t.get_gid(), pp)
        pin = self.pins[t.get_gid()]
        at = _pinned_at(pin)
        t.set_fontsize(size)
        t.set_position((float(at[0]), float(at[1])))
        apart = p.apart
        if apart is not None:   # a text along a line: the em the others keep from it moves with it
            (ox0, oy0, _, _), (nx0, ny0, _, _) = p.box.bounds, b.bounds
            apart = affinity.translate(p.apart, nx0 - ox0, ny0 - oy0)
            self.along[next(i for i, g in enumerate(self.along) if g is p.apart)] = apart
        self.labels[self.labels.index(p)] = replace(p, box=b, leader=ln, leader_geom=geom, apart=apart)
        self.placed[t.get_gid()] = pin

    def _search(self, anchor, w: float, h: float, prefer, gap: float, leader: bool, within, accept,
                clear: bool = False, reach: bool = False, scene=None, crossing: int = LEADER_MOST):
        """The first free candidate, ring after ring, crossing the fewest soft obstacles (None if none is free);
        ``clear``: the far rings too while every free candidate nearer lies on a line (a place there off
        every line, whose leader crosses at most ``crossing`` lines and outlines); ``reach``: the farthest rings too
        while nothing nearer is free. A ring's candidates are tested together (:class:`_Scene`: the same
        answers as testing each box with shapely, in the same order; a second search on the same scene, as
        :meth:`place` makes with ``accept``, finds the rings and their tests made: :meth:`_Scene.ring`)."""
        scene = _Scene(self, anchor, per_point(self.ax)) if scene is None else scene
        rings = (gap,) + tuple(r for r in RINGS if r > gap)
        best = None
        for ring_i, ring in enumerate(rings + FAR_RINGS + (REACH_RINGS if reach and leader else ())):
            far = ring_i >= len(rings)
            # farther out, in finer steps, only when nothing nearer is free (or, ``clear``, free of lines)
            seeking = far and best is not None
            if seeking and not (clear and leader and best[0][0] > 0):
                break
            k = 48 if ring in REACH_RINGS else 24 if far else 16 if ring_i >= 2 else 8
            cands = scene.ring(anchor, w, h, prefer, ring, k, within)
            # the first ring's preferred place alone first (where most labels go), then the rest together
            for part in np.split(np.arange(len(cands)), [1] if ring_i == 0 else []):
                lines = leader and ring >= 9.0
                free, soft, crosses, line_hits = scene.tests(cands, part, lines)
                if not len(free):
                    continue
                for n, i in enumerate(free):
                    b = cands.geom(i)
                    if accept is not None and not accept(b):
                        continue
                    hits = (int(soft[n]), 0)   # lines under the box first, then lines its leader crosses
                    if seeking and hits[0]:
                        continue
                    if lines:
                        if crosses[n]:
                            continue
                        hits = (hits[0], int(line_hits[n]))
                        if seeking and hits[1] > crossing:
                            continue
                    if best is None or hits < best[0]:
                        best = (hits, cands.centres[i].copy(), b, ring)
                    if hits == (0, 0):
                        return best
        return best

    def _least_bad(self, anchor, w: float, h: float, prefer, gap: float, leader: bool, reach: bool = False):
        """Nothing free: the place clear of every label (and of their leaders) whose leader crosses the fewest
        labels, then covering the fewest arrowheads, pins and lines that labels keep off, then whose leader
        crosses the fewest other leaders, then covering the fewest lines (``reach``: out to
        :data:`REACH_RINGS` too, where only such a place covers less or crosses fewer leaders); else the first
        ring's preferred spot. Kept in the anchor's scene (:meth:`_scene`) with its arguments: a crowded label's
        tries at one state ask again."""
        pp = per_point(self.ax)
        scene = self._scene(anchor, pp)
        key = (w, h, prefer, gap, leader, reach, type(w), type(h), type(prefer), type(gap))
        try:
            got = scene.least.get(key)
        except TypeError:
            return self._least_bad_made(scene, anchor, w, h, prefer, gap, leader, reach)
        if got is None:
            got = scene.least[key] = self._least_bad_made(scene, anchor, w, h, prefer, gap, leader, reach)
        return got[0], got[1].copy(), got[2], got[3]

    def _least_bad_made(self, scene: _Scene, anchor, w: float, h: float, prefer, gap: float, leader: bool,
                        reach: bool):
        """:meth:`_least_bad`'s answer, found on ``scene``."""
        pp = scene.pp
        hard, labels, leaders, soft = scene.rows   # marks, pins, lines and leaders; what its leader had best not
        keep_off = scene.crossed                   # cross, then these; what its box must keep off (labels, leaders)
        best = None
        # (the far rings in finer steps too: a leader that crosses a label, the worst, is rarely the only way)
        far = REACH_RINGS if reach and leader else ()
        for ring in sorted({gap, *(r for r in RINGS if r > gap), *FAR_RINGS, 135.0, *far}):
            if ring in far and best is not None and best[0][1:3] == (0, 0):
                break   # farther only while every place nearer covers a mark or a line, or crosses a leader
            cands = scene.ring(anchor, w, h, prefer, ring, 48 if ring in far else 24 if ring in FAR_RINGS else 16,
                               None)
            ok = scene.in_view(cands)
            if keep_off.size:
                ok &= ~keep_off.any(cands.geoms, cands.bounds)
            idx = np.flatnonzero(ok)
            if not len(idx):
                continue
            g, gb = cands.geoms[idx], cands.bounds[idx]
            n = len(idx)
            if leader and ring >= 9.0:
                lines = _leaders(g, anchor)
                lb = shapely.bounds(lines)
                crossed, across = labels.count(lines, lb, True), leaders.count(lines, lb, True)
            else:
                crossed = across = np.zeros(n, int)
            on_hard, on_soft = hard.count(g, gb), soft.count(g, gb)
            for m, i in enumerate(idx):
                score = (int(crossed[m]), int(on_hard[m]), int(across[m]), int(on_soft[m]))
                if best is None or score < best[0]:
                    best = (score, cands.centres[i].copy(), cands.geom(i), ring)
        if best is None:
            first = _Ring(anchor, w, h, prefer, gap * pp, 1)
            best = (math.inf, first.centres[0].copy(), first.geom(0), gap)
        return best

    def _put(self, t, anchor, best, gid, leader: bool, obstacle: bool, again, pp: float | None = None) -> None:
        """Move the text to the place chosen, with its leader where it stands far from its anchor; keep its
        :class:`Placed` (a label that is an obstacle to the later ones; ``pp``: the axes' :func:`per_point`,
        where known)."""
        _, c, b, ring = best
        t.set_position((float(c[0]), float(c[1])))
        if gid:
            self.placed[gid] = ("place", (float(c[0]), float(c[1])), ring, t.get_fontsize())
        ln = geom = None
        if leader and ring >= 9.0:
            pp = per_point(self.ax) if pp is None else pp
            ln, geom = self._draw_leader(t, _leader_segment(anchor, b, pp), gid, pp)
        if obstacle:
            self.labels.append(Placed(t, b, ln, geom, again, np.asarray(anchor, float)))

    def _draw_leader(self, t, line, gid, pp: float):
        """The leader ``line`` (:func:`_leader_segment`) drawn for Text ``t`` in its colour, and its obstacle
        (the line grown by 0.4 pt: later labels keep off it): ``(Line2D, geometry)``."""
        from matplotlib.lines import Line2D
        (x0, y0), (x1, y1) = line.coords
        ln = Line2D([x0, x1], [y0, y1], lw=0.4, color=t.get_color(), zorder=t.get_zorder(),
                    gid=(gid + "-leader") if gid else None)
        self.ax.add_line(ln)
        return ln, line.buffer(0.4 * pp)

    def place_at(self, centres, s: str, *, gid: str | None = None, pad: float = 1.0, avoid=(), soft: bool = False,
                 anchor=None, **text_kw):
        """Draw ``s`` centred on the first of ``centres`` where it is free; None if none is.

        For a mark that belongs *on* something (a number on a chord). ``avoid``:
        further geometries (data coordinates) the box must not meet, for this
        text only (the other chords, for a chord's number); ``soft``: the box must
        meet no soft obstacle either. ``anchor``: what it marks (kept in its :class:`Placed`, see :meth:`add_box`).
        """
        ax = self.ax
        c0 = np.asarray(centres[0], float)
        t = ax.text(c0[0], c0[1], s, ha="center", va="center", **text_kw)
        if gid:
            t.set_gid(gid)
        w, h = self.text_size(t, pad)
        view = view_box(ax)
        pin = self.pins.get(gid) if gid else None
        if pin is not None and pin[0] == "at":
            centres = [pin[1]] + list(centres)
        for c in centres:
            c = np.asarray(c, float)
            b = box(c[0] - w / 2, c[1] - h / 2, c[0] + w / 2, c[1] + h / 2)
            if view.contains(b) and self.free(b, soft=soft) and not any(g.intersects(b) for g in avoid):
                t.set_position((float(c[0]), float(c[1])))
                if gid:
                    self.placed[gid] = ("at", (float(c[0]), float(c[1])))
                self.labels.append(Placed(t, b, anchor=None if anchor is None else np.asarray(anchor, float)))
                return t
        t.remove()
        return None

    def place_along(self, p0, p1, s: str, *, offset: float = 1.5, gid: str | None = None, pad: float = 1.0,
                    **text_kw):
        """Write ``s`` along the segment p0-p1 (rotated to it), where it is free; None if nowhere.

        Tried at fractions of the segment from its far end inwards, on either side. ``pad``: the
        margin (points) kept between the text's ends and other labels or arrowheads, so that the
        words do not run on into a label ("... the path of B on 1 O_v"). Two texts along lines keep
        an em (:data:`ALONG_APART` of the type size) apart, so that two reasons never read as one
        text of two lines (the reasons of two paths along one line, one each side of it).
        """
        ax = self.ax
        p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
        d = p1 - p0
        length = float(np.hypot(*d))
        if length == 0:
            return None
        u = d / length
        ang = math.degrees(math.atan2(u[1], u[0]))
        if ang > 90:
            ang -= 180
        elif ang <= -90:
            ang += 180
        t = ax.text(p0[0], p0[1], s, ha="center", va="center", rotation=ang, rotation_mode="anchor", **text_kw)
        if gid:
            t.set_gid(gid)
        w, h = self.text_size(t)
        if w > 0.92 * length:
            t.remove()
            return None
        pp = per_point(ax)
        grow = max(pad - 1.0, 0.0) * pp
        n = np.array([-u[1], u[0]])
        view = view_box(ax)
        pin = self.pins.get(gid) if gid else None
        tries = [(f, side) for f in (0.78, 0.62, 0.46, 0.3, 0.7, 0.54, 0.38, 0.22) for side in (1, -1)]
        if pin is not None and pin[0] == "along":
            tries.insert(0, pin[1])
        # a step frame: the places the finished construction gives the other texts along lines are theirs
        reserved = [q[3] for g, q in self.pins.items() if g != gid and q[0] == "along" and len(q) > 3]
        for frac, side in tries:
            c = p0 + u * (frac * length) + n * side * (offset * pp + h / 2)
            b = affinity.rotate(box(c[0] - w / 2, c[1] - h / 2, c[0] + w / 2, c[1] + h / 2), ang,
                                origin=(c[0], c[1]))
            # its ends kept ``pad`` from labels and arrowheads (the words must not run on into a label; that box
            # made only where the text's own is free)
            if view.contains(b) and self.free(b, soft=True) and (grow == 0 or self.free(affinity.rotate(
                    box(c[0] - w / 2 - grow, c[1] - h / 2, c[0] + w / 2 + grow, c[1] + h / 2), ang,
                    origin=(c[0], c[1])))) and not any(g.intersects(b) for g in self.along + reserved):
                t.set_position((float(c[0]), float(c[1])))
                self.along.append(b.buffer(ALONG_APART * t.get_fontsize() * pp))
                if gid:
                    self.placed[gid] = ("along", (frac, side), (float(c[0]), float(c[1])), self.along[-1])
                self.labels.append(Placed(t, b, apart=self.along[-1]))
                return t
        t.remove()
        return None

    def untangle(self, texts, accept: dict | None = None) -> int:
        """Swap the places of two of ``texts`` (labels this placer put down with :meth:`place`) whose leaders
        cross, where the swap leaves fewer crossings (leader on leader, leader on label) and puts neither box on
        a label or on more hard obstacles, lines and outlines than it met where it stood, each box in view (the two
        labels in a crossing first, then one in a crossing with any other of ``texts``); repeated while one
        helps, or leaves as many and shortens the two leaders together (so that the next swap may help). Two
        leaders from anchors a, b to boxes A, B that cross do not cross as a-B and b-A (the swap shortens them
        together): a crowd's last-resort places, taken one at a time, end crossed where the same places,
        exchanged, are not. ``accept``: id(text) -> the test its box passed where it could (a
        pole's label nearer its own ring), kept by as many boxes as before. Return the swaps made."""
        mine = {id(t) for t in texts}
        accept = accept or {}
        swaps = 0
        for _ in range(4 * len(mine)):
            crossings = self._crossings()
            ours = [k for k, p in enumerate(self.labels) if id(p.text) in mine and p.anchor is not None]
            crossed = [k for k in ours if any(k in c[:2] for c in crossings)]
            # the two in a crossing first, then one in a crossing with any other
            pairs = sorted({tuple(sorted((i, j))) for i, j, _ in crossings if i in ours and j in ours})
            pairs += [(i, k) for i in crossed for k in ours if k != i and tuple(sorted((i, k))) not in pairs]
            if not any(self._swap(i, j, _tally(crossings), accept) for i, j in pairs):
                break
            swaps += 1
        return swaps

    def relocate(self, text, prefer=None, accept=None, sizes=(), gap: float = 2.5) -> bool:
        """Move the placed label ``text`` (put down with :meth:`place`) to where it covers least, its own box and
        leader lifted and every other label known (:meth:`_least_bad`, out to :data:`REACH_RINGS`), at its size,
        else at each of ``sizes`` in turn (type sizes, points), where that leaves fewer crossings (a leader
        across a label, then across a leader: :func:`_tally`), its box meets no more hard obstacles, other
        labels' leaders, lines and outlines than where it stood and, if its place passed ``accept`` (a pole's
        label nearer its own ring), the new one does too. Whether it moved."""
        own = self.of(text)
        if own is None or own.anchor is None:
            return False
        k, size = self.labels.index(own), text.get_fontsize()
        x0, y0, x1, y1 = own.box.bounds
        w0, h0 = self.text_size(text, 0.0)
        before = _tally(self._crossings())
        for s in (size,) + tuple(x for x in sizes if x < size):
            text.set_fontsize(s)
            w, h = self.text_size(text, 0.0)
            del self.labels[k]
            try:
                b = self._least_bad(own.anchor, w + x1 - x0 - w0, h + y1 - y0 - h0, prefer, gap, True, True)[2]
                covered = [np.array(g, dtype=object) for g in (self.hard, self.prepared_soft())]
            finally:
                self.labels.insert(k, own)
            new = list(self.labels)
            new[k] = self._moved(own, b, self._leader_line(own.anchor, b))
            if _tally(self._crossings(new)) < before and not any(
                    g.size and shapely.intersects(g, b).sum() > shapely.intersects(g, own.box).sum() for g in covered) \
                    and not (accept is not None and accept(own.box) and not accept(b)):
                self._commit(new, (k,))
                return True
        text.set_fontsize(size)
        return False

    def clear_places(self, anchor, w: float, h: float, prefer=None, gap: float = 2.5) -> dict:
        """Every place near ``anchor`` (out to :data:`REACH_RINGS`, in 24 directions, 48 on those) where a w x h box
        stands in view clear of every placed label and leader, and its leader as :meth:`_leader_line` draws it
        (none within 8 pt) crosses no label and no leader: a place that leaves no crossing at all. Returns arrays
        (one row a place, nearest rings first): ``centres``, ``boxes``, ``leaders`` (None: none), ``hard`` (marks,
        pins and lines the box covers), ``soft`` (lines and outlines it covers), ``across`` (lines and outlines
        its leader crosses besides those at the anchor), ``reach`` (the leader's length, 0 without one)."""
        pp, anchor = per_point(self.ax), np.asarray(anchor, float)
        scene = self._scene(anchor, pp)
        keep_off, hard, soft, at_anchor = scene.crossed, scene.own_hard, scene.soft, scene.at_anchor
        got = []
        for ring in sorted({gap, *(r for r in RINGS if r > gap), *FAR_RINGS, *REACH_RINGS}):
            cands = scene.ring(anchor, w, h, prefer, ring, 48 if ring in REACH_RINGS else 24, None)
            ok = scene.in_view(cands)
            if keep_off.size:
                ok &= ~keep_off.any(cands.geoms, cands.bounds)
            idx = np.flatnonzero(ok)
            edges = _towards(cands.geoms[idx], anchor)
            far = np.hypot(*(edges - anchor).T)
            has = ~(far < 8.0 * pp)   # (as a NaN reach had one)
            lines = np.full(len(idx), None, dtype=object)
            lines[has] = _leader_segments(anchor, edges[has], pp)
            if keep_off.size and has.any():   # (None: a missing geometry, which meets nothing)
                crossing = np.zeros(len(idx), bool)
                crossing[has] = keep_off.any(lines[has], lines=True)
                idx, lines, far, has = idx[~crossing], lines[~crossing], far[~crossing], has[~crossing]
            g, gb = cands.geoms[idx], cands.bounds[idx]
            across = np.zeros(len(idx), int)
            if soft.size and has.any():
                across[has] = (soft.meets(lines[has]) & ~at_anchor).sum(axis=1)
            got.append((cands.centres[idx], g, lines, hard.count(g, gb), soft.count(g, gb), across,
                        np.where(has, far, 0.0)))
        keys = ("centres", "boxes", "leaders", "hard", "soft", "across", "reach")
        return {k: np.concatenate([x[n] for x in got]) for n, k in enumerate(keys)}

    def _leader_line(self, anchor, b):
        """The leader from ``anchor`` to box ``b`` as :meth:`_put` draws it (its first 1.5 pt left open), or None
        where the box stands near enough not to need one."""
        pp = per_point(self.ax)
        if b.distance(Point(*anchor)) < 8.0 * pp:
            return None
        return _leader_segment(anchor, b, pp)

    def tally(self) -> tuple[int, int]:
        """The placed labels' crossings as :func:`_tally` counts them: (leaders across a label, leaders across a
        leader); fewer is better, a label struck through first."""
        return _tally(self._crossings())

    def _crossings(self, labels=None) -> list:
        """(i, j) of every leader of label i that crosses the leader or the box of label j (see :func:`_tally`)."""
        labels = self.labels if labels is None else labels
        lines = np.array([_drawn(p.leader) for p in labels], dtype=object)
        has = np.flatnonzero([p.leader is not None for p in labels])   # (the labels with a leader)
        if not has.size:
            return []
        # every leader against every box and every later leader at once (GEOS's predicate, as one at a time), in
        # the order the pairs were listed one at a time: by leader, then by label; a box met before a leader
        n = len(labels)
        on_box = shapely.intersects(lines[has][:, None], np.array([q.box for q in labels], dtype=object)[None, :])
        on_box[np.arange(has.size), has] = False
        later = np.zeros((has.size, n), bool)
        later[:, has] = shapely.intersects(lines[has][:, None], lines[has][None, :]) & (has[None, :] > has[:, None])
        kinds = np.where(on_box, 1, np.where(later, 2, 0))   # (a box met first)
        return [(int(has[a]), int(j), "box" if kinds[a, j] == 1 else "leader") for a, j in np.argwhere(kinds)]

    def _swap(self, i: int, j: int, before: tuple, accept: dict) -> bool:
        """Exchange the places of labels i and j where :meth:`untangle` says it helps; whether it did."""
        a, b = self.labels[i], self.labels[j]
        if a.text.get_fontsize() != b.text.get_fontsize():
            return False   # places, not sizes, are exchanged: a label set smaller keeps its own
        view = view_box(self.ax)
        others = [p.box for k, p in enumerate(self.labels) if k not in (i, j)]
        hard = self._hard + [p.leader_geom for k, p in enumerate(self.labels)
                             if k not in (i, j) and p.leader_geom is not None]

        def moved(p, q):
            (x0, y0, x1, y1), (u0, v0, u1, v1) = p.box.bounds, q.box.bounds
            cx, cy = (u0 + u1) / 2, (v0 + v1) / 2
            return box(cx - (x1 - x0) / 2, cy - (y1 - y0) / 2, cx + (x1 - x0) / 2, cy + (y1 - y0) / 2)
        na, nb = moved(a, b), moved(b, a)
        if na.intersects(nb) or not (view.contains(na) and view.contains(nb)) or \
                any(g.intersects(na) or g.intersects(nb) for g in others):
            return False

        def cost(boxes):
            return (sum(sum(1 for g in hard if g.intersects(x)) for x in boxes),
                    sum(self.soft_hits(x) for x in boxes))
        if any(n > o for new, old in ((na, a.box), (nb, b.box)) for n, o in zip(cost((new,)), cost((old,)))):
            return False   # neither box on more marks or lines than where it stood
        oks = [accept.get(id(p.text), lambda x: True) for p in (a, b)]
        if sum(f(x) for f, x in zip(oks, (na, nb))) < sum(f(x) for f, x in zip(oks, (a.box, b.box))):
            return False
        la, lb = self._leader_line(a.anchor, na), self._leader_line(b.anchor, nb)
        pp = per_point(self.ax)
        new = list(self.labels)
        new[i], new[j] = self._moved(a, na, la), self._moved(b, nb, lb)
        after = _tally(self._crossings(new))
        if after > before or after[0] > before[0] or (after == before and _reach(la, lb) >= _reach(
                *(_drawn(p.leader) for p in (a, b))) - 1e-9 * pp):
            return False
        self._commit(new, (i, j))
        return True

    def _moved(self, p, nbox, line) -> Placed:
        """Placed label ``p`` as it would stand in the box ``nbox`` (its size kept), with the leader ``line``
        (:meth:`_leader_line`; None: none): its new Line2D made, not yet drawn."""
        from matplotlib.lines import Line2D
        ln = None
        if line is not None:
            ln = Line2D(*np.asarray(line.coords).T, lw=0.4, color=p.text.get_color(), zorder=p.text.get_zorder(),
                        gid=(p.text.get_gid() + "-leader") if p.text.get_gid() else None)
        return Placed(p.text, nbox, ln, None if line is None else line.buffer(0.4 * per_point(self.ax)), p.again,
                      p.anchor)

    def _commit(self, new: list, moved) -> None:
        """The labels at the indices ``moved`` put where ``new`` (:meth:`_moved`'s) has them: their old leaders
        taken off, the new drawn, each text centred in its box, and where it went remembered."""
        for k in moved:
            old, p = self.labels[k], new[k]
            if old.leader is not None:
                old.leader.remove()
            if p.leader is not None:
                self.ax.add_line(p.leader)
            x0, y0, x1, y1 = p.box.bounds
            c = ((x0 + x1) / 2, (y0 + y1) / 2)
            p.text.set_position(c)
            gid = p.text.get_gid()
            if gid and gid in self.placed:
                self.placed[gid] = ("place", c, 9.0 if p.leader is not None else 0.0, p.text.get_fontsize())
            self.labels[k] = p

    @property
    def overlapping(self) -> list:
        if not hasattr(self, "_overlapping"):
            self._overlapping = []
        return self._overlapping


class _Ring:
    """The candidate boxes ``reach`` (data units) from the anchor in ``k`` directions (those ``within`` of
    ``prefer``), in :func:`_directions`' order: their centres, bounds and (made when asked) shapely boxes,
    each the very box :func:`_box` makes on the centre ``anchor + u * (reach + half_extent(w, h, u))`` (the
    numbers of the candidates made one at a time before: tests/test_placer_speed.py)."""

    def __init__(self, anchor, w: float, h: float, prefer, reach: float, k: int, within=None):
        u, he = _kept_or_made(_unit_extents_kept, _unit_extents_made, prefer, k, within, w, h)
        self.centres = anchor[None, :] + u * (reach + he)[:, None]
        cx, cy = self.centres[:, 0], self.centres[:, 1]
        self.bounds = np.column_stack([cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2])
        self._geoms = None
        self.tested: dict = {}   # a search's tests of its candidates (:meth:`_Scene.tests`)

    def __len__(self) -> int:
        return len(self.centres)

    @property
    def geoms(self) -> np.ndarray:
        if self._geoms is None:
            x0, y0, x1, y1 = self.bounds.T
            g = shapely.box(x0, y0, x1, y1)
            for i in np.flatnonzero(shapely.is_missing(g)):   # a NaN corner: the box canvas.box makes
                g[i] = box(*self.bounds[i])
            self._geoms = g
        return self._geoms

    def geom(self, i: int):
        return self.geoms[i]


class _Row:
    """Obstacles tested together, a row as shapely's broadcasting takes them (``geoms``), with each one's envelope
    (``bounds``, as shapely gives it). :meth:`meets` answers ``shapely.intersects(geoms, g)`` for every obstacle
    and every geometry ``g`` of a column, asking GEOS only of the pairs whose envelopes meet (touching
    included): GEOS's intersects (plain or prepared) is false where the envelopes are apart (its first test), so
    the answers are the very ones, and a pair whose envelope is not finite (an empty or missing geometry, a NaN
    corner) is asked all the same. The same argument order, the same objects (a prepared copy where one was
    asked): pair for pair the same GEOS call, for a tenth of the pairs in a crowd."""

    def __init__(self, geoms, copies: Callable | None = None):
        self.geoms = np.array(geoms, dtype=object).reshape(-1)
        self.size = len(self.geoms)
        self.bounds = shapely.bounds(self.geoms) if self.size else np.empty((0, 4))
        self.known = bool(np.isfinite(self.bounds).all())
        self._copies = copies   # (LabelPlacer.prepared)
        self._prepared = None

    def meets(self, geoms, bounds: np.ndarray | None = None, lines: bool = False) -> np.ndarray:
        """``(len(geoms), size)``: whether each obstacle meets each of ``geoms`` (``bounds``: their envelopes,
        where known: a ring's); ``shapely.intersects(self.geoms[None, :], geoms[:, None])``. ``lines``: ``geoms``
        are leaders (segments), tested against the obstacles' prepared copies (:meth:`LabelPlacer.prepared`,
        where the row was given them: GEOS's prepared intersects answers as the plain one, and a segment across
        a leader's or a ring's outline of 67 points is found three times faster; a box, a rectangle, is tested
        faster by the plain one)."""
        n = len(geoms)
        out = np.zeros((n, self.size), bool)
        if not n or not self.size:
            return out
        gb = shapely.bounds(geoms) if bounds is None else bounds
        ob = self.bounds
        near = ((ob[:, 0] <= gb[:, 2, None]) & (gb[:, 0, None] <= ob[:, 2])
                & (ob[:, 1] <= gb[:, 3, None]) & (gb[:, 1, None] <= ob[:, 3]))
        if not self.known:
            near |= ~np.isfinite(ob).all(axis=1)
        unknown = ~np.isfinite(gb).all(axis=1)
        if unknown.any():
            near[unknown] = True
        i, j = np.nonzero(near)
        if len(i):
            row = self.geoms
            if lines and self._copies is not None:
                if self._prepared is None:
                    self._prepared = np.array(self._copies(self.geoms), dtype=object).reshape(-1)
                row = self._prepared
            out[i, j] = shapely.intersects(row[j], geoms[i])
        return out

    def count(self, geoms, bounds: np.ndarray | None = None, lines: bool = False) -> np.ndarray:
        """How many of the obstacles each of ``geoms`` meets (:meth:`meets`)."""
        return self.meets(geoms, bounds, lines).sum(axis=1)

    def any(self, geoms, bounds: np.ndarray | None = None, lines: bool = False) -> np.ndarray:
        """Whether each of ``geoms`` meets any of the obstacles (:meth:`meets`)."""
        return self.meets(geoms, bounds, lines).any(axis=1)


class _Scene:
    """What one label's search tests its candidates against, gathered once: nothing is placed while it
    searches (the placed labels and hard obstacles, the soft ones, the leaders, the lines through the
    anchor, the view, the axes' scale). A ring's candidates are tested in one shapely call per test (every
    candidate against every obstacle whose envelope meets its own, :class:`_Row`: the very predicate
    :meth:`LabelPlacer.free` and the others ask of each pair, without a Python call per candidate).

    ``state``: the geometries it was gathered from (:meth:`LabelPlacer._state`); a placer keeps its last scenes
    and gives one again to a search from the same anchor while every one of these is the very object it was
    (:meth:`LabelPlacer._scene`: the same rings, their tests and the last resort's answers, for the tries a
    crowded label makes at one state, each undone by :meth:`LabelPlacer.trial`)."""

    def __init__(self, pl: LabelPlacer, anchor, pp: float, state: tuple | None = None):
        self.pp = pp
        self.anchor = np.asarray(anchor, float)
        self.view = view_box(pl.ax)
        self.view_bounds = np.array(self.view.bounds, float)
        self.state = pl._state() if state is None else state
        boxes, hard, leaders, _ = self.state
        self.taken = _Row(boxes + hard + leaders)   # what a label's box must not meet (pl.boxes + pl.hard)
        self.soft = _Row(pl.prepared_soft())        # (prepared copies: the same answers)
        self.crossed = _Row(boxes + leaders, pl.prepared)   # what a leader must not cross
        self._copies = pl.prepared
        # the lines and outlines at the anchor itself: a leader leaving it does not count them
        self.at_anchor = (self.soft.meets(np.array([Point(*anchor).buffer(2.0 * self.pp)], dtype=object))[0]
                          if self.soft.size else None)
        self._rings: dict = {}   # (ring, its size and directions) -> _Ring (see ring())
        self.least: dict = {}    # (the last resort's arguments) -> its answer (LabelPlacer._least_bad)

    @functools.cached_property
    def rows(self) -> tuple:
        """The last resort's rows (:meth:`LabelPlacer._least_bad`): hard obstacles and leaders, labels' boxes, leaders,
        soft obstacles (plain)."""
        boxes, hard, leaders, soft = self.state
        return _Row(hard + leaders), _Row(boxes, self._copies), _Row(leaders, self._copies), _Row(soft)

    @functools.cached_property
    def own_hard(self) -> _Row:
        """The hard obstacles registered (no leader)."""
        return _Row(self.state[1])

    def ring(self, anchor, w: float, h: float, prefer, ring: float, k: int, within) -> _Ring:
        """The candidates ``ring`` points out from ``anchor`` (``_Ring(anchor, w, h, prefer, ring * pp, k,
        within)``), made once per scene with their tests (:meth:`tests`): nothing is placed while a scene
        lives, so a second search of the same label (:meth:`LabelPlacer.place` with ``accept``) walks the
        same rings to the same answers. Kept by the exact values and their types (a numpy float's arithmetic is
        its own); an unhashable argument: made anew."""
        anchor = np.asarray(anchor, float)
        key = (anchor.tobytes(), w, h, prefer, ring, k, within, type(w), type(h), type(prefer), type(ring),
               type(within))
        try:
            got = self._rings.get(key)
        except TypeError:
            return _Ring(anchor, w, h, prefer, ring * self.pp, k, within)
        if got is None:
            got = self._rings[key] = _Ring(anchor, w, h, prefer, ring * self.pp, k, within)
        return got

    def tests(self, cands: _Ring, part: np.ndarray, lines: bool) -> tuple:
        """For the candidates ``part`` of a ring: the free ones (:meth:`free`), the soft obstacles each of those
        meets (:meth:`soft_hits`) and, with ``lines``, their leaders' tests (:meth:`leader_tests`; else None,
        None), kept on the ring for a second search (:meth:`ring`)."""
        key = (tuple(part.tolist()), lines)
        got = cands.tested.get(key)
        if got is None:
            free = self.free(cands, part)
            soft = self.soft_hits(cands, free) if len(free) else None
            crosses, line_hits = self.leader_tests(cands, free) if lines and len(free) else (None, None)
            got = cands.tested[key] = (free, soft, crosses, line_hits)
        return got

    def in_view(self, cands: _Ring) -> np.ndarray:
        """Which candidates the view contains (``view.contains(b)``): a box of some width and height in a box is
        contained exactly where its bounds lie within the view's, edges included; shapely is asked where either
        is not such a box (no width, or not finite)."""
        v, bd = self.view_bounds, cands.bounds
        proper = _proper(bd)
        if _proper(v[None, :])[0]:
            inside = proper & (v[0] <= bd[:, 0]) & (bd[:, 2] <= v[2]) & (v[1] <= bd[:, 1]) & (bd[:, 3] <= v[3])
        else:
            inside, proper = np.zeros(len(bd), bool), np.zeros(len(bd), bool)
        if not proper.all():
            inside[~proper] = shapely.contains(self.view, cands.geoms[~proper])
        return inside

    def free(self, cands: _Ring, idx: np.ndarray) -> np.ndarray:
        """The indices of the candidates (of ``idx``) in view that meet no placed label and no hard obstacle
        (:meth:`LabelPlacer.free`), in order."""
        idx = idx[self.in_view(cands)[idx]]
        if len(idx) and self.taken.size:
            idx = idx[~self.taken.any(cands.geoms[idx], cands.bounds[idx])]
        return idx

    def soft_hits(self, cands: _Ring, idx) -> np.ndarray:
        """How many soft obstacles each of the candidates ``idx`` meets (:meth:`LabelPlacer.soft_hits`)."""
        if not self.soft.size:
            return np.zeros(len(idx), int)
        return self.soft.count(cands.geoms[idx], cands.bounds[idx])

    def leader_tests(self, cands: _Ring, idx) -> tuple[np.ndarray, np.ndarray]:
        """For the candidates ``idx``, the leader from the anchor to the nearest point of each box's outline
        (:func:`_toward`): whether it crosses a label or leader, and how many lines and outlines it crosses
        besides those at its anchor."""
        lines = _leaders(cands.geoms[idx], self.anchor)
        bounds = shapely.bounds(lines)
        crosses = self.crossed.any(lines, bounds, True) if self.crossed.size else np.zeros(len(idx), bool)
        if not self.soft.size:
            return crosses, np.zeros(len(idx), int)
        return crosses, (self.soft.meets(lines, bounds) & ~self.at_anchor[None, :]).sum(axis=1)


def _unit_rows(prefer, k: int, within):
    """The unit vectors of :func:`_directions` within ``within`` of ``prefer`` (read only), as the candidates
    were made one at a time: kept per (prefer, k, within) and their types (a numpy float's arithmetic is its
    own), else (unhashable) made anew."""
    return _kept_or_made(_unit_rows_kept, _unit_rows_made, prefer, k, within)


def _kept_or_made(kept, made, *args):
    """``kept(*args)`` (``made`` kept by an lru_cache), or ``made(*args)`` where an argument is unhashable."""
    try:
        return kept(*args)
    except TypeError:
        return made(*args)


def _unit_rows_made(prefer, k: int, within):
    rows = []
    for ang in _directions(prefer, k):
        if within is not None and abs((ang - (prefer or 45.0) + 180.0) % 360.0 - 180.0) > within + 1e-9:
            continue
        rows.append((math.cos(math.radians(ang)), math.sin(math.radians(ang))))
    u = np.array(rows, float).reshape(-1, 2)
    u.setflags(write=False)
    return u


_unit_rows_kept = functools.lru_cache(maxsize=4096, typed=True)(_unit_rows_made)


def _units(prefer, k: int, within, w: float, h: float):
    """The directions' unit vectors and :func:`half_extent`'s two distances along each (which exist)."""
    u = _unit_rows(prefer, k, within)
    ux, uy = np.abs(u[:, 0]), np.abs(u[:, 1])
    has_a, has_b = ux > 1e-12, uy > 1e-12
    with np.errstate(divide="ignore", invalid="ignore"):
        return u, (w / 2) / ux, (h / 2) / uy, has_a, has_b


def _unit_extents_made(prefer, k: int, within, w: float, h: float):
    """The directions' unit vectors (:func:`_unit_rows`) and :func:`half_extent` of a w x h box along each (read
    only): the same for every ring of one size and number of directions (:class:`_Ring` keeps them per the
    arguments and their types, :data:`_unit_extents_kept`)."""
    u, a, b, has_a, has_b = _units(prefer, k, within, w, h)
    # half_extent(w, h, u), as min() of its list picks: the second where it is smaller
    with np.errstate(divide="ignore", invalid="ignore"):
        he = np.where(has_a & has_b, np.where(b < a, b, a), np.where(has_a, a, b))
    he.setflags(write=False)
    return u, he


_unit_extents_kept = functools.lru_cache(maxsize=4096, typed=True)(_unit_extents_made)


def _proper(bounds: np.ndarray) -> np.ndarray:
    """Which rows of bounds (x0, y0, x1, y1) are a box's of some width and height, finite."""
    return np.isfinite(bounds).all(axis=1) & (bounds[:, 0] < bounds[:, 2]) & (bounds[:, 1] < bounds[:, 3])


def _leaders(boxes: np.ndarray, anchor) -> np.ndarray:
    """The leaders (shapely segments) from ``anchor`` to the nearest point of each box's outline, as
    ``LineString([tuple(anchor), tuple(_toward(b, anchor))])`` makes each."""
    anchor = np.asarray(anchor, float)
    ends = _towards(boxes, anchor)
    return shapely.linestrings(np.stack([np.broadcast_to(anchor, ends.shape), ends], axis=1))


def _towards(boxes: np.ndarray, p) -> np.ndarray:
    """:func:`_toward` of each box (one shapely call for them all): (n, 2)."""
    if not len(boxes):
        return np.empty((0, 2))
    lines = shapely.shortest_line(shapely.get_exterior_ring(boxes), shapely.points(float(p[0]), float(p[1])))
    return shapely.get_coordinates(lines).reshape(len(boxes), 2, 2)[:, 0, :]


def _tally(crossings) -> tuple[int, int]:
    """(leaders across a label, leaders across a leader) of :meth:`LabelPlacer._crossings`: a label struck
    through is the worse."""
    return (sum(1 for c in crossings if c[2] == "box"), sum(1 for c in crossings if c[2] == "leader"))


def _leader_segment(anchor, b, pp: float) -> LineString:
    """A leader from ``anchor`` to the nearest point of box ``b``'s outline, its first 1.5 pt left open."""
    edge = _toward(b, anchor)
    start = anchor + (edge - anchor) * (1.5 * pp / max(np.hypot(*(edge - anchor)), 1e-300))
    return LineString([tuple(start), tuple(edge)])


def _leader_segments(anchor, edges: np.ndarray, pp: float) -> np.ndarray:
    """:func:`_leader_segment` of each box, given the nearest points of their outlines (``edges``: :func:`_towards`;
    the same arithmetic, element by element, in one shapely call)."""
    d = edges - anchor
    start = anchor + d * ((1.5 * pp) / np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-300))[:, None]
    return shapely.linestrings(np.stack([start, edges], axis=1)) if len(edges) else np.empty(0, dtype=object)


def _pinned_at(pin) -> tuple:
    """Where a pin (:attr:`LabelPlacer.pins`) puts its text's position: a place's or a mark's point, a text along
    a line's centre there."""
    return pin[2] if pin[0] == "along" else pin[1]


def _meet(box_a, line_a, box_b, line_b) -> bool:
    """Whether two labels meet: box on box, or a leader (line or buffered geometry, None: none) on the other's box."""
    return (box_a.intersects(box_b) or (line_a is not None and line_a.intersects(box_b))
            or (line_b is not None and line_b.intersects(box_a)))


def _drawn(leader):
    """A leader's Line2D as a shapely segment (None: None)."""
    return None if leader is None else LineString(np.column_stack(leader.get_data()))


def _reach(*lines) -> float:
    """The leaders' length together (None: no leader)."""
    return sum(ln.length for ln in lines if ln is not None)


def _box(c, w: float, h: float):
    """The w x h box centred on c."""
    return box(c[0] - w / 2, c[1] - h / 2, c[0] + w / 2, c[1] + h / 2)


def _directions(prefer: float | None, k: int) -> list[float]:
    base = 45.0 if prefer is None else float(prefer)
    step = 360.0 / k
    out = [base]
    for i in range(1, k // 2 + 1):
        out.append(base + i * step)
        if i < k // 2:
            out.append(base - i * step)
    return out


def half_extent(w: float, h: float, u) -> float:
    """Distance from a w x h box's centre to its edge along unit u."""
    ux, uy = abs(u[0]), abs(u[1])
    cands = []
    if ux > 1e-12:
        cands.append((w / 2) / ux)
    if uy > 1e-12:
        cands.append((h / 2) / uy)
    return min(cands)


def _toward(b, p):
    """The point of box b's outline nearest to p."""
    from shapely.geometry import Point
    from shapely.ops import nearest_points
    q = nearest_points(b.exterior, Point(p))[0]
    return np.array([q.x, q.y])


def meets_any(obstacles, geoms) -> np.ndarray:
    """``shapely.intersects(obstacles[None, :], geoms[:, None]).any(axis=1)``: whether each of ``geoms`` meets any of
    ``obstacles``, GEOS asked only of the pairs whose envelopes meet (:class:`_Row`: the very answers)."""
    return _Row(obstacles).any(np.asarray(geoms, dtype=object).reshape(-1))


def all_farther(points, xy: np.ndarray, boxes, bounds: np.ndarray, limit: float) -> np.ndarray:
    """``(shapely.distance(points[None, :], boxes[:, None]) > limit).all(axis=1)``: whether every point (shapely
    ``points``, their coordinates ``xy``) lies farther than ``limit`` from each box (``boxes``, axis-parallel
    rectangles, their corners ``bounds``: ``(n, 4)``), GEOS asked only of the pairs that may be within ``limit``.

    A point's distance from a rectangle (its inside included) is ``|(dx, dy)|``, dx and dy how far the point lies
    outside the rectangle's x and y ranges; GEOS computes the same from the rectangle's edges, to within a few
    units in the last place of the coordinates. A pair that is by this measure farther than ``limit`` by more than
    a billionth of the coordinates' size is farther by GEOS's too; every other pair (and any that is not finite)
    is asked of GEOS: the answers are GEOS's, pair for pair."""
    n, m = len(bounds), len(xy)
    if not n or not m:
        return np.ones(n, bool)
    px, py = xy[:, 0][None, :], xy[:, 1][None, :]
    dx = np.maximum(np.maximum(bounds[:, 0, None] - px, px - bounds[:, 2, None]), 0.0)
    dy = np.maximum(np.maximum(bounds[:, 1, None] - py, py - bounds[:, 3, None]), 0.0)
    with np.errstate(invalid="ignore"):   # (a NaN corner: its pairs are asked of GEOS)
        size = max(float(np.nanmax(np.abs(bounds), initial=0.0)), float(np.nanmax(np.abs(xy), initial=0.0)),
                   abs(limit))
        far = np.hypot(dx, dy) > limit + 1e-9 * size
    i, j = np.nonzero(~far)
    if len(i):
        far[i, j] = shapely.distance(points[j], boxes[i]) > limit
    return far.all(axis=1)


def placer(ax) -> LabelPlacer:
    """The axes' :class:`LabelPlacer` (created on first use), shared by every drawing on it."""
    p = getattr(ax, "_velpoly_placer", None)
    if p is None:
        p = LabelPlacer(ax)
        ax._velpoly_placer = p
    return p


def segment(p0, p1) -> LineString:
    """A shapely segment (for soft obstacles)."""
    return LineString([tuple(map(float, p0)), tuple(map(float, p1))])
