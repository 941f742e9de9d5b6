"""Errors that sunwind reports to its users as one line: what is wrong, where, and the fix."""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence


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
    problems : tuple of SunwindError
        The problems an error made by :func:`combine` lists, one line each (without their fixes,
        which its ``hint`` holds, one per line).
    """

    def __init__(
        self,
        message: str,
        *,
        path: str | None = None,
        part: str | None = None,
        hint: str | None = None,
        parameters: tuple[str, ...] = (),
        problems: tuple[SunwindError, ...] = (),
    ) -> None:
        self.message = message
        self.path = path
        self.part = part
        self.hint = hint
        self.parameters = parameters
        self.problems = problems
        super().__init__(str(self))

    def renamed(self, names: Mapping[str, str]) -> SunwindError:
        """The same error with each of its :attr:`parameters` found in ``names`` written as
        ``names[parameter]`` (a command-line flag) in the message and the hint."""

        def rename(text: str | None) -> str | None:
            return None if text is None else renamed_parameters(text, self.parameters, names)

        kind = type(self)
        return kind(
            rename(self.message),
            path=self.path,
            part=self.part,
            hint=rename(self.hint),
            parameters=self.parameters,
            problems=tuple(problem.renamed(names) for problem in self.problems),
        )

    def __str__(self) -> str:
        where = f"{self.path}: " if self.path else ""
        which = f"part '{self.part}' " if self.part else ""
        if self.problems:
            lines = [f"{where}{self.message}:"]
            for problem in self.problems:
                shown = problem if problem.path != self.path else _without_path(problem)
                lines.append(f"  {shown}")
            lines += [f"  fix: {fix}" for fix in (self.hint or "").splitlines()]
            return "\n".join(lines)
        fix = f"; {self.hint}" if self.hint else ""
        return f"{where}{which}{self.message}{fix}"


def _without_path(error: SunwindError) -> SunwindError:
    """``error`` without its file, for a list under a heading that names the file."""
    return type(error)(error.message, part=error.part, hint=error.hint, parameters=error.parameters)


def combine(errors: Sequence[SunwindError], hint: str | None = None) -> SunwindError:
    """One error listing every problem of ``errors``, one line each, then their distinct fixes.

    Errors made by this function are flattened into their problems and fixes. ``hint`` replaces the
    fixes of the other ``errors`` (one fix for a list of problems of one kind). One problem without
    ``hint`` is returned as it is. The result has the type of the first problem and names the file when
    every problem is in the same file.
    """
    problems: list[SunwindError] = []
    fixes: list[str] = [] if hint is None else [hint]
    for error in errors:
        if error.problems:
            problems += error.problems
            fixes += (error.hint or "").splitlines()
            continue
        problems.append(
            type(error)(error.message, path=error.path, part=error.part, parameters=error.parameters)
        )
        if hint is None and error.hint:
            fixes.append(error.hint)
    if len(problems) == 1 and hint is None and len(errors) == 1:
        return errors[0]
    paths = {problem.path for problem in problems}
    return type(problems[0])(
        f"{len(problems)} problems" if len(problems) > 1 else problems[0].message,
        path=paths.pop() if len(paths) == 1 else None,
        part=None if len(problems) > 1 else problems[0].part,
        hint="\n".join(dict.fromkeys(fixes)) or None,
        parameters=tuple(dict.fromkeys(p for problem in problems for p in problem.parameters)),
        problems=tuple(problems) if len(problems) > 1 else (),
    )


class MeshError(SunwindError):
    """A mesh file that cannot be read or is not a valid spacecraft surface."""


class MaterialError(SunwindError):
    """A material file or material assignment that is incomplete or out of range."""


class InputError(SunwindError):
    """A bad argument: a zero Sun vector, a NaN flux, an unknown unit."""


def renamed_parameters(text: str, parameters: Sequence[str], names: Mapping[str, str]) -> str:
    """``text`` with each of ``parameters`` found in ``names`` written as ``names[parameter]`` (a
    command-line flag), where it stands as a whole word.

    >>> renamed_parameters("speed_m_s 3 is slow", ("speed_m_s",), {"speed_m_s": "--speed"})
    '--speed 3 is slow'
    """
    for parameter in parameters:
        if parameter in names:
            text = re.sub(rf"(?<![\w-]){re.escape(parameter)}(?![\w-])", names[parameter], text)
    return text


class FlaggedWarning(UserWarning):
    """A warning whose message names Python ``parameters``, which the command line writes as its
    flags (:func:`renamed_parameters`). ``key``: what it is about, where one value may be checked
    under two names (a sweep's speed, then each of its velocities), so that it is said once."""

    def __init__(self, message: str, parameters: tuple[str, ...] = (), key: object = None) -> None:
        super().__init__(message)
        self.parameters = parameters
        self.key = key


class UnitWarning(FlaggedWarning):
    """A value whose size suggests a slip of unit (km/s typed for m/s, a model in mm read as metres):
    the run goes on with the value as given."""


class ReferencePointWarning(FlaggedWarning):
    """A table file whose moments are not about the table's reference point, or whose reading program
    must be told the point: the file is written, the warning says what was done and what to set there."""
