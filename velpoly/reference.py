"""Published answers (``[reference]``) in textbook notation, and their comparison.

Keys of ``values`` are read the way books print them:

=============  ==============================================================
``V_B``        absolute velocity of B (``A_B``: acceleration)
``V_B3``       velocity of the point of link 3 at B
``V_BA``       V_B - V_A, B relative to A (``V_D5C5``: both on link 5)
``V_B3/B4``    V_B3 - V_B4, coincident points of links 3 and 4
``omega_3``    angular velocity of link 3 (``alpha_3``; ``theta_3`` its angle)
``R_BA``       position of B relative to A
``P_13``       position of the pole of links 1 and 3, ``[x, y]`` (``P_lever,cylinder`` where
               a link's name is a word: the figures' P_{lever,cylinder})
``V_P24``      velocity of the pole P_24
``A^n_BA``     normal component of A_BA (B and A on one link): -omega^2 R_BA
``A^t_BA``     tangential component of A_BA: alpha x R_BA
``A^c_B3/B4``  Coriolis component of A_B3/B4: 2 omega_4 x V_B3/B4 (B4 on the guide or slot)
``A^s_B3/B4``  acceleration of sliding: A_B3/B4 - A^c_B3/B4, the relative acceleration in link 4
=============  ==============================================================

A vector is ``[magnitude, direction]`` (a negative magnitude reverses it) or
a bare magnitude. A ``note`` is keyed by the value it explains, in the same
notation (``omega_3``, ``V_B``, ``A^c_B3/B4``).
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from .driver import driver_reference_angle
from .errors import InputError
from .rigid import coriolis as coriolis_term, normal_acceleration, rate_cross

__all__ = ["Quantity", "parse_key", "validate_reference", "compare", "Row", "relative_pole", "value_keys",
           "note_for", "COMPONENTS", "kind_scales", "scale_of"]


@dataclass(frozen=True)
class Quantity:
    """A parsed textbook key: ``kind`` and its operands.

    kind: 'V' or 'A' (difference of point refs), 'R' (position difference),
    'omega', 'alpha', 'theta' (a link), 'P' (pole position), 'VP'/'AP' (pole motion).
    ``refs`` are (point, link-or-None) pairs; ``links`` link names. ``part`` names a
    component of an acceleration difference ('n', 't', 'c', 's'; kind 'A'): for 'n'
    and 't' both refs carry the link they share, for 'c' and 's' each its own link.
    """

    kind: str
    refs: tuple = ()
    links: tuple = ()
    part: str = ""


def _point_refs(m, s: str, count: int):
    """Split ``s`` into ``count`` point refs (point name + optional link suffix)."""
    names = sorted(set(m.points), key=len, reverse=True)
    links = set(m.link_names)

    def one(tok):
        if "@" in tok:
            p, lk = tok.split("@", 1)
            return (p, lk) if p in m.points and lk in links else None
        if tok in m.points:
            return (tok, None)
        for p in names:
            if tok.startswith(p) and tok[len(p):] in links:
                return (p, tok[len(p):])
        return None

    if count == 1:
        r = one(s)
        return [r] if r else None
    for i in range(1, len(s)):
        a, b = one(s[:i]), one(s[i:])
        if a and b:
            return [a, b]
    return None


def _pole_splits(s: str) -> list[tuple[str, str]]:
    """The ways ``s`` (what follows ``P_``) names two links: at a comma where it has one, as the
    figures print a pole of named links (``P_lever,cylinder``: P_{lever,cylinder}), else at every
    place (``P_13``)."""
    s = s.lstrip("_")
    if "," in s:
        return [(s[:i], s[i + 1:]) for i, c in enumerate(s) if c == ","]
    return [(s[:i], s[i:]) for i in range(1, len(s))]


def _two_links(m, s: str):
    links = m.link_names
    return next(((a, b) for a, b in _pole_splits(s) if a in links and b in links and a != b), None)


def _pole_trouble(m, s: str) -> str:
    """Why ``P_s`` names no pole here (for the error message): the link it names that the file has
    not, or how a pole's key is written."""
    links = m.link_names
    shown = ", ".join(links)
    for a, b in _pole_splits(s):
        if a in links and b in links:   # one link twice
            return f"a pole is of two different links, got link {a} twice"
        if (a in links) != (b in links):
            return f"no link {b if a in links else a!r} (links: {shown}): P_{s} is the pole of links {a} and {b}"
    return f"a pole is P_ij of two links i and j (P_13), or P_i,j where a link is a word (links: {shown})"


COMPONENTS = {"n": "normal", "t": "tangential", "c": "Coriolis", "s": "sliding"}


def _component(m, part: str, body: str) -> Quantity | None:
    """``A^n_BA``/``A^t_BA`` (B and A on one link, named or shared) or ``A^c_B3/B4``/``A^s_B3/B4``
    (coincident points of two named links); None if the body does not read so."""
    if part in "nt":
        if "/" in body:
            return None
        refs = _point_refs(m, body, 2)
        if not refs:
            return None
        (b, lb), (a, la) = refs
        if b == a:   # a point relative to itself has no components
            return None
        named = {lk for lk in (lb, la) if lk}
        shared = [lk for lk in m.link_names if lk in m.carriers.get(b, ()) and lk in m.carriers.get(a, ())]
        if len(named) > 1 or (named and named.pop() not in shared) or not shared:
            return None
        lk = lb or la or shared[0]
        return Quantity("A", refs=((b, lk), (a, lk)), links=(lk,), part=part)
    a, sep, b = body.partition("/")
    ra, rb = _point_refs(m, a, 1), _point_refs(m, b, 1) if sep else None
    if not (ra and rb) or ra[0][1] is None or rb[0][1] is None or ra[0][1] == rb[0][1]:
        return None
    return Quantity("A", refs=(ra[0], rb[0]), links=(ra[0][1], rb[0][1]), part=part)


def parse_key(m, key: str) -> Quantity | None:
    """Read a textbook key; None if it cannot be read for this mechanism."""
    mo = re.fullmatch(r"A\^([ntcs])_(.+)", key)
    if mo:
        return _component(m, *mo.groups())
    mo = re.fullmatch(r"(omega|alpha|theta)_?(.+)", key)
    if mo and mo.group(2) in m.link_names:
        return Quantity(mo.group(1), links=(mo.group(2),))
    mo = re.fullmatch(r"([VA])_?P_?(.+)", key)
    if mo:
        two = _two_links(m, mo.group(2))
        if two:
            return Quantity(mo.group(1) + "P", links=two)
    mo = re.fullmatch(r"P_?(.+)", key)
    if mo:
        two = _two_links(m, mo.group(1))
        if two:
            return Quantity("P", links=two)
    mo = re.fullmatch(r"([VAR])_(.+)", key)
    if not mo:
        return None
    kind, body = mo.groups()
    if "/" in body:
        a, _, b = body.partition("/")
        ra, rb = _point_refs(m, a, 1), _point_refs(m, b, 1)
        return Quantity(kind, refs=(ra[0], rb[0])) if ra and rb else None
    if kind != "R":
        r = _point_refs(m, body, 1)
        if r:
            return Quantity(kind, refs=(r[0],))
    r = _point_refs(m, body, 2)
    if r and r[0] == r[1]:   # V_AA: a point relative to itself, no quantity a book prints
        return None
    return Quantity(kind, refs=tuple(r)) if r else None


def validate_reference(m, ctx=None) -> None:
    """Raise InputError for a ``values`` key that cannot be read (FORMAT.md section 1)."""
    for key in m.reference.values:
        if parse_key(m, key) is None:
            raise InputError(f"unknown quantity {key!r}" + _trouble(m, key),
                             where=f"reference.values.{key}", file=m.source,
                             hint="keys in textbook notation: V_B, A_B, V_BA, V_B3/B4, omega_3, alpha_3, "
                                  "theta_3, R_BA, P_13, V_P24, A^n_BA, A^t_BA, A^c_B3/B4, A^s_B3/B4")
    ref = m.reference
    for key, v in ref.values.items():
        trouble = _shape_trouble(parse_key(m, key), key, v)
        if trouble:
            raise InputError(trouble[0], where=f"reference.values.{key}", file=m.source, hint=trouble[1])
    known = value_keys(ref)
    for key in list(ref.note):
        if key in known:
            continue
        bare = _bare_targets(ref, key)
        if len(bare) == 1:   # an older file's bare key ("3", "B") that names one printed value: still read
            continue
        if len(bare) > 1:
            raise InputError(f"a note for {key!r}, which names {' and '.join(bare)}", where=f"reference.note.{key}",
                             file=m.source, hint="key a note by the one value it explains: " + " or ".join(bare))
        # a note explains a printed value: one that is not there is a slip of the pen
        raise InputError(f"a note for {key!r}, which is no reference value", where=f"reference.note.{key}",
                         file=m.source, hint="key a note like the value it explains: "
                         + (", ".join(sorted(known)[:12]) + ("..." if len(known) > 12 else "") if known
                            else "there are no printed values to explain"))


def _shape_trouble(q: Quantity, key: str, v) -> tuple[str, str] | None:
    """(what, hint) where the printed value ``v`` of ``key`` has not the shape its kind takes (FORMAT.md
    section 1), else None: an angular rate or a link angle is one number; a pole's position is ``[x, y]``;
    every other quantity is a vector, ``[magnitude, direction]`` or a bare magnitude."""
    listed = isinstance(v, (list, tuple))
    if q.kind in ("omega", "alpha", "theta") and not q.part:
        if listed:
            return (f"expected a number, got a list: {key} is a scalar, not a vector",
                    f"{key} = 6.702 (signed: counter-clockwise positive)" if q.kind != "theta"
                    else f"{key} = 18.584 (degrees)")
    elif q.kind == "P":
        if not listed or len(v) != 2:
            got = f"a list of {len(v)}" if listed else "a number"
            return (f"expected a pole's position [x, y], got {got}",
                    f"{key} = [0.214, -0.087] (its x and y in frame coordinates)")
    elif listed and len(v) != 2:
        return (f"expected a magnitude or [magnitude, direction], got a list of {len(v)}",
                "a vector is [magnitude, direction in degrees], e.g. [435.2, 21.7]")
    return None


def value_keys(ref) -> list[str]:
    """The textbook key of every printed value (what a note is keyed by), in the file's order."""
    keys = [f"omega_{k}" for k in ref.omega] + [f"alpha_{k}" for k in ref.alpha]
    keys += [f"V_{p}" for p in ref.speed] + [f"|V_{p}|" for p in ref.speed]
    keys += [f"V_{p}" for p in ref.velocity] + [f"A_{p}" for p in ref.acceleration] + list(ref.values)
    return list(dict.fromkeys(keys))


def _bare_targets(ref, key: str) -> list[str]:
    """The printed values an older file's bare note key names: a link ("3": omega_3, alpha_3) or a
    point ("B": V_B, |V_B|, A_B)."""
    out = [f"{kind}_{key}" for kind, table in (("omega", ref.omega), ("alpha", ref.alpha)) if key in table]
    if key in ref.speed or key in ref.velocity:
        out.append(f"V_{key}")
    if key in ref.acceleration:
        out.append(f"A_{key}")
    return out


def note_for(ref, key: str) -> str:
    """The note on the printed value ``key`` (a key of :func:`value_keys` or a row's ``|V_B|``): keyed
    by the value, or (an older file) by the bare link or point that names this value alone."""
    if key in ref.note:
        return ref.note[key]
    if key.startswith("|V_") and key[1:-1] in ref.note:
        return ref.note[key[1:-1]]
    mo = re.fullmatch(r"(?:omega|alpha|V|A)_(.+)", key.strip("|"))
    if mo and mo.group(1) in ref.note and len(_bare_targets(ref, mo.group(1))) == 1:
        return ref.note[mo.group(1)]
    return ""


def _trouble(m, key: str) -> str:
    """``: why`` a ``values`` key reads as no quantity here, where that can be said ("" otherwise)."""
    mo = re.fullmatch(r"A\^([ntcs])_(.+)", key)
    if mo:
        return ": " + _component_trouble(m, *mo.groups())
    points = re.fullmatch(r"([VAR])_([^/]+)", key)
    refs = points and (_point_refs(m, points.group(2), 1) or _point_refs(m, points.group(2), 2))
    if refs and len(refs) == 2 and refs[0] == refs[1]:
        return f": {refs[0][0]} relative to itself ({points.group(1)}_BA is of two points B and A)"
    pole = re.fullmatch(r"(?:[VA]_?P_?|P_?)(.+)", key)
    if pole and not refs:   # no point (V_P24 may be the velocity of a point P24): a pole's key
        return ": " + _pole_trouble(m, pole.group(1))
    return ""


def _component_trouble(m, part: str, body: str) -> str:
    """Why ``A^part_body`` reads as no component here (for the error message)."""
    what = COMPONENTS[part]
    if part in "nt":
        refs = _point_refs(m, body, 2) if "/" not in body else None
        if not refs:
            return f"the {what} component is A^{part}_BA of two points B and A on one link"
        if refs[0][0] == refs[1][0]:
            return f"{refs[0][0]} relative to itself: the {what} component is A^{part}_BA of two points B and A"
        return (f"{refs[0][0]!r} and {refs[1][0]!r} are not on one link: the {what} component of A_BA needs "
                f"both points on one link")
    return (f"the {what} component is A^{part}_B3/B4, the point B of two links named by their numbers "
            f"(B3 on link 3 relative to B4 on link 4, the guide or slot)")


def relative_pole(sol, i: str, j: str):
    """The pole of links i and j: the point where their velocity fields agree.

    V_O(i) + omega_i x (W - O_i) = V_O(j) + omega_j x (W - O_j). Returns the
    position, or ``None`` at infinity (equal omegas), with the direction.
    """
    def twist(lk):
        k = sol.kinematics.system.index.get(lk)
        if k is None:
            return np.zeros(2), 0.0
        o = sol.q[3 * k:3 * k + 2]
        w = sol.qd[3 * k + 2]
        v = sol.qd[3 * k:3 * k + 2]
        return v - w * np.array([-o[1], o[0]]), w   # velocity of the body point at the world origin
    vi, wi = twist(i)
    vj, wj = twist(j)
    dv, dw = vi - vj, wi - wj
    # dv + dw * perp(W) = 0, perp(W) = (-W_y, W_x)  ->  W = (-dv_y, dv_x) / dw
    if abs(dw) <= 1e-300 or np.hypot(*dv) / abs(dw) > 1e9 * sol.mechanism.size:
        if np.hypot(*dv) == 0:
            return None, None
        d = math.degrees(math.atan2(dv[1], dv[0]))  # the velocity direction; the pole lies at 90 deg to it
        return None, (d + 90.0) % 180.0
    return np.array([-dv[1], dv[0]]) / dw, None


def _place(sol, p, lk):
    pos = sol.position
    if p in pos:
        return pos[p]
    key = f"{p}@{lk}" if lk and f"{p}@{lk}" in pos else next(k for k in pos if k.startswith(p + "@"))
    return pos[key]


def _ref_vec(sol, ref, acc: bool):
    p, lk = ref
    table = sol.acceleration if acc else sol.velocity
    if lk is None:
        if p in table:
            return table[p]
        keys = [k for k in table if k.startswith(p + "@")]
        if len(keys) == 1:
            return table[keys[0]]
        raise InputError(f"point {p!r} moves differently on links {', '.join(k.split('@')[1] for k in keys)}: "
                         f"say which, e.g. {p}{keys[0].split('@')[1]}", where="reference.values",
                         file=sol.mechanism.source)
    w = _place(sol, p, lk)
    return sol.body_acceleration(lk, w) if acc else sol.body_velocity(lk, w)


def _part(sol, q: Quantity) -> np.ndarray:
    """A component of an acceleration difference (``q.part``).

    n, t (B and A on link k): A_BA = alpha_k x R_BA - omega_k^2 R_BA; the normal part
    -omega_k^2 R_BA, the tangential alpha_k x R_BA. c, s (coincident points B3, B4 of links
    3 and 4): A_B3 = A_B4 + 2 omega_4 x V_B3/B4 + A_rel, the Coriolis part 2 omega_4 x V_B3/B4
    and the acceleration of sliding A_rel = A_B3/B4 - 2 omega_4 x V_B3/B4 (B3 relative to link 4).
    """
    if q.part in "nt":
        lk = q.links[0]
        r = _place(sol, *q.refs[0]) - _place(sol, *q.refs[1])
        return normal_acceleration(sol.omega[lk], r) if q.part == "n" else rate_cross(sol.alpha[lk], r)
    v_rel = _ref_vec(sol, q.refs[0], False) - _ref_vec(sol, q.refs[1], False)
    coriolis = coriolis_term(sol.omega[q.links[1]], v_rel)
    if q.part == "c":
        return coriolis
    return _ref_vec(sol, q.refs[0], True) - _ref_vec(sol, q.refs[1], True) - coriolis


def evaluate(sol, q: Quantity):
    """The computed value of a parsed key: a vector (2,), a scalar, or None (a pole at infinity)."""
    if q.part:
        return _part(sol, q)
    if q.kind in ("omega", "alpha"):
        return (sol.omega if q.kind == "omega" else sol.alpha)[q.links[0]]
    if q.kind == "theta":
        return sol.angle[q.links[0]]
    if q.kind in ("P", "VP", "AP"):
        from .poles import locate_poles   # the poles as the instant-centre tables show them
        pole = locate_poles(sol).pole(*q.links)
        pos = None if pole.position is None else np.asarray(pole.position, float)
        if pos is None or q.kind == "P":
            return pos
        return (sol.body_velocity if q.kind == "VP" else sol.body_acceleration)(q.links[0], pos)
    if q.kind == "R":
        a = _place(sol, *q.refs[0])
        return a - _place(sol, *q.refs[1]) if len(q.refs) == 2 else a
    acc = q.kind == "A"
    v = _ref_vec(sol, q.refs[0], acc)
    if len(q.refs) == 2:
        v = v - _ref_vec(sol, q.refs[1], acc)
    return v


@dataclass(frozen=True)
class Row:
    """One printed value beside the computed one.

    ``printed`` and ``computed`` are (magnitude, direction) for vectors, a
    number for scalars; ``deviation`` is relative (magnitudes) and
    ``angle_error`` in degrees (directions, link angles).
    """

    key: str
    printed: object
    computed: object
    deviation: float | None
    angle_error: float | None
    note: str = ""


def _polar(v):
    return float(np.hypot(*v)), float(math.degrees(math.atan2(v[1], v[0])))


def _angle_diff(a, b):
    return abs((a - b + 180.0) % 360.0 - 180.0)


def _rel(printed, computed, scale: float):
    """|computed - printed| relative to the printed value; where that is 0, relative to ``scale``, the largest
    value of its kind in the mechanism (a pole printed at the origin, omega_3 = 0: no printed size to be
    relative to)."""
    if printed == 0:
        return abs(computed) / scale
    return abs(computed - printed) / abs(printed)


def _row(key, printed, value, note, scale: float = 1.0):
    if value is None:   # a pole at infinity: the printed vector stays a (magnitude, direction) or (x, y) pair
        return Row(key, tuple(printed) if isinstance(printed, list) else printed, None, None, None, note)
    if isinstance(value, np.ndarray):
        mag, ang = _polar(value)
        if isinstance(printed, (list, tuple)):
            pm, pa = float(printed[0]), float(printed[1])
            if pm < 0:
                pm, pa = -pm, pa + 180.0
            return Row(key, (pm, pa % 360.0), (mag, ang % 360.0), _rel(pm, mag, scale),
                       _angle_diff(pa, ang) if mag > 0 else None, note)
        # a bare magnitude: a negative one reverses the vector (as [magnitude, direction]'s), whose magnitude
        # it still is (a book's V_B = -53.1, against the direction it assumed)
        return Row(key, float(printed), mag, _rel(abs(float(printed)), mag, scale), None, note)
    value = float(value)
    if key.startswith("theta"):
        return Row(key, float(printed), value, None, _angle_diff(float(printed), value), note)
    return Row(key, float(printed), value, _rel(float(printed), value, scale), None, note)


def kind_scales(sol) -> dict:
    """The size of each kind of quantity in the mechanism, to which a graphical value's error is
    relative (as FORMAT.md's graphical.max_error): the largest |omega|, speed, |alpha| (at least
    omega_max^2) and acceleration (at least v_max^2 / size), and the mechanism's size for positions."""
    def top(values):
        v = [abs(float(x)) for x in values if x is not None and math.isfinite(float(x))]
        return max(v, default=0.0)
    size = sol.mechanism.size
    omega = top(sol.omega.values()) or 1.0
    speed = top(np.hypot(*v) for v in sol.velocity.values()) or size * omega
    return {"omega": omega, "alpha": max(top(sol.alpha.values()), omega ** 2),
            "V": speed, "A": max(top(np.hypot(*a) for a in sol.acceleration.values()), speed ** 2 / size),
            "P": size}


def scale_of(kind: str, scales: dict) -> float:
    """The size of a quantity of ``kind`` (a [reference] key's: ``VP`` a velocity, ``R`` a position ...) in
    ``scales`` (:func:`kind_scales`)."""
    kind = {"VP": "V", "AP": "A", "R": "P", "theta": "P"}.get(kind, kind)
    return scales.get(kind, 1.0)


def file_pose_angle(m) -> float | None:
    """The driver angle (deg) of the pose the file describes, to which its printed values belong:
    ``driver.angle`` if the file gives one, else the reference pose's; None for a slider driver."""
    if m.driver.is_slider:
        return None
    return m.driver.angle if m.driver.angle is not None else driver_reference_angle(m)


def at_file_pose(sol) -> bool:
    """Whether ``sol`` is the pose the file describes (so its printed values apply to it)."""
    pose = file_pose_angle(sol.mechanism)
    return pose is None or sol.driver_angle is None or abs(_angle_diff(sol.driver_angle, pose)) < 1e-9


def _printed(v):
    """A printed value as _row reads it: a vector [magnitude, direction] as a list, a magnitude as a number."""
    return list(v) if isinstance(v, (list, tuple)) else v


def compare(sol) -> list[Row]:
    """Every ``[reference]`` value beside the analytic one, in the file's order."""
    m = sol.mechanism
    ref = m.reference
    scales = kind_scales(sol)
    rows = []
    for lk, v in ref.omega.items():
        rows.append(_row(f"omega_{lk}", v, sol.omega[lk], note_for(ref, f"omega_{lk}"), scales["omega"]))
    for lk, v in ref.alpha.items():
        rows.append(_row(f"alpha_{lk}", v, sol.alpha[lk], note_for(ref, f"alpha_{lk}"), scales["alpha"]))
    for p, v in ref.speed.items():
        rows.append(_row(f"|V_{p}|", v, evaluate(sol, parse_key(m, f"V_{p}") or Quantity("V", ((p, None),))),
                         note_for(ref, f"|V_{p}|"), scales["V"]))
    for p, v in ref.velocity.items():   # [magnitude, direction], or a bare magnitude
        rows.append(_row(f"V_{p}", _printed(v), evaluate(sol, parse_key(m, f"V_{p}") or Quantity("V", ((p, None),))),
                         note_for(ref, f"V_{p}"), scales["V"]))
    for p, v in ref.acceleration.items():
        rows.append(_row(f"A_{p}", _printed(v), evaluate(sol, parse_key(m, f"A_{p}") or Quantity("A", ((p, None),))),
                         note_for(ref, f"A_{p}"), scales["A"]))
    for key, v in ref.values.items():
        q = parse_key(m, key)
        value = evaluate(sol, q)
        if q.kind == "P" and isinstance(v, (list, tuple)) and value is not None:
            # a pole's position is printed as [x, y]: its distance from it, relative to the printed
            # position's distance from the origin (the mechanism's size for a pole printed there)
            d = float(np.hypot(value[0] - v[0], value[1] - v[1]))
            rows.append(Row(key, (float(v[0]), float(v[1])), (float(value[0]), float(value[1])),
                            d / (float(np.hypot(*v)) or scales["P"]), None, note_for(ref, key)))
            continue
        rows.append(_row(key, _printed(v), value, note_for(ref, key), scale_of(q.kind, scales)))
    return rows


def display_key(m, key: str) -> str:
    """A ``[reference]`` key as the tables show it (:mod:`velpoly.names`): each point of a named link with
    the link as its subscript, ``V_Pcam`` -> ``V_P(cam)``, ``|V_P@2|`` -> ``|V_P₂|``, ``V_B3/B4`` ->
    ``V_B₃/B₄`` (a point named B3 stays B3); a key that names no point (``omega_3``, ``P_13``) as written.
    The key itself (what a note is keyed by) stays as the file writes it."""
    from .names import place, relative
    bars = key.startswith("|") and key.endswith("|")
    body = key[1:-1] if bars else key
    mo = re.fullmatch(r"([VAR](?:\^[ntcs])?)_(.+)", body)
    if not mo or parse_key(m, body) is None or parse_key(m, body).kind not in "VAR":
        return key
    head, idx = mo.groups()
    if "/" in idx:
        a, _, b = idx.partition("/")
        ra, rb = _point_refs(m, a, 1), _point_refs(m, b, 1)
        refs = None if not (ra and rb) else [ra[0], rb[0]]
        shown = None if refs is None else relative(place(*refs[0]), place(*refs[1]))
    else:
        refs = _point_refs(m, idx, 1) or _point_refs(m, idx, 2)
        shown = None if refs is None else "".join(place(*r) for r in refs)
    if shown is None:
        return key
    out = f"{head}_{shown}"
    return f"|{out}|" if bars else out
