"""What every subcommand of ``hyperrotor`` shares: the usage error, number checks, budgets, progress.

The subcommand modules (:mod:`hyperrotor.cli.demo`, ``.scene``, ``.verify``,
``.bench``) import from here, never from :mod:`hyperrotor.cli` itself (which
imports them to build its registry).
"""
from __future__ import annotations

import argparse
import math
import re
from typing import Callable

import numpy as np

from hyperrotor import _parse, _validate
from hyperrotor._options import options
from hyperrotor._parallel import progress_bar
from hyperrotor.cli._signals import bar_shown, checkpoint

__all__ = ["UsageError", "budget_message", "CLI_BUDGETS",
           "num", "nums", "usage", "MAX_MAGNITUDE", "bounded", "number", "integer", "number_list",
           "int_list", "choice_of", "byte_size", "size_text", "duration_text", "check_budget", "bar", "have_module",
           "have_matplotlib", "add_common", "check_common"]


class UsageError(ValueError):
    """A bad argument or output path: one line on stderr, exit status 2."""


def num(x, digits: int = 12) -> str:
    """A number as plain text with ``digits`` significant digits (``-0.33``, ``2``, ``1.5e-12``)."""
    x = float(x)
    return "0" if x == 0.0 else format(x, f".{digits}g")


def nums(values, digits: int = 12) -> str:
    """A list of numbers as plain text: ``[0, -0.33, 1.5]``."""
    return "[" + ", ".join(num(v, digits) for v in values) + "]"


def usage(fn, *a, **kw):
    """Call a ``_validate`` check; its ValueError/TypeError becomes a :class:`UsageError`."""
    try:
        return fn(*a, **kw)
    except (TypeError, ValueError) as err:
        raise UsageError(str(err)) from None


#: Largest magnitude of a number given on the command line (kappa, omega, sides): squares and
#: products of a few of them must stay far inside double precision.
MAX_MAGNITUDE = 1e100


def bounded(option: str, value: float) -> float:
    """A finite real number with ``|value| <= MAX_MAGNITUDE`` (else :class:`UsageError`)."""
    value = usage(_validate.real, option, value)
    if abs(value) > MAX_MAGNITUDE:
        raise UsageError(f"{option} must have magnitude <= {MAX_MAGNITUDE:g}, got {_validate.fmt(value)}")
    return value


def number(text, option: str, *, exact: bool = False):
    """A number given on the command line, read by the one parser of user text (:mod:`hyperrotor._parse`).

    ``text``: numbers, fractions, ``+ - * / **`` and parentheses (``1/2``,
    ``2.5e-3``, ``(3/4)**2``), nothing else: nothing is evaluated, sizes are
    bounded before any work. A number that is already parsed (an option's
    default) is passed through. Returns a float of magnitude at most
    :data:`MAX_MAGNITUDE`, or with ``exact`` a ``sympy.Rational``. Refusals are
    :class:`UsageError` naming ``option`` (exit status 2).
    """
    if isinstance(text, str):
        try:
            text = _parse.number(text, option, exact=exact)
        except (_parse.ParseError, TypeError) as err:
            raise UsageError(str(err)) from None
    bounded(option, float(text))
    return text


def integer(text, option: str, *, minimum: int | None = None, maximum: int | None = None) -> int:
    """An integer given on the command line, read by :mod:`hyperrotor._parse` (as :func:`number`), in range."""
    value = text
    if isinstance(text, str):
        try:
            value = _parse.integer(text, option)
        except (ValueError, TypeError) as err:  # (ParseError is a ValueError)
            raise UsageError(str(err)) from None
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) > MAX_MAGNITUDE:  # (1e400, 2**1000:
        raise UsageError(f"{option} must have magnitude <= {MAX_MAGNITUDE:g}, got an integer of "  # not 400 digits)
                         f"{len(str(abs(value)))} digits")
    return usage(_validate.integer, option, value, minimum=minimum, maximum=maximum)


#: the library's budget options and the command-line options that set them
CLI_BUDGETS = {"max_steps": "--max-steps", "max_output_bytes": "--max-memory", "max_memory_bytes": "--max-memory",
               "max_seconds": "--max-seconds"}


def budget_message(err: Exception, args: argparse.Namespace | None = None) -> str:
    """A library budget refusal worded with the command line's options: the advice to raise a Python option
    (``hr.options(...)``, ``simulate(..., max_steps=...)``) is replaced by the subcommand's own option, when it has
    one (``args``), else by "choose a smaller run"; a limit without an option is named as the library's limit."""
    text = str(err).split("; raise it with", 1)[0].split(" (raise it", 1)[0]
    flags = [f for key, f in CLI_BUDGETS.items()
             if key in text and (args is None or hasattr(args, f[2:].replace("-", "_")))]
    for key, flag in CLI_BUDGETS.items():
        if flag in flags:
            text = text.replace(f"hr.options['{key}']", flag).replace(f"budget {key} =", f"budget {flag} =")
    text = re.sub(r"hr\.options\['(\w+)'\]", r"the library's limit \1", text)
    return text + "; choose a smaller run" + (f" or raise {flags[0]}" if flags else "")


def number_list(text: str, option: str, count: int | None = None, *, positive: bool = False) -> np.ndarray:
    """Comma-separated numbers (each as :func:`number`; exactly ``count`` when given; ``> 0`` with ``positive``)."""
    arr = np.array([number(v, option) for v in text.split(",") if v.strip()], dtype=float)
    if count is not None and arr.size != count:
        raise UsageError(f"{option} needs {count} comma-separated numbers, got {arr.size} ({text!r})")
    bad = [float(v) for v in arr if positive and v <= 0]
    if bad:
        raise UsageError(f"{option} values must be > 0, got {_validate.fmt(bad)}")
    return arr


def int_list(text: str, option: str) -> list[int]:
    """Comma-separated integers (``1,2,3``), each as :func:`integer`."""
    return [integer(v, option) for v in text.split(",") if v.strip()]


def choice_of(allowed) -> Callable[[str], str]:
    """An argparse ``type=`` for ``choices=allowed`` matched ignoring case (``--method DOP853`` or ``dop853``).

    Returns the spelling of ``allowed``; other text is returned unchanged, so
    argparse refuses it with its "invalid choice" message listing ``allowed``.
    """
    def convert(text: str) -> str:
        try:
            return _validate.choice("value", text, tuple(allowed))
        except (TypeError, ValueError):
            return text

    return convert


_BYTE_UNITS = {"": 1, "K": 2**10, "M": 2**20, "G": 2**30, "T": 2**40}


def byte_size(text: str) -> int:
    """``--max-memory``: bytes, or a number with K, M, G or T (binary units), e.g. ``4G``."""
    m = re.fullmatch(r"\s*([0-9.]+(?:[eE][+-]?[0-9]+)?)\s*([KMGT]?)(?:i?B)?\s*", text, flags=re.I)
    if not m:
        raise argparse.ArgumentTypeError(f"expected a size such as 2G, 500M or 1000000, got {text!r}")
    value = float(m.group(1)) * _BYTE_UNITS[m.group(2).upper()]
    if not math.isfinite(value) or value < 1:  # (0.5 was a budget of 0 bytes)
        raise argparse.ArgumentTypeError(f"expected a size of at least one byte, got {text!r}")
    return int(value)


def size_text(n: float) -> str:
    """Bytes as text: ``8.0 TiB``, ``512 MiB``."""
    for unit, k in (("TiB", 40), ("GiB", 30), ("MiB", 20), ("KiB", 10)):
        if n >= 2**k:
            return f"{n / 2**k:.3g} {unit}"
    return f"{int(n)} bytes"


def duration_text(s: float) -> str:
    """Seconds as text: ``12 s``, ``3.5 min``, ``2 h``, ``4.1 days``."""
    if s >= 86400:
        return f"{s / 86400:.3g} days"
    if s >= 3600:
        return f"{s / 3600:.3g} h"
    if s >= 60:
        return f"{s / 60:.3g} min"
    return f"{s:.2g} s"


def check_budget(args: argparse.Namespace, what: str, seconds: float, memory: float | None = None,
                 hint: str = "") -> None:
    """Refuse a run whose estimated time or memory exceeds the budget (before any work)."""
    max_s = args.max_seconds if args.max_seconds is not None else float(options["cli_max_seconds"])
    max_m = getattr(args, "max_memory", None)
    max_m = max_m if max_m is not None else int(options["cli_max_memory"])
    tail = f"; {hint}" if hint else ""
    if memory is not None and memory > max_m:
        raise UsageError(f"{what} needs about {size_text(memory)} of memory, over the budget of {size_text(max_m)} "
                         f"(--max-memory, default hr.options['cli_max_memory']){tail}")
    if seconds > max_s:
        raise UsageError(f"{what} would take about {duration_text(seconds)}, over the budget of "
                         f"{duration_text(max_s)} (--max-seconds, default hr.options['cli_max_seconds']){tail}")


class _Steps:
    """Progress of a command: a bar (or none) whose every step is also a safe point for signals."""

    def __init__(self, pbar) -> None:
        self._bar = pbar
        bar_shown(pbar is not None)

    def update(self, n: int = 1) -> None:
        checkpoint()  # a signal deferred while numba compiled is acted on here
        if self._bar is not None:
            self._bar.update(n)

    def set_postfix_str(self, text: str) -> None:
        if self._bar is not None:
            self._bar.set_postfix_str(text)

    def __enter__(self) -> "_Steps":
        return self

    def __exit__(self, *exc) -> None:
        if self._bar is not None:
            self._bar.close()
            bar_shown(False)


def bar(args: argparse.Namespace, total: int, desc: str, unit: str) -> _Steps:
    """The package's progress bar on stderr (``--progress``/``--no-progress``, default on a terminal).

    Use as ``with bar(...) as steps: ... steps.update()``; each update is a
    safe point where a pending signal stops the command (:mod:`hyperrotor.cli._signals`).
    """
    return _Steps(progress_bar(args.progress, total, desc, unit=unit, leave=False))


def have_module(name: str) -> bool:
    """Whether the module ``name`` can be imported (matplotlib, plotly: the ``viz`` extra)."""
    import importlib.util

    return importlib.util.find_spec(name) is not None


def have_matplotlib() -> bool:
    """Whether matplotlib can be imported (the ``viz`` extra)."""
    return have_module("matplotlib")


def add_common(p: argparse.ArgumentParser, *, budget: bool = False, memory: bool = False, steps: str = "") -> None:
    """The options every subcommand has (--force, --progress, --debug) and the budget options.

    ``budget``: --max-seconds; ``memory``: --max-memory; ``steps`` (what integrates): --max-steps.
    """
    g = p.add_argument_group("behaviour")
    g.add_argument("--force", action="store_true",
                   help="replace existing output files (default: refuse and leave them as they are)")
    g.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress bars on stderr (default: only when stderr is a terminal)")
    g.add_argument("--debug", action="store_true", help="show the Python traceback of an error")
    if budget:
        g = p.add_argument_group("budget (checked against estimates before any work)")
        g.add_argument("--max-seconds", default=None, metavar="S",
                       help="refuse a run estimated to take longer (default hr.options['cli_max_seconds'] "
                            f"= {options['cli_max_seconds']:g} s)")
    if memory:
        g.add_argument("--max-memory", type=byte_size, default=None, metavar="SIZE",
                       help="refuse a run estimated to need more memory, e.g. 4G (default "
                            f"hr.options['cli_max_memory'] = {size_text(options['cli_max_memory'])})")
    if steps:
        g.add_argument("--max-steps", default=None, metavar="N",
                       help=f"refuse {steps} estimated to need more integration steps "
                            f"(default hr.options['max_steps'] = {options['max_steps']:.3g})")


def check_common(args: argparse.Namespace) -> None:
    """Check the common options (a positive --max-seconds, stored back as a float)."""
    if getattr(args, "max_seconds", None) is not None:
        args.max_seconds = usage(_validate.positive, "--max-seconds", number(args.max_seconds, "--max-seconds"))
