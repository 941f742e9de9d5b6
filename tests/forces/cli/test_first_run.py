"""The first run says it is compiling numba's kernels, and only when they are not on disk yet."""

import os
import subprocess
import sys

from sunwind.forces.cli import progress


def test_a_fresh_numba_cache_has_every_kernel_to_compile(tmp_path):
    code = (
        "import sunwind.forces.cli.app; from sunwind.forces.cli import progress; "
        "from numba.core.dispatcher import Dispatcher; import sys; "
        "n = len({id(v) for m in list(sys.modules.values()) if m and m.__name__.startswith('sunwind.') "
        "for v in vars(m).values() if isinstance(v, Dispatcher)}); "
        "print(progress.uncompiled_kernels(), n)"
    )
    env = os.environ | {"NUMBA_CACHE_DIR": str(tmp_path)}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    missing, total = map(int, out.stdout.split())
    assert total > 50 and missing == total  # an empty cache: every kernel is still to be compiled


def test_the_first_compilation_of_a_run_says_so_once(monkeypatch, capsys):
    import numba

    monkeypatch.setattr(progress, "uncompiled_kernels", lambda: 40)
    with progress.compile_notices():
        for offset in (1.0, 2.0):  # two compilations, one notice
            numba.njit(lambda x, a=offset: x + a)(1.0)
    err = capsys.readouterr().err
    assert err.startswith("sunwind: notice: compiling numba kernels on first use (40 not on disk yet")
    assert "about 30 s at most" in err and err.count("\n") == 1
    numba.njit(lambda x: x * 3.0)(1.0)  # outside the context: nothing said
    assert capsys.readouterr().err == ""


def test_a_kernel_that_has_run_is_found_compiled(run_cli, tmp_path):
    from sunwind.geometry.rays import crossings

    mesh = tmp_path / "box.obj"
    assert run_cli("mesh", "box", "-o", mesh)[0] == 0
    code, _, err = run_cli(
        "srp", mesh, "--sun", "1", "0", "0", "--reflectivity", "0", "--specular-fraction", "0"
    )
    assert code == 0, err
    kernels = [v for v in vars(crossings).values() if hasattr(v, "_cache") and v.signatures]
    assert kernels and all(kernel._cache._cache_file._load_index() for kernel in kernels)
