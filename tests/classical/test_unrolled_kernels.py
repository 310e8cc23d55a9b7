"""The splitting kernels unrolled per dimension (``solvers/_unrolled.py``): the generic kernels' numbers to the bit."""
import numpy as np
import pytest

from hyperrotor import simulate
from hyperrotor._jit import JIT_ENABLED
from hyperrotor.classical.solvers import _kernels, _unrolled
from hyperrotor.classical.solvers.splitting import splitting_slots, splitting_word

needs_jit = pytest.mark.skipif(not JIT_ENABLED, reason="numba disabled: the generic kernels run")


def _random_case(rng, N, B):
    """Rates with some planes switched off for every row (as the Casimir shift does) and others for one row
    only, a start with low parts (a chunk continuing a compensated run), output intervals of different
    steps, angles beyond the polynomial range of the sines included (plain storage keeps the low parts as they
    are and adds them to every output, as the generic kernel does)."""
    n = N * (N - 1) // 2
    rates = rng.uniform(-2.0, 2.0, size=(B, n))
    off = rng.random(n) < 0.3
    rates[:, off] = 0.0
    rates[0, rng.integers(n)] = 0.0
    seq = tuple(int(a) for a in np.flatnonzero(np.any(rates != 0.0, axis=0)))
    L0 = rng.normal(size=(B, n)) * np.where(rng.random((B, 1)) < 0.3, 40.0, 1.0)
    carry = np.zeros((B, 2, n))
    carry[:, 1] = rng.normal(size=(B, n)) * 1e-17
    nsub = rng.integers(1, 6, size=4)
    hstep = rng.uniform(0.01, 0.3, size=4)
    return rates, seq, L0, carry, nsub, hstep


@needs_jit
@pytest.mark.parametrize("N", [3, 4, 5])
def test_unrolled_kernel_equals_the_generic_kernel_bit_for_bit(N, rng):
    compensated = False
    run = _unrolled.kernel(N, compensated)
    assert run is not None  # JIT on, a writable cache folder, N <= MAX_UNROLLED_N
    assert _unrolled.kernel(N, compensated=True) is None  # (compensated storage: the generic kernel)
    tables = _kernels.rotation_tables(N)
    for order in (2, 4, 8, 10):
        rates, seq, L0, carry, nsub, hstep = _random_case(rng, N, B=3)
        word = splitting_word(order, seq)
        K = nsub.size + 1
        a, ca = np.empty((3, K, L0.shape[1])), carry.copy()
        _kernels.split_run_serial(L0, rates, *word, *tables, hstep, nsub, np.zeros_like(L0), np.zeros((1, N, N)),
                                  False, compensated, a, np.empty((3, 1, N, N)), ca)
        b, cb = np.empty_like(a), carry.copy()
        run(L0, cb, rates, *splitting_slots(N, order, seq), hstep, nsub, b)
        np.testing.assert_array_equal(b, a)
        np.testing.assert_array_equal(cb, ca)  # the exact last state: a chunked run continues identically
        # the pair kernel (the step control's probes and companions): the same two runs in one call
        nsub2 = 2 * nsub
        a2, ca2 = np.empty_like(a), carry.copy()
        _kernels.split_run_serial(L0[::-1].copy(), rates, *word, *tables, hstep / 2, nsub2, np.zeros_like(L0),
                                  np.zeros((1, N, N)), False, compensated, a2, np.empty((3, 1, N, N)), ca2)
        pa, pb, qa, qb = np.empty_like(a), np.empty_like(a), carry.copy(), carry.copy()
        _unrolled.kernel(N, compensated, pair=True)(L0, qa, L0[::-1].copy(), qb, rates, *splitting_slots(N, order, seq),
                                                     hstep, nsub, hstep / 2, nsub2, pa, pb)
        for got, want in ((pa, a), (qa, ca), (pb, a2), (qb, ca2)):
            np.testing.assert_array_equal(got, want)


@pytest.mark.parametrize("N", [3, 5, 7])
def test_slot_table_lays_out_the_word_in_order(N, rng):
    """Read slot by slot, the non-zero slots are the word's flows (plane and fraction of h), in its order."""
    n = N * (N - 1) // 2
    for order in (2, 6, 10):
        for seq in (tuple(range(n)), tuple(sorted(rng.choice(n, size=max(1, n // 2), replace=False).tolist()))):
            planes_, coefs = splitting_word(order, seq)
            slot_coef, slot_plane = _unrolled.slot_table(N, planes_, coefs)
            assert slot_plane.tolist() == list(range(n)) + list(range(n - 2, -1, -1))
            nz = slot_coef.ravel() != 0.0
            np.testing.assert_array_equal(np.tile(slot_plane, slot_coef.shape[0])[nz], planes_)
            np.testing.assert_array_equal(slot_coef.ravel()[nz], coefs)
    assert _unrolled.slot_table(N, *splitting_word(4, tuple(range(n)), kick=True)) is None  # torque kicks
    assert _unrolled.slot_table(N, np.zeros(0, dtype=np.int64), np.zeros(0)) is None  # no plane left


def test_no_unrolled_kernel_without_a_writable_folder_or_beyond_the_largest_dimension(tmp_path, monkeypatch):
    _unrolled._module.cache_clear()
    try:
        blocker = tmp_path / "file"
        blocker.write_text("")
        monkeypatch.setenv("HYPERROTOR_CACHE_DIR", str(blocker))  # a file: no folder can be made inside
        assert _unrolled.kernel(5, False) is None
        monkeypatch.setenv("HYPERROTOR_CACHE_DIR", str(tmp_path / "cache"))
        assert _unrolled.kernel(_unrolled.MAX_UNROLLED_N + 1, False) is None
        if JIT_ENABLED:
            assert _unrolled.kernel(3, False) is not None
            written = list((tmp_path / "cache" / "unrolled").glob("hyperrotor_unrolled_so3_*.py"))
            assert len(written) == 1 and written[0].read_text() == _unrolled.source(3)
            written[0].write_text(_unrolled.source(3) + "raise RuntimeError('not ours')\n")  # damaged or edited
            _unrolled._module.cache_clear()
            assert _unrolled.kernel(3, False) is not None  # (the file is written again before it is imported)
            assert written[0].read_text() == _unrolled.source(3)
    finally:
        _unrolled._module.cache_clear()


@needs_jit
def test_a_new_kernels_module_gives_a_new_unrolled_module(tmp_path, monkeypatch):
    """The generated code inlines _kernels.rotation, and numba's cache looks at the generated file only: the
    file's name carries a hash of _kernels.py, so a changed rotation() is compiled in, never an old one from the
    cache (the unrolled and generic kernels parted in the last bits after rotation() changed); an unreadable
    _kernels.py gives the generic kernels."""
    monkeypatch.setenv("HYPERROTOR_CACHE_DIR", str(tmp_path / "cache"))
    _unrolled._module.cache_clear()
    try:
        first = _unrolled._module(3).__name__
        monkeypatch.setattr(_unrolled, "_inlined_digest", lambda: "another rotation()")
        _unrolled._module.cache_clear()
        second = _unrolled._module(3).__name__
        assert first != second and first.rsplit("_", 1)[0] == second.rsplit("_", 1)[0]
        monkeypatch.setattr(_unrolled, "_inlined_digest", lambda: None)
        _unrolled._module.cache_clear()
        assert _unrolled.kernel(3, False) is None
    finally:
        _unrolled._module.cache_clear()


@needs_jit
@pytest.mark.parametrize("kwargs", [dict(dt=0.04), dict(rtol=1e-7), dict(rtol=1e-12)], ids=["dt", "rtol", "rtol-comp"])
def test_simulate_runs_the_unrolled_kernel_with_the_generic_numbers(kwargs, rng, monkeypatch):
    """One body and a small ensemble, fixed step and step control (probe and check companions included): the
    unrolled kernel runs (for plain storage: at rtol 1e-12 only the probe's plain runs), and switching it off
    gives the same trajectory, steps and work bit for bit."""
    moments = np.exp(rng.uniform(np.log(0.3), np.log(3.0), 10))
    w0 = rng.normal(size=(3, 10)) * 0.5
    t = np.linspace(0.0, 4.0, 9)
    calls = []
    kernel = _unrolled.kernel

    def spy(N, compensated, pair=False):
        run = kernel(N, compensated, pair)
        return None if run is None else lambda *a: (calls.append(run), run(*a))[1]

    for w in (w0[0], w0):
        monkeypatch.setattr(_unrolled, "kernel", spy)
        a = simulate(moments, w, t, method="splitting8", **kwargs)
        assert calls and a.stats["compensated"] == (kwargs.get("rtol") == 1e-12)  # (compensated below rtol 1e-11)
        monkeypatch.setattr(_unrolled, "kernel", lambda N, compensated, pair=False: None)
        b = simulate(moments, w, t, method="splitting8", **kwargs)
        np.testing.assert_array_equal(a.L, b.L)
        assert (a.stats["steps"], a.stats["work"]) == (b.stats["steps"], b.stats["work"])
        calls.clear()
