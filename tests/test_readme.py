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


def test_quick_start_srp_command_runs(run_cli, monkeypatch):
    monkeypatch.chdir(ROOT)
    command = re.search(r"&& sunwind (srp [^\n]+)", README).group(1).split()
    code, out, err = run_cli(*command)
    assert code == 0, err
    assert "force   [N]" in out and "sample_spacecraft.usda" in out
