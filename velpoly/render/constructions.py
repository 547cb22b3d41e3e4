"""What a sheet draws from: the polygons and the poles a sheet needs, built once.

:mod:`velpoly.render.sheet` lays the pages out and :mod:`velpoly.render.table`
reads the results from the same :class:`Constructions`; both import it from here.
"""
from __future__ import annotations

from dataclasses import dataclass

from ..errors import InputError
from .options import SHEETS

__all__ = ["Constructions", "constructions", "check_sheet"]


@dataclass(frozen=True)
class Constructions:
    """What a sheet draws from: the polygons and the poles (None where the sheet needs none)."""

    velocity: object = None
    acceleration: object = None
    poles: object = None


def check_sheet(sheet: str) -> None:
    """An InputError unless ``sheet`` is one of SHEETS."""
    if sheet not in SHEETS:
        raise InputError(f"unknown sheet {sheet!r}; valid sheets: " + ", ".join(SHEETS), where="--sheet")


def constructions(sol, sheet: str) -> Constructions:
    """Build what ``sheet`` needs with :mod:`velpoly.polygons` and :mod:`velpoly.poles`.

    The acceleration sheet needs accelerations (InputError without centres of
    curvature); the full sheet then shows velocities only. The displacement
    sheet needs none (it shows no answers).
    """
    check_sheet(sheet)
    vel = acc = poles = None
    if sheet in ("velocity", "full"):
        from ..polygons import velocity_polygon
        vel = velocity_polygon(sol)
    if sheet == "acceleration" or (sheet == "full" and sol.has_accelerations):
        from ..polygons import acceleration_polygon
        acc = acceleration_polygon(sol)
    if sheet in ("poles", "velocity", "full"):
        from ..poles import locate_poles
        poles = locate_poles(sol)
    return Constructions(vel, acc, poles)
