"""Measure the labels of the polygon panels and their details on generated full sheets (issue 17, items 3 and 4).

    PYTHONPATH=. python3 benchmarks/detail_labels.py [--seed 2026] [--count 60] [--styles textbook,slides]
                                                     [--only 3,55] [--far] [--json OUT]

For every full sheet of ``zoo(seed, count)`` (tests/zoo.py) in each style, every velocity and acceleration
panel is read back from its artists after ``draw_without_rendering`` (on the canvas, in pixels): each label of
an image or of the origin (gids ``label-*``, and ``detail-label-*`` in a detail), its outline as the renderer
lays it out shrunk by a pixel, against

- ``line``: every vector (shaft and arrowhead) and construction line of its own axes, as drawn (clipped to the
  axes: a detail's long vectors leave its frame), its own leader excepted;
- ``cut``: the edge of the axes it is drawn in (a detail's label outside the detail's inset, a panel's label
  outside its panel) and the detail's frame (a panel's label on the frame or inside it, a detail's label on
  the frame's rule as drawn, within a pixel: a glyph touching it reads as cut);
- ``text``: every other text of its panel and of the panel's detail (labels, reasons, the caption, the scale
  bar's numbers).

``--far``: instead, both polygons of generated six- and eight-bars given a point far out on one link (``--seed
1777``: the suite's tests/test_detail_labels.py draws three of them), each drawn alone in a panel.

Prints one line per panel with any count above zero, then the totals split by panels with and without a detail.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

POLYGONS = ("velocity", "acceleration")


def measure(fig) -> list[dict]:
    """One row per polygon panel of ``fig``: its name, whether it has a detail, its labels and what they meet
    (tests/test_detail_labels.py's ``label_clashes``)."""
    from test_detail_labels import label_clashes
    return [{"panel": ax.get_label(), "detail": any(p.get_gid() == "detail-frame" for p in ax.patches),
             **label_clashes(ax)} for ax in fig.axes if ax.get_label() in POLYGONS]


def sheets(args):
    """(index, kind, style, rows) of every full sheet of ``zoo(seed, count)`` in each style."""
    import velpoly
    from velpoly.errors import VelpolyError
    from velpoly.render import sheet
    from velpoly.render.style import get_style, rc_context
    from zoo import zoo
    only = {int(i) for i in args.only.split(",") if i}
    for i, sp in enumerate(zoo(args.seed, args.count)):
        if only and i not in only:
            continue
        try:
            sol = velpoly.solve(velpoly.load(sp.mech))
        except VelpolyError:
            continue
        for style in args.styles.split(","):
            with rc_context(get_style(style)):
                fig = sheet.render(sol, "full", get_style(style)).figure
                fig.draw_without_rendering()
                yield i, sp.kind, style, measure(fig)


FAR = (("eight-bar", "stephenson III + dyad"), ("six-bar", None), ("eight-bar", "watt II + dyad"),
       ("slot", "straight six-bar"), ("eight-bar", "watt II + dyad to crank"), ("six-bar", None))


def far(args):
    """(index, kind, style, rows) of both polygons of six- and eight-bars (:data:`FAR`, drawn from
    ``default_rng(seed)``) with a point 8 to 30 sizes out on one link, each drawn alone in the panels of
    tests/test_detail.py (in turn), in each style: crushed polygons, nearly all with a detail."""
    import numpy as np
    import velpoly
    import zoo
    from test_detail import PANELS, _far_point
    from test_detail_labels import _drawn
    from velpoly.polygons import acceleration_polygon, velocity_polygon
    rng = np.random.default_rng(args.seed)
    for n, (kind, variant) in enumerate(FAR):
        sp = zoo.specimen(rng, kind, variant)
        sol = velpoly.solve(velpoly.load(_far_point(sp.mech, rng, far=(8.0, 15.0, 30.0))))
        for poly in (velocity_polygon(sol), acceleration_polygon(sol)):
            for style in args.styles.split(","):
                ax, _ = _drawn(sol, poly, style, PANELS[n % len(PANELS)])
                ax.set_label(poly.kind)
                yield n, sp.kind, style, measure(ax.figure)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--count", type=int, default=60)
    ap.add_argument("--styles", default="textbook,slides")
    ap.add_argument("--only", default="")
    ap.add_argument("--far", action="store_true", help="generated crushed polygons drawn alone (seed 1777 in the suite)")
    ap.add_argument("--json", default="")
    args = ap.parse_args(argv)
    out = []
    t0 = time.process_time()
    for i, kind, style, rows in (far(args) if args.far else sheets(args)):
        for row in rows:
            row.update(index=i, kind=kind, style=style)
            out.append(row)
            if row["line"] or row["cut"] or row["text"]:
                print(f"{i:3d} {style:8s} {row['panel']:12s} detail={row['detail']!s:5s} "
                      f"line={len(row['line'])} cut={len(row['cut'])} text={len(row['text'])} "
                      f"{row['line'] + row['cut'] + row['text']}", flush=True)
    for has in (True, False):
        rows = [r for r in out if r["detail"] == has]
        print(f"panels {'with' if has else 'without'} a detail: {len(rows)} panels, "
              f"{sum(r['labels'] for r in rows)} panel labels, {sum(r['detail_labels'] for r in rows)} detail labels; "
              f"on a line {sum(len(r['line']) for r in rows)}, cut {sum(len(r['cut']) for r in rows)}, "
              f"on a text {sum(len(r['text']) for r in rows)}")
        for style in args.styles.split(","):
            rs = [r for r in rows if r["style"] == style]
            print(f"   {style}: {len(rs)} panels; on a line {sum(len(r['line']) for r in rs)}, "
                  f"cut {sum(len(r['cut']) for r in rs)}, on a text {sum(len(r['text']) for r in rs)}")
    print(f"{time.process_time() - t0:.1f} CPU s")
    if args.json:
        Path(args.json).write_text(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
