"""The one error hierarchy of velpoly.

Every failure a user can cause is a :class:`VelpolyError`. Its message is the
one line the command line prints, ``FILE: WHERE: WHAT``, and ``hint`` says
what to do about it. The command line maps :class:`InputError` to exit
status 2 and :class:`PoseError` (a pose that cannot be assembled, or is
singular) to exit status 3.
"""
from __future__ import annotations

__all__ = ["VelpolyError", "InputError", "PoseError", "AssemblyError", "SingularPoseError"]


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
        """The one-line message ``FILE: WHERE: WHAT``."""
        parts = [p for p in (self.file, self.where, self.what) if p]
        return ": ".join(parts)

    def with_file(self, file: str) -> "VelpolyError":
        """The same error, naming ``file`` (where none was named yet)."""
        if not self.file:
            self.file = file
            self.args = (self.line(),)
        return self

    def __str__(self) -> str:
        return self.line()


class InputError(VelpolyError):
    """The mechanism file (or an argument) is wrong: exit status 2."""

    exit_code = 2


class PoseError(VelpolyError):
    """The mechanism cannot be analysed at the requested pose: exit status 3.

    ``links`` names the links involved (those that come into line, say).
    """

    exit_code = 3

    def __init__(self, what: str, where: str = "", file: str = "", hint: str = "",
                 links: tuple[str, ...] = ()):
        self.links = tuple(links)
        super().__init__(what, where, file, hint)


class AssemblyError(PoseError):
    """The mechanism cannot be assembled at the requested driver position."""


class SingularPoseError(PoseError):
    """The pose is singular (toggle, dead centre, parallel construction lines)."""
