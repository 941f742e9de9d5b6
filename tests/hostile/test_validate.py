"""Issue 17 item 19 on the command line: ``sunwind validate`` runs every family and ends with a count.

Before: ``validate`` ran the SRP cases only and printed no count; ``--quick`` and ``--json`` were
unknown options (exit 2). After: every family, ``N passed, M failed``, exit 1 when any failed (the run
itself: ``tests/forces/cli/test_tools.py``).
"""

import pytest

CASES = [
    pytest.param(("validate", "--samples", "4"), 2, "No such option '--samples'", id="unknown-option"),
    pytest.param(("validate", "cases.txt"), 2, "Got unexpected extra argument", id="extra-argument"),
]


@pytest.mark.parametrize(("argv", "code", "words"), CASES)
def test_validate_command_lines(run_cli, argv, code, words):
    got, out, err = run_cli(*argv)
    assert got == code, out + err
    assert words in (out.splitlines()[-1] if code == 0 else err)
    assert "Traceback" not in out + err
