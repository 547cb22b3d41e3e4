"""Not a benchmark: the check that speed work on the kernel keeps every output the same.

    python benchmarks/same_json.py [--before COMMIT] [--zoo N]

On many poses (the seeded zoo of tests/zoo.py, N mechanisms, default 160, at the offsets each
specimen gives; the Coriolis, slot, contact and frame-slider generators of tests/mechanisms.py;
long chains and ladders of tests/chains.py; degenerate poses (slider-cranks and four-bars at dead
centre and folded, a parallelogram, a flat follower and pins in slots at rest); every example at
its own pose and at 24 driver angles), this checkout's velpoly and the one of ``--before``
(default: main's a7fd73a, exported from git) each compute, in a process of their own:

* ``solve --json``'s text (``json.dumps(solve(m, angle).to_dict(), indent=2)``, or the error),
* the whole pole set and both polygons, every field (``repr`` of each float: the bits).

The two must be the same text for every pose; the first differences are printed (exit 1).
About 860 poses; a few minutes on a loaded machine.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from _common import ROOT, export

WORKER = r'''
import hashlib, json, sys
import numpy as np
import velpoly
from velpoly.poles import locate_poles
from velpoly.polygons import acceleration_polygon, velocity_polygon
from velpoly.solution import driver_reference_angle

def ser(x):
    if isinstance(x, np.ndarray): return ser(x.tolist())
    if isinstance(x, dict): return {str(k): ser(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)): return [ser(v) for v in x]
    if isinstance(x, float): return repr(x)
    if hasattr(x, "__dataclass_fields__"): return {k: ser(getattr(x, k)) for k in x.__dataclass_fields__}
    return x

def text(m, angle):
    try:
        s = velpoly.solve(m, angle)
    except Exception as e:
        return f"solve {type(e).__name__}: {e}"
    try:
        out = json.dumps(s.to_dict(), indent=2, allow_nan=False)
    except Exception as e:
        out = f"to_dict {type(e).__name__}: {e}"
    for fn in (locate_poles, velocity_polygon, acceleration_polygon):
        try:
            out += json.dumps(ser(fn(s)))
        except Exception as e:
            out += f"{fn.__name__} {type(e).__name__}: {e}"
    return out

for name, mech, offsets in json.load(open(sys.argv[1])):
    try:
        m = velpoly.load(mech)
    except Exception as e:
        print(f"{name}\t-\t-\tload {type(e).__name__}: {e}")
        continue
    try:
        ref = driver_reference_angle(m)
    except Exception:
        ref = None
    for o in offsets:
        a = None if o is None or ref is None or m.driver.is_slider else ref + o
        t = text(m, a)
        print(f"{name}\t{a}\t{hashlib.sha1(t.encode()).hexdigest()}\t{t[:60]!r}")
'''


def cases(zoo_count: int) -> list:
    """``[(name, mechanism file or dict, [driver offsets from the reference, None: the file's pose])]``."""
    sys.path.insert(0, str(ROOT / "tests"))
    import math

    import numpy as np

    import chains
    import mechanisms as M
    import zoo
    out = [(f"zoo {i} {sp.kind}", sp.mech, list(dict.fromkeys(list(sp.offsets) + [None])))
           for i, sp in enumerate(zoo.zoo(7, zoo_count))]
    for seed in range(8):
        for fn in (M.block_on_driven_crank, M.block_on_driving_guide, M.pin_in_slot, M.sliding_cam,
                   M.sliding_on_frame):
            out.append((f"{fn.__name__} {seed}", fn(seed), [None]))
        out.append((f"pin_in_slot {seed} slot-driven", M.pin_in_slot(seed, driver="slot"), [None]))
        out.append((f"pin_in_slot {seed} circular", M.pin_in_slot(seed, circular=True), [None]))
    out += [(f"parallel_chain {n}", chains.parallel_chain(n), [None]) for n in (20, 30)]
    out += [("stage_chain 9", chains.stage_chain(9), [None])]
    out += [(f"ladder {n} {s}", chains.ladder(n, s), [None]) for n, s in ((12, 0), (30, 1))]
    special = []   # degenerate poses: dead centres, folded and parallelogram four-bars, things at rest
    for th in (0.0, 180.0):
        special += [M.slider_crank(r=3, l=10, e=0, theta=th, path=0), M.slider_crank(r=3, l=10, e=0, theta=th, path=30)]
    for a, b, c, d in ((2, 7, 6, 5), (5, 8, 5, 8), (3, 8, 3, 8), (2, 5, 4, 6)):
        for th in (0.0, 180.0, 40.0):
            for br in ("left", "right"):
                try:
                    special.append(M.fourbar(a, b, c, d, th, 10.0, branch=br, coupler=(3.0, 40.0)))
                except Exception:
                    pass   # no assembly there
    for th in (0.0, 180.0, 60.0):
        special.append(M.set_path_angle(M.inverted_slider_crank(3, 7, th, 5)))
    for theta, psi in ((60.0, 60.0), (30.0, 90.0), (120.0, 120.0)):   # a flat follower on an eccentric
        k = 0.4 * np.array([math.cos(math.radians(theta)), math.sin(math.radians(theta))])
        dvec = np.array([math.cos(math.radians(psi)), math.sin(math.radians(psi))])
        p = k + dvec
        special.append({
            "points": {"O": [0, 0], "K": k.tolist(), "P": p.tolist(), "F": (p + 0.3 * np.array([-dvec[1], dvec[0]])).tolist()},
            "links": {"1": {"points": ["O"], "frame": True}, "2": {"points": ["O", "K"]}, "3": {"points": ["F"]}},
            "sliders": [{"block": "3", "guide": "1", "point": "F", "angle": psi}],
            "contacts": [{"links": ["2", "3"], "point": "P", "kind": "sliding", "centres": ["K", "flat"]}],
            "driver": {"link": "2", "omega": 3.0}})
    for slot in (0.0, 45.0, 90.0):   # a pin in a slot whose lever stands still
        special.append({
            "points": {"O2": [0, 0], "O3": [2.5, 0], "A": [0.5, 0.0], "S": [3, 2], "K": [2, 1]},
            "links": {"1": {"points": ["O2", "O3"], "frame": True}, "2": {"points": ["O2", "A"]},
                      "3": {"points": ["O3", "S", "K"]}},
            "slots": [{"pin": "A", "link": "2", "slot": "3", "angle": slot}],
            "driver": {"link": "2", "omega": 4.0}})
    out += [(f"special {i}", mech, [None]) for i, mech in enumerate(special)]
    for f in sorted((ROOT / "velpoly" / "examples").glob("*.toml")):
        out.append((f.stem, str(f), [None] + [k * 15.0 for k in range(24)]))   # offsets: a slider driver takes None
    return out


def run(where: Path, case_file: Path, tmp: str) -> list[str]:
    proc = subprocess.run([sys.executable, "-c", WORKER, str(case_file)], capture_output=True, text=True,
                          env=dict(os.environ, PYTHONPATH=str(where)), cwd=tmp)
    if proc.returncode:
        raise SystemExit(f"the velpoly of {where} failed: {proc.stderr.strip()[-500:]}")
    return proc.stdout.splitlines()


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--before", default="a7fd73a", help="the commit to compare with (default %(default)s)")
    p.add_argument("--zoo", type=int, default=160, help="how many zoo mechanisms (default %(default)s)")
    args = p.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="velpoly-same-json-") as tmp:
        case_file = Path(tmp) / "cases.json"
        case_file.write_text(json.dumps(cases(args.zoo)))
        old = export(args.before, Path(tmp) / "before")
        if old is None:
            raise SystemExit(f"commit {args.before} not available (git archive failed)")
        before, now = run(old, case_file, tmp), run(ROOT, case_file, tmp)
    differ = [(a, b) for a, b in zip(before, now) if a != b]
    if len(before) != len(now):
        differ.append((f"{len(before)} lines", f"{len(now)} lines"))
    errors = sum(line.split("\t")[3].startswith(("'solve ", "load ")) for line in now)
    if differ:
        print(f"{len(differ)} of {len(now)} poses differ from {args.before}'s; the first:")
        for a, b in differ[:5]:
            print(f"  {args.before}: {a[:160]}\n  now:     {b[:160]}")
        return 1
    print(f"the same as {args.before}'s on all {len(now)} poses (solve --json's text, the pole set and both "
          f"polygons; {errors} of them an error, the same)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
