"""The ``[[contacts]]`` table: two links touching at a point, rolling or sliding (higher pairs).

The profiles are given by their centres of curvature (``centres = ["Ca", "Cb"]``, ``"flat"`` for a
straight one; the point lies on the line of centres) or by the common normal's direction (``normal``).
"""
from __future__ import annotations

import numpy as np

from ..model import Contact
from .context import Ctx, array_of_tables, check_keys, length, read_number, show

__all__ = ["read_contacts"]


def read_contacts(ctx: Ctx, data: dict) -> list[Contact]:
    """Every contact; its point rides both links as a coincident point (carried, no pin)."""
    return [_contact(ctx, f"contacts[{i}]", c) for i, c in enumerate(array_of_tables(ctx, data, "contacts"))]


def _contact(ctx: Ctx, where: str, c: dict) -> Contact:
    check_keys(ctx, where, c, ("links", "point", "kind", "slip", "centres", "normal"))
    if "links" not in c or not isinstance(c["links"], list) or len(c["links"]) != 2:
        raise ctx.err(where + ".links", "expected links = [\"a\", \"b\"]" +
                      (f", got {show(c['links'])}" if "links" in c else ""),
                      hint="the two links that touch")
    a, b = ctx.link_ref(where + ".links", c["links"][0]), ctx.link_ref(where + ".links", c["links"][1])
    if a == b:
        raise ctx.err(where + ".links", f"a contact needs two different links, got {a!r} twice",
                      hint="the two links that touch")
    ctx.require(where, c, ("point",), 'point = "P": the contact point, defined in [points]')
    p = ctx.point_ref(where + ".point", c["point"])
    kind = c.get("kind")
    if kind not in ("rolling", "sliding"):
        raise ctx.err(where + ".kind", "expected \"rolling\" or \"sliding\"" +
                      (f", got {show(kind)}" if "kind" in c else " (kind is missing)"),
                      hint="rolling: no slip; sliding: slip along the common tangent")
    slip = None
    if "slip" in c:
        if kind != "sliding":
            raise ctx.err(where + ".slip", "a prescribed slip needs kind = \"sliding\"",
                          hint="a rolling contact has no slip: remove slip, or make it sliding")
        slip = read_number(ctx, where + ".slip", c["slip"])
    if ("centres" in c) == ("normal" in c):
        raise ctx.err(where, "give exactly one of 'centres' and 'normal'" +
                      (" (both are given)" if "normal" in c else ""),
                      hint="centres = [\"Ca\", \"Cb\"] (\"flat\" for a straight profile), or normal = deg")
    centres = normal = None
    if "centres" in c:
        centres = _contact_centres(ctx, where, c["centres"], (a, b), p)
    else:
        normal = read_number(ctx, where + ".normal", c["normal"])
    for lk in (a, b):
        if lk not in ctx.listed.get(p, []):
            ctx.owned.setdefault(p, []).append(lk)
        ctx.coincident.add((p, lk))
    return Contact((a, b), p, kind, slip, centres, normal)


def _contact_centres(ctx: Ctx, where: str, cs, owners: tuple[str, str], p: str):
    """A contact's centres of curvature, checked: each a point of its link (or "flat")."""
    w = where + ".centres"
    if not isinstance(cs, list) or len(cs) != 2:
        raise ctx.err(w, f"expected [\"Ca\", \"Cb\"], got {show(cs)}",
                      hint="the centres of curvature of the profiles of links a and b, \"flat\" for a straight one")
    pts = ctx.pts
    cc = []
    for cn, owner in zip(cs, owners):
        if cn == "flat":
            cc.append(None)
            continue
        cn = ctx.point_ref(w, cn)
        if cn == p or np.hypot(*(pts[cn] - pts[p])) == 0:
            raise ctx.err(w, f"centre {cn!r} is at the contact point: the profile has no radius",
                          hint="the centre of curvature is the centre of the profile's arc at the contact")
        cc.append(cn)
        if not ctx.carry(cn, owner):
            raise ctx.err(w, f"centre {cn!r} is not a point of link {owner!r}",
                          hint=f"the centres are in the order of links: list {cn!r} in links.{owner}")
    if cc[0] is None and cc[1] is None:
        raise ctx.err(w, "both profiles are flat", hint="a flat on a flat is a slider: use [[sliders]]")
    if cc[0] is not None and cc[1] is not None:
        A, B, P = pts[cc[0]], pts[cc[1]], pts[p]
        d = B - A
        if np.hypot(*d) == 0:
            raise ctx.err(w, "the two centres of curvature coincide",
                          hint="concentric profiles touch everywhere or nowhere")
        off = abs(d[0] * (P - A)[1] - d[1] * (P - A)[0]) / np.hypot(*d)
        if off > 1e-6 * ctx.size:
            raise ctx.err(where + ".point", f"the contact point is off the line of centres by {length(ctx, off)}",
                          hint="profiles touch on their common normal, the line through both centres "
                               "of curvature: put the point there")
    return tuple(cc)
