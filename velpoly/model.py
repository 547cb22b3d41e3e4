"""The immutable mechanism: points, links, joints, driver, reference values.

A :class:`Mechanism` is a one-degree-of-freedom planar linkage at its
*reference pose* (the pose the file draws). Links are rigid; every point a
link lists is fixed to it, with the shape taken from the reference pose.
Joints are inferred or declared:

* :class:`Pin` -- a revolute joint at a point shared by two links,
  ``V_P(i) = V_P(j)``;
* :class:`Slider` -- a prismatic joint: ``block`` slides on ``guide`` along
  a straight path (``angle``) or a circular one (``centre``);
* :class:`Contact` -- a higher pair (rolling or sliding) at ``point``;
* :class:`Slot` -- a pin in a slot: the pin slides along and turns in the
  slot (one constraint).

All containers are tuples or read-only mappings; positions are tuples of
floats. Nothing here changes after :func:`velpoly.load` builds it.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Mapping

import numpy as np

__all__ = [
    "Link", "Pin", "Slider", "Contact", "Slot", "Driver", "Reference", "Mechanism", "Construction",
    "frozen_map",
]


def frozen_map(d: Mapping | None = None) -> Mapping:
    """A read-only mapping (``MappingProxyType``) of a copy of ``d``."""
    return MappingProxyType(dict(d or {}))


@dataclass(frozen=True)
class Link:
    """A rigid link: its name, the points fixed to it, and whether it is the frame.

    The *angle* of a link is the direction from its first point to its second.
    """

    name: str
    points: tuple[str, ...]
    frame: bool = False


@dataclass(frozen=True)
class Pin:
    """A revolute joint at ``point`` between ``links[0]`` and ``links[1]``.

    Velocity equation: ``V_P(links[0]) = V_P(links[1])``.
    """

    point: str
    links: tuple[str, str]


@dataclass(frozen=True)
class Slider:
    """A prismatic joint: ``block`` slides on ``guide`` with its ``point`` on the path.

    The path is straight (``angle`` in degrees, fixed to the guide, through the
    point at the reference pose) or circular (``centre``, a point of the guide).
    Velocity equation: ``V_P(block) = V_P(guide) + V_P(block)/P(guide)``, the
    relative velocity along the path; on a straight path ``omega_block = omega_guide``.
    """

    block: str
    guide: str
    point: str
    angle: float | None = None
    centre: str | None = None


@dataclass(frozen=True)
class Contact:
    """A higher pair between ``links = (a, b)`` touching at ``point``.

    ``kind`` is ``"rolling"`` (no slip: ``V_P(a) = V_P(b)``) or ``"sliding"``
    (``(V_P(a) - V_P(b)) . u = 0`` along the common normal ``u``; with a
    prescribed ``slip``, also ``(V_P(a) - V_P(b)) . t = slip``). The profiles
    are given by their centres of curvature ``centres = (Ca, Cb)`` (``None`` for
    a flat profile) or, for velocities only, by the ``normal`` direction.
    """

    links: tuple[str, str]
    point: str
    kind: str
    slip: float | None = None
    centres: tuple[str | None, str | None] | None = None
    normal: float | None = None


@dataclass(frozen=True)
class Slot:
    """A pin in a slot: ``pin`` (a point of ``link``) slides in the slot of ``slot``.

    The slot's path at the pin is straight (``angle``, fixed to the slot link)
    or circular about the slot link's point ``centre``. One constraint:
    ``(V_P(link) - V_P(slot)) . n = 0``, n the path's normal.
    ``ends``: two points of the slot link bounding a straight slot (or None: unbounded);
    the pin's slip coordinate (P - S1) . e / (S2 - S1) . e stays in [0, 1], and reaching
    0 or 1 ends the motion.
    """

    pin: str
    link: str
    slot: str
    angle: float | None = None
    centre: str | None = None
    ends: tuple[str, str] | None = None


@dataclass(frozen=True)
class Driver:
    """The input motion: a crank ``link`` (omega, alpha) or a ``slider`` (speed, accel).

    ``omega`` is in rad/s, counter-clockwise positive; ``alpha`` in rad/s^2.
    ``angle`` (degrees, absolute) analyses the mechanism with the crank turned
    there instead of at the reference pose.
    """

    link: str | None = None
    omega: float = 0.0
    alpha: float = 0.0
    angle: float | None = None
    slider: str | None = None
    speed: float = 0.0
    accel: float = 0.0

    @property
    def is_slider(self) -> bool:
        return self.slider is not None


@dataclass(frozen=True)
class Reference:
    """Published answers to compare against (FORMAT.md section 1, ``[reference]``)."""

    source: str = ""
    omega: Mapping = field(default_factory=frozen_map)
    alpha: Mapping = field(default_factory=frozen_map)
    speed: Mapping = field(default_factory=frozen_map)
    velocity: Mapping = field(default_factory=frozen_map)
    acceleration: Mapping = field(default_factory=frozen_map)
    values: Mapping = field(default_factory=frozen_map)
    note: Mapping = field(default_factory=frozen_map)

    def __bool__(self) -> bool:
        return any((self.omega, self.alpha, self.speed, self.velocity, self.acceleration,
                    self.values))


@dataclass(frozen=True)
class Construction:
    """A compass construction of ``[points]`` (two circles, or a circle and a line): the
    intersection the file picks and the other one, at the reference pose.

    ``rule``: how the file picks (``near = [x, y]``, ``side = "left"``...); ``side``: the
    chosen one's side of the directed line between the two circles' centres (None for a
    circle and a line); ``other`` is None where the two touch; ``switch``: what to write
    instead of ``rule`` to take the other one.
    """

    point: str
    kind: str                  # "circles" or "circle and line"
    given: str                 # the construction as written, short: 'circles B 0.4, D 0.37'
    chosen: tuple
    other: tuple | None
    rule: str
    side: str | None = None
    switch: str = ""


@dataclass(frozen=True)
class Mechanism:
    """A planar mechanism at its reference pose.

    ``points`` maps each point's name to its reference position ``(x, y)``;
    ``carriers`` maps it to the links that carry it (list it, or own it as a
    contact point, a centre of curvature or a path centre).
    """

    title: str
    units: str
    points: Mapping  # name -> (x, y)
    links: tuple[Link, ...]
    pins: tuple[Pin, ...]
    sliders: tuple[Slider, ...]
    contacts: tuple[Contact, ...]
    slots: tuple[Slot, ...]
    driver: Driver
    reference: Reference = field(default_factory=Reference)
    drawing: Mapping = field(default_factory=frozen_map)
    carriers: Mapping = field(default_factory=frozen_map)  # point -> tuple of link names
    source: str = ""  # the file's name, for messages
    point_order: tuple[str, ...] = ()
    constructions: tuple[Construction, ...] = ()  # the compass constructions of [points], in file order

    # -- lookups -------------------------------------------------------------
    @property
    def frame(self) -> Link:
        return next(k for k in self.links if k.frame)

    @property
    def link_names(self) -> tuple[str, ...]:
        return tuple(k.name for k in self.links)

    @property
    def moving_links(self) -> tuple[Link, ...]:
        return tuple(k for k in self.links if not k.frame)

    def link(self, name: str) -> Link:
        for k in self.links:
            if k.name == name:
                return k
        raise KeyError(name)

    def position(self, name: str) -> np.ndarray:
        """The reference position of a point as a numpy array."""
        return np.array(self.points[name], dtype=float)

    @property
    def size(self) -> float:
        """A characteristic length: the diagonal of the points' bounding box."""
        p = np.array(list(self.points.values()), dtype=float)
        if len(p) == 0:
            return 1.0
        d = float(np.hypot(*(p.max(axis=0) - p.min(axis=0))))
        return d if d > 0 else 1.0

    def _repr_svg_(self) -> str:  # Jupyter display; rendering is imported lazily
        from .render import mechanism_svg
        return mechanism_svg(self)
