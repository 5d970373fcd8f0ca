"""What every fuzzed run of the command line and the library must do, and the values the
fuzzers draw from.

A run of ``archquake.cli.main(argv)`` in this process ends in one of three ways
(:func:`check_run`): a result (status 0) whose ``--json`` output parses as strict JSON with
finite numbers only, and whose text never says ``nan`` or ``inf``; an error (status 2) that
is one line ``archquake: error: ...`` naming an option or a file; or argparse's own refusal of
a command line that does not parse (status 2, its usage and one error line). Never a traceback,
and never longer than :data:`EXAMPLE_SECONDS` (:func:`time_limit`).
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import re
import signal
import string

from hypothesis import strategies as st

from archquake.cli import main

EXAMPLE_SECONDS = 120.0
"""Longest a fuzzed example may run [s] (a command that hangs fails the property); generous
for a shared machine: each runs in well under a second on an idle one."""


class TooLong(Exception):
    """An example ran longer than its limit."""


@contextlib.contextmanager
def time_limit(seconds: float = EXAMPLE_SECONDS):
    """Raise :class:`TooLong` in the block after ``seconds`` (SIGALRM; the main thread)."""
    def expire(signum, frame):
        raise TooLong(f"the example ran longer than {seconds:g} s")

    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def run_cli(argv: list[str], seconds: float = EXAMPLE_SECONDS) -> tuple[object, str, str]:
    """``(status, stdout, stderr)`` of ``main(argv)`` run here; status ``("argparse", code)``
    when argparse exits."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), time_limit(seconds):
        try:
            status = main(argv)
        except SystemExit as exc:
            status = ("argparse", exc.code)
    return status, out.getvalue(), err.getvalue()


def _refuse(name):
    raise AssertionError(f"{name} in the JSON output")


def finite_json(text: str):
    """``text`` as strict JSON whose numbers are all finite (``1e400`` parses as inf)."""
    value = json.loads(text, parse_constant=_refuse)

    def walk(v, where="$"):
        if isinstance(v, float):
            assert math.isfinite(v), f"{where} = {v!r}"
        elif isinstance(v, dict):
            for k, item in v.items():
                walk(item, f"{where}.{k}")
        elif isinstance(v, list):
            for i, item in enumerate(v):
                walk(item, f"{where}[{i}]")

    walk(value)
    return value


_NOT_A_NUMBER = re.compile(r"(?<![\w.])-?(nan|inf|infinity)(?![\w])", re.IGNORECASE)
_PROGRESS = re.compile(r"\d+%\|")


def _lines(err: str) -> list[str]:
    """The lines of stderr without progress bars."""
    lines = []
    for line in err.replace("\r", "\n").splitlines():
        if line.strip() and not _PROGRESS.search(line):
            lines.append(line)
    return lines


def check_run(argv: list[str], status, out: str, err: str, *, names=()) -> str:
    """Assert the contract of the module docstring for one run; return ``"ok"``, ``"error"``
    or ``"usage"``. ``names``: words of which an error must name one (the options and files
    of ``argv``)."""
    assert "Traceback" not in err and "Traceback" not in out, (argv, err[-2000:])
    lines = _lines(err)
    others = [line for line in lines if not line.startswith("archquake: warning:")]
    if isinstance(status, tuple):  # argparse refused the command line
        assert status[1] in (0, 2), (argv, status, err)
        if status[1] == 2:
            assert others and others[-1].startswith("archquake") and "error:" in others[-1], \
                (argv, err)
        return "usage"
    if status == 0:
        assert not [line for line in others if "error" in line.lower()], (argv, err)
        if "--json" in argv:
            finite_json(out)
        else:
            assert not _NOT_A_NUMBER.search(out), (argv, out)
        return "ok"
    assert status == 2, (argv, status, err)
    assert len(others) == 1 and others[0].startswith("archquake: error: "), (argv, err)
    message = others[0]
    if names:
        assert any(name in message for name in names), (argv, message)
    return "error"


# ------------------------------------------------------------------------------ values

HOSTILE_TEXT = ["", " ", "nan", "NaN", "inf", "-inf", "1e400", "-1e400", "1e-400", "1_0",
                "0x10", "1e", "--", "-", "１", "½", "0.3:1:0.1", "1,2,3", "1:0:1", "1:2:0",
                "9" * 400, "\x00", "é", "None", "true", "[1]", "1 2"]
"""Option values no one should give, and some one might."""


def numbers(low: float, high: float):
    """Text of numbers around ``[low, high]``: inside it, at and beyond its ends, zero,
    negative, huge, tiny, non-finite, and hostile text."""
    inside = st.floats(low, high, allow_nan=False, allow_infinity=False)
    edges = st.sampled_from([low, high, 0.0, -low, -high, 2 * high, low / 2, 1e-300, 1e300,
                             -1.0, 1e-9])
    wild = st.floats(allow_nan=True, allow_infinity=True)
    return st.one_of(inside.map(repr), edges.map(repr), wild.map(repr),
                     st.integers(-10**9, 10**9).map(str), st.sampled_from(HOSTILE_TEXT))


def integers_text(low: int, high: int):
    """Text of integers around ``[low, high]``, and hostile text."""
    return st.one_of(st.integers(low, high).map(str),
                     st.sampled_from([low - 1, high + 1, 0, -1, 10**12]).map(str),
                     st.floats(allow_nan=True).map(repr), st.sampled_from(HOSTILE_TEXT))


def words(choices):
    """One of ``choices`` or something near it."""
    return st.one_of(st.sampled_from(list(choices)), st.sampled_from(HOSTILE_TEXT),
                     st.text(string.ascii_letters + "-_", max_size=12))


def options(table: dict) -> st.SearchStrategy[list[str]]:
    """A command line's options: a subset of ``table`` (option -> strategy of its text, or
    None for a flag), each drawn once, in a drawn order."""
    @st.composite
    def draw(d):
        chosen = d(st.lists(st.sampled_from(sorted(table)), unique=True,
                            max_size=min(6, len(table))))
        argv = []
        for option in chosen:
            strategy = table[option]
            argv.append(option)
            if strategy is not None:
                argv.append(d(strategy))
        return argv

    return draw()
