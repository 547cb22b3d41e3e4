"""Boundary labelling: labels in a column along a free side of the panel (issue 17 item 4, "leaders never crossing").

Where a crowd's labels, placed one at a time, leave leaders crossing, books set the crowd's labels in a column
beside the figure (or a row above or below it), each with a straight leader to its point, ordered as their points
are so that no two leaders cross. Two straight leaders a -> A and b -> B that cross are longer together than
a -> B and b -> A (the triangle inequality on the two triangles their crossing cuts), so the matching of
points to places of least total leader length has no two leaders crossing: here the free places of a column at
each side (or of all of them) are matched to the points as that least total (the Hungarian method), then any two
leaders that still cross (their ends are the boxes' nearest points) exchange places (each exchange shortens them
together, so it ends).

Every place of a column is free: its box meets no label, leader, mark, pin, line or outline and lies in the
view; its leader pays a large price for each label and leader it would cross (:data:`ACROSS_COST`).
"""
from __future__ import annotations

import itertools

import numpy as np
import shapely
from shapely.geometry import box

from .canvas import per_cm, per_point, view_box

__all__ = ["in_column", "SIDES", "INWARD_STEPS"]

SIDES = ("right", "left", "top", "bottom")   # a column at the right or left edge, a row at the top or bottom
INWARD_STEPS = 8   # how many 0.5-cm steps in from the panel's edge a column may stand (else that side is not free)
SLOT_GAP = 1.0     # points between two boxes of a column (besides each box's own margin)
STEPS_MOST = 200   # the most single steps that better a column's dealing (_improved)
ACROSS_COST = 1e6  # a leader's price for each label or leader it crosses, in data units of length


def in_column(pl, movers: list, accept: dict, sizes: dict) -> tuple | None:
    """The best columns for the placed labels ``movers`` (:class:`~velpoly.render.labels.Placed`, each with its
    anchor), or None: ``(tally, moved)``, ``moved`` a list of ``(placed, box, leader)`` for :meth:`_moved`.

    Each side of the view (:data:`SIDES`) gives its column nearest its edge whose free places
    (:func:`_slots`) are at least one (stepped in from the edge, :data:`INWARD_STEPS`), the labels at ``sizes``
    (id of a Text -> the type size it is set at there). The labels are dealt the places of each side alone and of
    all sides together as the matching of least total price (:func:`_costs`, :func:`_astray`,
    :func:`_least_matching`), then bettered step by step where labels of the column clash (:func:`_improved`);
    each dealing is scored by the crossings it
    leaves (:meth:`~velpoly.render.labels.LabelPlacer.tally` over every label), then by the labels that pass ``accept``
    (id of a Text -> a test of its box, a pole's label nearer its own ring) fewer, then by its leaders' total
    length; the best kept."""
    ids = {id(p) for p in movers}
    rest = [p for p in pl.labels if id(p) not in ids]
    blocks = _obstacles(pl, rest)
    pp = per_point(pl.ax)
    sides = [got for side in SIDES if (got := _slots(pl, movers, side, blocks, sizes)) is not None]
    together = [[b for got in sides for b in got[i]] for i in range(len(movers))] if sides else []
    best = None
    for boxes in [*sides, together]:
        if not boxes or len(boxes[0]) < len(movers):   # (no side with a free place: none together)
            continue
        lines = [[pl._leader_line(p.anchor, b) for b in row] for p, row in zip(movers, boxes)]
        cost = _costs(lines, rest, pp) + _astray(movers, boxes, accept)
        at = _improved(lines, boxes, cost, _least_matching(cost))
        got = [(p, boxes[i][at[i]], lines[i][at[i]]) for i, p in enumerate(movers)]
        new = list(pl.labels)
        for p, b, line in got:
            new[pl.labels.index(p)] = pl._moved(p, b, line)
        saved, pl.labels = pl.labels, new
        try:
            tally = pl.tally()
        finally:
            pl.labels = saved
        near = -sum(accept.get(id(p.text), lambda b: True)(b) for p, b, _ in got)
        score = (tally, near, sum(0.0 if line is None else line.length for _, _, line in got))
        if best is None or score < best[0]:
            best = (score, got)
    return None if best is None else (best[0][0], best[1])


def _obstacles(pl, rest: list):
    """What a column's box must not meet: the labels staying and their leaders, every hard and soft obstacle
    (marks, pins, Kennedy lines, lines and outlines), as an STRtree."""
    geoms = [p.box for p in rest] + [p.leader_geom for p in rest if p.leader_geom is not None]
    geoms += list(pl._hard) + list(pl.soft)
    return shapely.STRtree([g for g in geoms if g is not None and not g.is_empty])


def _slots(pl, movers: list, side: str, blocks, sizes: dict) -> list | None:
    """The free places of ``movers`` in the column at ``side`` nearest the view's edge that has one (stepped in
    by half centimetres, :data:`INWARD_STEPS`): for each label, its box at each place (its width and height at
    ``sizes``, aligned on the column's line: a column's boxes flush towards the drawing, a row's centred),
    the places those whose widest and tallest box meets nothing in ``blocks``; None where no column has one."""
    pp = per_point(pl.ax)
    x0, y0, x1, y1 = view_box(pl.ax).bounds
    dims = [_size(pl, p, sizes) for p in movers]
    wmax, hmax = max(d[0] for d in dims), max(d[1] for d in dims)
    upright = side in ("right", "left")
    pitch = (hmax if upright else wmax) + SLOT_GAP * pp
    for step in range(INWARD_STEPS):
        inset = 2.0 * pp + step * 0.5 * per_cm(pl.ax)
        lo, hi = (y0, y1) if upright else (x0, x1)
        along = np.arange(lo + inset + pitch / 2, hi - inset - pitch / 2 + 1e-12, pitch)
        across = {"right": x1 - inset - wmax, "left": x0 + inset + wmax, "top": y1 - inset - hmax,
                  "bottom": y0 + inset + hmax}[side]
        free = along[_free_slots([_place(side, across, c, wmax, hmax) for c in along], blocks)]
        if len(free):
            return [[_place(side, across, c, w, h) for c in free] for w, h in dims]
    return None


def _place(side: str, across: float, c: float, w: float, h: float):
    """A w x h box in the column at ``side`` whose line is ``across`` (x of a column, y of a row), at ``c`` along
    it: flush with the line on the drawing's side of a column, centred along a row and flush with its line."""
    if side == "right":
        return box(across, c - h / 2, across + w, c + h / 2)
    if side == "left":
        return box(across - w, c - h / 2, across, c + h / 2)
    if side == "top":
        return box(c - w / 2, across, c + w / 2, across + h)
    return box(c - w / 2, across - h, c + w / 2, across)


def _size(pl, p, sizes: dict) -> tuple[float, float]:
    """The width and height of the placed label ``p``'s box (its margin kept) at the type size ``sizes`` gives
    its Text (else the size it has)."""
    t = p.text
    x0, y0, x1, y1 = p.box.bounds
    w0, h0 = pl.text_size(t, 0.0)
    size = t.get_fontsize()
    t.set_fontsize(sizes.get(id(t), size))
    try:
        w, h = pl.text_size(t, 0.0)
    finally:
        t.set_fontsize(size)
    return w + (x1 - x0 - w0), h + (y1 - y0 - h0)


def _astray(movers: list, boxes: list, accept: dict) -> np.ndarray:
    """Each label's (row) price at each place (column) for leaving the test it passed where it stood (``accept``:
    id of a Text -> a test of its box, a pole's label nearer its own ring): :data:`ACROSS_COST`."""
    out = np.zeros((len(movers), len(boxes[0]) if boxes else 0))
    for i, (p, row) in enumerate(zip(movers, boxes)):
        test = accept.get(id(p.text))
        if test is not None and test(p.box):
            out[i] = [ACROSS_COST * (not test(b)) for b in row]
    return out


def _free_slots(boxes: list, blocks) -> np.ndarray:
    """Which of ``boxes`` meet nothing in ``blocks`` (an STRtree)."""
    hit = np.zeros(len(boxes), bool)
    if len(blocks):
        hit[np.unique(blocks.query(np.array(boxes, dtype=object), predicate="intersects")[0])] = True
    return ~hit


def _costs(lines: list, rest: list, pp: float) -> np.ndarray:
    """Each label's (row) price at each place (column): its leader's length, plus :data:`ACROSS_COST` for each
    staying label's box and leader it crosses (no leader: its box's nearness, nothing to cross)."""
    others = [p.box for p in rest] + [shapely.LineString(np.column_stack(p.leader.get_data()))
                                      for p in rest if p.leader is not None]
    tree = shapely.STRtree(others) if others else None
    flat = np.array([ln for row in lines for ln in row], dtype=object)
    has = np.array([ln is not None for ln in flat])
    cost = np.zeros(len(flat))
    cost[has] = shapely.length(flat[has].astype(object))
    if tree is not None and has.any():
        a, _ = tree.query(flat[has], predicate="intersects")
        cost[np.flatnonzero(has)] += ACROSS_COST * np.bincount(a, minlength=int(has.sum()))
    return cost.reshape(len(lines), -1)


def _least_matching(cost: np.ndarray) -> np.ndarray:
    """The place (column of ``cost``, n x m, n <= m) of each label (row) in the matching of least total cost: the
    Hungarian method with potentials (u_i + v_j <= cost_ij, equal on the matching; each row added by a shortest
    augmenting path), O(n^2 m)."""
    n, m = cost.shape
    u, v = np.zeros(n + 1), np.zeros(m + 1)
    row_of = np.zeros(m + 1, int)   # the row (1-based; 0: none) at each column (1-based; 0: the root)
    for i in range(1, n + 1):
        row_of[0], j0 = i, 0
        least, way, done = np.full(m + 1, np.inf), np.zeros(m + 1, int), np.zeros(m + 1, bool)
        while row_of[j0]:
            done[j0] = True
            i0 = row_of[j0]
            cur = cost[i0 - 1] - u[i0] - v[1:]
            better = ~done[1:] & (cur < least[1:])
            least[1:][better] = cur[better]
            way[1:][better] = j0
            free = np.flatnonzero(~done[1:]) + 1
            j1 = int(free[np.argmin(least[free])])
            delta = least[j1]
            u[row_of[done]] += delta
            v[done] -= delta
            least[~done] -= delta
            j0 = j1
        while j0:
            j1 = way[j0]
            row_of[j0] = row_of[j1]
            j0 = j1
    at = np.empty(n, int)
    for j in range(1, m + 1):
        if row_of[j]:
            at[row_of[j] - 1] = j - 1
    return at


def _improved(lines: list, boxes: list, cost: np.ndarray, at: np.ndarray) -> np.ndarray:
    """The places ``at`` (label -> place) bettered by single steps while one lowers the total price, each pair of
    labels that meet (:func:`_meet`) paying :data:`ACROSS_COST`: a label moved to a place no other has, or two
    labels exchanging places (two leaders that cross are shorter exchanged, so the crossings among the column's
    own leaders go first); at most :data:`STEPS_MOST` steps."""
    at = at.copy()
    n, m = cost.shape

    def clashes(i: int, s: int, skip: int = -1) -> int:
        return sum(_meet(lines[i][s], boxes[i][s], lines[k][at[k]], boxes[k][at[k]]) for k in range(n)
                   if k != i and k != skip)
    for _ in range(STEPS_MOST):
        used = set(at.tolist())
        now = [cost[i, at[i]] + ACROSS_COST * clashes(i, at[i]) for i in range(n)]
        step = None
        for i in range(n):
            for s in range(m):
                if s not in used and cost[i, s] < now[i] and cost[i, s] + ACROSS_COST * clashes(i, s) < now[i] - 1e-9:
                    step = (i, s)
                    break
            if step:
                break
        if step is None:
            for i, j in itertools.combinations(range(n), 2):
                a, b = at[i], at[j]
                old = now[i] + now[j] - ACROSS_COST * _meet(lines[i][a], boxes[i][a], lines[j][b], boxes[j][b])
                at[i], at[j] = b, a
                new = (cost[i, b] + cost[j, a] + ACROSS_COST * (clashes(i, b, j) + clashes(j, a, i)
                                                                 + _meet(lines[i][b], boxes[i][b], lines[j][a], boxes[j][a])))
                at[i], at[j] = a, b
                if new < old - 1e-9:
                    step = (i, j, True)
                    break
        if step is None:
            return at
        if len(step) == 2:
            at[step[0]] = step[1]
        else:
            at[step[0]], at[step[1]] = at[step[1]], at[step[0]]
    return at


def _meet(line_a, box_a, line_b, box_b) -> bool:
    """Whether two labels of a column clash: their boxes overlap, or a leader (None: none) crosses the other's leader
    or box."""
    return bool(box_a.intersects(box_b) or (line_a is not None and (line_a.intersects(box_b) or (
        line_b is not None and line_a.intersects(line_b)))) or (line_b is not None and line_b.intersects(box_a)))
