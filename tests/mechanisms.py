"""Mechanism dicts for tests: textbook examples and random generators.

Every generator returns a dict for ``velpoly.load`` (FORMAT.md section 1).
"""
from __future__ import annotations

import math


def fourbar(a=5.0, b=8.0, c=9.0, d=8.0, theta=40.0, omega=10.0, alpha=0.0, branch="left",
            coupler=None):
    """Crank O2A = a, coupler AB = b, rocker O4B = c, frame O2O4 = d along +x."""
    pts = {
        "O2": [0.0, 0.0],
        "O4": [d, 0.0],
        "A": {"from": "O2", "length": a, "angle": theta},
        "B": {"circles": [["A", b], ["O4", c]], "side": branch},
    }
    links = {
        "1": {"points": ["O2", "O4"], "frame": True},
        "2": {"points": ["O2", "A"]},
        "3": {"points": ["A", "B"]},
        "4": {"points": ["O4", "B"]},
    }
    if coupler:
        r, turn = coupler
        pts["E"] = {"from": "A", "length": r, "along": ["A", "B"], "turn": turn}
        links["3"]["points"].append("E")
    return {"title": "four-bar", "units": "mm", "points": pts, "links": links,
            "driver": {"link": "2", "omega": omega, "alpha": alpha}}


def slider_crank(r=3.0, l=10.0, e=1.0, theta=50.0, omega=7.0, alpha=2.0, path=0.0):
    """Crank O2A = r, rod AB = l, block B on a frame path at angle ``path`` offset e."""
    t = math.radians(path)
    through = [-e * math.sin(t), e * math.cos(t)]
    return {
        "points": {
            "O2": [0.0, 0.0],
            "A": {"from": "O2", "length": r, "angle": theta},
            "B": {"circle": ["A", l], "line": {"through": through, "angle": path},
                  "near": [through[0] + 2 * l * math.cos(t), through[1] + 2 * l * math.sin(t)]},
        },
        "links": {
            "1": {"points": ["O2"], "frame": True},
            "2": {"points": ["O2", "A"]},
            "3": {"points": ["A", "B"]},
            "4": {"points": ["B"]},
        },
        "sliders": [{"block": "4", "guide": "1", "point": "B", "angle": path}],
        "driver": {"link": "2", "omega": omega, "alpha": alpha},
    }


def inverted_slider_crank(r=3.0, d=7.0, theta=60.0, omega=5.0, alpha=-3.0):
    """Crank O2A = r; block (link 3) pinned at A slides on the rocker O4 (link 4) through A."""
    return {
        "points": {
            "O2": [0.0, 0.0],
            "O4": [d, 0.0],
            "A": {"from": "O2", "length": r, "angle": theta},
            "C": {"from": "O4", "length": 2 * (r + d), "along": ["O4", "A"]},
        },
        "links": {
            "1": {"points": ["O2", "O4"], "frame": True},
            "2": {"points": ["O2", "A"]},
            "3": {"points": ["A"]},
            "4": {"points": ["O4", "C", "A"]},
        },
        "sliders": [{"block": "3", "guide": "4", "point": "A", "angle": 0.0}],
        "driver": {"link": "2", "omega": omega, "alpha": alpha},
    }


def set_path_angle(mech: dict) -> dict:
    """Give an inverted slider-crank's slider the direction O4 -> A of its reference pose."""
    import velpoly
    m = velpoly.load({**mech, "sliders": [{**mech["sliders"][0], "angle": 0.0}]})
    a, o4 = m.position("A"), m.position("O4")
    mech["sliders"][0]["angle"] = math.degrees(math.atan2(a[1] - o4[1], a[0] - o4[0]))
    return mech


SIXBAR_1_4_4 = """
format = 1
title = "Problem 1.4.4"
units = "m"
[points]
A = [0, 0]
D = [0.30, 0.45]
B = { from = "A", length = 0.15, angle = 30 }
C = { circles = [["B", 0.40], ["D", 0.37]], near = [-0.07, 0.42] }
E = { from = "C", length = 0.23, along = ["D", "C"] }
F = { circle = ["E", 0.23], line = { through = [-0.37, 0], angle = 90 }, near = [-0.37, 0.19] }
[links]
0 = { points = ["A", "D"], frame = true }
1 = { points = ["A", "B"] }
2 = { points = ["B", "C"] }
3 = { points = ["D", "C", "E"] }
4 = { points = ["E", "F"] }
5 = { points = ["F"] }
[[sliders]]
block = "5"
guide = "0"
point = "F"
angle = 90
[driver]
link = "1"
omega = "60 rpm"
"""

EXAMPLE_3_6 = """
title = "Example 3.6"
units = "mm"
[points]
O2 = [0, 0]
O4 = [20, 0]
A = { from = "O2", length = 40, angle = 120 }
B = { circles = [["A", 80], ["O4", 70]], near = [56, 60] }
E = { from = "A", length = 40, along = ["A", "B"] }
F = { from = "E", length = 15, along = ["A", "B"], turn = -90 }
[links]
1 = { points = ["O2", "O4"], frame = true }
2 = { points = ["O2", "A"] }
3 = { points = ["A", "B", "E", "F"] }
4 = { points = ["O4", "B"] }
[driver]
link = 2
omega = "10 rad/s ccw"
"""


WHEEL_ROLLING = """
title = "wheel rolling on the ground, driven by a crank and rod"
units = "mm"
[points]
O2 = [0, 40]
A = { from = "O2", length = 15, angle = 60 }
C = { circle = ["A", 60], line = { through = [0, 20], angle = 0 }, near = [60, 20] }
P = { from = "C", length = 20, angle = -90 }
[links]
1 = { points = ["O2"], frame = true }
2 = { points = ["O2", "A"] }
3 = { points = ["A", "C"] }
4 = { points = ["C"] }
[[contacts]]
links = ["4", "1"]
point = "P"
kind = "rolling"
centres = ["C", "flat"]
[driver]
link = 2
omega = 10
alpha = 3
"""

CAM_FLAT = """
title = "eccentric cam with a flat-faced translating follower"
units = "mm"
[points]
O = [0, 0]
K = { from = "O", length = 10, angle = 30 }
P = { from = "K", length = 25, angle = 90 }
F = { from = "P", length = 20, angle = 0 }
[links]
1 = { points = ["O"], frame = true }
2 = { points = ["O", "K"] }
3 = { points = ["F"] }
[[sliders]]
block = "3"
guide = "1"
point = "F"
angle = 90
[[contacts]]
links = ["2", "3"]
point = "P"
kind = "sliding"
centres = ["K", "flat"]
[driver]
link = 2
omega = 10
alpha = 4
"""

CAM_ROLLER = """
title = "circular cam with a roller follower"
units = "mm"
[points]
O = [0, 0]
K = { from = "O", length = 10, angle = 30 }
R = { from = "K", length = 30, angle = 80 }
P = { from = "K", length = 25, along = ["K", "R"] }
[links]
1 = { points = ["O"], frame = true }
2 = { points = ["O", "K"] }
3 = { points = ["R"] }
4 = { points = ["R"] }
[[sliders]]
block = "3"
guide = "1"
point = "R"
angle = 90
[[contacts]]
links = ["2", "4"]
point = "P"
kind = "rolling"
centres = ["K", "R"]
[driver]
link = 2
omega = 10
alpha = -2
"""

SLOTTED_LEVER = """
title = "pin of a crank in the slot of a lever (Example 3.4's first loop)"
units = "mm"
[points]
O1 = [0, 0]
C = [0, -20]
A = { from = "O1", length = 2, angle = 100 }
D = { from = "C", length = 41.284, along = ["C", "A"] }
[links]
1 = { points = ["O1", "C"], frame = true }
2 = { points = ["O1", "A"] }
3 = { points = ["C", "D", "A"] }
[[slots]]
pin = "A"
link = "2"
slot = "3"
angle = 95.7
[driver]
link = 2
omega = "30 rad/s"
"""
