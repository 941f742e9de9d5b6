"""The documentation's examples run as written, and its printed outputs are what the commands print
(to the digits shown): README.md, docs/getting_started.md and every docs/guides/*.md page
(tests/helpers/doc_outputs.py finds and compares them)."""

import re

import pytest

from helpers import REPO
from helpers.doc_outputs import (
    block_differences,
    console_blocks,
    line_differences,
    output_blocks,
    pages,
    python_blocks,
    refresh,
)

PAGES = pages(REPO)
README = (REPO / "README.md").read_text()
#: What each command printed in this process, so that a command shown on two pages runs once.
_PRINTED: dict[str, list[str]] = {}


def _name(path) -> str:
    return path.relative_to(REPO).as_posix()


@pytest.fixture
def in_scratch(monkeypatch, tmp_path):
    """Run from an empty folder whose ``meshes/`` is the repository's: the pages' examples read the
    bundled meshes by relative paths and write their files (``-o sample.nc``) beside them."""
    (tmp_path / "meshes").symlink_to(REPO / "meshes", target_is_directory=True)
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_the_pages_are_there():
    names = [_name(p) for p in PAGES]
    assert names[0] == "README.md" and "docs/getting_started.md" in names
    assert len([n for n in names if n.startswith("docs/guides/")]) >= 10, names
    assert python_blocks(README), "README shows no Python example"


@pytest.mark.slow
@pytest.mark.parametrize("page", [p for p in PAGES if python_blocks(p.read_text())], ids=_name)
def test_python_examples_run(in_scratch, page):
    """A page's ``python`` blocks run in order in one namespace (a block may use what one above made)."""
    namespace: dict = {"__name__": "__doc_example__"}
    for k, code in enumerate(python_blocks(page.read_text())):
        exec(compile(code, f"{_name(page)}, python block {k + 1}", "exec"), namespace)


@pytest.mark.slow
def test_quick_start_sweep_and_plot_commands_run(run_cli, in_scratch):
    """The quick start's first command, on a coarse grid without inter-reflection (its default grid takes
    half a minute, and the reflections' precompute as long again)."""
    sweep = re.search(r"&& sunwind (sweep [^&\n]+)", README).group(1).split()
    plot = re.search(r"&& sunwind (plot [^&\n]+)", README).group(1).split()
    code, out, err = run_cli(*sweep, "--step", "90", "--reflections", "none")
    assert code == 0, err
    assert "sample_spacecraft.usda" in out and "sample.nc" in out
    code, out, err = run_cli(*plot)
    assert code == 0, err
    assert len(list((in_scratch / "plots").glob("*.png"))) == 6  # 2 x 2 maps, a view each


@pytest.mark.slow
def test_readme_single_attitude_command_runs(run_cli, in_scratch):
    """The README's first command line (it shows no output, so no output block checks it)."""
    command = re.search(r"^\$ sunwind (srp [^\n#]+)", README, flags=re.M).group(1).split()
    code, out, err = run_cli(*command)
    assert code == 0, err
    assert "force   [N]" in out and "sample_spacecraft.usda" in out


def test_comparison_catches_the_last_shown_digit():
    """The comparison of ``test_printed_outputs_are_what_the_commands_print`` has teeth."""
    line = "  force   [N]      [-7.574603e-06  +1.430111e-05]  |F| = 2.573961e-05"
    assert line_differences(line, line.replace("2.573961", "2.573963"))
    assert not line_differences(line, line.replace("2.573961", "2.573962"))  # a processor's rounding flip
    assert line_differences("power 7670.57 W", "power 7670.58 W")  # six digits: no flip allowed
    assert line_differences(line, line.replace("+1.430111", "-1.430111"))
    assert line_differences(line, line.replace("|F|", "|M|"))
    assert not line_differences(line, line.replace("2.573961e-05", "2.5739614e-05"))  # more digits printed
    assert not line_differences("power 7670.57 W", "power    7670.574 W")  # rounds to the digits shown
    assert line_differences("power 7670.57 W", "power 7670.565 W")


#: The first printed example of the getting-started page (kept here so that an edit that drops it fails).
SRP_EXAMPLE = "meshes/data/sample_spacecraft.obj -m meshes/data/sample_spacecraft.toml --sun 0.3 -0.5 0.8"


def test_every_console_block_that_shows_output_is_checked():
    """A ``console`` block is commands only (every line ``$ ...``) or one ``$ sunwind`` command and what
    it prints, which ``test_printed_outputs_are_what_the_commands_print`` compares."""
    checked = 0
    for page in PAGES:
        text = page.read_text()
        lines = [(b, b.rstrip("\n").split("\n")) for b in console_blocks(text)]
        showing = [b for b, shown in lines if any(not line.startswith("$") for line in shown)]
        assert len(showing) == len(output_blocks(text)), _name(page)
        for block in showing:
            assert block.startswith("$ sunwind ") and block.count("\n$") == 0, f"{_name(page)}: {block}"
        checked += len(showing)
    assert checked >= 6
    started = output_blocks((REPO / "docs" / "getting_started.md").read_text())
    assert [b.command for b in started][:1] == ["sunwind srp " + SRP_EXAMPLE]


def _printed_by(run_cli, command: str) -> list[str]:
    """What ``command`` (``sunwind ...``) prints on stdout, line by line; it must succeed."""
    if command not in _PRINTED:
        code, out, err = run_cli(*command.split()[1:])
        assert code == 0, err
        _PRINTED[command] = out.rstrip("\n").split("\n")
    return list(_PRINTED[command])


OUTPUTS = [(page, block) for page in PAGES for block in output_blocks(page.read_text())]


@pytest.mark.slow
@pytest.mark.parametrize(("page", "block"), OUTPUTS, ids=[f"{_name(p)}: {b.command}" for p, b in OUTPUTS])
def test_printed_outputs_are_what_the_commands_print(run_cli, in_scratch, request, page, block):
    """Every output block of every page against a run, numbers to the digits shown.

    After a change of what a command prints, refresh the pages' blocks from actual runs with
    ``python -m pytest -p no:cacheprovider -n 0 tests/test_doc_outputs.py -m slow -k printed --update-docs``
    (then review ``git diff README.md docs``).
    """
    if request.config.getoption("--update-docs"):
        refresh(page, lambda command: _printed_by(run_cli, command), only=block.command)
        return
    differences = block_differences(block, _printed_by(run_cli, block.command))
    assert not differences, "\n".join(differences)
