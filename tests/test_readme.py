"""The README's quick-start command and Python example run as written; its printed outputs are what
the commands print (to the digits shown)."""

import re

import pytest

from helpers import REPO
from helpers.readme import block_differences, line_differences, output_blocks, refresh

ROOT = REPO
README = (ROOT / "README.md").read_text()


@pytest.mark.slow
def test_python_example_runs(monkeypatch, tmp_path):
    monkeypatch.chdir(ROOT)
    blocks = re.findall(r"```python\n(.*?)```", README, flags=re.S)
    assert len(blocks) == 4
    namespaces = []
    for code in blocks:
        namespace: dict = {}
        exec(
            compile(code.replace("/tmp/sample.nc", str(tmp_path / "sample.nc")), "README.md", "exec"),
            namespace,
        )
        namespaces.append(namespace)
    light, gas, tables, laws = namespaces
    assert light["result"].reference_point == "user"  # the model's own point
    assert light["batch"].force_N.shape == (3, 3) and light["result"].force_N.shape == (3,)
    assert gas["result"].force_N.shape == (3,) and gas["result"].CD > 0
    assert tables["files"] == [tmp_path / "sample.nc"] and tables["result"].force_N.shape == (3,)
    assert "flux_W_m2" in tables["table"].attrs and "mesh_sha256" in tables["table"].attrs
    assert laws["c_n"].shape == laws["lobe"].c_n.shape == (5,)


@pytest.mark.slow
def test_quick_start_sweep_and_plot_commands_run(run_cli, monkeypatch, tmp_path):
    """The quick start's first command, on a coarse grid (its default grid takes minutes)."""
    monkeypatch.chdir(ROOT)
    sweep = re.search(r"&& sunwind (sweep [^&\n]+)", README).group(1).split()
    plot = re.search(r"&& sunwind (plot [^&\n]+)", README).group(1).split()
    table = str(tmp_path / "sample.nc")
    sweep = [table if word == "sample.nc" else word for word in sweep]
    code, out, err = run_cli(*sweep, "--step", "90", "--samples", "1")
    assert code == 0, err
    assert "sample_spacecraft.usda" in out and table in out
    plot = [
        table if word == "sample.nc" else str(tmp_path / word) if word == "plots" else word for word in plot
    ]
    code, out, err = run_cli(*plot)
    assert code == 0, err
    assert len(list((tmp_path / "plots").glob("*.png"))) == 6  # 2 x 2 maps, a view each


@pytest.mark.slow
def test_single_attitude_command_runs(run_cli, monkeypatch):
    monkeypatch.chdir(ROOT)
    command = re.search(r"`sunwind (srp [^`]+)`", README).group(1).split()
    code, out, err = run_cli(*command)
    assert code == 0, err
    assert "force   [N]" in out and "sample_spacecraft.usda" in out


def _printed_by(run_cli, command: str) -> list[str]:
    """What ``command`` (``sunwind ...``) prints on stdout, line by line; it must succeed."""
    code, out, err = run_cli(*command.split()[1:])
    assert code == 0, err
    return out.rstrip("\n").split("\n")


def test_readme_comparison_catches_the_last_shown_digit():
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
    assert [b.command for b in output_blocks(README)][:1] == ["sunwind srp " + SRP_EXAMPLE]


def test_every_console_block_that_shows_output_is_checked():
    """A ``console`` block is commands only (every line ``$ ...``) or one ``$ sunwind`` command and what
    it prints, which ``test_printed_outputs_are_what_the_commands_print`` compares."""
    blocks = re.findall(r"```console\n(.*?)```", README, flags=re.S)
    showing = [b for b in blocks if any(not line.startswith("$") for line in b.rstrip("\n").split("\n"))]
    assert len(showing) == len(output_blocks(README)) >= 2
    for block in showing:
        assert block.startswith("$ sunwind ") and block.count("\n$") == 0, block


#: The first printed example (kept here so that a README edit that drops it fails).
SRP_EXAMPLE = "meshes/data/sample_spacecraft.obj -m meshes/data/sample_spacecraft.toml --sun 0.3 -0.5 0.8"


@pytest.mark.slow
@pytest.mark.parametrize("block", output_blocks(README), ids=lambda b: b.command)
def test_printed_outputs_are_what_the_commands_print(run_cli, monkeypatch, request, block):
    """Every README output block against a run, numbers to the digits shown (tests/helpers/readme.py).

    After a change of what a command prints, refresh README's blocks from actual runs with
    ``python -m pytest -p no:cacheprovider -n 0 tests/test_readme.py -m slow -k printed --update-readme``
    (then review ``git diff README.md``).
    """
    monkeypatch.chdir(ROOT)
    if request.config.getoption("--update-readme"):
        refresh(ROOT / "README.md", lambda command: _printed_by(run_cli, command), only=block.command)
        return
    differences = block_differences(block, _printed_by(run_cli, block.command))
    assert not differences, "\n".join(differences)
