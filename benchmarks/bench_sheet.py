"""One full A4 sheet to PNG in process (`draw_to_file`), against the code before, with where the time goes.

    python benchmarks/bench_sheet.py [--repeats 5] [--json OUT] [--file MECHANISM.toml] [--before COMMIT]

The six-bar's full sheet (``velpoly/examples/problem_1_4_4_sixbar.toml``, textbook style, 200 dpi):
``velpoly.render.draw_to_file(sol, "sheet.png")`` in a warm process (imported, one sheet drawn
before: what a notebook or the gallery's workers see), the solution fresh each time (its
constructions are built in the time). Side by side in rounds, each in a fresh process of its own,
best of ``--repeats`` sheets each:

* now:    this checkout (target, issue 20: under 0.5 s);
* before: the velpoly of ``--before`` (default: the commit before issue 20's work), exported from git;
* now, fresh / before, fresh: the same, the process warmed by another example's sheet (the crank and
  slider) instead: the six-bar's sheet drawn for the first time in the process, as in a gallery worker
  (velpoly keeps text measures and glyphs per process, velpoly/render/textcache.py: a sheet drawn again
  finds all of them, a fresh one those its texts share with the sheets before).

Both PNGs are decoded and compared first: the same pixels (the files differ: velpoly now writes an
opaque sheet as RGB, its rows unfiltered, velpoly/render/pngfile.py), or a note says they differ (figure work changes sheets on
purpose; before / now then times two different drawings). Then, in this process, the parts of the time: the figure built
(``render_sheet``: layout, text measured at 72 dpi), the Agg canvas drawn at 200 dpi, and the PNG
encoded, by matplotlib's writer and by velpoly's (velpoly/render/pngfile.py).
"""
from __future__ import annotations

import io
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _common import ROOT, export, file_before_arguments, finish, row

TIMER = r'''
import json, sys, time
import velpoly
from velpoly.render import draw_to_file
m = velpoly.load(sys.argv[1])
out, repeats = sys.argv[2], int(sys.argv[3])
warm = velpoly.load(sys.argv[4]) if len(sys.argv) > 4 else m   # another example: this sheet drawn fresh
draw_to_file(velpoly.solve(warm), out, sheet="full")  # warm: the imports, fonts, the mathtext parser
wall = cpu = float("inf")
for _ in range(repeats):
    sol = velpoly.solve(m)
    t0, c0 = time.perf_counter(), time.process_time()
    draw_to_file(sol, out, sheet="full")
    wall, cpu = min(wall, time.perf_counter() - t0), min(cpu, time.process_time() - c0)
print(json.dumps({"wall": wall, "cpu": cpu}))
'''


def pixels(path: Path):
    import numpy as np
    from PIL import Image
    with Image.open(path) as im:
        return np.asarray(im.convert("RGBA"))


def parts(path: str, repeats: int) -> dict:
    """CPU seconds of the parts of one sheet, best of ``repeats``, in this process."""
    import velpoly
    from velpoly.render.pngfile import save_png
    from velpoly.render.sheet import constructions, render_sheet
    from velpoly.render.style import get_style, rc_context
    st = get_style("textbook")
    m = velpoly.load(path)
    best: dict = {}

    def keep(name, c0):
        best[name] = min(best.get(name, float("inf")), time.process_time() - c0)

    for _ in range(repeats + 1):              # the first round warms up and is dropped
        sol = velpoly.solve(m)
        c0 = time.process_time()
        cons = constructions(sol, "full")
        keep("constructions (polygons, poles)", c0)
        with rc_context(st):
            c0 = time.process_time()
            fig = render_sheet(sol, "full", st, cons=cons)
            keep("figure built (render_sheet)", c0)
            c0 = time.process_time()
            fig.savefig(io.BytesIO(), format="rgba", dpi=st.dpi)
            keep("Agg canvas drawn at 200 dpi", c0)
            c0 = time.process_time()
            fig.savefig(io.BytesIO(), format="png", dpi=st.dpi, metadata={})
            keep("drawn + matplotlib's PNG writer", c0)
            c0 = time.process_time()
            save_png(fig, io.BytesIO(), st.dpi)
            keep("drawn + velpoly's PNG writer", c0)
        if _ == 0:
            best.clear()
    return best


def main(argv=None) -> int:
    args = file_before_arguments(__doc__, argv)
    notes: list[str] = []
    with tempfile.TemporaryDirectory(prefix="velpoly-bench-sheet-") as tmp:
        tmp = Path(tmp)
        old = export(args.before, tmp / "before")
        who = {"now": ROOT} | ({"before": old} if old is not None else {})
        other = str(ROOT / "velpoly" / "examples" / "crank_slider.toml")
        runs = {k: (w, []) for k, w in who.items()} | {f"{k}, fresh": (w, [other]) for k, w in who.items()}
        if old is None:
            notes.append(f"commit {args.before} not available (git archive failed): no 'before'")
        best = {k: {"wall": float("inf"), "cpu": float("inf")} for k in runs}
        for _ in range(args.repeats):                 # side by side: one process of each a round
            for name, (where, extra) in runs.items():
                png = tmp / f"{name.replace(', ', '-')}.png"
                proc = subprocess.run([sys.executable, "-c", TIMER, args.file, str(png), "1", *extra],
                                      capture_output=True, text=True, env=dict(os.environ, PYTHONPATH=str(where)),
                                      cwd=tmp)   # not the checkout: python -c puts the folder first on the path
                if proc.returncode:
                    raise SystemExit(f"the velpoly of {where} failed: {proc.stderr.strip()[-300:]}")
                got = json.loads(proc.stdout)
                for k in ("wall", "cpu"):
                    best[name][k] = min(best[name][k], got[k])
        if old is not None:
            import numpy as np
            sizes = {k: (tmp / f"{k}.png").stat().st_size for k in who}
            same = np.array_equal(pixels(tmp / "now.png"), pixels(tmp / "before.png"))
            if not same:   # the figure work changes sheets on purpose: then before / now times two drawings
                print(f"the sheet of {args.before} and of this checkout differ in their pixels", file=sys.stderr)
            notes.append((f"the same pixels as {args.before}'s PNG" if same else
                          f"NOT the same pixels as {args.before}'s PNG (the sheets changed since, on purpose): "
                          f"before / now compares two different drawings") +
                         f"; file {sizes['now'] / 1e3:.0f} KB (before {sizes['before'] / 1e3:.0f} KB)" +
                         ("; the same bytes, drawn again and drawn fresh" if len({(tmp / f"{k}.png").read_bytes()
                          for k in ("now", "before", "now-fresh", "before-fresh")}) == 1 else ""))
    split = parts(args.file, args.repeats)
    print(f"{Path(args.file).name}, full sheet to PNG in a warm process, best of {args.repeats}:")
    for name, b in best.items():
        print(f"  {name:14s} {b['wall']:.3f} s wall, {b['cpu']:.3f} s CPU")
    print("where the time goes (CPU, this process, best of each):")
    for name, t in split.items():
        print(f"  {name:34s} {t:.3f} s")
    now = best["now"]
    fresh = best["now, fresh"]
    rows = [row("sheet to PNG in process: velpoly draw_to_file, full sheet", now["wall"], "s", "< 0.5 s",
                now["wall"] < 0.5),
            row("sheet to PNG in process: CPU time", now["cpu"], "s", "< 0.5 s", now["cpu"] < 0.5,
                "less sensitive to other load"),
            row("sheet to PNG in process, drawn fresh (after another example): CPU", fresh["cpu"], "s", "< 0.5 s",
                fresh["cpu"] < 0.5, "its first drawing in the process")]
    if "before" in best:
        rows += [row(f"sheet to PNG before ({args.before})", best["before"]["wall"], "s"),
                 row("sheet to PNG: before / now (CPU)", best["before"]["cpu"] / now["cpu"], "x",
                     note="same pixels" if same else "other pixels: the sheets changed since"),
                 row(f"sheet to PNG drawn fresh, before ({args.before}): CPU", best["before, fresh"]["cpu"], "s"),
                 row("sheet to PNG drawn fresh: before / now (CPU)", best["before, fresh"]["cpu"] / fresh["cpu"], "x")]
    rows += [row(f"sheet part: {k}", v, "s") for k, v in split.items()]
    return finish("sheet", args, rows, notes)


if __name__ == "__main__":
    sys.exit(main())
