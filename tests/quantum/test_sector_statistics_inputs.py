"""Behaviour at the edges of the inputs of sectors, level statistics and the operator helpers (#12 fuzzing).

The fuzz module (tests/property/test_fuzz_entry_points.py) checks that bad values are refused
with a named ValueError/TypeError; here are the values behind the fixes it led to: densities
outside their support, degenerate spectra, budgets, and that a good call gives what it gave.
"""
import math

import numpy as np
import pytest
import scipy.sparse as sps

import hyperrotor as hr
import hyperrotor.quantum as hq
from hyperrotor import _validate


# ----------------------------------------------------------------------------- statistics
@pytest.mark.parametrize("ensemble", ["poisson", "goe", "gue"])
def test_densities_vanish_outside_their_support_and_keep_their_values_inside(ensemble):
    r = np.array([-2.0, -1.0, -1e-300, 0.0, 0.25, 1.0, 1.0 + 1e-15, 3.0, 1e300])
    dens = hq.ratio_density(r, ensemble)
    inside = (r >= 0) & (r <= 1)
    assert np.all(dens[~inside] == 0.0)
    beta = {"poisson": 0, "goe": 1, "gue": 2}[ensemble]
    x = r[inside]
    if beta == 0:
        ref = 2.0 / (1.0 + x) ** 2
    else:
        Z = 8.0 / 27.0 if beta == 1 else 4.0 * math.pi / (81.0 * math.sqrt(3.0))
        ref = 2.0 / Z * (x + x * x) ** beta / (1.0 + x + x * x) ** (1.0 + 1.5 * beta)
    np.testing.assert_array_equal(dens[inside], ref)

    s = np.array([-5.0, -1e-300, 0.0, 0.5, 2.0, 1e160, 1e300])
    with np.errstate(over="raise", invalid="raise"):  # huge s: the density is 0 there, no overflow or inf * 0
        p = hq.spacing_density(s, ensemble)
    assert np.all(p[s < 0] == 0.0) and np.all(p[-2:] == 0.0)
    ref = {"poisson": np.exp(-0.5), "goe": 0.25 * math.pi * math.exp(-math.pi / 16),
           "gue": 8.0 / math.pi**2 * math.exp(-1.0 / math.pi)}[ensemble]
    assert p[3] == pytest.approx(ref, rel=4 * np.finfo(float).eps)
    assert np.ndim(hq.spacing_density(0.5, ensemble)) == 0 and np.ndim(hq.ratio_density(0.5, ensemble)) == 0


def test_degenerate_spectra_are_refused_with_the_reason():
    with pytest.raises(ValueError, match="the 5 levels are all equal: no level statistics"):
        hq.spacing_ratio(np.full(5, 2.0))
    with pytest.raises(ValueError, match="2 of the 4 spacings of levels vanish"):
        hq.spacing_ratio([0.0, 1.0, 1.0, 1.0, 3.0])  # was 0.0 silently (one zero ratio, one dropped triple)
    E = np.cumsum(np.arange(1.0, 11.0) ** 1.5)  # 10 spacings with the repeated level below, one zero: a warning
    with pytest.warns(RuntimeWarning, match="1 of the 10 spacings") as record:
        assert 0 < hq.spacing_ratio(np.insert(E, 3, E[3])) < hq.spacing_ratio(E)
    assert [w.filename for w in record] == [__file__]  # (attributed to the caller, not to the package)
    # a spinor irrep: every level four times in the full spectrum (refused), once in its sector (fine)
    spec = hq.sector_spectra(hq.irrep(5, (1.5, 0.5)), 0.5 + np.arange(10) / 7)
    with pytest.raises(ValueError, match="12 of the 15 spacings"):
        hq.spacing_ratio(spec.eigenvalues())
    assert 0 < hq.spacing_ratio(spec["spinor"]) < 1
    with pytest.raises(ValueError, match="the 10 levels are all equal"):
        hq.unfold(np.full(10, 3.5))
    with pytest.raises(ValueError, match="7 of the 8 spacings of levels vanish"):  # (2 distinct values)
        hq.unfold([0.0] * 5 + [1.0] * 4, degree=7)


def test_unfolding_near_the_float_range_does_not_overflow():
    E = np.linspace(-1.0, 1.0, 12)
    with np.errstate(over="raise", invalid="raise"):
        big = hq.unfold(E * 1e308, degree=3)
    np.testing.assert_allclose(big, hq.unfold(E, degree=3), rtol=0, atol=1e-12)


def test_bins_as_edges_equal_bins_as_a_count():
    E = hq.sample_spectrum("goe", 60, rng=3)
    a = hq.spacing_distribution(E, bins=8, s_max=3.0, degree=3)
    b = hq.spacing_distribution(E, bins=np.linspace(0.0, 3.0, 9), degree=3)
    np.testing.assert_array_equal(a.counts, b.counts)
    np.testing.assert_array_equal(a.density, b.density)
    for bad, exc in [(0, ValueError), (2.5, TypeError), (True, TypeError), ([1.0, 1.0], ValueError),
                     ([2.0, 1.0, 3.0], ValueError), ([0.0, np.nan], ValueError), (10**9, ValueError)]:
        with pytest.raises(exc, match="bins"):  # 10**9 bins: refused before 8 GB of edges are allocated
            hq.spacing_distribution(E, bins=bad, degree=3)
    with hr.options(statistics_max_size=4):
        with pytest.raises(ValueError, match="statistics_max_size"):
            hq.spacing_distribution(E, bins=np.linspace(0.0, 3.0, 6), degree=3)


def test_random_matrix_samples_respect_the_dense_budget():
    with hr.options(quantum_max_dense_dim=5):
        with pytest.raises(ValueError, match="quantum_max_dense_dim"):
            hq.sample_spectrum("gue", 6, rng=1)
        assert hq.sample_spectrum("poisson", 6, rng=1).shape == (6,)  # no matrix: no limit
    with hr.options(statistics_max_size=5), pytest.raises(ValueError, match="statistics_max_size"):
        hq.sample_spectrum("poisson", 6, rng=1)
    with pytest.raises(ValueError, match="keeps no level"):
        hq.sample_spectrum("goe", 10, rng=1, bulk=1e-300)
    assert hq.sample_spectrum("goe", 12, rng=1, bulk=0.5).shape == (6,)  # the middle half
    np.testing.assert_array_equal(hq.sample_spectrum("goe", 6, rng=1), hq.sample_spectrum("goe", 6, rng=1))


def test_switches_take_booleans_only():
    assert _validate.flag("x", np.True_) is True and _validate.flag("x", None, allow_none=True) is None
    E = np.arange(10.0) ** 1.5
    assert hq.spacing_ratio(E, return_error=np.False_) == hq.spacing_ratio(E)
    for bad in (1, "yes", None):
        with pytest.raises(TypeError, match="return_error"):
            hq.spacing_ratio(E, return_error=bad)
        with pytest.raises(TypeError, match="unfolded"):
            hq.spacings(E, unfolded=bad)


#: Booleans (and text, masks, dates) that NumPy reads as numbers, hidden where numeric_input did not look: inside
#: object arrays and inside arrays nested in lists (the entry after it is the message; each was accepted, so True
#: became the number 1).
_HIDDEN_NON_NUMBERS = [
    ([np.array([True, False]), 1.0], r"got a boolean entry in \[\[True, False\], 1.0\]"),
    (np.array([True, 1.0], dtype=object), r"got a boolean entry in \[True, 1.0\]"),
    ((np.array([1.0, 2.0]), np.array([True, False])), r"got a boolean entry in \(\[1.0, 2.0\], \[True, False\]\)"),
    ([1.0, 2.0, np.array(True)], r"got a boolean entry in \[1.0, 2.0, True\]"),
    (np.array([np.array([True, False]), 1.0], dtype=object), r"got a boolean entry in \[\[True, False\], 1.0\]"),
    ([[True, 2.0]], r"got a boolean entry in \[\[True, 2.0\]\]"),  # (refused before too: kept)
    (np.array(["1.5", 2.0], dtype=object), r"got text in \['1.5', 2.0\] \(x\[0\] = '1.5'; text is never read as a "
                                           r"number here\)"),
    ([np.ma.masked_array([1.0, 2.0], mask=[True, False]), 1.0],
     r"got a masked array entry in .* \(x\[0\]: its mask would be ignored\)"),
    ([[1.0, [2.0, 3.0]], [4.0, [5.0, True]]], r"got a boolean entry in .* \(x\[1\]\[1\]\[1\] = True\)"),
    (np.array([[1.0, 2.0], [3.0, True]], dtype=object), r"got a boolean entry in .* \(x\[1, 1\] = True\)"),
    ([0.0] * 20 + ["x"], r"got text in \[0.0, .*\.\.\. \(21 entries\)\] \(x\[20\] = 'x'; text is never"),
]


@pytest.mark.parametrize("value, match", _HIDDEN_NON_NUMBERS)
def test_numeric_input_finds_booleans_wherever_they_are(value, match):
    with pytest.raises(TypeError, match=r"x must be numeric, " + match):
        _validate.numeric_input("x", value)


def test_numeric_input_refusals_reach_the_quantum_entry_points():
    rep = hq.irrep(3, (1,))
    with pytest.raises(TypeError, match=r"body must be numeric, got a boolean entry in \[1.0, True, 3.0\]"):
        hq.rotor_hamiltonian(rep, np.array([1.0, True, 3.0], dtype=object))  # (was read as I_13 = 1)
    with pytest.raises(TypeError, match=r"body must be numeric, got a boolean entry in \[\[True\], 2.0, 3.0\]"):
        hq.rotor_hamiltonian(rep, [np.array([True]), 2.0, 3.0])
    H = hq.rotor_hamiltonian(rep, [1.0, 2.0, 3.0])
    with pytest.raises(TypeError, match=r"psi0 must be numeric, got a boolean entry in \[\[True, False\], 1.0\]"):
        hq.evolve(H, [np.array([True, False]), 1.0], [0.0, 1.0])  # (was the state (1, 0, 1)/sqrt(2))
    with pytest.raises(TypeError, match=r"t must be numeric, got a boolean entry in \[0.0, True\]"):
        hq.evolve(H, [1.0, 0.0, 0.0], np.array([0.0, True], dtype=object))
    # good input of every kind still passes: numbers in lists, object arrays and nested arrays, a list holding itself
    loop = [1.0]
    loop.append(loop)
    for good in (np.ones(3), [1, 2.0, np.float32(3)], np.array([1.0, 2], dtype=object), [np.ones(2), np.int64(1)],
                 loop, 1.5, np.float64(2.0)):
        assert _validate.numeric_input("x", good) is None


# ----------------------------------------------------------------------------- sectors
def _rep_and_H():
    rep = hq.irrep(3, (2,))
    return rep, hq.rotor_hamiltonian(rep, [1.0, 1.7, 2.9])


def test_sector_hamiltonian_is_the_same_for_a_sector_its_basis_and_a_dense_H():
    rep, H = _rep_and_H()
    Hd = H.full()
    for sec in hq.symmetry_sectors(rep):
        if not sec.dim:
            continue
        a = hq.sector_hamiltonian(H, sec)
        b = hq.sector_hamiltonian(Hd, sec.basis.toarray())
        B = sec.basis.toarray()
        ref = B.conj().T @ Hd @ B
        tol = 8 * np.finfo(float).eps * rep.dim * np.abs(Hd).max()
        assert np.abs(a - ref).max() <= tol and np.abs(b - ref).max() <= tol


def test_sector_functions_refuse_a_non_hermitian_or_non_finite_H():
    rep, H = _rep_and_H()
    sec = next(s for s in hq.symmetry_sectors(rep) if s.dim)
    bad = H.full() + 1e-3 * np.triu(np.ones((rep.dim, rep.dim)), 1)  # was symmetrized silently
    with pytest.raises(ValueError, match="Hermitian"):
        hq.sector_hamiltonian(bad, sec)
    with pytest.raises(ValueError, match="Hermitian"):
        hq.sector_blocks(bad, rep)
    nan = H.full().real
    nan[0, 0] = np.nan
    with pytest.raises(ValueError, match=r"H must be finite; H\[0, 0\] = nan"):
        hq.evolution_blocks(nan, rep, np.ones(rep.dim))
    with pytest.raises(ValueError, match="psi0"):
        hq.evolution_blocks(H, rep, np.ones(rep.dim + 1))
    with pytest.raises(TypeError, match="sector must be"):
        hq.sector_hamiltonian(H, None)
    with pytest.raises(ValueError, match=r"shape \(5, n\)"):
        hq.sector_hamiltonian(H, np.ones(5))


def test_evolution_blocks_rebuild_the_state():
    rep, H = _rep_and_H()
    psi = np.arange(1.0, rep.dim + 1) + 0.5j
    parts = hq.evolution_blocks(H, rep, psi)
    back = sum(B @ c0 for B, _, c0 in parts)
    assert np.abs(back - psi).max() <= 8 * np.finfo(float).eps * rep.dim * np.abs(psi).max()


def test_sector_spectra_checks_its_switches_and_workers():
    rep = hq.irrep(3, (1,))
    good = hq.sector_spectra(rep, [1.0, 2.0, 3.0], workers=1, progress=False)
    A, B, C = (1.0 / (2.0 * I) for I in (1.0, 2.0, 3.0))  # l = 1: levels B + C, A + C, A + B (test_rotor.py)
    np.testing.assert_allclose(np.sort(good.eigenvalues()), [B + C, A + C, A + B], rtol=0,
                               atol=16 * np.finfo(float).eps * rep.dim * (A + B + C))
    with pytest.raises(TypeError, match="workers"):
        hq.sector_spectra(rep, [1.0, 2.0, 3.0], workers="2")
    with pytest.raises(TypeError, match="parallel"):  # the old switch is gone (workers=1 is serial)
        hq.sector_spectra(rep, [1.0, 2.0, 3.0], parallel=True)
    with pytest.raises(TypeError, match="progress"):
        hq.sector_spectra(rep, [1.0, 2.0, 3.0], progress="no")
    with pytest.raises(TypeError, match="rep must be"):
        hq.sector_spectra(None, [1.0, 2.0, 3.0])


# ----------------------------------------------------------------------------- operators
def test_rotor_hamiltonian_refuses_an_overflowing_hbar():
    rep = hq.irrep(3, (1,))
    with pytest.raises(ValueError, match=r"hbar = 1e\+200"):
        hq.rotor_hamiltonian(rep, [1.0, 2.0, 3.0], hbar=1e200)
    with pytest.raises(TypeError, match="must be real"):
        hq.rotor_hamiltonian(rep, [1.0 + 1j, 2.0, 3.0])


def test_as_csr_and_check_antihermitian_name_what_is_wrong():
    M = np.eye(3)
    M[1, 2] = np.inf
    with pytest.raises(ValueError, match=r"X must be finite; X\[1, 2\] = inf"):
        hq.as_csr(M, "X")
    assert hq.as_csr(sps.eye(2, dtype=complex)).dtype == float
    X = np.array([[0.0, -1.0], [1.0, 0.0]])
    hq.check_antihermitian({(1, 2): X})
    with pytest.raises(ValueError, match="form"):
        hq.check_antihermitian({(1, 2): X}, form="nonsense")
    with pytest.raises(ValueError, match='pass form="hermitian"'):
        hq.check_antihermitian({(1, 2): 1j * X})
    with pytest.raises(TypeError, match="mapping"):
        hq.check_antihermitian([X])


def test_jmat_generators_spin_checks_and_budget():
    with pytest.raises(TypeError, match="spin j"):
        hq.jmat_generators("1")
    with pytest.raises(ValueError, match="half-integer"):
        hq.jmat_generators(0.3)
    with pytest.raises(ValueError, match="DEFAULT_MAX_DIM"):
        hq.jmat_generators(1e300)


def test_register_propagator_takes_a_propagator_class_only():
    before = dict(hq.PROPAGATORS)
    for bad in (None, "krylov", hq.PROPAGATORS["krylov"](), dict):
        with pytest.raises(TypeError, match="cls must be"):
            hq.register_propagator(bad)
    assert hq.PROPAGATORS == before


def test_refusal_messages_stay_short_and_finite():
    """The message of a refused input is built by _validate.fmt: a list holding itself, deep nesting and a million
    entries give a short TypeError (were RecursionError, RecursionError and a 5 MB message)."""
    loop = [1.0, True]
    loop.append(loop)
    deep = [True, 1.0]
    for _ in range(3000):
        deep = [deep]
    long = [0.5] * 10**6 + [True]
    for value, shown in ((loop, r"\[1.0, True, \[1.0, True, \[1.0, True, \[1.0, True, <list of 3 entries>\]\]\]\] "
                                r"\(x\[1\] = True\)"),
                         (deep, r"\[\[\[\[<list of 1 entries>\]\]\]\] \(x(\[0\]){3000}\[0\] = True\)"),
                         (long, r"\[0.5, 0.5, 0.5, 0.5, 0.5, 0.5, \.\.\. \(1000001 entries\)\] "
                                r"\(x\[1000000\] = True\)")):
        with pytest.raises(TypeError, match=r"^x must be numeric, got a boolean entry in " + shown + "$") as info:
            _validate.numeric_input("x", value)
        assert len(str(info.value)) < 200 + 3 * 3000  # (the deep one's path: 3000 "[0]")
    assert _validate.fmt(list(range(12))) == str(list(range(12)))  # (up to 12 entries: all of them)
    assert _validate.fmt((1.5,)) == "(1.5,)"
    assert _validate.fmt(tuple(range(13))) == "(0, 1, 2, 3, 4, 5, ... (13 entries))"


def test_every_block_is_priced_not_only_the_largest():
    """spectrum and sector_spectra diagonalize every block: 60 blocks of 400 ran ~100x over max_seconds, priced as
    one; the 16 sectors of an so(5) irrep as 4 (a review)."""
    from hyperrotor._pricing import estimate
    from hyperrotor.quantum.sectors.construction import sectors_of

    def seconds(entry, **sizes):
        return sum(c.amount for c in estimate(entry, **sizes) if c.unit == "seconds")

    g = np.random.default_rng(0)
    A = g.normal(size=(400, 400))
    H = sps.block_diag([A + A.T] * 60, format="csr")
    one = seconds("dense_diagonalization", dim=400, complex=False)
    with hr.options(max_seconds=5 * one):  # (one block's estimate, 5x over: let through before)
        with pytest.raises(ValueError, match="diagonalizing a dense 400 x 400 block and the others"):
            hq.spectrum(H)
    rep = hq.irrep(5, (16, 8))
    secs = sectors_of(rep, False)
    big = max(s.dim for s in secs)
    assert len(secs) == 16 and sum(s.dim**3 for s in secs) > 8 * big**3
    with hr.options(max_seconds=2 * seconds("sector_spectra", dim=big)):  # (the old estimate: 4 sectors' worth)
        with pytest.raises(ValueError, match="sector_spectra"):
            hq.sector_spectra(rep, np.linspace(1.0, 2.0, 10))
