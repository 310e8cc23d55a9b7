"""Symmetry sectors of the sign rotations and the reflection (hyperrotor.quantum.sectors, issues #16, #24).

Every assertion is an invariant that a wrong construction breaks: the monomial
matrices equal the dense exponentials exp(pi X), they conjugate every generator
with the right signs, the sector bases are orthonormal, real-gauged and H-invariant,
every sector is irreducible (a second inertia connects all eigenvectors of a first
one), the class sizes of D2 follow the closed formulas, and the union of the sector
spectra (with the forced degeneracies) is the dense spectrum.
"""
from __future__ import annotations

from fractions import Fraction as F

import numpy as np
import pytest
import scipy.linalg as sla
import scipy.sparse as sps
from scipy.sparse.csgraph import connected_components

import hyperrotor as hr
from hyperrotor.quantum import (
    adjoint_rep,
    direct_sum,
    harmonic_rep,
    irrep,
    rotor_hamiltonian,
    spinor_rep,
    tensor,
    vector_rep,
)
from hyperrotor.quantum.sectors import (
    pi_rotation,
    sector_blocks,
    sector_hamiltonian,
    sector_spectra,
    symmetry_sectors,
)
from hyperrotor.quantum.sectors.group import group_of
from tolerance import norm, scaled_tol

H_ = F(1, 2)

#: (N, highest weight) of GT irreps covering odd/even N, tensor/spinor
GT_CASES = [
    (3, (3,)), (3, (F(5, 2),)), (4, (2, 1)), (4, (2, -1)), (4, (F(3, 2), -H_)),
    (4, (2, 0)), (5, (2, 1)), (5, (3, 0)), (5, (F(3, 2), H_)), (6, (1, 1, 0)), (6, (2, 1, 1)),
    (6, (F(3, 2), H_, -H_)), (7, (1, 1, 0)), (7, (H_, H_, H_)),
]


def _ids(cases):
    return [f"so{N}-{'-'.join(str(x) for x in hw)}" for N, hw in cases]


def _moments(N, rng):
    return 0.5 + rng.random(N * (N - 1) // 2)


def _dense_H(rep, moments):
    return rotor_hamiltonian(rep, moments).full()


def _sign_of(plane, i, j):
    """s_i s_j for the rotation by pi in ``plane`` (s = -1 on the plane's two axes)."""
    s = {plane[0]: -1, plane[1]: -1}
    return s.get(i, 1) * s.get(j, 1)


# ----------------------------------------------------------------------------
# the monomial matrices D(g) = exp(pi X)
# ----------------------------------------------------------------------------
@pytest.mark.parametrize("N, hw", GT_CASES, ids=_ids(GT_CASES))
def test_pi_rotation_is_the_exponential(N, hw):
    rep = irrep(N, hw)
    for k in range(1, N):
        X = rep.generator((k, k + 1), format="dense")
        E = sla.expm(np.pi * X)
        D = pi_rotation(rep, (k, k + 1))
        assert sps.issparse(D) and D.nnz == rep.dim  # monomial: one entry per column
        # expm of a d x d matrix of norm pi ||X||: round-off ~ d eps (pi ||X||) (k absorbs the Pade steps)
        tol = scaled_tol(np.pi * norm(X), k=64, dim=rep.dim)
        np.testing.assert_allclose(D.toarray(), E, rtol=0, atol=tol)


@pytest.mark.parametrize("N, hw", GT_CASES, ids=_ids(GT_CASES))
def test_pi_rotation_conjugates_every_generator_with_signs(N, hw):
    """D X_ij D^-1 = s_i s_j X_ij for every plane (not only the chain planes the construction uses)."""
    rep = irrep(N, hw)
    spin = any(F(x).denominator == 2 for x in hw)
    for k in range(1, N):
        D = pi_rotation(rep, (k, k + 1))
        # D^2 = +1 (tensor) or -1 (spinor): exact, the entries are 0, +-1, +-i
        D2 = (D @ D).toarray()
        np.testing.assert_array_equal(D2, (-1 if spin else 1) * np.eye(rep.dim))
        Dinv = D.conj().T
        for (i, j), X in rep.generators().items():
            lhs = (D @ X @ Dinv).toarray()
            rhs = _sign_of((k, k + 1), i, j) * X.toarray()
            np.testing.assert_allclose(lhs, rhs, rtol=0, atol=scaled_tol(X, k=8, dim=1))


def test_pi_rotation_other_plane_and_rep_use_dense_exponential():
    rep = vector_rep(4)
    D = pi_rotation(rep, (1, 3), format="dense")
    np.testing.assert_allclose(D, np.diag([-1.0, 1.0, -1.0, 1.0]), rtol=0, atol=1e-14)


# ----------------------------------------------------------------------------
# 3D: the D2 classes of the asymmetric top
# ----------------------------------------------------------------------------
def _d2_sizes(J):
    if J % 2 == 0:
        return {"A": J // 2 + 1, "B1": J // 2, "B2": J // 2, "B3": J // 2}
    return {"A": (J - 1) // 2, "B1": (J + 1) // 2, "B2": (J + 1) // 2, "B3": (J + 1) // 2}


@pytest.mark.parametrize("N, hw", [(6, (2, 1, 0)), (7, (2, 1, 1)), (8, (1, 1, 1, 0)), (8, (H_, H_, H_, -H_))])
def test_last_label_flips_compose_to_the_flip_of_several_rows(N, hw):
    """Every intertwiner of the sign group takes its pattern permutation as a product of the single-row flips of
    the last labels of the even rows (the rotations, the reflection, the antiunitary): each product must send a
    pattern exactly to the pattern with those labels negated, for every set of rows."""
    import itertools

    from hyperrotor.quantum.gelfand_tsetlin import _row_offsets, last_label_flips, patterns

    m = tuple(F(x) for x in hw)
    P = patterns(N, m)
    flips = last_label_flips(N, P, m)
    assert sorted(flips) == list(range(2, N, 2))
    last = {k: _row_offsets(N)[k][1] - 1 for k in flips}
    for r in range(1, len(flips) + 1):
        for rows in itertools.combinations(sorted(flips), r):
            perm = np.arange(len(P))
            for k in rows:
                perm = flips[k][perm]
            Q = P.copy()
            Q[:, [last[k] for k in rows]] *= -1.0
            np.testing.assert_array_equal(P[perm], Q)
            assert np.array_equal(np.sort(perm), np.arange(len(P)))  # a permutation of the basis


def test_a_highest_weight_that_is_not_the_representations_takes_the_dense_route():
    """A representation that claims a highest weight of another dimension: its GT patterns are counted while they
    are built and the count stops past ``dim`` (no Weyl product, no pattern array of the claimed irrep, even a huge
    one), and the sectors come from the dense exponentials, the same as without the claim."""
    from hyperrotor.quantum import Representation
    from hyperrotor.quantum.gelfand_tsetlin import patterns

    gens = irrep(4, (1, 0)).generators()
    assert group_of(Representation(4, gens, highest_weight=(1, 0))).monomial  # the true weight: GT basis
    for hw in ((3, 0), (10**9, 0), (2, 2)):
        rep = Representation(4, gens, highest_weight=hw)
        with hr.options(max_memory_bytes=10**7):
            group = group_of(rep)
        assert not group.monomial and not group.reflection
        labels = [s.label for s in symmetry_sectors(rep)]
        assert labels == [s.label for s in symmetry_sectors(Representation(4, gens))]
    assert patterns(4, (F(3), F(0)), max_count=15) is None  # so(4) (3, 0) = (3/2, 3/2) of su(2) + su(2): 16
    assert len(patterns(4, (F(3), F(0)), max_count=16)) == 16 == len(patterns(4, (F(3), F(0))))


@pytest.mark.parametrize("J", range(1, 9))
def test_3d_four_sectors_with_d2_class_sizes(J):
    rep = irrep(3, (J,))
    secs = symmetry_sectors(rep)
    assert [s.label for s in secs] == ["A", "B1", "B2", "B3"]
    assert {s.label: s.dim for s in secs} == _d2_sizes(J)
    moments = [1.0, 1.7, 2.9]  # I_12, I_13, I_23: asymmetric top
    spec = sector_spectra(rep, moments)
    full = np.linalg.eigvalsh(_dense_H(rep, moments))
    np.testing.assert_allclose(spec.eigenvalues(), full, rtol=0, atol=1e-10 * np.abs(full).max())


def test_3d_class_labels_are_the_c2_characters():
    """B1 is even under C2(z) = rotation by pi in plane 12 and odd under C2(x) (plane 23), etc."""
    rep = irrep(3, (4,))
    expected = {"A": (1, 1), "B1": (1, -1), "B2": (-1, -1), "B3": (-1, 1)}
    D12, D23 = pi_rotation(rep, (1, 2)), pi_rotation(rep, (2, 3))
    for s in symmetry_sectors(rep):
        c12, c23 = expected[s.label]
        B = s.basis.toarray()
        np.testing.assert_array_equal(D12 @ B, c12 * B)  # (signed permutations: one product per entry, exact)
        np.testing.assert_array_equal(D23 @ B, c23 * B)


@pytest.mark.parametrize("twoj", [1, 3, 5, 7, 15])
def test_3d_half_integer_kramers_doublets(twoj):
    rep = irrep(3, (F(twoj, 2),))
    (s,) = symmetry_sectors(rep)
    assert (s.label, s.degeneracy, s.dim) == ("E1/2", 2, (twoj + 1) // 2)
    moments = [1.0, 1.7, 2.9]
    full = np.linalg.eigvalsh(_dense_H(rep, moments))
    levels = sector_spectra(rep, moments)["E1/2"]
    # every dense eigenvalue comes in a pair equal to one sector level
    np.testing.assert_allclose(full[0::2], levels, rtol=0, atol=1e-10 * np.abs(full).max())
    np.testing.assert_allclose(full[1::2], levels, rtol=0, atol=1e-10 * np.abs(full).max())


# ----------------------------------------------------------------------------
# so(5) and general N
# ----------------------------------------------------------------------------
def _check_sectors(rep, secs, H, *, complete):
    dim = rep.dim
    covered = 0
    for s in secs:
        B = s.basis.toarray() if sps.issparse(s.basis) else s.basis
        covered += s.dim * (1 if complete else s.degeneracy)
        if s.dim == 0:
            continue
        # orthonormal columns (entries are sums of at most 2^(N-1) phases: exact to a few eps)
        np.testing.assert_allclose(B.conj().T @ B, np.eye(s.dim), rtol=0, atol=scaled_tol(k=16, dim=dim))
        # invariant under H: H B = B (B^H H B)
        Hs = sector_hamiltonian(H, s)
        np.testing.assert_allclose(H @ B, B @ Hs, rtol=0, atol=scaled_tol(norm(H), k=16, dim=dim))
        assert s.real == sps.issparse(s.basis)  # real gauge for every GT sector, not for the dense fallback
        if s.real:
            assert Hs.dtype == np.float64
    assert covered == dim
    if complete:  # the sectors together are an orthonormal basis of the whole space
        Q = np.hstack([s.basis.toarray() if sps.issparse(s.basis) else s.basis for s in secs if s.dim])
        np.testing.assert_allclose(Q.conj().T @ Q, np.eye(dim), rtol=0, atol=scaled_tol(k=16, dim=dim))


@pytest.mark.parametrize("hw", [(6, 3), (4, 0)])
def test_so5_tensor_sixteen_sectors(hw, rng):
    rep = irrep(5, hw)
    secs = symmetry_sectors(rep)
    assert len(secs) == 16
    assert len({s.label for s in secs}) == 16
    assert all(s.dim > 0 and s.degeneracy == 1 and s.real for s in secs)
    moments = _moments(5, rng)
    H = _dense_H(rep, moments)
    _check_sectors(rep, secs, H, complete=True)
    full = np.linalg.eigvalsh(H)
    spec = sector_spectra(rep, moments)
    np.testing.assert_allclose(spec.eigenvalues(), full, rtol=1e-10)


@pytest.mark.parametrize("hw", [(F(5, 2), F(3, 2)), (F(7, 2), H_)])
def test_so5_spinor_four_fold_degenerate(hw, rng):
    rep = irrep(5, hw)
    (s,) = symmetry_sectors(rep)
    assert (s.label, s.degeneracy, 4 * s.dim) == ("spinor", 4, rep.dim)
    moments = _moments(5, rng)
    H = _dense_H(rep, moments)
    _check_sectors(rep, [s], H, complete=False)
    full = np.linalg.eigvalsh(H)
    levels = sector_spectra(rep, moments)["spinor"]
    for q in range(4):  # each level exactly four times in the dense spectrum
        np.testing.assert_allclose(full[q::4], levels, rtol=1e-10)
    # the complete decomposition: four copies (characters of the Cartan-plane rotations) span the space
    copies = symmetry_sectors(rep, complete=True)
    assert len(copies) == 4
    _check_sectors(rep, copies, H, complete=True)


@pytest.mark.parametrize("N, hw", GT_CASES, ids=_ids(GT_CASES))
def test_gt_sectors_invariant_and_spectrum(N, hw, rng):
    rep = irrep(N, hw)
    spin = any(F(x).denominator == 2 for x in hw)
    secs = symmetry_sectors(rep)
    if spin:
        assert len(secs) == 1 and secs[0].degeneracy == 2 ** ((N - 1) // 2)
    else:  # (Z2)^(N-1); for even N the centre -1 fixes one more sign, and the reflection doubles them if m_n = 0
        assert len(secs) == 2 ** (N - 1 if N % 2 else N - 2) * (2 if N % 2 == 0 and hw[-1] == 0 else 1)
    moments = _moments(N, rng)
    H = _dense_H(rep, moments)
    _check_sectors(rep, secs, H, complete=not spin)
    # eigenvalues of Hermitian matrices are perturbed by at most the norm of the perturbation (Weyl):
    # round-off of both eigh and of the projections, ~ eps * dim * ||H||
    np.testing.assert_allclose(sector_spectra(rep, moments).eigenvalues(), np.linalg.eigvalsh(H), rtol=0,
                               atol=scaled_tol(norm(H), k=16, dim=rep.dim))


def test_sector_characters_are_eigenvalues_of_the_rotations():
    rep = irrep(5, (3, 1))
    for s in symmetry_sectors(rep):
        B = s.basis.toarray()
        assert len(s.character) == 4
        for (i, j), lam in s.character.items():
            np.testing.assert_array_equal(pi_rotation(rep, (i, j)) @ B, lam * B)  # (a signed permutation: exact)
        assert s.label == tuple(s.character[(k, k + 1)] for k in range(1, 5))


@pytest.mark.parametrize("N, hw", [(4, (2, 0)), (4, (3, 0)), (6, (2, 1, 0)), (6, (1, 1, 0))],
                         ids=_ids([(4, (2, 0)), (4, (3, 0)), (6, (2, 1, 0)), (6, (1, 1, 0))]))
def test_reflection_is_a_signed_permutation_implementing_r(N, hw):
    """U X_ij U^-1 = -X_ij when exactly one of i, j is 1 (r = diag(-1, 1, ..., 1)), U^2 = 1, U commutes with
    the sign rotations, and every sector is an eigenspace of U with the parity of its character."""
    rep = irrep(N, hw)
    group = group_of(rep)
    assert group.reflection
    U = group.ops[-1].matrix()  # U_r joins the sign rotations as the last generator
    assert U.nnz == rep.dim and set(np.unique(np.abs(U.data))) == {1.0}
    np.testing.assert_array_equal((U @ U).toarray(), np.eye(rep.dim))
    for (i, j), X in rep.generators().items():
        sign = -1 if (i == 1) != (j == 1) else 1
        np.testing.assert_allclose((U @ X @ U.conj().T).toarray(), sign * X.toarray(), rtol=0,
                                   atol=scaled_tol(X, k=8, dim=1))
    for k in range(1, N):
        D = pi_rotation(rep, (k, k + 1))
        np.testing.assert_array_equal((U @ D).toarray(), (D @ U).toarray())
    for s in symmetry_sectors(rep):
        np.testing.assert_array_equal(U @ s.basis.toarray(), s.character["reflection"] * s.basis.toarray())


#: N = 3..7, tensor (real and complex type, with and without reflection) and spinor irreps
IRREDUCIBLE_CASES = [
    (3, (4,)), (3, (F(7, 2),)), (4, (2, 0)), (4, (4, 0)), (4, (3, -2)), (4, (F(5, 2), H_)), (5, (3, 1)),
    (5, (F(5, 2), F(3, 2))), (6, (2, 1, 0)), (6, (2, 1, 1)), (6, (F(3, 2), H_, -H_)), (7, (2, 1, 0)),
    (7, (F(3, 2), H_, H_)),
]


@pytest.mark.parametrize("N, hw", IRREDUCIBLE_CASES, ids=_ids(IRREDUCIBLE_CASES))
def test_every_sector_is_irreducible_and_real(N, hw, rng):
    """In the eigenbasis of one generic inertia's block, the block of a second generic inertia connects every
    eigenvector (one connected component per sector): no symmetry is left inside a sector. Both blocks real."""
    rep = irrep(N, hw)
    H1, H2 = (rotor_hamiltonian(rep, _moments(N, rng)) for _ in range(2))
    for s in symmetry_sectors(rep):
        if not s.dim:
            continue
        A, B = sector_hamiltonian(H1, s), sector_hamiltonian(H2, s)
        assert s.real and A.dtype == B.dtype == np.float64
        _, W = np.linalg.eigh(A)
        C = np.abs(W.T @ B @ W) > scaled_tol(norm(B), k=1e4, dim=s.dim)
        assert connected_components(sps.csr_matrix(C), directed=False)[0] == 1, s.label


def test_h_that_breaks_the_symmetry_and_bad_bases_are_refused(rng):
    rep = irrep(4, (2, 1))
    H = rotor_hamiltonian(rep, _moments(4, rng)).full()
    sec = symmetry_sectors(rep)[0]
    X = rep.generator((1, 2), format="dense")
    broken = H + 0.1j * X  # Hermitian, but -i X_12 is odd under the rotations by pi in planes 23, 34, ...
    with pytest.raises(ValueError, match="invariant"):
        sector_hamiltonian(broken, sec)
    with pytest.raises(ValueError, match=r"does not commute with the rotation by pi in the plane \(2, 3\)"):
        sector_blocks(broken, rep)
    with pytest.raises(ValueError, match="orthonormal"):
        sector_hamiltonian(H, 2.0 * sec.basis)
    with hr.options(sectors_dense_max_dim=3):  # no sectors to offer: the caller uses its own blocks
        assert sector_blocks(rotor_hamiltonian(vector_rep(4), np.ones(6)), vector_rep(4)) is None


def _rotated(rep, rng):
    """The same representation in another (random orthogonal) basis, with the same highest weight."""
    O, _ = np.linalg.qr(rng.normal(size=(rep.dim, rep.dim)))
    return hr.quantum.Representation(rep.N, {p: O @ rep.generator(p, format="dense") @ O.T for p in rep.planes},
                                     highest_weight=rep.highest_weight, name="rotated")


@pytest.mark.parametrize("case", ["field", "other basis", "field, spinor"])
def test_a_rep_that_h_does_not_respect_is_refused_on_every_sector_route(case, rng):
    """spectrum, evolve (every native method), otoc, SectorPropagator and sector_blocks split H by the sectors
    of a given rep= only after checking that H commutes with its rotations by pi: a rotor in a field (the
    helper's 3D case: states off by 0.11, levels by 11.6) or rep in another basis (0.48, 43) was trusted."""
    rep = irrep(3, (20,)) if case != "field, spinor" else irrep(4, (F(7, 2), H_))
    H = rotor_hamiltonian(rep, _moments(rep.N, rng))
    if case == "other basis":
        given = _rotated(rep, rng)
    else:
        given = rep
        H = H + 0.3 * rep.to_qobj((1, 3), form="hermitian")  # (arithmetic drops the recorded representation)
    M = H.full()
    psi = rng.normal(size=rep.dim) + 1j * rng.normal(size=rep.dim)
    psi /= np.linalg.norm(psi)
    t = np.linspace(0.0, 0.5, 3)
    W, V = (rng.normal(size=(rep.dim, rep.dim)) for _ in range(2))
    msg = r"does not commute with the rotation by pi in the plane \(\d, \d\) of "
    with hr.options(quantum_eigen_max_block=4):  # (the sector route, also for these small matrices)
        for call in (lambda: hr.quantum.spectrum(H, rep=given), lambda: hr.quantum.otoc(H, W, V, t, rep=given),
                     lambda: hr.quantum.SectorPropagator(H, rep=given), lambda: sector_blocks(H, given),
                     *(lambda m=m: hr.quantum.evolve(H, psi, t, rep=given, method=m)
                       for m in ("auto", "eigen", "krylov"))):
            with pytest.raises(ValueError, match=msg):
                call()
        # without rep=: H's own sparsity blocks, the right answers
        exact = np.linalg.eigvalsh(M)
        spec = hr.quantum.spectrum(H)
        np.testing.assert_allclose(np.repeat(spec.levels, spec.degeneracies), exact,
                                   atol=1e-10 * np.abs(exact).max(), rtol=0)
        states = np.array([s.full().ravel() for s in hr.quantum.evolve(H, psi, t).states])
        ref = np.array([sla.expm(-1j * M * x) @ psi for x in t])
        np.testing.assert_allclose(states, ref, atol=1e-8, rtol=0)


def test_sector_spectra_of_both_chiralities_keep_every_level(rng):
    """A reducible even-N spinor representation holding both chiralities has two sectors with distinct labels
    (the second overwrote the first in sector_spectra's dictionary: 4 of 8 levels of the Dirac spinor of so(6))."""
    for rep, types in ((spinor_rep(6), ["+i", "-i"]), (tensor(spinor_rep(4), vector_rep(4)), [-1, 1]),
                       (direct_sum(irrep(4, (F(3, 2), H_)), irrep(4, (F(3, 2), -H_))), [-1, 1])):
        moments = _moments(rep.N, rng)
        spec = sector_spectra(rep, moments)
        assert sorted(spec, key=str) == sorted((("spinor", c) for c in types), key=str)
        E = spec.eigenvalues()
        exact = np.linalg.eigvalsh(rotor_hamiltonian(rep, moments).full())
        assert E.size == rep.dim
        np.testing.assert_allclose(E, exact, atol=1e-10 * np.abs(exact).max(), rtol=0)
    assert [s.label for s in symmetry_sectors(irrep(4, (F(3, 2), H_)))] == ["spinor"]  # one chirality: as before


def test_so3_is_served_by_the_monomial_construction():
    """A large so(3) irrep: no dense exp(pi X_23) of the whole irrep (#21: it was a 596 GiB attempt at l = 99999)."""
    J = 4000
    with hr.options(max_memory_bytes=10**8):  # a dense 8001 x 8001 block would be refused
        secs = symmetry_sectors(irrep(3, (J,)))
    assert {s.label: s.dim for s in secs} == _d2_sizes(J) and all(s.real for s in secs)


def test_sectors_commute_with_any_inertia_including_physical_bodies(rng):
    """The symmetry holds for every inertia: a mass-tensor body and a random one share the sectors."""
    rep = irrep(4, (3, 1))
    secs = symmetry_sectors(rep)
    for inertia in (hr.Inertia.from_mass_tensor([1.0, 2.0, 3.5, 5.0]), _moments(4, rng)):
        moments = inertia.moments if hasattr(inertia, "moments") else inertia
        _check_sectors(rep, secs, _dense_H(rep, moments), complete=True)


# ----------------------------------------------------------------------------
# other representations: dense fallback
# ----------------------------------------------------------------------------
@pytest.mark.parametrize(
    "make",
    [lambda: vector_rep(5), lambda: spinor_rep(5), lambda: adjoint_rep(4), lambda: harmonic_rep(4, 2),
     lambda: tensor(vector_rep(3), vector_rep(3)), lambda: spinor_rep(4, chirality=1)],
    ids=["vector5", "spinor5", "adjoint4", "harmonic4-2", "vec3xvec3", "spinor4+"],
)
def test_dense_fallback_sectors(make, rng):
    rep = make()
    secs = symmetry_sectors(rep, complete=True)
    moments = _moments(rep.N, rng)
    H = _dense_H(rep, moments)
    _check_sectors(rep, secs, H, complete=True)
    spec = sector_spectra(rep, moments)
    np.testing.assert_allclose(spec.eigenvalues(), np.linalg.eigvalsh(H), rtol=1e-10, atol=1e-12)


def test_sector_blocks_hook_for_spectrum_and_evolve(rng):
    rep = irrep(5, (F(3, 2), H_))
    H = rotor_hamiltonian(rep, _moments(5, rng))
    blocks = sector_blocks(H, rep, complete=True)  # for evolution: the copies span the space, weight 1
    assert sum(B.shape[1] for B, _, _ in blocks) == rep.dim and {w for _, w, _ in blocks} == {1}
    one = sector_blocks(H, rep)  # for spectra: one copy, each level 4 times
    assert [(w, lab) for _, w, lab in one] == [(4, "spinor")]
    for parts in (blocks, one):
        E = np.sort(np.concatenate([np.repeat(np.linalg.eigvalsh(sector_hamiltonian(H, B)), w) for B, w, _ in parts]))
        np.testing.assert_allclose(E, np.linalg.eigvalsh(H.full()), rtol=1e-10)


def test_parallel_threads_agree_with_serial(rng):
    rep = irrep(5, (4, 2))
    moments = _moments(5, rng)
    a = sector_spectra(rep, moments)
    b = sector_spectra(rep, moments, workers=2)
    assert list(a) == list(b)
    for k in a:
        np.testing.assert_allclose(a[k], b[k], rtol=1e-12, atol=1e-12 * np.abs(a[k]).max())


def test_hbar_scales_levels(rng):
    rep = irrep(3, (5,))
    moments = _moments(3, rng)
    a, b = sector_spectra(rep, moments), sector_spectra(rep, moments, hbar=0.5)
    for k in a:
        np.testing.assert_allclose(b[k], 0.25 * a[k], rtol=1e-13)


# ----------------------------------------------------------------------------
# errors
# ----------------------------------------------------------------------------
def test_errors():
    with pytest.raises(TypeError, match="Representation"):
        symmetry_sectors(np.eye(3))
    with pytest.raises(TypeError, match="complete"):
        symmetry_sectors(irrep(3, (1,)), complete=1)
    with pytest.raises(ValueError, match="mixes tensor and spinor"):
        symmetry_sectors(direct_sum(vector_rep(3), spinor_rep(3)))
    with hr.options(sectors_dense_max_dim=3):
        with pytest.raises(hr.BudgetError, match="sectors_dense_max_dim"):
            symmetry_sectors(vector_rep(5))
    with hr.options(sectors_max_block_dim=2):
        with pytest.raises(hr.BudgetError, match="sectors_max_block_dim"):
            sector_spectra(irrep(5, (3, 1)), np.ones(10))
    with pytest.raises(ValueError, match="hbar"):
        sector_spectra(irrep(3, (1,)), [1, 2, 3], hbar=0.0)
    with pytest.raises(ValueError, match="body"):
        sector_spectra(irrep(3, (1,)), 3.0)
    with hr.options(max_seconds=1e-3):  # the sparse construction is priced too (model "gt_sectors")
        with pytest.raises(hr.BudgetError, match="gt_sectors"):
            symmetry_sectors(irrep(5, (3, 1)))
    with pytest.raises(ValueError, match="so\\(3\\) needs 3"):
        sector_spectra(irrep(3, (1,)), [1, 2, 3, 4, 5, 6])
    with pytest.raises(ValueError, match="workers"):
        sector_spectra(irrep(3, (1,)), [1, 2, 3], workers=0)
    with pytest.raises(ValueError, match="format"):
        sector_hamiltonian(np.eye(3), np.eye(3), format="sparse")
    with pytest.raises(ValueError, match="plane"):
        pi_rotation(irrep(3, (1,)), (2, 2))


def test_spectrum_uses_sectors_for_a_generic_inertia(rng):
    """spectrum(H) of a rotor Hamiltonian knows its representation and diagonalizes sector by sector:
    with a dense limit below the sparsity blocks but above the sectors it still returns every level."""
    rep = irrep(5, (6, 3))
    moments = _moments(5, rng)
    H = rotor_hamiltonian(rep, moments)
    dense = np.linalg.eigvalsh(H.full())
    with hr.options(quantum_max_dense_dim=100, quantum_eigen_max_block=60):
        res = hr.quantum.spectrum(H)
    assert isinstance(res, hr.quantum.Spectrum)
    np.testing.assert_allclose(np.repeat(res.levels, res.degeneracies), dense, rtol=1e-10)
    spin = irrep(5, (F(5, 2), F(3, 2)))
    with hr.options(quantum_eigen_max_block=8):
        _, deg = hr.quantum.spectrum(rotor_hamiltonian(spin, moments))
    assert set(deg.tolist()) == {4}


@pytest.mark.parametrize("hw", [(3, 1), (F(3, 2), H_)], ids=["tensor", "spinor"])
def test_evolution_blocks_reproduce_the_full_propagator(hw, rng):
    """exp(-iHt) psi0 = sum_s B_s exp(-i H_s t) B_s^H psi0 over the populated sectors."""
    from hyperrotor.quantum.sectors import evolution_blocks

    rep = irrep(5, hw)
    H = rotor_hamiltonian(rep, _moments(5, rng)).full()
    psi0 = rng.standard_normal(rep.dim) + 1j * rng.standard_normal(rep.dim)
    psi0 /= np.linalg.norm(psi0)
    t = 0.7
    jobs = evolution_blocks(H, rep, psi0)
    assert sum(B.shape[1] for B, _, _ in jobs) == rep.dim  # a generic state populates every sector
    out = sum(B @ (sla.expm(-1j * t * blk.toarray()) @ c0) for B, blk, c0 in jobs)
    exact = sla.expm(-1j * t * H) @ psi0
    np.testing.assert_allclose(out, exact, rtol=0, atol=scaled_tol(t * norm(H), k=64, dim=rep.dim))
    # a state inside one sector populates only that sector
    B0 = jobs[0][0]
    only = evolution_blocks(H, rep, B0[:, 0].toarray().ravel())
    assert len(only) == 1


@pytest.mark.slow
def test_sector_spectra_on_a_dask_client(dask_client, rng):
    """client=: one task per sector; the workers rebuild the irrep from its highest weight (same levels)."""
    rep = irrep(5, (3, 1))
    moments = _moments(5, rng)
    local = sector_spectra(rep, moments)
    local_vec = sector_spectra(vector_rep(5), moments)
    on_dask = sector_spectra(rep, moments, client=dask_client)
    # any basis of the irrep: the workers use the GT basis, and the sector levels are the same
    vec = sector_spectra(vector_rep(5), moments, client=dask_client)
    with pytest.raises(ValueError, match="highest weight"):
        sector_spectra(direct_sum(vector_rep(5), vector_rep(5)), moments, client=dask_client)
    for ref, got in ((local, on_dask), (local_vec, vec)):
        assert list(got) == list(ref)
        for k in ref:
            np.testing.assert_allclose(got[k], ref[k], rtol=1e-12, atol=1e-12 * max(1.0, np.abs(ref[k]).max(initial=0)))


@pytest.mark.slow
@pytest.mark.parametrize("make", [lambda: vector_rep(4), lambda: harmonic_rep(4, 2), lambda: irrep(4, (2, 0))],
                         ids=["vector4", "harmonic4-2", "irrep4-(2,0)"])
def test_sector_spectra_on_a_dask_client_in_even_dimension(make, dask_client, rng):
    """Even N: a Gelfand-Tsetlin irrep has a reflection parity that the vector and harmonic representations
    do not, so their sectors differ from those of irrep(N, highest_weight). client= gives each representation its
    own sectors' levels (they came back paired with the GT irrep's sectors: misplaced levels and NaN); with
    multiplicity, the full spectrum of the dense Hamiltonian."""
    rep = make()
    moments = _moments(4, rng)
    local = sector_spectra(rep, moments)
    on_dask = sector_spectra(rep, moments, client=dask_client)
    assert list(on_dask) == list(local)
    for k in local:
        assert np.all(np.isfinite(on_dask[k]))
        np.testing.assert_allclose(on_dask[k], local[k], rtol=0, atol=1e-12 * max(1.0, np.abs(local[k]).max(initial=0)))
    dense = np.linalg.eigvalsh(rotor_hamiltonian(rep, moments).full())
    np.testing.assert_allclose(on_dask.eigenvalues(), dense, rtol=0, atol=1e-10 * max(1.0, np.abs(dense).max()))


@pytest.mark.parametrize("method", ["eigen", "krylov"])
def test_evolve_uses_sectors_for_a_generic_inertia(method, rng):
    """evolve() of a generic rotor knows its representation and propagates sector by sector;
    the states agree with the dense exponential and with the run without blocks. ("auto" may first
    rent a whole-space Krylov run: test_evolve_propagator.py::test_evolve_rents_krylov_then_buys_the_sectors.)"""
    rep = irrep(5, (4, 2))
    H = rotor_hamiltonian(rep, _moments(5, rng))
    psi0 = rng.standard_normal(rep.dim) + 1j * rng.standard_normal(rep.dim)
    psi0 /= np.linalg.norm(psi0)
    t = np.linspace(0.0, 0.5, 4)
    with hr.options(quantum_eigen_max_block=40):
        res = hr.quantum.evolve(H, psi0, t, method=method)
    assert res.stats["sectors"] == 16
    Hd = H.full()
    for tk, state in zip(t, res.states):
        exact = sla.expm(-1j * tk * Hd) @ psi0
        np.testing.assert_allclose(state.full().ravel(), exact, rtol=0, atol=1e-9)
    plain = hr.quantum.evolve(H, psi0, t, method=method, options={"blocks": False})
    assert "sectors" not in plain.stats
