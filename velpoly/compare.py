"""Graphical against analytic against the book: one comparison, read by every table that shows one.

The graphical value of a quantity is read off the constructions (the velocity
and acceleration polygons' rates and images, the poles found on the Kennedy
circle), the analytic one off the linear solve, the book's off the file's
``[reference]`` (:func:`velpoly.reference.compare`). :func:`polygon_values`
pairs a polygon's rates and images with the analytic values (the polygons'
tables of ``velpoly solve``, the sheets' results table, the gallery);
:func:`comparison` is the gallery's and the demo's table of book, graphical
and analytic values. Nothing here draws or writes Markdown (velpoly.gallery
does), nothing prints.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import InputError
from .reference import Quantity, compare, evaluate, kind_scales, parse_key, scale_of   # re-exported
from .rigid import point_acceleration, point_velocity
from .tables import ZERO, Table, coordinates, fmt, magnitude_angle, magnitude_direction, zero_floor

__all__ = ["Graphical", "Comparison", "comparison", "HEADER", "Value", "polygon_values", "kind_scales", "kind_floor", "key_floor", "scale_of"]


# -- graphical values ----------------------------------------------------------------------------
class Graphical:
    """The graphical constructions of one solution, read like a Solution by :func:`reference.evaluate`.

    omega and alpha are the polygons' rates; a point's velocity (acceleration) is
    its image in the velocity (acceleration) polygon; a body point of a link
    that has no image of its own follows from the link's image
    (``V = V_a + omega x R``, ``A = A_a + alpha x R - omega^2 R`` from an image a);
    a pole's position is the one found on the Kennedy circle.
    """

    def __init__(self, sol):
        from .poles import locate_poles
        from .polygons import acceleration_polygon, velocity_polygon
        self.sol = sol
        self.mechanism = sol.mechanism
        self.vel = velocity_polygon(sol)
        self.acc = acceleration_polygon(sol) if sol.has_accelerations else None
        self.poles = locate_poles(sol)
        # what reference.evaluate reads
        self.angle, self.position = sol.angle, sol.position
        self.omega, self.velocity = self.vel.rates, self.vel.images
        self.alpha = self.acc.rates if self.acc else {}
        self.acceleration = self.acc.images if self.acc else {}

    def _anchor(self, link: str, images: dict):
        """An imaged point key carried by ``link``: (key, its position)."""
        m = self.mechanism
        for p in m.link(link).points:
            for key in (p, f"{p}@{link}"):
                if key in images and key in self.sol.position:
                    return key, self.sol.position[key]
        return None, None

    def _body(self, link: str, w, acc: bool) -> np.ndarray:
        """V (A) of the body point of ``link`` at w from the link's image: V_a + omega x R
        (A_a + alpha x R - omega^2 R)."""
        if link == self.mechanism.frame.name:
            return np.zeros(2)
        poly = self.acc if acc else self.vel
        key, at = self._anchor(link, poly.images)
        if key is None:
            raise KeyError(link)
        r, image = np.asarray(w, float) - at, np.asarray(poly.images[key], float)
        if acc:
            return point_acceleration(image, poly.rates[link], self.vel.rates[link], r)
        return point_velocity(image, poly.rates[link], r)

    def body_velocity(self, link: str, w) -> np.ndarray:
        return self._body(link, w, False)

    def body_acceleration(self, link: str, w) -> np.ndarray:
        return self._body(link, w, True)

    def pole(self, i: str, j: str):
        names = self.mechanism.link_names
        a, b = sorted((i, j), key=names.index)
        return self.poles.poles[f"{a}-{b}"].position

    def value(self, q: Quantity):
        """The graphical value of a parsed reference key, or None where no construction gives it."""
        if q.kind in ("theta", "R"):
            return None               # positions: the displacement diagram is the analytic pose itself
        if q.kind == "P":
            return self.pole(*q.links)
        if q.kind in ("A", "alpha", "AP") and self.acc is None:
            return None
        if q.kind in ("VP", "AP"):
            at = self.pole(*q.links)
            if at is None:
                return None
            return (self.body_velocity if q.kind == "VP" else self.body_acceleration)(q.links[0], at)
        try:
            return evaluate(self, q)
        except (KeyError, InputError):
            return None


# -- the comparison table ------------------------------------------------------------------------
@dataclass(frozen=True)
class Comparison:
    """The book's values beside the graphical and analytic ones: a :class:`Table` and its notes.

    ``table.rows`` hold strings; ``notes`` are ``(number, quantity, sentence)``,
    one per distinct ``[reference] note``; ``values`` keeps each row's numbers
    ``(quantity, printed, graphical, analytic)`` for checks.
    """

    title: str
    table: Table
    notes: tuple = ()
    values: tuple = ()


def _show(value, kind: str, floor: float = ZERO) -> str:
    if value is None:
        return "-"
    if kind == "P":
        return coordinates(value, floor)
    if isinstance(value, tuple):
        return "0" if fmt(value[0], floor=floor) == "0" else magnitude_angle(value[0], value[1], floor)
    return fmt(value, floor=floor)


def key_floor(m, key: str, scales: dict) -> float:
    """Below what a row's computed value prints as 0 (:func:`velpoly.tables.zero_floor`): a billionth of the
    largest value of its kind in the mechanism (:func:`kind_scales`), at most ZERO; a link angle's, ZERO."""
    if key.startswith(("omega_", "alpha_")):
        q = Quantity(key.split("_", 1)[0], links=(key.split("_", 1)[1],))
    else:
        q = _key_kind(m, key)
    return kind_floor(scales, q.kind)


def kind_floor(scales: dict, kind: str) -> float:
    """Below what a value of ``kind`` (``omega``, ``alpha``, ``V``, ``A``, ``P``, a reference's ``VP``, ``AP``,
    ``R``; ``theta`` a link angle) prints as 0: a billionth of the largest value of its kind in the mechanism
    (``scales``, :func:`kind_scales`), at most ZERO (:func:`velpoly.tables.zero_floor`); a link angle's, ZERO.
    Every table of a Solution reads this, ``velpoly solve``'s and the drawn sheets' alike."""
    return ZERO if kind == "theta" else zero_floor([scale_of(kind, scales)])


def _graphical_shown(row, q: Quantity, g):
    """The graphical value in the row's printed form: (magnitude, direction), a magnitude, a number."""
    if g is None:
        return None
    if q.kind == "P":
        return (float(g[0]), float(g[1]))
    if isinstance(g, np.ndarray):
        if isinstance(row.computed, tuple):
            return magnitude_direction(g)
        return float(np.hypot(*g))
    return float(g)


def _cartesian(v, polar: bool) -> np.ndarray:
    if polar:
        return np.array([v[0] * math.cos(math.radians(v[1])), v[0] * math.sin(math.radians(v[1]))])
    return np.asarray(v, float)


def _difference(g, a, scale: float, polar: bool = True) -> str:
    """|graphical - analytic| relative to ``scale``, the largest value of its kind in the mechanism.

    Tuples are vectors: (magnitude, direction in degrees) if ``polar``, else (x, y).
    """
    if g is None or a is None:
        return "-"
    if isinstance(a, tuple):
        d = float(np.hypot(*(_cartesian(g, polar) - _cartesian(a, polar))))
    else:
        d = abs(float(g) - float(a))
    rel = d / scale
    return "0" if rel == 0 else f"{rel:.1e}"


def _book_deviation(r) -> str:
    dev = [] if r.deviation is None else [f"{100 * r.deviation:.3g}%"]
    if r.angle_error is not None:
        dev.append(f"{r.angle_error:.3g}°")
    return " ".join(dev) or "-"


def _key_kind(m, key: str) -> Quantity:
    label = key[1:-1] if key.startswith("|") else key       # "|V_F|" is a speed
    q = parse_key(m, label)
    if q is None:
        q = Quantity("V", ((label[2:], None),)) if label.startswith("V_") else Quantity("A", ((label[2:], None),))
    return q


def comparison(sol) -> Comparison:
    """Every ``[reference]`` value: book, graphical, analytic, and the deviations.

    A file without printed values gets the main results instead (each moving
    link's omega and alpha, each moving point's velocity and acceleration),
    graphical beside analytic, the book's column empty.
    """
    m = sol.mechanism
    g = Graphical(sol)
    scales = kind_scales(sol)
    if not m.reference:
        return _results(sol, g, scales)
    rows, notes, values = [], [], []
    note_no = {}
    for r in compare(sol):
        if r.key.startswith("omega_") or r.key.startswith("alpha_"):
            q = Quantity(r.key.split("_", 1)[0], links=(r.key.split("_", 1)[1],))
        else:
            q = _key_kind(m, r.key)
        gv = _graphical_shown(r, q, g.value(q))
        kind, floor = "P" if q.kind == "P" else "", key_floor(m, r.key, scales)
        ref = ""
        if r.note:
            if r.note not in note_no:
                note_no[r.note] = len(note_no) + 1
                notes.append((note_no[r.note], r.key, r.note))
            ref = f"[{note_no[r.note]}]"
        rows.append((r.key, _show(r.printed, kind, 0.0), _show(gv, kind, floor), _show(r.computed, kind, floor),
                     _book_deviation(r),
                     _difference(gv, r.computed, scale_of(q.kind, scales), polar=q.kind != "P"), ref))
        values.append((r.key, r.printed, gv, r.computed))
    title = "Book, graphical and analytic values" + (f" ({m.reference.source})" if m.reference.source else "")
    table = Table(title, HEADER, tuple(rows))
    return Comparison(title, table, tuple(notes), tuple(values))


HEADER = ("quantity", "book", "graphical", "analytic", "book vs analytic", "graphical vs analytic", "note")


def _results(sol, g: Graphical, scales: dict) -> Comparison:
    rows, values = [], []

    def add(key, graphical, analytic):
        kind = key.split("_", 1)[0]
        scale, floor = scales[kind], kind_floor(scales, kind)   # rounding noise prints 0, a slow mechanism's values as they are
        rows.append((key, "-", _show(graphical, "", floor), _show(analytic, "", floor), "-",
                     _difference(graphical, analytic, scale), ""))
        values.append((key, None, graphical, analytic))
    keys = [k for k, v in sol.velocity.items() if np.hypot(*v) > 0]
    levels = [("omega", "V", polygon_values(sol, g.vel, keys))]
    if sol.has_accelerations:
        levels.append(("alpha", "A", polygon_values(sol, g.acc, keys)))
    for rate, _, (rates, _) in levels:
        for v in rates:
            add(f"{rate}_{v.key}", v.graphical, v.analytic)
    for _, point, (_, points) in levels:
        for v in points:
            add(f"{point}_{v.key}", magnitude_direction(v.graphical), magnitude_direction(v.analytic))
    title = "Graphical and analytic values (no printed values to compare)"
    return Comparison(title, Table(title, HEADER, tuple(rows)), (), tuple(values))


# -- a polygon against the analytic solve ----------------------------------------------------------------
@dataclass(frozen=True)
class Value:
    """One quantity two ways: ``key`` (a link, or a point key), ``graphical`` (read off the polygon: a
    rate, or an image's vector; None where the polygon has none) and ``analytic`` (the solve's)."""

    key: str
    graphical: object
    analytic: object


def polygon_values(sol, poly, keys=None) -> tuple[list[Value], list[Value]]:
    """A velocity (acceleration) polygon beside the analytic solve: ``(rates, points)``.

    ``rates``: each moving link's omega (alpha) in file order, the polygon's
    against the solve's; ``points``: each point's velocity (acceleration) as its
    image gives it, ``V_B = Ob`` (``A_B = O'b'``), against the solve's, for the
    polygon's images in its order, or for ``keys``. The polygons' tables of
    ``velpoly solve``, the sheets' results table and the gallery's comparison
    all read these pairs.
    """
    vel = poly.kind == "velocity"
    rate = sol.omega if vel else sol.alpha
    point = sol.velocity if vel else sol.acceleration
    rates = [Value(k.name, poly.rates.get(k.name), rate[k.name]) for k in sol.mechanism.moving_links]
    points = [Value(key, poly.images.get(key), point.get(key)) for key in (poly.images if keys is None else keys)]
    return rates, points
