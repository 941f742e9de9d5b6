"""The README's quick-start command and Python example run as written."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text()


def test_python_example_runs(monkeypatch):
    monkeypatch.chdir(ROOT)
    blocks = re.findall(r"```python\n(.*?)```", README, flags=re.S)
    assert blocks
    results = []
    for code in blocks:
        namespace: dict = {}
        exec(compile(code, "README.md", "exec"), namespace)
        results.append(namespace["result"])
    assert all(result.force_N.shape == (3,) for result in results)
    assert results[0].reference_point == "user"  # the SRP example gives its own point


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
