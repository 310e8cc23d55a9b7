r"""Level statistics: spacing ratios, unfolded spacing distributions and their random-matrix references.

Use them on the levels of **one symmetry sector** (:func:`~hyperrotor.quantum.sectors.sector_spectra`):
levels of different sectors do not repel, and a superposition of :math:`k`
independent sectors looks Poissonian whatever each sector does.

Spacing ratio (no unfolding)
----------------------------
With the spacings :math:`s_n = E_{n+1} - E_n` of the sorted levels,

.. math:: \tilde r_n = \frac{\min(s_n, s_{n-1})}{\max(s_n, s_{n-1})} \in [0, 1],

(Oganesyan & Huse 2007; Atas, Bogomolny, Giraud & Roux, PRL 110, 084101 (2013)).
The ratio does not depend on the local density of states, so no unfolding is
needed. Reference means :data:`R_MEAN`: Poisson :math:`2\ln 2 - 1 = 0.38629`,
GOE 0.5307, GUE 0.5996 (large-matrix values of Atas et al., Table I), and the
3x3 surmise :math:`P(r) = \frac{1}{Z_\beta}\frac{(r + r^2)^\beta}{(1 + r + r^2)^{1 + 3\beta/2}}`
(:func:`ratio_density`, :math:`Z_1 = 8/27`, :math:`Z_2 = 4\pi/(81\sqrt3)`), whose means
are :math:`4 - 2\sqrt3 = 0.5359` and :math:`2\sqrt3/\pi - 1/2 = 0.6027`.

Spacing distribution (with unfolding)
-------------------------------------
:func:`unfold` maps the levels through a smooth fit of the staircase
:math:`\mathcal N(E) = \#\{E_n \le E\}` (a polynomial of low degree in the
rescaled energy, least squares), so that the unfolded levels have unit mean
spacing; :func:`spacing_distribution` histograms the unfolded spacings. References
(:func:`spacing_density`): Poisson :math:`e^{-s}`, and the Wigner surmises
GOE :math:`\frac{\pi}{2} s\, e^{-\pi s^2/4}`, GUE :math:`\frac{32}{\pi^2} s^2 e^{-4 s^2/\pi}`.

Validation: :func:`sample_spectrum` draws Poisson, GOE and GUE spectra (the
tests check :data:`R_MEAN` within a tolerance set by the sample size).
"""
from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.integrate import trapezoid  # numpy's own is numpy >= 2 only

from .. import _pricing, _validate
from .._equality import fields_equal
from .._options import options
from .._parallel import interruptible
from .._pricing import refuse
from .._warn import warn

__all__ = [
    "ENSEMBLES",
    "R_MEAN",
    "R_SURMISE_MEAN",
    "spacing_ratios",
    "spacing_ratio",
    "ratio_density",
    "unfold",
    "spacings",
    "spacing_density",
    "SpacingDistribution",
    "spacing_distribution",
    "sample_spectrum",
]

#: A spacing at most this times max|E| is zero: far above the round-off splitting of a degenerate level by
#: eigh (~1e-15 * dim * max|E|), far below a physical spacing (a Poisson spectrum of 10^6 levels has one
#: this small with probability ~1e-6)
_ZERO_SPACING_RTOL = 1e-12
#: Names of the reference ensembles.
ENSEMBLES = ("poisson", "goe", "gue")
#: Mean spacing ratio :math:`\langle\tilde r\rangle` of large matrices (Atas et al. 2013, Table I).
R_MEAN = {"poisson": 2 * math.log(2) - 1, "goe": 0.5307, "gue": 0.5996}
#: Mean of the 3x3 surmise :func:`ratio_density` (exact).
R_SURMISE_MEAN = {"poisson": 2 * math.log(2) - 1, "goe": 4 - 2 * math.sqrt(3), "gue": 2 * math.sqrt(3) / math.pi - 0.5}


def _levels(levels: Any, minimum: int) -> np.ndarray:
    E = _validate.finite_array("levels", levels, ndim=1)
    if E.size < minimum:
        raise ValueError(f"levels needs at least {minimum} values, got {E.size}")
    return np.sort(E)


def _ensemble(ensemble: Any) -> str:
    return _validate.choice("ensemble", ensemble, ENSEMBLES)


def _points(name: str, x: Any) -> np.ndarray:
    """Where a density is evaluated: finite reals of any shape (a scalar gives a 0-d array)."""
    return _validate.finite_array(name, x)


# ----------------------------------------------------------------------------
# spacing ratios
# ----------------------------------------------------------------------------
def spacing_ratios(levels: Any) -> np.ndarray:
    r"""The ratios :math:`\tilde r_n = \min(s_n, s_{n-1})/\max(s_n, s_{n-1})` of consecutive spacings.

    Parameters
    ----------
    levels : 1-D array_like
        Energies of one symmetry sector (sorted here), at least 3.

    Returns
    -------
    ndarray
        ``len(levels) - 2`` values in ``[0, 1]``, except that a triple with both
        spacings exactly zero (a degenerate level counted three times) has no
        ratio and is left out.
    """
    E = _levels(levels, 3)
    s = np.diff(E)
    a, b = s[1:], s[:-1]
    hi = np.maximum(a, b)
    ok = hi > 0
    return np.minimum(a, b)[ok] / hi[ok]


def spacing_ratio(levels: Any, *, return_error: bool = False):
    r"""Mean spacing ratio :math:`\langle\tilde r\rangle` (Atas et al., PRL 110, 084101 (2013)).

    Parameters
    ----------
    levels : 1-D array_like
        Energies of one symmetry sector, at least 3.
    return_error : bool, keyword-only
        Also return the standard error of the mean, ``std(r) / sqrt(n / 2)``: the
        effective sample is halved because neighbouring ratios share a spacing
        (their correlation makes the naive ``std/sqrt(n)`` too small).

    Returns
    -------
    float, or (float, float)
        Compare with :data:`R_MEAN`: Poisson 0.3863, GOE 0.5307, GUE 0.5996.

    Raises
    ------
    ValueError
        When a quarter or more of the spacings vanish (at most ``1e-12 * max|E|``:
        exact repeats, or the round-off splitting of a degenerate level by ``eigh``,
        ~``1e-15 * dim * max|E|``): forced degeneracies
        (e.g. the multiplets of a spinor irrep, or several sectors' levels merged)
        would pull the mean towards 0; all of them: one degenerate level, whose
        round-off splitting has no statistics. Fewer vanishing spacings give a
        ``RuntimeWarning`` (accidental degeneracies: each makes a ratio 0).

    Examples
    --------
    >>> round(spacing_ratio(sample_spectrum("poisson", 20000, rng=1)), 2)
    0.39
    """
    return_error = _validate.flag("return_error", return_error)
    _check_degeneracies(levels)
    r = spacing_ratios(levels)
    if not r.size:
        raise ValueError("levels has no spacing ratio: every three consecutive levels coincide (all spacings are zero)")
    mean = float(r.mean())
    if not return_error:
        return mean
    err = float(r.std(ddof=1) / math.sqrt(max(r.size / 2, 1))) if r.size > 1 else float("inf")
    return mean, err


def _check_degeneracies(levels: Any, effect: str = "each gives a spacing ratio of 0") -> int:
    """Refuse (a quarter or more) or warn about vanishing spacings (see :func:`spacing_ratio`); ``effect``: what
    each does to the statistic of the caller. Returns how many vanish."""
    E = _levels(levels, 3)
    tol = _ZERO_SPACING_RTOL * float(np.abs(E).max())
    zero = int(np.count_nonzero(np.diff(E) <= tol))
    n = E.size - 1
    if not zero:
        return 0
    if zero == n:  # (returned silently before: a degenerate sector's round-off splitting gave <r> = 0.23, a review)
        how = ("all equal" if E[0] == E[-1] else
               f"one degenerate level, split only by round-off (all {n} spacings <= 1e-12 * max|E| = {tol:.2e})")
        raise ValueError(f"the {E.size} levels are {how}: no level statistics (e.g. a sector of the spherical top); "
                         f"pass the levels of a sector whose levels are distinct")
    text = (f"{zero} of the {n} spacings of levels vanish (<= 1e-12 * max|E| = {tol:.2e}), "
            f"and {effect}")
    if 4 * zero >= n:
        raise ValueError(f"{text}: forced degeneracies? Pass the levels of one symmetry sector "
                         f"(sector_spectra; a spinor irrep's multiplets count once there) or distinct levels "
                         f"(spectrum(H).levels)")
    warn(f"{text} (accidental degeneracies?)", RuntimeWarning)
    return zero


def ratio_density(r: Any, ensemble: str) -> np.ndarray:
    r"""Density of :math:`\tilde r \in [0, 1]`: Poisson :math:`2/(1+r)^2`, GOE/GUE the surmise of Atas et al.

    :math:`P(\tilde r) = 2 P_W(\tilde r)` with
    :math:`P_W(r) = \frac{1}{Z_\beta}\frac{(r + r^2)^\beta}{(1 + r + r^2)^{1 + 3\beta/2}}`,
    :math:`\beta = 1` (GOE, :math:`Z_1 = 8/27`), :math:`\beta = 2` (GUE,
    :math:`Z_2 = 4\pi/(81\sqrt3)`). Each integrates to 1 on ``[0, 1]`` and is 0 outside
    (``r`` may be any finite array or number).
    """
    ens = _ensemble(ensemble)
    r = _points("r", r)
    inside = (r >= 0) & (r <= 1)
    x = np.clip(r, 0.0, 1.0)
    if ens == "poisson":
        dens = 2.0 / (1.0 + x) ** 2
    else:
        beta = 1 if ens == "goe" else 2
        Z = 8.0 / 27.0 if beta == 1 else 4.0 * math.pi / (81.0 * math.sqrt(3.0))
        dens = 2.0 / Z * (x + x * x) ** beta / (1.0 + x + x * x) ** (1.0 + 1.5 * beta)
    return np.where(inside, dens, 0.0)[()]  # a number for a number


# ----------------------------------------------------------------------------
# unfolding and the spacing distribution
# ----------------------------------------------------------------------------
def unfold(levels: Any, *, degree: int = 7) -> np.ndarray:
    r"""Unfolded levels :math:`x_n = \bar{\mathcal N}(E_n)`: a smooth staircase fit, unit mean spacing.

    Parameters
    ----------
    levels : 1-D array_like
        At least ``degree + 2`` energies (sorted here).
    degree : int, default 7
        Degree of the least-squares polynomial fit of the staircase
        :math:`\mathcal N(E_n) = n + 1/2` in the energy rescaled to ``[-1, 1]``
        (Chebyshev basis, well conditioned). Low enough not to follow the
        fluctuations (which are what is measured), high enough for the density's
        shape; check the result with :func:`spacings` (mean 1 by construction of
        the returned values, see there).

    Returns
    -------
    ndarray
        The smooth staircase at each level, sorted.

    Raises
    ------
    ValueError
        As :func:`spacing_ratio`, when a quarter or more of the spacings vanish (all of them: one degenerate
        level split by round-off); fewer give a ``RuntimeWarning``.
    """
    degree = _validate.integer("degree", degree, minimum=1, maximum=50)
    E = _levels(levels, degree + 2)
    # (as spacing_ratio; equal levels are refused there, so hi > lo below)
    distinct = E.size - _check_degeneracies(E, "each gives an unfolded spacing of 0")
    lo, hi = E[0], E[-1]
    if distinct <= degree:
        raise ValueError(f"levels has {distinct} distinct values; a staircase fit of degree {degree} needs at "
                         f"least {degree + 1} (lower degree=)")
    half = 0.5 * hi - 0.5 * lo  # halves first: no overflow for levels near the float range
    x = np.clip((E - (0.5 * lo + 0.5 * hi)) / half, -1.0, 1.0)
    n = np.arange(E.size) + 0.5
    fit = np.polynomial.chebyshev.Chebyshev.fit(x, n, degree, domain=[-1, 1])
    return np.sort(fit(x))


def spacings(levels: Any, *, degree: int = 7, unfolded: bool = False) -> np.ndarray:
    r"""Nearest-neighbour spacings of the unfolded levels, normalized to mean 1.

    ``unfolded=True`` takes ``levels`` as already unfolded (only normalizes).
    """
    degree = _validate.integer("degree", degree, minimum=1, maximum=50)
    x = np.sort(_validate.finite_array("levels", levels, ndim=1)) if _validate.flag("unfolded", unfolded) else unfold(levels, degree=degree)
    if x.size < 2:
        raise ValueError(f"levels needs at least 2 values, got {x.size}")
    s = np.diff(x)
    m = s.mean()
    if not m > 0:
        raise ValueError("all levels coincide: no spacing to normalize")
    return s / m


def spacing_density(s: Any, ensemble: str) -> np.ndarray:
    r"""Reference spacing densities: Poisson :math:`e^{-s}`, Wigner surmises for GOE and GUE (unit mean).

    ``s`` may be any finite array or number; the densities are 0 for ``s < 0``.
    """
    ens = _ensemble(ensemble)
    s = _points("s", s)
    x = np.clip(s, 0.0, 1e3)  # every density is 0.0 in double precision beyond s = 745 (no inf * 0 for huge s)
    if ens == "poisson":
        dens = np.exp(-x)
    elif ens == "goe":
        dens = 0.5 * math.pi * x * np.exp(-0.25 * math.pi * x * x)
    else:
        dens = 32.0 / math.pi**2 * x * x * np.exp(-4.0 * x * x / math.pi)
    return np.where(s >= 0, dens, 0.0)[()]  # a number for a number


@dataclass(frozen=True)
class SpacingDistribution:
    """Histogram of unfolded spacings (:func:`spacing_distribution`).

    Attributes
    ----------
    edges : ndarray
        Bin edges (``len(density) + 1``).
    density : ndarray
        Normalized histogram (integrates to 1 over the bins).
    counts : ndarray of int
        Spacings per bin (the statistical error of ``density[k]`` is about
        ``density[k] / sqrt(counts[k])``).
    s : ndarray
        The unfolded spacings (mean 1).
    """

    edges: np.ndarray
    density: np.ndarray
    counts: np.ndarray
    s: np.ndarray

    __eq__ = fields_equal  # (field by field: the generated == refuses array fields)
    __hash__ = None

    @property
    def centres(self) -> np.ndarray:
        """Bin centres."""
        return 0.5 * (self.edges[1:] + self.edges[:-1])

    def reference(self, ensemble: str) -> np.ndarray:
        """The reference density of ``ensemble`` averaged over each bin (compare with :attr:`density`)."""
        fine = np.linspace(0.0, 1.0, 33)
        out = np.empty(len(self.density))
        for k, (a, b) in enumerate(zip(self.edges[:-1], self.edges[1:])):
            out[k] = trapezoid(spacing_density(a + (b - a) * fine, ensemble), dx=1.0 / 32)
        return out

    def distance(self, ensemble: str) -> float:
        """Kolmogorov-Smirnov distance between the spacings and ``ensemble``'s cumulative distribution."""
        ens = _ensemble(ensemble)
        s = np.sort(self.s)
        if ens == "poisson":
            F = 1 - np.exp(-s)
        elif ens == "goe":
            F = 1 - np.exp(-0.25 * math.pi * s * s)
        else:
            from scipy.special import erf

            F = erf(2 * s / math.sqrt(math.pi)) - 4 * s / math.pi * np.exp(-4 * s * s / math.pi)
        n = s.size
        emp_hi = np.arange(1, n + 1) / n
        emp_lo = np.arange(0, n) / n
        return float(max(np.abs(emp_hi - F).max(), np.abs(emp_lo - F).max()))


def spacing_distribution(levels: Any, *, bins: Any = 30, s_max: float = 4.0, degree: int = 7) -> SpacingDistribution:
    r"""Distribution :math:`P(s)` of the unfolded nearest-neighbour spacings of one sector.

    Parameters
    ----------
    levels : 1-D array_like
        Energies of one symmetry sector.
    bins : int or array_like, default 30
        Number of equal bins on ``[0, s_max]``, or the bin edges (strictly increasing);
        at most ``options["statistics_max_size"]`` bins.
    s_max : float, default 4
    degree : int, default 7
        Staircase fit of :func:`unfold`.

    Returns
    -------
    SpacingDistribution
        ``density`` normalized over all spacings (spacings beyond the last edge
        count in the normalization but not in a bin); ``reference("goe")`` etc.
        give the bin-averaged reference curves, ``distance(...)`` the
        Kolmogorov-Smirnov distance.
    """
    s_max = _validate.positive("s_max", s_max)
    if isinstance(bins, (str, bytes, Mapping)) or not isinstance(bins, (Sequence, np.ndarray)):
        n_bins = _validate.integer("bins", bins, minimum=1)
        if n_bins > options["statistics_max_size"]:
            raise refuse("spacing_distribution", f"the histogram of bins = {n_bins}", n_bins, "statistics_max_size",
                         "bins", "ask for fewer bins")
        edges = np.linspace(0.0, s_max, n_bins + 1)
    else:
        edges = _validate.finite_array("bins", bins, ndim=1)
        if edges.size < 2 or not np.all(np.diff(edges) > 0):
            raise ValueError(f"bins as edges must be at least 2 strictly increasing numbers, got {_validate.fmt(edges)}")
        if edges.size - 1 > options["statistics_max_size"]:
            raise refuse("spacing_distribution", f"the histogram of bins ({edges.size} edges)", edges.size - 1,
                         "statistics_max_size", "bins", "give fewer edges")
    s = spacings(levels, degree=degree)
    counts, edges = np.histogram(s, bins=edges)
    density = counts / (s.size * np.diff(edges))
    return SpacingDistribution(edges, density, counts, s)


# ----------------------------------------------------------------------------
# synthetic spectra
# ----------------------------------------------------------------------------
def sample_spectrum(ensemble: str, n: int, *, rng: Any = 0, bulk: float = 1.0) -> np.ndarray:
    r"""A synthetic spectrum: ``n`` Poisson levels, or the eigenvalues of one n x n GOE/GUE matrix.

    Parameters
    ----------
    ensemble : {"poisson", "goe", "gue"}
    n : int
        Number of levels (matrix size for GOE/GUE, ``n >= 3``; for GOE/GUE priced as a dense
        diagonalization, the ``"dense_diagonalization"`` model: at most ``options["quantum_max_dense_dim"]``
        and within ``max_memory_bytes`` and ``max_seconds``; for Poisson at most
        ``options["statistics_max_size"]``). The ``eigvalsh`` runs where Ctrl-C reaches the caller at once
        (:func:`hyperrotor._parallel.interruptible`).
    rng : seed, numpy.random.Generator or None, keyword-only, default 0
        The draws: reproducible by default (seed 0); ``None`` for fresh entropy (a new spectrum each call).
    bulk : float in (0, 1], default 1
        Keep only the central fraction of the levels (the semicircle's edges have
        a different local statistics; ``bulk=0.5`` keeps the middle half).

    Returns
    -------
    ndarray, sorted
        Poisson: cumulative sums of unit exponential spacings (flat density).
        GOE: :math:`(A + A^{\mathsf T})/2`, GUE: :math:`(A + A^\dagger)/2`, A Gaussian.
    """
    ens = _ensemble(ensemble)
    n = _validate.integer("n", n, minimum=3)
    if ens != "poisson":  # (the n x n matrix, its eigvalsh: dimension, memory and time budgets, before any draw)
        _pricing.check("dense_diagonalization", dim=n, complex=ens == "gue")
    if n > options["statistics_max_size"]:
        raise refuse("sample_spectrum", f"a spectrum of n = {n} levels", n, "statistics_max_size", "levels",
                     "ask for a smaller n")
    bulk = _validate.positive("bulk", bulk)
    if bulk > 1:
        raise ValueError(f"bulk must be in (0, 1], got {_validate.fmt(bulk)}")
    g = _validate.rng(rng)
    if ens == "poisson":
        E = np.cumsum(g.exponential(size=n))
    elif ens == "goe":
        A = g.standard_normal((n, n))
        E = interruptible(np.linalg.eigvalsh, 0.5 * (A + A.T))  # (Ctrl-C: _parallel.interruptible)
    else:
        A = g.standard_normal((n, n)) + 1j * g.standard_normal((n, n))
        E = interruptible(np.linalg.eigvalsh, 0.5 * (A + A.conj().T))
    if bulk < 1:
        k = int(round(n * (1 - bulk) / 2))
        if n - 2 * k < 1:
            raise ValueError(f"bulk = {_validate.fmt(bulk)} keeps no level of n = {n}; raise bulk or n")
        E = E[k: n - k]
    return np.sort(E)
