"""Instant centres: every pole on the mechanism, the Kennedy lines used, the Kennedy circle.

Drawn from :mod:`velpoly.poles`' objects (a :class:`~velpoly.poles.PoleSet`
and its :func:`~velpoly.poles.kennedy_circle`). On the mechanism, each pole
P_ij is marked and labelled; a pole at infinity (a relative translation) is
an arrow at the border of the view pointing its way, labelled ``P_ij ∞``, and
a finite pole outside the view is an arrow at the border on its Kennedy line,
pointing along it towards the pole, labelled with its position. The Kennedy
lines that located each pole (P_ik P_jk and P_il P_jl, or a constraint line: a
sliding contact's common normal, a slot's normal at its pin) are drawn thin
through their poles (a constraint line through its defining points) and on past
the pole found, over every body: a wheel's rim or a plate's outline never cuts
them. On the Kennedy circle the links are
points on a circle (the first at the top, the others clockwise), poles known
by inspection are solid chords, and poles found are dashed chords numbered
in the order of their discovery.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from shapely.geometry import LineString, Point

from .canvas import (Artists, arrow, border_point, fit_view, get_ax, math_literal, per_cm, per_point, view_box,
                     view_scale)
from .columns import in_column
from .displacement import SMALLER, draw_mechanism, mechanism_bounds, shape_patch
from .labels import Moment, placer, segment
from .options import drawing_options
from .style import get_style

__all__ = ["draw_poles", "draw_kennedy_circle", "pole_label", "shown_poles", "REACH", "KENNEDY_Z"]

NUMBER_SPOTS = (0.3, 0.7, 0.5, 0.4, 0.6, 0.22, 0.78, 0.35, 0.65, 0.45, 0.55)  # along a chord, tried in turn
# then, where none of those is clear of the other chords (a crowd of seven links), every 2 % of the chord from
# its middle out to an eighth of it from either end (the chords meet at the links' points)
FINE_SPOTS = tuple(sorted((round(0.12 + 0.02 * i, 2) for i in range(39)), key=lambda f: (abs(f - 0.5), f)))
KENNEDY_Z = 3.6   # Kennedy and constraint lines: above every body (links 2, ground 2.9, blocks 3.2), below points 4
REACH = 2.5   # the view holds the finite poles within REACH mechanism sizes of the mechanism
THIRD_MOST, THIRD_TRIES = 4, 8   # a crossing's third label lifted: the nearest so many, each with so many places
PAIR_MOST = 80   # of each label's places that leave no crossing, the best so many are paired (_clear_pair)
FAR_BAND = 0.15   # mechanism sizes beyond the box's corners: a crowded view's room towards a pole out of it
COLUMN_TRIES = 12   # the most columns tried on one drawing (_in_columns)
APART_BY = 1e-6   # of a distance (and of a ring's size): a ring whose envelope lies farther is farther (_nearer_own)


def pole_label(links: tuple[str, str]) -> str:
    """``$P_{13}$``, or ``$P_{2,10}$`` when a link's name is longer than one character."""
    i, j = links
    sub = f"{i}{j}" if len(i) == 1 and len(j) == 1 else f"{i},{j}"
    return "$P_{" + math_literal(sub) + "}$"


def shown_poles(ps, upto: int | None = None) -> list:
    """The poles known after ``upto`` discoveries (all if None): inspection first, then in order."""
    poles = list(ps.poles.values())
    if upto is None:
        return poles
    return [p for p in poles if p.order <= upto]


def _poleset(sol, poleset):
    if poleset is not None:
        return poleset
    from ..poles import locate_poles
    return locate_poles(sol)


def _centre(sol) -> np.ndarray:
    x0, y0, x1, y1 = mechanism_bounds(sol)
    return np.array([(x0 + x1) / 2, (y0 + y1) / 2])


def poles_bounds(sol, ps, reach: float | None = None) -> tuple[float, float, float, float]:
    """The mechanism's box grown to hold every finite pole within ``reach`` mechanism sizes of its centre
    (None: :data:`REACH`). A crowded poles sheet's view holds fewer (``velpoly.render.sheet.CROWD_REACHES``, less
    than :data:`REACH`) and is grown towards each farther pole to :data:`FAR_BAND` sizes beyond the box's
    corners (where its arrow at the border stands clear of the links)."""
    x0, y0, x1, y1 = mechanism_bounds(sol)
    c = _centre(sol)
    size = sol.mechanism.size
    reach = REACH if reach is None else reach
    band = math.hypot(x1 - x0, y1 - y0) / 2 + FAR_BAND * size if reach < REACH else 0.0
    for p in ps.poles.values():
        if p.position is None:
            continue
        d = float(np.hypot(*(p.position - c)))
        q = p.position if d <= reach * size else c + (p.position - c) * min(band / d, 1.0)
        x0, y0 = min(x0, q[0]), min(y0, q[1])
        x1, y1 = max(x1, q[0]), max(y1, q[1])
    return x0, y0, x1, y1


def far_pole_arrow(view, pole, lines, centre, inset: float) -> tuple[np.ndarray, np.ndarray]:
    """Where the arrow to a finite pole out of view stands: ``(tip, unit direction towards the pole)``.

    On the pole's Kennedy line (``lines``: each as drawn, clipped to the view) where it leaves the view
    towards the pole, ``inset`` back inside, so that a reader follows the arrow along the line to the
    pole; of several lines, the one that leaves the view nearest the pole. Without a line leaving the
    view (a pole known by inspection), on the line from ``centre`` towards the pole, at the view's border.
    """
    pole = np.asarray(pole, float)
    best = None
    for xy in lines:
        a, b = np.asarray(xy[0], float), np.asarray(xy[-1], float)
        end, other = (a, b) if np.hypot(*(a - pole)) <= np.hypot(*(b - pole)) else (b, a)
        u = end - other
        if float(np.hypot(*u)) <= inset:
            continue
        u = u / float(np.hypot(*u))
        dist = float(np.hypot(*(pole - end)))
        if best is None or dist < best[0]:
            best = (dist, end - u * inset, u)
    if best is not None:
        return best[1], best[2]
    d = (pole - centre) / max(float(np.hypot(*(pole - centre))), 1e-300)
    return border_point(view, centre, d, inset), d


def draw_poles(sol, ax=None, *, style="textbook", options=None, poleset=None, upto: int | None = None,
               mechanism: bool = True, reach: float | None = None) -> Artists:
    """Draw the mechanism with every instant centre and the Kennedy lines used; return the Artists.

    Parameters
    ----------
    poleset : PoleSet, optional
        From :func:`velpoly.poles.locate_poles` (located if None).
    upto : int, optional
        Show only the poles known by inspection and the first ``upto`` found
        (the ``--steps`` frames); the last one's lines are drawn heavier.
    mechanism : bool
        Draw the displacement diagram first (default); False to draw the
        poles over a mechanism already drawn on ``ax``.
    reach : float, optional
        A crowded sheet's view: the poles within so many mechanism sizes
        (:func:`poles_bounds`), the labels of those out of it placed first.

    Returns
    -------
    Artists
        The mechanism's roles and ``poles`` (markers), ``far`` (arrows to
        poles at infinity or out of view), ``kennedy_lines``; ``.labels``
        maps each pole's key ("1-3") to its label (with the points' labels).
        Every pole's label is nearer its own ring than any other ring where a
        free place allows, and no leader crosses another.

    The labels are placed one at a time, each taking the best place the ones
    before it left (a crowd's last come last). Where a pole label's leader
    still crosses another leader or label after every untangling step, the
    labels are placed again with the poles labelled in the reverse order, then
    the most crowded first (:func:`_crowded_first`); each kept over the best
    before it where it has fewer such crossings and no more labels nearer
    another ring, on a line or struck through (:func:`_tangle`), and one with
    none ends the search. A step frame's labels stand at their pins: drawn once.
    """
    ax = get_ax(ax)
    st = get_style(style)
    opts = options if options is not None else drawing_options(sol.mechanism)
    ps = _poleset(sol, poleset)
    if view_scale(ax) is None:
        fit_view(ax, poles_bounds(sol, ps, reach), scale=opts.scale, margin=0.1)
        ax.set_axis_off()
    return _least_tangled(sol, ax, st, opts, ps, upto, mechanism, reach)


def _least_tangled(sol, ax, st, opts, ps, upto, mechanism: bool, reach) -> Artists:
    """:func:`draw_poles`' drawing, its labels placed in the listed order, else (a pole label's leader crossing,
    :func:`_crossed`) in the first of the other orders that leaves none, else the least tangled (:func:`_tangle`).

    What the labels' order does not change is drawn once: the mechanism, the Kennedy lines, the poles' marks. For
    each other order the drawing comes back to where it stood before the poles' labels (:class:`_Drawn`; what the
    mechanism's labels moved for them put back) with the things drawn pole by pole (the Kennedy lines, the marks
    and the obstacles they are) in that order, as a drawing made anew in that order has them (:func:`_in_order`),
    and only the labels are placed again; the order kept is put back as it was placed."""
    pl = placer(ax)
    shown = shown_poles(ps, upto)
    again = mechanism and not (pl.pins or pl.labels or pl.hard or pl.soft)   # (a step frame's: pinned labels)
    art, pole_lines, own = _poles_drawn(sol, ax, st, opts, ps, shown, upto, mechanism)
    base = _Drawn.of(art) if again else None
    _poles_labelled(sol, ax, ps, shown, pole_lines, st, art, reach)
    if not again or not _crossed(art):
        return art
    orders = [shown, shown[::-1], _crowded_first(shown, per_cm(ax))]
    best, k = (_tangle(art), 0, _Drawn.of(art)), 0
    for k in range(1, len(orders)):
        base.in_order(own, orders[k]).restore(art)
        _poles_labelled(sol, ax, ps, orders[k], pole_lines, st, art, reach)
        tangle = _tangle(art)
        if tangle[0] < best[0][0] and all(a <= b for a, b in zip(tangle[1:], best[0][1:])):
            best = (tangle, k, _Drawn.of(art))
        if best[0][0] == 0:
            break
    if best[1] != k:   # the last placed is not the one kept: the kept one's put back
        best[2].restore(art)
    if best[0][0]:
        _in_columns(pl, art, st.font_size * 0.9)
    return art


def _in_columns(pl, art, size: float) -> bool:
    """Where pole labels' leaders still cross after every order (:func:`_least_tangled`), pole labels in a
    crossing set in columns along the free sides of the panel, at the pole labels' ``size``
    (:func:`~velpoly.render.columns.in_column`: boundary labelling, dealt so that their leaders cross none of each
    other): all of them, or each alone; where the column of all crosses another pole label's leader or box,
    that label joins it and it is tried again (at most :data:`COLUMN_TRIES` columns in all). Of the columns
    that leave fewer crossings (:meth:`LabelPlacer.tally`), no more leaders across a label and as many pole
    labels nearer their own rings (each box in a column meets no label, leader, mark, line or outline), the one
    leaving fewest, then moving fewest labels, then of the shortest leaders is kept; whether one was."""
    poles = {id(t) for t in art.labels.values()}
    rings = list(art.rings.values())
    accept = {id(art.labels[k]): _nearer_own(g, rings) for k, g in art.rings.items() if k in art.labels}
    before = pl.tally()
    first = _in_crossings(pl, pl.labels, poles)
    groups = [first] + ([[p] for p in first] if len(first) > 1 else [])
    best, seen = None, set()
    while groups and len(seen) < COLUMN_TRIES:
        movers = groups.pop(0)
        if frozenset(map(id, movers)) in seen:
            continue
        seen.add(frozenset(map(id, movers)))
        got = in_column(pl, movers, accept, {id(p.text): size for p in movers})
        if got is None:
            continue
        tally, moved = got
        near = [accept.get(id(p.text), lambda b: True) for p, _, _ in moved]
        if tally < before and tally[0] <= before[0] and \
                sum(f(b) for f, (_, b, _) in zip(near, moved)) >= sum(f(p.box) for f, (p, _, _) in zip(near, moved)):
            score = (tally, len(moved), sum(0.0 if line is None else line.length for _, _, line in moved))
            best = min(best, (score, moved), key=lambda x: x[0]) if best else (score, moved)
        elif len(movers) >= len(first):
            new = list(pl.labels)
            for p, b, line in moved:
                new[pl.labels.index(p)] = pl._moved(p, b, line)
            more = [pl.labels[new.index(q)] for q in _in_crossings(pl, new, poles)]
            groups.append(list({id(p): p for p in movers + more}.values()))
    if best is None:
        return False
    new, ks = list(pl.labels), []
    for p, b, line in best[1]:
        p.text.set_fontsize(size)
        ks.append(pl.labels.index(p))
        new[ks[-1]] = pl._moved(p, b, line)
    pl._commit(new, ks)
    return True


def _in_crossings(pl, labels: list, poles: set) -> list:
    """The placed pole labels (``poles``: ids of their Texts) of ``labels`` (a placer's list) in a crossing (a
    leader across a leader or a box), with an anchor."""
    ks = sorted({k for c in pl._crossings(labels) for k in c[:2]})
    return [labels[k] for k in ks if id(labels[k].text) in poles and labels[k].anchor is not None]


def _crowded_first(shown: list, near: float) -> list:
    """The poles ``shown``, those with the most other poles within ``near`` first (else as listed)."""
    at = [p.position for p in shown if p.position is not None]

    def crowd(p) -> int:
        return 0 if p.position is None else sum(float(np.hypot(*(q - p.position))) < near for q in at)
    return sorted(shown, key=lambda p: -crowd(p))


def _poles_drawn(sol, ax, st, opts, ps, shown, upto, mechanism: bool) -> tuple:
    """:func:`draw_poles`' drawing but the poles' labels (its view fitted), the poles taken in the order ``shown``.
    Returns its Artists, each pole's Kennedy lines as drawn (key -> [xy, ...]) and what each pole added to the axes
    and the placer, in runs of a kind (:func:`_in_order`): id -> (the thing, its kind, its pole's key)."""
    art = Artists(ax)
    art.labels = {}
    pl = placer(ax)
    current = max((p.order for p in shown), default=0) if upto is not None else None
    # the Kennedy lines, known before the mechanism's labels are placed so that these keep clear of them
    klines, pole_lines = _kennedy_lines(ps, shown, current, view_box(ax), per_cm(ax))
    own = {}
    for xy, _, _, key in klines:   # no label on one (hard); a leader crosses as few as it can (soft)
        for hard in (True, False):
            g = segment(xy[0], xy[-1])
            pl.add_obstacle(g, hard=hard)
            own[id(g)] = (g, 0, key)
    if mechanism:
        # the poles' marks first, so that the mechanism's labels keep clear of them
        for p in shown:
            if p.position is not None and view_box(ax).contains(Point(*p.position)):
                g = Point(*p.position).buffer(0.085 * per_cm(ax))
                pl.add_obstacle(g)
                own[id(g)] = (g, 1, p.key)
        mech = draw_mechanism(sol, ax, style=st, options=opts)
        art.update_from(mech)
        art.labels = {}
        art.point_labels = mech.labels
    _draw_kennedy_lines(ax, klines, st, art)
    drawn = art.get("kennedy_lines", [])
    own.update((id(a), (a, 0, key)) for a, (_, _, _, key) in zip(drawn[len(drawn) - len(klines):], klines))
    _draw_pole_marks(sol, ax, shown, st, art)
    marks = art.get("poles", [])
    own.update((id(a), (a, 2, marks[n - n % 2].get_gid()[len("pole-"):])) for n, a in enumerate(marks))
    own.update((id(g), (g, 3, key)) for key, g in art.rings.items())
    return art, pole_lines, own


def _poles_labelled(sol, ax, ps, shown, pole_lines, st, art, reach) -> None:
    """The poles ``shown`` labelled in that order on their drawing (:func:`_poles_drawn`'s ``art``), then their
    leaders taken apart (:func:`_apart`)."""
    _apart(placer(ax), art, _label_poles(sol, ax, ps, shown, pole_lines, st, art, reach))


def _in_order(seq: list, own: dict, rank: dict) -> list:
    """``seq`` (a poles drawing's artists, a role's or obstacles) as the drawing made with its poles in the order
    ``rank`` (pole key -> its place) has it: each run of things the poles added (``own``: id -> (the thing, its kind,
    its pole's key); a drawing adds each kind pole by pole, a kind after another) sorted by kind, then by pole; a
    pole's own things of a kind in the order it added them."""
    out, run = [], []
    end = object()
    for a in [*seq, end]:
        got = own.get(id(a))
        if got is not None and got[0] is a:
            run.append(got)
            continue
        out += [g[0] for g in sorted(run, key=lambda g: (g[1], rank[g[2]]))]
        run = []
        if a is not end:
            out.append(a)
    return out


@dataclass(frozen=True)
class _Drawn:
    """A poles drawing as it stood: its placer and axes (:class:`~velpoly.render.labels.Moment`), its Artists'
    ``roles``, pole ``labels`` and ``rings``."""

    moment: Moment
    roles: dict
    labels: dict
    rings: dict

    @classmethod
    def of(cls, art) -> _Drawn:
        return cls(placer(art.ax).moment(), {k: list(v) for k, v in art.items()}, dict(art.labels), dict(art.rings))

    def restore(self, art) -> None:
        """``art``'s drawing as it stood (its placer, axes and Artists)."""
        placer(art.ax).back_to(self.moment)
        art.clear()
        art.update({k: list(v) for k, v in self.roles.items()})
        art.labels, art.rings = dict(self.labels), dict(self.rings)

    def in_order(self, own: dict, order: list) -> _Drawn:
        """This drawing as made with the poles taken in ``order`` (:func:`_in_order`; ``own``: :func:`_poles_drawn`'s)."""
        rank = {p.key: n for n, p in enumerate(order)}
        m = self.moment
        lists = {f: _in_order(getattr(m, f), own, rank) for f in ("artists", "hard", "soft")}
        return _Drawn(replace(m, **lists), {k: _in_order(v, own, rank) for k, v in self.roles.items()}, self.labels,
                      {k: self.rings[k] for k in sorted(self.rings, key=rank.__getitem__)})


def _crossed(art) -> int:
    """How many crossings a pole label's leader makes in a poles drawing (``art``: its Artists): across another
    leader or another label's box."""
    pl = placer(art.ax)
    poles = {id(t) for t in art.labels.values()}
    return sum(1 for i, j, _ in pl._crossings() if id(pl.labels[i].text) in poles or id(pl.labels[j].text) in poles)


def _tangle(art) -> tuple:
    """How tangled a poles drawing's labels are, each count fewer the better: (:func:`_crossed`; pole labels
    nearer another ring than their own; pole labels on a drawn line; leaders across a label)."""
    pl = placer(art.ax)
    rings = list(art.rings.values())
    nearer = sum(not _nearer_own(g, rings)(pl.of(art.labels[k]).box) for k, g in art.rings.items()
                 if k in art.labels and len(rings) > 1)
    lines = _drawn_lines(art.ax)
    return _crossed(art), nearer, sum(_on_lines(pl, t, lines) for t in art.labels.values()), pl.tally()[0]


def _apart(pl, art, how: dict) -> None:
    """The leaders a crowd's last-resort places leave crossing taken apart, in turn: two pole labels' places
    swapped (:func:`_untangle`), one label moved to where it covers least (:func:`_uncross`), the two labels of a
    crossing placed again together (:func:`_afresh`); then the driver's values a pole label's leader crosses
    placed again (:func:`_off_the_leaders`). ``how``: :func:`_label_poles`'."""
    _untangle(pl, art)
    _uncross(pl, art, how)
    _afresh(pl, art, how)
    _off_the_leaders(pl, art)
    _clear_of_all(pl, art, how)


def _clear_of_all(pl, art, how: dict) -> None:
    """Leaders that still cross after every step above (issue 17: one cannot tell which ring is which): the labels
    of each crossing of a pole label's leader (the pole's, and the other: a pole's, a driver's value, a point's
    label or a link number) moved to places that leave no crossing at all: one of them alone, else the two
    together (:func:`_clear_pair`), else the two with a third label lifted too (:func:`_clear_with_third`); every
    other label stays where it stands. A label so moved covers no more marks, pins and lines than where it
    stood, stays nearer its own ring if it was (and always where it has no leader) and off the lines drawn if
    it was, and the leaders moved cross no more lines and outlines together than before; a pole's label at its
    size or smaller (:data:`SMALLER`), any other at its size. Of such places, the one covering least, at the
    largest size, whose leader crosses the fewest lines and is shortest. Each crossing is tried once. A step
    frame's labels stand where the finished construction's do: left as placed."""
    if pl.pins:
        return
    poles = {id(t): k for k, t in art.labels.items()}
    tried = set()
    while True:
        pairs = [(pl.labels[i], pl.labels[j]) for i, j, _ in pl._crossings()]
        pairs = [two for two in pairs if any(id(p.text) in poles for p in two)
                 and frozenset(id(p.text) for p in two) not in tried]
        if not pairs:
            return
        tried.add(frozenset(id(p.text) for p in pairs[0]))
        movers = [(p, _spec(p, how, poles)) for p in pairs[0] if p.anchor is not None]
        alone = [(_clear_places(pl, p, spec), p) for p, spec in movers]
        alone = [(c[0], c, p) for c, p in alone if c is not None]
        if alone:
            _, c, p = min(alone, key=lambda x: x[0])
            _clear_commit(pl, [(p, c)])
        elif not (len(movers) == 2 and _clear_pair(pl, movers)):
            _clear_with_third(pl, how, movers, poles)


def _limits(pl, p, accept, lines) -> tuple:
    """What a placed label ``p`` may not get worse at when moved (:func:`_clear_options`): the hard obstacles and
    the soft ones its box meets, whether it is nearer its own ring (``accept``) and off the ``lines`` drawn, the
    lines and outlines its leader crosses (:func:`_across`)."""
    return (_hard_hits(pl, p), pl.soft_hits(p.box), accept is not None and accept(p.box),
            not _on_lines(pl, p.text, lines), _across(pl, p))


def _across(pl, p) -> int:
    """How many lines and outlines (soft obstacles) the placed label ``p``'s leader crosses besides those at its
    anchor, as :meth:`~velpoly.render.labels.LabelPlacer.clear_places` counts them (0 without a leader)."""
    import shapely
    if p.leader is None or not pl.soft:
        return 0
    soft = np.array(pl.prepared_soft(), dtype=object)
    at = shapely.intersects(soft, Point(*p.anchor).buffer(2.0 * per_point(pl.ax)))
    return int((shapely.intersects(soft, LineString(np.column_stack(p.leader.get_data()))) & ~at).sum())


def _spec(p, how: dict, poles: dict) -> dict:
    """How the placed label ``p`` may be placed anew (:func:`_clear_options`): a pole's label (``poles``: id of its
    Text -> its pole's key; ``how``: :func:`_label_poles`') as it was placed, at its size or smaller; any other
    (a driver's value, a point's label) at the size it has."""
    if id(p.text) in poles:
        kw = how[poles[id(p.text)]][2]
        return dict(fontsize=kw["fontsize"], prefer=kw["prefer"], accept=kw.get("accept"), sizes=(1.0,) + SMALLER)
    return dict(fontsize=p.text.get_fontsize(), prefer=None, accept=None, sizes=(1.0,))


def _clear_options(pl, p, spec: dict, lifted: list, limits=None, spare: int = 0) -> list:
    """The places that leave no crossing (:meth:`~velpoly.render.labels.LabelPlacer.clear_places`) for the pole
    label ``p`` (placed as ``spec`` says, :func:`_spec`), the labels ``lifted`` (``p`` among them) taken off while they are sought,
    that :func:`_clear_of_all` allows (``limits``: :func:`_limits`' of ``p`` where it stood; ``spare``: lines its
    leader may cross beyond its old one's, which others of a group cross fewer), best first: ``[(score, size, box,
    leader or None)]``, the score (marks,
    pins and lines the box covers; lines and outlines it covers; the size's rank; lines the leader crosses; its
    length)."""
    import shapely
    kw = spec
    accept, lines = kw.get("accept"), np.array(_drawn_lines(pl.ax), dtype=object)[None, :]
    pp, t = per_point(pl.ax), p.text
    old_hard, old_soft, keep_near, keep_off, old_across = (_limits(pl, p, accept, list(lines[0])) if limits is None
                                                           else limits)
    taken = sorted(((pl.labels.index(q), q) for q in lifted), key=lambda x: x[0])
    size, out = t.get_fontsize(), []
    for k, _ in reversed(taken):
        del pl.labels[k]
    try:
        for rank, f in enumerate(kw["sizes"]):
            t.set_fontsize(kw["fontsize"] * f)
            got = pl.clear_places(p.anchor, *pl.text_size(t), kw["prefer"])
            ok = (got["hard"] <= old_hard) & (got["soft"] <= old_soft) & (got["across"] <= old_across + spare)
            if keep_off and lines.size and ok.any():   # (its box as placed: the margin off)
                inner = shapely.buffer(got["boxes"][ok], -pp, join_style="mitre")
                ok[ok] = ~shapely.intersects(lines, inner[:, None]).any(axis=1)
            for n in np.flatnonzero(ok):
                b = got["boxes"][n]
                if (keep_near or got["leaders"][n] is None) and accept is not None and not accept(b):
                    continue   # (a label with no leader is read as the nearest ring's)
                score = (int(got["hard"][n]), int(got["soft"][n]), rank, int(got["across"][n]), float(got["reach"][n]))
                out.append((score, t.get_fontsize(), b, got["leaders"][n]))
    finally:
        t.set_fontsize(size)
        for k, q in taken:
            pl.labels.insert(k, q)
    return sorted(out, key=lambda x: x[0])


def _clear_places(pl, p, spec: dict):
    """The best place :func:`_clear_options` finds for the label ``p`` alone, or None."""
    got = _clear_options(pl, p, spec, [p])
    return got[0] if got else None


def _clear_pair(pl, movers: list) -> bool:
    """The two labels ``movers`` (each with its :func:`_spec`) of a crossing, where neither alone has a place
    that leaves no crossing, placed together: the best two places of :func:`_combos`, both lifted, their
    leaders across no more lines and outlines together than before; whether they moved."""
    lifted = [p for p, _ in movers]
    combos = _combos(pl, movers, lifted, sum(_across(pl, p) for p in lifted))
    if combos:
        _clear_commit(pl, list(zip(lifted, combos[0])))
    return bool(combos)


def _combos(pl, movers: list, lifted: list, budget: int) -> list:
    """The places of ``movers`` (one label, or the two of a crossing, each with its :func:`_spec`), ``lifted``
    taken off, that leave no crossing among them and whose leaders cross at most ``budget`` lines and outlines
    together, best first (at most :data:`THIRD_TRIES`; of two, the best :data:`PAIR_MOST` places of each paired,
    their scores summed): ``[[option, ...]]`` (:func:`_clear_options`' each)."""
    import shapely
    opts = [_clear_options(pl, p, spec, lifted, spare=budget - _across(pl, p))[:PAIR_MOST] for p, spec in movers]
    if not all(opts):
        return []
    if len(opts) == 1:
        return [[o] for o in opts[0][:THIRD_TRIES]]
    pp = per_point(pl.ax)
    boxes = [np.array([o[2] for o in x], dtype=object) for x in opts]
    lines = [np.array([None if o[3] is None else o[3].buffer(0.4 * pp) for o in x], dtype=object) for x in opts]
    meet = shapely.intersects(boxes[0][:, None], boxes[1][None, :])
    meet |= shapely.intersects(lines[0][:, None], boxes[1][None, :]) | shapely.intersects(boxes[0][:, None], lines[1][None, :])
    meet |= shapely.intersects(lines[0][:, None], lines[1][None, :])
    pairs = sorted((tuple(a + b for a, b in zip(opts[0][i][0], opts[1][j][0])), int(i), int(j))
                   for i, j in np.argwhere(~meet) if opts[0][i][0][3] + opts[1][j][0][3] <= budget)
    return [[opts[0][i], opts[1][j]] for _, i, j in pairs[:THIRD_TRIES]]


def _clear_with_third(pl, how: dict, movers: list, poles: dict) -> bool:
    """The labels ``movers`` of a crossing with no place that leaves none, while a third label stands where it
    does (a crowd: its box or leader takes their free places): with a third lifted too (the labels nearest the
    movers' anchors first, at most :data:`THIRD_MOST`), the movers placed as
    :func:`_combos` finds (best first) and the third where :func:`_clear_options` then finds it a place, the
    three leaders across no more lines and outlines together than before; of such threes, the one whose scores
    summed are least (:func:`_clear_options`) kept. Whether they moved."""
    ones = {id(p) for p, _ in movers}
    at = [np.asarray(p.anchor, float) for p, _ in movers]
    thirds = sorted((q for q in pl.labels if id(q) not in ones and q.anchor is not None),
                    key=lambda q: min(q.box.distance(Point(*a)) for a in at))[:THIRD_MOST]
    best, n = None, 0
    for q in thirds:
        spec = _spec(q, how, poles)
        limits = _limits(pl, q, spec["accept"], _drawn_lines(pl.ax))
        budget = sum(_across(pl, p) for p, _ in movers) + limits[4]
        for combo in _combos(pl, movers, [p for p, _ in movers] + [q], budget):
            saved = list(pl.labels)
            sizes = [p.text.get_fontsize() for p, _ in movers]
            for (p, _), o in zip(movers, combo):
                p.text.set_fontsize(o[1])
                pl.labels[pl.labels.index(p)] = pl._moved(p, o[2], o[3])
            got = _clear_options(pl, q, spec, [q], limits, budget - sum(o[0][3] for o in combo) - limits[4])
            pl.labels[:] = saved
            for (p, _), size in zip(movers, sizes):
                p.text.set_fontsize(size)
            if got:
                group = [(p, o) for (p, _), o in zip(movers, combo)] + [(q, got[0])]
                score = tuple(sum(x) for x in zip(*(o[0] for _, o in group)))
                best = min(best, (score, n, group), key=lambda x: x[:2]) if best else (score, n, group)
                n += 1
    if best:
        _clear_commit(pl, best[2])
    return best is not None


def _clear_commit(pl, moves: list) -> None:
    """Each placed label of ``moves`` put at its place (:func:`_clear_options`' ``(score, size, box, leader)``)."""
    new, ks = list(pl.labels), []
    for p, (_, size, b, line) in moves:
        p.text.set_fontsize(size)
        k = pl.labels.index(p)
        new[k] = pl._moved(p, b, line)
        ks.append(k)
    pl._commit(new, ks)


def _untangle(pl, art) -> None:
    """Leaders that cross (a crowd's last-resort places, taken one at a time) untangled: two pole labels' places
    exchanged where that leaves fewer crossings (:meth:`LabelPlacer.untangle`)."""
    rings = list(art.rings.values())
    texts = list(art.labels.values())
    accept = {id(art.labels[k]): _nearer_own(g, rings) for k, g in art.rings.items() if k in art.labels}
    pl.untangle(texts, accept)


def _uncross(pl, art, how: dict) -> None:
    """The labels whose leaders still cross another label's leader or box (a crowd's last-resort places, each
    taken before the later ones were known) moved, one at a time, to where they cover least now that every
    other label is known (:meth:`LabelPlacer.relocate`: a pole's at its size, else smaller), where that leaves
    fewer crossings. Pole labels first, of those the one that had a free place first (another place may lie
    clear of the later leader), then a point's or a link number's with a leader; each tried at most twice.
    ``how``: each pole's key -> (anchor, text, its placing's arguments) (:func:`_label_poles`). A step frame's
    labels stand where the finished construction's do: left as placed."""
    if pl.pins:
        return
    keys = {id(t): k for k, t in art.labels.items()}
    tries: dict = {}
    while True:
        crowded = {id(t) for t in pl.overlapping}
        crossed = [pl.labels[k] for i, j, _ in pl._crossings() for k in (j, i)]
        crossed = sorted(dict.fromkeys(p.text for p in crossed if p.anchor is not None and tries.get(id(p.text), 0) < 2),
                         key=lambda t: (id(t) not in keys, id(t) in crowded))
        if not crossed:
            return
        t = crossed[0]
        tries[id(t)] = tries.get(id(t), 0) + 1
        kw = how[keys[id(t)]][2] if id(t) in keys else {"prefer": None}
        sizes = tuple(kw["fontsize"] * f for f in SMALLER) if id(t) in keys else ()
        pl.relocate(t, kw["prefer"], kw.get("accept"), sizes)


def _afresh(pl, art, how: dict) -> None:
    """Leaders that still cross (issue 17: one cannot tell which ring is which) where the labels in the crossing
    (a pole's, and the other if it is a pole's or a driver's value, :attr:`~velpoly.render.labels.Placed.again`)
    lifted together and placed again as at first, in either order (the one placed second keeps off the first's
    new leader), leave fewer crossings (:func:`_place_again`). Untangling by swaps (:func:`_untangle`) and by
    moving one label to where it covers least (:func:`_uncross`) keeps a pair whose swapped leaders strike
    through another label, or a label with no free place while its neighbour in the crossing stands; lifting
    both frees one. Each pair is tried once. A step frame's labels stand where the finished construction's do:
    left as placed."""
    if pl.pins:
        return
    tried = set()
    for _ in range(2 * len(art.labels)):
        poles = {id(t): k for k, t in art.labels.items()}
        pairs = {}
        for i, j, _ in pl._crossings():
            two = [p for p in (pl.labels[i], pl.labels[j]) if id(p.text) in poles or p.again is not None]
            gids = tuple(p.text.get_gid() for p in two)
            if any(id(p.text) in poles for p in two) and gids not in tried:
                pairs.setdefault(gids, two)
        if not pairs:
            return
        gids, two = next(iter(pairs.items()))
        tried.add(gids)
        _place_again(pl, art, [(p, poles.get(id(p.text))) for p in two], how)


def _place_again(pl, art, olds: list, how: dict) -> bool:
    """The placed labels ``olds`` (each with its pole's key, or None for a driver's value) lifted and placed again
    as at first (a pole's by :func:`_place_free` with ``how``'s arguments, a value by its ``again``), in either
    order, kept where :func:`_better`; whether they moved."""
    before = (pl.tally(), [_hard_hits(pl, p) for p, _ in olds])
    idx = [pl.labels.index(p) for p, _ in olds]
    for k in sorted(idx, reverse=True):
        del pl.labels[k]
    kept = False
    try:
        for order in (olds, olds[::-1])[:len(olds)]:
            with pl.trial():
                new = {id(p): (_place_free(pl, *how[k][:2], **how[k][2]) if k is not None else p.again())
                       for p, k in order}
                pl.keep = _better(pl, art, olds, [new[id(p)] for p, _ in olds], before)
            kept = all(pl.of(t) is not None for t in new.values())
            if kept:
                break
    finally:
        if not kept:   # the lifted ones back where they stood
            for k, p in sorted(zip(idx, (p for p, _ in olds)), key=lambda x: x[0]):
                pl.labels.insert(k, p)
    for p, k in olds if kept else ():
        _replace_text(pl, art, p, k, new[id(p)])
    return kept


def _better(pl, art, olds: list, new: list, before: tuple) -> bool:
    """Whether the labels ``olds`` (:func:`_place_again`'s, lifted) placed anew as ``new`` (their Texts) leave
    fewer crossings than ``before[0]`` (:meth:`~velpoly.render.labels.LabelPlacer.tally`) with no label on more hard
    obstacles (Kennedy lines, marks, leaders) than ``before[1]`` (each where it stood), as many pole labels
    nearer their own rings than any other as before, and none on a drawn line where it was on none."""
    if pl.tally() >= before[0]:
        return False
    lines, rings = _drawn_lines(pl.ax), list(art.rings.values())
    placed = [pl.of(t) for t in new]
    if any(_hard_hits(pl, p) > hits for p, hits in zip(placed, before[1])) or any(
            _on_lines(pl, p.text, lines) and not _on_lines(pl, old.text, lines) for (old, _), p in zip(olds, placed)):
        return False
    tests = [_nearer_own(art.rings[k], rings) if k in art.rings else (lambda b: True) for _, k in olds]
    return sum(f(p.box) for f, p in zip(tests, placed)) >= sum(f(old.box) for f, (old, _) in zip(tests, olds))


def _replace_text(pl, art, old, key, new) -> None:
    """The label ``old`` (a :class:`~velpoly.render.labels.Placed`, lifted; ``key``: its pole's, or None) taken
    off the axes with its leader, ``new`` (its Text placed anew) standing for it in ``art``."""
    if old.leader is not None:
        old.leader.remove()
    old.text.remove()
    pl.overlapping[:] = [t for t in pl.overlapping if t is not old.text]
    if key is not None:
        art.labels[key] = new
    for role in art.values():
        role[:] = [new if a is old.text else a for a in role]


def _off_the_leaders(pl, art) -> None:
    """The driver's values that a pole label's leader crosses (they are placed before the poles' labels, and a
    crowded pole's label may have had no other place) placed again, now clear of the leaders; one whose own
    leader crosses a pole label's placed again where a free place leaves fewer crossings (:func:`_again_free`)."""
    poles = {id(t) for t in art.labels.values()}
    lines = [LineString(np.column_stack(p.leader.get_data())) for p in pl.labels
             if id(p.text) in poles and p.leader is not None]
    for p in [p for p in pl.labels if p.again is not None]:
        t = p.text
        box = pl.box_of(t, pad=0.0)
        if any(line.intersects(box) for line in lines):
            pl.remove(t)   # with its own leader, which is drawn again with it
            new = p.again()
        elif p.leader is not None and any(line.intersects(LineString(np.column_stack(p.leader.get_data())))
                                          for line in lines):
            new = _again_free(pl, p)
        else:
            continue
        for role in art.values():
            role[:] = [new if a is t else a for a in role]


def _again_free(pl, p):
    """The placed label ``p`` (a driver's value, :attr:`~velpoly.render.labels.Placed.again`) placed again, its
    own box and leader lifted, where that finds a free place (no last resort) and leaves fewer crossings
    (:meth:`~velpoly.render.labels.LabelPlacer.tally`): the new Text, else ``p``'s, left where it stood."""
    before = pl.tally()
    k = pl.labels.index(p)
    del pl.labels[k]
    with pl.trial():
        n = len(pl.overlapping)
        new = p.again()
        pl.keep = len(pl.overlapping) == n and pl.tally() < before
    if pl.of(new) is None:
        pl.labels.insert(k, p)
        return p.text
    if p.leader is not None:
        p.leader.remove()
    p.text.remove()
    return new


def _kennedy_lines(ps, shown, current, vb, pc):
    """The Kennedy lines of the poles found: ``([(xy, heavy, gid, pole key)], {pole key: [xy, ...]})``, each clipped to
    the view ``vb``: through the poles that define it (a constraint line: through its points: the contact
    point, the pin, a circular slot's centre), and on past the pole found (a pole at infinity: across)."""
    klines, pole_lines = [], {}
    for p in shown:
        if p.order == 0:
            continue
        heavy = current is not None and p.order == current
        for ln in p.construction:
            if ln.point is None or ln.direction is None:
                continue
            base = np.asarray(ln.point, float)
            d = np.asarray(ln.direction, float)
            d = d / max(float(np.hypot(*d)), 1e-300)
            ts = [0.0]
            for q in [ps.poles[k].position if k in ps.poles else None for k in ln.through] + \
                    list(ln.marks):
                if q is not None:
                    ts.append(float(np.dot(np.asarray(q, float) - base, d)))
            if p.position is not None:
                ts.append(float(np.dot(p.position - base, d)))
            far = 4 * max(vb.bounds[2] - vb.bounds[0], vb.bounds[3] - vb.bounds[1])
            lo, hi = (min(ts) - 0.8 * pc, max(ts) + 0.8 * pc) if p.position is not None else (-far, far)
            seg = LineString([tuple(base + d * lo), tuple(base + d * hi)]).intersection(vb)
            if seg.is_empty or seg.geom_type != "LineString":
                continue
            klines.append((np.asarray(seg.coords), heavy, f"kennedy-line-{p.key}-{ln.label}", p.key))
            if p.position is not None:
                pole_lines.setdefault(p.key, []).append(np.asarray(seg.coords))
    return klines, pole_lines


def _draw_kennedy_lines(ax, klines, st, art) -> None:
    """Over the links, blocks and ground (a Kennedy line runs straight through every body: the collinearity
    is the proof), under the pins, points and poles' marks; the current step's heavier."""
    from matplotlib.lines import Line2D
    for xy, heavy, gid, _ in klines:
        line = Line2D(xy[:, 0], xy[:, 1], lw=st.thin_lw * (2.0 if heavy else 1.0),
                      color=st.ink if not st.coloured else "#7f7f7f", linestyle=(0, (7, 2, 1.5, 2)),
                      zorder=KENNEDY_Z, gid=gid)
        ax.add_line(line)
        art.add("kennedy_lines", line)


def _pole_colour(st) -> str:
    return st.ink if not st.coloured else "#c0392b"


def _in_view(ax, p) -> bool:
    return p.position is not None and view_box(ax).contains(Point(*p.position))


def _draw_pole_marks(sol, ax, shown, st, art) -> None:
    """A ring with a cross on each pole in view that is no pin (a pole at a pin is the pin); every ring is an
    obstacle before any pole's label is placed."""
    from matplotlib.lines import Line2D
    pins = {pin.point for pin in sol.mechanism.pins}
    pin_places = [np.asarray(sol.position[k], float) for k in sol.position if k.split("@")[0] in pins]
    tol = 1e-9 * sol.mechanism.size
    r = 0.085 * per_cm(ax)
    art.rings = {}
    for p in shown:
        if not _in_view(ax, p):
            continue
        q = np.asarray(p.position, float)
        ring = Point(*q).buffer(r, quad_segs=10)
        art.rings[p.key] = ring
        if any(float(np.hypot(*(q - w))) <= tol for w in pin_places):
            continue
        colour = _pole_colour(st)
        mk = shape_patch(ring, facecolor=st.paper, edgecolor=colour, lw=st.link_lw, zorder=5.5, gid=f"pole-{p.key}")
        ax.add_patch(mk)
        cross = Line2D([q[0] - r, q[0] + r, np.nan, q[0], q[0]], [q[1], q[1], np.nan, q[1] - r, q[1] + r],
                       lw=st.thin_lw, color=colour, zorder=5.6)
        ax.add_line(cross)
        art.add("poles", mk, cross)
        placer(ax).add_obstacle(ring)


def _nearer_own(own, rings):
    """A test of a label's box: nearer its own ring than any other ring (a pole's label by its pole).

    ``b.distance(g)`` of every other ring is asked of GEOS (in one call) where the gap between the two envelopes
    is not clearly more than the distance to its own ring (:data:`APART_BY`): a ring is never nearer than its
    envelope, and GEOS's distances are exact to far less than that, so a ring left out is one GEOS puts
    farther (the same answers)."""
    import shapely
    others = np.array([g for g in rings if not g.equals(own)], dtype=object)
    bounds = shapely.bounds(others) if len(others) else np.empty((0, 4))
    x0, y0, x1, y1 = own.bounds
    slack = APART_BY * max(x1 - x0, y1 - y0)

    def accept(b) -> bool:
        d = b.distance(own)
        u0, v0, u1, v1 = b.bounds
        gap = np.hypot(np.maximum(np.maximum(bounds[:, 0] - u1, u0 - bounds[:, 2]), 0.0),
                       np.maximum(np.maximum(bounds[:, 1] - v1, v0 - bounds[:, 3]), 0.0))
        near = ~(gap > d * (1.0 + APART_BY) + slack)   # (NaN: asked)
        return bool(np.all(d < shapely.distance(b, others[near])))
    return accept




def _place_free(pl, anchor, text, *, fontsize: float, **kw):
    """A pole's label (or an arrow's to a pole out of view) where a free place exists (off every Kennedy line,
    label, leader and mark), smaller (:data:`SMALLER`) if only that finds one, else at the end of a longer
    leader (:data:`~velpoly.render.labels.REACH_RINGS`, at its size, else smaller), else at its size where it
    covers least (a crowd of poles)."""
    tries = [(reach, f) for reach in (False, True) for f in (1.0,) + SMALLER]
    for reach, f in tries:
        t = pl.place(anchor, text, fontsize=fontsize * f, reach=reach, last_resort=False, **kw)
        if t is not None:
            return t if pl.at_pin(t) or not _on_lines(pl, t) else _off_drawn_lines(pl, t, anchor, text, fontsize, tries, kw)
    return _least_covering(pl, anchor, text, fontsize, kw)


def _least_covering(pl, anchor, text, fontsize: float, kw):
    """A crowd's last resort (no free place at any size or reach): where it covers least, at the size (its own,
    else :data:`SMALLER`) whose place there meets the fewest hard obstacles (Kennedy lines, marks, leaders): the
    place covering least at its own size may lie on a Kennedy line where a smaller box's lies on none (Example
    3.4's P26 on slides). A step frame's label stands at its pin (:meth:`LabelPlacer.place` tries it first).
    The size chosen, where it is the last tried (one that meets none, or the smallest), is kept as tried: placed
    again at the same moment it would go to the same place."""
    best, sizes = None, (1.0,) + SMALLER
    for n, f in enumerate(sizes):
        with pl.trial():
            t = pl.place(anchor, text, fontsize=fontsize * f, reach=True, **kw)
            hits = 0 if pl.at_pin(t) else _hard_hits(pl, pl.of(t))
            kept = pl.keep = hits == 0 or (n == len(sizes) - 1 and (best is None or hits < best[0]))
        if kept:
            return t
        if best is None or hits < best[0]:
            best = (hits, f)
    return pl.place(anchor, text, fontsize=fontsize * best[1], reach=True, **kw)


def _hard_hits(pl, own) -> int:
    """How many hard obstacles (and other labels' leaders) the placed label ``own``'s box meets."""
    import shapely
    hard = np.array(pl._hard + [q.leader_geom for q in pl.labels if q is not own and q.leader_geom is not None],
                    dtype=object)
    return int(shapely.intersects(hard, own.box).sum()) if hard.size else 0


def _drawn_lines(ax) -> list:
    """Every line drawn on ``ax`` (Line2D, in data coordinates, each run between gaps), leaders excepted. Kept
    on the axes while the same lines stand with the same points: a pole's label asks at every place it tries."""
    shown = [(ln, ln.get_xydata()) for ln in ax.lines
             if not (ln.get_gid() or "").endswith("-leader") and ln.get_visible()]
    got = getattr(ax, "_velpoly_lines", None)   # (the lines with their points, the runs made of them)
    if got is not None and len(got[0]) == len(shown) and all(
            a is c and x is y for (a, x), (c, y) in zip(got[0], shown)):
        return list(got[1])
    out = []
    for _, xy in shown:
        xy = np.asarray(xy, float)
        ok = np.all(np.isfinite(xy), axis=1)
        for run in np.split(xy, np.flatnonzero(~ok)):
            run = run[np.all(np.isfinite(run), axis=1)]
            if len(run) >= 2:
                out.append(LineString(run))
    ax._velpoly_lines = (shown, out)
    return list(out)


def _on_lines(pl, t, lines=None) -> bool:
    """Whether the Text's box (as placed, no margin) meets a line drawn (:func:`_drawn_lines`)."""
    b = pl.box_of(t, pad=0.0)
    return any(g.intersects(b) for g in (_drawn_lines(pl.ax) if lines is None else lines))


def _off_drawn_lines(pl, t, anchor, text, fontsize: float, tries, kw):
    """A pole's label whose free place lies on a drawn line (a slider's path: a soft obstacle, which the
    search weighs against a leader across a Kennedy line) placed again where its box meets no drawn line: the
    same tries (nearer, farther, smaller), each box tested (``accept``) off the lines; where none is free, where
    it was (put back as it stood: placed again it would go there)."""
    lines = _drawn_lines(pl.ax)
    was, placed = pl.moment(), t
    pl.remove(t)
    accept = kw.pop("accept", None)

    def off(b) -> bool:
        return (accept is None or accept(b)) and not any(g.intersects(b) for g in lines)
    for reach, f in tries:
        with pl.trial():
            t = pl.place(anchor, text, fontsize=fontsize * f, reach=reach, accept=off, last_resort=False, **kw)
            pl.keep = t is not None and not _on_lines(pl, t, lines)
        if t is not None and pl.of(t) is not None:
            return t
    pl.back_to(was)
    return placed


INFINITY_SHIFTS = (0.0,) + tuple(x for k in range(1, 16) for x in (0.4 * k, -0.4 * k))   # cm, across its way


def _infinity_arrow_tip(pl, content, c, d, pc: float, far) -> np.ndarray:
    """Where the arrow to a pole at infinity (in direction ``d``) ends: at the border of what is drawn
    (``content``) on the ray from the centre ``c`` along ``d``, or on a ray beside it (shifted across by
    :data:`INFINITY_SHIFTS`; a pole at infinity is a direction, not a place) where the arrow and the room
    for its label at its tail meet no label, no leader and no other such arrow (the first such ray; in a
    crowd, the centre's)."""
    n = np.array([-d[1], d[0]])
    taken = pl.boxes + pl.leaders + list(far)
    for s in INFINITY_SHIFTS:
        tip = border_point(content, c + n * s * pc, d, 0.2 * pc)
        tail = tip - d * 1.1 * pc
        room = segment(tail, tip).buffer(0.1 * pc).union(Point(*tail).buffer(0.35 * pc))
        if content.contains(Point(*tip)) and not any(g.intersects(room) for g in taken):
            return tip
    return border_point(content, c, d, 0.2 * pc)


def _label_poles(sol, ax, ps, shown, pole_lines, st, art, reach: float | None = None) -> dict:
    """Each pole's label: by its ring (nearer it than any other ring), or by the arrow at the border that
    points to a pole at infinity or out of view. Return how each was placed: its key -> (anchor, text, the
    placing's arguments), for placing it again (:func:`_uncross`). A crowded sheet's (``reach`` given, the view
    it holds): the poles out of view first (their labels long, the position), while the border has room."""
    pl = placer(ax)
    pc, pp = per_cm(ax), per_point(ax)
    view = view_box(ax)
    c = _centre(sol)
    # arrows to poles at infinity stand at the border of what is drawn, not of the whole panel
    from shapely.geometry import box as sbox
    bx0, by0, bx1, by1 = poles_bounds(sol, ps, reach)
    content = sbox(bx0 - 1.6 * pc, by0 - 1.6 * pc, bx1 + 1.6 * pc, by1 + 1.6 * pc).intersection(view)
    rings = list(art.rings.values())
    colour = _pole_colour(st)
    kw = dict(fontsize=st.font_size * 0.9, color=colour, zorder=7)
    far = []   # the arrows drawn to poles out of view (another such arrow keeps off them)
    how = {}
    for p in (sorted(shown, key=lambda p: _in_view(ax, p)) if reach is not None else shown):
        if p.position is None and p.direction is None:
            continue   # undefined: the links move alike (listed in the table)
        label = pole_label(p.links)
        if _in_view(ax, p):   # in view: where it is
            anchor, text, prefer = np.asarray(p.position, float), label, -45.0
            accept = _nearer_own(art.rings[p.key], rings)
        else:
            if p.position is None:
                d = np.array([math.cos(math.radians(p.direction)), math.sin(math.radians(p.direction))])
                text = label + r" $\infty$"
                pin = pl.pins.get(f"pole-{p.key}")   # a step frame: where the finished construction has it
                tip = np.asarray(pin[1], float) if pin is not None else _infinity_arrow_tip(pl, content, c, d, pc, far)
                pl.placed[f"pole-{p.key}"] = ("arrow", (float(tip[0]), float(tip[1])))
            else:
                text = label + f" ({p.position[0]:.4g}, {p.position[1]:.4g})".replace("-", "−")
                tip, d = far_pole_arrow(view, p.position, pole_lines.get(p.key, ()), c, 0.2 * pc)
            tail = tip - d * 1.1 * pc
            sh, hd, poly = arrow(ax, tail, tip, lw=st.arrow_lw, head_length=st.head_length, colour=colour,
                                 zorder=6, gid=f"pole-{p.key}")
            art.add("far", sh, hd)
            pl.add_obstacle(poly)
            pl.add_obstacle(segment(tail, tip).buffer(pp), hard=True)
            far.append(segment(tail, tip).buffer(pp))
            anchor, prefer, accept = tail, math.degrees(math.atan2(-d[1], -d[0])), None
        how[p.key] = (anchor, text, dict(kw, prefer=prefer, gid=f"label-pole-{p.key}",
                                         **({} if accept is None else {"accept": accept})))
        t = _place_free(pl, anchor, text, **how[p.key][2])
        art.add("labels", t)
        art.labels[p.key] = t
    return how


def draw_kennedy_circle(sol, ax=None, *, style="textbook", options=None, poleset=None,
                        upto: int | None = None) -> Artists:
    """Draw the Kennedy circle of ``sol``'s poles; return its Artists.

    The links are points on a circle; each of the n(n-1)/2 poles is a chord:
    solid if known by inspection, dashed and numbered by order of discovery
    if found (with ``upto``, only the first ``upto`` found are drawn, the
    last one heavier), dotted if undefined. The first frame of a step
    sequence (``upto`` = 0) shows the poles sought as thin grey dashed chords,
    unnumbered.

    Returns
    -------
    Artists
        Roles ``circle``, ``points`` (one per link, gid ``kennedy-point-<link>``),
        ``chords`` (one per pole drawn, gid ``chord-<key>``; a pole sought
        ``chord-sought-<key>``), ``numbers``, ``labels``; ``.labels`` maps each
        link to its label.
    """
    from ..poles import kennedy_circle
    from matplotlib.patches import Circle
    ax = get_ax(ax)
    st = get_style(style)
    ps = _poleset(sol, poleset)
    kc = kennedy_circle(ps)
    if view_scale(ax) is None:
        fit_view(ax, (-1.0, -1.0, 1.0, 1.0), margin=0.16)
        ax.set_axis_off()
    art = Artists(ax)
    pl = placer(ax)
    circ = Circle((0, 0), 1.0, fill=False, lw=st.thin_lw, edgecolor=st.ink, zorder=1, gid="kennedy-circle")
    ax.add_patch(circ)
    art.add("circle", circ)
    numbered = _draw_chords(ax, kc, ps, st, upto, art)
    for lk, q in kc.points.items():
        dot = Circle(tuple(q), 0.05 * per_cm(ax), facecolor=st.ink, edgecolor=st.ink, zorder=4,
                     gid=f"kennedy-point-{lk}")
        ax.add_patch(dot)
        art.add("points", dot)
        pl.add_obstacle(Point(*q).buffer(0.05 * per_cm(ax)))
    for lk, q in kc.points.items():
        t = pl.place(q, lk, prefer=math.degrees(math.atan2(q[1], q[0])), fontsize=st.font_size, zorder=7,
                     gid=f"kennedy-label-{lk}")
        art.add("labels", t)
        art.labels[lk] = t
    _number_chords(pl, kc, numbered, st, art)
    return art


def _chord_style(ch, pole, upto, last: int, st):
    """(line style, width, colour) of a chord: solid known by inspection, dotted undefined, dashed found (the
    last found of a step frame heavier), thin grey dashes sought (a step frame's first)."""
    undefined = pole.position is None and pole.direction is None
    if ch.solid:
        return "-", st.link_lw, st.ink
    if undefined and ch.order == 0:
        return (0, (1, 2)), st.thin_lw * 1.5, st.ink
    if upto is not None and ch.order > upto:
        return (0, (3, 3)), st.thin_lw, "#9a9a9a"
    heavy = 1.8 if upto is not None and ch.order == last else 1.0
    # the dashes as long as the other chords' (matplotlib scales them with the width): a heavy chord keeps
    # reaching its points instead of ending in a long gap
    return (0, (5 / heavy, 3 / heavy)), st.link_lw * heavy, st.ink if not st.coloured else "#c0392b"


def _draw_chords(ax, kc, ps, st, upto, art) -> list:
    """Every chord of the frame (a step frame after the first: no chord of a pole not yet found); return
    the found ones to number: ``[(chord, a, b, colour)]``."""
    from matplotlib.lines import Line2D
    found = [ch for ch in kc.chords if not ch.solid and ch.order > 0]
    last = max((ch.order for ch in found if upto is None or ch.order <= upto), default=0)
    numbered = []
    for ch in kc.chords:
        sought = not ch.solid and upto is not None and ch.order > upto
        if sought and upto != 0:
            continue
        a, b = kc.points[ch.links[0]], kc.points[ch.links[1]]
        ls, lw, colour = _chord_style(ch, ps.poles[ch.key], upto, last, st)
        line = Line2D([a[0], b[0]], [a[1], b[1]], lw=lw, linestyle=ls, color=colour, zorder=2 if not sought else 1.5,
                      gid=f"chord-sought-{ch.key}" if sought else f"chord-{ch.key}")
        ax.add_line(line)
        art.add("chords", line)
        if not ch.solid and 0 < ch.order and not sought:
            numbered.append((ch, a, b, colour))
    return numbered


def _number_chords(pl, kc, numbered, st, art) -> None:
    """Each found chord's number on its own chord where it meets no other chord (so never at a crossing: on
    a four-bar the two diagonals cross at the centre), no other number and no link label: at its size, else
    smaller (:data:`SMALLER`). A number with no such place on its chord (a crowd of chords in a small circle)
    goes beside the circle's crowd with a leader to its chord, off every chord, the circle and every label
    (:func:`_number_off_chords`); only where none is free does it go where it covers least."""
    segs = {ch.key: segment(kc.points[ch.links[0]], kc.points[ch.links[1]]) for ch in kc.chords}
    fractions = NUMBER_SPOTS + tuple(f for f in FINE_SPOTS if f not in NUMBER_SPOTS)
    left = []
    for ch, a, b, colour in sorted(numbered, key=lambda x: x[0].order):
        spots = [a + (b - a) * f for f in fractions]
        others = [g for k, g in segs.items() if k != ch.key]
        for f in (1.0,) + SMALLER:
            t = pl.place_at(spots, str(ch.order), gid=f"chord-number-{ch.key}", pad=3.0, avoid=others,
                            **_number_style(st, colour, f))
            if t is not None:
                art.add("numbers", t)
                break
        else:
            left.append((ch, spots, colour))
    if left:
        _number_off_chords(pl, kc, segs, left, st, art)


def _number_style(st, colour, f: float = 1.0) -> dict:
    """A chord number's text: small, in a circle the colour of its chord (``f``: of its size)."""
    return dict(fontsize=st.small_size * f, color=colour, zorder=6,
                bbox=dict(boxstyle="circle,pad=0.15", facecolor=st.paper, edgecolor=colour, lw=st.thin_lw))


def _number_off_chords(pl, kc, segs, left, st, art) -> None:
    """The chord numbers with no free place on their chords: each chord and the circle's rim an obstacle, each
    such number placed by the placer (:meth:`LabelPlacer.place`; at its size, else smaller) with a leader
    from the spot of its chord nearest the rim that is 5 pt from every other chord (else the spot farthest
    from them), so that its leader is short and its end on no other chord; with no free place, where it
    covers least off the other chords (:func:`_least_on_chords`)."""
    from matplotlib.patches import Circle
    for g in segs.values():   # no number on a chord (hard); a leader crosses as few as it can (soft)
        pl.add_obstacle(g)
        pl.add_obstacle(g, hard=False)
    rim = next((p for p in pl.ax.patches if isinstance(p, Circle) and p.get_gid() == "kennedy-circle"), None)
    if rim is not None:
        pl.add_obstacle(Point(*rim.center).buffer(rim.radius).exterior)
    pp = per_point(pl.ax)
    for ch, spots, colour in left:
        others = [g for k, g in segs.items() if k != ch.key]
        apart = [min(g.distance(Point(*q)) for g in others) for q in spots]
        clear = [q for q, d in zip(spots, apart) if d >= 5.0 * pp]   # a leader's end no one reads as another's
        anchor = max(clear, key=lambda q: float(np.hypot(*q))) if clear else spots[int(np.argmax(apart))]
        gid = f"chord-number-{ch.key}"
        for f in (1.0,) + SMALLER:
            t = pl.place(anchor, str(ch.order), gid=gid, pad=3.0, reach=True, last_resort=False,
                         prefer=math.degrees(math.atan2(anchor[1], anchor[0])), **_number_style(st, colour, f))
            if t is not None:
                break
        if t is None:   # no free place (none kept): where it covers least
            t = _least_on_chords(pl, [anchor, spots[0]], str(ch.order), gid, others, _number_style(st, colour))
        art.add("numbers", t)


def _least_on_chords(pl, anchors, s: str, gid: str, others, kw):
    """A chord number with no free place: where it covers least (:meth:`LabelPlacer.place`'s last resort) from
    each anchor in turn, at its size, else smaller: the first whose box meets no other chord; else from the
    first anchor at its size."""
    for at in anchors:
        for f in (1.0,) + SMALLER:
            with pl.trial():
                t = pl.place(at, s, gid=gid, pad=3.0, **{**kw, "fontsize": kw["fontsize"] * f})
                pl.keep = not any(g.intersects(pl.box_of(t, pad=0.0)) for g in others)
            if pl.of(t) is not None:
                return t
    return pl.place(anchors[0], s, gid=gid, pad=3.0, **kw)
