"""Textbook figures of a solved mechanism (matplotlib lives only in this package).

The sheets (``velpoly draw FILE --sheet ...``)::

    from velpoly.render import draw_to_file
    draw_to_file(sol, "sixbar.svg", sheet="full", style="textbook", steps=False)

and the panels, each drawn on ``ax`` (pyplot's current axes if None) and
returning its artists, shapely-style::

    draw_mechanism(sol, ax=None)              # displacement diagram to scale
    draw_velocity_polygon(sol, ax=None)       # from velpoly.polygons.velocity_polygon(sol)
    draw_acceleration_polygon(sol, ax=None)
    draw_poles(sol, ax=None)                  # every instant centre on the mechanism
    draw_kennedy_circle(sol, ax=None)
    draw_results_table(sol, ax=None)

``mechanism_svg(m)`` is the SVG Jupyter shows for a Mechanism.
"""
from __future__ import annotations

__all__ = ["draw_to_file", "render_sheet", "mechanism_svg", "draw_mechanism", "draw_velocity_polygon",
           "draw_acceleration_polygon", "draw_poles", "draw_kennedy_circle", "draw_results_table", "SHEETS"]

_WHERE = {
    "draw_to_file": "sheet", "render_sheet": "sheet", "mechanism_svg": "sheet", "SHEETS": "sheet",
    "draw_mechanism": "displacement",
    "draw_velocity_polygon": "polygon", "draw_acceleration_polygon": "polygon",
    "draw_poles": "kennedy", "draw_kennedy_circle": "kennedy",
    "draw_results_table": "table",
}


def __getattr__(name):
    # the modules are imported on first use, so that `velpoly.render` costs nothing until it draws
    if name in _WHERE:
        import importlib
        return getattr(importlib.import_module(f".{_WHERE[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
