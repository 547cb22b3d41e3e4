"""Pole labels and their leaders over generated mechanisms (issue 17 item 4: "leaders never crossing").

Draws the poles sheet of every specimen of ``zoo(SEED, COUNT)`` (tests/zoo.py) in both styles, as
``velpoly draw --sheet poles`` does (without writing a file), and counts on each sheet's poles panel:

- ``crossed``: pairs of leaders that cross (a pole label's leader and any other leader), ``pairs``: their gids (the
  totals printed by the other label's kind: a pole's, a point's, a link number or the driver's value);
- ``through``: a pole label's leader across another text's box (its outline as laid out, no margin);
- ``nearer``: pole labels whose box is nearer another pole's ring than its own; ``bare_nearer``: of those, the
  ones with no leader to their own (which nothing tells from the other ring's);
- ``on_kennedy``: pole labels whose box (shrunk by a pixel) meets a Kennedy line; ``on_line``: any other line drawn;
- ``leaders``, ``reach``: the pole labels' leaders and their mean length (points).

Usage (from the checkout's root, PYTHONPATH=$PWD)::

    python3 benchmarks/leaders_zoo.py [--seed 2026] [--count 60] [--part 0/1] [--only 25-39,54-56] [--worst 8]
                                      [--json OUT]
"""
from __future__ import annotations

import argparse
import itertools
import json
import sys
import time
from pathlib import Path

import numpy as np
from shapely.geometry import LineString, Point, box

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

KEYS = ("crossed", "through", "nearer", "bare_nearer", "on_kennedy", "on_line", "leaders", "reach")


def panel_counts(ax, poles_at: dict) -> dict:
    """The counts (see the module's docstring) of one poles panel ``ax``, in display points (``poles_at``: each
    pole's key -> its position, data coordinates; its ring is 0.085 cm about it, a pin's too)."""
    from velpoly.render.canvas import renderer_of
    r = renderer_of(ax.figure)
    k = 72.0 / ax.figure.dpi
    texts = [t for t in ax.texts if t.get_text() and t.get_visible()]
    boxes = {id(t): box(*(np.array(t.get_window_extent(r).extents) * k)) for t in texts}
    poles = [t for t in texts if (t.get_gid() or "").startswith("label-pole-")]

    def xy(ln):
        return LineString(ax.transData.transform(np.column_stack(ln.get_data())) * k)
    leaders = {ln.get_gid()[:-len("-leader")]: xy(ln) for ln in ax.lines if (ln.get_gid() or "").endswith("-leader")}
    lines = [(ln.get_gid() or "", xy(ln)) for ln in ax.lines
             if not (ln.get_gid() or "").endswith("-leader") and ln.get_visible() and len(ln.get_xydata()) >= 2
             and np.isfinite(ln.get_xydata()).all()]
    view = ax.bbox.extents * k
    rings = {}
    for key, q in poles_at.items():
        x, y = ax.transData.transform(q) * k
        if view[0] <= x <= view[2] and view[1] <= y <= view[3]:
            rings[key] = Point(x, y).buffer(0.085 / 2.54 * 72.0)
    out = dict.fromkeys(KEYS, 0)
    out["pairs"] = []
    reach = []
    pole_gids = {t.get_gid() for t in poles}
    for a, b in itertools.combinations(sorted(leaders), 2):
        if (a in pole_gids or b in pole_gids) and leaders[a].intersects(leaders[b]):
            out["crossed"] += 1
            out["pairs"].append((a, b))
    for t in poles:
        gid = t.get_gid()
        b = boxes[id(t)]
        line = leaders.get(gid)
        if line is not None:
            out["leaders"] += 1
            reach.append(line.length)
            out["through"] += sum(1 for u in texts if u is not t and boxes[id(u)].intersects(line))
        key = gid[len("label-pole-"):]
        if key in rings and len(rings) > 1:
            own = b.distance(rings[key])
            if any(b.distance(g) < own for k2, g in rings.items() if k2 != key):
                out["nearer"] += 1
                out["bare_nearer"] += line is None
        inner = b.buffer(-k)   # a pixel in
        out["on_kennedy"] += any(ln.intersects(inner) for g, ln in lines if g.startswith("kennedy-line-"))
        out["on_line"] += any(ln.intersects(inner) for g, ln in lines if not g.startswith("kennedy-line-"))
    out["reach"] = float(np.mean(reach)) if reach else 0.0
    return out


def sheet_counts(sol, style: str) -> dict:
    """The counts of the poles sheet of ``sol`` in ``style`` (its poles panels together)."""
    from velpoly.poles import locate_poles
    from velpoly.render import sheet
    from velpoly.render.style import get_style, rc_context
    with rc_context(get_style(style)):
        fig = sheet.render(sol, "poles", get_style(style)).figure
        fig.draw_without_rendering()
        at = {p.key: p.position for p in locate_poles(sol).poles.values() if p.position is not None}
        got = [panel_counts(ax, at) for ax in fig.axes if any((t.get_gid() or "").startswith("label-pole-")
                                                            for t in ax.texts)]
    out = {k: sum(g[k] for g in got) for k in KEYS if k != "reach"}
    out["pairs"] = [p for g in got for p in g["pairs"]]
    out["reach"] = float(np.mean([g["reach"] for g in got if g["leaders"]])) if any(g["leaders"] for g in got) else 0.0
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--count", type=int, default=60)
    ap.add_argument("--part", default="0/1", help="i/n: only the specimens whose index is i modulo n")
    ap.add_argument("--only", help="comma-separated specimen indices (e.g. the crowded ones: 25-39,43,44,54-56)")
    ap.add_argument("--styles", default="textbook,slides")
    ap.add_argument("--worst", type=int, default=8, help="list the worst sheets")
    ap.add_argument("--json", help="write every sheet's counts here")
    a = ap.parse_args()
    import velpoly
    from zoo import zoo
    i0, n = map(int, a.part.split("/"))
    only = None
    if a.only:
        only = set()
        for part in a.only.split(","):
            lo, _, hi = part.partition("-")
            only.update(range(int(lo), int(hi or lo) + 1))
    rows = []
    t0 = time.process_time()
    for i, sp in enumerate(zoo(a.seed, a.count)):
        if i % n != i0 or (only is not None and i not in only):
            continue
        sol = velpoly.solve(velpoly.load(sp.mech))
        for style in a.styles.split(","):
            try:
                c = sheet_counts(sol, style)
            except Exception as e:   # a specimen that does not draw is reported, not counted
                print(f"{i} {sp.kind} {style}: {type(e).__name__}: {e}", file=sys.stderr)
                continue
            rows.append({"index": i, "kind": sp.kind, "style": style, **c})
    total = {k: sum(r[k] for r in rows) for k in KEYS if k != "reach"}
    lead = [r for r in rows if r["leaders"]]
    total["reach"] = round(sum(r["reach"] * r["leaders"] for r in lead) / max(sum(r["leaders"] for r in lead), 1), 1)
    print(f"{len(rows)} sheets, {time.process_time() - t0:.0f} CPU s")
    print("  ".join(f"{k} {v}" for k, v in total.items()))
    print("sheets with a crossing:", sum(1 for r in rows if r["crossed"] or r["through"]))
    kinds = [" and ".join(sorted(g.split("-")[1] if g.startswith("label-") else g.rstrip("-0123456789") for g in p))
             for r in rows for p in r["pairs"]]
    print("crossed with:", ", ".join(f"{k} {kinds.count(k)}" for k in sorted(set(kinds))))
    for r in sorted(rows, key=lambda r: -(2 * r["crossed"] + 2 * r["through"] + r["nearer"] + r["on_kennedy"]))[:a.worst]:
        print("  ", r)
    if a.json:
        Path(a.json).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
