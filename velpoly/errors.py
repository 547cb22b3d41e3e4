"""The one error hierarchy of velpoly.

Every failure a user can cause is a :class:`VelpolyError`. Its message is the
one line the command line prints, ``FILE: WHERE: WHAT``, and ``hint`` says
what to do about it. The command line maps :class:`InputError` to exit
status 2 and :class:`PoseError` (a pose that cannot be assembled, or is
singular) to exit status 3.
"""
from __future__ import annotations

import re

__all__ = ["VelpolyError", "InputError", "ArgumentTypeError", "ArgumentValueError", "ConstructionError", "PoseError",
           "AssemblyError", "SingularPoseError", "one_line", "control_character"]


class VelpolyError(Exception):
    """Base class of every error velpoly raises on purpose.

    Parameters
    ----------
    what : str
        What is wrong, in words.
    where : str, optional
        The entry concerned, as ``table.key`` (``points.C``, ``driver.omega``).
    file : str, optional
        The file's name (or ``<text>`` for TOML text, ``<dict>`` for a dict).
    hint : str, optional
        What to do about it.
    """

    exit_code = 2

    def __init__(self, what: str, where: str = "", file: str = "", hint: str = ""):
        self.what = what
        self.where = where
        self.file = file
        self.hint = hint
        super().__init__(self.line())

    def line(self) -> str:
        """The one-line message ``FILE: WHERE: WHAT`` (control characters escaped)."""
        parts = [p for p in (self.file, self.where, self.what) if p]
        return one_line(": ".join(parts))

    def hint_line(self) -> str:
        """The hint on one line ("" if none)."""
        return one_line(self.hint)

    def with_file(self, file: str) -> "VelpolyError":
        """The same error, naming ``file`` (where none was named yet)."""
        if not self.file:
            self.file = file
            self.args = (self.line(),)
        return self

    def __str__(self) -> str:
        return self.line()


def one_line(text: str) -> str:
    """``text`` with line breaks and other control characters escaped, so it prints as one line.

    >>> print(one_line("two" + chr(10) + "lines"))
    two\\nlines
    """
    text = str(text)
    if not any(control_character(ch) for ch in text):
        return text
    return "".join(ascii(ch)[1:-1] if control_character(ch) else ch for ch in text)


def control_character(ch: str) -> bool:
    """A control character (C0, DEL, C1) or a line or paragraph separator (U+2028, U+2029): never
    printed raw in a message, never part of a name."""
    return ch < " " or "\x7f" <= ch <= "\x9f" or ch in "\u2028\u2029"


class InputError(VelpolyError):
    """The mechanism file (or an argument) is wrong: exit status 2."""

    exit_code = 2


class ArgumentTypeError(InputError, TypeError):
    """A Python API argument of the wrong type (``solve(None)``, ``angle="30"``): ``where`` names it."""


class ArgumentValueError(InputError, ValueError):
    """A Python API argument of the right type but a wrong value (``angle=nan``, 2-D angles)."""


class ConstructionError(VelpolyError):
    """The mechanism has no graphical construction order that velpoly.polygons knows
    (exit status 2); the analytic solve still stands. Also importable from velpoly.polygons."""

    exit_code = 2


class PoseError(VelpolyError):
    """The mechanism cannot be analysed at the requested pose: exit status 3.

    ``links`` names the links involved (those that come into line, say).
    """

    exit_code = 3

    def __init__(self, what: str, where: str = "", file: str = "", hint: str = "",
                 links: tuple[str, ...] = ()):
        self.links = tuple(str(k) for k in links)
        super().__init__(what, where, file, hint)

    def line(self) -> str:
        """``FILE: WHERE: WHAT (links i, j)``: the message names the links involved."""
        text = super().line()
        if self.links and not re.search(r"\blinks? \d|\blinks? '", self.what):
            text += " (" + ("link " if len(self.links) == 1 else "links ") + ", ".join(self.links) + ")"
        return one_line(text)


class AssemblyError(PoseError):
    """The mechanism cannot be assembled at the requested driver position."""


class SingularPoseError(PoseError):
    """The pose is singular (toggle, dead centre, parallel construction lines)."""
