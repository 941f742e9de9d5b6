"""The README's quick-start command and Python example run as written."""

import re

import pytest

from helpers import REPO

ROOT = REPO
README = (ROOT / "README.md").read_text()


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
    assert len(list((tmp_path / "plots").glob("*.png"))) == 5


def test_single_attitude_command_runs(run_cli, monkeypatch):
    monkeypatch.chdir(ROOT)
    command = re.search(r"`sunwind (srp [^`]+)`", README).group(1).split()
    code, out, err = run_cli(*command)
    assert code == 0, err
    assert "force   [N]" in out and "sample_spacecraft.usda" in out


def console_examples() -> list[tuple[str, list[str]]]:
    """README's ``console`` blocks that print what they run: the command and the lines it prints."""
    examples = []
    for block in re.findall(r"```console\n(.*?)```", README, flags=re.S):
        lines = block.rstrip("\n").split("\n")
        if lines[0].startswith("$ sunwind ") and len(lines) > 1 and not lines[1].startswith("$"):
            examples.append((lines[0][2:], lines[1:]))
    return examples


@pytest.mark.slow
@pytest.mark.parametrize(
    ("command", "printed"), console_examples(), ids=lambda x: x if isinstance(x, str) else ""
)
def test_printed_outputs_are_what_the_commands_print(run_cli, monkeypatch, command, printed):
    """Line for line, but where the view factors came from (computed, or read from a cache)."""
    monkeypatch.chdir(ROOT)
    code, out, err = run_cli(*command.split()[1:])
    assert code == 0, err
    got = out.rstrip("\n").split("\n")
    assert len(got) == len(printed)
    for line, expected in zip(got, printed, strict=True):
        if expected.lstrip().startswith("view factors"):
            assert line.split(",")[0] == expected.split(",")[0]
        else:
            assert line == expected
