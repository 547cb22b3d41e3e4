"""Text off the lines where a crowd leaves no free place (issue 17, item 4; render/kennedy.py, render/scalebar.py).

- A pole's label with no free place at any size or reach goes where it covers least: at the size (its own, 0.85,
  0.72 of it) whose least-covering place meets the fewest Kennedy lines, marks and leaders
  (``kennedy._least_covering``), out to the longest leaders' rings where nearer places all cover one. Before, it
  went at its own size, on a Kennedy line where a smaller box had a place on none (Example 3.4's P26 on its slide:
  five poles 2-x within 1.3 mm at the lever's pivot).
- A scale bar whose room (the bar with its numbers) is free nowhere along the panel's sides stands where its
  numbers meet the fewest lines, labels and marks, then its bar, over a grid across the panel
  (``scalebar._least_on_texts``). Before, it took the side's place meeting the fewest things, its numbers
  among them: the cam with a roller follower's "20000 mm/s²" on three vectors of its acceleration polygon (slides).

Checked at the data level on seeded scenes of the kind the sheets draw: a crowd of Kennedy lines (segments
registered as the poles drawing registers them) about a pole's ring; a panel crossed by vectors (Line2D drawn and
registered as a polygon's shafts). Each scene is tested against a brute-force answer from the drawn artists (the
label's least-covering places at the three sizes; every translation of the scale bar's drawn boxes on a 1 mm
grid), so the checks hold where a crowd does leave a place, and the scenes are chosen so that several leave one
only the fallback finds (on e730b9f: 2 of the 6 crowds had their label on a line, 3 of the 6 panels a scale bar's
number on a vector)."""
from __future__ import annotations

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
import shapely
from shapely import STRtree
from shapely.geometry import LineString, Point, box

import sheets
from velpoly.render import kennedy
from velpoly.render.canvas import fit_view, view_box
from velpoly.render.displacement import SMALLER
from velpoly.render.labels import placer, segment
from velpoly.render.scalebar import scale_bar
from velpoly.render.style import get_style, rc_context


def _panel(side_in: float, view: bool = True):
    """An axes filling a ``side_in`` inch square figure, 1 unit a cm, centred on the origin (no view set: the
    drawing sets its own)."""
    fig = Figure(figsize=(side_in, side_in), dpi=72)
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0, 0, 1, 1))
    if view:
        half = side_in * 2.54 / 2
        fit_view(ax, (-half, -half, half, half), scale=1.0, margin=0.0)
        ax.set_axis_off()
    return fig, ax


def _data_box(ax, t):
    """The Text's window extent in data coordinates (shapely), shrunk by a pixel."""
    bb = t.get_window_extent(ax.figure.canvas.get_renderer())
    (x0, y0), (x1, y1) = ax.transData.inverted().transform([[bb.x0 + 1, bb.y0 + 1], [bb.x1 - 1, bb.y1 - 1]])
    return box(x0, y0, x1, y1)


def test_crowded_pole_labels_go_at_the_size_off_the_lines():
    """A seeded crowd (the second of seed 1) of six poles within a few millimetres, 12 to 20 Kennedy lines through
    them (or through one and out), in a 7.6 cm panel, labelled in turn: each label meets no Kennedy line or mark wherever, at one of
    its three sizes, the placer's least-covering place meets none (brute force: ``_least_bad`` at each size before
    the label is placed), and where only a smaller size has such a place it is set smaller (three labels; on
    e730b9f the last stood on a line at its own size)."""
    st = get_style("slides")
    size = st.font_size * 0.9
    rng = np.random.default_rng(1)
    smaller = 0
    with rc_context(st):
        for crowd in range(2):
            fig, ax = _panel(3.0)
            pl = placer(ax)
            poles = rng.normal(0, 0.08, (6, 2))
            for _ in range(int(rng.integers(12, 20))):
                i, j = rng.choice(len(poles), 2, replace=False) if rng.random() < 0.6 else (rng.integers(len(poles)), None)
                a = poles[i]
                b = poles[j] if j is not None else rng.uniform(-3.8, 3.8, 2)
                d = (b - a) / max(float(np.hypot(*(b - a))), 1e-9) * 7.6
                pl.add_obstacle(segment(a - d, a + d), hard=True)    # as draw_poles registers a Kennedy line
                pl.add_obstacle(segment(a - d, a + d), hard=False)
            for p in poles:
                pl.add_obstacle(Point(*p).buffer(0.085))   # the rings
            for k, p in enumerate(poles if crowd == 1 else ()):   # (the first: drawn for the seed's sake)
                probe = ax.text(0, 0, "$P_{26}$")
                free = []   # whether the least-covering place at each size meets no Kennedy line or mark
                for f in (1.0,) + SMALLER:
                    probe.set_fontsize(size * f)
                    w, h = pl.text_size(probe)
                    free.append(pl._least_bad(p, w, h, -45.0, 2.5, True, True)[0][1] == 0)
                probe.remove()
                t = kennedy._place_free(pl, p, "$P_{26}$", prefer=-45.0, gid=f"label-pole-{k}", fontsize=size)
                hard = [g for g in pl._hard if g.intersects(_data_box(ax, t))]
                if any(free):
                    assert not hard, (k, free, t.get_fontsize())
                if not free[0] and any(free):
                    smaller += 1
                    assert t.get_fontsize() < size
    assert smaller >= 2   # the crowd this test is about


def _vectors(ax, pl, rng, n: int) -> list:
    """``n`` random vectors' shafts across the panel, drawn and registered as a polygon's (soft obstacles)."""
    x0, y0, x1, y1 = view_box(ax).bounds
    out = []
    for _ in range(n):
        p, q = rng.uniform((x0, y0), (x1, y1)), rng.uniform((x0, y0), (x1, y1))
        ax.add_line(Line2D([p[0], q[0]], [p[1], q[1]], lw=1.0))
        out.append(LineString([tuple(p), tuple(q)]))
        pl.add_obstacle(out[-1], hard=False)
    return out


def test_scale_bar_numbers_off_the_vectors():
    """Seeded panels (5 cm square) crossed by 7 to 11 vectors, where the scale bar's room is free nowhere along the
    sides: the bar's numbers meet no vector wherever some translation of the drawn bar and numbers (every 1 mm
    across the panel, 0.35 cm in from its edges) has them on none; the bar stays in the panel."""
    st = get_style("slides")
    rng = np.random.default_rng(3)
    among = 0
    with rc_context(st):
        for _ in range(6):
            fig, ax = _panel(5.0 / 2.54)
            pl = placer(ax)
            lines = _vectors(ax, pl, rng, int(rng.integers(7, 12)))
            arts = scale_bar(ax, st, "mm", 2, target_cm=1.5)
            bar, texts = arts[0], [a for a in arts if hasattr(a, "get_text")]
            (bx, by), w, h = bar.get_xy(), bar.get_width(), bar.get_height()
            shapes = [box(bx, by, bx + w, by + h)] + [_data_box(ax, t) for t in texts]
            view = view_box(ax).buffer(-0.35 + 1e-9)
            assert view.buffer(0.35).contains(shapes[0])
            on = [g for g in lines if any(g.intersects(s) for s in shapes[1:])]
            x0, y0, x1, y1 = view.bounds
            room = np.array([s.bounds for s in shapes])
            dx, dy = np.meshgrid(np.arange(x0 - room[:, 0].min(), x1 - room[:, 2].max(), 0.1),
                                 np.arange(y0 - room[:, 1].min(), y1 - room[:, 3].max(), 0.1))
            dx, dy = dx.ravel(), dy.ravel()
            tree = STRtree(lines)
            taken = np.zeros(len(dx), bool)
            for x0_, y0_, x1_, y1_ in room[1:]:   # each number moved there, 1 mm to spare (corners every mm)
                moved = shapely.box(x0_ + dx - 0.1, y0_ + dy - 0.1, x1_ + dx + 0.1, y1_ + dy + 0.1)
                taken[np.unique(tree.query(moved, predicate="intersects")[0])] = True
            if not taken.all():
                assert not on, len(on)
            hull = box(*shapes[0].union(shapes[1]).union(shapes[2]).bounds)
            among += any(g.intersects(hull) for g in lines) and not on
    assert among >= 2   # panels where the bar stands among the vectors (a vector across its room), its numbers off them


def test_contact_normal_and_tangent_are_lines_labels_keep_off():
    """A contact given by its normal only is drawn as its tangent and normal through the contact point: lines the
    labels keep off (soft obstacles, as a slider's path). Seeded generated cams with a flat follower given by its
    normal, each space diagram drawn in a 10 cm square: no text meets those two lines (on e730b9f the contact
    point's name P sat on the tangent in 9 of seeds 0-7's 16 drawings, these three among them; in 8 of their 16
    displacement sheets)."""
    from velpoly.render.displacement import draw_mechanism
    from zoo import specimen
    for seed, style in ((5, "slides"), (5, "textbook"), (1, "slides")):
        sol = specimen(np.random.default_rng(seed), "contact", "cam flat follower by its normal").drawn
        st = get_style(style)
        with rc_context(st):
            fig, ax = _panel(4.0, view=False)
            draw_mechanism(sol, ax, style=st)
            contact = [LineString(ln.get_xydata()) for ln in ax.lines if ln.get_gid() is None and len(ln.get_xydata()) == 2]
            assert len(contact) >= 2
            on = [(t.get_text(), k) for t in ax.texts if t.get_text().strip()
                  for k, g in enumerate(contact) if g.intersects(_data_box(ax, t))]
            assert not on, (seed, style, on)


@sheets.on("slides")
def test_gallery_scale_bars_numbers_off_the_lines():
    """The cam with a roller follower's own sheet on slides (tests/sheets.py: drawn once, shared with
    test_render_gallery): no scale bar's number meets a line of its panel (Line2D as drawn; before, its
    acceleration polygon's "20000 mm/s²" sat on three vectors), and the acceleration polygon, which has a detail,
    is drawn at the scale where the bar's room is free (``detail.make_room``: 1 cm = 20000 mm/s², not 15000)."""
    from velpoly.render.canvas import per_cm
    fig = sheets.page("cam_roller_follower", "full", "slides")
    with sheets.styled("slides"):
        r = fig.canvas.get_renderer()
        for ax in fig.axes:
            lines = []
            for ln in ax.lines:
                xy = ax.transData.transform(ln.get_xydata())
                xy = xy[np.all(np.isfinite(xy), axis=1)]
                if len(xy) >= 2:
                    lines.append(LineString(xy))
            for t in ax.texts:
                if (t.get_gid() or "").startswith("scale-bar"):
                    bb = t.get_window_extent(r)
                    b = box(bb.x0 + 1, bb.y0 + 1, bb.x1 - 1, bb.y1 - 1)
                    assert not any(g.intersects(b) for g in lines), (ax.get_label(), t.get_text())
        acc = next(ax for ax in fig.axes if ax.get_label() == "acceleration")
        assert any(p.get_gid() == "detail-frame" for p in acc.patches)
        assert per_cm(acc) == 20000
