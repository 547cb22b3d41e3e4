"""The ``[reference]`` table: a book's printed answers (``omega``, ``alpha``, ``speed``, ``velocity``,
``acceleration``, ``values`` in textbook notation) and notes on them, checked against the mechanism."""
from __future__ import annotations

from ..errors import InputError
from ..model import Mechanism, Reference, frozen_map
from .context import Ctx, check_keys, key_repr, read_number, show
from .driver import read_rate
from .units import ALPHA_HINT, OMEGA_HINT, parse_alpha, parse_omega

__all__ = ["read_reference", "check_reference"]

_TABLES = ("omega", "alpha", "speed", "velocity", "acceleration", "values", "note")


def read_reference(ctx: Ctx, r: dict) -> Reference:
    if not r:
        return Reference()
    check_keys(ctx, "reference", r, ("source",) + _TABLES)
    src = r.get("source", "")
    if not isinstance(src, str):
        raise ctx.err("reference.source", f"expected a string, got {show(src)}", hint='source = "Example 3.6"')
    out = {}
    for key in _TABLES:
        t = r.get(key, {})
        if not isinstance(t, dict):
            raise ctx.err(f"reference.{key}", f"expected a table, got {show(t)}",
                          hint=f'{key} = {{ "3" = 6.702 }}' if key in ("omega", "alpha") else
                          f"{key} = {{ KEY = VALUE, ... }}")
        t = {k: _rated(ctx, key, k, v) for k, v in t.items()}
        for k, v in t.items():
            _value(ctx, key, k, v)
        # vectors become tuples: the model shares no list with the caller's dict (it is immutable)
        out[key] = frozen_map({str(k): tuple(v) if isinstance(v, list) else v for k, v in t.items()})
    return Reference(source=src, **out)


_RATES = {"omega": (parse_omega, "an angular velocity", OMEGA_HINT),
          "alpha": (parse_alpha, "an angular acceleration", ALPHA_HINT)}


def _rated(ctx: Ctx, key: str, k, v):
    """A printed omega or alpha (``omega``, ``alpha``, a ``values`` key ``omega_3``) written as books print it,
    ``"6.702 rad/s cw"``: its number, read as the driver's rate is (its units, its sense in words); any other
    value as it is."""
    kind = key if key in _RATES else (str(k).split("_")[0] if key == "values" else None)
    if isinstance(v, str) and kind in _RATES:
        return read_rate(ctx, f"reference.{key}.{k}", v, *_RATES[kind])
    return v


def _value(ctx: Ctx, key: str, k, v) -> None:
    """One printed value of the table ``key``: a number, a vector, or (``note``) a string."""
    w = f"reference.{key}.{k}"
    if key in ("omega", "alpha"):
        lnames = ctx.link_names
        if str(k) not in lnames:
            raise ctx.err(w, f"unknown link {key_repr(k)}", hint="links: " + ", ".join(lnames))
        read_number(ctx, w, v)
    elif key == "speed":   # a magnitude, as a bare one in velocity: a negative one is the reversed vector's
        read_number(ctx, w, v)
    elif key in ("velocity", "acceleration"):   # [magnitude, direction] or a bare magnitude
        if isinstance(v, list):
            vector_shape(ctx, w, v)
        read_numbers(ctx, w, v)
    elif key == "values":   # numbers, or a list of them: which shape a key takes is checked by its kind
        read_numbers(ctx, w, v)
    elif not isinstance(v, str):
        raise ctx.err(w, f"expected a string saying what is wrong with the printed value, got {show(v)}",
                      hint='note = { V_B = "misprint: ..." }')


def read_numbers(ctx: Ctx, where: str, v) -> None:
    """A number, or a list of numbers (each checked)."""
    for x in (v if isinstance(v, list) else [v]):
        read_number(ctx, where, x)


def vector_shape(ctx: Ctx, where: str, v: list) -> None:
    """A printed vector written as a list is ``[magnitude, direction]``."""
    if len(v) != 2:
        raise ctx.err(where, f"expected a magnitude or [magnitude, direction], got a list of {len(v)}",
                      hint="a vector is [magnitude, direction in degrees], e.g. [435.2, 21.7]")


def check_reference(ctx: Ctx, m: Mechanism) -> None:
    """Every reference key names something of this mechanism (FORMAT.md section 1)."""
    from ..motion import point_keys
    from ..reference import parse_key, validate_reference
    try:
        validate_reference(m, ctx)
    except InputError as e:
        raise ctx.err(e.where, e.what, e.hint) from None
    moving: dict[str, list[str]] = {}
    for key, p, lk in point_keys(m):
        if key != p:
            moving.setdefault(p, []).append(lk)
    ref = m.reference
    for table, prefix in (("speed", "V_"), ("velocity", "V_"), ("acceleration", "A_"), ("values", "")):
        for k in getattr(ref, table):
            q = parse_key(m, prefix + k)
            w = f"reference.{table}.{k}"
            if q is None:
                raise ctx.err(w, f"unknown point {k!r}", hint="a point's name, or point and link (B3 or B@3): "
                              + ", ".join(m.point_order[:20]))
            for p, lk in (q.refs if q.kind in ("V", "A") else ()):
                if lk is None and p in moving:
                    raise ctx.err(w, f"point {p!r} moves differently on links {', '.join(moving[p])}: say which",
                                  hint=f"e.g. {prefix or (q.kind + '_')}{p}{moving[p][0]} or {p}@{moving[p][0]}")
