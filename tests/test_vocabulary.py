"""Every public signature against the one table of spellings (docs/conventions.md, "Vocabulary").

The walk covers every public callable of ``hyperrotor``, ``hyperrotor.quantum``,
``hyperrotor.paper``, ``hyperrotor.demo``, ``hyperrotor.bench`` and ``hyperrotor.plotting`` and the
public methods of their public classes, so a new public name is checked the day it is added (a
review found ``compare_quartet_motion(progress=False)``, a ``progress`` callback in ``bench`` and a
positional ``format`` in ``paper.render`` outside the first three). It asserts what ``inspect`` can see:

* no old spelling of a concept as a parameter name (``seed``, ``Omega``, ``times``, ...);
* no ``**kwargs`` catch-all or ``*args`` trap that hides the real signature (the few
  legitimate ones are listed below with their reason);
* ``convention`` always keyword-only; everything after ``t`` keyword-only in
  ``simulate`` and ``evolve``;
* ``hbar`` defaults to the exact 1; ``rtol``/``atol`` default to ``None`` (the named
  entries of ``hyperrotor.options``), never to a number in the signature;
* ``progress`` and ``format`` keyword-only, ``progress`` defaulting to ``None`` (a bar on a terminal) and never a
  function (``callback``); ``rng`` defaulting to the seed 0.
"""
from __future__ import annotations

import inspect

import pytest

import hyperrotor as hr
from hyperrotor import quantum as hq

#: Old spellings and the spelling of the table that replaces them.
OLD_SPELLINGS = {
    "seed": "rng",
    "Omega": "omega0",
    "times": "t",
    "tlist": "t",
    "tol": "rtol/atol",
    "dense": "format",
    "parallel": "workers/client",
    "hermitian": "form",
    "generators": "rep",
    "representation": "rep",
    "inertia": "body",
    "moments3": "body",
}

#: Parameters that legitimately keep a name of the list above, with the reason.
OWN_NAMES = {
    ("RigidBody", "inertia"): "RigidBody(inertia): the constructor names its own input",
    ("Representation", "generators"): "the constructor takes the generator mapping itself",
    ("Representation.from_qobj", "generators"): "a mapping plane -> Qobj, not a Representation",
    ("check_antihermitian", "generators"): "a mapping plane -> matrix, not a Representation",
    ("Trajectory", "dense"): "the dense-output interpolant of the run, not a storage format",
}

#: ``*args`` / ``**kwargs`` that are the point of the function, with the reason.
VARIADIC_ALLOWED = {
    "direct_sum": "direct_sum(*reps): any number of representations",
    "PoincareSection.coordinates": "coordinates(*planes): any number of planes",
    "Inertia.subs": "Inertia.subs(*args, **kwargs): SymPy's own subs signature, passed on",
    "options": "hr.options(**changes): option names are the table's keys",
    "plane_symbols": "plane_symbols(..., **assumptions): SymPy assumptions, passed to Symbol",
    "Solver": "Solver(**options): each solver's documented option table (checked by the solver)",
    "Propagator": "Propagator(**opts): each propagator's documented option table (checked)",
    "plot_poincare": "plot_poincare(..., **scatter_options): matplotlib scatter keywords",
    "register": "the option table's register",
}

KEYWORD_ONLY_AFTER_T = ("simulate", "evolve")


def _public_callables():
    seen = {}
    import hyperrotor.bench as hb
    import hyperrotor.demo as hd
    import hyperrotor.paper as hp
    import hyperrotor.plotting as hpl

    modules = [hr, hq, hp, hd, hb, hpl]
    for mod in modules:
        for name in getattr(mod, "__all__", ()):
            obj = getattr(mod, name, None)
            if obj is None or inspect.ismodule(obj) or not callable(obj):
                continue
            if inspect.isclass(obj) and issubclass(obj, BaseException):
                continue  # exceptions take a message
            seen.setdefault(name, obj)
            if inspect.isclass(obj):
                for attr, member in vars(obj).items():
                    if attr.startswith("_"):
                        continue
                    if isinstance(member, (staticmethod, classmethod)):
                        member = member.__func__
                    if inspect.isfunction(member):
                        seen.setdefault(f"{name}.{attr}", member)
    return seen


CALLABLES = _public_callables()


def _signature(obj):
    try:
        return inspect.signature(obj)
    except (TypeError, ValueError):
        return None


def test_the_walk_sees_the_package():
    # guards against a walk that silently covers nothing
    assert {"simulate", "lyapunov", "rotor_hamiltonian", "evolve", "spectrum", "irrep"} <= set(CALLABLES)
    assert len(CALLABLES) > 150


@pytest.mark.parametrize("name", sorted(CALLABLES))
def test_signature_follows_the_vocabulary(name):
    sig = _signature(CALLABLES[name])
    if sig is None:
        pytest.skip(f"{name}: no inspectable signature (a builtin)")
    problems = []
    params = list(sig.parameters.values())
    for p in params:
        if p.name in OLD_SPELLINGS and (name, p.name) not in OWN_NAMES:
            problems.append(f"parameter {p.name!r} is an old spelling; the table says {OLD_SPELLINGS[p.name]!r}")
        if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD) and name not in VARIADIC_ALLOWED:
            star = "*" if p.kind == p.VAR_POSITIONAL else "**"
            problems.append(f"{star}{p.name} hides the signature (list it in VARIADIC_ALLOWED with a reason if it is the point)")
        if p.name == "convention" and p.kind != p.KEYWORD_ONLY:
            problems.append("convention= must be keyword-only")
        if p.name == "hbar" and p.default is not p.empty and not (p.default == 1 and not isinstance(p.default, bool)):
            problems.append(f"hbar defaults to {p.default!r}; the one default is 1")
        if p.name in ("rtol", "atol") and p.default is not p.empty and p.default is not None:
            problems.append(f"{p.name} defaults to {p.default!r} in the signature; use None and a named hr.options entry")
        if p.name in ("progress", "format") and p.kind != p.KEYWORD_ONLY:
            problems.append(f"{p.name}= must be keyword-only")
        if p.name == "progress" and p.default is not p.empty and p.default is not None:
            problems.append(f"progress defaults to {p.default!r}; the one default is None (a bar on a terminal)")
        if p.name == "rng" and p.default is not p.empty and not (p.default == 0 and not isinstance(p.default, bool)):
            problems.append(f"rng defaults to {p.default!r}; the one default is the seed 0 (None: fresh entropy)")
        if p.name == "progress" and "Callable" in str(p.annotation):
            problems.append("progress is a flag (True, False, None); a function called back is callback=")
    if name in KEYWORD_ONLY_AFTER_T:
        names = [p.name for p in params]
        assert "t" in names, f"{name} has no time grid t"
        after = params[names.index("t") + 1:]
        positional = [p.name for p in after if p.kind not in (p.KEYWORD_ONLY, p.VAR_KEYWORD)]
        if positional:
            problems.append(f"everything after t must be keyword-only; positional: {positional}")
    assert not problems, f"{name}{sig}:\n  " + "\n  ".join(problems)


def test_no_renamed_keyword_shims_are_left():
    from hyperrotor import _validate

    assert not hasattr(_validate, "old_keywords"), "the renamed-keyword helper is gone with the shims"
