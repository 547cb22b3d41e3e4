"""`velpoly draw --sheet full` against a bare matplotlib process drawing as much.

    python benchmarks/bench_draw.py [--repeats 5] [--json OUT] [--file MECHANISM.toml]

Both are timed as whole processes (start-up, imports, drawing, saving), side
by side, best of ``--repeats``:

* velpoly: ``velpoly draw FILE --sheet full -o OUT.svg`` (default FILE: the
  six-bar example);
* before:  the same command with the velpoly of ``--before`` (default: the commit before issue 20's
  work), exported from git;
* bare:    a Python process that imports matplotlib and saves, for each SVG
  velpoly wrote, a figure of the same size with as many drawn paths (one
  two-point line each) and the same texts (the strings matplotlib records in
  the SVG, so mathtext is typeset alike), in the same SVG font mode.

The counts are read back from both SVGs and printed, so the comparison can be
checked. Targets: velpoly at most 2x the bare process (issue 8); the command under 1.2 s (issue
20). Every process runs with its bytecode cached (in the temporary folder, filled by one untimed
run of each), as an installed velpoly has it, even where PYTHONDONTWRITEBYTECODE is set. If
``velpoly draw`` fails (velpoly/render/ is being written), the benchmark is
skipped with a note.
"""
from __future__ import annotations

import html
import json
import resource
import re
import subprocess
import sys
import tempfile
from pathlib import Path

from _common import BEFORE, ROOT, bytecode_env, export, finish, parser, row, run_timed

BARE = r'''
import json, sys
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
for spec in json.load(open(sys.argv[1])):
    plt.rcParams["svg.fonttype"] = spec["fonttype"]
    fig = plt.figure(figsize=(spec["width"] / 72.0, spec["height"] / 72.0))
    ax = fig.add_axes([0, 0, 1, 1])
    ax.set_axis_off()
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    rng = np.random.default_rng(0)
    for x, y in rng.uniform(0.05, 0.95, (max(spec["paths"] - 1, 0), 2, 2)):   # - the figure's patch
        ax.plot(x, y, color="k", lw=0.8)
    for (x, y), s in zip(rng.uniform(0.05, 0.9, (len(spec["texts"]), 2)), spec["texts"]):
        ax.text(x, y, s, fontsize=9)
    fig.savefig(spec["out"])
    plt.close(fig)
'''

# a text artist: <g id="text_N">, then either the comment matplotlib writes with the string
# (mathtext, or any text in font mode "path") or a <text> element (plain text in font mode "none")
_TEXT = re.compile(r'<g id="text_\d+">\s*(?:<!-- (.*?) -->|<text\b[^>]*>(.*?)</text>)', re.S)


def svg_counts(path: Path) -> dict:
    """Size (pt), drawn paths (not definitions), texts and SVG font mode of a matplotlib SVG."""
    svg = path.read_text()
    m = re.search(r'<svg[^>]*\bwidth="([\d.]+)pt"[^>]*\bheight="([\d.]+)pt"', svg)
    width, height = (float(m.group(1)), float(m.group(2))) if m else (432.0, 288.0)
    paths = len(re.findall(r"<path\b(?![^>]*\bid=)", svg))     # definitions (glyphs, markers) have ids
    texts = [html.unescape(c if c else re.sub(r"<[^>]+>", "", t)).strip() for c, t in _TEXT.findall(svg)]
    fonttype = "none" if "<text" in svg else "path"
    return {"width": width, "height": height, "paths": paths, "texts": texts, "fonttype": fonttype}


def cpu_run(cmd, **kw):
    """(wall seconds, CPU seconds of the process, CompletedProcess) of one run."""
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t, proc = run_timed(cmd, 1, **kw)
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return t, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime), proc


def main(argv=None) -> int:
    p = parser(__doc__.splitlines()[0])
    p.add_argument("--file", help="mechanism file to draw (default: velpoly/examples/problem_1_4_4_sixbar.toml)")
    p.add_argument("--before", default=BEFORE, help="the commit to compare with (default %(default)s)")
    args = p.parse_args(argv)
    import velpoly
    notes: list[str] = []
    mech = Path(args.file) if args.file else Path(velpoly.__file__).parent / "examples" / "problem_1_4_4_sixbar.toml"
    mech = mech.resolve()
    base_cmd = [sys.executable, "-m", "velpoly"]   # this checkout (PYTHONPATH), not an installed script
    target_row = lambda value, met, note="": row("draw --sheet full: velpoly / bare matplotlib",  # noqa: E731
                                                  value, "x", "<= 2x", met, note)
    with tempfile.TemporaryDirectory(prefix="velpoly-bench-draw-") as tmp:
        tmp = Path(tmp)
        out = tmp / "velpoly.svg"
        cmd = base_cmd + ["draw", str(mech), "--sheet", "full", "-o", str(out)]
        env = bytecode_env(tmp, PYTHONPATH=str(ROOT))
        old = export(args.before, tmp / "before")
        old_cmd = base_cmd + ["draw", str(mech), "--sheet", "full", "-o", str(tmp / "before.svg")]
        old_env = bytecode_env(tmp, PYTHONPATH=str(old)) if old is not None else None
        if old is None:
            notes.append(f"commit {args.before} not available (git archive failed): no 'before'")
        proc = subprocess.run(cmd, capture_output=True, text=True, cwd=tmp, env=env)   # also fills the cache
        if proc.returncode != 0:
            why = (proc.stderr.strip().splitlines() or ["no message"])[0]
            notes.append(f"skipped: `velpoly draw --sheet full` exits {proc.returncode} ({why}); "
                         "velpoly/render/ is being written")
            print(f"velpoly draw failed: {why}")
            return finish("draw", args, [target_row(None, None, "skipped: velpoly draw fails")], notes)
        written = [Path(s) for s in proc.stdout.split("\n") if s.strip() and Path(s.strip()).is_file()]
        written = [w for w in written if w.suffix == ".svg"] or [out]
        specs = []
        for i, w in enumerate(written):
            spec = svg_counts(w)
            spec["out"] = str(tmp / f"bare_{i}.svg")
            specs.append(spec)
        (tmp / "spec.json").write_text(json.dumps(specs))
        (tmp / "bare.py").write_text(BARE)
        bare_cmd = [sys.executable, str(tmp / "bare.py"), str(tmp / "spec.json")]

        subprocess.run(bare_cmd, capture_output=True, cwd=tmp, env=env)          # untimed: fills the cache
        if old is not None:
            subprocess.run(old_cmd, capture_output=True, cwd=tmp, env=old_env)
        times = {"velpoly": float("inf"), "bare": float("inf")} | ({"before": float("inf")} if old else {})
        cpu = dict(times)
        for _ in range(args.repeats):            # side by side, round-robin
            t, c, proc = cpu_run(cmd, cwd=tmp, env=env)
            times["velpoly"], cpu["velpoly"] = min(times["velpoly"], t), min(cpu["velpoly"], c)
            if old is not None:
                t, c, proc_o = cpu_run(old_cmd, cwd=tmp, env=old_env)
                times["before"], cpu["before"] = min(times["before"], t), min(cpu["before"], c)
            t, c, proc_b = cpu_run(bare_cmd, cwd=tmp, env=env)
            cpu["bare"] = min(cpu["bare"], c)
            if proc_b.returncode != 0:
                raise SystemExit(f"the bare matplotlib process failed: {proc_b.stderr.strip()}")
            times["bare"] = min(times["bare"], t)

        print(f"{mech.name}: velpoly draw --sheet full wrote {len(written)} SVG file(s)")
        for spec in specs:
            got = svg_counts(Path(spec["out"]))
            print(f"  {spec['width']:g} x {spec['height']:g} pt, font mode {spec['fonttype']}: "
                  f"velpoly {spec['paths']} paths, {len(spec['texts'])} texts; "
                  f"bare {got['paths']} paths, {len(got['texts'])} texts")
    print(f"wall time, best of {args.repeats} runs of each process:")
    print(f"  velpoly draw      {times['velpoly']:.3f} s   (CPU {cpu['velpoly']:.3f} s)")
    if "before" in times:
        print(f"  before ({args.before})  {times['before']:.3f} s   (CPU {cpu['before']:.3f} s)")
    print(f"  bare matplotlib   {times['bare']:.3f} s   (CPU {cpu['bare']:.3f} s)")
    ratio = times["velpoly"] / times["bare"]
    rows = [row("draw --sheet full: velpoly (the whole command)", times["velpoly"], "s", "< 1.2 s",
                times["velpoly"] < 1.2),
            row("draw --sheet full: bare matplotlib, same paths and texts", times["bare"], "s"),
            target_row(ratio, ratio <= 2),
            row("draw --sheet full: velpoly, CPU seconds (user + sys)", cpu["velpoly"], "s", "< 1.2 s",
                cpu["velpoly"] < 1.2, "less sensitive to other load than the wall time")]
    if "before" in times:
        rows += [row(f"draw --sheet full: before ({args.before})", times["before"], "s"),
                 row("draw --sheet full: before / now", times["before"] / times["velpoly"], "x")]
    return finish("draw", args, rows, notes)


if __name__ == "__main__":
    sys.exit(main())
