"""The whole file: the top-level keys, then each table's reader in order, then the pins and carriers
that follow from them, into one immutable :class:`~velpoly.model.Mechanism`."""
from __future__ import annotations

from ..model import Mechanism, Pin, Slider, frozen_map
from .contacts import read_contacts
from .context import Ctx, key_repr, show, table
from .drawing import check_drawing, read_drawing
from .driver import check_range, read_driver
from .links import read_links
from .paths import read_sliders, read_slots
from .points import read_points
from .reference import check_reference, read_reference

__all__ = ["build", "TOP_KEYS"]

TOP_KEYS = ("format", "title", "units", "points", "links", "sliders", "contacts", "slots",
            "driver", "reference", "drawing")


def build(ctx: Ctx, data: dict, default_title: str) -> Mechanism:
    """The mechanism of the file's ``data`` (plain TOML values); an InputError names the first bad entry."""
    title, units = _header(ctx, data, default_title)
    read_points(ctx, data)
    read_links(ctx, data)
    sliders = read_sliders(ctx, data)
    slots = read_slots(ctx, data)
    contacts = read_contacts(ctx, data)
    for pname in ctx.pts:   # every point is carried by something
        if pname not in ctx.listed and pname not in ctx.owned:
            raise ctx.err(f"points.{pname}", f"point {pname!r} is listed in no link",
                          hint="list it in the link that carries it")
    pins = _pins(ctx, sliders)
    frame = next(k.name for k in ctx.links if k.frame)
    driver = read_driver(ctx, table(ctx, data, "driver"), frame, pins, sliders)
    reference = read_reference(ctx, table(ctx, data, "reference", required=False))
    drawing = read_drawing(ctx, data)
    m = Mechanism(
        title=title, units=units,
        points=frozen_map({k: (float(v[0]), float(v[1])) for k, v in ctx.pts.items()}),
        links=tuple(ctx.links), pins=tuple(pins), sliders=tuple(sliders), contacts=tuple(contacts),
        slots=tuple(slots), driver=driver, reference=reference, drawing=frozen_map(drawing),
        carriers=frozen_map(_carriers(ctx)), source=ctx.file, point_order=tuple(ctx.pts),
        constructions=tuple(ctx.compass),
    )
    check_range(ctx, m)
    check_reference(ctx, m)
    check_drawing(ctx, m)
    return m


def _header(ctx: Ctx, data: dict, default_title: str) -> tuple[str, str]:
    """The top-level keys checked; the title and the units (kept in ``ctx.units`` for messages)."""
    for k in data:
        if k not in TOP_KEYS:
            raise ctx.err(str(k), f"unknown key {key_repr(k)}", hint="valid keys: " + ", ".join(TOP_KEYS))
    fmt = data.get("format", 1)
    if isinstance(fmt, bool) or fmt != 1:
        raise ctx.err("format", f"unsupported format {show(fmt)}", hint="this velpoly reads format = 1")
    title = data.get("title", default_title)
    if not isinstance(title, str):
        raise ctx.err("title", f"expected a string, got {show(title)}", hint='title = "Four-bar, Example 3.6"')
    units = data.get("units", "m")
    if not isinstance(units, str):
        raise ctx.err("units", f"expected a string such as \"mm\", got {show(units)}",
                      hint='units = "mm" (a label for lengths; "" for none)')
    ctx.units = units
    return title, units


def _pins(ctx: Ctx, sliders: list[Slider]) -> list[Pin]:
    """k links listing a point (not as a coincident point) -> k-1 pins, each with the first carrier
    (a slider's block first)."""
    pins = []
    for pname, ls in ctx.listed.items():
        carriers = [lk for lk in ls if (pname, lk) not in ctx.coincident]
        block = next((s.block for s in sliders if s.point == pname), None)
        if block in carriers:
            carriers.remove(block)
            carriers.insert(0, block)
        for other in carriers[1:]:
            pins.append(Pin(pname, (carriers[0], other)))
    return pins


def _carriers(ctx: Ctx) -> dict[str, tuple[str, ...]]:
    """Each point's carrying links: those listing it, then those carrying it unlisted."""
    carriers = {}
    for pname in ctx.pts:
        cl = list(ctx.listed.get(pname, []))
        for lk in ctx.owned.get(pname, []):
            if lk not in cl:
                cl.append(lk)
        carriers[pname] = tuple(cl)
    return carriers
