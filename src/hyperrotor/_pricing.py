r"""Priced work: the one place where a size-driven request is estimated and refused.

Every public entry point whose cost grows with a size the user chooses (a dimension
``N``, a degree ``l``, a representation's dimension, a number of output times or
bodies) calls :func:`check` with those sizes at its door, before any allocation or
loop::

    _pricing.check("spinor_rep", N=N)

:func:`check` evaluates the entry's cost model (:data:`MODELS`: bytes of working
memory, estimated single-core seconds, output bytes, dense dimensions, as functions of
the sizes) and compares every figure with its NAMED budget in :data:`hyperrotor.options`.
A request over a budget raises :class:`BudgetError` (a ``ValueError``) with one message
format::

    spinor_rep: the generators (dimension 2^30) would need ~3.9e+20 bytes (working memory),
    over the budget hr.options['max_memory_bytes'] = 4294967296; raise it with
    hr.options(max_memory_bytes=...)

A refusal that is not a cost model's (a number of bins, a step count, a fixed limit of a
constructor) is built by :func:`refuse`, which :func:`check` uses too: one format, one
exception type.

The central models live in :mod:`hyperrotor._cost_models` (registered when the package is
imported); an entry point's own module may register its model beside it (``@_pricing.model``).
The models describe the algorithms as they are implemented; the constants (bytes per
entry, seconds per elementary operation) were measured on the reference machine (2 cores)
by ``benchmarks/pricing.py``, which prints the estimate next to the measured time and peak
memory of each priced entry point (they agree within a factor ~3; docs/safety.md).

A budget is a number in :data:`hyperrotor.options`: ``max_memory_bytes`` and
``max_seconds`` (registered here), and the older ones that keep their meaning
(``max_output_bytes``, ``quantum_max_dense_dim``, ``sectors_dense_max_dim``, ...).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable

from ._options import options, register

__all__ = ["BudgetError", "Cost", "MODELS", "check", "estimate", "model", "refuse", "as_float"]


class BudgetError(ValueError):
    """A request whose estimated cost exceeds a budget of :data:`hyperrotor.options`.

    Raised before any work by :func:`hyperrotor._pricing.check`; the message names the
    entry point, the estimate, the budget (``hr.options['<key>']``) and how to raise it. Built by
    :func:`refuse`, it also carries them: ``what``, ``needed`` (in ``unit``), ``budget`` and ``option`` (the key).
    ``StepBudgetError`` (runs of :func:`hyperrotor.simulate`) is a subclass.
    """


register(
    "max_memory_bytes", 2**32,
    "Budget of every size-driven entry point (hyperrotor._pricing): largest working memory, in bytes, "
    "that one call may need, estimated from its sizes before any allocation (dense matrices of a "
    "representation, sparse generators of a tensor product or spinor representation, structure-constant "
    "tables of so(N), ...). 4 GiB by default: the test machine is shared, and a request that would need "
    "more is almost always a mistyped size (spinor_rep(60) would need ~1e20 bytes). Raise it with "
    "hr.options(max_memory_bytes=...).",
)
register(
    "max_seconds", 600.0,
    "Budget of every size-driven entry point (hyperrotor._pricing): longest single-core run time, in "
    "seconds, of one call, estimated from its sizes before any work (SymPy constructions, exact "
    "rational bases, dense diagonalizations, Freudenthal's recursion, output loops). The estimates are "
    "calibrated on the 2-core reference machine within a factor ~3 (benchmarks/pricing.py). Raise it with "
    "hr.options(max_seconds=...) for a long run you mean.",
)


@dataclass(frozen=True)
class Cost:
    """One figure of a cost model: ``amount`` (in ``unit``) of ``what``, checked against ``options[key]``."""

    what: str
    amount: float
    key: str
    unit: str


#: entry name -> (model, cheaper alternative or ""). A model maps the sizes to a tuple of Cost.
MODELS: dict[str, tuple[Callable[..., tuple[Cost, ...]], str]] = {}


def model(entry: str, alternative: str = "") -> Callable:
    """Register the cost model of ``entry`` (decorator); ``alternative`` is named in the refusal."""

    def deco(fn: Callable[..., tuple[Cost, ...]]) -> Callable[..., tuple[Cost, ...]]:
        MODELS[entry] = (fn, alternative)
        return fn

    return deco


def estimate(entry: str, **sizes: Any) -> tuple[Cost, ...]:
    """The figures of ``entry``'s cost model for ``sizes`` (no check; used by the benchmark)."""
    try:
        fn, _ = MODELS[entry]
    except KeyError:
        raise KeyError(f"no cost model for {entry!r}; known: {', '.join(sorted(MODELS))}") from None
    return fn(**sizes)


def check(entry: str, **sizes: Any) -> None:
    """Refuse ``entry`` with ``sizes`` (:class:`BudgetError`) if a figure of its cost model is over budget.

    Call it at the door of the entry point, before any allocation or loop. The sizes are
    plain numbers (Python ints may be arbitrarily large: the models compute in floats and
    an overflow counts as infinitely expensive).
    """
    fn, alternative = MODELS[entry]
    for c in fn(**sizes):
        if not c.amount <= options[c.key]:  # also refuses NaN and inf
            raise refuse(entry, c.what, c.amount, c.key, c.unit, alternative)


def refuse(entry: str, what: str, amount: float, key: str, unit: str, alternative: str = "", *,
           limit: Any = None, raise_with: str | None = None, cls: type = BudgetError, **attributes: Any) -> BudgetError:
    """The refusal of ``entry``: a :class:`BudgetError` with the one message format of the package.

    ``{entry}: {what} would need ~{amount}, over the budget hr.options['{key}'] = {limit};
    raise it with hr.options({key}=...)[ or {alternative}]``. Returned, not raised (``raise
    _pricing.refuse(...)``), so that a caller can add a cause.

    Parameters
    ----------
    entry : str
        The public entry point (``"lyapunov"``, ``"sample_spectrum"``, ...).
    what : str
        What would be built or run, naming the argument and the size that set it.
    amount, unit : float, str
        The estimate and its unit (``"bytes"``, ``"seconds"``, ``"dimension"``, ``"steps"``, ...).
    key : str
        The budget: a key of :data:`hyperrotor.options`, or (with ``limit`` and ``raise_with``)
        a fixed limit or an argument such as ``max_dim``.
    alternative : str, optional
        How to ask for less ("use method 'krylov'"), named after the way to raise the budget.
    limit : optional
        The budget's value (default ``options[key]``).
    raise_with : str, optional
        How to raise it (default ``hr.options(key=...)``).
    cls : type, optional
        :class:`BudgetError` or a subclass (``StepBudgetError``); ``attributes`` go to its constructor.
    """
    if limit is None:
        limit, budget = options[key], f"hr.options['{key}']"
    else:
        budget = key
    how = f"hr.options({key}=...)" if raise_with is None else raise_with
    tail = f" or {alternative}" if alternative else ""
    err = cls(f"{entry}: {what} would need ~{_amount(amount, unit)}, over the budget {budget} = {limit!r}; "
              f"raise it with {how}{tail}", **attributes)
    # the figures beside the text, for a caller that words the refusal its own way (the command line): they pickle
    # with the exception (its __dict__)
    err.what, err.unit = what, unit
    for name, value in (("needed", amount), ("budget", limit), ("option", key)):
        if getattr(err, name, None) is None:
            setattr(err, name, value)
    return err


def _amount(x: float, unit: str) -> str:
    x = as_float(x)  # (an exact int beyond the floats: a huge count)
    if not math.isfinite(x):
        return f"more than 1e308 ({unit})"
    if unit == "bytes":
        return f"{x:.3g} bytes ({x / 2**30:.3g} GiB)"
    if unit == "seconds":
        return f"{x:.3g} s of one core ({x / 3600:.3g} h)" if x >= 3600 else f"{x:.3g} s of one core"
    return f"{x:.6g} ({unit})"


def as_float(x: Any) -> float:
    """A size as a float (an int too large for a float is infinite)."""
    try:
        return float(x)
    except OverflowError:
        return math.inf
