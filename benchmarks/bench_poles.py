"""All the instant centres of a 20-link chain: 190 poles by inspection and Aronhold-Kennedy.

    python benchmarks/bench_poles.py [--repeats 5] [--json OUT]

The chain: the frame, a crank, then nine four-bar stages in series, each stage's rocker driving the
next stage's coupler (1 + 1 + 9 x 2 = 20 links, 28 pins; mobility 1), its points jittered at random
(fixed seed) so that no two lines are parallel by construction. ``velpoly.poles.locate_poles``
finds the 28 pins by inspection and the other 162 poles by Kennedy's lines, round by round; it is
timed on one solution, uncached, best of ``--repeats`` batches, per call. Target (DESIGN.md
section 5): under 50 ms. Also timed: the instant-centre method (every omega and point velocity
through the poles) and, for scale, the six-bar of ``velpoly/examples``. Every result is checked
against the velocity solution before it is timed.
"""
from __future__ import annotations

import collections
import sys
from pathlib import Path

import numpy as np

from _common import best_of, finish, parser, row


def stage_chain(stages: int = 9, seed: int = 0) -> dict:
    """Frame 0, crank 1, then four-bar stages (coupler 2d, rocker 2d + 1), as a dict for velpoly.load."""
    rng = np.random.default_rng(seed)
    jitter = lambda: rng.uniform(-0.3, 0.3)  # noqa: E731
    pts = {"O": [0.0, 0.0]}
    links = {"0": {"points": ["O"], "frame": True}, "1": {"points": ["O"]}}
    driving = "1"
    for d in range(1, stages + 1):
        c, e, g = f"C{d}", f"D{d}", f"G{d}"
        pts[c] = [2.0 * d - 1.0 + jitter(), 1.0 + jitter()]    # on the driving link
        pts[e] = [2.0 * d + 0.5 + jitter(), 1.6 + jitter()]    # coupler-rocker pin
        pts[g] = [2.0 * d + jitter(), jitter()]                # the rocker's ground pivot
        links[driving]["points"].append(c)
        coupler, rocker = str(2 * d), str(2 * d + 1)
        links[coupler] = {"points": [c, e]}
        links[rocker] = {"points": [g, e]}
        links["0"]["points"].append(g)
        driving = rocker
    return {"title": f"{2 * stages + 2}-link chain of four-bar stages", "units": "m", "points": pts,
            "links": links, "driver": {"link": "1", "omega": 1.0}}


def main(argv=None) -> int:
    args = parser(__doc__.splitlines()[0]).parse_args(argv)
    import velpoly
    from velpoly.poles import instant_centre_velocities, locate_poles

    notes: list[str] = []
    sol = velpoly.solve(velpoly.load(stage_chain()))
    n = len(sol.mechanism.links)
    ps = locate_poles(sol, cached=False)
    ic = instant_centre_velocities(sol, ps)
    hows = collections.Counter(p.how for p in ps.poles.values())
    assert len(ps) == n * (n - 1) // 2, len(ps)
    assert ps.max_error < 1e-9 and max(ic["max_error"].values()) < 1e-9, (ps.max_error, ic["max_error"])

    t_poles = best_of(lambda: locate_poles(sol, cached=False), args.repeats, 10)
    t_ic = best_of(lambda: instant_centre_velocities(sol, ps), args.repeats, 10)
    six = velpoly.solve(velpoly.load(Path(velpoly.__file__).parent / "examples" / "problem_1_4_4_sixbar.toml"))
    t_six = best_of(lambda: locate_poles(six, cached=False), args.repeats, 100)

    print(f"{sol.mechanism.title}: {n} links, {len(ps)} poles "
          f"({', '.join(f'{k} {v}' for k, v in sorted(hows.items()))}), {len(ps.order)} found in "
          f"order; largest deviation from the velocity solution {ps.max_error:.1e}")
    print(f"  locate_poles                 {t_poles * 1e3:8.3f} ms   (best of {args.repeats} x 10 calls)")
    print(f"  instant_centre_velocities    {t_ic * 1e3:8.3f} ms   (omegas {ic['max_error']['omega']:.1e}, "
          f"speeds {ic['max_error']['velocity']:.1e} from the analytic solve)")
    print(f"  six-bar example, 15 poles    {t_six * 1e3:8.3f} ms")
    if hows.get("velocity"):
        notes.append(f"{hows['velocity']} poles came from the velocity solution (Kennedy stalled)")
    rows = [row(f"poles: {len(ps)} of a {n}-link chain", t_poles * 1e3, "ms", "< 50 ms", t_poles < 0.05),
            row("poles: instant-centre method, same chain", t_ic * 1e3, "ms"),
            row("poles: six-bar example (15 poles)", t_six * 1e3, "ms")]
    return finish("poles", args, rows, notes)


if __name__ == "__main__":
    sys.exit(main())
