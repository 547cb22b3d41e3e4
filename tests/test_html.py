"""``velpoly html``: the interactive page.

In Python: the embedded poses decode to exactly what ``velpoly.solve`` gives at their angles
(every gallery file, generated mechanisms), the page is self-contained and small enough.
In a real browser (headless Chromium): the page's script draws points, images and poles where
``velpoly solve --angle A`` puts them, the construction stepper shows the steps of
``velpoly.polygons``, the URL fragment selects angle and step, and the screenshots (JPEG) are not blank.
The browser tests skip where Chromium is missing, unless VELPOLY_REQUIRE_BROWSER=1 (CI) makes them
fail.
"""
from __future__ import annotations

import base64
import functools
import json
import math
import os
import random
import re
import subprocess
import sys
import time
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest

import velpoly
from velpoly.cli import main
from velpoly.html import _split, cycle_solutions, page, pose_values, sheet_data
import velpoly.html as html_module   # the module itself: page() looks sheet_data up in it
from velpoly.names import key_text
from velpoly.polygons import acceleration_polygon, velocity_polygon

from mechanisms import SIXBAR_1_4_4, fourbar, in_process, slider_crank

ROOT = Path(__file__).resolve().parent.parent
GALLERY = ROOT / "velpoly" / "examples"   # the gallery's mechanism files (tests/paths.py)
SIXBAR = GALLERY / "problem_1_4_4_sixbar.toml"


# -- decoding, as the page's script does ---------------------------------------------------------------
def decode(data: dict, i: int):
    tpl_id, nums, sids = data["poses"][i]
    nums, sids = iter(nums), iter(sids)

    def fill(t):
        if isinstance(t, bool) or t is None:
            return t
        if t == 0 and isinstance(t, int):
            return next(nums)
        if t == "":
            return data["strings"][next(sids)]
        if isinstance(t, list):
            return [fill(x) for x in t]
        return {k: fill(v) for k, v in t.items()}
    return fill(data["templates"][tpl_id])


def embedded(text: str) -> tuple[dict, dict]:
    """The static data and the poses embedded in a page."""
    s = re.search(r"window\.VELPOLY_STATIC=(.*?);\nwindow\.VELPOLY_POSES=", text, re.S).group(1)
    p = re.search(r"window\.VELPOLY_POSES=(.*?);\n</script>", text, re.S).group(1)
    return json.loads(s.replace("<\\/", "</")), json.loads(p.replace("<\\/", "</"))


def wrap(a: float) -> float:
    w = (a + 180.0) % 360.0 - 180.0
    return 180.0 if w == -180.0 else w


def check_pose(m, P: dict, angle: float, tol: float = 1e-6, own=None):
    """A decoded pose against velpoly.solve at its angle: positions, velocities, accelerations,
    the polygons' images and the poles, to ``tol`` of the mechanism's size (its largest speed,
    its largest acceleration). ``own``: the sweep's Solution of the pose, whose construction steps
    the page shows (at a pose where two construction orders are equally good, ``solve`` at the
    same angle may choose the other: the pose agrees to 1e-14, the order's tie-break does not)."""
    sol = velpoly.solve(m, angle=None if m.driver.is_slider else angle)
    d = sol.to_dict()
    size = m.size
    vmax = max(float(np.hypot(*v)) for v in sol.velocity.values()) or 1.0
    assert set(P["P"]) == set(sol.position)
    for key, p in P["P"].items():
        assert np.hypot(*(np.array(p) - sol.position[key])) <= tol * size, key
        assert np.hypot(*(np.array(P["V"][key]) - sol.velocity[key])) <= tol * vmax, key
    assert P["vp"] is not None
    for key, img in P["vp"]["img"].items():
        assert np.hypot(*(np.array(img) - sol.velocity[key])) <= tol * vmax, key
    if own is not None:   # the steps are velpoly.polygons' at the sweep's pose (velpoly draw --steps)
        assert [s["eq"] for s in P["vp"]["st"]] == [s.equation for s in velocity_polygon(own).steps]
        if own.has_accelerations:
            assert [s["eq"] for s in P["ap"]["st"]] == [s.equation for s in acceleration_polygon(own).steps]
    if sol.has_accelerations:
        amax = max(float(np.hypot(*a)) for a in sol.acceleration.values()) or 1.0
        for key, img in P["ap"]["img"].items():
            assert np.hypot(*(np.array(img) - sol.acceleration[key])) <= tol * amax, key
    for key, pole in d["poles"].items():
        if pole["position"] is None:
            assert P["poles"][key]["p"] is None
            if pole.get("direction") is not None:
                assert abs(P["poles"][key]["d"] - pole["direction"]) < 1e-5 or \
                    abs(abs(P["poles"][key]["d"] - pole["direction"]) - 180) < 1e-5
        elif np.hypot(*pole["position"]) < 1e3 * size:
            assert np.hypot(*(np.array(P["poles"][key]["p"]) - pole["position"])) <= tol * size, key


def _digitless(s: str) -> str:
    """An equation with its numbers left out (a scale printed to 6 digits may round either way)."""
    return re.sub(r"-?[0-9][0-9.e+-]*", "#", s)


# -- Python: every gallery file, generated mechanisms -----------------------------------------------------
# the tests of the six-bar's page and of the browser share its module fixtures: one worker builds them (their
# xdist group), the page and the browser once
ON_PAGE = pytest.mark.xdist_group("html-page")


# (file, fragment): a handful of gallery files in the browser, at angles and steps
BROWSER_CASES = [
    ("problem_1_4_4_sixbar", "#angle=47&step=3"),
    ("problem_1_4_4_sixbar", "#angle=-120"),
    ("ex3_4_slotted_lever", "#angle=200&step=7"),
    ("cam_roller_follower", "#angle=100&step=12"),
    ("fig3_15a_rolling", "#angle=60"),
    ("stephenson_sixbar", "#angle=10&step=4"),
    ("crank_shaper", "#angle=-150&step=20"),
]


@functools.cache
def gallery_data(stem: str):
    """(mechanism, cycle_solutions, static data, poses' JSON) of a gallery file's page every 30 degrees, made once
    a process: what test_gallery_pages_embed_the_solution decodes is what the browser's page of the file embeds
    (the browser's files are in its group: one worker makes each once, 0.5-0.9 CPU s less than twice)."""
    m = velpoly.load(GALLERY / f"{stem}.toml")
    cycle = cycle_solutions(m, 30.0)
    static, poses = sheet_data(m, step=30.0, cycle=cycle)
    return m, cycle, static, poses


IN_BROWSER = {name for name, _ in BROWSER_CASES} - {SIXBAR.stem}   # (the six-bar's browser page: every degree)


@pytest.mark.parametrize("path", [pytest.param(p, marks=[ON_PAGE] if p.stem in IN_BROWSER else [])
                                  for p in sorted(GALLERY.glob("*.toml"))], ids=lambda p: p.stem)
def test_gallery_pages_embed_the_solution(path):
    """Every gallery file: the page is made, its data is valid JSON, and poses a quarter-turn apart
    decode to what ``velpoly.solve`` gives there."""
    m, cycle, static, poses = gallery_data(path.stem)
    data = json.loads(poses)
    assert len(data["poses"]) == len(static["angles"]) >= 2
    own = cycle[3]
    for i in range(0, len(static["angles"]), 3):
        P = decode(data, i)
        assert P["msg"] == [], P["msg"]
        check_pose(m, P, wrap(static["angles"][i]), own=own[i])


def _generated():
    rng = random.Random(20261125)
    out = []
    for _ in range(3):   # Grashof crank-rockers: the crank the shortest link
        a = rng.uniform(1.0, 2.0)
        b, c, d = (rng.uniform(4.0, 6.0) for _ in range(3))
        out.append(fourbar(a=a, b=b, c=c, d=d, theta=rng.uniform(-180, 180), omega=rng.uniform(-20, 20),
                           alpha=rng.uniform(-5, 5), coupler=(rng.uniform(1, 4), rng.uniform(-60, 60))))
    out.append(slider_crank(r=rng.uniform(1, 3), l=rng.uniform(7, 11), e=rng.uniform(-1, 1),
                            theta=rng.uniform(-180, 180), path=rng.uniform(-30, 30)))
    out.append(fourbar(a=9.0, b=5.0, c=8.0, d=8.0, theta=40.0))   # a double rocker: a limited range
    return out


@pytest.mark.parametrize("mech", _generated(), ids=lambda d: d.get("title", "slider-crank"))
def test_generated_mechanisms(mech):
    m = velpoly.load(mech)
    cycle = cycle_solutions(m, 40.0)
    static, poses = sheet_data(m, step=40.0, cycle=cycle)
    data = json.loads(poses)
    n = len(static["angles"])
    assert n >= 2
    own = cycle[3]
    for i in range(n):
        check_pose(m, decode(data, i), wrap(static["angles"][i]), own=own[i])
    if static["limited"]:   # both ways to the ends of the reachable range, in order
        a = np.array(static["angles"])
        assert np.all(np.diff(a) > 0)


SLIDER_DRIVEN = {
    "title": "slider-driven crank", "units": "mm",
    "points": {"A": [0, 0], "B": {"from": "A", "length": 40, "angle": 60},
               "C": {"circle": ["B", 100], "line": {"through": [0, 0], "angle": 0}, "near": [110, 0]}},
    "links": {"0": {"points": ["A"], "frame": True}, "1": {"points": ["A", "B"]}, "2": {"points": ["B", "C"]},
              "3": {"points": ["C"]}},
    "sliders": [{"block": "3", "guide": "0", "point": "C", "angle": 0}],
    "driver": {"slider": "C", "speed": 2.5},
}


def test_slider_driver_runs_over_its_stroke():
    """A slider driver: the page's positions are displacements along the path over the stroke, in
    ascending order, starting at the drawn position (0), which is velpoly.solve's pose."""
    m = velpoly.load(SLIDER_DRIVEN)
    cycle = cycle_solutions(m, 20.0)
    static, poses = sheet_data(m, step=20.0, cycle=cycle)
    data = json.loads(poses)
    a = np.array(static["angles"])
    assert np.all(np.diff(a) > 0) and a[0] < 0 < a[-1]
    assert a[static["start"]] == 0.0 and static["driver"]["slider"] == "C"
    check_pose(m, decode(data, static["start"]), 0.0, own=cycle[3][static["start"]])
    for i in range(len(a)):   # the block's point moves along its path by the displacement
        P = decode(data, i)
        assert P["P"]["C"][0] - data_c0(data, static) == pytest.approx(a[i], abs=1e-6 * m.size)


def data_c0(data, static):
    return decode(data, static["start"])["P"]["C"][0]


def test_template_order_is_a_browsers():
    """Index-like keys come first, ascending, as a browser walks an object; the rest keep their order."""
    nums, strs = [], []
    t = _split({"b": 1.0, "10": 2.0, "2": 3.0, "a": "x", "01": 4.0, "1": [5.0, None, True]}, nums, strs)
    assert list(t) == ["1", "2", "10", "b", "a", "01"]
    assert nums == [5.0, 3.0, 2.0, 1.0, 4.0] and strs == ["x"]


@pytest.fixture(scope="module")
def sixbar_page(tmp_path_factory):
    out = tmp_path_factory.mktemp("html") / "sixbar.html"
    r = in_process(["html", SIXBAR, "-o", out])   # in this process: test_wheel runs `velpoly html` as a program
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == str(out)
    return out


@ON_PAGE
def test_sixbar_page_is_small_and_self_contained(sixbar_page):
    text = sixbar_page.read_text(encoding="utf-8")
    assert len(text.encode("utf-8")) < 2_000_000
    # nothing fetched: no external scripts, styles, fonts, images or links
    assert not re.search(r"<(link|img|iframe|object|embed)\b", text, re.I)
    assert not re.search(r"<script[^>]+src=", text, re.I)
    assert not re.search(r"https?://|@import|url\(|fetch\(|XMLHttpRequest|//cdn", text, re.I)
    static, data = embedded(text)
    assert len(static["angles"]) == 360
    # every degree of the turn, from the drawn pose (30 deg) in the crank's sense
    assert np.allclose(np.diff(static["angles"]), 1.0)
    assert static["angles"][static["start"]] == pytest.approx(30.0)
    m = velpoly.load(SIXBAR)
    for i in (0, 17, 200, 359):
        check_pose(m, decode(data, i), wrap(static["angles"][i]))


def test_cli_errors(tmp_path, capsys):
    def run(*args):   # velpoly html ARGS in this process (velpoly.cli.main: the exit code and the messages)
        capsys.readouterr()
        rc = main(["html", *map(str, args)])
        out = capsys.readouterr()
        return subprocess.CompletedProcess(args, rc, out.out, out.err)
    r = run(SIXBAR, "-o", tmp_path / "x.png")
    assert r.returncode == 2 and r.stderr.startswith("error: ") and "hint:" in r.stderr
    r = run(tmp_path / "missing.toml", "-o", tmp_path / "x.html")
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert not (tmp_path / "x.html").exists()
    r = run(SIXBAR, "-o", tmp_path / "x.html", "--step", "0.01")
    assert r.returncode == 2 and "--step" in r.stderr and not (tmp_path / "x.html").exists()
    r = run(SIXBAR, "-o", tmp_path / "x.html", "--step", "0")
    assert r.returncode == 2 and "--step" in r.stderr and not (tmp_path / "x.html").exists()
    normal = tmp_path / "normal.toml"   # a contact given by its normal: the drawn pose only, no cycle
    normal.write_text('[points]\nO2 = [0, 0]\nQ = [0.05, 0]\nO4 = [0.02, 0.12]\nR = [0.04, 0.07]\n'
                      'P = [0.04, 0.05]\n[links]\n1 = { points = ["O2", "O4"], frame = true }\n'
                      '2 = { points = ["O2", "Q"] }\n4 = { points = ["O4", "R"] }\n[[contacts]]\n'
                      'links = ["2", "4"]\npoint = "P"\nkind = "sliding"\nnormal = 80\n'
                      '[driver]\nlink = "2"\nomega = 7\n')
    r = run(normal, "-o", tmp_path / "x.html")
    assert r.returncode == 2 and "contacts[0]" in r.stderr and "centres of curvature" in r.stderr
    assert not (tmp_path / "x.html").exists()
    src = tmp_path / "in.html"
    src.write_text(SIXBAR_1_4_4)
    r = run(src, "-o", src)
    assert r.returncode == 2 and "input" in r.stderr
    assert src.read_text() == SIXBAR_1_4_4


def test_notebook_display():
    import velpoly.html   # noqa: F401  (the module is the function too)
    m = velpoly.load(SIXBAR_1_4_4)
    sheet = velpoly.html(m, step=30.0)
    shown = sheet._repr_html_()
    assert shown.startswith("<iframe srcdoc=\"") and "&lt;svg id=&quot;space&quot;" in shown
    assert "window.VELPOLY_POSES" in str(sheet)
    with pytest.raises(velpoly.VelpolyError):
        velpoly.html("not a mechanism")


def test_velpoly_html_without_importing_the_module():
    code = f"import velpoly; m = velpoly.load(r'{SIXBAR}'); print(type(velpoly.html(m, step=60.0)).__name__)"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                       env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "HtmlSheet"


def test_a_failing_construction_is_reported_not_raised(monkeypatch):
    """A pose whose polygon cannot be constructed (a singular pose) keeps the rest of the sheet and
    says why: the page shows the message in the polygon's panel."""
    import velpoly.polygons as polygons
    from velpoly.errors import SingularPoseError
    m = velpoly.load(SIXBAR_1_4_4)
    sol = velpoly.solve(m)

    def fails(sol):
        raise SingularPoseError("lines 2 and 3 meet at 1e-11 rad", where="velocity polygon")
    monkeypatch.setattr(polygons, "velocity_polygon", fails)
    P = pose_values(sol, sol.kinematics.system.index)
    assert P["vp"] is None and P["ap"] is not None and P["poles"] is not None
    assert P["msg"] == ["lines 2 and 3 meet at 1e-11 rad"]


# -- the browser ---------------------------------------------------------------------------------------
class Dom(HTMLParser):
    """The body's attributes and every element carrying data-key."""

    def __init__(self, text):
        super().__init__()
        self.body, self.marks, self.svg, self.caption = None, [], None, None
        self.feed(text)

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "body":
            self.body = a
        elif tag == "svg" and a.get("id"):
            self.svg = a["id"]
        elif tag == "p" and a.get("id") == "caption":
            self.caption = a
        if "data-key" in a:
            a["panel"] = self.svg
            self.marks.append(a)

    def of(self, cls, panel=None):
        return [a for a in self.marks if cls in a.get("class", "").split() and (panel is None or a["panel"] == panel)]


@pytest.fixture(scope="module")
def browser_runs(tmp_path_factory, sixbar_page, browser):
    tmp = tmp_path_factory.mktemp("browser")
    pages = {"problem_1_4_4_sixbar": sixbar_page}
    out = {}
    for case in BROWSER_CASES:
        name, frag = case
        if name not in pages:
            # every 30 degrees (the nearest pose is drawn, whatever the page's step; 10 until the suite had to fit
            # 2 minutes: 0.8 CPU s more): the six-bar's page (every degree) is the size test's
            pages[name] = tmp / f"{name}.html"
            m, _, static, poses = gallery_data(name)
            with pytest.MonkeyPatch.context() as mp:   # velpoly.html.page of the data made once (gallery_data)
                mp.setattr(html_module, "sheet_data", lambda *a, **k: (static, poses))
                pages[name].write_text(page(m, step=30.0), encoding="utf-8")
        browser.open(pages[name].resolve().as_uri() + frag)
        shot = tmp / f"{name}-{len(out)}.jpg"   # a JPEG: Chromium encodes it in a third of a PNG's wall time
        shot.write_bytes(base64.b64decode(browser.send("Page.captureScreenshot", format="jpeg")["data"]))
        out[case] = (browser.dom(), shot, pages[name])
    assert not browser.errors(), browser.errors()      # the page's script threw or logged nothing
    return out


def _similar(marks, x="data-x", y="data-y", flip=True):
    """The panel maps (x, y) to (sx, sy) by one similarity (a scale, the y axis turned down)."""
    pts = [(float(a[x]), float(a[y]), float(a["data-sx"]), float(a["data-sy"])) for a in marks]
    if len(pts) < 2:
        return
    (x0, y0, X0, Y0) = pts[0]
    far = max(pts, key=lambda p: math.hypot(p[0] - x0, p[1] - y0))
    d = math.hypot(far[0] - x0, far[1] - y0)
    if d == 0:
        return
    k = math.hypot(far[2] - X0, far[3] - Y0) / d
    for (x1, y1, X1, Y1) in pts:
        assert X1 - X0 == pytest.approx(k * (x1 - x0), abs=1e-6 * (1 + abs(X1)))
        assert Y1 - Y0 == pytest.approx(-k * (y1 - y0), abs=1e-6 * (1 + abs(Y1)))


@ON_PAGE
@pytest.mark.parametrize("case", BROWSER_CASES, ids=lambda c: c[0] + c[1])
def test_browser_draws_the_solution(case, browser_runs):
    """What the browser drew (the DOM after the page's script ran) is what velpoly solve gives at
    that angle: points, velocity and acceleration images, poles; the step shows its construction."""
    name, frag = case
    dom_text, shot, path = browser_runs[case]
    dom = Dom(dom_text)
    m = velpoly.load(GALLERY / f"{name}.toml")
    want_angle = float(re.search(r"angle=(-?[0-9.]+)", frag).group(1))
    want_step = int(re.search(r"step=([0-9]+)", frag).group(1)) if "step=" in frag else 0
    assert dom.body is not None and "data-rendered" in dom.body, "the page's script did not run"
    drawn = float(dom.body["data-rendered"])
    static, data = embedded(path.read_text(encoding="utf-8"))
    assert abs(wrap(drawn - want_angle)) <= static["step"] / 2 + 1e-9     # the pose nearest the fragment's angle
    want_step = min(want_step, int(dom.body["data-steps"]))   # a step past the last is the last
    assert int(dom.body["data-step"]) == want_step
    sol = velpoly.solve(m, angle=drawn)
    size = m.size
    # points of the space diagram
    pts = dom.of("pt", "space")
    assert {a["data-key"] for a in pts} == set(sol.position)
    for a in pts:
        p = sol.position[a["data-key"]]
        assert math.hypot(float(a["data-x"]) - p[0], float(a["data-y"]) - p[1]) <= 1e-6 * size
        assert float(a["cx"]) == pytest.approx(float(a["data-sx"]), abs=0.006)
        assert float(a["cy"]) == pytest.approx(float(a["data-sy"]), abs=0.006)
    _similar(pts)
    v = static["views"]["space"]   # drawn to the page's scale of the space diagram
    for a in pts:
        assert float(a["data-sx"]) == pytest.approx(v["k"] * (float(a["data-x"]) - v["x0"]), abs=1e-6)
        assert float(a["data-sy"]) == pytest.approx(v["k"] * (v["y1"] - float(a["data-y"])), abs=1e-6)
    for a in dom.marks:   # hover or tap: every point, image and pole names itself and its value
        key, tip, cls = a["data-key"], a.get("data-tip", ""), a.get("class", "").split()
        if "pt" in cls:
            assert tip.startswith(f"{key_text(key)}: (") and "V = " in tip, tip   # P₂, as velpoly.names names it
        elif "img" in cls:
            assert f"{'V' if a['data-level'] == 'velocity' else 'A'}_{key} = " in tip, tip
        else:
            assert tip.startswith("P" + key.replace("-", "")) or tip.startswith("P{" + key + "}"), tip
        assert re.search(r"[0-9]", tip.split("=", 1)[-1]), tip
    # the construction drawn up to the step: velocity steps, then acceleration steps, then poles
    vel, acc = velocity_polygon(sol), acceleration_polygon(sol) if sol.has_accelerations else None
    nv, na = len(vel.steps), len(acc.steps) if acc else 0
    if want_step == 0:
        upto_v, upto_a = nv, na
    elif want_step <= nv:
        upto_v, upto_a = want_step, 0
    else:
        upto_v, upto_a = nv, min(want_step - nv, na)
    vmax = max(float(np.hypot(*v)) for v in sol.velocity.values())
    for level, poly, upto, ref in (("velocity", vel, upto_v, sol.velocity),
                                   ("acceleration", acc, upto_a, sol.acceleration)):
        imgs = [a for a in dom.of("img", level)]
        if poly is None:
            assert not imgs
            continue
        found = {k for s in poly.steps[:upto] for k in s.found}
        assert {a["data-key"] for a in imgs} == found
        top = max(float(np.hypot(*v)) for v in ref.values()) or 1.0
        for a in imgs:
            v = ref[a["data-key"]]
            assert math.hypot(float(a["data-x"]) - v[0], float(a["data-y"]) - v[1]) <= 1e-6 * top
            assert int(a["data-step"]) <= upto
        _similar(imgs)
    assert vmax > 0
    # the caption is the step's equation from velpoly.polygons, as embedded for this pose (the equations
    # of velpoly.polygons at the sweep's pose: check_pose checks those)
    if want_step:
        P = decode(data, int(dom.body["data-pose-index"]))
        steps = [s["eq"] for s in P["vp"]["st"]] + ([s["eq"] for s in P["ap"]["st"]] if P["ap"] else [])
        if want_step > len(steps):   # a pole's step: the poles found so far, the step in words
            order = sorted((p["o"], k) for k, p in P["poles"].items() if p["o"] > 0)
            n, key = order[want_step - len(steps) - 1]
            assert dom.caption["data-equation"] == P["poles"][key]["s"] and dom.caption["data-level"] == "poles"
            assert dom.caption["data-caption"] == P["poles"][key]["s"]
            shown = {a["data-key"] for a in dom.marks if "pole" in a.get("class", "").split()}
            assert shown == {k for k, p in P["poles"].items() if p["o"] <= n and (p["p"] or p["d"] is not None)}
        if want_step <= len(steps):
            assert dom.caption["data-equation"] == steps[want_step - 1]
            # the caption shown is the step's own, word for word the --steps frame's (Step.caption)
            caps = [s["cap"] for s in P["vp"]["st"]] + ([s["cap"] for s in P["ap"]["st"]] if P["ap"] else [])
            assert dom.caption["data-caption"] == caps[want_step - 1] and caps[want_step - 1]
            assert _digitless(dom.caption["data-equation"]) == _digitless(
                ([s.equation for s in vel.steps] + ([s.equation for s in acc.steps] if acc else []))[want_step - 1]) \
                or len(steps) == nv + na
    else:
        # poles: every pole with a place, where the solve puts it
        poles = sol.to_dict()["poles"]
        drawn_poles = {a["data-key"]: a for a in dom.of("pole", "poles")}
        for key, p in poles.items():
            if p["position"] is not None and np.hypot(*p["position"]) < 1e3 * size:
                a = drawn_poles[key]
                assert math.hypot(float(a["data-x"]) - p["position"][0],
                                  float(a["data-y"]) - p["position"][1]) <= 1e-6 * size, key
        inside = [a for a in drawn_poles.values() if "data-x" in a and "data-outside" not in a]
        _similar(inside)
    # the screenshot shows a drawing, not a blank page
    from PIL import Image, ImageStat
    img = Image.open(shot).convert("L")
    assert img.size == (1280, 900)
    stat = ImageStat.Stat(img)
    assert stat.stddev[0] > 20
    dark = sum(img.histogram()[:128]) / (img.size[0] * img.size[1])
    assert 0.005 < dark < 0.5


@ON_PAGE
def test_browser_controls(browser, sixbar_page):
    """Keys, the slider, play/pause, hover and tap, in the browser with real input events."""
    static, data = embedded(sixbar_page.read_text(encoding="utf-8"))
    b = browser
    b.open(sixbar_page.resolve().as_uri() + "#angle=30")

    def state():
        return (float(b.js("document.body.dataset.rendered")), int(b.js("document.body.dataset.step")),
                b.js("location.hash"))
    assert state() == (30.0, 0, "#angle=30")
    b.key("ArrowRight", 39)
    assert state() == (31.0, 0, "#angle=31")
    b.key("ArrowRight", 39, shift=True)
    b.key("ArrowLeft", 37)
    assert state() == (40.0, 0, "#angle=40")
    for _ in range(3):
        b.key("ArrowDown", 40)
    assert state() == (40.0, 3, "#angle=40&step=3")
    P = decode(data, int(b.js("document.body.dataset.poseIndex")))
    assert b.js("document.getElementById('caption').dataset.equation") == P["vp"]["st"][2]["eq"]
    assert b.js("document.querySelectorAll('#acceleration .img').length") == 0   # not yet constructed
    b.key("ArrowUp", 38)
    assert state()[1] == 2
    b.key("End", 35)
    assert state()[1] == int(b.js("document.body.dataset.steps")) == len(P["vp"]["st"]) + len(P["ap"]["st"]) + \
        sum(1 for p in P["poles"].values() if p["o"] > 0)
    b.key("Home", 36)
    assert state()[1] == 0
    # the slider: a click three quarters along it
    r = b.js("(function(){var r=document.getElementById('angle').getBoundingClientRect();"
             "return [r.left, r.top, r.width, r.height];})()")
    b.mouse("click", r[0] + 0.75 * r[2], r[1] + r[3] / 2)
    i = int(b.js("document.body.dataset.poseIndex"))
    assert abs(i - 0.75 * 359) < 15
    assert float(b.js("document.body.dataset.rendered")) == pytest.approx(wrap(static["angles"][i]))
    # play, then pause
    b.key(" ", 32)
    b.wait(f"document.body.dataset.poseIndex != '{i}'", timeout=10)
    b.key(" ", 32)
    j = b.js("document.body.dataset.poseIndex")
    time.sleep(0.3)
    assert b.js("document.body.dataset.poseIndex") == j
    # hover over point B: its name and value; a tap on image c keeps its value shown
    b.open(sixbar_page.resolve().as_uri() + "#angle=30")
    sol = velpoly.solve(velpoly.load(SIXBAR), angle=30.0)

    def centre(sel):
        return b.js(f"(function(){{var r=document.querySelector('{sel}').getBoundingClientRect();"
                    "return [r.left + r.width / 2, r.top + r.height / 2];})()")
    x, y = centre('#space .pt[data-key="B"]')
    b.mouse("mouseMoved", x, y)
    assert b.js("document.getElementById('tip').hidden") is False
    tip = b.js("document.getElementById('tip').textContent")
    assert tip.startswith("B: (") and f"{sol.position['B'][0]:.5g}"[:5] in tip.replace("\u2212", "-")
    x, y = centre('#velocity .img[data-key="C"]')
    b.mouse("click", x, y)
    b.mouse("mouseMoved", 5, 5)          # moving away keeps a tapped value shown
    tip = b.js("document.getElementById('tip').textContent")
    speed = float(np.hypot(*sol.velocity["C"]))
    assert "V_C = " in tip and f"{speed:.5g}"[:5] in tip
    # the results table: graphical and analytic omega and speeds at this pose
    table = b.js("document.getElementById('results-table').textContent").replace("\u2212", "-")
    assert "30°" in table and f"{sol.omega['3']:.5g}" in table and f"{speed:.4g}" in table
    assert not b.errors(), b.errors()
