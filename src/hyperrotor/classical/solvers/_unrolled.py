r"""Splitting kernels unrolled for one dimension ``N``: ``L`` in registers (private).

The generic kernels of :mod:`._kernels` keep ``L`` in an array and look each flow's plane and
component pairs up in tables at run time, so every flow stores its rotated components and the
next flow loads them back, and the compiler cannot schedule across flows. For a given ``N``
the sweep of Strang's method over the planes is a fixed straight line of code: this module
writes it out (one local variable per component of ``L``, constant component pairs and signs)
and compiles it with numba. Same arithmetic as :func:`._kernels._split_run` flow by flow (the
same :func:`._kernels.rotation`, the same expressions in the same order), so the results agree
to the last bit (tested). Plain storage only (compensated: see :func:`kernel`). Whole ``simulate`` calls, the two
kernels in turn in one process (``benchmarks/unrolled_kernels.py``): 1.1-1.25x faster, the most on long runs
(1e4 steps: 1.18-1.25x), the least on short ones, where Python's share is larger (the kernel alone, called back to
back: 1.3-1.45x on the generic 5D body).

A step's word of flows (:func:`.splitting.splitting_word`) is laid onto *slots*: row ``r`` of
:func:`slot_table` is one sweep over all ``n`` planes forward and ``n - 1`` back, each slot a
plane and a fraction of ``h`` (0: no flow, skipped by a branch that goes the same way at every step).
So one compiled function per ``N`` serves every order, every set of planes the Casimir shift
leaves and every body (and ``run_pair``, two such runs in one call for the step control's probes and
companions: one dispatch from Python instead of two, 0.6 s more of cold compile for ``N = 5``). Words with
torque kicks, runs with attitude and ensembles of ``PARALLEL_MIN_BODIES`` or more bodies keep the generic
kernels (an unrolled attitude, ``N^2`` more locals passed through every flow, made 5D runs 1.9x and 3D runs 1.4x
slower: tried and dropped).

The generated module is written once into a cache folder (``$HYPERROTOR_CACHE_DIR``, else
``$XDG_CACHE_HOME/hyperrotor`` or ``~/.cache/hyperrotor``), its name carrying a hash of its
source, so numba caches its compiled code on disk like the package's own kernels (a first call
for an ``N`` compiles for a few seconds, later processes load it). Without a writable folder (or
with one that others could write: :func:`_folder`), with ``HYPERROTOR_DISABLE_JIT=1`` or
``HYPERROTOR_DISABLE_CACHE=1``, or beyond ``MAX_UNROLLED_N``, :func:`kernel` returns ``None``
and the generic kernels run (the same numbers, only slower).
"""
from __future__ import annotations

import hashlib
import importlib.util
import os
import stat
import sys
import tempfile
from functools import lru_cache
from pathlib import Path

import numpy as np

from hyperrotor import _jit
from hyperrotor._warn import warn

__all__: list[str] = []  # private module

#: dimensions up to this one get unrolled kernels (the paper's; the code grows like N^3 and so does its cold
#: compile: N = 5 takes 2.8 s, N = 6 4.1 s)
MAX_UNROLLED_N = 5


def sweep_planes(n: int) -> list[int]:
    """The planes of one slot row: Strang's sweep over all ``n`` planes forward and back (the order of
    :func:`.splitting.splitting_word`)."""
    return list(range(n)) + list(range(n - 2, -1, -1))


def slot_table(N: int, planes_: np.ndarray, coefs: np.ndarray):
    """``(slot_coef (R, 2n - 1), slot_plane (2n - 1,))`` laying the word ``(planes_, coefs)`` onto sweeps,
    or ``None`` when it is not a sequence of plane flows in sweep order (a torque kick ``-1``)."""
    n = N * (N - 1) // 2
    if n == 0 or planes_.size == 0 or np.any(planes_ < 0):
        return None
    slot_plane = np.array(sweep_planes(n), dtype=np.int64)
    W = slot_plane.size
    rows: list[np.ndarray] = []
    pos = W  # slot index in the current row (W: start a new row)
    for a, c in zip(planes_.tolist(), coefs.tolist()):
        for _ in range(2 * W + 1):  # a plane appears in every row: the next slot of plane a is within two rows
            if pos == W:
                rows.append(np.zeros(W))
                pos = 0
            if slot_plane[pos] == a:
                break
            pos += 1
        else:  # pragma: no cover - every plane index < n has a slot in each row
            return None
        rows[-1][pos] = c
        pos += 1
    slot_coef = np.array(rows)
    slot_coef.setflags(write=False)
    slot_plane.setflags(write=False)
    return slot_coef, slot_plane


def _flow_function(npair: int) -> list[str]:
    """``flow(x, ua, g_0..g_{npair-1}, x_0, y_0, x_1, y_1, ...)``: one plane's exact flow.

    ``x`` is the half-angle per unit momentum, ``ua`` the plane's momentum, ``g_e`` the signs of
    :func:`._kernels.rotation_tables` and ``x_e, y_e`` the component pairs it rotates; returns the rotated
    pairs. The arithmetic of :func:`._kernels._split_run` (plain storage), expression for expression."""
    g = [f"g{e}" for e in range(npair)]
    pairs = [f"x{e}, y{e}" for e in range(npair)]
    lines = ["", "", "@jit", f"def flow(x, ua, {', '.join(g + pairs)}):",
             "    s, v = rotation(x * ua)"]
    for e in range(npair):
        lines += [f"    ss = s * g{e}",
                  f"    x{e}, y{e} = x{e} + (ss * y{e} - v * x{e}), y{e} - (ss * x{e} + v * y{e})"]
    return lines + [f"    return {', '.join(pairs)}"]


def source(N: int) -> str:
    """The module text of the unrolled kernel for ``N``."""
    from ._kernels import rotation_tables

    pair_p, pair_q, pair_s, _, _ = rotation_tables(N)
    n, npair = N * (N - 1) // 2, N - 2
    slots = sweep_planes(n)
    text = [f'"""Unrolled splitting kernel for so({N}), written by hyperrotor.classical.solvers._unrolled."""',
            "import numpy as np",
            "from hyperrotor._jit import jit",
            "from hyperrotor.classical.solvers._kernels import rotation"]
    text += _flow_function(npair)
    text += ["", "", "@jit", "def run(L0, carry, rates, slot_coef, slot_plane, hstep, nsub, outL):",
             "    B = L0.shape[0]", "    K = hstep.shape[0] + 1", "    R = slot_coef.shape[0]",
             f"    W = {len(slots)}", "    f = np.empty((R, W))", "    for b in range(B):"]
    text += [f"        u{a} = L0[b, {a}]" for a in range(n)]
    text += [f"        l{a} = carry[b, 1, {a}]" for a in range(n)]  # (a start's low parts, kept: plain storage)
    text += [f"        outL[b, 0, {a}] = u{a} + l{a}" for a in range(n)]
    text += ["        for k in range(K - 1):", "            h = hstep[k]",
             "            for r in range(R):", "                for w in range(W):",
             "                    f[r, w] = 0.5 * slot_coef[r, w] * h * rates[b, slot_plane[w]]",
             "            for _ in range(nsub[k]):", "                for r in range(R):"]
    for w, a in enumerate(slots):
        signs = [repr(float(pair_s[a, e])) for e in range(npair)]
        args = ", ".join(f"u{int(pair_p[a, e])}, u{int(pair_q[a, e])}" for e in range(npair))
        text += [f"                    if slot_coef[r, {w}] != 0.0:", f"                        x = f[r, {w}]",
                 f"                        {args} = flow(x, u{a}, {', '.join(signs)}, {args})"]
    text += [f"            outL[b, k + 1, {a}] = u{a} + l{a}" for a in range(n)]
    text += [f"        carry[b, 0, {a}] = u{a}" for a in range(n)]
    text += [f"        carry[b, 1, {a}] = l{a}" for a in range(n)]
    text += ["", "", "@jit",
             "def run_pair(L0a, carry_a, L0b, carry_b, rates, slot_coef, slot_plane, ha, na, hb, nb, outa, outb):",
             "    run(L0a, carry_a, rates, slot_coef, slot_plane, ha, na, outa)",
             "    run(L0b, carry_b, rates, slot_coef, slot_plane, hb, nb, outb)"]
    return "\n".join(text) + "\n"


#: the folders refused in this process (one warning each)
_refused: set[str] = set()


def _folder() -> Path | None:
    """The folder of the generated modules, ``unrolled`` in the cache root, if it is safe to load code from.

    Returns
    -------
    pathlib.Path or None
        The folder, or ``None``: the caller runs the generic kernels (the same numbers, slower).

    Notes
    -----
    Python imports the modules written here and numba unpickles the index files of its cache next to
    them: whoever can write this folder can run code in every process that uses it. So:

    * missing folders (``unrolled``, the cache root and its missing parents) are created with mode
      ``0o700``, as the XDG base directory specification asks;
    * an existing ``unrolled`` is used only if it is a folder, not a symbolic link, owned by the
      effective user (the one that creates the folder and runs the code) and writable by neither its
      group nor others. Otherwise ``None`` and one ``UserWarning`` per folder and process, naming the
      folder and the reason: the unrolled kernel is a speed-up, so a run goes on without it, but a
      refused folder may have been tampered with and the slower runs need an explanation. The folder
      is neither tightened nor emptied (what it holds cannot be trusted): remove it (it is created
      again, private) or point ``HYPERROTOR_CACHE_DIR`` at a folder of your own;
    * a folder that cannot be created or written (a read-only installation) gives ``None`` silently.

    Windows has no ``os.geteuid`` and its permission bits only mirror the read-only attribute: there,
    only the symbolic link is refused.
    """
    root = os.environ.get("HYPERROTOR_CACHE_DIR") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache"), "hyperrotor")
    folder = Path(root) / "unrolled"
    try:
        for part in reversed((folder, *folder.parents)):  # (Path.mkdir(parents=True) ignores mode for parents)
            if not part.exists():
                try:
                    part.mkdir(mode=0o700)
                except FileExistsError:  # (made by a process starting together, or a dangling link)
                    pass
        st = os.lstat(folder)
    except OSError:
        return None
    reason = None
    if stat.S_ISLNK(st.st_mode):
        reason = "it is a symbolic link"
    elif not stat.S_ISDIR(st.st_mode):
        return None
    elif hasattr(os, "geteuid") and st.st_uid != os.geteuid():
        reason = f"it is owned by user id {st.st_uid}, not by this user ({os.geteuid()})"
    elif hasattr(os, "geteuid") and st.st_mode & (stat.S_IWGRP | stat.S_IWOTH):
        reason = f"its group or other users can write it (mode {oct(stat.S_IMODE(st.st_mode))})"
    if reason is not None:
        if str(folder) not in _refused:
            _refused.add(str(folder))
            warn(f"hyperrotor does not use the kernel cache folder {folder}: {reason}, and Python and numba "
                 "load code from it. The generic kernels run (the same numbers, slower). Remove the folder "
                 "(it is created again, private) or set HYPERROTOR_CACHE_DIR to a folder of your own.")
        return None
    return folder if os.access(folder, os.W_OK) else None


def _inlined_digest() -> str | None:
    """Hash of the text of :mod:`._kernels`, whose :func:`~._kernels.rotation` the generated code inlines
    (``None`` if it cannot be read: no unrolled kernel then, the generic ones give the same numbers)."""
    from . import _kernels

    try:
        return hashlib.sha256(Path(_kernels.__file__).read_bytes()).hexdigest()
    except (OSError, TypeError):
        return None


@lru_cache(maxsize=None)
def _module(N: int):
    """The generated module for ``N`` (written once, named by its content's hash), or ``None``."""
    if not (_jit.JIT_ENABLED and _jit.CACHE_ENABLED) or not 3 <= N <= MAX_UNROLLED_N:
        return None
    folder = _folder()
    if folder is None:
        return None
    text = source(N)
    # one file per text, per text of the module it inlines from (numba's cache sees only the generated file: a new
    # rotation() in _kernels.py left the old one compiled in, while the generic kernels had the new one) and per
    # numba and Python (environments sharing the folder do not invalidate each other's compiled code)
    inlined = _inlined_digest()
    if inlined is None:
        return None
    digest = hashlib.sha256(f"{text}{inlined}{_jit.NUMBA_VERSION}{sys.version}".encode()).hexdigest()[:16]
    name = f"hyperrotor_unrolled_so{N}_{digest}"
    path = folder / f"{name}.py"
    try:
        # written atomically (processes starting together write the same text); a file whose text is not this
        # one (damaged, edited) is written again: only the text generated here is ever executed
        if not path.exists() or path.read_text() != text:
            fd, tmp = tempfile.mkstemp(dir=folder, suffix=".tmp")
            try:
                with os.fdopen(fd, "w") as fh:
                    fh.write(text)
                os.replace(tmp, path)
            finally:  # (a failed write, e.g. a full disk, leaves no temporary file behind)
                if os.path.exists(tmp):
                    os.remove(tmp)
        spec = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module  # numba's cache locator looks the module up by name
        spec.loader.exec_module(module)
    except (OSError, UnicodeDecodeError):
        return None
    return module


def kernel(N: int, compensated: bool, pair: bool = False):
    """The unrolled run of ``N`` for plain storage, or ``None`` (the generic kernels: compensated storage, JIT or
    cache off, no writable folder, ``N`` out of range).

    Signature ``run(L0, carry, rates, slot_coef, slot_plane, hstep, nsub, outL)``: as
    :func:`._kernels._split_run` without torque and attitude (``carry`` holds the start's low parts on
    entry and the last state on exit). ``pair``: ``run_pair(L0a, carry_a, L0b, carry_b, rates, slot_coef,
    slot_plane, ha, na, hb, nb, outa, outb)``, two runs of the same rows in one compiled call (the step control's
    probes and companions: one dispatch from Python instead of two). Compensated storage was unrolled too and
    dropped: its TwoSum doubles the locals and the code, and whole runs were 0.92-1.01x as fast as with the generic
    kernel."""
    if compensated:
        return None
    module = _module(N)
    return None if module is None else (module.run_pair if pair else module.run)
