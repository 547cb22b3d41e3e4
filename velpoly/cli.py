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
import os
import sys
import warnings
from pathlib import Path

from .errors import InputError, VelpolyError, one_line

__all__ = ["main", "build_parser"]

SHEETS = ("velocity", "acceleration", "poles", "full")
STYLES = ("textbook", "slides")


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="velpoly", description="Graphical kinematics of planar mechanisms: "
                                "velocity and acceleration polygons, instant centres, textbook figures.")
    p.add_argument("--version", action="version", version="velpoly " + _version())
    p.add_argument("--debug", action="store_true", help="show the traceback of an error")
    # --debug is also accepted after the command (velpoly solve FILE --debug)
    debug = argparse.ArgumentParser(add_help=False)
    debug.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                       help="show the traceback of an error")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=_sub_parser(debug))

    s = sub.add_parser("solve", help="analytic positions, velocities, accelerations, poles")
    s.add_argument("file")
    s.add_argument("--angle", type=float, help="driver angle in degrees (absolute)")
    s.add_argument("--json", action="store_true", help="print the JSON results (FORMAT.md section 2)")
    s.add_argument("--format", choices=("text", "markdown", "latex", "csv"), default="text",
                   help="table style of the readable output")

    d = sub.add_parser("draw", help="textbook figure(s): SVG, PNG or PDF by the output's suffix")
    d.add_argument("file")
    d.add_argument("-o", "--output", help="output file (default: FILE's name with .svg)")
    d.add_argument("--sheet", choices=SHEETS, default="full")
    d.add_argument("--steps", action="store_true", help="one construction step a frame (multi-page PDF "
                   "or numbered SVG/PNG files)")
    d.add_argument("--angle", type=float, help="driver angle in degrees (absolute)")
    d.add_argument("--style", choices=STYLES, default="textbook")

    w = sub.add_parser("sweep", help="a whole driver cycle: plots and a table")
    w.add_argument("file")
    w.add_argument("--step", type=float, default=1.0, help="driver step in degrees (default 1)")
    w.add_argument("-o", "--output", help="plot file (SVG, PNG or PDF)")
    w.add_argument("--csv", help="CSV file of every quantity over the cycle")
    w.add_argument("--points", help="comma-separated points whose speeds to plot (default: all)")
    w.add_argument("--centrodes", metavar="LINK", help="draw the fixed and moving centrodes of this link")
    w.add_argument("--gif", help="animated GIF of the mechanism with its velocity polygon")
    w.add_argument("--style", choices=STYLES, default="textbook")

    a = sub.add_parser("animate", help="the motion over the cycle with its polygons: GIF, animated PNG, MP4, "
                       "multi-page PDF (by the output's suffix)")
    a.add_argument("file")
    a.add_argument("-o", "--output", required=True, help="output file: .gif, .png (animated PNG), .mp4, .pdf "
                   "(one page a frame, for LaTeX's animate package) or .html (velpoly html)")
    a.add_argument("--sheet", choices=SHEETS, default="velocity", help="the panels beside the mechanism "
                   "(default: velocity)")
    a.add_argument("--step", type=float, default=2.0, help="driver step between frames in degrees (default 2)")
    a.add_argument("--size", default="1920x1080", help="frame size WIDTHxHEIGHT in pixels (default 1920x1080)")
    a.add_argument("--fps", type=float, default=15.0, help="frames a second (default 15)")
    a.add_argument("--style", choices=STYLES, default="slides")

    e = sub.add_parser("demo", help="the main job on a built-in example, no file needed")
    e.add_argument("-o", "--output", default="out", help="output folder (default: out/)")
    e.add_argument("--style", choices=STYLES, default="textbook")

    g = sub.add_parser("gallery", help="rebuild the gallery's figures and README")
    g.add_argument("-o", "--output", default=None, help="output folder (default: the source folder)")
    g.add_argument("--source", default=None, help="folder of the example *.toml files (default: the "
                   "repository's gallery/)")
    g.add_argument("--style", choices=STYLES, default="textbook")
    return p


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


def cmd_draw(args) -> int:
    out = Path(args.output) if args.output else Path(Path(args.file).stem + ".svg")
    if out.suffix.lower() not in (".svg", ".png", ".pdf"):
        raise InputError(f"unknown figure type {out.suffix or '(none)'!r}", where="-o", file=str(out),
                         hint="end the output's name with .svg, .png or .pdf")
    _, sol = _load_and_solve(args)
    _warn(sol)
    from .render import draw_to_file
    written = draw_to_file(sol, out, sheet=args.sheet, style=args.style, steps=args.steps)
    for path in written:
        print(path)
    return 0


MIN_STEP = 1e-3   # degrees: 360 000 poses a turn; a finer step would only exhaust the memory


def cmd_sweep(args) -> int:
    step = getattr(args, "step", 1.0)
    if step is not None and 0 < step < MIN_STEP:   # other bad steps are refused by the cycle itself
        raise InputError(f"the step {step:g} deg is too fine: {360 / step:.3g} poses a turn",
                         where="--step", hint=f"use a step of at least {MIN_STEP:g} deg (e.g. --step 0.1)")
    from .cycle import sweep_command
    return sweep_command(args)


def cmd_animate(args) -> int:
    out = Path(args.output)
    suffix = out.suffix.lower()
    if suffix == ".html":
        return _animate_html(args, out)
    from .render.animate import FORMATS, parse_size
    if suffix not in FORMATS:
        raise InputError(f"unknown animation type {out.suffix or '(none)'!r}", where="-o", file=str(out),
                         hint="end the output's name with .gif, .png (animated PNG), .mp4, .pdf or .html")
    if out.resolve() == Path(args.file).resolve():
        raise InputError("the output would replace the input file", where="-o", file=str(out),
                         hint="give the animation another name")
    size = parse_size(args.size)
    if suffix == ".mp4" and (size[0] % 2 or size[1] % 2):
        raise InputError(f"an MP4 needs an even width and height, got {size[0]}x{size[1]}", where="--size",
                         hint="e.g. --size 1920x1080")
    from . import load
    from .render.animate import Animator, plan_frames, write_animation, _mp4_writer
    if suffix == ".mp4":
        _mp4_writer()             # the missing extra is said before any work
    m = load(Path(args.file), name=args.file)
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


def _animate_html(args, out: Path) -> int:
    """``velpoly animate FILE -o PAGE.html``: the interactive page of ``velpoly html``, where it exists."""
    try:
        import importlib
        importlib.import_module(".html", __package__)
    except ImportError:
        raise InputError("an HTML animation is the interactive page of `velpoly html`, which this velpoly "
                         "does not have", where="-o", file=str(out),
                         hint="write .gif, .png, .mp4 or .pdf, or use `velpoly html FILE -o PAGE.html` where "
                         "it is installed") from None
    if "html" not in COMMANDS:
        raise InputError("an HTML animation is written by `velpoly html`", where="-o", file=str(out),
                         hint=f"use: velpoly html {args.file} -o {out}")
    return COMMANDS["html"](build_parser().parse_args(["html", args.file, "-o", str(out)]))


def cmd_demo(args) -> int:
    from .gallery import demo_command
    return demo_command(args)


def cmd_gallery(args) -> int:
    from .gallery import gallery_command
    return gallery_command(args)


COMMANDS = {"solve": cmd_solve, "draw": cmd_draw, "sweep": cmd_sweep, "demo": cmd_demo, "gallery": cmd_gallery}
COMMANDS["animate"] = cmd_animate


def main(argv=None) -> int:
    """Run the ``velpoly`` command; returns the exit status (FORMAT.md section 3)."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if not args.command:
        parser.print_help()
        return 2
    for stream in (sys.stdout, sys.stderr):  # a title in any script prints on any terminal
        try:
            stream.reconfigure(errors="backslashreplace")
        except (AttributeError, ValueError, OSError):
            pass
    try:
        with warnings.catch_warnings():
            if not args.debug:  # numpy's overflow chatter is not for users: errors say what is wrong
                warnings.simplefilter("ignore", RuntimeWarning)
            return COMMANDS[args.command](args)
    except VelpolyError as e:
        if args.debug:
            raise
        _explain(e, args)
        return e.exit_code
    except KeyboardInterrupt:
        print("error: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # the reader of our output went away (velpoly solve F | head)
        try:  # point stdout at devnull so the interpreter's final flush cannot fail again
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, sys.stdout.fileno())
        except (OSError, AttributeError, ValueError):
            pass
        return 0
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
    if getattr(args, "angle", None) is not None and e.where == "driver.angle":
        e.where = "--angle"
    if file and e.where and "(line " not in e.where and e.file == file:
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
