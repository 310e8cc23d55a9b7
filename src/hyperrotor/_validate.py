"""The package's input checks: one place, one message style.

Every public entry point of :mod:`hyperrotor` (classical and quantum) checks
its arguments with these functions, so a given kind of input is accepted,
normalised and refused the same way everywhere. A refusal is a ``TypeError``
(wrong kind of object) or a ``ValueError`` (right kind, bad value) whose
message names the argument, shows the offending value as a plain number
(``2.0``, never ``np.float64(2.0)``) and says what is allowed.

Nothing here imports SymPy, QuTiP or matplotlib: objects from those libraries
are recognised by duck typing (``.moments``, ``.full()``), so validating an
input never pays for a heavy import.
"""
from __future__ import annotations

import math
from functools import lru_cache
from collections.abc import Mapping
from numbers import Integral, Real
from typing import Any, Sequence

import numpy as np

from . import _parse

__all__ = [
    "fmt",
    "integer",
    "sequence",
    "dimension",
    "real",
    "positive",
    "tolerance",
    "hbar",
    "flag",
    "rng",
    "choice",
    "convention",
    "time_grid",
    "finite_array",
    "components",
    "plane",
    "moments",
    "axis_signs",
    "ket",
    "form",
    "form_hbar",
    "unknown_option",
    "numeric_input",
    "plane_table",
    "dimension_from_count",
    "representation",
    "real_array",
]

#: The allowed values of every ``form=`` keyword (Hermitian vs anti-Hermitian generators, docs/conventions.md).
FORMS = ("antihermitian", "hermitian")

#: The allowed values of every ``convention=`` keyword for matrices (see :mod:`hyperrotor.conventions`).
CONVENTIONS = ("paper", "standard")


# ----------------------------------------------------------------------------
# message formatting
# ----------------------------------------------------------------------------
def fmt(value: Any, _depth: int = 0) -> str:
    """Plain text of ``value`` for an error message.

    NumPy scalars print as Python numbers (``2.0``, not ``np.float64(2.0)``),
    floats with ``repr`` precision, containers element by element (past 12 entries
    the first 6 and their count; nested deeper than 4 levels, or holding themselves,
    by their size); integers beyond 2^128 by their order of magnitude; anything else falls back to ``repr``
    (shortened past 80 characters).
    """
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, bool) or value is None:
        return repr(value)
    if isinstance(value, Integral):
        v = int(value)
        if abs(v).bit_length() <= 128:
            return str(v)
        # (hundreds of digits, or more than str() converts: its order of magnitude)
        return f"{'-' if v < 0 else ''}~1e+{math.floor(math.log10(abs(v)))} (an integer)"
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, complex):
        return repr(value)
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, np.ndarray):
        if value.size <= 12:
            return fmt(value.tolist(), _depth)
        return f"<array of shape {value.shape}, dtype {value.dtype}>"
    if isinstance(value, (list, tuple)):
        if _depth >= 4:
            return f"<{type(value).__name__} of {len(value)} entries>"
        shown = [fmt(v, _depth + 1) for v in value[:6 if len(value) > 12 else 12]]
        if len(value) > 12:
            shown.append(f"... ({len(value)} entries)")
        inner = ", ".join(shown)
        if isinstance(value, list):
            return f"[{inner}]"
        return f"({inner},)" if len(value) == 1 else f"({inner})"
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


def _is_real_scalar(value: Any) -> bool:
    return not isinstance(value, bool) and isinstance(value, (Real, np.floating, np.integer))


# ----------------------------------------------------------------------------
# scalars
# ----------------------------------------------------------------------------
def integer(name: str, value: Any, *, minimum: int | None = None, maximum: int | None = None) -> int:
    """Return ``value`` as ``int``; refuse booleans, floats and out-of-range values.

    SymPy integers are accepted (they are ``numbers.Integral`` subclasses only by
    registration, so they are recognised by ``is_Integer``).
    """
    if isinstance(value, bool) or not (isinstance(value, (Integral, np.integer)) or getattr(value, "is_Integer", False)):
        rng_txt = _range_text(minimum, maximum)
        raise TypeError(f"{name} must be an integer{rng_txt}, got {fmt(value)} of type {type(value).__name__}")
    value = int(value)
    if (minimum is not None and value < minimum) or (maximum is not None and value > maximum):
        raise ValueError(f"{name} must be an integer{_range_text(minimum, maximum)}, got {value}")
    return value


def whole_number(name: str, value: Any, *, minimum: int | None = None, maximum: int | None = None) -> int:
    """:func:`integer`, also accepting a float with an integral value (``1e5``, as options of other packages such as
    QuTiP's ``nsteps`` are often written); booleans, fractions, infinities and NaN are refused."""
    if isinstance(value, (float, np.floating)) and math.isfinite(value) and float(value).is_integer():
        value = int(value)
    return integer(name, value, minimum=minimum, maximum=maximum)


def sequence(name: str, value: Any, what: str) -> tuple:
    """The entries of ``value`` as a tuple: a list, tuple, array or other iterable, not text and not a single
    number (``TypeError`` naming ``name`` and what its entries must be, ``what``)."""
    if not isinstance(value, (str, bytes)):
        try:
            return tuple(value)
        except TypeError:  # (not iterable: a number, None, a 0-d array)
            pass
    raise TypeError(f"{name} must be a sequence of {what}, got {fmt(value)} of type {type(value).__name__}")


def mapping(name: str, value: Any, example: str = "") -> dict:
    """A mapping of option names (strings) to values, as a new ``dict`` (``None``: an empty one)."""
    if value is None:
        return {}
    if not isinstance(value, Mapping) or not all(isinstance(k, str) for k in value):
        raise TypeError(f"{name} must be a mapping of option names to values{example}, got {fmt(value)} of type "
                        f"{type(value).__name__}")
    return dict(value)


def _range_text(minimum: int | None, maximum: int | None) -> str:
    if minimum is not None and maximum is not None:
        return f" in {minimum}..{maximum}"
    if minimum is not None:
        return f" >= {minimum}"
    if maximum is not None:
        return f" <= {maximum}"
    return ""


def dimension(N: Any, *, minimum: int = 2, name: str = "N") -> int:
    """The space dimension ``N`` of so(N), an integer ``>= minimum`` and at most ``options["max_dimension"]``.

    The budget (1000 by default) turns a huge ``N``, which would hang or exhaust memory in
    the plane tables, into a message.
    """
    from hyperrotor._options import options

    from hyperrotor._pricing import refuse

    N = integer(name, N, minimum=minimum)
    if N > options["max_dimension"]:
        raise refuse(f"so({N})", f"{name} = {N} (so({N}) has {N * (N - 1) // 2} planes)", N, "max_dimension",
                     "dimension", f"ask for a smaller {name}")
    return N


def _float(name: str, value: Any) -> float:
    """``float(value)`` of a real scalar; an exact number beyond the floats (``10**400``, a huge Fraction) is
    refused by name (``ValueError``, as ``inf`` is) instead of Python's ``OverflowError``."""
    try:
        return float(value)
    except OverflowError:
        raise ValueError(f"{name} must be finite, got {fmt(value)}, beyond double precision (about 1.8e308)") from None


def real(name: str, value: Any, *, allow_none: bool = False) -> float | None:
    """A finite real number as ``float`` (``None`` passes through when ``allow_none``)."""
    if value is None and allow_none:
        return None
    if not _is_real_scalar(value):
        raise TypeError(f"{name} must be a real number, got {fmt(value)} of type {type(value).__name__}")
    value = _float(name, value)
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {fmt(value)}")
    return value


def positive(name: str, value: Any, *, allow_none: bool = False, allow_zero: bool = False) -> float | None:
    """A finite real number ``> 0`` (``>= 0`` with ``allow_zero``) as ``float``."""
    if value is None and allow_none:
        return None
    if not _is_real_scalar(value):
        raise TypeError(f"{name} must be a positive real number, got {fmt(value)} of type {type(value).__name__}")
    value = _float(name, value)
    ok = value >= 0 if allow_zero else value > 0
    if not (math.isfinite(value) and ok):
        raise ValueError(f"{name} must be finite and {'>= 0' if allow_zero else '> 0'}, got {fmt(value)}")
    return value


def tolerance(name: str, value: Any, *, allow_none: bool = False, allow_zero: bool = False) -> float | None:
    """A relative tolerance: a finite number with ``0 < value < 1`` (``0 <= value < 1`` with ``allow_zero``)
    as ``float`` (``None`` passes through when ``allow_none``). A relative tolerance of 1 or more accepts
    any value, so it is refused with the allowed range."""
    if value is None and allow_none:
        return None
    low = f"0 {'<=' if allow_zero else '<'} {name} < 1"
    if not _is_real_scalar(value):
        raise TypeError(f"{name} must be a relative tolerance, a real number with {low}, got {fmt(value)} "
                        f"of type {type(value).__name__}")
    x = _float(name, value)
    if not (math.isfinite(x) and (x >= 0 if allow_zero else x > 0) and x < 1):
        raise ValueError(f"{name} must be a relative tolerance with {low}, got {fmt(value)}")
    return x


def hbar(value: Any) -> float:
    """The reduced Planck constant: a finite number ``> 0`` (the package's one default is ``hbar=1``)."""
    return positive("hbar", value)


def client(value: Any, name: str = "client") -> Any:
    """``None``, or a dask ``Client`` that is not closed (duck-typed: ``submit`` and ``gather``); a closed one is
    refused at the door (a review: an ensemble's in-process step check ran 5 min before dask's ClosedClientError,
    which named no argument)."""
    if value is None:
        return None
    if not (callable(getattr(value, "submit", None)) and callable(getattr(value, "gather", None))):
        raise TypeError(f"{name} must be a dask.distributed.Client (or None for an in-process run), got "
                        f"{fmt(value)} of type {type(value).__name__}")
    status = getattr(value, "status", "running")
    if isinstance(status, str) and status in ("closing", "closed"):
        raise ValueError(f"{name} is a dask client that is {status}: pass a running dask.distributed.Client, or None "
                         f"for an in-process run")
    return value


def flag(name: str, value: Any, *, allow_none: bool = False) -> bool | None:
    """A switch: ``True`` or ``False`` (NumPy booleans too; ``None`` passes through when ``allow_none``).

    Integers, strings and other truthy objects are refused: ``progress="no"`` or
    ``complete=0`` would otherwise act by their truth value, not by what they say.
    """
    if value is None and allow_none:
        return None
    if not isinstance(value, (bool, np.bool_)):
        allowed = "True, False or None" if allow_none else "True or False"
        raise TypeError(f"{name} must be {allowed}, got {fmt(value)} of type {type(value).__name__}")
    return bool(value)


def rng(value: Any = None) -> np.random.Generator:
    """A :class:`numpy.random.Generator` from ``rng=``: ``None`` (fresh entropy), an integer seed,
    a :class:`numpy.random.SeedSequence` or a ``Generator`` (used as is), as in SPEC 7."""
    if isinstance(value, np.random.Generator):
        return value
    if value is None or isinstance(value, np.random.SeedSequence):
        return np.random.default_rng(value)
    if isinstance(value, bool) or not isinstance(value, (Integral, np.integer)):
        raise TypeError(
            f"rng must be None, an integer seed, a SeedSequence or a numpy.random.Generator, "
            f"got {fmt(value)} of type {type(value).__name__}"
        )
    if int(value) < 0:
        raise ValueError(f"rng seed must be a non-negative integer, got {int(value)}")
    return np.random.default_rng(int(value))


def choice(name: str, value: Any, allowed: Sequence[str], *, case_insensitive: bool = True) -> str:
    """One of ``allowed`` (matched ignoring case when ``case_insensitive``), returned as spelled there."""
    if not isinstance(value, str):
        raise TypeError(f"{name} must be one of {', '.join(map(repr, allowed))}, got {fmt(value)}")
    for a in allowed:
        if value == a or (case_insensitive and value.lower() == a.lower()):
            return a
    raise ValueError(f"unknown {name} {value!r}; allowed: {', '.join(map(repr, allowed))}")


def convention(value: Any) -> str:
    """A matrix sign convention, one of :data:`CONVENTIONS` (``"paper"`` or ``"standard"``)."""
    return choice("convention", value, CONVENTIONS)


def form(value: Any) -> str:
    """Which generators: ``"antihermitian"`` (real antisymmetric X, eq. 142) or
    ``"hermitian"`` (-i hbar X, eq. 141), one of :data:`FORMS`."""
    return choice("form", value, FORMS)


def form_hbar(form_value: Any, hbar_value: Any, *, exact: bool = False) -> tuple[str, Any]:
    """Check ``form=`` and the ``hbar=`` that goes with it; returns ``(form, hbar)``.

    The package has one default, ``hbar=1`` (docs/conventions.md). ``hbar`` only
    applies to ``form="hermitian"`` (L = -i hbar X); with ``form="antihermitian"``
    any value other than 1 is refused (``ValueError``), since it would be silently
    ignored, and ``(form, 1)`` is returned.

    With ``form="hermitian"``: ``exact=False`` (numeric callers) returns
    :func:`hbar` of the value (a finite float > 0); ``exact=True`` (the symbolic
    layer) returns a SymPy object made by :func:`hyperrotor._parse.to_sympy`
    with text refused (``TypeError``: write ``sympy.Symbol("hbar", positive=True)``),
    refusing values known not to be positive; the exact 1 stays ``Integer(1)``.
    """
    f = form(form_value)
    if f == "antihermitian":
        if isinstance(hbar_value, (str, bool)) or not _equals_one(hbar_value):
            raise ValueError(
                f'hbar={fmt(hbar_value)} applies to form="hermitian" only (-i hbar X); '
                f'pass form="hermitian" for the Hermitian generators (docs/conventions.md)'
            )
        return f, 1
    if not exact:
        return f, hbar(hbar_value)
    from . import _parse

    h = _parse.to_sympy(hbar_value, "hbar", text=False)
    if h.is_positive is False:
        raise ValueError(f"hbar must be > 0, got {h}")
    return f, h


def _equals_one(value: Any) -> bool:
    try:
        return bool(value == 1)
    except Exception:  # an object whose comparison fails is not 1
        return False


def representation(name: str, value: Any, *, dim: int | None = None, of: str = "H") -> Any:
    """A representation of so(N): anything with ``.N``, ``.dim`` and ``.generators()`` (duck typing).

    With ``dim``, its dimension must be ``dim``, the dimension of the operator named ``of``.
    """
    if not (hasattr(value, "N") and hasattr(value, "dim") and callable(getattr(value, "generators", None))):
        raise TypeError(
            f"{name} must be a hyperrotor.quantum.Representation (e.g. irrep(5, (2, 1))), "
            f"got {fmt(value)} of type {type(value).__name__}"
        )
    if dim is not None and value.dim != dim:
        raise ValueError(f"{of} has dimension {dim} but {name} has dimension {value.dim}")
    return value


def as_array(name: str, value: Any, *, what: str = "numeric array") -> np.ndarray:
    """``np.asarray(value)`` (text as an object array, for the caller's dtype test), with ragged nesting
    (``[0.1, [1.0]]``) refused as a ``TypeError`` naming ``name`` instead of NumPy's "inhomogeneous shape"."""
    if isinstance(value, (str, bytes)):
        return np.asarray(value, dtype=object)
    try:
        return np.asarray(value)
    except (TypeError, ValueError):  # (ragged nesting)
        raise TypeError(f"{name} must be a {what}, got {fmt(value)} of type {type(value).__name__}") from None


def real_array(name: str, value: Any, *, ndim: int | tuple[int, ...] | None = None) -> np.ndarray:
    """A finite real float array; complex input is refused (no silent loss of the imaginary part)."""
    numeric_input(name, value)  # before np.asarray, which would drop a mask
    arr = as_array(name, value, what="real numeric array")
    if arr.dtype.kind not in "biuf":
        raise TypeError(f"{name} must be a real numeric array, got {fmt(value)} (dtype {arr.dtype})")
    return finite_array(name, arr, ndim=ndim)


def unknown_option(where: str, key: Any, allowed: Sequence[str]) -> None:
    """Raise the package's one exception for an unknown option name (``UnknownOptionError``).

    ``where`` names the function or table (``"evolve options"``), ``allowed`` the valid keys.
    """
    from ._options import UnknownOptionError

    names = ", ".join(map(repr, sorted(allowed))) or "none"
    raise UnknownOptionError(f"{where}: unknown option {fmt(key)}; allowed: {names}")


# ----------------------------------------------------------------------------
# arrays
# ----------------------------------------------------------------------------
#: NumPy dtype kinds that are never numbers here: bool, datetime64, timedelta64, bytes, str, void.
_NON_NUMERIC_KINDS = {"b": "booleans", "M": "datetime64 values", "m": "timedelta64 values",
                      "S": "bytes", "U": "text", "V": "raw (void) data"}


def numeric_input(name: str, value: Any) -> None:
    """Refuse what NumPy would silently turn into numbers: text (``"1.5"``), booleans, datetime64
    and timedelta64 values, and masked arrays (``np.asarray`` drops the mask), wherever they appear:
    the value itself, its dtype, or an entry of a (nested) list, tuple or object array, including
    arrays inside lists (``[np.array([True, False]), 1.0]``, ``np.array([True, 1.0], dtype=object)``).

    Raises ``TypeError`` naming the argument; anything else passes (and is converted by the caller).
    A plain numeric ndarray is judged by its dtype alone (no scan of its entries).
    """
    if isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be numeric, got text {fmt(value)} (text is never read as a number here)")
    if isinstance(value, np.ma.MaskedArray):
        raise TypeError(
            f"{name} must be a plain array, got a masked array (its mask would be ignored); "
            f"pass value.filled(...) or value.compressed()"
        )
    if isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be numeric, got the boolean {fmt(value)}")
    kind = getattr(getattr(value, "dtype", None), "kind", None)
    if kind is None and isinstance(value, (list, tuple)):
        try:
            kind = np.asarray(value).dtype.kind
        except (TypeError, ValueError):  # ragged: scanned below, else the caller's conversion reports it
            kind = None
    # (a list NumPy reads as text may hold one text entry among numbers: walked first, to name it)
    if kind in _NON_NUMERIC_KINDS and not (kind in "US" and isinstance(value, (list, tuple))):
        raise TypeError(f"{name} must be numeric, got {_NON_NUMERIC_KINDS[kind]} {fmt(value)}")
    # ([True, 2, 3] is an int array, [np.array([True]), 2.0] a float one, an object array keeps True as is)
    if isinstance(value, (list, tuple)) or (kind == "O" and isinstance(value, np.ndarray)):
        bad = _non_numeric_entry(value)
        if bad is not None:
            what, path = bad
            raise TypeError(f"{name} must be numeric, got {what} in {fmt(value)} ({name}{path})")


#: entry types :func:`_non_numeric_entry` passes at once (exact types: bool, a subclass of int, is not among them)
_PLAIN_NUMBERS = frozenset({float, int, complex, np.float64, np.float32, np.float16, np.longdouble, np.int64, np.int32,
                            np.int16, np.int8, np.uint64, np.uint32, np.uint16, np.uint8, np.complex128, np.complex64})


def _non_numeric_entry(value: list | tuple | np.ndarray) -> tuple[str, str] | None:
    """The first entry (in reading order) that :func:`numeric_input` refuses in a (nested) list, tuple or object
    array: what it is, for the message (``"a boolean entry"``), and where (``"[2][0] = True"``), or ``None``. Arrays
    inside are judged by their dtype (object arrays are scanned); each container is visited once (a list holding
    itself ends the walk); iterative (no recursion limit)."""

    def entries(seq):
        return enumerate(seq.flat if isinstance(seq, np.ndarray) else seq)

    def where(seq, i):  # (the index as written, built only for an entry that is not a plain number)
        if isinstance(seq, np.ndarray) and seq.ndim > 1:
            return f"[{', '.join(map(str, np.unravel_index(i, seq.shape)))}]"
        return f"[{i}]"

    stack, seen = [("", value, entries(value))], {id(value)}
    while stack:
        path, seq, todo = stack[-1]
        for i, x in todo:
            if type(x) in _PLAIN_NUMBERS:  # (the common entries: one test)
                continue
            here = path + where(seq, i)
            if isinstance(x, (bool, np.bool_)):
                return "a boolean entry", f"{here} = {fmt(x)}"
            if isinstance(x, (str, bytes)):
                return "text", f"{here} = {fmt(x)}; text is never read as a number here"
            if isinstance(x, np.ma.MaskedArray):
                return "a masked array entry", f"{here}: its mask would be ignored"
            if isinstance(x, (np.ndarray, np.generic)):
                k = x.dtype.kind
                if k == "b":
                    return "a boolean entry", f"{here} = {fmt(x)}"
                if k in _NON_NUMERIC_KINDS:
                    return f"an entry of {_NON_NUMERIC_KINDS[k]}", f"{here} = {fmt(x)}"
                if k != "O" or not isinstance(x, np.ndarray):
                    continue
            elif not isinstance(x, (list, tuple)):
                continue
            if id(x) not in seen:  # a container: walked next, then the rest of this one
                seen.add(id(x))
                stack.append((here, x, entries(x)))
                break
        else:
            stack.pop()
    return None


def finite_array(name: str, value: Any, *, ndim: int | tuple[int, ...] | None = None, dtype: Any = float) -> np.ndarray:
    """``value`` as a finite ndarray of ``dtype`` (and of ``ndim`` dimensions when given).

    For a real ``dtype``, complex input is refused (NumPy would drop the imaginary part with a
    ``ComplexWarning``); text, booleans, datetime/timedelta values and masked arrays are refused
    (:func:`numeric_input`)."""
    if value is None:
        raise TypeError(f"{name} must be a numeric array, got None")
    numeric_input(name, value)
    try:
        if np.dtype(dtype).kind in "biuf" and np.iscomplexobj(value):
            raise TypeError(f"{name} must be real, got complex values {fmt(value)}")
        arr = np.asarray(value, dtype=dtype)
    except (TypeError, ValueError) as exc:
        if str(exc).startswith(f"{name} must be real"):
            raise
        raise TypeError(f"{name} must be a numeric array, got {fmt(value)} of type {type(value).__name__}") from None
    if ndim is not None:
        allowed = (ndim,) if isinstance(ndim, int) else tuple(ndim)
        if arr.ndim not in allowed:
            raise ValueError(
                f"{name} must have {' or '.join(map(str, allowed))} dimension(s), got shape {arr.shape}"
            )
    if not np.all(np.isfinite(arr)):
        bad = np.argwhere(~np.isfinite(arr))[0]
        idx = tuple(int(b) for b in bad)
        raise ValueError(f"{name} must be finite; {name}{list(idx)} = {fmt(arr[idx])}")
    return arr


def orthogonal_matrix(name: str, value: Any, N: int, *, batched: bool = False) -> np.ndarray:
    """``value`` as a finite real orthogonal ``N x N`` matrix (a batch of them, shape ``batch + (N, N)``, when
    ``batched``): max|T^T T - 1| <= 1e-8, else ``ValueError`` (an attitude; text, booleans, complex and
    non-finite entries are refused by :func:`finite_array`)."""
    T = finite_array(name, value)
    if T.ndim < 2 or T.shape[-2:] != (N, N) or (T.ndim != 2 and not batched):
        raise ValueError(f"{name} must have shape ({N}, {N}){f' or batch + ({N}, {N})' if batched else ''}, "
                         f"got {T.shape}")
    dev = float(np.abs(np.swapaxes(T, -1, -2) @ T - np.eye(N)).max()) if T.size else 0.0
    if dev > 1e-8:
        raise ValueError(f"{name} must be orthogonal (max|T^T T - 1| = {dev:.3g})")
    return T


def exact_or_float_array(name: str, value: Any, *, what: str = "numeric array") -> np.ndarray:
    """``value`` as a finite numeric array that keeps exact integers exact: integer input as ``int64``
    (``uint64`` as ``float64``), so that negating or adding entries cannot wrap around (``-np.uint8(1)``
    is 255; an ``int8`` ``-128`` stays ``-128``), real and complex floats as they are, finite. Text, booleans,
    dates, masked and ragged input are refused with ``name`` (:func:`numeric_input`)."""
    numeric_input(name, value)
    arr = as_array(name, value, what=what)
    if arr.dtype.kind not in "iufc":
        raise TypeError(f"{name} must be a {what}, got {fmt(value)} of dtype {arr.dtype}")
    if arr.dtype.kind in "iu":
        return arr.astype(np.float64 if arr.dtype == np.uint64 else np.int64)
    if not np.all(np.isfinite(arr)):
        idx = tuple(int(b) for b in np.argwhere(~np.isfinite(arr))[0])
        raise ValueError(f"{name} must be finite; {name}{list(idx)} = {fmt(arr[idx])}")
    return arr


def components(name: str, value: Any, n: int, *, what: str = "plane components", batch: bool = True) -> np.ndarray:
    """A finite float array of shape batch + ``(n,)`` (one vector of ``n`` components per member).

    For ensembles of initial conditions such as ``omega0``: the last axis holds the ``n``
    components (``what`` names them in the message), leading axes are the ensemble
    (``batch=False``: one vector, shape ``(n,)``).
    """
    arr = finite_array(name, value)
    if arr.ndim == 0 or arr.shape[-1] != n or (not batch and arr.ndim != 1):
        shapes = f"({n},) or batch + ({n},)" if batch else f"({n},)"
        raise ValueError(f"{name} must have shape {shapes} ({n} {what}), got shape {arr.shape}")
    return arr


def time_count(t: Any, *, name: str = "t") -> int:
    """The number of entries of the output times ``t`` before any copy of them (a huge grid is priced by its size
    first), or the ``TypeError`` of :func:`time_grid` for input that is no array (a ragged list)."""
    try:
        return int(np.size(t)) if isinstance(t, (np.ndarray, list, tuple)) else 1
    except (TypeError, ValueError):  # (ragged nesting: NumPy's "inhomogeneous shape")
        raise TypeError(f"{name} must be a 1-D array of real output times, got {fmt(t)}") from None


def time_grid(t: Any, *, name: str = "t", allow_decreasing: bool = True) -> np.ndarray:
    """Output times: a finite, strictly monotonic 1-D float array with at least one entry.

    Time may run backwards (a strictly decreasing grid) unless ``allow_decreasing``
    is ``False``. The returned array is a fresh float64 copy. Text, booleans, datetime/timedelta
    values and masked arrays are refused (:func:`numeric_input`).
    """
    numeric_input(name, t)
    try:
        if np.iscomplexobj(t):
            raise TypeError
        arr = np.array(t, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a 1-D array of real output times, got {fmt(t)}") from None
    if arr.ndim != 1 or arr.size < 1:
        raise ValueError(f"{name} must be a 1-D array of output times (at least one), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        k = int(np.argmax(~np.isfinite(arr)))
        raise ValueError(f"{name} must be finite; {name}[{k}] = {fmt(arr[k])}")
    if arr.size > 1:
        d = np.diff(arr)
        increasing = d[0] > 0
        if not allow_decreasing and not increasing:
            raise ValueError(f"{name} must be strictly increasing; {name}[0] = {fmt(arr[0])} >= {name}[1] = {fmt(arr[1])}")
        bad = np.nonzero(d <= 0 if increasing else d >= 0)[0]
        if bad.size:
            k = int(bad[0])
            word = "increasing" if increasing else "decreasing"
            raise ValueError(
                f"{name} must be strictly monotonic (here {word}, as set by its first two entries); "
                f"{name}[{k}] = {fmt(arr[k])}, {name}[{k + 1}] = {fmt(arr[k + 1])}"
            )
    return arr


# ----------------------------------------------------------------------------
# so(N) labels and bodies
# ----------------------------------------------------------------------------
def plane(value: Any, N: int | None) -> tuple[int, int]:
    """A rotation plane of so(N): a 1-based pair ``(i, j)`` with ``1 <= i < j <= N``.

    Accepts a pair of integers or a digit string such as ``"12"`` (N < 10) or ``"1,10"``.
    ``N=None``: N is not known yet (a label read before the dimension): only ``1 <= i < j``.
    """
    N = dimension(N) if N is not None else None
    bound = "N" if N is None else str(N)
    pair: Any = value
    if isinstance(value, str):
        text = value.strip()
        pair = text.split(",") if "," in text else (list(text) if len(text) == 2 else None)
    if isinstance(pair, (tuple, list)) and any(isinstance(v, (bool, np.bool_)) or v is None for v in pair):
        raise TypeError(f"a plane is a pair (i, j) of integers with 1 <= i < j <= {bound}, got {fmt(value)} "
                        f"(booleans and None are not plane indices)")
    try:
        if pair is None or len(pair) != 2:
            raise ValueError
        # (text through the one parser: int() also read "1_0" and non-ASCII digits)
        i, j = (integer("plane index", v) if not isinstance(v, str) else _parse.integer(v.strip(), "plane index")
                for v in pair)
    except (TypeError, ValueError):
        raise ValueError(f"a plane is a pair (i, j) of integers with 1 <= i < j <= {bound}, got {fmt(value)}") from None
    if not (1 <= i < j and (N is None or j <= N)):
        where = "" if N is None else f" for N = {N}"
        raise ValueError(f"unknown plane {fmt(value)}{where}: planes are pairs (i, j) with 1 <= i < j <= {bound}")
    return i, j


@lru_cache(maxsize=None)
def plane_table(N: int) -> tuple[tuple[int, int], ...]:
    """The planes ``(i, j)``, ``1 <= i < j <= N``, in lexicographic (paper) order.

    ``N`` is trusted (checked by the caller with :func:`dimension`); the public
    door is :func:`hyperrotor.planes`.
    """
    return tuple((i, j) for i in range(1, N + 1) for j in range(i + 1, N + 1))


def dimension_from_count(count: int, *, name: str = "count", what: str = "plane components") -> int:
    """``N`` from a number ``count = N(N-1)/2`` of plane components (or moments).

    Raises ``ValueError`` naming ``name`` and the nearby allowed counts when
    ``count`` is not of that form (1, 3, 6, 10, 15, ... for N = 2, 3, 4, 5, 6, ...).
    """
    N = int(round((1 + math.sqrt(1 + 8 * count)) / 2))
    if N < 2 or N * (N - 1) // 2 != count:
        lo = max(N - 1, 2)
        allowed = ", ".join(str(n * (n - 1) // 2) for n in range(lo, lo + 3))
        raise ValueError(
            f"{name} has {count} {what}, which matches no so(N): the count must be N(N-1)/2 "
            f"for an integer N >= 2 (nearby allowed counts: {allowed})"
        )
    return N


def moments(value: Any, N: int | None = None, *, name: str = "inertia") -> np.ndarray:
    """Plane moments ``I_ij`` (float64, plane order) of so(N), finite and positive.

    Accepts a :class:`~hyperrotor.RigidBody` (anything with ``.inertia.moments``),
    an :class:`~hyperrotor.Inertia` (anything with ``.moments``), a mapping
    ``{(i, j): I_ij}`` naming every plane once (needs ``N`` or infers it from the
    largest index), or a 1-D sequence of ``N(N-1)/2`` numbers in plane order.
    With ``N`` given, a mismatch is an error naming both dimensions.
    """
    src = value
    if hasattr(value, "inertia") and hasattr(value.inertia, "moments"):
        src = value.inertia.moments
    elif hasattr(value, "moments") and not isinstance(value, Mapping):
        src = value.moments
    if isinstance(src, Mapping):
        try:
            if N is None:  # infer N from the largest index named (validated against it just below)
                labels = [plane(p, None) for p in src]
                n = max(j for _, j in labels)
            else:
                n = N
            labels = [plane(p, n) for p in src]
        except ValueError as exc:  # name the argument: the keys must be planes
            raise ValueError(f"{name}: a mapping must have planes (i, j) as keys; {exc}") from None
        missing = [p for p in plane_table(n) if p not in labels]
        if missing:
            raise ValueError(
                f"{name} mapping misses the planes {', '.join(f'{i}{j}' for i, j in missing[:6])}"
                f"{' ...' if len(missing) > 6 else ''}; so({n}) needs a moment for each of its {n * (n - 1) // 2} planes"
            )
        if len(set(labels)) != len(labels):
            raise ValueError(f"{name} mapping names a plane twice")
        by_plane = dict(zip(labels, src.values()))
        src = [by_plane[p] for p in plane_table(n)]
    if src is None or isinstance(src, (str, bytes)):
        raise TypeError(f"{name} must be an Inertia, a RigidBody, a mapping plane -> moment or a sequence of moments, got {fmt(src)}")
    numeric_input(name, src)  # booleans, datetime64/timedelta64 values and masked arrays are not moments
    try:
        is_complex = np.iscomplexobj(src)
        arr = None if is_complex else np.asarray(src, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(
            f"{name} must be an Inertia, a RigidBody, a mapping plane -> moment or a sequence of moments, "
            f"got {type(value).__name__}"
        ) from None
    if is_complex:  # NumPy would drop the imaginary part with a ComplexWarning
        raise TypeError(f"{name}: moments of inertia must be real, got complex values {fmt(src)}")
    if arr.ndim != 1:
        raise ValueError(f"{name}: plane moments must be a 1-D sequence of N(N-1)/2 values, got shape {arr.shape}")
    n = dimension_from_count(arr.size, name=name, what="plane moments")
    if N is not None and n != N:
        raise ValueError(
            f"{name} has {arr.size} plane moments (so({n})) but so({N}) needs {N * (N - 1) // 2}; "
            f"they must act on the same dimension"
        )
    ok = np.isfinite(arr) & (arr > 0)
    if not ok.all():  # (one vectorised test: a loop over the planes costs ~0.3 s at N = 1000)
        table = plane_table(n)
        bad = {f"I_{table[k][0]}{table[k][1]}": float(arr[k]) for k in np.flatnonzero(~ok)}
        raise ValueError(f"{name}: moments of inertia must be finite and > 0, got {fmt(bad)}")
    return arr


def axis_signs(N: int, convention: str, axes: Sequence[int] | None = None) -> np.ndarray:
    """Diagonal of ``S`` with ``X_paper = S X_standard S`` (eq. 21): ``(-1)^a`` per axis.

    ``axes`` are the original 1-based axis labels of the body's ``N`` axes (a body
    reduced by :meth:`~hyperrotor.RigidBody.lock` keeps its labels, so its signs
    are those of the full body, not of ``1..N``). Ones for ``"standard"``.
    """
    if choice("convention", convention, CONVENTIONS) == "standard":
        return np.ones(N)
    labels = tuple(range(1, N + 1)) if axes is None else tuple(int(a) for a in axes)
    if len(labels) != N:
        raise ValueError(f"axes {fmt(labels)} must name exactly N = {N} axes")
    return np.array([(-1.0) ** a for a in labels])


def ket(name: str, value: Any, dim: int, *, of: str, columns: bool = False) -> np.ndarray:
    """A state vector as a finite complex 1-D array of length ``dim``.

    Accepts a ket ``qutip.Qobj`` (recognised by ``.isket``/``.full()``, so QuTiP is not
    imported here), a 1-D array or a ``(dim, 1)`` column. ``of`` names what fixes ``dim``
    in the message (``"H"``, ``"the representation"``). With ``columns``, a ``(dim, k)`` matrix of
    ``k`` states is returned as it is (a ``(dim, 1)`` column too).
    """
    if hasattr(value, "isket") and hasattr(value, "full"):
        if not value.isket:
            raise ValueError(f"{name} must be a ket, got a Qobj of type {value.type!r}")
        vec = value.full().ravel()
    else:
        if not isinstance(value, (str, bytes)):
            numeric_input(name, value)  # booleans and masked arrays (np.asarray drops the mask) are not states
        vec = as_array(name, value, what="ket Qobj or a numeric vector")
        if vec.dtype.kind not in "biufc":
            raise TypeError(f"{name} must be a ket Qobj or a numeric vector, got {fmt(value)}")
        if vec.ndim == 2 and vec.shape[1] == 1 and not columns:
            vec = vec[:, 0]
        if vec.ndim != 1 and not (columns and vec.ndim == 2):
            raise ValueError(f"{name} must be a vector (ket) of length {dim}"
                             + (f" or a ({dim}, k) matrix of k of them" if columns else "")
                             + f", got shape {vec.shape}")
    if vec.shape[0] != dim:
        raise ValueError(f"{name} has dimension {vec.shape[0]} but {of} has dimension {dim}")
    if not np.all(np.isfinite(vec)):
        raise ValueError(f"{name} must be finite, got non-finite amplitudes")
    return vec.astype(complex)
