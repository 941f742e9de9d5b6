"""Errors that sunwind reports to its users as one line: what is wrong, where, and the fix."""

from __future__ import annotations

import re
from collections.abc import Mapping


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
    parameters : tuple of str
        The Python parameters the message names (``"flux_W_m2"``), as written in it: the command line
        renames them to its flags (:meth:`renamed`).
    """

    def __init__(
        self,
        message: str,
        *,
        path: str | None = None,
        part: str | None = None,
        hint: str | None = None,
        parameters: tuple[str, ...] = (),
    ) -> None:
        self.message = message
        self.path = path
        self.part = part
        self.hint = hint
        self.parameters = parameters
        super().__init__(str(self))

    def renamed(self, names: Mapping[str, str]) -> SunwindError:
        """The same error with each of its :attr:`parameters` found in ``names`` written as
        ``names[parameter]`` (a command-line flag) in the message and the hint."""

        def rename(text: str | None) -> str | None:
            for parameter in self.parameters:
                if text is not None and parameter in names:
                    text = re.sub(rf"(?<![\w-]){re.escape(parameter)}(?![\w-])", names[parameter], text)
            return text

        kind = type(self)
        return kind(
            rename(self.message),
            path=self.path,
            part=self.part,
            hint=rename(self.hint),
            parameters=self.parameters,
        )

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
