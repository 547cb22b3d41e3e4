"""Each example its own sheet (issue 17, item 1): ``[drawing] sheet`` is the sheet ``velpoly draw``
draws without --sheet and the gallery shows; ``--sheet displacement`` is the space diagram alone
with the problem's data and no answers (no polygon, no pole, no computed value in any text).
Checked on generated mechanisms (tests/zoo.py) and on the built-in instant-centre examples."""
from __future__ import annotations

import copy
import re

import numpy as np
import pytest

import velpoly
from velpoly.cli import main
from velpoly.errors import InputError
from velpoly.render import sheet
from velpoly.render.options import SHEETS, drawing_options
from velpoly.render.style import get_style, rc_context

import sheets
import zoo
from paths import EXAMPLES

SEED = 1717
KINDS = ("four-bar", "slider-crank", "inverted slider-crank", "six-bar", "slot", "contact")
SLIDER_DRIVEN = (("slider-crank", "offset slider"), ("inverted slider-crank", "curved slider"))


@pytest.fixture(scope="module")
def specimens():
    """One of each kind (its first variant), then two driven by a slider."""
    rng = np.random.default_rng(SEED)
    pairs = [(kind, zoo.KINDS[kind][1][0]) for kind in KINDS] + list(SLIDER_DRIVEN)
    return [zoo.specimen(rng, kind, variant) for kind, variant in pairs]


def _with_sheet(mech: dict, name) -> dict:
    mech = copy.deepcopy(mech)
    mech.setdefault("drawing", {})["sheet"] = name
    return mech


def test_the_sheet_option_is_checked_on_load(specimens):
    mech = specimens[0].mech
    for name in SHEETS:
        assert drawing_options(velpoly.load(_with_sheet(mech, name))).sheet == name
    assert drawing_options(velpoly.load(mech)).sheet == "full"   # the default
    for bad in ("pole", "Poles", 3, ["poles"], ""):
        with pytest.raises(InputError) as e:
            velpoly.load(_with_sheet(mech, bad))
        assert e.value.where == "drawing.sheet" and "valid sheets: " + ", ".join(SHEETS) in e.value.what


def _ids(svg: str) -> set:
    return set(re.findall(r'id="([^"]+)"', svg))


def test_draw_draws_the_files_own_sheet(tmp_path, specimens):
    """Without --sheet the file's [drawing] sheet; --sheet overrides it; a bad one is exit 2."""
    import tomllib   # noqa: F401  (the files are written as TOML by the zoo's own writer below)
    with sheets.unlabelled_mechanism():   # the sheets' panels and tables read (ids), not the space diagram's marks
        for sp, name, panels in zip(specimens[:3], ("poles", "displacement", "velocity"),
                                    ({"caption-poles", "caption-kennedy"}, {"caption-mechanism", "data-table"},
                                     {"caption-mechanism", "caption-velocity"})):
            src = tmp_path / f"{name}.toml"
            src.write_text(_toml(_with_sheet(sp.mech, name)))
            out = tmp_path / f"{name}.svg"
            assert main(["draw", str(src), "-o", str(out)]) == 0
            ids = _ids(out.read_text())
            assert panels <= ids, (name, panels - ids)
            others = {"caption-poles", "caption-kennedy", "caption-velocity", "caption-acceleration"} - panels
            assert not ids & others, (name, ids & others)
        # the option wins (shown once, on the poles file: the displacement sheet, not the file's poles sheet; the
        # velocity sheet until issue 19 item 7, the dearer to draw for the same check)
        src = tmp_path / "poles.toml"
        assert main(["draw", str(src), "--sheet", "displacement", "-o", str(tmp_path / "override.svg")]) == 0
        ids = _ids((tmp_path / "override.svg").read_text())
        assert "data-table" in ids and not ids & {"caption-kennedy", "caption-poles", "caption-velocity"}, ids
        bad = tmp_path / "bad.toml"
        bad.write_text(_toml(_with_sheet(specimens[0].mech, "handout")))
        assert main(["draw", str(bad), "-o", str(tmp_path / "bad.svg")]) == 2
        assert not (tmp_path / "bad.svg").exists()


def _toml(d, prefix="") -> str:
    """A small TOML writer for the zoo's dicts (tables, inline tables, arrays, strings, numbers)."""
    def val(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
        if isinstance(v, (int, float)):
            return repr(float(v)) if isinstance(v, float) else str(v)
        if isinstance(v, dict):
            return "{ " + ", ".join(f'"{k}" = {val(x)}' for k, x in v.items()) + " }"
        return "[" + ", ".join(val(x) for x in v) + "]"
    lines, tables = [], []
    for k, v in d.items():
        if isinstance(v, dict):
            tables.append((k, v))
        else:
            lines.append(f'"{k}" = {val(v)}')
    for k, v in tables:
        lines.append(f"\n[{prefix}{k}]")
        lines.append(_toml(v, prefix=f"{prefix}{k}.").strip())
    return "\n".join(lines) + "\n"


def test_the_gallery_shows_each_examples_own_sheet(tmp_path):
    """The instant-centre examples are shown as their poles sheet, the others as the full sheet."""
    from velpoly.gallery import build_gallery
    drawn = {}

    def draw(sol, target, sheet, style, steps):
        drawn[target.stem] = sheet
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(b"")
        return [target]
    names = ["ex3_7_instant_centres", "ex3_8_instant_centres_cw", "ex3_6_fourbar"]
    build_gallery(out=tmp_path, draw=draw, names=names, copy=False)
    assert drawn == {"ex3_7_instant_centres": "poles", "ex3_8_instant_centres_cw": "poles",
                     "ex3_6_fourbar": "full"}
    for stem in names[:2]:
        assert drawing_options(velpoly.load(EXAMPLES / f"{stem}.toml")).sheet == "poles"


ANSWER_GIDS = ("auxiliary-", "chord-", "construction-", "image-", "kennedy-", "label-pole-", "label-velocity",
               "label-acceleration", "origin-", "pole-", "results-table")
_NUMBER = re.compile(r"[−-]?\d+(?:\.\d+)?(?:×10[⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)?")


def _numbers(text: str, ulp: bool = False) -> list:
    """The numbers printed in ``text``; with ``ulp``, each as (value, half its last printed digit's unit)."""
    out = []
    for s in _NUMBER.findall(text):
        s = s.replace("−", "-")
        mant, _, e = s.partition("×10")
        e = int(e.translate(str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789"))) if e else 0
        decimals = len(mant.partition(".")[2])
        x, half = float(mant) * 10 ** e, 0.5 * 10 ** (e - decimals)
        out.append((x, half) if ulp else x)
    return out


def _answers(sol) -> list[float]:
    """Every value the analysis computes (and the problem does not give): the driven links' ω and
    α, every moving point's speed and acceleration, every relative pole's coordinates."""
    m = sol.mechanism
    drv = m.driver
    vals = []
    for lk in (k.name for k in m.moving_links):
        if lk != drv.link:
            vals += [sol.omega[lk], sol.alpha[lk]]
    for key, v in sol.velocity.items():
        vals.append(float(np.hypot(*v)))
    for key, a in sol.acceleration.items():
        if np.all(np.isfinite(a)):
            vals.append(float(np.hypot(*a)))
    from velpoly.poles import locate_poles
    for p in locate_poles(sol).poles.values():
        if p.order > 0 and p.position is not None:
            vals += [float(p.position[0]), float(p.position[1])]
    given = [abs(drv.omega), abs(drv.alpha), abs(drv.speed), abs(drv.accel)]
    scale = max(abs(v) for v in vals + [1e-300])
    return [abs(v) for v in vals if abs(v) > 1e-6 * scale and
            not any(abs(abs(v) - g) <= 1e-6 * abs(v) for g in given)]


def _given(sol) -> list[float]:
    """What the problem gives: the driver's motion and angle, each link's point-to-point lengths, the
    frame points' coordinates."""
    m = sol.mechanism
    drv = m.driver
    out = [abs(drv.omega), abs(drv.alpha), abs(drv.speed), abs(drv.accel), abs(sol.driver_angle or 0)]
    for link in m.links:
        ps = [np.asarray(sol.position.get(f"{p}@{link.name}", sol.position.get(p)), float) for p in link.points]
        out += [float(np.hypot(*(a - b))) for i, a in enumerate(ps) for b in ps[i + 1:]]
    for p in m.frame.points:
        out += [abs(float(c)) for c in sol.position.get(p, sol.position.get(f"{p}@{m.frame.name}"))]
    return out


def test_the_displacement_sheet_shows_the_data_and_no_answers(specimens):
    assert sum(sp.drawn.mechanism.driver.is_slider for sp in specimens) == len(SLIDER_DRIVEN)
    with rc_context(get_style("textbook")):
        for sp in specimens:
            sol = sp.drawn
            cons = sheet.constructions(sol, "displacement")
            assert cons == sheet.Constructions()          # nothing constructed: nothing to give away
            fig = sheet.render_sheet(sol, "displacement", "textbook")
            axes = {ax.get_label(): ax for ax in fig.axes}
            assert set(axes) == {"mechanism", "table"}, sp.kind
            mech = axes["mechanism"]
            drawn = {a.get_gid() for a in mech.get_children()}
            assert {f"link-number-{k.name}" for k in sol.mechanism.moving_links} <= drawn, sp.kind   # the mechanism
            assert any(g.startswith("pin-") for g in drawn if g) and mech.lines, sp.kind
            gids = [a.get_gid() or "" for ax in fig.axes for a in ax.get_children()] + \
                   [t.get_gid() or "" for t in fig.texts]
            assert not [g for g in gids if g.startswith(ANSWER_GIDS)], sp.kind
            assert "data-table" in gids
            texts = [t.get_text() for t in fig.texts] + [t.get_text() for ax in fig.axes for t in ax.texts]
            # numbers of three significant digits or more (a link's number "3" or a scale bar's "0" tells nothing)
            shown = [(x, half) for t in texts for x, half in _numbers(t, ulp=True) if abs(x) >= 200 * half]
            shown = [(x, half) for x, half in shown if not any(abs(abs(x) - g) <= half * (1 + 1e-9)
                                                               for g in _given(sol))]   # the data, explained
            for v in _answers(sol):   # an answer rounded to a printed number's digits would be that number
                hit = [x for x, half in shown if abs(abs(x) - v) <= half * (1 + 1e-9)]
                assert not hit, f"{sp.kind}: the answer {v:.6g} is printed ({hit})"
            table = " ".join(t.get_text() for t in axes["table"].texts)
            # the data: the driver's ω (or a slider's speed) and every frame point are given
            drv = sol.mechanism.driver
            given = abs(drv.speed) if drv.is_slider else abs(drv.omega)
            assert any(abs(x - given) <= 1e-4 * given for x in _numbers(table)), sp.kind
            for p in sol.mechanism.frame.points:
                assert p in table


# -- item 6: the table shows what the teacher typed ------------------------------------------------------

def _with_reference(sp):
    """The specimen with book values on its last rows (the last driven link's ω and α, the last plain
    point's speed and acceleration), two of them explained by notes: they would be cut in file order."""
    sol = sp.drawn
    m = sol.mechanism
    lk = [k.name for k in m.moving_links if k.name != m.driver.link][-1]
    pts = [p for p in sol.velocity if "@" not in p and float(np.hypot(*sol.velocity[p])) > 0]
    p = pts[-1]
    mech = copy.deepcopy(sp.mech)
    mech["reference"] = {"source": "Problem 9.99", "omega": {lk: round(sol.omega[lk] * 1.33, 6)},
                         "alpha": {lk: round(sol.alpha[lk] * 0.9 + 1, 6)},
                         "speed": {p: round(float(np.hypot(*sol.velocity[p])) * 3.1, 6)},
                         "note": {f"omega_{lk}": f"misprint: the book's omega_{lk} carries a slip (for {sp.kind})",
                                  f"V_{p}": "rounded intermediate: the $ & % of it {x}"}}
    return velpoly.solve(velpoly.load(mech))


def test_rows_with_book_values_come_first_and_notes_are_footnotes(specimens):
    """Every specimen's table: the book's rows first, one mark a note. Drawn (the sheet, its footnotes, the rows
    shown) for every second specimen (a four-bar, an inverted slider-crank, a slot, a slider-driven
    slider-crank; all eight until the suite had to fit 2 minutes: the marks and notes are the table's, checked
    on all), its space diagram unlabelled (``sheets.unlabelled_mechanism``: the table read)."""
    from velpoly.render.table import NOTED, draw_results_table, results_table
    with rc_context(get_style("textbook")):
        for i, sp in enumerate(specimens):
            sol = _with_reference(sp)
            cons = sheet.constructions(sol, "full")
            t = results_table(sol, "full", velocity=cons.velocity, acceleration=cons.acceleration, poleset=cons.poles)
            ref = t.header.index("reference")
            has = [bool(row[ref]) for row in t.rows]
            assert sum(has) >= 3 and has == sorted(has, reverse=True), (sp.kind, has)   # book's rows first
            assert len(t.notes) == 2 and NOTED in t.title
            last = [(row[-1].split() or [""])[-1] for row in t.rows]
            marks = [x for x in last if x in {n[0] for n in t.notes}]
            assert sorted(marks) == sorted(n[0] for n in t.notes) and len(set(marks)) == 2   # one mark each
            if i % 2:
                continue
            with sheets.unlabelled_mechanism():   # the table read, not the space diagram's marks
                fig = sheet.render_sheet(sol, "full", "textbook", cons=cons)
            tab = next(ax for ax in fig.axes if ax.get_label() == "table")
            cells = [x.get_text() for x in tab.texts if x.get_gid() is None]
            notes = {x.get_gid(): x for x in tab.texts if (x.get_gid() or "").startswith("footnote-")}
            foot = " ".join(x.get_text() for x in tab.texts if x in notes.values() or
                            (x.get_text().startswith("   ")))
            # every marked row shown has its footnote on the sheet: the mark, then the note's own words
            for mark, key, text in t.notes:
                assert any(c.endswith(mark) for c in cells), (sp.kind, mark)
                first = next(x for x in notes.values() if x.get_text().startswith(mark + " "))
                assert text.split()[0] in first.get_text()
                words = re.sub(r"\\(.)", r"\1", foot)
                plain = [w for w in text.split() if re.fullmatch(r"[A-Za-z:().,&%]+", w)]   # typeset words aside
                assert len(plain) >= 3 and all(w in words for w in plain), (sp.kind, text, words)
            # the rows with book values are all shown, above the footnotes, inside the table's axes
            art = draw_results_table(sol, tab.figure.add_axes(tab.get_position().bounds, label="probe"),
                                     sheet="full", style="textbook", velocity=cons.velocity,
                                     acceleration=cons.acceleration, poleset=cons.poles)
            assert art.shown >= sum(has) and len(art.notes) == 2
            r = fig.canvas.get_renderer()
            lowest_cell = min(c.get_window_extent(r).y0 for c in art["cells"])
            for n in art["footnotes"]:
                box = n.get_window_extent(r)
                assert box.y1 <= lowest_cell and box.y0 >= art.ax.get_window_extent(r).y0 - 1


# -- item 9: sweep plots ----------------------------------------------------------------------------------

def _legend_texts(ax) -> list[str]:
    leg = ax.get_legend()
    return [t.get_text() for t in leg.get_texts()] if leg else []


@pytest.mark.parametrize("seed", [3, 11, 29])
def test_sweep_plots_merge_coinciding_curves_omit_zero_ones_and_mark_the_drawn_pose(seed):
    """A block on a rocking guide turns with it (ω3 = ω4, α3 = α4 over the whole cycle): one curve,
    one legend entry "ω3 = ω4"; a block on the frame's guide never turns (ω4 = α4 = 0): not drawn, the
    legend says so; a dashed vertical line marks the drawn pose, where the sweep equals velpoly.solve."""
    import mechanisms
    from velpoly.render.sweep import cycle_figure
    from velpoly.sweeps import run_cycle
    from velpoly.reference import file_pose_angle
    for mech, same, zero in ((mechanisms.block_on_driven_crank(seed, angle=15.0 + 47.0 * seed), ("3", "4"), ()),
                             (mechanisms.slider_crank(r=2 + seed % 3, theta=10.0 + 31.0 * seed), (), ("4",))):
        m = velpoly.load(mech)
        sw = run_cycle(m, step=6.0)
        fig = cycle_figure(sw)
        w_ax, a_ax = fig.axes[0], fig.axes[1]
        for ax, sym, values in ((w_ax, r"\omega", sw.omega), (a_ax, r"\alpha", sw.alpha)):
            labels = _legend_texts(ax)
            curves = [ln for ln in ax.get_lines() if (ln.get_gid() or "").startswith("curve-")]
            # each drawn curve is the quantities its label names, every one of them, at every pose
            for ln in curves:
                names = re.findall(sym.replace("\\", r"\\") + r"_\{([^}]+)\}", ln.get_label())
                assert names and ln.get_label() in labels
                for lk in names:
                    assert np.allclose(ln.get_ydata(), values[lk], rtol=0, atol=1e-9 * np.nanmax(np.abs(values[lk])))
            drawn_names = [n for ln in curves for n in re.findall(r"_\{([^}]+)\}", ln.get_label())]
            assert sorted(drawn_names) == sorted(k.name for k in m.moving_links if k.name not in zero
                                                 and np.nanmax(np.abs(values[k.name])) > 0)   # each once
            if same:
                merged = f"${sym}_{{{same[0]}}}$ = ${sym}_{{{same[1]}}}$"
                assert merged in labels, labels
            else:   # nothing coincides: one entry a curve
                assert all(" = $" not in lab for lab in labels if not lab.startswith("drawn pose"))
            notes = [ln for ln in ax.get_lines() if ln.get_gid() == "zero-note"]
            for lk in zero:
                assert np.all(values[lk] == 0) or np.nanmax(np.abs(values[lk])) < 1e-12
                assert notes and f"${sym}_{{{lk}}}$" in notes[0].get_label() and "not drawn" in notes[0].get_label()
                assert notes[0].get_label() in labels and len(notes[0].get_xdata()) == 0
        # the drawn pose: one dashed vertical line a panel, at the file's driver angle, where the sweep's
        # values are velpoly.solve's at the file's pose
        sol = velpoly.solve(m)
        x0 = None
        for ax in fig.axes[:4]:
            marks = [ln for ln in ax.get_lines() if ln.get_gid() == "drawn-pose"]
            assert len(marks) == 1
            xs = set(np.asarray(marks[0].get_xdata(), float))
            assert len(xs) == 1
            x0 = xs.pop()
        assert (x0 - file_pose_angle(m)) % 360 == pytest.approx(0, abs=1e-9) or \
            (x0 - file_pose_angle(m)) % 360 == pytest.approx(360, abs=1e-9)
        i = int(np.argmin(np.abs(sw.angles - x0)))
        assert abs(sw.angles[i] - x0) < 1e-9
        for k in m.moving_links:
            assert sw.omega[k.name][i] == pytest.approx(sol.omega[k.name], abs=1e-9 * max(1, abs(sol.omega[k.name])))
        assert any(t.startswith("drawn pose") for t in _legend_texts(fig.axes[0]))


def test_merge_series_keeps_curves_that_only_touch():
    """Curves equal at some poses (crossing) are two curves; equal everywhere, one; NaN where the other
    is defined, two."""
    from velpoly.render.sweep import merge_series
    x = np.linspace(0, 6, 50)
    a, b = np.sin(x), np.cos(x)
    c = a.copy()
    d = a.copy()
    d[5] = np.nan
    curves, zero = merge_series([("a", a), ("b", b), ("c", c), ("d", d), ("z", 0 * x)])
    assert [lab for lab, _ in curves] == ["a = c", "b", "d"] and zero == ["z"]
    assert merge_series([("z", 0 * x), ("y", 0 * x)]) == ([], ["z", "y"])   # a panel of zeros: a note only


@pytest.mark.parametrize("stem,style", [pytest.param(stem, style, marks=sheets.on(style)) for stem, style in (
    ("ex3_4_slotted_lever", "textbook"), ("ex3_10_rolling_contact", "textbook"), ("fig3_15b_sliding", "slides"))])
def test_a_promised_footnote_is_on_the_sheet(stem, style):
    """The rows a [reference] note explains lead the book's rows, so a table cut to its room keeps them
    and their footnotes; the title announces a footnote only when one is drawn (Ex. 3.4's full sheet
    promised a † whose row was among the rows cut). The sheet is the shared gallery page (tests/sheets.py:
    each is drawn for test_render_gallery anyway; Fig. 3.15b's in slides, its gallery style, since issue 19
    item 7: a textbook page of its own cost a draw); the table is drawn again on a page of its own of the
    same size, in the sheet's table's place."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from velpoly.render.table import NOTED, draw_results_table, results_table
    sol, cons = sheets.solved(stem), sheets.constructions(stem, "full")
    t = results_table(sol, "full", velocity=cons.velocity, acceleration=cons.acceleration, poleset=cons.poles)
    marks = {n[0] for n in t.notes}
    ref = t.header.index("reference")
    kinds = [(bool(row[ref]), (row[-1].split() or [""])[-1] in marks) for row in t.rows]
    assert any(k[1] for k in kinds) and kinds == sorted(kinds, key=lambda k: (not k[0], not k[1]))
    fig = sheets.page(stem, "full", style)     # read only
    tab = next(ax for ax in fig.axes if ax.get_label() == "table")
    probe = Figure(figsize=fig.get_size_inches(), dpi=fig.dpi)
    FigureCanvasAgg(probe)
    with sheets.styled(style):
        art = draw_results_table(sol, probe.add_axes(tab.get_position().bounds, label="probe"), sheet="full",
                                 style=style, velocity=cons.velocity, acceleration=cons.acceleration,
                                 poleset=cons.poles)
    promised = f"{NOTED} the book's value is explained in a footnote" in " ".join(art["title"][0].get_text().split())
    assert promised == bool(art.notes) and art.notes, (stem, art.shown)
