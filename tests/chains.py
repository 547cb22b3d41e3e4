"""Long pinned chains for the poles' tests and benchmarks (seeded; dicts for ``velpoly.load``).

``stage_chain``: four-bar stages in series, each rocker driving the next stage's coupler; the
stages slow each other down, so far down the chain links move alike to the velocity solution's
precision (the case where a pin's pole once came out "undefined"). ``parallel_chain``: nearly
parallelogram stages, every link turning at about the crank's speed, so that every one of the
n(n-1)/2 poles is defined (the benchmark). ``ladder``: dyads pinned to random earlier links.
"""
from __future__ import annotations

import numpy as np


def stage_chain(stages: int = 9, seed: int = 0) -> dict:
    """Frame 0, crank 1, then four-bar stages (coupler 2d, rocker 2d + 1): 2 stages + 2 links."""
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


def parallel_chain(links: int = 20, seed: int = 1, jitter: float = 0.15, omega: float = 1.0) -> dict:
    """Frame 0, crank 1, then (links - 2) / 2 stages, each a jittered parallelogram: coupler 2d from
    the driving link's point C_d to E_d, rocker 2d + 1 from its ground pivot G_d through E_d (and on
    to the next stage's C). Every rocker turns at about the crank's speed, so no pole is undefined;
    the jitter keeps lines from being parallel. (Seed 1 assembles and drives at 20, 50, 100, 200.)"""
    rng = np.random.default_rng(seed)
    j = lambda: rng.uniform(-jitter, jitter)  # noqa: E731
    stages = (links - 2) // 2
    pts = {"G0": [0.0, 0.0], "C1": [0.6 + j(), 1.0 + j()]}
    lk = {"0": {"points": ["G0"], "frame": True}, "1": {"points": ["G0", "C1"]}}
    for d in range(1, stages + 1):
        g, c, e = f"G{d}", f"C{d}", f"E{d}"
        pts[g] = [1.5 * d + j(), j()]
        pts[e] = [pts[c][0] + 1.5 + j(), pts[c][1] + j()]
        lk["0"]["points"].append(g)
        lk[str(2 * d)] = {"points": [c, e]}
        lk[str(2 * d + 1)] = {"points": [g, e]}
        if d < stages:
            pts[f"C{d + 1}"] = [pts[g][0] + 0.6 + j(), pts[g][1] + 1.0 + j()]
            lk[str(2 * d + 1)]["points"].append(f"C{d + 1}")
    return {"title": f"{links}-link chain", "units": "m", "points": pts, "links": lk,
            "driver": {"link": "1", "omega": omega}}


def ladder(n_links: int, seed: int) -> dict:
    """A random one-degree-of-freedom chain of n_links: a crank, then dyads pinned to random
    earlier links and to each other (each dyad closes one more loop)."""
    rng = np.random.default_rng(seed)
    pts = {"O": [0.0, 0.0]}
    links = {"0": {"points": ["O"], "frame": True}, "1": {"points": ["O"]}}
    k = 2
    while k + 1 < n_links:
        u, v = str(k), str(k + 1)
        ea, eb = ("1", "0") if k == 2 else (str(x) for x in rng.choice(k, 2, replace=False))
        for name in (f"J{u}", f"J{v}", f"M{u}"):
            pts[name] = rng.uniform(-3, 3, 2).tolist()
        links[ea]["points"].append(f"J{u}")
        links[eb]["points"].append(f"J{v}")
        links[u] = {"points": [f"J{u}", f"M{u}"]}
        links[v] = {"points": [f"J{v}", f"M{u}"]}
        k += 2
    return {"points": pts, "links": links, "driver": {"link": "1", "omega": 1.0}}
