"""Mechanism dicts for tests: textbook examples and random generators.

Every generator returns a dict for ``velpoly.load`` (FORMAT.md section 1).
"""
from __future__ import annotations

import math


def ranges_by_dyads_only(monkeypatch) -> None:
    """Make the reachable range an AssemblyError names (``solve`` at an angle beyond a toggle) cheap for a
    test that checks the refusal, not the range: computed, and checked to hold the drawn pose, where the
    mechanism has a chain of dyads (a walk: milliseconds); (0, 0) where only continuation reaches its poses
    (four continuations past the toggles: a second or more a mechanism). That path is tested on its own
    (test_slot_ends, test_cycle's and test_gallery's rolling-contact sweeps, test_change_points,
    test_branch)."""
    from velpoly import pose, solution
    real = solution.reachable_range

    def ranged(kin):
        if pose.plan_for(kin.system.positions) is None:
            return 0.0, 0.0
        lo, hi = real(kin)
        assert lo <= 0.0 <= hi, (lo, hi)
        return lo, hi
    real_words = solution.reachable_words

    def words(kin, ref, refused=None):   # the message's range (driver.reachable_ends) the same way
        return real_words(kin, ref, refused) if pose.plan_for(kin.system.positions) is not None else "0 to 0"
    monkeypatch.setattr(solution, "reachable_range", ranged)
    monkeypatch.setattr(solution, "reachable_words", words)


def shapes_only(mechanism):
    """``mechanism``'s ``[drawing]`` options with no point labels and no link numbers, for a test of the space
    diagram's shapes alone (bodies, slot cuts, ground hatching and what it may touch, the view): those are all
    made before the marks are placed (``displacement._Drawing.draw``: ``marks`` last), so they are the same with
    or without the labels, and the label placer, most of a space diagram's cost, is spared; a poles drawing's
    Kennedy lines are made before any label too (``kennedy.draw_poles``). Issue 19 item 7, every body, cut,
    hatching, exemption, zorder, Kennedy line and view limit compared equal with and without the labels:
    test_slot_drawing's and test_audit_ground's 45 drawings 10.9 -> 4.1 CPU s, test_space_plates' 11 8.6 -> 2.7,
    test_poles' drawn Kennedy lines (13 poles drawings) 4.5 -> 3.4."""
    from dataclasses import replace

    from velpoly.render.options import drawing_options
    return replace(drawing_options(mechanism), label_points=(), link_numbers="none")


def in_process(args):
    """``velpoly ARGS`` run in this process (``velpoly.cli.main``, what ``python -m velpoly`` runs) with its
    output captured, as a ``subprocess.CompletedProcess``: the exit code and text a user sees, without a
    subprocess's second of imports; an exception main let escape fails the test (a process would print its
    traceback)."""
    import contextlib
    import io
    import subprocess
    from velpoly.cli import main
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = main([str(a) for a in args])
    return subprocess.CompletedProcess(args, rc, out.getvalue(), err.getvalue())

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


# -- seeded generators of joints whose polygons have Coriolis, slip and contact terms ----------------
# Each takes a seed (the dimensions, speeds and variant) and the angle of the pose's free crank in
# degrees (the pose: solving other driver angles of these joints walks the cycle, which is slow); a
# straight path is given by its angle, through the guide's pivot or offset from it.
def _rng(seed):
    import random
    return random.Random(seed)


def _driver(rng, link):
    return {"link": link, "omega": rng.choice((-1, 1)) * rng.uniform(2.0, 20.0), "alpha": rng.uniform(-50.0, 50.0)}


def _polar(p, r, deg):
    return [p[0] + r * math.cos(math.radians(deg)), p[1] + r * math.sin(math.radians(deg))]


def _direction(p, q):
    return math.degrees(math.atan2(q[1] - p[1], q[0] - p[0]))


def block_on_driven_crank(seed, angle=60.0):
    """Crank O2A drives block 3 (pinned at A) along rocker 4 (pivot O4): the guide's point A4 is found
    from the block's image (the Coriolis and slip terms subtracted)."""
    rng = _rng(seed)
    r, d = rng.uniform(2.0, 4.0), rng.uniform(5.0, 9.0)
    m = inverted_slider_crank(r=r, d=d, theta=angle)
    m["driver"] = _driver(rng, "2")
    through = _direction([d, 0.0], _polar([0.0, 0.0], r, angle))
    m["sliders"][0]["angle"] = through if rng.random() < 0.5 else through + rng.uniform(-40, 40)
    m["title"] = f"block on a rocking guide {seed}"
    return m


def block_on_driving_guide(seed, angle=60.0):
    """A driven slotted arm 2 (pivot O2) carries block 3, pinned at B to rocker 4 (pivot O4): the block's
    point B is found from the guide's point under it (the terms added; Whitworth-like)."""
    rng = _rng(seed)
    d, c = rng.uniform(3.0, 6.0), rng.uniform(2.0, 4.5)
    b = _polar([d, 0.0], c, angle)
    through = _direction([0.0, 0.0], b)
    return {
        "title": f"block on a driven guide {seed}",
        "points": {"O2": [0.0, 0.0], "O4": [d, 0.0], "B": b, "G": _polar([0.0, 0.0], d + c + 2.0, through + 5.0)},
        "links": {"1": {"points": ["O2", "O4"], "frame": True}, "2": {"points": ["O2", "G"]},
                  "3": {"points": ["B"]}, "4": {"points": ["O4", "B"]}},
        "sliders": [{"block": "3", "guide": "2", "point": "B",
                     "angle": through if rng.random() < 0.5 else through + rng.uniform(-40, 40)}],
        "driver": _driver(rng, "2"),
    }


def pin_in_slot(seed, angle=60.0, driver="pin", circular=False):
    """Crank 2 (O1A) with its pin A in a slot of lever 3 (pivot C), straight or circular about K.

    ``driver = "pin"``: the crank drives (the slot's point A3 is found from the pin's image);
    ``"slot"``: the lever drives the crank (the pin's image from the slot's point under it).
    """
    rng = _rng(seed)
    c = rng.uniform(4.0, 8.0)
    a = rng.uniform(1.5, 0.7 * c)
    cc = [rng.uniform(-1, 1), -c]
    pa = _polar([0.0, 0.0], a, angle)
    ca = _direction(cc, pa)
    pts = {"O1": [0.0, 0.0], "C": cc, "A": pa, "D": _polar(cc, c + a + 2.0, ca + rng.uniform(-20, 20))}
    slot = {"pin": "A", "link": "2", "slot": "3"}
    lever = ["C", "D"]
    if circular:
        pts["K"] = _polar(pa, rng.uniform(2.0, 8.0), rng.uniform(0, 360))
        slot["centre"] = "K"
        lever.append("K")
    else:
        slot["angle"] = ca if rng.random() < 0.5 else ca + rng.uniform(-40, 40)
    return {
        "title": f"pin in a {'circular' if circular else 'straight'} slot, {driver} driven {seed}",
        "points": pts,
        "links": {"1": {"points": ["O1", "C"], "frame": True}, "2": {"points": ["O1", "A"]},
                  "3": {"points": lever}},
        "slots": [slot],
        "driver": _driver(rng, "2" if driver == "pin" else "3"),
    }


def sliding_cam(seed, angle=60.0, follower="curved"):
    """Disc cam 2 (centre K at ``angle``, pivot O2) sliding on a follower 3: ``follower`` "curved" (an
    arm pivoted at O3 with a face of centre C3), "flat" (an arm with a flat face), or "translating" (a
    block on a vertical frame guide with a curved face of centre R)."""
    rng = _rng(seed)
    e, rk = rng.uniform(0.5, 2.0), rng.uniform(3.0, 5.0)
    k = _polar([0.0, 0.0], e, angle)
    pts = {"O2": [0.0, 0.0], "K": k}
    links = {"1": {"points": ["O2"], "frame": True}, "2": {"points": ["O2", "K"]}}
    m = {"title": f"sliding cam, {follower} follower {seed}", "points": pts, "links": links,
         "driver": _driver(rng, "2")}
    if follower == "translating":
        r3 = rng.uniform(1.0, 3.0)
        x = rng.uniform(-0.4, 0.4) * (rk + r3)
        pts["R"] = {"circle": ["K", rk + r3], "line": {"through": [x, 0.0], "angle": 90}, "near": [x, 20.0]}
        pts["P"] = {"from": "K", "length": rk, "along": ["K", "R"]}
        pts["F"] = {"from": "R", "length": 3.0, "angle": 90}
        links["3"] = {"points": ["R", "F"]}
        m["sliders"] = [{"block": "3", "guide": "1", "point": "R", "angle": 90}]
        centres = ["K", "R"]
    elif follower == "curved":
        r3, l3 = rng.uniform(1.0, 3.0), rng.uniform(5.0, 8.0)
        pts["O3"] = [rng.uniform(-2, 2), rk + r3 + 2.0]
        pts["C3"] = {"circles": [["K", rk + r3], ["O3", l3]], "side": rng.choice(("left", "right"))}
        pts["P"] = {"from": "K", "length": rk, "along": ["K", "C3"]}
        links["1"]["points"].append("O3")
        links["3"] = {"points": ["O3", "C3"]}
        centres = ["K", "C3"]
    else:
        ang = rng.uniform(45, 135)
        pts["P"] = {"from": "K", "length": rk, "angle": ang}
        pts["E"] = {"from": "P", "length": rng.uniform(2.0, 5.0), "angle": ang + 90}
        pts["O3"] = {"from": "E", "length": rng.uniform(2.0, 5.0), "angle": ang + rng.uniform(20, 70)}
        links["1"]["points"].append("O3")
        links["3"] = {"points": ["O3", "E"]}
        centres = ["K", "flat"]
    m["contacts"] = [{"links": ["2", "3"], "point": "P", "kind": "sliding", "centres": centres}]
    return m


def sliding_on_frame(seed, angle=60.0, surface="curved"):
    """Crank 2 (O2A) and a rod 3 (A to its rounded end, centre C3) sliding on the frame: on a fixed
    drum about K (``surface`` "curved") or on a fixed flat floor ("flat")."""
    rng = _rng(seed)
    r, l, r3 = rng.uniform(1.0, 2.0), rng.uniform(5.0, 7.0), rng.uniform(0.5, 1.5)
    pts = {"O2": [0.0, 0.0], "A": _polar([0.0, 0.0], r, angle)}
    links = {"1": {"points": ["O2"], "frame": True}, "2": {"points": ["O2", "A"]}, "3": {"points": ["A", "C3"]}}
    if surface == "curved":
        big = rng.uniform(3.0, 5.0)
        pts["K"] = [l * 0.8, -(big + r3 + rng.uniform(0.5, 2.0))]
        pts["C3"] = {"circles": [["A", l], ["K", big + r3]], "near": [l, 0.0]}
        pts["P"] = {"from": "K", "length": big, "along": ["K", "C3"]}
        links["1"]["points"].append("K")
        centres = ["C3", "K"]
    else:
        h = -rng.uniform(2.5, 4.0)
        pts["C3"] = {"circle": ["A", l], "line": {"through": [0.0, h + r3], "angle": 0}, "near": [l, h]}
        pts["P"] = {"from": "C3", "length": r3, "angle": -90}
        centres = ["C3", "flat"]
    return {"title": f"rod sliding on a fixed {surface} surface {seed}", "points": pts, "links": links,
            "contacts": [{"links": ["3", "1"], "point": "P", "kind": "sliding", "centres": centres}],
            "driver": _driver(rng, "2")}


ARROW_GENERATORS = {
    "block on a driven crank": block_on_driven_crank,
    "block on a driving guide": block_on_driving_guide,
    "pin in a straight slot, pin driven": lambda s, a: pin_in_slot(s, a, "pin"),
    "pin in a straight slot, slot driven": lambda s, a: pin_in_slot(s, a, "slot"),
    "pin in a circular slot, pin driven": lambda s, a: pin_in_slot(s, a, "pin", circular=True),
    "pin in a circular slot, slot driven": lambda s, a: pin_in_slot(s, a, "slot", circular=True),
    "sliding cam, curved follower": lambda s, a: sliding_cam(s, a, "curved"),
    "sliding cam, flat follower": lambda s, a: sliding_cam(s, a, "flat"),
    "sliding cam, translating follower": lambda s, a: sliding_cam(s, a, "translating"),
    "rod sliding on a fixed drum": lambda s, a: sliding_on_frame(s, a, "curved"),
    "rod sliding on a fixed floor": lambda s, a: sliding_on_frame(s, a, "flat"),
}


WORDS = ("frame", "cam", "follower", "lever", "crank", "blk", "rocker", "arm", "S", "slider", "yoke", "bar")


def rename_links(mech: dict, names=WORDS) -> dict:
    """The mechanism ``mech`` (a dict for ``velpoly.load``) with its links renamed, in file order, to
    ``names`` (words, as some lecturers name links: "cam", "follower"; one letter: "S"), everywhere a
    link is named: links, sliders, slots, contacts, the driver, ``[drawing] link_colours``. A
    ``[reference]`` (keyed by link numbers) is dropped."""
    import copy
    m = copy.deepcopy(mech)
    new = dict(zip(m["links"], names))
    m["links"] = {new[k]: v for k, v in m["links"].items()}
    for s in m.get("sliders", ()):
        s["block"], s["guide"] = new[str(s["block"])], new[str(s["guide"])]
    for s in m.get("slots", ()):
        s["link"], s["slot"] = new[str(s["link"])], new[str(s["slot"])]
    for c in m.get("contacts", ()):
        c["links"] = [new[str(lk)] for lk in c["links"]]
    if "link" in m["driver"]:
        m["driver"]["link"] = new[str(m["driver"]["link"])]
    colours = m.get("drawing", {}).get("link_colours")
    if colours:
        m["drawing"]["link_colours"] = {new[str(k)]: v for k, v in colours.items()}
    m.pop("reference", None)
    return m


def drop_tiny(x: float) -> float:
    """A generated angular acceleration as a driver may have it: 0 for one so small (1e-311, a denormal) that the
    accelerations it gives fall under the floor a file may ask for (1e-200, velpoly.loader.driver.MIN_ACCEL: an
    input error, test_audit7_input)."""
    return x if abs(x) >= 1e-150 else 0.0
