"""`velpoly gallery`: all the built-in examples' sheets, in worker processes, against one process.

    python benchmarks/bench_gallery.py [--repeats 2] [--json OUT] [--animations] [--before COMMIT]

Whole processes, side by side in rounds, best of ``--repeats`` (at most 2 by default: a round takes
a minute or more on a busy machine), wall time and the CPU time of the process and its workers:

* now:         ``velpoly gallery --source velpoly/examples -o OUT``: the 19 examples' sheets, each
  example drawn in a worker process (one a core), the files written by the command in order
  (target, issue 20: under 10 s on this 2-core machine);
* one process: the same build in one process, one example after another
  (``build_gallery(..., jobs=1)``); the output must be the same bytes as the command's;
* before:      the command of the velpoly of ``--before`` (default: the commit before issue 20's
  work), exported from git; its PNGs compared pixel for pixel (velpoly now writes them itself, as RGB,
  rows unfiltered: other bytes); a difference (after figure work, on purpose) is said in a note.

``--animations`` builds the repository's whole gallery instead (``velpoly gallery -o OUT``: the
sheets and one animated GIF a mechanism family, seven more tasks of 1-3 s each).
"""
from __future__ import annotations

import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _common import BEFORE, ROOT, bytecode_env, export, finish, parser, row

ONE = r'''
import sys
from pathlib import Path
from velpoly.gallery import build_gallery
source = None if sys.argv[1] == "-" else Path(sys.argv[1])
build_gallery(source, Path(sys.argv[2]), copy=True if source else None, animations=source is None, jobs=1)
'''


def timed(cmd, env, cwd) -> tuple[float, float, subprocess.CompletedProcess]:
    """Wall and CPU seconds (the process and its workers) of one run."""
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=cwd)
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime), proc


def files(folder: Path) -> dict:
    """Every file of a gallery folder, its README with the folder's own name taken out."""
    out = {}
    for p in sorted(folder.rglob("*")):
        if p.is_file():
            data = p.read_bytes()
            out[p.relative_to(folder).as_posix()] = data.replace(folder.parent.name.encode(), b"RUN")
    return out


def same_pixels(a: bytes, b: bytes) -> bool:
    import io

    import numpy as np
    from PIL import Image
    with Image.open(io.BytesIO(a)) as x, Image.open(io.BytesIO(b)) as y:
        return np.array_equal(np.asarray(x.convert("RGBA")), np.asarray(y.convert("RGBA")))


def main(argv=None) -> int:
    p = parser(__doc__.splitlines()[0])
    p.add_argument("--animations", action="store_true", help="the whole repository gallery, with its animations")
    p.add_argument("--before", default=BEFORE, help="the commit to compare with (default %(default)s)")
    p.set_defaults(repeats=None)
    args = p.parse_args(argv)
    repeats = args.repeats if args.repeats is not None else 2
    if args.repeats is not None and args.repeats > 2 and not args.animations:
        repeats = 2
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    notes = [f"best of {repeats} rounds; {cores} cores"]
    source = ROOT / "velpoly" / "examples"
    n = len(list(source.glob("*.toml")))
    src_args = [] if args.animations else ["--source", str(source)]
    with tempfile.TemporaryDirectory(prefix="velpoly-bench-gallery-") as tmp:
        tmp = Path(tmp)
        old = export(args.before, tmp / "before-code")
        if old is None:
            notes.append(f"commit {args.before} not available (git archive failed): no 'before'")
        env = bytecode_env(tmp, PYTHONPATH=str(ROOT))
        runs = {"now": ([sys.executable, "-m", "velpoly", "gallery"] + src_args, env),
                "one process": ([sys.executable, "-c", ONE, "-" if args.animations else str(source)], env)}
        if old is not None:
            own = [] if args.animations else ["--source", str(old / "velpoly" / "examples")]   # its own examples
            runs["before"] = ([sys.executable, "-m", "velpoly", "gallery"] + own, bytecode_env(tmp, PYTHONPATH=str(old)))
        best = {k: (float("inf"), float("inf")) for k in runs}
        built = {}
        for r in range(repeats):                      # side by side: one of each a round
            for name, (cmd, e) in runs.items():
                out = tmp / f"{name.replace(' ', '-')}-{r}" / "gallery-out"
                cmd = cmd + (["-o", str(out)] if cmd[1] == "-m" else [str(out)])
                wall, cpu, proc = timed(cmd, e, tmp)
                if proc.returncode:
                    print(f"{name} failed (exit {proc.returncode}): {proc.stderr.strip()[-400:]}", file=sys.stderr)
                    return 1
                best[name] = (min(best[name][0], wall), min(best[name][1], cpu))
                built[name] = files(out)
        now, one = built["now"], built["one process"]
        if now != one:
            diff = sorted(k for k in set(now) | set(one) if now.get(k) != one.get(k))
            print(f"the gallery in workers and in one process differ: {diff[:5]}", file=sys.stderr)
            return 1
        if "before" in built:
            b = built["before"]
            pngs = [k for k in now if k.endswith(".png")]
            same = set(b) == set(now) and all(same_pixels(now[k], b[k]) for k in pngs)
            if not same:   # the figure work changes sheets on purpose: then before / now times two drawings
                print(f"the gallery of {args.before} has other files or pixels", file=sys.stderr)
            notes.append(f"the same files as {args.before}'s, the PNGs with the same pixels" if same else
                         f"NOT the same files or pixels as {args.before}'s (the sheets changed since, on "
                         f"purpose): before / now compares two different galleries")
    what = f"gallery, {n} examples" + (" and the animations" if args.animations else " (sheets)")
    print(f"{what}, whole processes, best of {repeats}:")
    for name, (wall, cpu) in best.items():
        print(f"  {name:12s} {wall:6.2f} s wall, {cpu:6.2f} s CPU (with its workers)")
    wall = best["now"][0]
    rows = [row(f"{what}: velpoly gallery, workers", wall, "s", "< 10 s", wall < 10.0),
            row(f"{what}: CPU seconds (all processes)", best["now"][1], "s"),
            row(f"{what}: one process", best["one process"][0], "s"),
            row(f"{what}: one process / workers", best["one process"][0] / wall, "x",
                note="same bytes")]
    if "before" in best:
        rows += [row(f"{what}: before ({args.before})", best["before"][0], "s"),
                 row(f"{what}: before / now", best["before"][0] / wall, "x",
                     note="same pixels" if same else "other pixels: the sheets changed since")]
    return finish("gallery", args, rows, notes)


if __name__ == "__main__":
    sys.exit(main())
