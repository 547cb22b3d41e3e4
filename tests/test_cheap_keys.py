"""The cheaper ways velpoly's drawing asks the same questions give the same answers as the plain ones, on generated
cases of the whole class: the settings read for the text caches' keys (``textcache.rc_reader``, ``_font_key``), a
text's size measured without its box (``LabelPlacer.text_size``), and the placer's batch tests of boxes against
obstacles (``labels.meets_any``) and against points (``labels.all_farther``), with pairs on and next to their
boundaries."""
from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("matplotlib")

import matplotlib  # noqa: E402
import shapely  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.font_manager import FontProperties  # noqa: E402

from velpoly.render import labels, textcache  # noqa: E402
from velpoly.render.style import get_style, rc_context  # noqa: E402


def _plain_font_key(prop, dpi):
    """``textcache._font_key`` as it read the settings before (``rcParams[name]``)."""
    rc = matplotlib.rcParams
    return (tuple(prop.get_family()), prop.get_style(), prop.get_variant(), prop.get_weight(),
            prop.get_stretch(), prop.get_size_in_points(), str(prop.get_file()), prop.get_math_fontfamily(),
            tuple(tuple(v) if isinstance(v, list) else v for v in (rc[k] for k in textcache._RC)), dpi)


@pytest.mark.parametrize("style", ["textbook", "slides"])
def test_the_settings_read_for_a_key_are_rcparams_own(style):
    with rc_context(get_style(style)), matplotlib.rc_context({"font.serif": ["STIXGeneral", "DejaVu Serif"],
                                                             "text.hinting": "auto"}):
        get = textcache.rc_reader()
        rc = matplotlib.rcParams
        for k in rc:
            if k != "backend":
                assert get(k) is rc[k], k
        rng = np.random.default_rng(19)
        for _ in range(40):
            prop = FontProperties(family=str(rng.choice(["serif", "sans-serif", "DejaVu Sans", "STIXGeneral"])),
                                  style=str(rng.choice(["normal", "italic"])), size=float(rng.uniform(5, 14)),
                                  weight=str(rng.choice(["normal", "bold"])))
            dpi = float(rng.choice([72, 100, 200]))
            assert textcache._font_key(prop, dpi) == _plain_font_key(prop, dpi)
        # a setting changed is a key changed (read live, never kept)
        before = textcache._font_key(FontProperties(size=9), 72)
        with matplotlib.rc_context({"font.sans-serif": ["STIXGeneral"], "font.stretch": "condensed"}):
            assert textcache._font_key(FontProperties(size=9), 72) == _plain_font_key(FontProperties(size=9), 72)
            assert textcache._font_key(FontProperties(size=9), 72) != before


def test_a_texts_size_is_its_boxs():
    fig = Figure(figsize=(4, 3), dpi=72)
    textcache.new_canvas(fig)
    ax = textcache.add_axes(fig, [0.1, 0.1, 0.8, 0.8])
    ax.set_xlim(-3.0, 7.0)
    ax.set_ylim(2.0, 9.5)
    pl = labels.placer(ax)
    rng = np.random.default_rng(7)
    for i in range(24):
        s = ["B", "$V_{B}$", "12.5 mm", r"$\omega_{3}$", "O₂"][i % 5]
        rot = float(rng.choice([0.0, 0.0, 30.0, 90.0, 271.5]))
        t = ax.text(float(rng.uniform(-3, 7)), float(rng.uniform(2, 9)), s, rotation=rot,
                    fontsize=float(rng.uniform(6, 12)))
        pad, pp = float(rng.choice([0.0, 1.0, 3.5])), (None if i % 2 else float(rng.uniform(0.01, 0.2)))
        t.set_rotation(0)
        x0, y0, x1, y1 = pl.box_of(t, pad, pp).bounds   # what text_size measured: the box of the unrotated text
        t.set_rotation(rot)
        assert pl.text_size(t, pad, pp) == (x1 - x0, y1 - y0)
        assert t.get_rotation() == rot


def _obstacles(rng, n):
    """Boxes (some touching or sharing an edge with the candidates' grid), segments, polygons, circles, an empty
    geometry and a missing one."""
    out = []
    for i in range(n):
        kind = i % 6
        x, y = (float(v) for v in rng.integers(0, 8, 2))
        if kind == 0:
            out.append(shapely.box(x, y, x + 1.0, y + float(rng.choice([0.5, 1.0]))))
        elif kind == 1:
            out.append(shapely.LineString([(x, y), (x + float(rng.uniform(-2, 2)), y + float(rng.uniform(-2, 2)))]))
        elif kind == 2:
            out.append(shapely.Polygon([(x, y), (x + 2, y + 0.5), (x + 0.5, y + 1.5)]))
        elif kind == 3:
            out.append(shapely.Point(x + 0.5, y).buffer(float(rng.uniform(0.2, 0.8)), quad_segs=8))
        elif kind == 4:
            out.append(shapely.LineString([(x, y), (x, y + 2.0)]))   # along a grid line: touching
        else:
            out.append(shapely.Polygon() if i % 12 == 5 else shapely.box(x + 0.25, y + 0.25, x + 0.75, y + 0.75))
    return np.array(out + [None], dtype=object)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_meets_any_is_shapelys_every_pair(seed):
    rng = np.random.default_rng(seed)
    obstacles = _obstacles(rng, 30)
    x0 = rng.integers(-1, 9, 120).astype(float) + rng.choice([0.0, 0.5, 1e-12], 120)
    y0 = rng.integers(-1, 9, 120).astype(float)
    w = rng.choice([0.5, 1.0, 1e-9], 120)
    boxes = shapely.box(x0, y0, x0 + w, y0 + w)
    want = shapely.intersects(obstacles[None, :], boxes[:, None]).any(axis=1)
    got = labels.meets_any(obstacles, boxes)
    assert got.dtype == bool and (got == want).all()
    assert 0 < want.sum() < len(want)   # both answers among them
    assert not labels.meets_any(np.array([], dtype=object), boxes).any()


@pytest.mark.filterwarnings("ignore::RuntimeWarning")   # (shapely on the NaN corners, as for the plain test)
@pytest.mark.parametrize("seed", [4, 5, 6])
def test_all_farther_is_shapelys_every_pair(seed, monkeypatch):
    rng = np.random.default_rng(seed)
    limit = float(rng.uniform(0.5, 2.0))
    n = 90
    cx, cy, r = rng.uniform(-50, 50, n), rng.uniform(-50, 50, n), rng.uniform(0.1, 3.0, n)
    corners = np.column_stack([cx - r, cy - r, cx + r, cy + r])
    # each box's points: inside it, on its edge, at the limit and a hair either side of it off an edge or a
    # corner, far off; with a few boxes missing (a NaN corner) and a point that is not finite
    xy = []
    for (a, b, c, d) in corners[:6]:
        for eps in (-1e-12, 0.0, 1e-12, 1e-7):
            xy += [(c + limit * (1 + eps), (b + d) / 2), ((a + c) / 2, b - limit * (1 + eps)),
                   (c + limit * (1 + eps) / np.sqrt(2), d + limit * (1 + eps) / np.sqrt(2))]
        xy += [((a + c) / 2, (b + d) / 2), (a, b), (a - 100.0, d)]
    xy = np.array(xy)
    corners[7] = [np.nan, 0.0, 1.0, 1.0]
    boxes = shapely.box(*corners.T)
    for i in range(len(boxes)):
        if boxes[i] is None:
            boxes[i] = shapely.geometry.box(*corners[i])
    points = shapely.points(xy)
    for one in range(len(xy)):   # point by point: every pair's answer
        p, q = points[one:one + 1], xy[one:one + 1]
        want = (shapely.distance(p[None, :], boxes[:, None]) > limit).all(axis=1)
        assert (labels.all_farther(p, q, boxes, corners, limit) == want).all(), one
    want = (shapely.distance(points[None, :], boxes[:, None]) > limit).all(axis=1)
    asked, plain = [], shapely.distance

    def distance(a, b):
        asked.append(len(a))
        return plain(a, b)
    monkeypatch.setattr(labels.shapely, "distance", distance)
    assert (labels.all_farther(points, xy, boxes, corners, limit) == want).all()
    assert sum(asked) < len(points) * len(boxes) / 5   # GEOS asked of the few pairs near their limit (a NaN box's)
    monkeypatch.undo()
    bad = np.vstack([xy, [[np.nan, 0.0]]])
    want = (shapely.distance(shapely.points(bad)[None, :], boxes[:, None]) > limit).all(axis=1)
    assert (labels.all_farther(shapely.points(bad), bad, boxes, corners, limit) == want).all()
