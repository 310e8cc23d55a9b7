"""What every subcommand of ``hyperrotor`` shares: the usage error, number checks, budgets, progress.

The subcommand modules (:mod:`hyperrotor.cli.demo`, ``.scene``, ``.verify``,
``.bench``) import from here, never from :mod:`hyperrotor.cli` itself (which
imports them to build its registry).
"""
from __future__ import annotations

import argparse
import math
import re
import warnings
from typing import Any, Callable

import numpy as np

from hyperrotor import _parse, _validate
from hyperrotor._options import options
from hyperrotor._parallel import progress_bar
from hyperrotor.cli._signals import bar_shown, checkpoint

__all__ = ["UsageError", "budget_message", "CLI_BUDGETS",
           "num", "nums", "usage", "MAX_MAGNITUDE", "bounded", "number", "integer", "number_list",
           "int_list", "check_invariants_fit", "choice_of", "byte_size", "size_text", "duration_text", "check_budget",
           "bar", "have_module", "have_matplotlib", "add_common", "check_common"]


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
    :class:`UsageError` naming ``option`` (exit status 2); a value that double
    precision cannot hold (``1e400``, or ``1e-400``, which would round to 0) is
    named as typed.
    """
    if not isinstance(text, str):
        bounded(option, float(text))
        return text
    try:
        value = _parse.number(text, option, exact=exact)
    except (_parse.ParseError, TypeError) as err:
        raise UsageError(str(err)) from None
    typed = text.strip()
    if exact and abs(value) > MAX_MAGNITUDE:  # (compared exactly: 1e400 is no float)
        raise UsageError(f"{option} must have magnitude <= {MAX_MAGNITUDE:g}, got {typed}")
    f = float(value)
    if f == 0.0 and not _is_zero(text, option, value, exact):
        raise UsageError(f"{option} {typed} is too close to 0 for double precision: it would round to 0 (a nonzero "
                         "magnitude must be at least about 5e-324)")
    bounded(option, f)
    return value


def _is_zero(text: str, option: str, value, exact: bool) -> bool:
    """Whether the number ``text`` (read as ``value``, a float 0.0 unless ``exact``) is exactly zero."""
    if exact:
        return value == 0
    if len(text) <= _parse._DECIMAL_LENGTH and _parse._DECIMAL.fullmatch(text):
        return True  # (a short plain decimal, exponent of two digits at most, is 0.0 only when it is 0: no SymPy)
    try:
        return bool(_parse.expression(text, option, symbols=False).is_zero)
    except (_parse.ParseError, TypeError) as err:  # (it was read once already)
        raise UsageError(str(err)) from None


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
#: what each budget counts, for a refusal whose subcommand has no option for it
_BUDGET_WORDS = {"max_steps": "integration steps", "max_output_bytes": "output memory",
                 "max_memory_bytes": "memory", "max_seconds": "time"}


def budget_message(err: Exception, args: argparse.Namespace | None = None) -> str:
    """A library budget refusal worded with the command line's options: the advice to raise a Python option
    (``hr.options(...)``, ``simulate(..., max_steps=...)``) is replaced by the subcommand's own option, when it has
    one (``args``), else by "choose a smaller run"; a limit without an option is named as the library's limit.
    No budget keyword of the library (``max_steps``) is left in the text. A run beyond every budget ("more than any
    budget ... allows") is not told to raise one."""
    text = str(err).split("; raise it with", 1)[0].split(" (raise it", 1)[0]
    flags = [f for key, f in CLI_BUDGETS.items()
             if key in text and (args is None or hasattr(args, f[2:].replace("-", "_")))]
    beyond = "more than any budget" in text
    for key, flag in CLI_BUDGETS.items():
        if flag in flags:
            text = (text.replace(f"hr.options['{key}']", flag).replace(f"budget {key} =", f"budget {flag} =")
                    .replace(f"any budget {key} allows", f"any {flag} value allows"))
        else:
            text = text.replace(f"any budget {key} allows", f"any budget of {_BUDGET_WORDS[key]} allows")
    text = re.sub(r"hr\.options\['(\w+)'\]", r"the library's limit \1", text)
    for key, flag in CLI_BUDGETS.items():  # a keyword left anywhere else: the option, or what it counts
        text = re.sub(rf"(?<!limit )(?<![\w-]){key}(?!\w)", flag if flag in flags else _BUDGET_WORDS[key], text)
    if beyond:
        return text + "; choose a smaller run"
    return text + "; choose a smaller run" + (f" or raise {flags[0]}" if flags else "")


def unreachable(err: Exception, what: str, advice: str) -> RuntimeError:
    """The command's words for a step control that cannot reach its accuracy (``UnreachableAccuracyError``): the
    library's reason without its advice (a larger ``rtol``, which no command takes), then ``advice`` (options of the
    command). Raise it ``from None``: the work failed (exit status 1)."""
    return RuntimeError(f"{what} cannot be integrated to its accuracy: {str(err).split('. Ask for')[0]}; {advice}")


def _fields(text: str, option: str, what: str) -> list[str]:
    """The comma-separated fields of ``text`` (none for an empty text); an empty field is refused, naming it."""
    if not text.strip():
        return []
    fields = text.split(",")
    for k, v in enumerate(fields, start=1):
        if not v.strip():
            raise UsageError(f"{option} {text!r}: field {k} of {len(fields)} is empty; give comma-separated "
                             f"{what} with nothing empty between the commas")
    return fields


def number_list(text: str, option: str, count: int | None = None, *, positive: bool = False) -> np.ndarray:
    """Comma-separated numbers (each as :func:`number`; exactly ``count`` when given; ``> 0`` with ``positive``)."""
    arr = np.array([number(v, option) for v in _fields(text, option, "numbers")], dtype=float)
    if count is not None and arr.size != count:
        raise UsageError(f"{option} needs {count} comma-separated numbers, got {arr.size} ({text!r})")
    bad = [float(v) for v in arr if positive and v <= 0]
    if bad:
        raise UsageError(f"{option} values must be > 0, got {_validate.fmt(bad)}")
    return arr


def int_list(text: str, option: str) -> list[int]:
    """Comma-separated integers (``1,2,3``), each as :func:`integer`; an empty text is no integer."""
    return [integer(v, option) for v in _fields(text, option, "integers")]


def check_invariants_fit(option: str, omega: np.ndarray, invariants: Callable[[np.ndarray], Any], *,
                         body_options: str = "") -> None:
    """Refuse (:class:`UsageError`, before any work) an angular velocity whose invariants overflow double precision.

    ``invariants(w)``: the library's computation of the invariants the command shows (e.g. ``RigidBody.energy``
    and ``.casimirs``, whose own check raises ``ValueError`` "values too large ... overflows double precision";
    a result that is not finite counts alike). Every value of ``option`` may be within :data:`MAX_MAGNITUDE` while
    the Casimirs, of degree up to N in ``L = I omega``, are not: the message names ``option`` and the largest
    ``max|omega|`` (a power of ten) that fits for this body, found with the same computation; when none does,
    the body's options ``body_options`` (``--kappa``) are named.
    """
    def fits(w: np.ndarray) -> bool:
        try:
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore")
                values = invariants(w)
        except ValueError:
            return False
        values = values if isinstance(values, tuple) else (values,)
        return all(np.all(np.isfinite(np.asarray(v, dtype=float))) for v in values)

    omega = np.asarray(omega, dtype=float)
    peak = float(np.max(np.abs(omega))) if omega.size else 0.0
    if peak == 0.0 or fits(omega):
        return
    unit = omega / peak
    low, high = -300, max(math.ceil(math.log10(peak)), -299)  # 10**low * unit fits (checked), 10**high does not
    if not fits(unit * 10.0**low):
        raise UsageError(f"{option} with this body: its invariants (energy, Casimirs) overflow double precision for "
                         f"every --omega" + (f"; choose a {body_options} of smaller magnitude" if body_options else ""))
    while high - low > 1:
        mid = (low + high) // 2
        low, high = (mid, high) if fits(unit * 10.0**mid) else (low, mid)
    raise UsageError(f"{option} values too large for this body, max |{option[2:]}| = {_validate.fmt(peak)}: its "
                     f"invariants (energy, Casimirs, products of up to N components of L = I omega) would overflow "
                     "double precision; allowed for this body and these proportions: "
                     f"max |{option[2:]}| <= about 1e{low}")


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
#: a size: the number (read by :func:`number`) and an optional binary unit, K, M, G or T, with or without
#: B or iB (or B alone), any case
_SIZE = re.compile(r"(?P<number>.*?)\s*(?:(?P<unit>[KMGT])(?:i?B)?|B)?\s*", re.IGNORECASE | re.DOTALL)


def byte_size(text, option: str = "--max-memory") -> int:
    """``--max-memory``: bytes, or a number with K, M, G or T (binary units), e.g. ``4G``, ``500MiB``, ``2**31``.

    The number is read as every number option is (:func:`number`: the one parser, magnitude at most
    :data:`MAX_MAGNITUDE`); the result must be at least one byte. Refusals are :class:`UsageError` naming
    ``option``.
    """
    if not isinstance(text, str):  # (already read)
        return int(text)
    m = _SIZE.fullmatch(text)
    unit = (m.group("unit") or "").upper()
    try:
        value = number(m.group("number"), option)
    except UsageError as err:
        msg = str(err)
        if "cannot be read" in msg:
            msg += "; a size is a number with an optional unit K, M, G or T (binary), e.g. 2G, 500M or 2**31"
        if m.group("number").strip() != text.strip():  # (the number part is named as typed, with its unit)
            msg = f"{option} {text!r}: {msg}"
        raise UsageError(msg) from None
    size = value * _BYTE_UNITS[unit]
    if not size >= 1:  # (0.5 was a budget of 0 bytes)
        raise UsageError(f"{option} must be a size of at least one byte, got {text!r}")
    return int(size)


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
        needed, limit = duration_text(seconds), duration_text(max_s)
        if needed == limit:  # (2.92 s over 2.9 s: "about 2.9 s, over the budget of 2.9 s")
            needed, limit = f"{seconds:.6g} s", f"{max_s:.6g} s"
        raise UsageError(f"{what} would take about {needed}, over the budget of {limit} (--max-seconds, default "
                         f"hr.options['cli_max_seconds']){tail}")


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
        g.add_argument("--max-memory", default=None, metavar="SIZE",
                       help="refuse a run estimated to need more memory: bytes or a number with K, M, G or T "
                            "(binary units), e.g. 4G, 500M, 2**31 (default "
                            f"hr.options['cli_max_memory'] = {size_text(options['cli_max_memory'])})")
    if steps:
        g.add_argument("--max-steps", default=None, metavar="N",
                       help=f"refuse {steps} estimated to need more integration steps "
                            f"(default hr.options['max_steps'] = {options['max_steps']:.3g})")


def check_common(args: argparse.Namespace) -> None:
    """Check the common options (a positive --max-seconds, stored back as a float; --max-memory, stored back as
    bytes, an int)."""
    if getattr(args, "max_seconds", None) is not None:
        args.max_seconds = usage(_validate.positive, "--max-seconds", number(args.max_seconds, "--max-seconds"))
    if getattr(args, "max_memory", None) is not None:
        args.max_memory = byte_size(args.max_memory, "--max-memory")
