"""`velpoly animate`: the frames' poses, the drawn data against the sweep and the solve, the formats,
the fixed scales, rocking linkages out and back, errors and no files left behind."""
from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

import velpoly
from velpoly.render.animate import Animator, plan_frames, write_animation
from mechanisms import fourbar
from test_cycle import run, write

SMALL = (320, 180)


ON_COUPLER = pytest.mark.xdist_group("animate-coupler")   # the tests sharing coupler_anim: one worker builds it


@pytest.fixture(scope="module")
def coupler_anim():
    """A four-bar with a coupler point, 12 frames at 320 x 180 (shared: building it is the costly part)."""
    return Animator(plan_frames(velpoly.load(fourbar(coupler=(4.0, 30.0))), 30.0), "velocity", "slides", SMALL)


def drawn(anim, k):
    """What frame k draws, read back from the artists: pin centres, dots, and each polygon's arrow tips
    (the arrowhead's first vertex) by the arrow's key."""
    anim.render(k)
    pins = {p: np.array(c.center) for p, c in anim.pin_patches.items()}
    x, y = anim.dots.get_data()
    tips = {}
    for kind, art in anim._poly_art.items():
        for key, (shaft, head) in art["arrows"].items():
            if head.get_visible():
                xs, ys = shaft.get_data()
                tips[(kind, key)] = (np.array([xs[0], ys[0]]), np.asarray(head.get_xy())[0])
    return pins, np.column_stack([x, y]), tips


class _Pose:
    """The last pose of a sweep, seen as a Solution's dicts (position, velocity, acceleration, omega)."""

    def __init__(self, w):
        for name in ("position", "velocity", "acceleration", "omega"):
            setattr(self, name, {key: v[-1] for key, v in getattr(w, name).items()})


def _solved(m, angles):
    """velpoly.solve at the last of ``angles`` where the shorter way from the drawn pose reaches it, else
    the sweep along the frames' own path (a range over half a turn is walked, never jumped)."""
    try:
        return velpoly.solve(m, angle=float(angles[-1]))
    except velpoly.AssemblyError:   # walked from the drawn pose, as the animation walks there
        from velpoly.solution import driver_reference_angle
        ref, target = driver_reference_angle(m), float(angles[-1])
        path = np.linspace(ref, target, int(abs(target - ref) // 2) + 2)[1:]
        w = velpoly.sweep(m, path)
        assert len(w.angles) == len(path), w.stopped
        return _Pose(w)


def check_frame(anim, k, tol=1e-9):
    """Frame k's drawing equals velpoly.solve at the frame's driver angle (the velocities reversed on the
    way back, accelerations alike): positions, absolute velocity and acceleration images, the table."""
    m, plan = anim.m, anim.plan
    sol = _solved(m, plan.angles[:k + 1])
    size = m.size
    pins, dots, tips = drawn(anim, k)
    for p, c in pins.items():
        key = p if p in sol.position else next(q for q in sol.position if q.startswith(p + "@"))
        assert np.allclose(c, sol.position[key], atol=tol * size), (k, p)
    sense = plan.sense[k]
    vmax = max(float(np.hypot(*v)) for v in sol.velocity.values())
    seen = 0
    for (kind, key), (tail, tip) in tips.items():
        if not key.startswith("abs-"):
            continue
        pk = key[4:]
        n = anim.reduction[kind][k]   # a frame the panel cannot hold at its scale: drawn at 1/n of it, and says so
        assert anim._poly_art[kind]["note"].get_text() == ("" if n == 1 else f"drawn at 1/{n} scale")
        want = (sol.velocity[pk] * sense if kind == "velocity" else sol.acceleration[pk]) / n
        ref = (vmax if kind == "velocity" else max(float(np.hypot(*a)) for a in sol.acceleration.values())) / n
        assert np.allclose(tail, 0.0) and np.allclose(tip, want, atol=1e-7 * ref), (k, kind, pk, tip, want)
        seen += 1
    assert seen >= 1
    for name, (t, vals, dec) in anim.table.items():
        if name.startswith(r"$\omega_{"):
            lk = name[len(r"$\omega_{"):-2]
            assert vals[k] == pytest.approx(sol.omega[lk] * sense, abs=1e-9 * max(1.0, abs(sol.omega[lk])))
            assert float(t.get_text().replace("−", "-")) == pytest.approx(sol.omega[lk] * sense, abs=10.0 ** -dec)


@ON_COUPLER
def test_a_coupler_is_drawn_as_a_plate_as_in_the_space_diagram(coupler_anim):
    """A link of three points is one plate with its corners at its points in every frame (as the space
    diagram draws it: issue 17 item 7), not bars about them; a bar stays a bar."""
    from velpoly.render.displacement import plate_outline
    anim = coupler_anim
    m = anim.m
    plates = [lk for lk in anim.bodies if len(m.link(lk).points) >= 3]
    assert plates
    for k in (0, len(anim.sols) // 2):
        anim.update(k)
        sol = anim.sols[k]
        for lk, patch in anim.bodies.items():
            xy = patch.get_path().vertices[:-1]
            corners = np.array([sol.place(lk, p) for p in m.link(lk).points], float)
            if lk in plates:
                assert plate_outline(sol, lk, anim.bw) is not None
                # every corner of the drawn outline is one of the link's points, and every point a corner
                assert all(np.min(np.hypot(*(corners - v).T)) < 1e-9 for v in xy), lk
                assert all(np.min(np.hypot(*(xy - c).T)) < 1e-9 for c in corners), lk
            else:   # a bar: rounded, half a bar's width about its points
                assert len(xy) > 8 and np.max(np.hypot(*(xy - corners[0]).T)) > anim.bw / 2 * 0.99


def test_a_full_turn_is_one_frame_every_two_degrees_in_the_sense_of_omega():
    for omega in (10.0, -10.0):
        m = velpoly.load(fourbar(omega=omega))
        plan = plan_frames(m)
        assert len(plan) == 180 and plan.rocks is None and (plan.sense == 1).all()
        steps = np.diff(plan.angles)
        assert np.allclose(steps, 2.0 * math.copysign(1, omega))
        assert "full turn" in plan.caption


def test_generated_fourbars_draw_the_solved_poses_first_and_last():
    rng = np.random.default_rng(20261125)
    done = 0
    while done < 3:
        a, b, c, d = rng.uniform(2.0, 10.0, 4)
        theta = rng.uniform(0, 360)
        try:
            m = velpoly.load(fourbar(a=a, b=b, c=c, d=d, theta=theta, omega=rng.choice([-1, 1]) * rng.uniform(1, 20),
                                     alpha=rng.uniform(-5, 5)))
            velpoly.solve(m)
        except velpoly.VelpolyError:
            continue          # this four-bar does not assemble, or not here
        plan = plan_frames(m, 20.0)
        anim = Animator(plan, "full", "textbook" if done % 2 else "slides", SMALL)
        for k in (0, len(plan) - 1):
            check_frame(anim, k)
        done += 1


def test_a_rocking_crank_runs_its_range_out_and_back_with_the_driver_reversed():
    m = velpoly.load(fourbar(a=7, b=5, c=6, d=9, theta=60))         # non-Grashof: toggles at +-85.9 deg
    plan = plan_frames(m, 5.0)
    lo, hi = plan.rocks
    assert lo == pytest.approx(-85.9, abs=0.02) and hi == pytest.approx(85.9, abs=0.02)
    assert "rocks between −85.9° and 85.9°" in plan.caption.replace("-", "−")
    ang = plan.angles
    turn = int(np.argmax(ang))
    assert (np.diff(ang[:turn + 1]) > 0).all() and (np.diff(ang[turn:]) < 0).all()   # up, then back down
    assert lo < ang.min() and ang.max() < hi                                         # never at a toggle
    assert ang.min() - lo <= 2.5 + 1e-9 and hi - ang.max() <= 2.5 + 1e-9           # but close to it
    assert np.abs(np.diff(ang)).max() <= 5.0 + 1e-9
    assert (plan.sense[:turn + 1] == 1).all() and (plan.sense[turn + 1:] == -1).all()
    # looping: the last frame is one step from the first
    assert abs(ang[-1] - ang[0]) <= 5.0 + 1e-9
    anim = Animator(plan, "full", "slides", SMALL)
    for k in (0, turn, turn + 1, len(plan) - 1):
        check_frame(anim, k)


def test_a_slider_driver_runs_its_stroke_out_and_back():
    d = {"points": {"O2": [0.0, 0.0], "A": [2.0, 2.2], "B": [9.0, 1.0]},
         "links": {"1": {"points": ["O2"], "frame": True}, "2": {"points": ["O2", "A"]},
                   "3": {"points": ["A", "B"]}, "4": {"points": ["B"]}},
         "sliders": [{"block": "4", "guide": "1", "point": "B", "angle": 0.0}],
         "driver": {"slider": "B", "speed": 2.0}}
    m = velpoly.load(d)
    plan = plan_frames(m, 10.0)
    ang = plan.angles
    turn = int(np.argmax(ang))
    assert turn > 3 and (np.diff(ang[:turn + 1]) > 0).all() and (np.diff(ang[turn:]) < 0).all()
    assert plan.rocks is not None and "runs between" in plan.caption
    anim = Animator(plan, "velocity", "slides", SMALL)
    pins, dots, tips = drawn(anim, len(plan) - 1)
    leg, i = plan.frames[-1]
    assert leg == 1 and plan.sense[-1] == -1
    sw = plan.legs[1]
    assert np.allclose(pins["A"], sw.position["A"][i])
    tip = [t for (kind, key), (_, t) in tips.items() if key == "abs-A"][0]
    assert np.allclose(tip, sw.velocity["A"][i])          # the reversed driver's sweep
    assert np.allclose(sw.velocity["A"][i], -plan.legs[0].velocity["A"][
        int(np.argmin(np.abs(plan.legs[0].angles - sw.angles[i])))], atol=1e-9)


def test_layout_and_scales_are_fixed_and_every_frame_is_in_view():
    m = velpoly.load(fourbar(coupler=(4.0, 30.0)))
    plan = plan_frames(m, 30.0)   # 12 frames (36 until the suite had to fit 2 minutes: 0.4 CPU s more)
    anim = Animator(plan, "full", "slides", SMALL)
    limits = {n: (ax.get_xlim(), ax.get_ylim(), tuple(ax.get_position().bounds)) for n, ax in anim.axes.items()}
    background = anim.background
    for k in range(len(plan)):
        anim.render(k)
        for n, ax in anim.axes.items():
            assert (ax.get_xlim(), ax.get_ylim(), tuple(ax.get_position().bounds)) == limits[n]
        for kind in ("velocity", "acceleration"):
            x0, x1 = anim.axes[kind].get_xlim()
            y0, y1 = anim.axes[kind].get_ylim()
            for v in anim.images[kind].values():
                assert x0 <= v[0] <= x1 and y0 <= v[1] <= y1
    assert anim.background is background                 # the still parts (scale bars ...) drawn once
    # each polygon panel is filled at its largest frame: the images' extreme reaches the panel's margin (at
    # the top, the band kept for the acceleration legend, test_audit7_animate)
    for kind in ("velocity", "acceleration"):
        x0, x1 = anim.axes[kind].get_xlim()
        y0, y1 = anim.axes[kind].get_ylim()
        bx0, by0, bx1, by1 = anim.boxes[kind]
        fill = max((bx1 - bx0) / (x1 - x0), (by1 - by0 + anim.band[kind]) / (y1 - y0))
        assert fill == pytest.approx(1 - 2 * 0.07, rel=1e-6)


def test_type_is_at_least_14_px_at_1920x1080():
    m = velpoly.load(fourbar(coupler=(4.0, 30.0)))
    anim = Animator(plan_frames(m, 30.0), "full", "slides")
    assert anim.size == (1920, 1080)
    anim.render(0)
    from matplotlib.text import Text
    texts = [t for t in anim.fig.findobj(Text) if t.get_text() and t.get_visible()]
    assert len(texts) > 20
    small = [(t.get_text(), t.get_fontsize() * anim.dpi / 72) for t in texts if t.get_fontsize() * anim.dpi / 72 < 14]
    assert not small


def test_labels_sit_beside_their_points():
    m = velpoly.load(fourbar(coupler=(4.0, 30.0)))
    anim = Animator(plan_frames(m, 30.0), "velocity", "slides", (1280, 720))
    for k in (0, 5):
        anim.render(k)
        for p, t in anim.point_labels.items():
            assert np.allclose(t.xy, anim.points[p])
            assert 5 <= math.hypot(*t.get_position()) * anim.dpi / 72 <= 60     # pixels from the point


@ON_COUPLER
@pytest.mark.parametrize("suffix", [".gif", ".png", ".pdf"])
def test_each_format_is_written_and_readable(tmp_path, suffix, coupler_anim):
    from PIL import Image
    anim = coupler_anim
    calls = []
    out = write_animation(anim, tmp_path / f"a{suffix}", 10, lambda d, n: calls.append((d, n)))
    assert calls == [(k + 1, 12) for k in range(12)]
    data = out.read_bytes()
    if suffix == ".pdf":
        assert data.startswith(b"%PDF-") and len(re.findall(rb"/Type /Page\b", data)) == 12
        assert re.search(rb"/Count 12\b", data)
        start = int(data.rsplit(b"startxref", 1)[1].split()[0])
        table = data[start:].split(b"\n")
        n = int(table[1].split()[1])
        for i, row in enumerate(table[3:3 + n - 1], 1):      # every object where the xref says it is
            off = int(row.split()[0])
            assert data[off:].startswith(b"%d 0 obj" % i)
        return
    with Image.open(out) as im:
        assert im.format == ("GIF" if suffix == ".gif" else "PNG")
        assert im.n_frames == 12 and im.is_animated and im.size == SMALL
        for k in (0, 6, 11):
            im.seek(k)
            got = np.asarray(im.convert("RGB")).astype(int)
            want = anim.render(k)[..., :3].astype(int)
            assert np.abs(got - want).mean() < 3           # the frame itself, in 256 colours
    assert not list(tmp_path.glob(".*part"))


def test_mp4_needs_the_video_extra(tmp_path, capsys, monkeypatch):
    f = write(tmp_path, fourbar())
    import builtins
    real = builtins.__import__

    def no_ffmpeg(name, *a, **kw):
        if name == "imageio_ffmpeg":
            raise ImportError(name)
        return real(name, *a, **kw)
    monkeypatch.setattr(builtins, "__import__", no_ffmpeg)
    code, out, err = run(capsys, "animate", f, "-o", tmp_path / "a.mp4")
    assert code == 2 and "velpoly[video]" in err and "Traceback" not in err
    assert not (tmp_path / "a.mp4").exists() and not list(tmp_path.glob(".*part"))


@ON_COUPLER
def test_mp4_when_imageio_ffmpeg_is_there(tmp_path, coupler_anim):
    pytest.importorskip("imageio_ffmpeg")
    out = write_animation(coupler_anim, tmp_path / "a.mp4", 10)
    assert out.read_bytes()[4:8] == b"ftyp"


def test_an_html_animation_is_velpoly_html_s_page(tmp_path, capsys):
    """``animate -o PAGE.html`` writes the interactive page, the one ``velpoly html`` writes at that step. (Until
    issue 19 item 7 this test checked the command's refusal where velpoly.html is absent, and skipped: it always
    ships.)"""
    f = write(tmp_path, fourbar())
    assert run(capsys, "animate", f, "-o", tmp_path / "a.html", "--step", "45")[0] == 0
    assert run(capsys, "html", f, "-o", tmp_path / "b.html", "--step", "45")[0] == 0
    a = (tmp_path / "a.html").read_bytes()
    assert a == (tmp_path / "b.html").read_bytes() and a.startswith(b"<!DOCTYPE html>")


@pytest.mark.parametrize("args, where", [(["-o", "a.avi"], "-o"), (["-o", "a.gif", "--size", "12x9"], "--size"),
                                         (["-o", "a.gif", "--size", "big"], "--size"),
                                         (["-o", "a.gif", "--step", "0"], "--step"),
                                         (["-o", "a.gif", "--fps", "0"], "--fps"),
                                         (["-o", "a.mp4", "--size", "641x360"], "--size")])
def test_bad_options_are_input_errors(tmp_path, capsys, args, where):
    f = write(tmp_path, fourbar())
    argv = [str(tmp_path / a) if a.startswith("a.") else a for a in args]
    code, _, err = run(capsys, "animate", f, *argv)
    assert code == 2 and where in err and "Traceback" not in err
    assert not [p for p in tmp_path.iterdir() if p.name != "m.toml"]


def test_the_output_never_replaces_the_input(tmp_path, capsys):
    f = write(tmp_path, fourbar(), name="m.gif")
    before = f.read_bytes()
    code, _, err = run(capsys, "animate", f, "-o", f)
    assert code == 2 and f.read_bytes() == before


@ON_COUPLER
@pytest.mark.parametrize("error", [RuntimeError, KeyboardInterrupt])
def test_a_failure_leaves_no_file(tmp_path, monkeypatch, error, coupler_anim):
    anim = coupler_anim
    real = anim.render

    def fail(k):   # frame 1: after the samples (0 and 6) and with frame 0 written into the temporary file
        if k == 1:     # (frame 5 until the suite had to fit 2 minutes: four frames more a format, 0.8 CPU s)
            raise error("stop")
        return real(k)
    monkeypatch.setattr(anim, "render", fail)
    for suffix in (".gif", ".png", ".pdf"):
        with pytest.raises(error):
            write_animation(anim, tmp_path / f"a{suffix}", 10)
    assert not list(tmp_path.iterdir())


def test_the_command_writes_a_gif(tmp_path, capsys):
    from PIL import Image
    f = write(tmp_path, fourbar())
    code, out, err = run(capsys, "animate", f, "-o", tmp_path / "a.gif", "--step", "40", "--size", "640x360",
                         "--sheet", "acceleration", "--style", "textbook")   # (--step 20 until the suite had
    assert code == 0 and out.strip() == str(tmp_path / "a.gif")              # to fit 2 minutes: 0.2 CPU s more)
    with Image.open(tmp_path / "a.gif") as im:
        assert im.n_frames == 9 and im.size == (640, 360)


def test_a_contact_given_by_its_normal_only_cannot_be_animated(tmp_path, capsys):
    from mechanisms import CAM_FLAT
    f = tmp_path / "cam.toml"
    f.write_text(CAM_FLAT.replace('centres = ["K", "flat"]', "normal = 90"))
    code, _, err = run(capsys, "animate", f, "-o", tmp_path / "a.gif")
    assert code == 2 and "only the drawn pose can be analysed" in err and "Traceback" not in err
    assert not (tmp_path / "a.gif").exists()


def _stub(out: Path) -> Path:
    """A placeholder file where an animation would be written (its path, as gallery_animation returns it)."""
    out.write_bytes(b"GIF89a")
    return out


def test_the_gallery_gets_one_animation_a_family(tmp_path, monkeypatch):
    import shutil
    from PIL import Image
    from velpoly.gallery import build_gallery
    from velpoly.render import animate
    from test_gallery import fake_draw
    from paths import EXAMPLES as GALLERY
    src = tmp_path / "src"
    src.mkdir()
    for name in ("ex3_6_fourbar", "ex3_5_slider_crank", "stephenson_sixbar"):
        shutil.copy(GALLERY / f"{name}.toml", src)
    monkeypatch.setattr(animate, "GALLERY_STEP", 90.0)      # 4 frames (8 until the suite had to fit 2 minutes):
    # the hook, not the look, is tested here
    result = build_gallery(src, draw=fake_draw([]), animations=True)
    gifs = sorted(p.name for p in (src / "figures").glob("animate-*.gif"))
    assert gifs == ["animate-ex3_5_slider_crank.gif", "animate-ex3_6_fourbar.gif"]   # a family's example each
    assert all(Path(src / "figures" / g) in result.written for g in gifs)
    readme = (src / "README.md").read_text()
    assert "## Animations" in readme and "](figures/animate-ex3_6_fourbar.gif)" in readme
    with Image.open(src / "figures" / "animate-ex3_6_fourbar.gif") as im:
        assert im.size == animate.GALLERY_SIZE and im.n_frames == 4
    plain = tmp_path / "plain"
    plain.mkdir()
    shutil.copy(GALLERY / "ex3_6_fourbar.toml", plain)
    build_gallery(plain, draw=fake_draw([]))                  # not asked for: none
    assert not list((plain / "figures").glob("animate-*")) and "## Animations" not in (plain / "README.md").read_text()
    # which families a build with names animates (the GIF itself is the first build's, checked above): each
    # animation asked for is written as a stub, not drawn again (issue 19 item 7, twelfth session: 0.7 CPU s)
    asked = []
    monkeypatch.setattr(animate, "gallery_animation", lambda m, out: asked.append(out.name) or _stub(out))
    some = tmp_path / "some"
    build_gallery(src, some, draw=fake_draw([]), animations=True, names=["ex3_5_slider_crank", "stephenson_sixbar"])
    assert asked == ["animate-ex3_5_slider_crank.gif"]
    assert [p.name for p in (some / "figures").glob("animate-*")] == ["animate-ex3_5_slider_crank.gif"]   # theirs only


def test_sweep_gif_is_drawn_by_the_animate_renderer(tmp_path):
    from PIL import Image
    from velpoly.render.sweep import GIF_SIZE, write_gif
    from velpoly.sweeps import run_cycle
    m = velpoly.load(fourbar(coupler=(4.0, 30.0)))
    sw = run_cycle(m, 60.0)   # 6 frames (12 until the suite had to fit 2 minutes)
    out = write_gif(sw, tmp_path / "c.gif")
    with Image.open(out) as im:
        assert im.n_frames == 6 and im.size == GIF_SIZE
        im.seek(0)
        first = np.asarray(im.convert("RGB")).astype(int)
    from velpoly.render.animate import FramePlan
    plan = FramePlan(m, (sw,), tuple((0, i) for i in range(6)), sw.angles, np.ones(6), None, "", 0.0)
    anim = Animator(plan, "velocity", "textbook", GIF_SIZE)
    pins, _, _ = drawn(anim, 0)
    assert np.allclose(pins["A"], sw.position["A"][0])
    top = GIF_SIZE[1] // 8                       # below the title and the caption (the sweep's words differ)
    assert np.abs(first[top:] - anim.render(0)[top:, :, :3].astype(int)).mean() < 3   # the same picture


def test_names_that_look_like_mathtext_are_animated_as_written(tmp_path, capsys):
    """Point and link names such as ``$B$``, ``\\frac{a}`` or ``\\`` are drawn literally in every frame
    (FORMAT.md: user strings are never parsed as mathtext), never an internal ParseSyntaxException."""
    d = fourbar(theta=40.0)
    rename = {"A": "$A$", "B": r"\frac{a}"}
    text = json.dumps(d)
    for old, new in rename.items():
        text = text.replace(f'"{old}"', json.dumps(new))
    d = json.loads(text)
    d["links"]["\\"] = d["links"].pop("3")
    d["title"] = r"$\sqrt{$ four-bar"
    m = velpoly.load(d)
    plan = plan_frames(m, 45.0)
    anim = Animator(plan, "velocity", "slides", SMALL)
    out = tmp_path / "names.gif"
    write_animation(anim, out, 5.0)
    from PIL import Image
    with Image.open(out) as im:
        assert im.n_frames == len(plan)


# the slots turn a whole turn (0.05 CPU s to plan): seed 2611's rocked (0.5-0.6 CPU s each finding where by
# continuation), a path the track does not depend on (its extent is over the frames, out and back or round)
@pytest.mark.parametrize("kind,variant,seed", [("slot", "straight offset", 2601), ("slot", "circular", 2600),
                                               ("inverted slider-crank", "swinging-block slider", 2611)])
def test_a_pin_or_block_stays_in_the_track_its_moving_link_carries(kind, variant, seed):
    """A slot or guide cut in a moving link is drawn in every frame (it was not drawn at all: a slot's pin and a
    swinging block were seen off the link that carries them), long enough for the whole travel, and joined to its
    link: in every frame the pin (block) lies in the track's cut and in the link's body, and the link's body is
    one piece holding its own points, of one shape (its area) in every frame."""
    from matplotlib.path import Path as MPath
    from shapely.geometry import Point, Polygon as SPolygon
    from zoo import specimen
    sp = specimen(np.random.default_rng(seed), kind, variant)
    m = sp.drawn.mechanism
    anim = Animator(plan_frames(m, 30.0), "velocity", "textbook", SMALL)
    movers = {s.slot: (s.link, s.pin) for s in m.slots} | {s.guide: (s.block, s.point) for s in m.sliders}
    assert anim.tracks
    areas = {}
    for k in range(0, len(anim.plan), 3):
        anim.update(k)
        sol = anim.sols[k]
        for (lk, point, _), cut in zip(anim.tracks, anim.cuts):
            mover, _ = movers[lk]
            at = sol.place(mover, point)
            assert cut.get_path().contains_point(at), (k, lk)
            rings = [SPolygon(r) for r in anim.bodies[lk].get_path().to_polygons()]
            outer = max(rings, key=lambda r: r.area)
            areas.setdefault(lk, []).append(outer.area)
            assert outer.buffer(1e-9 * m.size).contains(Point(*at)), (k, lk)
            for q in m.link(lk).points:
                if q != point:
                    assert outer.buffer(1e-6 * m.size).contains(Point(*sol.place(lk, q))), (k, lk, q)
    for lk, a in areas.items():     # a rigid body keeps its shape: one choice of plate or bars for every frame
        assert max(a) - min(a) <= 1e-3 * max(a), (lk, a)
