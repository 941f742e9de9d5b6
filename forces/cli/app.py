"""The ``sunwind`` program: its commands, and one line on stderr for a bad input or a warning.

Every command parses its flags into library objects (:mod:`.options`), makes its call, and prints text
or ``--json``. A :class:`~sunwind.geometry.errors.SunwindError` becomes ``sunwind: error: ...`` with the
library's parameter names written as this program's flags, and exit status 1 (2 for a malformed command
line); a warning (a result outside a model's range, still given) becomes ``sunwind: warning: ...``;
a precompute that takes more than a second shows ``sunwind: <step> ...`` lines (:mod:`.progress`).
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import click

from sunwind.forces.cli.attitude import drag, forces, srp
from sunwind.forces.cli.earth import earth
from sunwind.forces.cli.fit import fit
from sunwind.forces.cli.mesh import info, mesh
from sunwind.forces.cli.options import FLAGS
from sunwind.forces.cli.orbit import orbit
from sunwind.forces.cli.progress import StepLines, compile_notices
from sunwind.forces.cli.sensing import attitude
from sunwind.forces.cli.sight import visibility
from sunwind.forces.cli.tables import plot, sweep_command
from sunwind.forces.cli.tools import bench, validate
from sunwind.geometry.errors import SunwindError, renamed_parameters
from sunwind.geometry.memory import LIMIT_VARIABLE
from sunwind.geometry.progress import reporting


@click.group(context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100})
@click.version_option(package_name="sunwind", message="%(prog)s %(version)s")
def app() -> None:
    """Solar-radiation-pressure forces and torques on a spacecraft mesh, with ray-cast shadowing.

    Body frame of the mesh, SI units. Run `sunwind COMMAND --help` for each command.
    """


#: Each command's job, one line of ``sunwind --help`` (click would cut the docstrings' first lines short).
JOBS = {
    "srp": "SRP force and torque at one Sun direction.",
    "drag": "Free-molecular drag force and torque for one flow.",
    "forces": "SRP and drag (and the Earth's radiation) at one attitude.",
    "earth": "Albedo, infrared and thermal loads from the planet below.",
    "sweep": "Tables over a grid or list of attitudes, for simulators.",
    "orbit": "Loads and accumulated momentum along an orbit.",
    "plot": "Pictures of a table: maps of every component, pressure views.",
    "info": "What a mesh holds and what the shadow pass makes of it.",
    "mesh": "Write a parametric mesh or the sample spacecraft.",
    "bench": "Time every setting on a model, each with its error.",
    "validate": "Run the validation cases against closed forms and tracers.",
    "fit": "Fit surface coefficients to flight telemetry.",
    "attitude": "Attitude from measured heat fluxes of sensor parts.",
    "visibility": "Lines of sight from points: blocked or clear, maps, orbits.",
}
for command in (
    srp,
    drag,
    forces,
    earth,
    sweep_command,
    orbit,
    plot,
    info,
    mesh,
    bench,
    validate,
    fit,
    attitude,
    visibility,
):
    command.short_help = JOBS[command.name]
    app.add_command(command)


def main(argv: list[str] | None = None) -> None:
    """Run the ``sunwind`` program on a command line.

    A bad input is reported as one ``sunwind: error: ...`` line on stderr (the library's parameter
    names written as this program's flags) and a non-zero exit; each warning becomes one
    ``sunwind: warning: ...`` line, said once. Long precompute steps and numba's first compilation
    are reported on stderr while the command runs.

    Parameters
    ----------
    argv : list of str or None, optional
        The arguments after the program's name; None (the default) takes ``sys.argv[1:]``.

    Raises
    ------
    SystemExit
        Status 1 for a refused input (a :class:`~sunwind.geometry.errors.SunwindError`) or memory
        running out, 2 for a malformed command line, 130 when aborted or interrupted. A command that
        succeeds returns normally.

    Examples
    --------
    >>> main(["--version"])
    sunwind ...
    >>> import contextlib, sys
    >>> with contextlib.redirect_stderr(sys.stdout):
    ...     try:
    ...         main(["srp", "no-such-mesh.obj", "--sun", "1", "0", "0"])
    ...     except SystemExit as exit:
    ...         print("exit status", exit.code)
    sunwind: error: no-such-mesh.obj: file not found; check the path and its spelling
    exit status 1
    """

    said: set[str] = set()

    def one_line(message, category, filename, lineno, file=None, line=None) -> None:
        text = renamed_parameters(str(message), getattr(message, "parameters", ()), FLAGS)
        if issubclass(category, RuntimeWarning) and "encountered in" in text:  # numpy's, unchecked input
            text = (
                f"numerical {text} ({Path(filename).name}:{lineno}): a value outside what sunwind checks "
                "reached the arithmetic; check the results for inf or NaN and report the command line"
            )
        key = getattr(message, "key", None) or text
        if key not in said:  # a check made for each of a batch's vectors, or twice, says it once
            said.add(key)
            print(f"sunwind: warning: {text}", file=sys.stderr)

    shown = warnings.showwarning
    warnings.showwarning = one_line
    try:
        with reporting(StepLines()), compile_notices():
            args = sys.argv[1:] if argv is None else list(argv)
            app.main(args=args, prog_name="sunwind", standalone_mode=False, obj={"argv": args})
    except SunwindError as error:
        print(f"sunwind: error: {error.renamed(FLAGS)}", file=sys.stderr)
        sys.exit(1)
    except click.UsageError as error:
        if isinstance(error, getattr(click.exceptions, "NoArgsIsHelpError", ())):
            print(error.format_message())  # click >= 8.2 raises this for a bare `sunwind`
            return
        command = error.ctx.command_path if error.ctx else "sunwind"
        print(f"{command}: error: {error.format_message()} (see --help)", file=sys.stderr)
        sys.exit(2)
    except MemoryError:  # a last resort: every size a user gives is checked before its arrays are made
        print(
            "sunwind: error: out of memory; lower the sizes asked for (--samples, --view-rays, a finer "
            f"--step, mesh resolution) or set {LIMIT_VARIABLE} to refuse such runs before they start",
            file=sys.stderr,
        )
        sys.exit(1)
    except click.exceptions.Abort:
        print("sunwind: aborted", file=sys.stderr)
        sys.exit(130)
    except KeyboardInterrupt:
        print("sunwind: interrupted", file=sys.stderr)
        sys.exit(130)
    finally:
        warnings.showwarning = shown
