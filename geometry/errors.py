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

    Examples
    --------
    >>> print(SunwindError("flux is negative", path="run.toml", hint="give a positive flux"))
    run.toml: flux is negative; give a positive flux
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
        """Return the same error with its parameter names written as command-line flags.

        Each of its :attr:`parameters` found in ``names`` is written as ``names[parameter]`` in the message
        and the hint, and likewise in the problems it lists.

        Parameters
        ----------
        names : mapping of str to str
            Flag for each Python parameter name.

        Returns
        -------
        SunwindError
            A new error of the same type.

        Examples
        --------
        >>> error = InputError("speed_m_s -1 is negative", parameters=("speed_m_s",))
        >>> print(error.renamed({"speed_m_s": "--speed"}))
        --speed -1 is negative
        """

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
    """Merge errors into one that lists every problem, one line each, then their distinct fixes.

    Errors made by this function are flattened into their problems and fixes. ``hint`` replaces the
    fixes of the other ``errors`` (one fix for a list of problems of one kind). One problem without
    ``hint`` is returned as it is. The result has the type of the first problem and names the file when
    every problem is in the same file.

    Parameters
    ----------
    errors : sequence of SunwindError
        The errors, at least one.
    hint : str or None, optional
        One fix for all of them, in place of theirs.

    Returns
    -------
    SunwindError
        The combined error (or the only one).

    Examples
    --------
    >>> error = combine([MaterialError("a lacks rho", path="m.toml", hint="give rho"),
    ...                  MaterialError("b lacks rho", path="m.toml", hint="give rho")])
    >>> print(error)
    m.toml: 2 problems:
      a lacks rho
      b lacks rho
      fix: give rho
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
    """A mesh file that cannot be read or is not a valid spacecraft surface.

    Parameters
    ----------
    message : str
        What is wrong.
    path : str, optional
        The file concerned.
    part : str, optional
        The mesh part concerned.
    hint : str, optional
        How to fix it.
    parameters : tuple of str
        The Python parameters the message names.
    problems : tuple of SunwindError
        The problems a combined error lists.

    Examples
    --------
    >>> print(MeshError("is an open surface", path="sat.obj", part="wing"))
    sat.obj: part 'wing' is an open surface
    """


class MaterialError(SunwindError):
    """A material file or material assignment that is incomplete or out of range.

    Parameters
    ----------
    message : str
        What is wrong.
    path : str, optional
        The file concerned.
    part : str, optional
        The mesh part concerned.
    hint : str, optional
        How to fix it.
    parameters : tuple of str
        The Python parameters the message names.
    problems : tuple of SunwindError
        The problems a combined error lists.

    Examples
    --------
    >>> isinstance(MaterialError("rho > 1"), SunwindError)
    True
    """


class InputError(SunwindError):
    """A bad argument: a zero Sun vector, a NaN flux, an unknown unit.

    Parameters
    ----------
    message : str
        What is wrong.
    path : str, optional
        The file concerned.
    part : str, optional
        The mesh part concerned.
    hint : str, optional
        How to fix it.
    parameters : tuple of str
        The Python parameters the message names.
    problems : tuple of SunwindError
        The problems a combined error lists.

    Examples
    --------
    >>> str(InputError("flux_W_m2 nan is not finite", parameters=("flux_W_m2",)))
    'flux_W_m2 nan is not finite'
    """


def renamed_parameters(text: str, parameters: Sequence[str], names: Mapping[str, str]) -> str:
    """Write each parameter name in a text as its command-line flag, where it stands as a whole word.

    Parameters
    ----------
    text : str
        A message or hint.
    parameters : sequence of str
        The Python parameter names the text may hold.
    names : mapping of str to str
        Flag for each parameter name; names missing from it stay as they are.

    Returns
    -------
    str
        ``text`` with the names replaced.

    Examples
    --------
    >>> renamed_parameters("speed_m_s 3 is slow", ("speed_m_s",), {"speed_m_s": "--speed"})
    '--speed 3 is slow'
    """
    for parameter in parameters:
        if parameter in names:
            text = re.sub(rf"(?<![\w-]){re.escape(parameter)}(?![\w-])", names[parameter], text)
    return text


class FlaggedWarning(UserWarning):
    """A warning whose message names Python parameters, which the command line writes as its flags.

    Parameters
    ----------
    message : str
        The warning text.
    parameters : tuple of str, optional
        The Python parameters the message names (see :func:`renamed_parameters`).
    key : object, optional
        What it is about, where one value may be checked under two names (a sweep's speed, then each
        of its velocities), so that it is said once.

    Examples
    --------
    >>> warning = FlaggedWarning("speed_m_s is large", ("speed_m_s",), key="speed")
    >>> str(warning), warning.parameters
    ('speed_m_s is large', ('speed_m_s',))
    """

    def __init__(self, message: str, parameters: tuple[str, ...] = (), key: object = None) -> None:
        super().__init__(message)
        self.parameters = parameters
        self.key = key


class UnitWarning(FlaggedWarning):
    """A value whose size suggests a slip of unit; the run goes on with the value as given.

    Examples are km/s typed for m/s, or a model in mm read as metres.

    Parameters
    ----------
    message : str
        The warning text.
    parameters : tuple of str, optional
        The Python parameters the message names.
    key : object, optional
        What it is about, so that it is said once.

    Examples
    --------
    >>> issubclass(UnitWarning, FlaggedWarning)
    True
    """


class ReferencePointWarning(FlaggedWarning):
    """A table file whose moments are not about the table's reference point, or whose reader must be told it.

    The file is written; the warning says what was done and what to set in the reading program.

    Parameters
    ----------
    message : str
        The warning text.
    parameters : tuple of str, optional
        The Python parameters the message names.
    key : object, optional
        What it is about, so that it is said once.

    Examples
    --------
    >>> issubclass(ReferencePointWarning, UserWarning)
    True
    """
