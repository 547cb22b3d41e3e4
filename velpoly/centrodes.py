"""Centrodes: the loci of a link's pole with the frame over a cycle.

The pole W of a link k with the frame follows from the link's velocity field,
``V_W = V_O + omega_k x (W - O) = 0``, so ``W = O + perp(V_O) / omega_k``. Its
locus in frame coordinates is the fixed centrode; expressed in the link's own
coordinates (those of the reference pose) it is the moving centrode, which
rolls on the fixed one.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import InputError
from .kinematics import Kinematics, prepare
from .rigid import perp
from .sweeps import Sweep

__all__ = ["Centrodes", "centrodes", "break_at_infinity"]


@dataclass(frozen=True)
class Centrodes:
    """The fixed and moving centrodes of ``link`` over a sweep, one row per pose.

    ``fixed`` (N, 2): the pole of the link with the frame, in frame coordinates;
    ``moving`` (N, 2): the same pole in the link's own coordinates (those of the
    reference pose). Rows are NaN where the link does not turn (omega ~ 0: the
    pole is at infinity, or farther than 1e9 mechanism sizes).
    """

    link: str
    fixed: np.ndarray
    moving: np.ndarray

    @property
    def defined(self) -> np.ndarray:
        return np.isfinite(self.fixed[:, 0])

    def carried(self, sw: Sweep, kin: Kinematics, i: int) -> np.ndarray:
        """The moving centrode where the link carries it at pose i (frame coordinates)."""
        k = kin.system.index[self.link]
        th = sw.q[i, 3 * k + 2]
        c, s = math.cos(th), math.sin(th)
        rot = np.array([[c, -s], [s, c]])
        return sw.q[i, 3 * k:3 * k + 2] + self.moving @ rot.T


def centrodes(sw: Sweep, link: str, kin: Kinematics | None = None) -> Centrodes:
    """The fixed and moving centrodes of ``link``: ``W = O + perp(V_O) / omega``.

    O is the link's body point that was at the world origin in the reference
    pose (so its place and velocity are the link's coordinates q and q').
    """
    m = sw.mechanism
    kin = kin or prepare(m)
    if link not in m.link_names:
        raise InputError(f"unknown link {link!r}", where="--centrodes", file=m.source,
                         hint="choose one of the moving links: " + ", ".join(k.name for k in m.moving_links))
    if link == m.frame.name:
        raise InputError(f"link {link!r} is the frame: its centrodes are points", where="--centrodes",
                         file=m.source, hint="choose one of the moving links: "
                         + ", ".join(k.name for k in m.moving_links))
    k = kin.system.index[link]
    o = sw.q[:, 3 * k:3 * k + 2]
    th = sw.q[:, 3 * k + 2]
    vo = sw.qd[:, 3 * k:3 * k + 2]
    om = sw.qd[:, 3 * k + 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        r = perp(vo) / om[:, None]
    far = ~(np.hypot(r[:, 0], r[:, 1]) <= 1e9 * m.size)        # omega ~ 0 (or exactly 0, or NaN)
    r[far] = np.nan
    fixed = o + r
    c, s = np.cos(th), np.sin(th)
    moving = np.stack([c * r[:, 0] + s * r[:, 1], -s * r[:, 0] + c * r[:, 1]], axis=-1)  # R(-theta) r
    return Centrodes(link, fixed, moving)


def break_at_infinity(xy: np.ndarray, omega: np.ndarray) -> np.ndarray:
    """A copy of a centrode with NaN rows inserted where the pole passes through infinity.

    (omega changes sign between two poses), so that a plotted line does not
    cross the figure.
    """
    rows = []
    for i in range(len(xy)):
        if i and np.sign(omega[i]) != np.sign(omega[i - 1]):
            rows.append([np.nan, np.nan])
        rows.append(xy[i])
    return np.array(rows, float).reshape(-1, 2)
