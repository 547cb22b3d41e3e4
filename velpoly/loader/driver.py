"""The ``[driver]`` table: a crank pinned to the frame (``link``, ``omega``, ``alpha``, ``angle``) or a
slider's point driven along its path (``slider``, ``speed``, ``accel``); and the range check of its rates."""
from __future__ import annotations

import math
from typing import Any, Callable

from ..model import Driver, Mechanism, Pin, Slider
from .context import Ctx, check_keys, read_name, read_number, show, too_large, too_small
from .units import ALPHA_HINT, OMEGA_HINT, RateTooLarge, RateTooSmall, parse_alpha, parse_omega

__all__ = ["read_driver", "read_rate", "check_range", "MAX_SPEED", "MAX_ACCEL", "MIN_SPEED", "MIN_ACCEL"]

# Floating point holds about 1e+-308: the kinematics squares speeds and multiplies rates by lengths,
# so the speeds and accelerations a file may ask for are bounded well inside that range.
MAX_SPEED = 1e100               # the driver's speeds: |omega| x size, |speed|
MAX_ACCEL = 1e200               # and accelerations: (omega^2 + |alpha|) x size, |accel|
MIN_SPEED = 1e-100              # and, unless zero, at least: speeds |omega| x size, |speed|
MIN_ACCEL = 1e-200              # and each acceleration term: omega^2 x size, |alpha| x size, |accel|


def read_driver(ctx: Ctx, d: dict, frame: str, pins: list[Pin], sliders: list[Slider]) -> Driver:
    check_keys(ctx, "driver", d, ("link", "omega", "alpha", "angle", "slider", "speed", "accel"))
    if ("link" in d) == ("slider" in d):
        raise ctx.err("driver", "give exactly one of 'link' (a crank) and 'slider' (a slider's point)" +
                      (" (both are given)" if "link" in d else ""),
                      hint='link = "2" with omega, or slider = "F" with speed')
    if "slider" in d:
        return _slider_driver(ctx, d, sliders)
    return _crank_driver(ctx, d, frame, pins)


def _slider_driver(ctx: Ctx, d: dict, sliders: list[Slider]) -> Driver:
    p = read_name(ctx, "driver.slider", d["slider"], "a point's name")
    if not any(s.point == p for s in sliders):
        raise ctx.err("driver.slider", f"no slider has the point {p!r}",
                      hint="name the point of a [[sliders]] entry" +
                      (": " + ", ".join(s.point for s in sliders) if sliders else " (there are none)"))
    for k in ("omega", "alpha", "angle"):
        if k in d:
            raise ctx.err(f"driver.{k}", f"'{k}' belongs to a crank driver",
                          hint="a slider driver has speed and accel (along its path)")
    if "speed" not in d:
        raise ctx.err("driver", "a slider driver needs 'speed'", hint="speed = v, in length units per second")
    for k in ("speed", "accel"):
        if too_small(d.get(k)):
            raise _too_small(ctx, f"driver.{k}", d[k])
    return Driver(slider=p, speed=read_number(ctx, "driver.speed", d["speed"]),
                  accel=read_number(ctx, "driver.accel", d.get("accel", 0.0)))


def _crank_driver(ctx: Ctx, d: dict, frame: str, pins: list[Pin]) -> Driver:
    link = read_name(ctx, "driver.link", d["link"], "a link's name")
    lnames = ctx.link_names
    if link not in lnames:
        raise ctx.err("driver.link", f"unknown link {link!r}", hint="links: " + ", ".join(lnames))
    if link == frame:
        raise ctx.err("driver.link", f"the driver cannot be the frame {frame!r}",
                      hint="drive a crank pinned to the frame")
    if not any(set(p.links) == {link, frame} for p in pins):
        raise ctx.err("driver.link", f"link {link!r} is not pinned to the frame {frame!r}",
                      hint="a crank driver turns about a pin on the frame (a point listed in both); "
                           "for a slider give slider = \"P\"")
    for k in ("speed", "accel"):
        if k in d:
            raise ctx.err(f"driver.{k}", f"'{k}' belongs to a slider driver", hint="a crank has omega and alpha")
    if "omega" not in d:
        raise ctx.err("driver", "missing 'omega'", hint='e.g. omega = "60 rpm" or omega = 10 (rad/s)')
    omega = read_rate(ctx, "driver.omega", d["omega"], parse_omega, "an angular velocity", OMEGA_HINT)
    alpha = read_rate(ctx, "driver.alpha", d.get("alpha", 0.0), parse_alpha, "an angular acceleration", ALPHA_HINT)
    angle = read_number(ctx, "driver.angle", d["angle"]) if "angle" in d else None
    return Driver(link=link, omega=omega, alpha=alpha, angle=angle)


def read_rate(ctx: Ctx, where: str, v: Any, parse: Callable[[Any], float], what: str, hint: str) -> float:
    """An omega or alpha (the driver's, or a book's printed one): a number, or a rate with its unit and sense in
    words (units.py: ``"6.702 rad/s cw"``)."""
    try:
        if too_large(v):   # a number beyond any float (1e400, 10**400), as "1e400 rpm" is
            raise RateTooLarge(v)
        if too_small(v):   # a nonzero number below any float (1e-400), as "1e-400 rpm" is
            raise RateTooSmall(v)
        x = parse(v)
    except RateTooLarge:
        raise ctx.err(where, f"{show(v)} is too large: beyond any floating-point number",
                      hint="check the driver's value and its unit (omega in rad/s or rpm)") from None
    except RateTooSmall:
        raise _too_small(ctx, where, v) from None
    except ValueError:
        raise ctx.err(where, f"cannot read {show(v)} as {what}", hint=hint) from None
    if not math.isfinite(x):
        raise ctx.err(where, f"must be finite, got {show(x)}", hint=hint)
    return x


def _too_small(ctx: Ctx, where: str, v: Any):
    """A rate written nonzero whose value is below any float: read, it would be 0, a driver at rest."""
    return ctx.err(where, f"{show(v)} is too small: below any floating-point number (it would read as 0)",
                   hint="check the driver's value and its unit; write 0 where 0 is meant")


def check_range(ctx: Ctx, m: Mechanism) -> None:
    """The driver's motion inside the range the arithmetic holds (the size is checked with the
    points): else speeds or accelerations would overflow or vanish (an input error, never a wrong number)."""
    size = m.size
    d = m.driver
    if d.is_slider:
        speed, accel = abs(d.speed), abs(d.accel)
        checks = (("driver.speed", speed, MAX_SPEED, f"{d.speed:g}"), ("driver.accel", accel, MAX_ACCEL, f"{d.accel:g}"))
    else:
        speed, accel = abs(d.omega) * size, (d.omega * d.omega + abs(d.alpha)) * size
        checks = (("driver.omega", speed, MAX_SPEED, f"{d.omega:g} rad/s"),
                  ("driver.alpha" if abs(d.alpha) > d.omega * d.omega else "driver.omega", accel, MAX_ACCEL,
                   f"{d.alpha:g} rad/s^2" if abs(d.alpha) > d.omega * d.omega else f"{d.omega:g} rad/s"))
    unit = m.units or "length units"
    _check_floor(ctx, m)
    for where, value, limit, shown in checks:
        if not value <= limit:
            what, per = ("speeds", "/s") if limit == MAX_SPEED else ("accelerations", "/s^2")
            reach = f"{value:.3g}" if math.isfinite(value) else "beyond 1e+308"
            raise ctx.err(where, f"{shown} is too large: {what} of {reach} {unit}{per} (at most {limit:g})",
                          hint="check the driver's value and its unit (omega in rad/s or rpm), and give the "
                               "lengths in units that keep the numbers within range")


def _check_floor(ctx: Ctx, m: Mechanism) -> None:
    """A driver rate written nonzero whose speeds |omega| x size (|speed|) would fall below MIN_SPEED, or
    whose acceleration terms omega^2 x size, |alpha| x size (|accel|) below MIN_ACCEL: an input error, as a
    rate below any float is (``omega = 1e-200``: omega^2 underflows to 0, the normal accelerations with it,
    and the polygons' scales fail)."""
    size, d = m.size, m.driver
    if d.is_slider:
        terms = (("driver.speed", d.speed, abs(d.speed), MIN_SPEED, "", "speeds"),
                 ("driver.accel", d.accel, abs(d.accel), MIN_ACCEL, "", "accelerations"))
    else:
        terms = (("driver.omega", d.omega, abs(d.omega) * size, MIN_SPEED, " rad/s", "speeds"),
                 ("driver.omega", d.omega, d.omega * d.omega * size, MIN_ACCEL, " rad/s", "accelerations"),
                 ("driver.alpha", d.alpha, abs(d.alpha) * size, MIN_ACCEL, " rad/s^2", "accelerations"))
    for where, rate, value, floor, unit, what in terms:
        shown = f"{rate:g}{unit}"
        if rate != 0 and not value >= floor:
            per = "/s" if what == "speeds" else "/s^2"
            raise ctx.err(where, f"{shown} is too small: {what} of {value:.3g} {m.units or 'length units'}{per} "
                                 f"(at least {floor:g}, or 0)",
                          hint="check the driver's value and its unit; write 0 where 0 is meant, and give the "
                               "lengths in units that keep the numbers within range")
