"""Printed outputs of the documentation pages (README.md, docs/index.md, docs/getting_started.md,
docs/guides/*.md):
find them, compare them with a run to the digits shown, and rewrite them.

An output block is a page's ``console`` block whose first line is ``$ sunwind ...`` and whose next
lines (up to the closing fence) are what that command prints. A printed line is split into numbers
and the text between them: the text must match (runs of spaces count as one, since column widths
follow the numbers), and each number must equal the run's number rounded to the digits the page
shows (``2.573961e-05`` fails against ``2.573963e-05``; ``7670.57`` passes against ``7670.574``). A
number shown to seven significant digits or more may be one unit off in its last digit: sums of
many terms can differ in their last bits between processors (the vector width orders the additions),
which flips the rounding of a seventh digit now and then (an orbit's angular impulse printed
``-5.457986e-04`` here is ``-5.457987e-04`` on an AVX-512 machine); any larger difference fails.
A ``view factors`` or ``open sky`` line is compared up to its first comma (whether they were computed
or read from a cache, and the cache's path, depend on the machine).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

#: The pages whose examples are checked, relative to the repository's root.
PAGE_GLOBS = ("README.md", "docs/index.md", "docs/getting_started.md", "docs/guides/*.md")


def pages(root: Path) -> list[Path]:
    """Every documentation page with examples, README.md first, then the site's pages by name."""
    return [path for pattern in PAGE_GLOBS for path in sorted(root.glob(pattern))]


def python_blocks(text: str) -> list[str]:
    """The code of every ``python`` block of ``text``, in order."""
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)


def console_blocks(text: str) -> list[str]:
    """The body of every ``console`` block of ``text``, in order."""
    return re.findall(r"^```console\n(.*?)^```", text, flags=re.S | re.M)


#: A number as the commands print them: not part of a word, optional sign, decimals and exponent.
NUMBER = re.compile(r"(?<![\w.^/:-])[+-]?\d+(?:\.\d+)?(?:e[+-]?\d+)?(?![\w.])")
#: Lines compared only up to their first comma.
MACHINE_DEPENDENT = ("view factors", "open sky")


@dataclass(frozen=True)
class OutputBlock:
    """One printed example: the command (without ``$``), its printed lines and where they sit in the text."""

    command: str
    printed: list[str]
    start: int
    end: int


def output_blocks(text: str) -> list[OutputBlock]:
    """Every output block of ``text`` in order; ``start:end`` spans the printed lines."""
    blocks = []
    for match in re.finditer(r"^```console\n(\$ sunwind [^\n]*)\n(.*?)^```", text, flags=re.S | re.M):
        body = match.group(2)
        if body and not body.startswith("$"):
            printed = body.rstrip("\n").split("\n")
            blocks.append(OutputBlock(match.group(1)[2:], printed, match.start(2), match.end(2)))
    return blocks


def _shown(token: str, value: float) -> str:
    """``value`` written with the sign, decimals and exponent form of ``token``."""
    sign = "+" if token.startswith("+") else ""
    mantissa, _, exponent = token.lstrip("+-").partition("e")
    decimals = len(mantissa.partition(".")[2])
    return f"{value:{sign}.{decimals}{'e' if exponent else 'f'}}"


def _last_digit_flip(token: str, value: float) -> bool:
    """Whether ``value`` is within one unit of the last digit of ``token`` that has seven significant
    digits or more (a rounding flipped by the processor, see the module's docstring)."""
    mantissa, _, exponent = token.lstrip("+-").partition("e")
    digits = len(mantissa.replace(".", "").lstrip("0"))
    unit = 10.0 ** (int(exponent or 0) - len(mantissa.partition(".")[2]))
    return digits >= 7 and abs(value - float(token)) <= 1.000001 * unit


def line_differences(expected: str, got: str) -> list[str]:
    """What differs between a page's line and the printed line, to the page's precision (empty: same)."""
    name = expected.strip()
    if name.startswith(MACHINE_DEPENDENT):
        expected, got = expected.split(",")[0], got.split(",")[0]
    texts = [re.sub(r"\s+", " ", t) for t in NUMBER.split(expected)]
    got_texts = [re.sub(r"\s+", " ", t) for t in NUMBER.split(got)]
    if texts != got_texts:
        return [f"text: {expected!r} != {got!r}"]
    problems = []
    for token, value in zip(NUMBER.findall(expected), NUMBER.findall(got), strict=True):
        if _shown(token, float(value)) != token and not _last_digit_flip(token, float(value)):
            problems.append(f"number: page {token}, run {value} (shown {_shown(token, float(value))})")
    return problems


def block_differences(block: OutputBlock, got: list[str]) -> list[str]:
    """Every difference between a block's printed lines and a run's, line by line."""
    if len(got) != len(block.printed):
        return [f"{len(block.printed)} lines on the page, {len(got)} printed: {got}"]
    return [
        f"line {k + 1}: {p}"
        for k, (e, g) in enumerate(zip(block.printed, got, strict=True))
        for p in line_differences(e, g)
    ]


def refresh(path: Path, run: Callable[[str], list[str]], only: str | None = None) -> int:
    """Rewrite every output block of the file at ``path`` (``only``: of that command) with
    ``run(command)``'s lines; how many changed. Machine-dependent lines keep the page's text after
    their first comma.
    """
    text = path.read_text()
    changed = 0
    for block in reversed(output_blocks(text)):  # from the end, so earlier spans stay valid
        if only is not None and block.command != only:
            continue
        got = run(block.command)
        for k, line in enumerate(got):
            if line.strip().startswith(MACHINE_DEPENDENT) and k < len(block.printed):
                old = block.printed[k]
                got[k] = line.split(",")[0] + ("," + old.split(",", 1)[1] if "," in old else "")
        if got != block.printed:
            changed += 1
            text = text[: block.start] + "\n".join(got) + "\n" + text[block.end :]
    path.write_text(text)
    return changed
