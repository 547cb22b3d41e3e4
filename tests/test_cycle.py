"""`velpoly sweep`: the cycle, the toggle stop, the CSV, centrodes, plots, the GIF and the summary.

The four-bars are O2A = a (crank, link 2), AB = b (coupler, 3), O4B = c (rocker, 4) and
O2O4 = d (frame, 1) of tests/mechanisms.py. A non-Grashof four-bar driven by a = 7 with
b = 5, c = 6, d = 9 reaches its toggle (coupler and rocker in line) where |A - O4| = b + c,
i.e. at cos(theta) = (a^2 + d^2 - (b + c)^2) / (2 a d) = 9 / 126: theta = +-85.904 deg.
"""
import csv
import functools
import io
import math
import re
import types

import numpy as np
import pytest

import velpoly
from velpoly.cli import main
from velpoly.centrodes import centrodes
from velpoly.cli import _Progress
from velpoly.render.sweep import cycle_figure
from velpoly.report import cycle_columns, cycle_csv, summary_table
from velpoly.sweeps import run_cycle
from velpoly.driver import reachable_range, reachable_text
from velpoly.kinematics import prepare
from velpoly.reference import relative_pole
from mechanisms import fourbar, slider_crank

TOGGLE = math.degrees(math.acos(9 / 126))


def write(tmp_path, d, name="m.toml"):
    """A mechanism dict as a TOML file (the loader reads dicts; the CLI reads files)."""
    def val(v):
        if isinstance(v, dict):
            return "{ " + ", ".join(f"{k} = {val(x)}" for k, x in v.items()) + " }"
        if isinstance(v, (list, tuple)):
            return "[" + ", ".join(val(x) for x in v) + "]"
        if isinstance(v, str):
            return f'"{v}"'
        if isinstance(v, bool):
            return "true" if v else "false"
        return repr(float(v)) if isinstance(v, float) else str(v)
    lines = [f'title = "{d.get("title", "test")}"', f'units = "{d.get("units", "mm")}"', "", "[points]"]
    lines += [f"{k} = {val(v)}" for k, v in d["points"].items()]
    lines += ["", "[links]"] + [f'"{k}" = {val(v)}' for k, v in d["links"].items()]
    for s in d.get("sliders", []):
        lines += ["", "[[sliders]]"] + [f"{k} = {val(v)}" for k, v in s.items()]
    lines += ["", "[driver]"] + [f"{k} = {val(v)}" for k, v in d["driver"].items()]
    path = tmp_path / name
    path.write_text("\n".join(lines) + "\n")
    return path


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def assert_continuous(sw, closed=False, material_only=False):
    """Every point moves between poses as its velocity predicts (no jump to another branch).

    ``material_only``: leave out the keys P@link of a contact, slider or slot point, which name the
    point of each link under the joint at every pose (not one material point followed)."""
    m = sw.mechanism
    drv = m.driver
    rate = drv.speed if drv.is_slider else drv.omega
    dt = np.diff(sw.angles) / rate * (1.0 if drv.is_slider else math.pi / 180)
    for key, p in sw.position.items():
        if material_only and "@" in key:
            continue
        v = sw.velocity[key]
        step = np.diff(p, axis=0)
        predicted = 0.5 * (v[1:] + v[:-1]) * dt[:, None]      # trapezoidal: error O(dt^3)
        err = np.hypot(*(step - predicted).T)
        assert err.max() <= 1e-3 * m.size, (key, err.max())
    if closed:   # the pose after the last is the first one again
        for key, p in sw.position.items():
            if material_only and "@" in key:
                continue
            gap = p[0] - p[-1]
            pred = 0.5 * (sw.velocity[key][0] + sw.velocity[key][-1]) * dt[-1]
            assert np.hypot(*(gap - pred)) <= 1e-3 * m.size, key


# -- the cycle ---------------------------------------------------------------------------------
def test_grashof_crank_rocker_gives_360_continuous_poses():
    m = velpoly.load(fourbar(a=5, b=8, c=9, d=8, theta=40))
    sw = run_cycle(m, 1.0)
    assert sw.stopped == ""
    assert len(sw.angles) == 360
    assert sw.angles == pytest.approx(40 + np.arange(360))
    assert_continuous(sw, closed=True)
    for k in (0, 97, 250, 359):          # each pose is the analytic solution at that angle
        s = velpoly.solve(m, angle=float(sw.angles[k]))
        for key in ("A", "B"):
            assert sw.position[key][k] == pytest.approx(s.position[key], abs=1e-9)
            assert sw.velocity[key][k] == pytest.approx(s.velocity[key], abs=1e-9)
            assert sw.acceleration[key][k] == pytest.approx(s.acceleration[key], abs=1e-7)


def test_a_clockwise_crank_turns_clockwise():
    m = velpoly.load(fourbar(a=5, b=8, c=9, d=8, theta=40, omega=-3.0))
    sw = run_cycle(m, 5.0)
    assert len(sw.angles) == 72
    assert sw.angles == pytest.approx(40 - 5 * np.arange(72))
    assert_continuous(sw, closed=True)


@pytest.mark.parametrize("omega, last, count", [(10.0, 85.0, 26), (-10.0, -85.0, 146)])
def test_non_grashof_fourbar_stops_before_its_toggle(omega, last, count):
    m = velpoly.load(fourbar(a=7, b=5, c=6, d=9, theta=60, omega=omega))
    sw = run_cycle(m, 1.0)
    assert "toggle" in sw.stopped
    assert len(sw.angles) == count and sw.angles[-1] == pytest.approx(last)
    assert abs(last) < TOGGLE < abs(last) + 1
    # continuous up to the toggle, where the rocker's speed grows without bound: each pose is the
    # drawn branch's (the analytic solve, carried there from the reference pose) and no step jumps
    for k in range(0, count, 5 if count > 50 else 1):
        s = velpoly.solve(m, angle=float(sw.angles[k]))
        assert sw.position["B"][k] == pytest.approx(s.position["B"], abs=1e-9)
    assert np.hypot(*np.diff(sw.position["B"], axis=0).T).max() < 0.1 * m.size


def test_sweep_command_warns_at_the_toggle_and_writes_the_reachable_part(tmp_path, capsys):
    f = write(tmp_path, fourbar(a=7, b=5, c=6, d=9, theta=60))
    out = tmp_path / "cycle.csv"
    code, stdout, err = run(capsys, "sweep", f, "--csv", out)
    assert code == 0
    assert err.startswith("warning: ") and "toggle after 85 deg" in err and "links 3, 4 come into line" in err
    # both toggles (|AO4| = b + c: cos theta = (a^2 + d^2 - (b + c)^2) / 2ad = 9/126, 85.904 deg), to 0.01 deg
    lo, hi = (float(x) for x in re.search(r"reachable on this branch: (\S+) to (\S+) deg", err).groups())
    toggle = math.degrees(math.acos(9 / 126))
    assert toggle - 0.02 <= hi <= toggle and -toggle <= lo <= -toggle + 0.02, err
    rows = list(csv.DictReader(out.open()))
    assert len(rows) == 26
    assert float(rows[0]["driver"]) == 60 and float(rows[-1]["driver"]) == 85
    assert str(out) in stdout


def test_fewer_than_two_reachable_poses_is_exit_3(tmp_path, capsys):
    f = write(tmp_path, fourbar(a=7, b=5, c=6, d=9, theta=TOGGLE - 0.5))
    out = tmp_path / "cycle.csv"
    code, _, err = run(capsys, "sweep", f, "--csv", out)
    assert code == 3
    assert err.startswith("error: ") and "cannot sweep: 1 pose(s)" in err and "Traceback" not in err
    assert not out.exists()


def test_slider_driver_runs_over_its_stroke():
    d = slider_crank(r=3.0, l=10.0, e=1.0, theta=50.0)
    d["driver"] = {"slider": "B", "speed": 2.0}
    m = velpoly.load(d)
    sw = run_cycle(m, 10.0)
    assert sw.stopped == ""
    x = sw.angles
    assert np.all(np.diff(x) > 0) and x[0] < 0 < x[-1] and 0.0 in x
    assert np.diff(x)[:-1] == pytest.approx(np.full(len(x) - 2, np.diff(x)[0]))
    # displacement along the path: B moves by exactly the driver's displacement
    ref = velpoly.solve(m).position["B"]
    assert sw.position["B"][:, 0] - ref[0] == pytest.approx(x, abs=1e-9)
    # the drawn branch all along (each pose as a continuation from the reference straight to it) and
    # no jump; the ends are near dead centres, where the crank turns fast
    for k in range(0, len(x), 3):
        alone = velpoly.sweep(m, [x[k]])
        assert sw.position["A"][k] == pytest.approx(alone.position["A"][0], abs=1e-9)
    assert np.hypot(*np.diff(sw.position["A"], axis=0).T).max() < 0.1 * m.size


def test_bad_step_is_an_input_error(tmp_path, capsys):
    f = write(tmp_path, fourbar())
    for step in ("0", "-2", "nan", "400"):
        code, _, err = run(capsys, "sweep", f, "--step", step)
        assert code == 2 and "--step" in err, step


# -- the CSV -----------------------------------------------------------------------------------
def test_csv_columns_are_complete_and_hold_the_sweep(tmp_path, capsys):
    d = slider_crank()
    f = write(tmp_path, d)
    out = tmp_path / "c.csv"
    code, _, _ = run(capsys, "sweep", f, "--step", "10", "--csv", out, "--centrodes", "3")
    assert code == 0
    m = velpoly.load(f)
    header = out.read_text().splitlines()[0].split(",")
    expected = ["driver"]
    for lk in m.link_names:
        expected += [f"theta_{lk}", f"omega_{lk}", f"alpha_{lk}"]
    for key in velpoly.solve(m).position:
        expected += [f"{c}_{key}" for c in ("x", "y", "vx", "vy", "ax", "ay")]
    expected += ["slip_velocity_B_4/1", "slip_acceleration_B_4/1"]
    expected += ["fixed_centrode_x_3", "fixed_centrode_y_3", "moving_centrode_x_3", "moving_centrode_y_3"]
    assert header == expected
    rows = list(csv.DictReader(out.open()))
    sw = run_cycle(m, 10.0)
    assert len(rows) == len(sw.angles) == 36
    col = {k: np.array([float(r[k] or "nan") for r in rows]) for k in header}   # empty: undefined
    assert col["driver"] == pytest.approx(sw.angles)
    assert col["omega_3"] == pytest.approx(sw.omega["3"], rel=1e-10)
    assert col["ay_A"] == pytest.approx(sw.acceleration["A"][:, 1], rel=1e-10, abs=1e-12)
    assert col["slip_velocity_B_4/1"] == pytest.approx(sw.sliders[0]["slip_velocity"], rel=1e-10)
    # the block slides along its path: its slip is its velocity along +x
    assert col["slip_velocity_B_4/1"] == pytest.approx(col["vx_B"], rel=1e-10, abs=1e-12)


def test_csv_leaves_undefined_values_empty():
    m = velpoly.load(fourbar(a=5, b=8, c=9, d=8, theta=40))
    sw = run_cycle(m, 30.0)
    cen = centrodes(sw, "2")                     # the crank's pole is its fixed pivot: always defined
    names = [n for n, _ in cycle_columns(sw, cen)]
    text = cycle_csv(sw, cen)
    rows = list(csv.reader(io.StringIO(text)))
    assert rows[0] == names and len(rows) == 1 + 12
    assert all(cell != "" and cell.lower() != "nan" for r in rows[1:] for cell in r)


# -- centrodes ---------------------------------------------------------------------------------
@pytest.mark.parametrize("link", ["3", "4"])
def test_fixed_centrode_is_the_pole_from_relative_velocity(link):
    m = velpoly.load(fourbar(a=5, b=8, c=9, d=8, theta=40, coupler=(4.0, 30.0)))
    kin = prepare(m)
    sw = run_cycle(m, 2.0, kin)
    cen = centrodes(sw, link, kin)
    for k in range(0, len(sw.angles), 23):
        s = velpoly.solve(m, angle=float(sw.angles[k]))
        pole, direction = relative_pole(s, "1", link)
        if pole is None:
            assert not cen.defined[k]
            continue
        assert cen.fixed[k] == pytest.approx(pole, abs=1e-9 * m.size)
        assert s.body_velocity(link, cen.fixed[k]) == pytest.approx([0, 0], abs=1e-9)
        # the moving centrode, carried by the link, touches the fixed one at the pole
        assert cen.carried(sw, kin, k)[k] == pytest.approx(cen.fixed[k], abs=1e-9 * m.size)
    # the rocker's pole is its fixed pivot O4 at every pose
    if link == "4":
        assert cen.fixed == pytest.approx(np.tile(m.position("O4"), (len(sw.angles), 1)), abs=1e-9)
        assert cen.moving == pytest.approx(np.tile(m.position("O4"), (len(sw.angles), 1)), abs=1e-9)


def test_centrodes_skip_poses_where_the_link_does_not_turn(tmp_path, capsys):
    m = velpoly.load(slider_crank())
    sw = run_cycle(m, 30.0)
    cen = centrodes(sw, "4")                     # the block translates: its pole is at infinity
    assert not cen.defined.any() and np.isnan(cen.moving).all()
    f = write(tmp_path, slider_crank())
    code, _, err = run(capsys, "sweep", f, "--step", "30", "--csv", tmp_path / "c.csv", "--centrodes", "4")
    assert code == 0 and "link 4 does not turn" in err


@pytest.mark.parametrize("link, why", [("1", "frame"), ("9", "unknown link")])
def test_centrodes_of_the_frame_or_an_unknown_link_are_input_errors(tmp_path, capsys, link, why):
    f = write(tmp_path, fourbar())
    code, _, err = run(capsys, "sweep", f, "--centrodes", link, "--csv", tmp_path / "c.csv")
    assert code == 2 and why in err and "moving links: 2, 3, 4" in err
    assert not (tmp_path / "c.csv").exists()


# -- plots, GIF, summary ------------------------------------------------------------------------
def test_cycle_figure_plots_every_quantity_with_units():
    m = velpoly.load(fourbar(a=5, b=8, c=9, d=8, theta=40, coupler=(4.0, 30.0)))
    kin = prepare(m)
    sw = run_cycle(m, 5.0, kin)
    fig = cycle_figure(sw, points=["B", "E"], cen=centrodes(sw, "3", kin), kin=kin)
    axes = fig.axes
    assert len(axes) == 6
    omega_ax, alpha_ax, speed_ax, acc_ax = axes[:4]
    assert omega_ax.get_ylabel() == r"$\omega$ (rad/s)" and speed_ax.get_ylabel() == "|V| (mm/s)"
    assert acc_ax.get_ylabel() == "|A| (mm/s²)" and "deg" in omega_ax.get_xlabel()
    for ax in axes[:4]:
        assert ax.get_legend() is not None and ax.xaxis.get_gridlines()[0].get_visible()
    lines = {ln.get_label(): ln for ln in omega_ax.lines if (ln.get_gid() or "").startswith("curve-")}
    assert set(lines) == {r"$\omega_{2}$", r"$\omega_{3}$", r"$\omega_{4}$"}
    assert lines[r"$\omega_{3}$"].get_ydata() == pytest.approx(sw.omega["3"])
    assert lines[r"$\omega_{3}$"].get_xdata() == pytest.approx(sw.angles)
    speeds = {ln.get_label(): ln for ln in speed_ax.lines if (ln.get_gid() or "").startswith("curve-")}
    assert set(speeds) == {"$|V_{B}|$", "$|V_{E}|$"}
    assert speeds["$|V_{E}|$"].get_ydata() == pytest.approx(np.hypot(*sw.velocity["E"].T))
    fixed = [ln for ln in axes[4].lines if ln.get_label() == "fixed centrode of link 3"][0]
    from velpoly.render.sweep import _quantity
    assert _quantity("V", "P@2", "|") == "$|V_{P_{2}}|$" and _quantity("V", "a{b}", "|") == r"$|V_{a\{b\}}|$"
    xy = np.column_stack([fixed.get_xdata(), fixed.get_ydata()])
    good = centrodes(sw, "3", kin).fixed
    good = good[np.isfinite(good[:, 0])]
    assert xy[np.isfinite(xy[:, 0])] == pytest.approx(good)


@pytest.mark.parametrize("style", ["textbook", "slides"])
def test_a_long_title_and_the_stop_message_stay_on_the_figure(style):
    d = fourbar(a=7, b=5, c=6, d=9, theta=60)
    d["title"] = "A non-Grashof four-bar whose crank cannot turn round, drawn with a long title " * 2
    m = velpoly.load(d)
    sw = run_cycle(m, 5.0)
    fig = cycle_figure(sw, style=style)
    fig.draw_without_rendering()
    title = fig._suptitle
    box = title.get_window_extent()
    assert "toggle after 85 deg" in title.get_text().replace("\n", " ")
    assert 0 <= box.x0 and box.x1 <= fig.bbox.width                  # within the figure's width
    assert all(ax.get_window_extent().y1 < box.y0 + 1 for ax in fig.axes)   # above the panels


def test_the_gif_polygon_scale_ignores_the_surge_at_a_toggle():
    from velpoly.report import moving_keys as _moving_keys
    from velpoly.render.animate import SURGE, _surge_box
    sw = run_cycle(velpoly.load(fourbar(a=7, b=5, c=6, d=9, theta=60, omega=-10.0)), 0.1)  # 60 down to -85.9
    keys = _moving_keys(sw)
    top = np.max([np.hypot(*sw.velocity[k].T) for k in keys], axis=0)
    assert top[-1] > 3 * SURGE * np.median(top)                 # the rocker's speed grows near the toggle
    per_frame = [np.vstack([np.zeros((1, 2))] + [sw.velocity[k][i:i + 1] for k in keys]) for i in range(len(top))]
    x0, y0, x1, y1 = _surge_box(per_frame)
    reach = max(abs(x0), abs(y0), abs(x1), abs(y1))
    assert reach <= SURGE * np.median(top)                      # ... and does not set the scale
    assert reach >= top[top <= SURGE * np.median(top)].max() / np.sqrt(2) - 1e-9
    assert x0 <= 0 <= x1 and y0 <= 0 <= y1                      # O_v is always in view


def test_plot_and_gif_are_written(tmp_path, capsys):
    f = write(tmp_path, slider_crank())
    plot, gif = tmp_path / "cycle.svg", tmp_path / "cycle.gif"
    code, out, _ = run(capsys, "sweep", f, "--step", "30", "-o", plot, "--gif", gif, "--centrodes", "3",
                       "--points", "A,B")
    assert code == 0
    assert out.split() == [str(plot), str(gif)]
    assert plot.read_text().lstrip().startswith("<?xml")
    from PIL import Image
    with Image.open(gif) as im:
        assert im.format == "GIF" and im.n_frames == 12 and im.is_animated
    assert gif.stat().st_size < 400_000
    assert not list(tmp_path.glob(".*part"))          # no temporary file left behind


@pytest.mark.parametrize("args, where", [(["-o", "x.txt"], "-o"), (["--gif", "x.png"], "--gif"),
                                         (["--points", "Z", "--csv", "c.csv"], "--points")])
def test_bad_output_options_are_input_errors(tmp_path, capsys, args, where):
    f = write(tmp_path, fourbar())
    code, _, err = run(capsys, "sweep", f, *[str(tmp_path / a) if a.endswith((".txt", ".png", ".csv")) else a
                                              for a in args])
    assert code == 2 and where in err and "Traceback" not in err
    assert not (tmp_path / "c.csv").exists()


def test_summary_table_without_outputs(tmp_path, capsys):
    d = fourbar(a=5, b=8, c=9, d=8, theta=40)
    f = write(tmp_path, d)
    code, out, err = run(capsys, "sweep", f, "--step", "2")
    assert code == 0 and err == ""
    sw = run_cycle(velpoly.load(d), 2.0)
    rows = {line.split()[0]: line.split() for line in out.splitlines() if line.startswith(("omega", "|V"))}
    i = int(np.argmin(sw.omega["4"]))
    assert float(rows["omega_4"][2]) == pytest.approx(sw.omega["4"][i], rel=1e-5)
    assert float(rows["omega_4"][3]) == pytest.approx(sw.angles[i])
    assert float(rows["|V_B|"][4]) == pytest.approx(np.hypot(*sw.velocity["B"].T).max(), rel=1e-5)
    assert "rad/s" in rows["omega_4"] and "mm/s" in rows["|V_B|"]
    # fixed points do not clutter it; --points chooses the points
    assert "|V_O2|" not in rows
    t = summary_table(sw, points=["A"])
    assert [r[0] for r in t.rows if r[0].startswith("|")] == ["|V_A|", "|A_A|"]


def test_progress_bar_only_on_a_terminal():
    class Stream(io.StringIO):
        def __init__(self, tty):
            super().__init__()
            self.tty = tty

        def isatty(self):
            return self.tty
    quiet, shown = Stream(False), Stream(True)
    for s in (quiet, shown):
        bar = _Progress(4, "x", stream=s)
        for _ in range(4):
            bar.advance()
        bar.close()
    assert quiet.getvalue() == ""
    assert "4/4" in shown.getvalue() and shown.getvalue().endswith("\n")


# -- every gallery mechanism -------------------------------------------------------------------
from paths import GALLERY_FILES as GALLERY  # noqa: E402
# the gallery files that cannot turn round, with their reachable driver range (absolute, degrees)
PARTIAL = {"fig3_15a_rolling": (-61.0, 151.0),    # a flat-faced cam: see the file's comments
           "fig3_15b_sliding": (-61.0, 151.0)}    # the same lever and cam; the slip turns the wheel only
# and fig3_15a's range exactly (displacements from the drawn pose, to 0.01 deg: a wheel rolling, continuation with
# jets) as the code before the continuation kept its knots (eb22ca2) found it; test_newton_speed's until the suite
# had to fit 2 minutes (0.5 CPU s): here it is the range reachable_text has just computed (kept: _RANGES)
EXACT = {"fig3_15a_rolling": (-61.0, 150.94)}


ON_FIG3_15 = pytest.mark.xdist_group("cycle-fig3-15")   # one worker sweeps the two cases once (partial_cycle)


@functools.cache
def partial_cycle(stem: str):
    """(mechanism, its cycle swept every 2 deg) of a PARTIAL gallery file, as `velpoly sweep --step 2` sweeps
    it: the two cases of Fig. 3.15 walk by continuation up to their toggle (seconds each), shared by the
    tests that look at them (ON_FIG3_15 keeps them on one worker). Read only."""
    m = velpoly.load(next(p for p in GALLERY if p.stem == stem))
    return m, run_cycle(m, 2.0)


@pytest.mark.parametrize("path", [pytest.param(p, marks=[ON_FIG3_15] if p.stem in PARTIAL else [])
                                  for p in GALLERY], ids=[p.stem for p in GALLERY])
def test_every_gallery_mechanism_sweeps_its_cycle(path):
    """`velpoly sweep` on each gallery file: the whole turn on the drawn branch (or the reachable part,
    with the toggle named), continuous, and the CSV with a row per pose and every column filled."""
    m, sw = partial_cycle(path.stem) if path.stem in PARTIAL else (None, None)
    if sw is None:
        m = velpoly.load(path)
        sw = run_cycle(m, 2.0)
    if path.stem in PARTIAL:
        lo, hi = PARTIAL[path.stem]
        assert "toggle" in sw.stopped
        assert hi - 3 <= sw.angles[-1] <= hi                      # stops within a step or so of the toggle
        text = reachable_text(m, prepare(m))
        assert path.stem not in EXACT or reachable_range(prepare(m)) == EXACT[path.stem]
        got = [float(x) for x in text.split(": ")[1].split(" deg")[0].split(" to ")]
        assert lo <= got[0] <= lo + 4 and hi - 2 <= got[1] <= hi
        # continuous up to ten degrees before the toggle (where the speeds grow without bound): the cycle's
        # poses up to there (the sweep of those angles, without walking them again)
        k = int(np.argmax(sw.angles >= hi - 10))
        assert k > 50 and np.all(np.diff(sw.angles[:k]) == 2.0)
        assert_continuous(types.SimpleNamespace(mechanism=m, angles=sw.angles[:k],
                                                position={key: p[:k] for key, p in sw.position.items()},
                                                velocity={key: v[:k] for key, v in sw.velocity.items()}),
                          material_only=True)
    else:
        assert sw.stopped == "" and len(sw.angles) == 180
        assert_continuous(sw, closed=True, material_only=True)
    rows = list(csv.DictReader(io.StringIO(cycle_csv(sw))))
    assert len(rows) == len(sw.angles)
    assert all(v != "" for r in rows for k, v in r.items()
               if not k.startswith(("alpha", "ax_", "ay_", "slip_acceleration")))


# -- Fig. 3.15 (b) over its cycle: a prescribed slip (formerly issue 2 of gallery/SOLVER_ISSUES.md) ---------
@ON_FIG3_15
def test_fig3_15b_sweeps_the_cycle_of_case_a_with_the_wheel_slipping():
    """The cycle `velpoly sweep --step 2` sweeps of case (b) (slip s = 6 of wheel 3 on cam 4, omega_4 = 5
    constant): the reachable part of case (a)'s cycle (its flat-faced cam stops at the same toggle), every
    link and point as in case (a) but wheel 3, which turns s / r3 faster and by s t / r3 more (r3 = 1,
    t = theta_4 / omega_4). Read from the CSV of the sweeps test_every_gallery_mechanism_sweeps_its_cycle
    looks at (partial_cycle); the command's own output is tested above."""
    cols, stops = {}, {}
    for case in ("fig3_15a_rolling", "fig3_15b_sliding"):
        m, sw = partial_cycle(case)
        assert sw.stopped.startswith("stopped at a toggle after 150 deg"), sw.stopped
        stops[case] = (sw.stopped, reachable_text(m, prepare(m)))
        rows = list(csv.DictReader(io.StringIO(cycle_csv(sw))))
        cols[case] = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    assert stops["fig3_15b_sliding"] == stops["fig3_15a_rolling"]     # the same toggle, the same range
    a, b = cols["fig3_15a_rolling"], cols["fig3_15b_sliding"]
    assert list(a) == list(b) and len(b["driver"]) == 76
    wheel = {"theta_3", "omega_3", "slip_velocity_P_3/4"} | {k for k in b if k.endswith("_P@3")}
    for k in set(b) - wheel:
        assert b[k] == pytest.approx(a[k], rel=1e-9, abs=1e-9 * max(np.abs(a[k]).max(), 1.0)), k
    s, t = 6.0, np.radians(b["driver"]) / 5.0
    assert b["slip_velocity_P_3/4"] == pytest.approx(np.full(76, s), rel=1e-10)
    assert b["omega_3"] - a["omega_3"] == pytest.approx(np.full(76, s), rel=1e-9)
    turn = b["theta_3"] - a["theta_3"] - np.degrees(s * t)
    assert np.abs((turn + 180) % 360 - 180).max() < 1e-8
    dv = np.hypot(b["vx_P@3"] - a["vx_P@3"], b["vy_P@3"] - a["vy_P@3"])   # s along the tangent
    assert dv == pytest.approx(np.full(76, s), rel=1e-9)
