"""Errors that sunwind reports to its users as one line: what is wrong, where, and the fix."""

from __future__ import annotations


class SunwindError(ValueError):
    """A problem with the user's input, reported as one line.

    Parameters
    ----------
    message : str
        What is wrong.
    path : str, optional
        The file concerned.
    part : str, optional
        The mesh part (OBJ group, glTF node, USD prim path) concerned; the message then reads as
        what the part is or has ("is an open surface", "has no material").
    hint : str, optional
        How to fix it.
    """

    def __init__(
        self,
        message: str,
        *,
        path: str | None = None,
        part: str | None = None,
        hint: str | None = None,
    ) -> None:
        self.message = message
        self.path = path
        self.part = part
        self.hint = hint
        super().__init__(str(self))

    def __str__(self) -> str:
        where = f"{self.path}: " if self.path else ""
        which = f"part '{self.part}' " if self.part else ""
        fix = f"; {self.hint}" if self.hint else ""
        return f"{where}{which}{self.message}{fix}"


class MeshError(SunwindError):
    """A mesh file that cannot be read or is not a valid spacecraft surface."""


class MaterialError(SunwindError):
    """A material file or material assignment that is incomplete or out of range."""


class InputError(SunwindError):
    """A bad argument: a zero Sun vector, a NaN flux, an unknown unit."""
