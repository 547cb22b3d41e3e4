"""The ``[links]`` table: each link's points (the first two give its angle) and the one frame."""
from __future__ import annotations

import numpy as np

from ..model import Link
from .context import Ctx, check_keys, named_entries, show, table

__all__ = ["read_links"]


def read_links(ctx: Ctx, data: dict) -> None:
    """Every link of ``[links]`` into ``ctx.links``, and which links list each point into ``ctx.listed``;
    exactly one link is the frame."""
    for lname, spec in named_entries(ctx, "links", table(ctx, data, "links"), "link"):
        ctx.links.append(_link(ctx, lname, spec))
    frames = [k for k in ctx.links if k.frame]
    if not frames:
        raise ctx.err("links", "no link is the frame", hint="mark exactly one link with frame = true")
    if len(frames) > 1:
        raise ctx.err(f"links.{frames[1].name}", "two or more links are the frame: " +
                      ", ".join(k.name for k in frames), hint="mark exactly one link with frame = true")
    for k in ctx.links:
        for p in k.points:
            ctx.listed.setdefault(p, []).append(k.name)


def _link(ctx: Ctx, lname: str, spec) -> Link:
    """One link: ``{ points = ["A", "B", ...], frame = true }``."""
    where = f"links.{lname}"
    if lname in ctx.pts:
        raise ctx.err(where, f"{lname!r} names both a point and a link",
                      hint="give links numbers and points letters, as textbooks do")
    if not isinstance(spec, dict):
        raise ctx.err(where, f"expected {{ points = [...] }}, got {show(spec)}",
                      hint=f'{lname} = {{ points = ["A", "B"] }}')
    check_keys(ctx, where, spec, ("points", "frame"))
    lp = spec.get("points")
    if not isinstance(lp, list) or not lp:
        raise ctx.err(where + ".points", "expected a non-empty list of point names" +
                      ("" if lp is None else f", got {show(lp)}"),
                      hint=f'{lname} = {{ points = ["A", "B"] }}: the points fixed to the link')
    names: list[str] = []
    for p in lp:
        p = ctx.point_ref(where + ".points", p)
        if p in names:
            raise ctx.err(where + ".points", f"point {p!r} is listed twice", hint="list each point once")
        names.append(p)
    frame = spec.get("frame", False)
    if not isinstance(frame, bool):
        raise ctx.err(where + ".frame", f"expected true or false, got {show(frame)}",
                      hint="frame = true marks the fixed link")
    pts = ctx.pts
    if len(names) >= 2 and np.hypot(*(pts[names[0]] - pts[names[1]])) <= 1e-12 * ctx.size:
        raise ctx.err(where + ".points", f"its first two points {names[0]!r} and {names[1]!r} coincide, "
                      "so the link's angle is undefined",
                      hint="a link's angle is the direction from its first point to its second: "
                           "list two points that are apart first")
    return Link(lname, tuple(names), frame)
