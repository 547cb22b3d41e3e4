"""The ``velpoly`` command: the only place that prints or exits.

Exit status: 0 done; 2 the input is wrong; 3 the pose cannot be assembled
or is singular (FORMAT.md section 3); 1 an internal error (a bug: please
report it); 130 interrupted. Errors are one line ``error: FILE: WHERE: WHAT``
and a line ``hint: ...``; ``--debug`` (before or after the command) shows
the traceback instead. Warnings (a near-singular pose) are lines
``warning: FILE: ...`` on standard error. See docs/errors.md.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import re
import signal
import sys
import warnings
from pathlib import Path

from .errors import InputError, VelpolyError, one_line
# at once, not when a signal comes: a Ctrl-C while a command imports fileio must find it whole
from .fileio import (atomic_write_text, check_not_input, check_output, committed_together, forget_inputs, same_file,
                     forget_interrupt, interrupted, interruption, note_interrupt, protect_input, raise_if_interrupted)

__all__ = ["main", "build_parser"]

SHEETS = ("velocity", "acceleration", "poles", "full", "displacement")
STYLES = ("textbook", "slides")
FIGURE_SUFFIXES = (".svg", ".png", ".pdf")   # what -o of draw and sweep writes, by its suffix
SHEET_HELP = {
    "velocity": "the mechanism to scale and its velocity polygon, with the results table",
    "acceleration": "the mechanism and its acceleration polygon (normal, tangential, Coriolis, slip components)",
    "poles": "the mechanism with every instant centre, the Kennedy lines and the Kennedy circle",
    "full": "the mechanism, both polygons and the results table (the default)",
    "displacement": "the space diagram alone with its data: a problem handout, no answers",
}
STYLE_HELP = {
    "textbook": "black on white, serif type, hatched ground, thin lines; A4 landscape",
    "slides": "colour (each link and each kind of vector its colour), large sans-serif type; 16:9",
}
STYLES_HELP = "textbook (black on white, A4) or slides (colour, 16:9); default: textbook"
ANGLE_HELP = "driver angle in degrees, absolute (counter-clockwise from +x; default: the file's pose)"


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="velpoly", description="Graphical kinematics of planar mechanisms: "
                                "velocity and acceleration polygons, instant centres, textbook figures.",
                                epilog="example:\n  velpoly examples ex3_6_fourbar > fourbar.toml && "
                                       "velpoly draw fourbar.toml -o fourbar.pdf",
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--version", action="version", version="velpoly " + _version())
    p.add_argument("--debug", action="store_true", help="show the traceback of an error")
    # --debug is also accepted after the command (velpoly solve FILE --debug)
    debug = argparse.ArgumentParser(add_help=False)
    debug.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                       help="show the traceback of an error")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=_sub_parser(debug),
                           help="what to do (velpoly COMMAND --help says more)")

    def command(name, help, example, description=None):
        """A subcommand whose help ends with an example."""
        return sub.add_parser(name, help=help, description=description or help[:1].upper() + help[1:] + ".",
                              epilog="example:\n  " + example, formatter_class=argparse.RawDescriptionHelpFormatter)

    for add in (_solve_parser, _draw_parser, _sweep_parser, _demo_parser, _animate_parser, _gallery_parser,
                _examples_parser, _html_parser):   # in the order `velpoly --help` lists them
        add(command)
    return p


def _solve_parser(command) -> None:
    """``velpoly solve``'s arguments."""
    s = command("solve", "analytic positions, velocities, accelerations, poles, and the book's values beside them",
                "velpoly solve fourbar.toml --angle 40")
    s.add_argument("file", help="the mechanism file (TOML, FORMAT.md section 1)")
    s.add_argument("--angle", type=_degrees, metavar="DEG", help=ANGLE_HELP)
    s.add_argument("--json", action="store_true", help="print the JSON results (FORMAT.md section 2) instead of tables")
    s.add_argument("--format", choices=("text", "markdown", "latex", "csv"), default="text",
                   help="table style of the readable output (default: text)")


def _draw_parser(command) -> None:
    """``velpoly draw``'s arguments."""
    d = command("draw", "textbook figure(s): SVG, PNG or PDF by the output's suffix",
                "velpoly draw fourbar.toml -o fourbar.pdf --sheet velocity --style slides",
                description="Draw a textbook figure of the mechanism: SVG, PNG or PDF by the output's suffix.\n\n"
                            "sheets:\n" + "\n".join(f"  {k:<13} {SHEET_HELP.get(k, '')}" for k in SHEETS) +
                            "\n\nstyles:\n" + "\n".join(f"  {k:<13} {STYLE_HELP.get(k, '')}" for k in STYLES))
    d.add_argument("file", help="the mechanism file (TOML)")
    d.add_argument("-o", "--output", metavar="OUT", help="output file: .svg, .png or .pdf (default: FILE's name with .svg)")
    d.add_argument("--sheet", choices=SHEETS, help="what to draw (listed above; default: the file's "
                   "[drawing] sheet, else full)")
    d.add_argument("--steps", action="store_true", help="one construction step a frame (multi-page PDF "
                   "or numbered SVG/PNG files), for slides")
    d.add_argument("--angle", type=_degrees, metavar="DEG", help=ANGLE_HELP)
    d.add_argument("--style", choices=STYLES, default="textbook", help="the look (listed above; default: textbook)")


def _sweep_parser(command) -> None:
    """``velpoly sweep``'s arguments."""
    w = command("sweep", "a whole driver cycle: plots and a table",
                "velpoly sweep fourbar.toml --step 5 -o cycle.svg --csv cycle.csv")
    w.add_argument("file", help="the mechanism file (TOML)")
    w.add_argument("--step", type=_step_degrees, default=1.0, metavar="DEG", help="driver step in degrees (default 1)")
    w.add_argument("-o", "--output", metavar="OUT", help="plot file (SVG, PNG or PDF)")
    w.add_argument("--csv", help="CSV file of every quantity over the cycle")
    w.add_argument("--points", help="comma-separated points whose speeds to plot (default: all)")
    w.add_argument("--centrodes", metavar="LINK", help="draw the fixed and moving centrodes of this link")
    w.add_argument("--gif", help="animated GIF of the mechanism with its velocity polygon")
    w.add_argument("--style", choices=STYLES, default="textbook", help=STYLES_HELP)


def _demo_parser(command) -> None:
    """``velpoly demo``'s arguments."""
    e = command("demo", "the main job on a built-in example, no file needed: the full sheet and the comparison "
                "with the book", "velpoly demo -o out")
    e.add_argument("-o", "--output", default="out", metavar="DIR", help="output folder (default: out/)")
    e.add_argument("--style", choices=STYLES, default="textbook", help=STYLES_HELP)


def _animate_parser(command) -> None:
    """``velpoly animate``'s arguments."""
    a = command("animate", "the motion over the cycle (or the reachable range, out and back) with its "
                "polygons: GIF, animated PNG, MP4, multi-page PDF or the html page, by the output's suffix",
                "velpoly animate ex36.toml -o ex36.gif --size 1280x720")
    a.add_argument("file", help="the mechanism file (TOML)")
    a.add_argument("-o", "--output", required=True, metavar="OUT", help="output file: .gif, .png (animated "
                   "PNG), .mp4 (needs velpoly[video]), .pdf (one page a frame, for LaTeX's animate package) or "
                   ".html (velpoly html)")
    a.add_argument("--sheet", choices=[s for s in SHEETS if s != "displacement"], default="velocity", help="the panels beside the mechanism "
                   "(default: velocity)")
    a.add_argument("--step", type=_step_degrees, default=2.0, metavar="DEG", help="driver step between frames in "
                   "degrees (default 2)")
    a.add_argument("--size", default="1920x1080", metavar="WxH", help="frame size in pixels (default 1920x1080)")
    a.add_argument("--fps", type=_frame_rate, default=15.0, metavar="N", help="frames a second (default 15)")
    a.add_argument("--style", choices=STYLES, default="slides", help="slides (colour, large type; the default) or textbook (black on white)")


def _gallery_parser(command) -> None:
    """``velpoly gallery``'s arguments."""
    g = command("gallery", "build the gallery: every built-in example's sheet and its comparison with the book",
                "velpoly gallery -o my-gallery")
    g.add_argument("-o", "--output", default=None, metavar="DIR", help="output folder (default: the --source "
                   "folder if given, else the checkout's gallery/, or ./gallery outside a checkout)")
    g.add_argument("--source", default=None, metavar="DIR", help="folder of the example *.toml files (default: "
                   "the built-in examples)")
    g.add_argument("--style", choices=STYLES, default="textbook", help=STYLES_HELP)
    g.add_argument("names", nargs="*", metavar="NAME", help="build only these examples (default: all)")


def _examples_parser(command) -> None:
    """``velpoly examples``'s arguments."""
    x = command("examples", "list the built-in examples, or print one to start a file from",
                "velpoly examples ex3_4_slotted_lever > lever.toml")
    x.add_argument("name", nargs="?", metavar="NAME", help="the example to print (its TOML text); without it, "
                   "list them all with their titles")


def _html_parser(command) -> None:
    """``velpoly html``'s arguments."""
    h = command("html", "one self-contained interactive page: the sheet over the driver's cycle, the "
                "construction step by step", "velpoly html ex36.toml -o ex36.html")
    h.add_argument("file", help="the mechanism file (TOML)")
    h.add_argument("-o", "--output", metavar="OUT", help="the page (default: FILE's name with .html)")
    h.add_argument("--step", type=_step_degrees, default=1.0, metavar="DEG", help="driver step between the poses, in "
                   "degrees (default 1; a slider driver's stroke in as many poses)")


def _degrees(text: str):
    """``--angle``'s number: a float, or, where the number is finite but beyond any float (``1e400``), its
    exact value (a Fraction), so that the angle's check says it is too large, as the API does for
    ``solve(m, angle=10**400)``, not that it is not finite."""
    x = _number(text)
    if math.isinf(x) and text.strip().lstrip("+-").lower() not in ("inf", "infinity"):
        return _exact(text)
    return x


_PLAIN = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_NOT_FINITE = ("inf", "infinity", "nan")   # read, so that the option's check says "not finite"


def _number(text: str, what: str = "a number of degrees") -> float:
    """A number as FORMAT.md writes numbers: plain decimal ASCII (``30``, ``-2.5``, ``1e3``), or an infinity or
    NaN typed as one (``inf``, ``nan``: the option's own check then says it is not finite). ``float`` alone
    would also read ``1_0`` as 10, `` 1`` and non-ASCII digits; argparse's error, one line naming the
    option, for those and for what is no number (``--angle abc``)."""
    if _PLAIN.fullmatch(text) or text.lstrip("+-").lower() in _NOT_FINITE:
        return float(text)
    raise argparse.ArgumentTypeError(f"expected {what} (plain decimal digits, as 30 or -2.5), got {text!r}")


def _frame_rate(text: str) -> float:
    """``--fps``'s number, read as :func:`_number` reads it."""
    return _number(text, "a number of frames a second")


def _exact(text: str):
    """The exact value (a Fraction) of a number ``float`` reads, whatever its size."""
    import decimal
    import fractions
    return fractions.Fraction(decimal.Decimal(text.strip().replace("_", "")))


def _step_degrees(text: str):
    """``--step``'s number: a float, or, where the number is finite and not zero but beyond any float
    (``1e400``, ``1e-400``), its exact value (a Fraction), which :func:`_check_step` refuses as too large or
    too small, not as "inf" or "0"."""
    x = _number(text)
    if (math.isinf(x) or x == 0) and text.strip().lstrip("+-").lower() not in ("inf", "infinity"):
        exact = _exact(text)
        return exact if exact != 0 else x
    return x


def _check_step(args) -> None:
    """A ``--step`` beyond any float (:func:`_step_degrees`): an input error saying it is too large or too
    small for the command's range (the command checks every other step)."""
    step = getattr(args, "step", None)
    if step is None or isinstance(step, float):
        return
    from .arguments import rational_g
    shown = rational_g(step)
    least, most = {"animate": (0.05, 90.0), "html": (HTML_MIN_STEP, 180.0)}.get(args.command, (MIN_STEP, 180.0))
    if step < 0:
        raise InputError(f"the step must be a number of degrees above 0, got {shown}", where="--step",
                         hint="e.g. --step 1 or --step 5")
    if step < least:
        raise InputError(f"the step {shown} deg is too small (at least {least:g} deg)", where="--step",
                         hint="e.g. --step 1 or --step 5")
    raise InputError(f"the step {shown} deg is too large (at most {most:g} deg)", where="--step",
                     hint="e.g. --step 1 or --step 5")


def _sub_parser(parent):
    class SubParser(argparse.ArgumentParser):
        def __init__(self, *a, **kw):
            kw.setdefault("parents", [parent])
            super().__init__(*a, **kw)
    return SubParser


def _version() -> str:
    from . import __version__
    return __version__


def _load_and_solve(args):
    from . import load, solve
    m = load(Path(args.file), name=args.file)
    return m, solve(m, angle=args.angle)


def _warn(sol) -> None:
    for w in sol.warnings:
        print(one_line(f"warning: {sol.mechanism.source}: {w}"), file=sys.stderr)


def cmd_solve(args) -> int:
    from .report import solution_report
    _, sol = _load_and_solve(args)
    if args.json:
        print(json.dumps(sol.to_dict(), indent=2, allow_nan=False))
    else:
        print(solution_report(sol, args.format), end="")
    _warn(sol)
    return 0


def _lean_matplotlib(args) -> None:
    """The velpoly program (``args.program``: :func:`main` run without arguments given from Python)
    imports matplotlib without what only an interactive session reads (velpoly.render.lean); velpoly
    called from Python imports it as it is."""
    if args.program:
        from .render.lean import import_matplotlib
        import_matplotlib(freeze=True)


def cmd_draw(args) -> int:
    out = Path(args.output) if args.output else Path(Path(args.file).stem + ".svg")
    if not args.output:   # the default name can be the input's own (a file named mech.svg)
        check_not_input(out, args.file, "-o", default=True)
    if out.suffix.lower() not in FIGURE_SUFFIXES:
        raise unknown_type(out, "figure", "-o", "end the output's name with .svg, .png or .pdf")
    _, sol = _load_and_solve(args)
    _warn(sol)
    _lean_matplotlib(args)
    from .render import draw_to_file
    from .render.sheet import default_sheet
    sheet = args.sheet or default_sheet(sol.mechanism)
    from .solution import polygon_at_rest
    still = polygon_at_rest(sol, sheet)
    if still is not None:
        raise still
    written = draw_to_file(sol, out, sheet=sheet, style=args.style, steps=args.steps)
    for path in written:
        print(path)
    return 0


MIN_STEP = 1e-3   # degrees: 360 000 poses a turn; a finer step would only exhaust the memory
LONG_SWEEP = 10_000   # poses: a sweep this long says how many it computes


def cmd_sweep(args) -> int:
    """``velpoly sweep FILE [--step DEG] [-o OUT] [--csv CSV] [--points P,Q] [--centrodes LINK] [--gif GIF]
    [--style]``: see docs/sweep.md. Warnings go to standard error once everything is written."""
    step = getattr(args, "step", 1.0)
    if step is not None and 0 < step < MIN_STEP:   # other bad steps are refused by the cycle itself
        raise InputError(f"the step {step:g} deg is too fine: {360 / step:.3g} poses a turn",
                         where="--step", hint=f"use a step of at least {MIN_STEP:g} deg (e.g. --step 0.1)")
    if step is not None and math.isfinite(step) and step > 0 and 360 / step >= LONG_SWEEP:
        print(f"velpoly sweep: --step {step:g} deg computes up to {math.ceil(360 / step - 1e-9)} poses",
              file=sys.stderr)
    plot_out = _suffixed(getattr(args, "output", None), FIGURE_SUFFIXES, "-o")
    gif_out = _suffixed(getattr(args, "gif", None), (".gif",), "--gif")
    csv_out = Path(args.csv) if getattr(args, "csv", None) else None
    style = getattr(args, "style", "textbook") or "textbook"
    sw, kin = _sweep_cycle(args.file, getattr(args, "step", 1.0), gif_out is not None)
    from .sweeps import stop_note
    m = sw.mechanism
    if gif_out:   # the GIF draws the velocity polygon: refused before anything is written
        _polygons_drawable(m, "velocity")
    note = stop_note(sw, kin)
    warnings = [f"warning: {m.source}: {note}"] if note else []
    points = _sweep_points(sw, getattr(args, "points", None))
    cen = None
    if getattr(args, "centrodes", None):
        from .centrodes import centrodes
        cen = centrodes(sw, str(args.centrodes), kin)
        if not cen.defined.any():
            warnings.append(f"warning: {m.source}: link {cen.link} does not turn: its pole with the frame "
                            f"stays at infinity, no centrode")
    written = []
    with committed_together():   # the CSV, the plot and the GIF all, or none of them
        if csv_out:
            from .report import cycle_csv
            written.append(atomic_write_text(csv_out, cycle_csv(sw, cen)))
        if plot_out or gif_out:
            _lean_matplotlib(args)
            from .render.sweep import plot_cycle, write_gif
            if plot_out:
                written.append(plot_cycle(sw, plot_out, points, cen, style, kin))
            if gif_out:
                written.append(_sweep_gif(write_gif, sw, gif_out, kin, style, cen))
    summary = ""
    if not written:
        from .report import summary_text
        summary = summary_text(sw, points)
        if cen is not None:
            warnings.append("note: the centrodes are drawn with -o or --gif and listed with --csv")
    for line in warnings:
        print(line, file=sys.stderr)
    sys.stdout.write(summary)
    for p in written:
        print(p)
    return 0


def unknown_type(out: Path, kind: str, option: str, hint: str) -> InputError:
    """The error of an output ``out`` (given by ``option``) whose suffix chooses no ``kind`` of output: its suffix
    named; or, where it has none, the output named, and said to be a special file where it is one (``/dev/null``:
    written straight through, FORMAT.md section 3, but with no suffix to choose what to write)."""
    if out.suffix:
        return InputError(f"unknown {kind} type {out.suffix!r}", where=option, file=str(out), hint=hint)
    from .fileio import is_special
    what = "a special file" if is_special(out) else "a name"
    return InputError(f"no {kind} type: {str(out)!r} is {what} with no suffix to choose one", where=option,
                      file=str(out), hint=hint)


def _suffixed(path: str | None, allowed, option: str) -> Path | None:
    """``path`` as a Path if its suffix is one of ``allowed``; an InputError naming ``option`` if not."""
    if not path:
        return None
    p = Path(path)
    if p.suffix.lower() not in allowed:
        raise unknown_type(p, "file", option, "end the name with " + " or ".join(allowed))
    return p


def _sweep_cycle(file: str, step, long: bool):
    """The file's cycle (a Sweep) and its Kinematics; a progress bar on a terminal for a long one, an
    error before any work for one too large for memory, a PoseError for fewer than two poses."""
    from . import load
    from .kinematics import prepare
    from .sweeps import MEMORY_BUDGET, check_cycle, check_memory, check_step, cycle_poses, memory_estimate, run_cycle
    step = check_step(step)
    m = load(file)
    kin = prepare(m)
    poses = cycle_poses(step)   # a turn, or each half-stroke
    check_memory(m, kin, poses, where="--step",
                 hint=f"use a coarser --step: {360 * memory_estimate(m, kin, poses) / poses / MEMORY_BUDGET:.2g} "
                      "deg or more for this mechanism")
    long = 360.0 / step >= 2000 or long or m.driver.is_slider
    bar = _Progress(1, "velpoly sweep: solving", min_total=1 if long else 10 ** 9)
    bar.advance(0)
    sw = run_cycle(m, step, kin)
    bar.advance()
    bar.close()
    check_cycle(sw, kin, step)
    return sw, kin


def _sweep_points(sw, text: str | None) -> list[str] | None:
    """``--points B,C`` as the cycle's point keys (a point name stands for each of its keys ``B@3``)."""
    if not text:
        return None
    keys = list(sw.position)
    out = []
    for tok in (t.strip() for t in text.split(",")):
        if not tok:
            continue
        found = [tok] if tok in sw.position else [k for k in keys if k.split("@")[0] == tok]
        if not found:
            raise InputError(f"unknown point {tok!r}", where="--points", file=sw.mechanism.source,
                             hint="choose from: " + ", ".join(keys))
        out += [k for k in found if k not in out]
    if not out:
        raise InputError("no point given", where="--points", file=sw.mechanism.source,
                         hint="e.g. --points B,C")
    return out


def _sweep_gif(write_gif, sw, out: Path, kin, style: str, cen) -> Path:
    """The sweep's GIF, with a progress bar (one step a frame) on a terminal."""
    bars = []

    def progress(done: int, total: int) -> None:
        if not bars:
            bars.append(_Progress(total, "velpoly sweep: GIF", min_total=2))
        bars[0].advance()
    written = write_gif(sw, out, kin, style, cen, progress=progress)
    for bar in bars:
        bar.close()
    return written


class _Progress:
    """A one-line progress bar on stderr, shown only when stderr is a terminal."""

    def __init__(self, total: int, label: str, stream=None, min_total: int = 1):
        self.stream = stream or sys.stderr
        self.total = max(int(total), 1)
        self.label = label
        self.on = bool(getattr(self.stream, "isatty", lambda: False)()) and total >= min_total
        self.done = 0

    def advance(self, k: int = 1) -> None:
        if not self.on:
            return
        self.done = min(self.done + k, self.total)
        width = 30
        filled = int(width * self.done / self.total)
        self.stream.write(f"\r{self.label} [{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total}")
        self.stream.flush()

    def close(self) -> None:
        if self.on:
            self.stream.write("\n")
            self.stream.flush()


def cmd_animate(args) -> int:
    out = Path(args.output)
    suffix = out.suffix.lower()
    if suffix == ".html":
        return _animate_html(args, out)
    from .render.animate import FORMATS, parse_size
    if suffix not in FORMATS:
        raise unknown_type(out, "animation", "-o",
                           "end the output's name with .gif, .png (animated PNG), .mp4, .pdf or .html")
    if out.resolve() == Path(args.file).resolve():
        raise InputError("the output would replace the input file", where="-o", file=str(out),
                         hint="give the animation another name")
    size = parse_size(args.size)
    if suffix == ".mp4" and (size[0] % 2 or size[1] % 2):
        raise InputError(f"an MP4 needs an even width and height, got {size[0]}x{size[1]}", where="--size",
                         hint="e.g. --size 1920x1080")
    from . import load
    _lean_matplotlib(args)
    from .render.animate import Animator, plan_frames, write_animation, mp4_writer
    if suffix == ".mp4":
        mp4_writer()             # the missing extra is said before any work
    m = load(Path(args.file), name=args.file)
    _polygons_drawable(m, args.sheet)
    plan = plan_frames(m, args.step)
    anim = Animator(plan, args.sheet, args.style, size)
    tty = bool(getattr(sys.stderr, "isatty", lambda: False)())

    def progress(done: int, total: int) -> None:
        if tty and total >= 30:
            sys.stderr.write(f"\rvelpoly animate: frame {done}/{total}")
            if done == total:
                sys.stderr.write("\n")
            sys.stderr.flush()
    write_animation(anim, out, args.fps, progress)
    print(out)
    return 0


def _polygons_drawable(m, sheet: str) -> None:
    """Refuse, as ``velpoly draw --sheet SHEET`` does (exit 2 naming the driver's rate), a figure of the cycle whose
    polygons would be single points (a mechanism at rest) or of numbers that lost their precision (below
    solution.FRAMES_RANGE, about 1e-292: the frames, drawn without shapely, hold any size above it, 1e-181 and
    1e179 mm/s² draw), at the file's pose: animate, html and sweep --gif drew them as dots beside a scale bar of a
    made-up size (2×10⁻¹² mm/s), or a polygon of 1e-320 as a dot at 0.02 mm/s². A pose that cannot be solved is
    left to the command's own cycle to report."""
    from . import solve
    from .solution import FRAMES_RANGE, polygon_at_rest
    try:
        sol = solve(m)
    except VelpolyError:
        return
    refused = polygon_at_rest(sol, sheet, FRAMES_RANGE, cycle=True)
    if refused is not None:
        raise refused


def _animate_html(args, out: Path) -> int:
    """``velpoly animate FILE -o PAGE.html``: the interactive page of ``velpoly html``, at the animation's step."""
    return cmd_html(argparse.Namespace(file=args.file, output=str(out), step=args.step))


def cmd_demo(args) -> int:
    from .gallery import DEMO_OUTPUT, build_demo
    out = Path(args.output or "out")
    for suffix in (".svg", ".png", "-results.txt", "-results.md"):   # a folder in the way: refused before any work
        check_output(out / f"{DEMO_OUTPUT}{suffix}")
    _lean_matplotlib(args)
    with committed_together():   # the four files all, or none of them
        m, written = build_demo(out, args.style or "textbook")
    book = f"the book's values ({m.reference.source})" if m.reference.source else "the book's values"
    print(f"{m.title}: the full sheet and the comparison with {book} are in {out}/")
    for p in written:
        print(f"  {p}")
    return 0


def cmd_gallery(args) -> int:
    """One failing example is reported with its error line and does not stop the others; the exit
    status is then the failures' (GalleryResult.exit_code: 2 or 3 where each is its input's, 1 where any
    is an internal error)."""
    from .gallery import build_gallery, check_gallery_folder, gallery_folders
    source, out, option = gallery_folders(args.output, args.source)
    check_gallery_folder(out, option)
    _lean_matplotlib(args)

    def log(line):
        print(f"error: {line}", file=sys.stderr)
    # the repository's gallery gets its animations (one a mechanism family); another --source does not
    result = build_gallery(source, out, style=args.style or "textbook", log=log, names=args.names,
                           animations=args.source is None)
    for p in result.written:
        print(p)
    if result.failed:
        n = len(result.built) + len(result.failed)
        print(f"gallery: {len(result.failed)} of {n} examples failed (listed above and at the end of "
              f"{out / 'README.md'})", file=sys.stderr)
    return result.exit_code


def cmd_examples(args) -> int:
    from .gallery import example_path, example_titles
    if args.name:
        sys.stdout.write(example_path(args.name).read_text(encoding="utf-8"))
        return 0
    rows = example_titles()
    width = max(len(name) for name, _ in rows)
    for name, title in rows:
        print(f"{name:<{width}}  {one_line(title)}")
    return 0


HTML_MIN_STEP = 0.1   # degrees: 3600 poses a turn, a page of 15 to 20 MB


def cmd_html(args) -> int:
    out = Path(args.output) if args.output else Path(Path(args.file).stem + ".html")
    if out.suffix.lower() not in (".html", ".htm"):
        raise unknown_type(out, "page", "-o", "end the output's name with .html")
    # outputs never replace their input (FORMAT.md section 3); the default name can be the input's own
    check_not_input(out, args.file, "-o", default=not args.output)
    if 0 < args.step < HTML_MIN_STEP:   # other bad steps are refused by the cycle itself
        raise InputError(f"the step {args.step:g} deg is too fine for a page: {360 / args.step:.3g} poses a turn",
                         where="--step", hint=f"use a step of at least {HTML_MIN_STEP:g} deg (the default, 1, "
                         "makes a page of 1 to 2 MB)")
    from . import load
    from .html import write_page
    m = load(Path(args.file), name=args.file)
    _polygons_drawable(m, "acceleration")   # the page draws both polygons (the velocity one of a start from rest)
    print(write_page(m, out, step=args.step))
    return 0


COMMANDS = {"solve": cmd_solve, "draw": cmd_draw, "sweep": cmd_sweep, "demo": cmd_demo, "gallery": cmd_gallery,
            "examples": cmd_examples, "html": cmd_html, "animate": cmd_animate}


OUTPUT_OPTIONS = (("output", "-o"), ("csv", "--csv"), ("gif", "--gif"))


class Terminated(BaseException):
    """SIGTERM, raised so that every ``finally`` runs (temporary files and folders are removed)."""


def _on_signal(signum, frame):
    kind = Terminated if signum == signal.SIGTERM else KeyboardInterrupt
    note_interrupt(kind)
    raise kind


def _unraisable(hook):
    """``sys.unraisablehook`` that records a Ctrl-C Python had to swallow (in a callback or ``__del__``),
    and, once the run is interrupted, stays silent: an object a library was building when Ctrl-C came
    (pyparsing's ``Forward`` while matplotlib imports) fails in its ``__del__`` when the interrupted
    frames are freed, which is no news to the user after ``error: interrupted``."""
    def unraisable(u):
        if isinstance(u.exc_value, (KeyboardInterrupt, Terminated)):
            note_interrupt(type(u.exc_value))
            return
        if not interrupted():
            hook(u)
    return unraisable


def _install_signals() -> dict:
    """Ctrl-C and SIGTERM raise (KeyboardInterrupt, Terminated) and are remembered even if swallowed."""
    old = {}
    for sig in (signal.SIGINT, signal.SIGTERM):
        try:
            old[sig] = signal.signal(sig, _on_signal)
        except (ValueError, OSError):   # not the main thread
            pass
    return old


class _Stdout:
    """Standard output whose write errors (no space, no permission) are input errors naming it."""

    def __init__(self, stream):
        self._stream = stream

    def _guard(self, fn, *a):
        try:
            return fn(*a)
        except BrokenPipeError:
            raise
        except OSError as e:
            raise StdoutError(e) from None

    def write(self, text):
        return self._guard(self._stream.write, text)

    def flush(self):
        return self._guard(self._stream.flush)

    def __getattr__(self, name):
        return getattr(self._stream, name)


class StdoutError(InputError):
    """Standard output cannot be written: ``cannot write standard output: REASON``."""

    def __init__(self, e: OSError):
        super().__init__(f"cannot write standard output: {e.strerror or e}",
                         hint="check where the output is redirected (a full disk, a read-only file)")


def _silence_stdout() -> None:
    """Point stdout at devnull so the interpreter's final flush cannot fail again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, AttributeError, ValueError):
        pass


def _check_outputs(args) -> None:
    """No output option names the input file (FORMAT.md section 3); the input is never written."""
    forget_inputs()
    file = getattr(args, "file", None)
    if not file:
        return
    protect_input(file)
    for attr, option in OUTPUT_OPTIONS:
        out = getattr(args, attr, None)
        check_not_input(out, file, option)
        if out == "-":   # FORMAT.md names no option's "-" standard output: a file named "-" would surprise
            raise InputError("'-' is not standard output here: the option names a file to write", where=option,
                             hint=f"give {option} a file name (./- for a file named '-')")
        if out:
            check_output(out, option)   # a folder is refused before any work, naming the option
    _distinct_outputs(args)


def _distinct_outputs(args) -> None:
    """No two output options name one file: ``velpoly sweep --csv c.svg -o c.svg`` wrote the plot over the
    CSV and exited 0, the CSV lost. The same path (after symbolic links) or the same existing file (a hard
    link) is exit 2 naming both options; a FIFO or a device takes both (each is written through)."""
    given = [(option, getattr(args, attr, None)) for attr, option in OUTPUT_OPTIONS if getattr(args, attr, None)]
    for i, (option, out) in enumerate(given):
        if Path(out).exists() and not Path(out).is_file():
            continue
        for first, other in given[:i]:
            if os.path.realpath(out) == os.path.realpath(other) or same_file(out, other):
                raise InputError(f"{first} and {option} name the same file {str(out)!r}: each output is a file "
                                 f"of its own", where=option, hint=f"give {option} another file name")


def main(argv=None) -> int:
    """Run the ``velpoly`` command; returns the exit status (FORMAT.md section 3)."""
    old_signals = _install_signals()
    old_hook, sys.unraisablehook = sys.unraisablehook, _unraisable(sys.unraisablehook)
    stdout = sys.stdout
    try:
        return _main(argv)
    except KeyboardInterrupt:   # before the command ran (parsing the arguments)
        print("error: interrupted", file=sys.stderr)
        return 130
    except Terminated:
        print("error: terminated", file=sys.stderr)
        return 143
    finally:
        if sys.stdout is not stdout and isinstance(sys.stdout, _Stdout):
            sys.stdout = stdout
        _forget_unhandled_interrupt()   # a Ctrl-C handled here is handled (exit 130, not killed by SIGINT)
        if argv is None and interrupted():
            # the program (not a caller in Python) stops now: objects a library left half-built when
            # interrupted may fail in their __del__ at exit, which is no news to the user
            sys.unraisablehook = lambda u: None
        else:
            sys.unraisablehook = old_hook
            forget_interrupt()   # the run is over: a caller in Python goes on writing files as before
        for sig, handler in old_signals.items():
            signal.signal(sig, handler)


def _forget_unhandled_interrupt() -> None:
    """Clear CPython's note of an unhandled Ctrl-C, so that the program exits with the status returned
    (130, 143), not killed by SIGINT. CPython notes a KeyboardInterrupt that leaves code compiled from a
    string (``exec`` of text: every dataclass's ``__init__`` is made so) as unhandled, even when velpoly
    handles it further up, and at exit kills itself with SIGINT; running such code again clears the note."""
    exec("pass", {})


def _interruption(e: BaseException | None):
    """The KeyboardInterrupt or Terminated that ``e`` was raised while handling (None if none): an
    interruption is remembered even when a callback swallowed it."""
    seen = set()
    while e is not None and id(e) not in seen:
        if isinstance(e, (KeyboardInterrupt, Terminated)):
            return e
        seen.add(id(e))
        e = e.__context__
    return interruption()


def _arguments(parser, argv):
    """The parsed arguments, or the exit status 2 of no command (the help printed). Help and ``--version``
    exit as argparse makes them (SystemExit 0; a wrong option, 2 with its usage on standard error), but what
    argparse prints on standard output goes through :class:`_Stdout` and is flushed here: argparse swallows a
    failed write (``velpoly --help > /dev/full`` exited 0), which FORMAT.md section 3 makes exit 2, ``cannot
    write standard output: REASON``, as for any command's output."""
    stdout, sys.stdout = sys.stdout, _Stdout(sys.stdout)
    try:
        try:
            args = parser.parse_args(argv)
        except SystemExit:
            sys.stdout.flush()
            raise
        if args.command:
            return args
        parser.print_help()
        sys.stdout.flush()
        return 2
    except StdoutError as e:
        _silence_stdout()
        print(f"error: {e.line()}\nhint: {e.hint_line()}", file=sys.stderr)
        return 2
    except BrokenPipeError:   # the reader went away (velpoly --help | head -1): not an error
        _silence_stdout()
        return 0
    finally:
        sys.stdout = stdout


_GLYPH = re.compile(r"Glyph (\d+) .*missing from font")


def _glyph_warning(where: str, show):
    """``warnings.showwarning`` that says once per character, in one line, that the fonts lack a glyph for a
    character of the file's names or title (matplotlib's warning, with its source line, for every text drawn
    with it); any other warning as ``show`` does."""
    said = set()

    def showwarning(message, category, filename, lineno, file=None, line=None):
        got = _GLYPH.search(str(message))
        if got is None:
            return show(message, category, filename, lineno, file, line)
        code = int(got.group(1))
        if code not in said:
            said.add(code)
            print(one_line(f"warning: {where}: the fonts have no glyph for {chr(code)!r} (U+{code:04X}): "
                           "it is drawn as a box"), file=sys.stderr)
    return showwarning


def _main(argv) -> int:
    args = _arguments(build_parser(), argv)
    if isinstance(args, int):
        return args
    args.program = argv is None   # the velpoly program itself, not cli.main([...]) from Python
    for stream in (sys.stdout, sys.stderr):  # a title in any script prints on any terminal
        try:
            stream.reconfigure(errors="backslashreplace")
        except (AttributeError, ValueError, OSError):
            pass
    try:
        try:
            sys.stdout = _Stdout(sys.stdout)
            with warnings.catch_warnings():
                if not args.debug:  # numpy's overflow chatter is not for users: errors say what is wrong
                    warnings.simplefilter("ignore", RuntimeWarning)
                    warnings.showwarning = _glyph_warning(getattr(args, "file", "") or "velpoly", warnings.showwarning)
                _check_outputs(args)
                _check_step(args)
                status = COMMANDS[args.command](args)
                raise_if_interrupted()   # a Ctrl-C swallowed inside a callback still stops the run
                sys.stdout.flush()
                return status
        except Exception:
            # an error raised while unwinding from Ctrl-C or SIGTERM (a library's cleanup failing on
            # its half-done work) is the interruption, not a bug
            if _interruption(sys.exc_info()[1]) is not None and not args.debug:
                raise _interruption(sys.exc_info()[1]) from None
            raise
    except VelpolyError as e:
        if isinstance(e, StdoutError):
            _silence_stdout()
        if args.debug:
            raise
        _explain(e, args)
        return e.exit_code
    except KeyboardInterrupt:
        print("error: interrupted", file=sys.stderr)
        return 130
    except Terminated:
        print("error: terminated", file=sys.stderr)
        return 143
    except BrokenPipeError:  # the reader of our output went away (velpoly solve F | head)
        _silence_stdout()
        return 0
    except MemoryError:
        if args.debug:
            raise
        where = getattr(args, "file", "") or "velpoly"
        print(f"error: {one_line(where)}: out of memory", file=sys.stderr)
        print("hint: ask for less at once (a coarser --step, fewer points)", file=sys.stderr)
        return 2
    except Exception as e:  # an internal error: still one line, never a traceback
        if args.debug:
            raise
        where = getattr(args, "file", "") or "velpoly"
        print(one_line(f"error: {where}: internal error: {type(e).__name__}: {e}"), file=sys.stderr)
        print("hint: this is a bug in velpoly: run again with --debug and report the traceback",
              file=sys.stderr)
        return 1


def _explain(e: VelpolyError, args) -> None:
    """Print ``error: FILE: WHERE: WHAT`` and ``hint: ...``, adding what the kernel cannot know:
    the file's name, the entry's TOML line, and that an angle came from --angle."""
    file = getattr(args, "file", None)
    if file and not e.file:
        e.with_file(file)
    if getattr(args, "angle", None) is not None and e.where in ("driver.angle", "angle"):
        if e.where == "angle":   # the API's argument: the hint about the option applies
            e.hint = ""
        e.where = "--angle"
    if file and e.where and "(line " not in e.where and e.file == file and os.path.isfile(file):
        # the file read again for the entry's line: a regular file only (a FIFO read again waits for ever)
        from .loader import locate
        try:
            line = locate(Path(file).read_text(encoding="utf-8"), e.where)
        except (OSError, UnicodeDecodeError):
            line = None
        if line:
            e.where = f"{e.where} (line {line})"
    print(f"error: {e.line()}", file=sys.stderr)
    hint = e.hint_line() or _default_hint(e, getattr(args, "command", None) or "COMMAND")
    print(f"hint: {hint}", file=sys.stderr)


def _default_hint(e: VelpolyError, command: str = "COMMAND") -> str:
    """The hint of an error raised without one: about the argument, the file or the pose."""
    if not isinstance(e, InputError):
        return "choose another driver angle, or draw the mechanism in another pose"
    if e.where.startswith("--angle"):
        return ("--angle DEG turns a crank driver to that absolute angle (a finite number of degrees, "
                "counter-clockwise from +x); a slider driver has none")
    if e.where.startswith("-"):
        return f"check the option {e.where.split()[0]} (velpoly {command} --help lists the options)"
    return "check the file against the format in the README"


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
