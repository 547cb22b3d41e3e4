"""Outside check, the frame at rest (FORMAT.md section 2: "links: every link, the frame included (omega and alpha
zero)"): a point of the frame has velocity and acceleration exactly zero, whatever the order of ``[links]``.

Found by the audit: a point the frame shares with a moving link (a pivot) took its motion from the first link
listing it, so a file that lists the frame after the rocker gave ``V_O4 = [0, 1.8e-15]`` and
``A_O4 = [7.1e-15, 4.3e-14]``, and ``velpoly solve`` printed "0 ∠ 90.000°" for a fixed pivot (72 of 80 poses of
40 zoo mechanisms with the frame listed last). Now such a point is the frame's.
"""
from __future__ import annotations

import numpy as np
import pytest

import velpoly

import zoo

SEED, COUNT = 20261125, 24   # test_zoo's first specimens, made once on its worker
pytestmark = pytest.mark.xdist_group("zoo")


def frame_last(mech: dict) -> dict:
    """The mechanism with the frame listed last in ``[links]`` (the contract lets links come in any order)."""
    links = mech["links"]
    frame = next(n for n, v in links.items() if v.get("frame"))
    mech["links"] = {n: links[n] for n in [*(n for n in links if n != frame), frame]}
    return mech


def test_the_frame_s_points_are_at_rest_exactly():
    checked = 0
    for sp in zoo.zoo(SEED, COUNT):
        m = velpoly.load(frame_last(sp.mech))
        fixed = set(m.frame.points)
        angles = [None] if m.driver.is_slider else [None, sp.drawn.driver_angle + 7.0]
        for angle in angles:
            try:
                d = velpoly.solve(m, angle=angle).to_dict()
            except velpoly.PoseError:
                continue
            for key, p in d["points"].items():
                point, _, carrier = key.partition("@")
                if point in fixed and carrier in ("", m.frame.name):
                    assert p["velocity"] == [0.0, 0.0], (sp.kind, angle, key, p)
                    assert p["acceleration"] in ([0.0, 0.0], None), (sp.kind, angle, key, p)
                    checked += 1
        w = velpoly.sweep(m, sp.drawn.driver_angle + np.array([0.0, 3.0])) if not m.driver.is_slider else None
        for key in (k for k in (w.velocity if w else ()) if k in fixed):
            assert not np.any(w.velocity[key]) and not np.any(w.acceleration[key]), (sp.kind, key)
    assert checked > 2 * COUNT
