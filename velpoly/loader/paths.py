"""The ``[[sliders]]`` and ``[[slots]]`` tables, read by one function: a point of one link moves on a
path of another (a block on its guide, a pin in its slot).

The path is straight (``angle = deg``, or ``along = ["P", "Q"]``: the direction P -> Q at the reference
pose) or circular (``centre = "K"``, a point of the path's link); a straight slot may have ``ends``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..model import Slider, Slot
from .context import Ctx, array_of_tables, check_keys, coincide, direction, read_number, show

__all__ = ["read_sliders", "read_slots"]

_PATH_KEYS = ("angle", "along", "centre")


@dataclass(frozen=True)
class _PathJoint:
    """How one table names its parts (in the order they are read and checked) and words its errors."""
    table: str                 # "sliders"
    keys: tuple[str, ...]      # every key an entry may have
    parts: tuple[str, ...]     # the keys of the moving point, its link and the path's link, in reading order
    roles: tuple[str, ...]     # for each part: "point", "mover" (the point's link) or "path" (the path's link)
    example: str               # the hint when a part is missing
    same_link: str             # when mover and path are one link ({0!r}: the link)
    same_hint: str
    off_mover: str             # when the point is not on its link ({0!r}: the point, {1!r}: the link)
    off_hint: str              # ({0!r}: the point, {1}: the link)
    what: str                  # "path" or "slot", in messages


_SLIDERS = _PathJoint(
    "sliders", ("block", "guide", "point") + _PATH_KEYS, ("block", "guide", "point"), ("mover", "path", "point"),
    'a slider has block = "5", guide = "0", point = "F" and angle = deg (or along = ["P", "Q"], '
    'or centre = "K")',
    "block and guide are the same link {0!r}", "the block slides on another link, its guide",
    "point {0!r} is not a point of the block {1!r}", "list {0!r} in links.{1}", "path")
_SLOTS = _PathJoint(
    "slots", ("pin", "link", "slot") + _PATH_KEYS + ("ends",), ("pin", "link", "slot"), ("point", "mover", "path"),
    'a slot has pin = "P", link = "3" (carries the pin), slot = "4" and angle = deg (or '
    'along = ["P", "Q"], or centre = "K")',
    "the pin's link and the slot's link are the same link {0!r}", "the pin of one link slides in a slot of another",
    "point {0!r} is not a point of link {1!r}", "list it in links.{1}", "slot")


def read_sliders(ctx: Ctx, data: dict) -> list[Slider]:
    """Every ``[[sliders]]`` entry: a block's point on a path of its guide."""
    return [Slider(*_path_joint(ctx, _SLIDERS, i, s)) for i, s in enumerate(array_of_tables(ctx, data, "sliders"))]


def read_slots(ctx: Ctx, data: dict) -> list[Slot]:
    """Every ``[[slots]]`` entry: a link's pin in a slot of another link, with the slot's ends if given."""
    out = []
    for i, s in enumerate(array_of_tables(ctx, data, "slots")):
        link, slot, pin, ang, cen = _path_joint(ctx, _SLOTS, i, s)
        ends = _slot_ends(ctx, f"slots[{i}].ends", s["ends"], pin, slot, ang) if "ends" in s else None
        out.append(Slot(pin, link, slot, ang, cen, ends))
    return out


def _path_joint(ctx: Ctx, kind: _PathJoint, i: int, s: dict):
    """One slider or slot: (the moving link, the path's link, the point, the path's angle or None,
    the circular path's centre or None). The point rides the path's link as a coincident point."""
    where = f"{kind.table}[{i}]"
    check_keys(ctx, where, s, kind.keys)
    ctx.require(where, s, kind.parts, kind.example)
    got = {}
    for key, role in zip(kind.parts, kind.roles):
        ref = ctx.point_ref if role == "point" else ctx.link_ref
        got[role] = (ref(f"{where}.{key}", s[key]), key)
    (mover, _), (guide, guide_key), (p, p_key) = got["mover"], got["path"], got["point"]
    if mover == guide:
        raise ctx.err(f"{where}.{guide_key}", kind.same_link.format(mover), hint=kind.same_hint)
    if p not in ctx.link(mover).points:
        raise ctx.err(f"{where}.{p_key}", kind.off_mover.format(p, mover), hint=kind.off_hint.format(p, mover))
    ang = _path_angle(ctx, where, s, kind.what)
    cen = ctx.point_ref(where + ".centre", s["centre"]) if "centre" in s else None
    if cen is not None:
        _path_centre(ctx, where + ".centre", cen, p, guide, kind.what)
    if p in ctx.link(guide).points:
        ctx.coincident.add((p, guide))
    return mover, guide, p, ang, cen


def _path_angle(ctx: Ctx, where: str, entry: dict, what: str) -> float | None:
    """The direction (deg) of a slider's path or a slot: ``angle = deg``, or ``along = ["P", "Q"]``
    (from P to Q at the reference pose); None for a circular one (``centre``). Exactly one is given."""
    given = [k for k in _PATH_KEYS if k in entry]
    if len(given) != 1:
        raise ctx.err(where, f"give the {what} as exactly one of 'angle', 'along' and 'centre'" +
                      (f" ({' and '.join(given)} are given)" if given else ""),
                      hint=f"angle = deg or along = [\"P\", \"Q\"] (a straight {what}: the line P -> Q), "
                           f"or centre = \"K\" (a circular one)")
    if "angle" in entry:
        return read_number(ctx, where + ".angle", entry["angle"])
    if "centre" in entry:
        return None
    al, w = entry["along"], where + ".along"
    if not (isinstance(al, list) and len(al) == 2):
        raise ctx.err(w, f"expected [\"P\", \"Q\"], got {show(al)}",
                      hint=f"the {what} runs in the direction from P to Q (two points' names), e.g. [\"O4\", \"B\"]")
    ends = [ctx.pts[ctx.point_ref(w, name)] for name in al]
    if coincide(*ends):
        raise ctx.err(w, f"{str(al[0])!r} and {str(al[1])!r} coincide: no direction",
                      hint="name two points that are apart")
    return direction(*ends)


def _path_centre(ctx: Ctx, where: str, cen: str, p: str, guide: str, what: str) -> None:
    """A circular path's centre: a point of the guide (or listed in no link: the guide's)."""
    if np.hypot(*(ctx.pts[p] - ctx.pts[cen])) == 0:
        raise ctx.err(where, f"the {what}'s centre is the point {p!r} itself",
                      hint="the centre of a circular path is the centre of its arc")
    if not ctx.carry(cen, guide):
        raise ctx.err(where, f"the centre {cen!r} is not a point of link {guide!r}",
                      hint=f"a circular path turns with its link: list {cen!r} in links.{guide}, "
                           "or in no link")


def _slot_ends(ctx: Ctx, where: str, v, pin: str, slot: str, angle: float | None) -> tuple[str, str]:
    """A straight slot's ``ends = ["S1", "S2"]``: two points of the slot link (or listed in no link:
    the slot link's), apart along the slot, with the pin between them at the reference pose."""
    if not isinstance(v, list) or len(v) != 2:
        raise ctx.err(where, "give the slot's ends as two points", hint='ends = ["S1", "S2"]: two points of '
                      f"link {slot!r} at the ends of the slot")
    if angle is None:
        raise ctx.err(where, "only a straight slot has ends", hint="give the slot's path by angle = deg, "
                      "or leave out 'ends' (a circular slot is unbounded)")
    names = tuple(ctx.point_ref(f"{where}[{i}]", x) for i, x in enumerate(v))
    for i, n in enumerate(names):
        if not ctx.carry(n, slot):
            raise ctx.err(f"{where}[{i}]", f"the end {n!r} is not a point of the slot's link {slot!r}",
                          hint=f"a slot's ends are cut in its link: list {n!r} in links.{slot}, or in no link")
    pts = ctx.pts
    e = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
    s1, s2, p = (np.asarray(pts[n], float) for n in (*names, pin))
    length = float(np.dot(s2 - s1, e))
    size = max(float(np.ptp(np.array(list(pts.values()), float), axis=0).max()), 1e-300)
    if abs(length) <= 1e-9 * size:
        raise ctx.err(where, f"the ends {names[0]!r} and {names[1]!r} are not apart along the slot",
                      hint="the ends bound the slot along its path: two points at either end of it")
    t = float(np.dot(p - s1, e)) / length
    if not -1e-9 <= t <= 1 + 1e-9:
        raise ctx.err(where, f"the pin {pin!r} is not between the ends {names[0]!r} and {names[1]!r} of the slot "
                      f"in the drawn pose (it is {abs(min(t, 1 - t)) * abs(length):.6g} beyond "
                      f"{names[0] if t < 0 else names[1]!r})",
                      hint="draw the pin inside its slot, or give the slot's true ends")
    return names
