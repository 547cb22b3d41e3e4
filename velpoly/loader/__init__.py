"""Mechanism files (TOML, FORMAT.md section 1) to :class:`~velpoly.model.Mechanism`.

Every check of the input lives in this package. Each failure raises
:class:`~velpoly.errors.InputError` naming the file, the entry
(``points.C``, ``driver.omega``) and what is wrong, with a hint.

One module per part of the work:

- ``source``: a path, TOML text or a dict in (``load``, ``loads``), plain TOML values out;
- ``build``: the top-level keys, then each table's reader in order, then pins and carriers;
- one reader per table: ``points`` (coordinates and compass constructions), ``links``,
  ``paths`` (``[[sliders]]`` and ``[[slots]]``, by one function), ``contacts``, ``driver``,
  ``reference``, ``drawing``;
- ``context``: the file being read and what has been read so far, and the checks all readers share;
- ``toml_positions``: the line of an entry in the TOML text (``locate``), for error messages;
- ``units``: angular rates with units and senses in words (``parse_omega``, ``parse_alpha``).
"""
from __future__ import annotations

import tomllib  # noqa: F401  (velpoly.loader.tomllib: tests read TOML as the loader does)

from .source import load, loads
from .toml_positions import locate
from .units import SENSES, parse_alpha, parse_omega

__all__ = ["load", "loads", "locate", "parse_omega", "parse_alpha", "SENSES"]
