"""The memory a request needs, against the memory it may use: sized before anything is allocated.

Every user-given size that drives an allocation (shadow points per side, view-factor rays, the grid
step of a sweep, mesh resolutions) is turned into an estimate of the peak bytes of its dominant
arrays and checked with :func:`require` before the arrays are made. The limit is
``SUNWIND_MAX_MEMORY`` (bytes, or with a suffix: ``500M``, ``4G``, ``1.5T``; powers of 1024) when
set, else the memory the system reports available (``MemAvailable`` of ``/proc/meminfo``, else
free pages by ``os.sysconf``).
"""

from __future__ import annotations

import math
import os
import re

from sunwind.geometry.errors import InputError

#: The environment variable that sets the memory limit [bytes, or a number with K, M, G or T].
LIMIT_VARIABLE = "SUNWIND_MAX_MEMORY"
_UNITS = {"": 1, "K": 2**10, "M": 2**20, "G": 2**30, "T": 2**40, "P": 2**50}
_SETTING = re.compile(r"\s*(\d+(?:\.\d*)?|\.\d+)(?:e([+-]?\d+))?\s*([KMGTP]?)(?:I?B)?\s*", re.IGNORECASE)


def parse_size(text: str) -> int:
    """Read a memory size written as ``123``, ``500M``, ``4G`` or ``1.5GiB``; suffixes are powers of 1024.

    Parameters
    ----------
    text : str
        The size, as :data:`LIMIT_VARIABLE` would hold it.

    Returns
    -------
    int
        The size [bytes].

    Raises
    ------
    InputError
        Not a size of at least one byte.

    Examples
    --------
    >>> parse_size("500M"), parse_size("1.5GiB"), parse_size("2e3")
    (524288000, 1610612736, 2000)
    """
    match = _SETTING.fullmatch(text)
    if match is not None:
        number, exponent, unit = match.groups()
        value = float(f"{number}e{exponent or 0}") * _UNITS[unit.upper()]
        if math.isfinite(value) and value >= 1:
            return int(value)
    raise InputError(
        f"{LIMIT_VARIABLE}={text!r} is not a memory size",
        hint=f"give bytes or a number with K, M, G or T, e.g. {LIMIT_VARIABLE}=4G, or unset it",
    )


#: A container's memory limit and use (cgroup v2, else v1): the kernel kills a process past the limit
#: whatever the machine has free.
CGROUP_FILES = (
    ("/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current"),
    ("/sys/fs/cgroup/memory/memory.limit_in_bytes", "/sys/fs/cgroup/memory/memory.usage_in_bytes"),
)


def available_memory() -> int:
    """Measure the memory the system can give without swapping [bytes].

    This is ``MemAvailable`` (else the free pages), and no more than what is left under the memory limit
    of the container (cgroup) the process runs in.

    Returns
    -------
    int
        Available memory [bytes], at least 0.

    Examples
    --------
    >>> available_memory() > 0
    True
    """
    free = _system_available()
    for limit_file, usage_file in CGROUP_FILES:
        limit, usage = _read_number(limit_file), _read_number(usage_file)
        if limit is not None:
            return max(0, min(free, limit - (usage or 0)))
    return free


def _system_available() -> int:
    try:
        with open("/proc/meminfo", encoding="ascii") as meminfo:
            for line in meminfo:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, AttributeError):  # no such query here: no limit known
        return 2**62


def _read_number(path: str) -> int | None:
    """The integer a cgroup file holds; None when absent, unreadable or unlimited (``max``)."""
    try:
        with open(path, encoding="ascii") as file:
            return int(file.read().strip())
    except (OSError, ValueError):
        return None


def memory_limit() -> tuple[int, str]:
    """Find the memory a request may use [bytes], and where the limit comes from.

    Returns
    -------
    limit : int
        The limit [bytes]: :data:`LIMIT_VARIABLE` when set, else :func:`available_memory`.
    source : str
        Where it comes from, in words, for messages.

    Raises
    ------
    InputError
        When :data:`LIMIT_VARIABLE` is set but malformed.

    Examples
    --------
    >>> import os
    >>> os.environ[LIMIT_VARIABLE] = "4G"
    >>> memory_limit()
    (4294967296, 'SUNWIND_MAX_MEMORY=4G')
    >>> del os.environ[LIMIT_VARIABLE]
    """
    setting = os.environ.get(LIMIT_VARIABLE)
    if setting is not None and setting.strip():
        return parse_size(setting), f"{LIMIT_VARIABLE}={setting.strip()}"
    return available_memory(), f"available memory; set {LIMIT_VARIABLE} to change it"


def human(nbytes: float) -> str:
    """Write a byte count in binary units, to three significant digits.

    Parameters
    ----------
    nbytes : float
        A number of bytes.

    Returns
    -------
    str
        E.g. ``"22.4 GiB"``.

    Examples
    --------
    >>> human(512), human(3 * 2**20), human(2.4e10)
    ('512 B', '3 MiB', '22.4 GiB')
    """
    for unit in ("B", "KiB", "MiB", "GiB", "TiB", "PiB"):
        if nbytes < 1000 or unit == "PiB":
            break
        nbytes /= 1024
    return f"{nbytes:.3g} {unit}"


def count(n: float) -> str:
    """Write a count to three significant digits, also a Python int past the largest float.

    Parameters
    ----------
    n : float or int
        The count.

    Returns
    -------
    str
        E.g. ``"1e+09"``.

    Examples
    --------
    >>> count(123456), count(10**400)
    ('1.23e+05', '~1e+400')
    """
    try:
        return f"{n:.3g}"
    except OverflowError:
        return f"~1e+{int(n.bit_length() * math.log10(2))}"


def require(nbytes: float, what: str, fix: str, parameters: tuple[str, ...] = ()) -> None:
    """Refuse a request whose estimated peak ``nbytes`` exceeds :func:`memory_limit`.

    Parameters
    ----------
    nbytes : float
        Estimated peak memory of the request's dominant arrays [bytes] (a Python number: sizes past
        int64 are fine).
    what : str
        What the memory is for, e.g. ``"1e+09 points per side x 12 sides"``.
    fix : str
        The remedy, e.g. ``"lower samples"``, naming the Python parameters of ``parameters``.
    parameters : tuple of str
        The parameters ``fix`` names, for :meth:`~sunwind.geometry.errors.SunwindError.renamed`.

    Raises
    ------
    InputError
        ``nbytes`` is above the limit, or ``SUNWIND_MAX_MEMORY`` is malformed.

    Examples
    --------
    >>> import os
    >>> os.environ[LIMIT_VARIABLE] = "1M"
    >>> require(1000, "a small array", "lower samples")
    >>> require(2**30, "1e+08 points", "lower samples", ("samples",))
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: not enough memory: needs ~1 GiB for 1e+08 points; limit 1 MiB ...
    >>> del os.environ[LIMIT_VARIABLE]
    """
    limit, source = memory_limit()
    if nbytes <= limit:
        return
    try:
        size = f"~{human(float(nbytes))}"
    except OverflowError:  # a Python int past the largest float
        size = "more than 1e308 B"
    raise InputError(
        f"not enough memory: needs {size} for {what}; limit {human(limit)} ({source})",
        hint=fix,
        parameters=parameters,
    )
