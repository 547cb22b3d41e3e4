"""``velpoly demo`` and ``velpoly gallery``: textbook examples drawn and checked against the book.

Both draw each example's own sheet (its ``[drawing] sheet``, else the full
sheet; :func:`velpoly.render.draw_to_file`) and write a comparison table: each ``[reference]`` value as the book prints it,
as the graphical constructions give it (velocity and acceleration polygons,
the poles found on the Kennedy circle) and as the analytic solve gives it,
with the deviations. The gallery's README also carries, for every example,
the sentences that explain a disagreement with the book: the file's
``[reference] note`` entries and its top comments.

The kernel part of this module imports no matplotlib; figures are drawn by
the render module.
"""
from __future__ import annotations

import contextlib
import re
import shutil
from dataclasses import dataclass
from pathlib import Path

from .errors import InputError, VelpolyError
from .fileio import atomic_write_bytes, atomic_write_text, committed_together, raise_if_interrupted
from .compare import comparison
from .report import Table, fmt, render_table
from .tables import angle, md_text

__all__ = ["example_path", "example_files", "example_titles", "EXAMPLES", "comparison_text", "top_comments", "example_markdown",
           "build_gallery", "GalleryResult", "find_gallery", "build_demo", "gallery_folders",
           "FiguresUnavailable"]

EXAMPLES = Path(__file__).resolve().parent / "examples"   # package data: every gallery file
DEMO_EXAMPLE = "problem_1_4_4_sixbar"   # the example of FORMAT.md section 1
DEMO_OUTPUT = "sixbar"                  # the stem of the demo's output files


class FiguresUnavailable(VelpolyError):
    """The figure module (velpoly.render) is not installed or offers no ``draw_to_file``."""

    exit_code = 1


def _draw_to_file():
    """:func:`velpoly.render.draw_to_file`, or a clear error if the render module is absent."""
    try:
        from .render import draw_to_file
    except ImportError as e:
        raise FiguresUnavailable(f"the figure module velpoly.render is not available ({e})", where="figures",
                                 hint="install velpoly completely (pip install -e .) or update the checkout; "
                                      "`velpoly solve` works without figures") from None
    return draw_to_file


def example_path(name: str = DEMO_EXAMPLE) -> Path:
    """The path of a built-in example file (``velpoly/examples/NAME.toml``; NAME may end in .toml)."""
    stem = _stem(name)
    path = EXAMPLES / f"{stem}.toml"
    if not stem or "/" in stem or "\\" in stem or not path.is_file():
        names = [p.stem for p in example_files()]
        close = [n for n in names if stem and stem.lower() in n.lower()]
        raise InputError(f"no built-in example {name!r}", where="examples",
                         hint=f"did you mean {' or '.join(close[:4])}? (`velpoly examples` lists them)" if close
                         else "`velpoly examples` lists them: " + ", ".join(names))
    return path


def _stem(name: str) -> str:
    """An example's name without a trailing .toml."""
    return name[:-5] if name.endswith(".toml") else name


def example_files() -> list[Path]:
    """Every built-in example file (the gallery's), in natural name order."""
    return sorted(EXAMPLES.glob("*.toml"), key=_natural)


def example_titles() -> list[tuple[str, str]]:
    """``(name, title)`` of every built-in example, in natural name order (the title as the file gives
    it, else its name)."""
    import tomllib
    out = []
    for path in example_files():
        try:
            title = tomllib.loads(path.read_text(encoding="utf-8")).get("title", path.stem)
        except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
            title = path.stem
        out.append((path.stem, str(title)))
    return out


def comparison_text(sol, style: str = "text") -> str:
    """The comparison as text or Markdown: a head line, the table, its notes."""
    m = sol.mechanism
    c = comparison(sol)
    drv = m.driver
    if drv.is_slider:
        head = f"driver: slider {drv.slider}, speed {fmt(drv.speed)} {m.units}/s, accel {fmt(drv.accel)} {m.units}/s^2"
    else:
        head = (f"driver: link {drv.link} at {angle(sol.driver_angle)} deg, omega {fmt(drv.omega)} rad/s, "
                f"alpha {fmt(drv.alpha)} rad/s^2")
    legend = ("book: the printed value; graphical: read off the exact polygons and the Kennedy "
              "construction; analytic: the linear solve. Deviations: book vs analytic relative (%) and in "
              "direction (deg); graphical vs analytic relative to the largest value of its kind (omega, "
              "alpha, speed, acceleration, mechanism size).")
    md = style == "markdown"
    out = [f"# {md_text(m.title)}" if md else m.title, "", md_text(head) if md else head, "", legend, ""]
    out.append(render_table(c.table, style))
    for n, key, note in c.notes:
        out.append(f"{n}. {_md(key) if md else key}: {_md(note) if md else note}")
    return "\n".join(out).rstrip("\n") + "\n"


# -- the files' own explanations -----------------------------------------------------------------
_ITEM = re.compile(r"^(?:[-*]|\d+[.)])\s+")


def top_comments(path) -> list[tuple[str, str]]:
    """The comment block at the top of a TOML file, as blocks in reading order.

    ``("text", paragraph)``: consecutive comment lines joined; ``("item", text)``:
    a list item (a line starting ``- ``, ``* `` or ``1. ``, with its indented
    continuation lines); ``("pre", lines)``: indented lines that continue no
    item (formulas, aligned lists), kept verbatim. A blank or empty comment
    line ends a block; the block ends at the first line that is not a comment.
    """
    try:
        lines = Path(path).read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError):
        return []
    blocks: list[list] = []
    current = None
    for line in lines:
        s = line.strip()
        if s and not s.startswith("#"):
            break
        body = s[1:] if s else ""
        if body.startswith(" "):
            body = body[1:]
        if not body.strip():
            current = None
            continue
        indented = body.startswith("  ")
        if _ITEM.match(body):
            current = ["item", [_ITEM.sub("", body).strip()]]
            blocks.append(current)
        elif indented and current is not None and current[0] == "item":
            current[1].append(body.strip())
        elif indented:
            if current is None or current[0] != "pre":
                current = ["pre", []]
                blocks.append(current)
            current[1].append(body.rstrip())
        elif current is not None and current[0] == "text":
            current[1].append(body.strip())
        else:
            current = ["text", [body.strip()]]
            blocks.append(current)
    out = []
    for kind, body in blocks:
        if kind == "pre":
            width = min(len(b) - len(b.lstrip()) for b in body)
            out.append(("pre", "\n".join(b[width:] for b in body)))
        else:
            out.append((kind, " ".join(body)))
    return out


def _md(text: str) -> str:
    """Text safe in Markdown prose and table cells, every underscore escaped (the README's rule)."""
    return md_text(text, words=False)


def _anchor(title: str, used: set) -> str:
    """GitHub's heading anchor of a title (lower case, punctuation dropped, spaces to hyphens)."""
    a = re.sub(r"[^\w\- ]", "", title.lower()).replace(" ", "-")
    base, k = a, 1
    while a in used:
        a = f"{base}-{k}"
        k += 1
    used.add(a)
    return a


def _md_table(t: Table) -> str:
    lines = ["| " + " | ".join(_md(h) for h in t.header) + " |", "|" + "|".join("---" for _ in t.header) + "|"]
    lines += ["| " + " | ".join(_md(c) for c in r) + " |" for r in t.rows]
    return "\n".join(lines) + "\n"


def example_markdown(path, sol, figure: str | None, table_page: str | None = None) -> str:
    """The README section of one example: title, file, figure (and its table page, where the sheet has
    one: every row the book gives with its notes), table, notes, the file's comments."""
    m = sol.mechanism
    path = Path(path)
    c = comparison(sol)
    out = [f"## {_md(m.title)}", "", f"File: [`{path.name}`]({path.name})"
           + (f" · source: {_md(m.reference.source)}" if m.reference.source else ""), ""]
    if figure:
        out += [f"![{_md(m.title)}]({figure})", ""]
    if table_page:
        out += [f"Every value the book gives, with its notes: [the sheet's table page]({table_page}).", ""]
    if not m.reference:
        out += ["No printed values to compare (the file has no `[reference]` table): the graphical "
                "constructions against the analytic solve.", ""]
    out.append(_md_table(c.table))
    if c.notes:
        out += ["Notes on the book's values:", ""]
        out += [f"{n}. **{_md(key)}**: {_md(note)}" for n, key, note in c.notes]
        out.append("")
    comments = top_comments(path)
    if comments:
        out += ["About this example (from the file's comments):", ""]
        for i, (kind, body) in enumerate(comments):
            if kind == "text":
                out += [_md(body), ""]
            elif kind == "item":
                out.append(f"- {_md(body)}")
                if i + 1 == len(comments) or comments[i + 1][0] != "item":
                    out.append("")
            else:
                out += ["```text", body, "```", ""]
    return "\n".join(out).rstrip("\n") + "\n"


# -- the gallery ---------------------------------------------------------------------------------
def _checkout(folder: Path) -> bool:
    """Whether ``folder`` is a velpoly checkout: its gallery/ page beside the examples' package folder."""
    return (folder / "gallery").is_dir() and (folder / "velpoly" / "examples").is_dir()


def find_gallery(start=None) -> Path | None:
    """The gallery folder of a velpoly checkout (``gallery/``, its README and figures), found from
    ``start`` (default: the current folder) or one above it, else the one beside the package (an
    editable install); None when velpoly runs from an installed wheel outside any checkout."""
    here = Path(start or Path.cwd()).resolve()
    for folder in (here, *here.parents):
        if _checkout(folder):
            return folder / "gallery"
    root = Path(__file__).resolve().parent.parent
    return root / "gallery" if _checkout(root) else None


def _gallery_source(out: Path) -> Path:
    """The example files a gallery folder is built from: its checkout's velpoly/examples/ for a
    checkout's gallery/, else the package's."""
    root = out.resolve().parent
    return root / "velpoly" / "examples" if out.name == "gallery" and _checkout(root) else EXAMPLES


@dataclass(frozen=True)
class GalleryResult:
    """What a gallery build did: the files written, and ``failed`` as (file, error line) pairs;
    ``statuses``, each failure's exit status (FORMAT.md section 3: 2 its input is wrong, 3 it cannot be
    assembled, 1 an internal error)."""

    written: tuple
    built: tuple
    failed: tuple
    statuses: tuple = ()

    @property
    def exit_code(self) -> int:
        """0 when every example was built; else the worst of the failures' statuses (3 over 2) where each
        is its input's, and 1 (an internal error) where any is not."""
        if not self.failed:
            return 0
        return 1 if not self.statuses or 1 in self.statuses else max(self.statuses)


def _error_line(e: BaseException, path: Path) -> str:
    """``NAME: WHERE: WHAT``, naming the file by its name alone (the README is read anywhere)."""
    if isinstance(e, VelpolyError):
        return ": ".join(p for p in (path.name, e.where, e.what) if p)
    return f"{path.name}: internal error: {type(e).__name__}: {e}"


def _failure(e: BaseException, path: Path) -> tuple[str, int]:
    """An example's failure: its error line and exit status (its error's, 2 or 3; 1 for an internal
    error)."""
    return _error_line(e, path), (e.exit_code if isinstance(e, VelpolyError) else 1)


def build_gallery(source=None, out=None, style: str = "textbook", draw=None, log=None,
                  copy: bool | None = None, names=None, animations: bool = False,
                  jobs: int | None = None) -> GalleryResult:
    """Rebuild every example of ``source`` (its ``*.toml`` files, in natural name order) into ``out``.

    ``source`` defaults to the built-in examples, ``out`` to ``source``. For each
    file: its own sheet (``[drawing] sheet``, else the full sheet) as ``figures/NAME.png``; then ``README.md`` with a section
    per example. A failing example is reported (``log`` gets its error line) and
    left out of the README's sections but listed at its end; the others are built.
    ``copy`` (default: when the built-in examples are drawn into a folder other than
    their checkout's gallery/, e.g. from an installed wheel) also writes each file
    as ``out/NAME.toml``, so that the folder stands alone and its README links
    to files beside it. ``names`` (file stems) builds only those examples.

    The examples (and the animations) are drawn in ``jobs`` worker processes (default: one a core
    this process may use), each into memory; this process writes every file, in the order a build
    one example after another writes them, so the output is the same. A ``draw`` given runs in this
    process, one example after another.

    The build is whole or nothing: every file stays a temporary file beside its target until the README
    is written, then all are renamed over their targets (:func:`~velpoly.fileio.committed_together`).
    Ctrl-C or an error that stops the build leaves ``out`` as it was (a folder it made removed again);
    a failing example leaves none of its own files.
    """
    source = Path(source) if source is not None else EXAMPLES
    out = Path(out) if out is not None else source
    if copy is None:   # the built-in examples drawn anywhere but their own checkout's gallery
        copy = source.resolve() == EXAMPLES and out.resolve() not in (EXAMPLES, EXAMPLES.parent.parent / "gallery")
    files = _gallery_files(source, names)
    here = draw is not None   # a given draw runs here, in order
    draw = draw or _draw_to_file()
    made = [f for f in (out, out / "figures") if not f.exists()]   # removed again if the build stops
    try:
        with committed_together():
            return _build(files, here, jobs, out, style, copy, draw, log, animations, names, source)
    except BaseException:
        for folder in reversed(made):
            with contextlib.suppress(OSError):
                folder.rmdir()   # only where it is still empty
        raise


def _build(files, here: bool, jobs, out: Path, style: str, copy: bool, draw, log, animations: bool, names,
           source: Path) -> GalleryResult:
    """:func:`build_gallery`'s work, inside its group of outputs committed together."""
    pool, extra = None, ""
    try:
        pool = None if here else _pool(len(files), jobs)
        written, built, failed, sections = _build_examples(files, pool, out, style, copy, draw, log)
        if animations:   # one animation a mechanism family (velpoly.render.animate.gallery_animations)
            from .render.animate import gallery_animations
            run = None if pool is None else (lambda todo: _animations_in(pool, todo))
            only = [p.stem for p in files] if names else None   # a partial build: its examples' families
            files, extra = gallery_animations(source, out / "figures", log, only, run=run)
            written += files
    except BaseException:
        if pool is not None:   # Ctrl-C or an error: the workers stop at once, what they drew is dropped
            _stop_workers(pool)
        raise
    finally:
        if pool is not None:
            pool.shutdown(wait=True, cancel_futures=True)
            shutil.rmtree(pool.scratch, ignore_errors=True)   # what a stopped worker left half removed
    readme = _readme(sections, failed, source, out, extra)
    written.append(atomic_write_text(out / "README.md", readme))
    return GalleryResult(tuple(written), tuple(built), tuple((p, line) for p, line, _ in failed),
                         tuple(status for _, _, status in failed))


def _build_examples(files, pool, out: Path, style: str, copy: bool, draw, log) -> tuple[list, list, list, list]:
    """Every example of ``files`` built, in order: (figures written, final files built, failed as
    (file, error line, exit status), README sections as (title, text)). With a ``pool`` each is drawn in a worker
    and its figures written here; else ``draw`` draws it here. A failing example is logged and the
    others are built."""
    written, built, failed, sections = [], [], [], []
    results = [None] * len(files)
    if pool is not None:   # every example in a worker, into memory; the longest first (by its file's size),
        # so that no core waits alone for a long one at the end; the files are written here in order
        for i in sorted(range(len(files)), key=lambda i: -_size(files[i])):
            results[i] = pool.submit(_example_in_worker, files[i], out, style, copy)
    for path, result in zip(files, results):
        try:
            with committed_together():   # a failing example's files are dropped, the others' kept
                done, failure = _example_result(path, result, out, style, copy, draw)
        except Exception as e:  # one example's failure must not stop the others
            raise_if_interrupted()   # unless it is Ctrl-C's aftermath: then nothing more is built
            done, failure = None, _failure(e, path)
        if failure is not None:
            line, status = failure
            failed.append((path, line, status))
            if log:
                log(line)
            continue
        title, text, figs, final = done
        written += figs
        sections.append((title, text))
        built.append(final)
    return written, built, failed, sections


def _size(path: Path) -> int:
    """A file's size in bytes (0 where it cannot be read): the gallery's guess of how long it draws."""
    try:
        return path.stat().st_size
    except OSError:
        return 0


def _example_result(path: Path, result, out: Path, style: str, copy: bool, draw) -> tuple:
    """One example built: ((title, text, figures written, final file), None), or (None, the error
    line and exit status its worker sent). ``result`` is its worker's future (its figures are written here, in
    order); None: ``draw`` draws it in this process."""
    if result is None:
        return _example(path, out, style, copy, draw), None
    done, failure = result.result()
    if failure is not None:
        return None, failure
    title, text, figs, final = done
    return (title, text, [atomic_write_bytes(f, data) for f, data in figs], final), None


def _gallery_files(source: Path, names=None) -> list[Path]:
    """The example files of ``source`` in natural name order (only ``names``, file stems, if given)."""
    if not source.is_dir():
        raise InputError("not a folder", where="--source", file=str(source))
    files = sorted(source.glob("*.toml"), key=_natural)
    if not files:
        raise InputError("no *.toml files in the gallery folder", where="--source", file=str(source))
    if names:
        stems = {p.stem: p for p in files}
        for n in names:
            if _stem(n) not in stems:
                raise InputError(f"no example {n!r} in {source}", where="gallery", hint=_names_hint(source, files))
        files = [p for p in files if p.stem in {_stem(n) for n in names}]
    return files


def _names_hint(source: Path, files: list[Path]) -> str:
    """Where the names ``velpoly gallery NAME`` takes are: the built-in examples (``velpoly examples``
    lists them), or a ``--source`` folder's own files, listed (a few, then how many more)."""
    if source.resolve() == EXAMPLES:
        return "`velpoly examples` lists the built-in ones: name them without .toml"
    shown = ", ".join(p.stem for p in files[:8]) + (f" and {len(files) - 8} more" if len(files) > 8 else "")
    return f"the examples in {source} (name them without .toml): {shown}"


def _example(path: Path, out: Path, style: str, copy: bool, draw, keep: bool = False) -> tuple:
    """One example of the gallery: ``(title, README section, files written, its file)``. With ``keep``
    (in a worker) nothing is written: the files are ``(path, bytes)`` pairs for the caller to write."""
    from . import load, solve
    from .render.options import drawing_options
    from .solution import polygon_at_rest
    src = path
    m = load(path)
    sol = solve(m)
    still = polygon_at_rest(sol, drawing_options(m).sheet)
    if still is not None:   # before anything is written
        raise still
    files = []
    if copy:
        text, target = path.read_text(encoding="utf-8"), out / path.name
        if target.exists() and (not target.is_file() or target.read_text(encoding="utf-8",
                                                                        errors="replace") != text):
            raise InputError(f"{target} exists and is not the built-in example: not replaced",
                             where="-o", hint="move it away, or build the gallery into another folder")
        if not target.exists():
            files.append((target, text.encode("utf-8")) if keep else atomic_write_text(target, text))
        path = target
    target = out / "figures" / f"{path.stem}.png"
    kw = dict(sheet=drawing_options(m).sheet, style=style, steps=False)   # its own sheet
    figs = _in_memory(draw, sol, target, **kw) if keep else list(draw(sol, target, **kw))
    files += figs
    first = (figs[0][0] if keep else Path(figs[0])) if figs else target
    names = [Path(f[0] if keep else f) for f in figs]
    page = next((p for p in names if p.stem.endswith("-table")), None)   # the sheet's table page, if any
    text = example_markdown(src, sol, _relative(first, out), page and _relative(page, out))   # src: its copy's text
    # links in the README point to the example files from where the README is
    text = text.replace(f"]({path.name})", f"]({_relative(path, out)})", 1)
    return m.title, text, files, path


def _in_memory(draw, what, target: Path, **kw) -> list:
    """``draw(what, OUT, **kw)`` into a private temporary folder: ``[(path, bytes)]`` of the files it
    wrote (one path or a list), each named as beside ``target``."""
    import tempfile
    with tempfile.TemporaryDirectory(prefix="velpoly-gallery-", dir=_WORKER["scratch"]) as tmp:
        written = draw(what, Path(tmp) / target.name, **kw)
        written = written if isinstance(written, (list, tuple)) else [written]
        return [(target.with_name(Path(f).name), Path(f).read_bytes()) for f in written]


def _example_in_worker(path: Path, out: Path, style: str, copy: bool) -> tuple:
    """A worker's part of :func:`_example`: ``(result, None)``, or ``(None, (error line, exit status))``."""
    with _busy():
        try:
            return _example(path, out, style, copy, _draw_to_file(), keep=True), None
        except Exception as e:   # a VelpolyError need not survive pickling: its line does
            return None, _failure(e, path)


def _animation_in_worker(path: Path, out: Path):
    """One gallery animation drawn in a worker: ``(path, bytes)``, or the exception it raised."""
    from . import load
    from .render.animate import gallery_animation
    with _busy():
        try:
            return _in_memory(gallery_animation, load(path), out)[0]
        except Exception as e:
            return e if _picklable(e) else RuntimeError(f"{type(e).__name__}: {e}")


def _picklable(e: BaseException) -> bool:
    import pickle
    try:
        pickle.loads(pickle.dumps(e))
    except Exception:
        return False
    return True


def _animations_in(pool, todo: list) -> list:
    """gallery_animations' ``run``: each ``(file, out)`` animated in the pool, written here, in order."""
    futures = [pool.submit(_animation_in_worker, path, out) for path, out in todo]
    done = []
    for f in futures:
        got = f.result()
        done.append(got if isinstance(got, BaseException) else atomic_write_bytes(*got))
    return done


def _pool(tasks: int, jobs: int | None):
    """A process pool of ``jobs`` workers (default: the cores this process may use), or None where
    one process does as well (one core, one task). ``pool.scratch``: the one temporary folder the
    workers draw in, which the command removes when the pool is done (a worker stopped in the middle of
    removing its own leaves nothing behind)."""
    import os
    if jobs is None:
        jobs = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    jobs = min(jobs, tasks)
    if jobs < 2:
        return None
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor
    methods = multiprocessing.get_all_start_methods()
    ctx = multiprocessing.get_context("fork" if "fork" in methods else None)   # fork: the modules come along
    if ctx.get_start_method() == "fork":   # what every worker's first drawing loads: once here, not once a worker
        from .render.style import preload
        preload()
    import tempfile
    scratch = tempfile.mkdtemp(prefix="velpoly-gallery-")
    try:
        pool = ProcessPoolExecutor(jobs, mp_context=ctx, initializer=_worker_start, initargs=(scratch,))
    except BaseException:   # Ctrl-C on the way: no folder left behind
        shutil.rmtree(scratch, ignore_errors=True)
        raise
    pool.scratch = scratch
    return pool


_WORKER = {"busy": False, "stopped": False, "scratch": None}   # in a worker: drawing now; told to stop
                                                               # (SIGTERM); the pool's temporary folder


def _worker_start(scratch: str | None = None) -> None:
    """A worker leaves Ctrl-C to the command, which stops the build (:func:`_stop_workers`); it draws
    in the pool's ``scratch`` folder."""
    import signal
    _WORKER["scratch"] = scratch
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, _worker_stop)


def _worker_stop(signum, frame):
    """SIGTERM in a worker: a drawing is abandoned (its temporary folder removed on the way out),
    an idle worker leaves at once: by SystemExit, so that a lock it holds on the way out (the pool's task
    queue's, while it waits for its next task) is released, where ``os._exit`` left it taken and a sibling
    waiting on it for ever (:func:`_stop_workers` kills a worker still there all the same)."""
    _WORKER["stopped"] = True
    if _WORKER["busy"]:
        raise KeyboardInterrupt
    raise SystemExit(0)


class _busy:
    """A worker's task: SIGTERM abandons it (KeyboardInterrupt), never writes to the output."""

    def __enter__(self):
        if _WORKER["stopped"]:   # a task queued before the command was interrupted: not begun
            raise KeyboardInterrupt
        _WORKER["busy"] = True

    def __exit__(self, *exc):
        _WORKER["busy"] = False


def _stop_workers(pool, grace: float = 3.0) -> None:
    """The command is interrupted: each worker stops what it draws (SIGTERM) and the tasks queued are
    dropped; nothing they drew is written. A worker still there after ``grace`` seconds is killed: an idle
    worker leaves on SIGTERM at once, and one that left while it held the pool's task queue (waiting for its
    next task) leaves its lock taken, so that a sibling back from an abandoned drawing waits on it for ever
    (and the pool's shutdown with it); workers write nothing, so a kill loses nothing."""
    import time
    from multiprocessing.connection import wait
    procs = list((getattr(pool, "_processes", None) or {}).values())
    for proc in procs:
        try:
            proc.terminate()
        except (OSError, ValueError):
            pass
    end = time.monotonic() + grace
    left = procs
    while left and time.monotonic() < end:   # a process's sentinel is ready once it has ended (not reaped here)
        ended = set(wait([p.sentinel for p in left], timeout=max(0.0, end - time.monotonic())))
        left = [p for p in left if p.sentinel not in ended]
    for proc in left:
        try:
            proc.kill()
        except (OSError, ValueError):
            pass


README_MARK = "<!-- generated by velpoly gallery -->"   # the first line of every README the gallery writes


def check_gallery_folder(out: Path, option: str = "-o") -> None:
    """``velpoly gallery`` writes README.md and figures/ only into a folder that is new, empty, or
    holds a README.md velpoly generated (its first line is README_MARK): never over a user's own
    README or figures. Else an InputError saying to give -o."""
    out = Path(out)
    if not out.exists():
        return
    if not out.is_dir():
        raise InputError("is a file, not a folder", where=option, file=str(out), hint=f"give {option} a folder")
    try:
        if not any(out.iterdir()):
            return
        readme = out / "README.md"
        with open(readme, encoding="utf-8", errors="replace") as fh:
            if fh.readline().rstrip("\r\n") == README_MARK:
                return
    except FileNotFoundError:
        pass
    except OSError as e:
        raise InputError(f"cannot read: {e.strerror or e}", file=str(out / "README.md"),
                         hint="give -o a new or empty folder for the gallery") from None
    raise InputError("the folder is not velpoly's gallery: it holds files, but no README.md that "
                     "velpoly gallery generated; writing README.md and figures/ there could replace "
                     "your own", file=str(out),
                     hint="give -o a new or empty folder (velpoly gallery --source DIR -o OUT)")


def _natural(path: Path):
    """Sort key: names in natural order (ex3_4 before ex3_10)."""
    return [(0, int(t), "") if t.isdigit() else (1, 0, t.lower()) for t in re.split(r"(\d+)", path.stem)]


def _relative(path: Path, base: Path) -> str:
    import os
    return Path(os.path.relpath(Path(path).resolve(), Path(base).resolve())).as_posix()


def _readme(sections, failed, source: Path, out: Path, extra: str = "") -> str:
    used: set = set()
    args = ""
    if not (out.name == "gallery" and _gallery_source(out).resolve() == source.resolve()):   # not a checkout's own
        if source.resolve() != EXAMPLES:
            args += f" --source {_relative(source, Path.cwd())}"
        if out.resolve() != source.resolve():
            args += f" -o {_relative(out, Path.cwd())}"
    lines = [
        README_MARK,
        "# Gallery",
        "",
        "Textbook mechanisms drawn by velpoly, each checked against the book's printed answers. Every",
        "section shows the example's own sheet (the full sheet: the mechanism to scale, its velocity and",
        "acceleration polygons and their results; the instant-centre examples: the poles and the Kennedy",
        "circle) and a table: **book** is the printed value, **graphical** what the",
        "polygons and the Kennedy construction give, **analytic** the linear solve; *book vs analytic*",
        "is the relative deviation (and the direction's, in degrees), *graphical vs analytic* the",
        "difference relative to the largest value of its kind in the mechanism (largest omega, alpha,",
        "speed or acceleration; the mechanism's size for positions). Where the book disagrees, the",
        "notes and the file's comments say why.",
        "",
        f"This page is generated: `velpoly gallery{args}` rebuilds it and every figure from the",
        "mechanism files it links to (do not edit it by hand). The files ship with velpoly:",
        "`velpoly examples` lists them, `velpoly examples NAME` prints one to start a problem from.",
        "",
    ]
    if sections:
        lines += ["Examples:", ""]
        for title, _ in sections:
            lines.append(f"- [{_md(title)}](#{_anchor(title, used)})")
        if extra:
            lines.append("- [Animations: one mechanism of each family](#animations)")
        lines.append("")
    if extra:        # the animations, between the index and the examples
        lines += [extra]
    for _, text in sections:
        lines += [text]
    if failed:
        lines += ["## Not built", "", "These files failed; the error each gave:", ""]
        lines += [f"- {_md(failure[1])}" for failure in failed]
        lines.append("")
    return "\n".join(lines).rstrip("\n") + "\n"


# -- what the commands build ---------------------------------------------------------------------
def build_demo(out, style: str = "textbook"):
    """``velpoly demo``: the built-in six-bar's full sheet (SVG, PNG) and its comparison tables (text,
    Markdown) written into ``out``; returns the mechanism and the files written."""
    from . import load, solve
    out = Path(out)
    draw = _draw_to_file()
    m = load(example_path(DEMO_EXAMPLE))
    sol = solve(m)
    written = []
    for suffix in (".svg", ".png"):
        written += list(draw(sol, out / f"{DEMO_OUTPUT}{suffix}", sheet="full", style=style, steps=False))
    written.append(atomic_write_text(out / f"{DEMO_OUTPUT}-results.txt", comparison_text(sol, "text")))
    written.append(atomic_write_text(out / f"{DEMO_OUTPUT}-results.md", comparison_text(sol, "markdown")))
    return m, written


def gallery_folders(output=None, source=None) -> tuple[Path, Path, str]:
    """``velpoly gallery``'s (source, out, option naming out).

    The default source is the built-in examples (a checkout's velpoly/examples/ for its
    gallery/); the default output is the ``--source`` folder when one is given, else the
    checkout's gallery/ where velpoly runs from one, else ./gallery.
    """
    if output:
        out = Path(output)
    elif source:   # a folder of the user's own examples is built in place
        out = Path(source)
    else:   # a checkout's gallery/, else a folder gallery/ here (an installed velpoly has no gallery of its own)
        out = find_gallery() or Path("gallery")
    return (Path(source) if source else _gallery_source(out)), out, ("-o" if output else "--source")
