"""Regenerate the artefacts the validation and performance pages are built from.

    python docs/_data/regenerate.py            # both
    python docs/_data/regenerate.py validate   # docs/_data/validate.json only
    python docs/_data/regenerate.py bench      # docs/_data/bench.json only

Each runs one ``sunwind`` command (``COMMANDS``), keeps its JSON output whole and adds a ``provenance``
object: the command, when and on what machine it ran, the sunwind version and the wall time. The
command's exit status is recorded, not enforced: a failing validation is written down like a passing
one, and the page shows it.
"""

from __future__ import annotations

import json
import os
import platform
import shlex
import subprocess
import sys
import time
from datetime import datetime, timezone
from importlib.metadata import version
from pathlib import Path

HERE = Path(__file__).resolve().parent

#: The artefacts and the commands that make them (small settings: the docs are not the benchmark).
COMMANDS = {
    "validate": ["sunwind", "validate", "--quick", "--json"],
    "bench": ["sunwind", "bench", "--triangles", "5000", "--attitudes", "10", "--json"],
}


def machine() -> str:
    """The processor, core count and operating system the command ran on."""
    processor = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                processor = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{processor}, {os.cpu_count()} logical cores, {platform.system()} {platform.release()}"


def regenerate(name: str) -> Path:
    """Run the command of ``name`` and write ``<name>.json`` beside this file."""
    command = COMMANDS[name]
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    wall_s = time.perf_counter() - start
    try:
        data = json.loads(done.stdout)
    except json.JSONDecodeError as error:
        sys.exit(f"{shlex.join(command)} printed no JSON (exit {done.returncode}): {error}\n{done.stderr}")
    data["provenance"] = {
        "command": shlex.join(command),
        "date": datetime.now(timezone.utc).isoformat(timespec="seconds"),
        "machine": machine(),
        "python": platform.python_version(),
        "sunwind": version("sunwind"),
        "wall_s": round(wall_s, 1),
        "exit_status": done.returncode,
    }
    path = HERE / f"{name}.json"
    path.write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")
    return path


if __name__ == "__main__":
    for name in sys.argv[1:] or list(COMMANDS):
        if name not in COMMANDS:
            sys.exit(f"unknown artefact {name!r}: one of {', '.join(COMMANDS)}")
        print(f"wrote {regenerate(name)}")
