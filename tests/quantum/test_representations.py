"""so(N) representations: vector, adjoint, spinor, harmonic, tensor, direct sum; equivalences with GT irreps."""
from collections import Counter
from fractions import Fraction

import numpy as np
import pytest
import qutip
import scipy.sparse as sps
import sympy as sp

from hyperrotor.conventions import basis_matrix, planes, structure_constants
from hyperrotor.quantum.gelfand_tsetlin import irrep
from hyperrotor.quantum.harmonic import harmonic_dimension
from hyperrotor.quantum.combine import direct_sum, tensor
from hyperrotor.quantum.equivalence import intertwiner, real_form
from hyperrotor.quantum.representation import Representation
from hyperrotor.quantum.standard_reps import adjoint_rep, harmonic_rep, spinor_rep, vector_rep
from hyperrotor.quantum.weights import casimir_eigenvalue, weight_multiplicities, weyl_dimension
from tolerance import norm, scaled_tol

H = Fraction(1, 2)


def _constructors():
    out = []
    for N in range(2, 8):
        out.append(pytest.param(lambda N=N: vector_rep(N), id=f"vector{N}"))
        out.append(pytest.param(lambda N=N: adjoint_rep(N), id=f"adjoint{N}"))
        for ch in ([None] if N % 2 else [None, 1, -1]):
            out.append(pytest.param(lambda N=N, ch=ch: spinor_rep(N, ch), id=f"spinor{N}_{ch}"))
    for N, l in [(2, 0), (2, 3), (3, 0), (3, 2), (4, 2), (4, 3), (5, 1), (5, 2), (5, 3), (6, 2), (7, 2)]:
        out.append(pytest.param(lambda N=N, l=l: harmonic_rep(N, l), id=f"harmonic{N}_{l}"))
    out.append(pytest.param(lambda: tensor(vector_rep(5), spinor_rep(5)), id="vector5xspinor5"))
    out.append(pytest.param(lambda: tensor(vector_rep(4), vector_rep(4)), id="vector4xvector4"))
    out.append(pytest.param(lambda: direct_sum(vector_rep(5), adjoint_rep(5), irrep(5, (H, H))), id="sum5"))
    out.append(pytest.param(lambda: tensor(spinor_rep(6, 1), spinor_rep(6, -1)), id="spinor6+xspinor6-"))
    return out


CONSTRUCTORS = _constructors()


def _X(rep, a, b):
    return rep.generator((a, b)) if a < b else -rep.generator((b, a))


@pytest.mark.parametrize("make", CONSTRUCTORS)
def test_brackets_and_contraction(make):
    rep = make()
    N = rep.N
    C = structure_constants(N)
    pl = planes(N)
    G = rep.generators()
    # entries of a commutator of two d x d generators: round-off ~ d eps ||X||^2 (tests/tolerance.py);
    # the contraction identity sums N - 2 commutators
    tol = scaled_tol(max(norm(M.toarray()) for M in G.values()) ** 2, dim=rep.dim, k=4 * N)
    for a, pa in enumerate(pl):
        for b, pb in enumerate(pl):
            res = G[pa] @ G[pb] - G[pb] @ G[pa]
            for c in np.nonzero(C[a, b])[0]:
                res = res - int(C[a, b, c]) * G[pl[c]]
            assert (abs(res).max() if res.nnz else 0.0) <= tol
    # contraction identity: sum_{k != i,j} [X_(ik), X_(kj)] = (N - 2) X_(ij)
    for i in range(1, N + 1):
        for j in range(1, N + 1):
            if i != j:
                tot = sum((_X(rep, i, k) @ _X(rep, k, j) - _X(rep, k, j) @ _X(rep, i, k)
                           for k in range(1, N + 1) if k not in (i, j)), sps.csr_matrix((rep.dim, rep.dim)))
                res = tot - (N - 2) * _X(rep, i, j)
                assert (abs(res).max() if res.nnz else 0.0) <= tol
                # the paper's form, eqs. (145)-(147) (-3, -2, -1 for N = 5, 4, 3):
                # sum_k (X_(ik) X_(jk) - X_(jk) X_(ik)) = -(N - 2) X_(ij)
                tot2 = sum((_X(rep, i, k) @ _X(rep, j, k) - _X(rep, j, k) @ _X(rep, i, k)
                            for k in range(1, N + 1) if k not in (i, j)), sps.csr_matrix((rep.dim, rep.dim)))
                res2 = tot2 + (N - 2) * _X(rep, i, j)
                assert (abs(res2).max() if res2.nnz else 0.0) <= tol


@pytest.mark.parametrize("make", CONSTRUCTORS)
def test_hermiticity_reality_casimir_weights(make):
    rep = make()
    for p in rep.planes:
        X = rep.generator(p, format="dense")
        assert np.abs(X + X.conj().T).max() <= scaled_tol(X)  # numerically built entries: round-off ~ eps |X|
        L = rep.generator(p, form="hermitian", hbar=2.0, format="dense")
        assert np.abs(L - L.conj().T).max() <= scaled_tol(L)
        np.testing.assert_array_equal(L, -2.0j * X)
    if rep.highest_weight is not None:
        c = float(rep.casimir_value())
        assert c == float(casimir_eigenvalue(rep.N, rep.highest_weight))
        assert np.abs(rep.casimir(format="dense") + c * np.eye(rep.dim)).max() <= scaled_tol(max(1.0, c), dim=rep.dim, k=4 * len(rep.planes))
        assert rep.dim == weyl_dimension(rep.N, rep.highest_weight)
        assert rep.weight_multiplicities() == weight_multiplicities(rep.N, rep.highest_weight)


def test_real_representations_are_real_antisymmetric():
    reps = [vector_rep(N) for N in range(2, 8)] + [adjoint_rep(N) for N in range(2, 8)]
    reps += [harmonic_rep(N, l) for N, l in [(3, 3), (4, 2), (5, 3), (6, 2)]]
    reps += [tensor(vector_rep(5), vector_rep(5)), direct_sum(vector_rep(4), adjoint_rep(4))]
    for rep in reps:
        assert rep.is_real
        for p in rep.planes:
            X = rep.generator(p, format="dense")
            assert X.dtype == np.float64
            assert np.abs(X + X.T).max() <= scaled_tol(X)
    assert not spinor_rep(5).is_real


def test_vector_rep_is_the_plane_basis():
    for N in range(2, 8):
        rep = vector_rep(N)
        for p in planes(N):
            np.testing.assert_array_equal(rep.generator(p, format="dense"), basis_matrix(p, N, convention="standard"))
            assert rep.generator(p, exact=True) == sp.Matrix(basis_matrix(p, N, convention="standard"))
        assert np.array_equal(rep.casimir(format="dense"), -(N - 1) * np.eye(N))


def test_adjoint_rep_is_ad():
    # (ad E_a) E_b = [E_a, E_b] expanded in the plane basis
    N = 5
    rep = adjoint_rep(N)
    pl = planes(N)
    E = [basis_matrix(p, N, convention="standard") for p in pl]
    for a, pa in enumerate(pl):
        M = rep.generator(pa, format="dense")
        for b in range(len(pl)):
            comm = E[a] @ E[b] - E[b] @ E[a]
            rebuilt = sum(M[c, b] * E[c] for c in range(len(pl)))
            assert np.array_equal(rebuilt, comm)
    assert rep.casimir_value() == 2 * (N - 2)


def test_spinor_gamma_structure():
    # X_(ij) = (1/2) g_i g_j with a Clifford algebra: X_(ij)^2 = -1/4
    for N in range(2, 9):
        rep = spinor_rep(N)
        assert rep.dim == 2 ** (N // 2)
        for p in rep.planes:
            X = rep.generator(p, format="dense")
            assert np.allclose(X @ X, -0.25 * np.eye(rep.dim), rtol=0, atol=1e-15)
        # Cartan generators diagonal, weights +-1/2
        w = rep.weights()
        assert np.all(np.abs(w) == 0.5)
    assert spinor_rep(5).highest_weight == (H, H)
    assert spinor_rep(6, 1).highest_weight == (H, H, H)
    assert spinor_rep(6, -1).highest_weight == (H, H, -H)
    assert spinor_rep(6).highest_weight is None
    # exact generators
    ex = spinor_rep(5).generator((1, 2), exact=True)
    assert ex == sp.diag(sp.I / 2, sp.I / 2, -sp.I / 2, -sp.I / 2)


def test_tensor_and_direct_sum_weights():
    # weights of a tensor product = all sums; of a direct sum = the union (independent of the matrices)
    a, b = vector_rep(5), spinor_rep(5)
    t = tensor(a, b)
    wa, wb = Counter(map(tuple, a.weights())), Counter(map(tuple, b.weights()))
    expected = Counter()
    for x, ca in wa.items():
        for y, cb in wb.items():
            expected[tuple(u + v for u, v in zip(x, y))] += ca * cb
    assert Counter(map(tuple, t.weights())) == expected
    # vector x spinor of so(5) = (3/2, 1/2) + (1/2, 1/2): Casimir eigenvalues 15/2 (16 times) and 5/2 (4 times)
    ev = np.linalg.eigvalsh(-t.casimir(format="dense"))
    assert np.allclose(np.sort(ev), [2.5] * 4 + [7.5] * 16, rtol=0, atol=scaled_tol(7.5, dim=20, k=16))
    s = direct_sum(a, b)
    assert Counter(map(tuple, s.weights())) == wa + wb
    assert s.highest_weight is None and s.dim == 9


def test_equivalences_with_gt_irreps():
    pairs = [(vector_rep(N), irrep(N, (1,) + (0,) * (N // 2 - 1))) for N in range(3, 8)]
    pairs += [(spinor_rep(5), irrep(5, (H, H))), (spinor_rep(3), irrep(3, (H,))), (spinor_rep(7), irrep(7, (H, H, H)))]
    pairs += [(spinor_rep(N, ch), irrep(N, (H,) * (N // 2 - 1) + (ch * H,))) for N in (4, 6) for ch in (1, -1)]
    pairs += [(adjoint_rep(N), irrep(N, (1, 1) + (0,) * (N // 2 - 2))) for N in (5, 6, 7)]
    pairs += [(harmonic_rep(5, l), irrep(5, (l, 0))) for l in range(0, 4)]
    pairs += [(harmonic_rep(3, 2), irrep(3, (2,))), (harmonic_rep(4, 2), irrep(4, (2, 0)))]
    for a, b in pairs:
        T = intertwiner(a, b)
        assert np.abs(T.conj().T @ T - np.eye(a.dim)).max() <= 1e-10  # unitary (both orthonormal bases)
        for p in a.planes:
            res = T @ a.generator(p, format="dense") - b.generator(p, format="dense") @ T
            assert np.abs(res).max() <= 1e-10


@pytest.mark.parametrize("l", [4, 5])
def test_harmonic_rep_so5_equivalent_to_irrep(l):
    a, b = harmonic_rep(5, l), irrep(5, (l, 0))
    assert a.dim == b.dim == harmonic_dimension(5, l) == (l + 1) * (l + 2) * (2 * l + 3) // 6
    assert a.casimir_value() == b.casimir_value() == l * (l + 3)
    assert abs(a.casimir(format="dense") + l * (l + 3) * np.eye(a.dim)).max() <= scaled_tol(l * (l + 3), dim=a.dim, k=4 * len(a.planes))
    assert a.weight_multiplicities() == b.weight_multiplicities()
    T = intertwiner(a, b)
    for p in a.planes:
        assert np.abs(T @ a.generator(p, format="dense") - b.generator(p, format="dense") @ T).max() <= 1e-10


def test_inequivalent_reps_rejected():
    with pytest.raises(ValueError, match="not equivalent"):
        intertwiner(spinor_rep(6, 1), irrep(6, (H, H, -H)))
    with pytest.raises(ValueError, match="dimensions differ"):
        intertwiner(vector_rep(5), spinor_rep(5))
    with pytest.raises(ValueError, match="not irreducible"):
        intertwiner(spinor_rep(6), spinor_rep(6))
    with pytest.raises(ValueError, match="different so"):
        intertwiner(vector_rep(5), vector_rep(4))


def test_exact_generators_of_constructors():
    for rep in [adjoint_rep(4), spinor_rep(6, -1), harmonic_rep(5, 2), harmonic_rep(3, 2),
                tensor(spinor_rep(3), vector_rep(3)), direct_sum(vector_rep(4), spinor_rep(4, 1))]:
        G = rep.generators(exact=True)
        for p in rep.planes:
            num = np.array(G[p].evalf(30), dtype=complex)
            assert np.abs(num - rep.generator(p, format="dense")).max() <= scaled_tol(num)
    # exact harmonic generators are exactly antisymmetric and satisfy [X12, X23] = X13
    G = harmonic_rep(4, 2).generators(exact=True)
    assert (G[(1, 2)] + G[(1, 2)].T).is_zero_matrix
    assert (G[(1, 2)] * G[(2, 3)] - G[(2, 3)] * G[(1, 2)] - G[(1, 3)]).applyfunc(sp.expand).is_zero_matrix


def test_to_qobj():
    rep = irrep(5, (1, 1))
    q = rep.to_qobj((2, 3), form="hermitian", hbar=0.5)
    assert isinstance(q, qutip.Qobj) and q.dims == [[10], [10]] and q.isherm
    np.testing.assert_allclose(q.full(), rep.generator((2, 3), form="hermitian", hbar=0.5, format="dense"), rtol=0, atol=0)
    allq = rep.to_qobj(form="hermitian")
    assert list(allq) == list(planes(5))
    # Casimir from QuTiP operators: sum L^2 = c for hbar = 1
    cas = sum(L * L for L in allq.values())
    np.testing.assert_allclose(cas.full(), 6 * np.eye(10), atol=scaled_tol(len(allq) * 6.0, dim=10), rtol=0)
    qa = rep.to_qobj((1, 2), form="antihermitian")
    np.testing.assert_allclose(qa.full(), rep.generator((1, 2), format="dense"), atol=0, rtol=0)


def test_cartan_and_ladders_vector():
    rep = vector_rep(5)
    Hs = rep.cartan_generators(form="hermitian", format="dense")
    assert len(Hs) == 2
    for root, E in rep.ladder_operators(format="dense").items():
        for k, Hk in enumerate(Hs):
            assert np.abs(Hk @ E - E @ Hk - root[k] * E).max() <= scaled_tol(norm(Hk) * norm(E))
        assert np.abs(E).max() > 0


def test_bad_input():
    with pytest.raises(ValueError, match="chirality"):
        spinor_rep(5, 1)
    with pytest.raises(ValueError, match="chirality"):
        spinor_rep(6, 2)
    with pytest.raises(ValueError, match="different so"):
        tensor(vector_rep(5), vector_rep(4))
    with pytest.raises(ValueError, match="different so"):
        direct_sum(vector_rep(5), vector_rep(4))
    with pytest.raises(TypeError, match="Representation"):
        direct_sum(vector_rep(5), np.eye(5))
    with pytest.raises(ValueError, match="at least one"):
        direct_sum()
    with pytest.raises(ValueError, match="degree"):
        harmonic_rep(5, -1)
    with pytest.raises(ValueError, match="N must be an integer >= 2"):
        vector_rep(1)
    with pytest.raises(ValueError, match="unknown plane"):
        vector_rep(4).generator((4, 5))
    with pytest.raises(ValueError, match="format"):
        vector_rep(4).generators(format="lil")
    with pytest.raises(ValueError, match="missing"):
        Representation(3, {(1, 2): np.zeros((2, 2))})
    with pytest.raises(ValueError, match="no exact"):
        Representation(2, {(1, 2): np.zeros((1, 1))}).generator((1, 2), exact=True)
    # chirality: 1.0 failed in a format string, True is not +1
    for bad in (1.0, True, "1"):
        with pytest.raises(TypeError, match=r"chirality \(None, \+1 or -1\) must be an integer"):
            spinor_rep(4, bad)
    # generator matrices: text reached scipy, NaN was accepted, exact_generators=5 failed at first use
    P = [(1, 2), (1, 3), (2, 3)]
    with pytest.raises(TypeError, match=r"generator of plane \(1, 2\) must be a qutip.Qobj"):
        Representation(3, {p: "a" for p in P})
    with pytest.raises(ValueError, match=r"generator of plane \(1, 2\) must be finite"):
        Representation(3, {p: np.full((2, 2), np.nan) for p in P})
    with pytest.raises(ValueError, match=r"generator of plane \(1, 2\) must be a finite numeric matrix"):
        Representation(3, {p: sps.csr_matrix(np.full((2, 2), np.inf)) for p in P})
    with pytest.raises(TypeError, match="exact_generators must be None, a mapping"):
        Representation(3, {p: np.zeros((2, 2)) for p in P}, exact_generators=5)
    vec = vector_rep(3)
    as_lists = Representation(3, {p: vec.generator(p, format="dense").tolist() for p in P})
    assert as_lists == Representation(3, {p: vec.generator(p) for p in P})  # nested lists: as before


def test_ladder_refuses_what_is_not_a_root():
    """A root with non-integer entries was truncated (1.9 -> 1) and gave another root's operator silently."""
    rep = irrep(5, (1, 1))
    for bad in ((1.9, -1.2), (True, False)):
        with pytest.raises(TypeError, match=r"root\[0\] must be an integer"):
            rep.ladder(bad)
    for bad in ("a", 1):
        with pytest.raises(TypeError, match=r"root must be a sequence of 2 integers"):
            rep.ladder(bad)
    with pytest.raises(ValueError, match=r"\(1, -1, 0\) is not a root of so\(5\)"):
        rep.ladder((1, -1, 0))
    E = rep.ladder(np.array([1, -1]))  # NumPy integers are integers
    assert (E != rep.ladder((1, -1))).nnz == 0


@pytest.mark.parametrize(
    "N, m",
    [(3, (1,)), (3, (2,)), (4, (1, 1)), (5, (1, 0)), (5, (2, 1)), (6, (1, 1, 0)), (7, (H, H, H)), (8, (H, H, H, H)), (8, (H, H, H, -H))],
    ids=str,
)
def test_real_form_of_real_irreps(N, m):
    rep = irrep(N, m)
    assert not rep.is_real
    R = real_form(rep)
    assert R.is_real and R.highest_weight == rep.highest_weight
    C = structure_constants(N)
    pl = planes(N)
    G = R.generators(format="dense")
    for p in pl:
        assert G[p].dtype == np.float64 and np.abs(G[p] + G[p].T).max() <= scaled_tol(G[p])
    for a, pa in enumerate(pl):
        for b, pb in enumerate(pl):
            rhs = sum(int(C[a, b, c]) * G[pl[c]] for c in np.nonzero(C[a, b])[0]) if C[a, b].any() else 0
            assert np.abs(G[pa] @ G[pb] - G[pb] @ G[pa] - rhs).max() <= scaled_tol(norm(G[pa]) * norm(G[pb]), k=8)
    assert R.weight_multiplicities() == weight_multiplicities(N, m)


def test_real_form_rejects_complex_and_quaternionic():
    with pytest.raises(ValueError, match="quaternionic"):
        real_form(irrep(3, (H,)))
    with pytest.raises(ValueError, match="quaternionic"):
        real_form(spinor_rep(5))
    with pytest.raises(ValueError, match="no real form"):
        real_form(irrep(6, (1, 1, 1)))  # conjugate irrep is (1, 1, -1)
    with pytest.raises(TypeError, match="Representation"):
        real_form(np.eye(3))
    v = vector_rep(4)
    assert real_form(v) is v


# ----------------------------------------------------------------------------
# results travel (#21 §4): pickle and deepcopy, equal round trips
# ----------------------------------------------------------------------------
@pytest.mark.parametrize("make", [
    lambda: irrep(5, (1, 1)), lambda: irrep(3, (H,)), lambda: harmonic_rep(4, 2), lambda: spinor_rep(6, 1),
    lambda: tensor(vector_rep(3), spinor_rep(3)), lambda: direct_sum(vector_rep(4), adjoint_rep(4)),
    lambda: real_form(irrep(3, (1,))),
], ids=["irrep", "spin1/2", "harmonic", "chiral-spinor", "tensor", "direct_sum", "real_form"])
def test_representations_pickle_and_deepcopy(make):
    import copy
    import pickle

    from hyperrotor.quantum.hamiltonian import rotor_hamiltonian

    rep = make()
    for back in (pickle.loads(pickle.dumps(rep)), copy.deepcopy(rep)):
        assert back == rep and back is not rep
        assert back.highest_weight == rep.highest_weight and back.name == rep.name
        if rep.has_exact_generators:  # the on-demand recipe travels too (no closure)
            assert back.generator((1, 2), exact=True) == rep.generator((1, 2), exact=True)
    # a changed generator is noticed
    other = Representation(rep.N, {p: (2 * M if p == (1, 2) else M) for p, M in rep.generators().items()},
                           highest_weight=rep.highest_weight, name=rep.name)
    assert other != rep
    H = rotor_hamiltonian(rep, np.linspace(1.0, 2.0, rep.N * (rep.N - 1) // 2))
    H2 = pickle.loads(pickle.dumps(H))
    assert H2 == H and H2._hyperrotor_rep == rep  # the sectors of spectrum/evolve still find the representation


def test_checking_generators_never_changes_them():
    """as_csr returns a canonical copy: checking a non-canonical generator whose data is complex with
    zero imaginary part (its real part shared the caller's index arrays, and scipy canonicalizes in
    place) scrambled the caller's matrix; rotor_hamiltonian of irrep (8, 0)'s generators changed by 0.2."""
    from hyperrotor.quantum import rotor_hamiltonian
    from hyperrotor.quantum.operator_input import as_csr, check_antihermitian

    # a non-canonical complex matrix with zero imaginary part: unsorted column indices in row 0
    M = sps.csr_matrix((np.array([2.0, 1.0, -1.0, -2.0], dtype=complex), np.array([2, 1, 0, 0]),
                        np.array([0, 2, 3, 4])), shape=(3, 3))
    M.has_sorted_indices = False
    dense = M.toarray()
    X = as_csr(M, "M")
    X.max(), abs(X).max()  # canonicalizing the result in place (scipy does) ...
    np.testing.assert_array_equal(M.toarray(), dense)  # ... leaves the caller's matrix alone
    assert X.has_canonical_format and not np.shares_memory(X.indices, M.indices)
    rep = irrep(5, (8, 0))
    gens = rep.generators(format="csr")
    before = {p: G.toarray() for p, G in gens.items()}
    moments = np.linspace(1.0, 2.0, 10)
    H_rep = rotor_hamiltonian(rep, moments).full()
    check_antihermitian(gens)
    H_map = rotor_hamiltonian(gens, moments).full()  # the mapping path checks them too
    for p, G in gens.items():
        np.testing.assert_array_equal(G.toarray(), before[p])
        np.testing.assert_array_equal(rep.generators(format="csr")[p].toarray(), before[p])
    np.testing.assert_allclose(H_map, H_rep, rtol=0, atol=1e-12 * np.abs(H_rep).max())
