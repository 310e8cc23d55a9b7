"""No text is ever run as code (issue #21 §1): hostile strings through every public callable and CLI option.

The corpus ``PAYLOADS`` (calls to ``os.system``, ``exec``, ``eval``, a lambda, the class hierarchy,
``__builtins__``, huge powers and literals, very long text) is sent

* through every argument of every public callable that the fuzz table of
  ``tests/property/test_fuzz_entry_points.py`` lists (one good call per public name; each marked
  argument replaced by the payload, and, for array arguments, by a list holding a SymPy symbol and
  the payload: the route on which SymPy used to evaluate strings), and through the methods named in
  issue #21 §1 (``EXTRA``);
* through every option of the command line that takes a value (the parser of
  ``hyperrotor.cli.build_parser()``), with ``main(argv)``.

Each call runs in a fresh temporary directory. Contract: no file appears (the payloads that would
run code create one), the answer comes within ``TIME_LIMIT`` seconds, and it is a ``TypeError`` or a
``ValueError`` (``hyperrotor.ParseError`` is one) from Python, or exit status 2 from the CLI. The
only accepted completions are the arguments listed in ``FREE_TEXT`` (a name or a title is text by
design and is never parsed).
"""
from __future__ import annotations

import argparse
import contextlib
import importlib.util
import io
import os
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from cpu_clock import CallCPU, call_cpu

import hyperrotor
import hyperrotor.paper

TIME_LIMIT = 1.0  # seconds of CPU per payload (the calling thread's: tests/cpu_clock.py)
HANG_LIMIT = 10.0  # wall seconds after which a call is interrupted (the machine is shared)

#: (id, text). Every payload that would run code creates a file in the working directory.
PAYLOADS = [
    ("os_system", "__import__('os').system('touch PWNED_system')"),
    ("exec", "exec(\"open('PWNED_exec', 'w').close()\")"),
    ("eval", "eval(\"open('PWNED_eval', 'w').close()\")"),
    ("open", "open('PWNED_open', 'w')"),
    ("lambda", "(lambda: open('PWNED_lambda', 'w'))()"),
    ("mro", "().__class__.__mro__[1].__subclasses__()"),
    ("builtins", "__builtins__"),
    ("dunder_attr", "x.__class__"),
    ("subscript", "x[0]"),
    ("huge_power", "9**9**9**9"),
    ("huge_float", "1e999999"),
    ("long_int", "1" * 100_000),
    ("long_name", "x" * 100_000),
    ("deep_parens", "(" * 5000 + "1" + ")" * 5000),
    ("symbol_range", "x:1000000000"),
]

#: (label, argument) of the fuzz table that take free text by design (never parsed): completion allowed.
FREE_TEXT = {
    ("q.as_csr", 1): "name: the label of the matrix in error messages, never parsed",
    ("Inertia.symbolic", 1): "name: the stem of the symbol names (an identifier; other text is refused)",
    ("plane_symbols", 0): "name: the stem of the symbol names (an identifier; other text is refused)",
}


def _load_fuzz():
    path = Path(__file__).resolve().parents[1] / "property" / "test_fuzz_entry_points.py"
    spec = importlib.util.spec_from_file_location("_fuzz_entry_points", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


FUZZ = _load_fuzz()


_Hang = FUZZ._Hang  # raised by the alarm (a BaseException: ``except Exception`` in library code cannot swallow it)
_limit = FUZZ._time_limit


def _with_symbol(good, text):
    """A list like the good array argument, holding a SymPy symbol and the payload."""
    flat = list(np.asarray(good, dtype=object).ravel())
    if len(flat) < 2:
        return [sp.Symbol("a"), text]
    flat[0], flat[1] = sp.Symbol("a"), text
    return np.array(flat, dtype=object).reshape(np.shape(good)).tolist()


def _python_cases():
    """Every argument of every entry's good call (marked for fuzzing or not; the bound method of a
    method entry excepted), plus the array arguments as lists holding a symbol and the payload."""
    for label, path, args, kwargs, kinds in FUZZ.ENTRIES:
        wheres = list(kinds) + [w for w in (*range(1 if path is None else 0, len(args())), *kwargs()) if w not in kinds]
        for where in wheres:
            yield pytest.param(label, path, args, kwargs, where, False, id=f"{label}-{where}")
            if kinds.get(where, "").startswith(("arr", "map", "vec", "pts")):
                yield pytest.param(label, path, args, kwargs, where, True, id=f"{label}-{where}-in_list")


def _inertia():
    return hyperrotor.Inertia.symbolic(3)


def _rep():
    return hyperrotor.quantum.irrep(3, (1,))


#: The methods of issue #21 §1 that are not in the fuzz table: (label, call taking the payload).
EXTRA = {
    "Inertia.subs": lambda text: _inertia().subs(text, 1),
    "Inertia.subs/value": lambda text: _inertia().subs(_inertia().symbolic_moments[0], text),
    "RigidBody.matrix": lambda text: hyperrotor.RigidBody(_inertia()).matrix([sp.Symbol("a"), text, 0]),
    "RigidBody.euler_equations/torque": lambda text: hyperrotor.RigidBody(_inertia()).euler_equations(
        torque=[sp.Symbol("a"), text, 0]),
    "Representation.generator/hbar": lambda text: _rep().generator((1, 2), exact=True, form="hermitian", hbar=text),
    "Representation.generators/hbar": lambda text: _rep().generators(exact=True, form="hermitian", hbar=text),
    "WeylElement.from_sympy": lambda text: hyperrotor.quantum.WeylElement.from_sympy(
        text, hyperrotor.quantum.coordinate_symbols(3)),
    "angular_momentum_operators/hbar": lambda text: hyperrotor.quantum.angular_momentum_operators(
        3, form="hermitian", hbar=text),
    "DifferentialOperator/division": lambda text: hyperrotor.quantum.angular_momentum_operators(3)[(1, 2)] / text,
    # public callables that the fuzz table excuses (NOT_FUZZED) but that take a value a user may give as text
    "DifferentialOperator/coordinates": lambda text: hyperrotor.quantum.DifferentialOperator(
        _l12().element, [text, "y", "z"]),
    "angular_momentum_operators/coordinates": lambda text: hyperrotor.quantum.angular_momentum_operators(
        3, coordinates=[text, "y", "z"]),
    "textbook_so3/hbar": lambda text: hyperrotor.quantum.textbook_so3(hbar=text),
    "textbook_so3/coordinates": lambda text: hyperrotor.quantum.textbook_so3(coordinates=[text, "y", "z"]),
    "polynomial_to_dict": lambda text: hyperrotor.quantum.polynomial_to_dict(text, _x3()),
    "polynomial_to_dict/coordinates": lambda text: hyperrotor.quantum.polynomial_to_dict(_x3()[0], [text, *_x3()[1:]]),
    "dict_to_polynomial": lambda text: hyperrotor.quantum.dict_to_polynomial({(1, 0, 0): text}, _x3()),
    "dict_to_polynomial/coordinates": lambda text: hyperrotor.quantum.dict_to_polynomial({(1, 0, 0): 1},
                                                                                         [text, *_x3()[1:]]),
    "apply_to_polynomial": lambda text: hyperrotor.quantum.apply_to_polynomial(_l12(), text),
    "sphere_inner_product/p": lambda text: hyperrotor.quantum.sphere_inner_product(text, _x3()[0], 3),
    "sphere_inner_product/coordinates": lambda text: hyperrotor.quantum.sphere_inner_product(
        _x3()[0], _x3()[0], 3, coordinates=[text, "y", "z"]),
    "operator_product": lambda text: hyperrotor.quantum.operator_product(text, text),
    "WeylElement/terms": lambda text: hyperrotor.quantum.WeylElement(3, {((0, 0, 0), (0, 0, 0)): text}),
    "evolve/options": lambda text: hyperrotor.quantum.evolve(
        hyperrotor.quantum.rotor_hamiltonian(_rep(), [1.0, 2.0, 3.0]), np.ones(3) / 3**0.5, [0.0, 1.0],
        method="auto", options={"atol": text}),
    "body_edges/kind": lambda text: hyperrotor.body_edges(np.zeros((4, 3)), text),
    "scene_html_bytes": lambda text: hyperrotor.scene_html_bytes(text, 1, 1),
    "projection_figure/t": lambda text: hyperrotor.projection_figure(text, np.zeros((3, 4, 3))),
    "options/assignment": lambda text: hyperrotor.options.__setitem__("max_seconds", text),
    "options/block": lambda text: hyperrotor.options(max_steps=text).__enter__(),
    "paper.verify_paper": lambda text: hyperrotor.paper.verify_paper([text]),
    "paper.render": lambda text: hyperrotor.paper.render([], format=text),
    "paper.Verdict": lambda text: hyperrotor.paper.Verdict("eq. 1", text, "detail"),
}

#: public callables with no argument that text could reach as a number or expression (each with its reason):
#: the result records and exception classes the fuzz table excuses, and these
NO_TEXT = {
    **{name: reason for name, reason in FUZZ.NOT_FUZZED.items() if "result record" in reason or "exception" in reason},
    "write_html": "its text argument is a file path (the figure was built and checked by projection_figure)",
    "Solver": "base class: its options are checked by name (UnknownOptionError) and by each method",
    "Propagator": "base class: evolve checks its options (evolve/options above)",
}


def _x3():
    return hyperrotor.quantum.coordinate_symbols(3)


def _l12():
    return hyperrotor.quantum.angular_momentum_operators(3)[(1, 2)]


def _covered_names():
    """Names reached by the walks: the fuzz table's entries (as its own coverage test reads them) and EXTRA."""
    names = {path.rsplit(".", 1)[-1].split(".")[0] for _, path, *_ in FUZZ.ENTRIES if path}
    names |= {label.split(".")[0] for label, *_ in FUZZ.ENTRIES}
    names |= {label.split(".", 1)[1].split(".")[0].split("/")[0] for label, *_ in FUZZ.ENTRIES if label.startswith("q.")}
    for label in EXTRA:
        head = label.split("/")[0]
        names |= {head.split(".")[0], head.split(".")[-1]}
    return names


def test_every_public_callable_is_walked_or_excused():
    """A public callable added to hyperrotor, hyperrotor.classical, hyperrotor.quantum or
    hyperrotor.paper without a payload case (a fuzz entry or EXTRA) or a NO_TEXT reason fails here."""
    import inspect

    import hyperrotor.classical
    import hyperrotor.paper

    covered = _covered_names() | set(NO_TEXT)
    missing = []
    for mod in (hyperrotor, hyperrotor.classical, hyperrotor.quantum, hyperrotor.paper):
        for name in mod.__all__:
            obj = getattr(mod, name)
            if inspect.ismodule(obj) or not callable(obj) or isinstance(obj, type(hyperrotor.options)):
                continue
            if name not in covered:
                missing.append(f"{mod.__name__}.{name}")
    assert not missing, f"public callables without a payload case (add one to EXTRA or a reason to NO_TEXT): {missing}"


def _check(call, where_text, tmp_path):
    """The outcome of ``call()`` in the empty directory ``tmp_path`` (the cwd), or a failure text."""
    outcome = "completed"
    clock = CallCPU()
    try:
        with _limit(HANG_LIMIT), warnings.catch_warnings(), call_cpu() as clock:
            warnings.simplefilter("ignore")
            call()
    except (TypeError, ValueError) as exc:  # hyperrotor.ParseError is a ValueError
        outcome = "TypeError" if isinstance(exc, TypeError) else "ValueError"
        if not str(exc):
            return f"{where_text}: {outcome} without a message"
    except _Hang:
        return f"{where_text}: no answer within {HANG_LIMIT} s"
    except Exception as exc:  # noqa: BLE001 (RecursionError, MemoryError, anything else: a failure)
        return f"{where_text}: {type(exc).__name__}: {str(exc)[:200]}"
    cpu = clock.seconds
    created = sorted(os.listdir(tmp_path))
    for name in created:
        os.remove(tmp_path / name)
    if created:
        return f"{where_text}: files appeared: {created} (the text was run as code)"
    if cpu > TIME_LIMIT:
        return f"{where_text}: {cpu:.2f} s of CPU ({outcome})"
    return outcome


@pytest.mark.parametrize("label, path, args, kwargs, where, in_list", list(_python_cases()))
def test_payloads_through_public_callable(label, path, args, kwargs, where, in_list, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    failures = []
    for pid, text in (PAYLOADS[:5] if in_list else PAYLOADS):
        fn, a, kw, shift = FUZZ._call(path, args, kwargs)
        if isinstance(where, int):
            a[where - shift] = _with_symbol(a[where - shift], text) if in_list else text
        else:
            kw[where] = _with_symbol(kw[where], text) if in_list else text
        outcome = _check(lambda: fn(*a, **kw), f"{label}({where}={pid})", tmp_path)
        if outcome == "completed" and (label, where) not in FREE_TEXT:
            outcome = f"{label}({where}={pid}) accepted hostile text"
        if outcome not in ("TypeError", "ValueError", "completed"):
            failures.append(outcome)
    assert not failures, "\n".join(failures)


@pytest.mark.parametrize("label", sorted(EXTRA))
def test_payloads_through_issue_methods(label, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    failures = []
    for pid, text in PAYLOADS:
        outcome = _check(lambda: EXTRA[label](text), f"{label}({pid})", tmp_path)
        if outcome == "completed":
            outcome = f"{label}({pid}) accepted hostile text"
        if outcome not in ("TypeError", "ValueError"):
            failures.append(outcome)
    assert not failures, "\n".join(failures)


# --------------------------------------------------------------------------- the command line
#: options whose value is a file name (text by design, written through the CLI's file path): not parsed
CLI_FILE_OPTIONS = {"output", "png"}


def _cli_options():
    from hyperrotor.cli import build_parser

    out = []

    def walk(parser, command):
        for action in parser._actions:
            if isinstance(action, argparse._SubParsersAction):
                for name, sub in action.choices.items():
                    walk(sub, command + [name])
            elif action.option_strings and action.nargs != 0 and action.dest not in CLI_FILE_OPTIONS:
                out.append((tuple(command), action.option_strings[-1], action.dest))
    walk(build_parser(), [])
    return out


CLI_OPTIONS = _cli_options()


def test_the_cli_walk_finds_the_text_options():
    dests = {d for _, _, d in CLI_OPTIONS}
    assert {"kappa", "omega", "t_end", "max_seconds"} <= dests, dests


@pytest.mark.parametrize("command, option, dest", CLI_OPTIONS, ids=[f"{' '.join(c)}{o}" for c, o, _ in CLI_OPTIONS])
def test_payloads_through_cli_option(command, option, dest, tmp_path, monkeypatch):
    from hyperrotor.cli import main

    monkeypatch.chdir(tmp_path)
    failures = []
    for pid, text in PAYLOADS:
        argv = [*command, f"{option}={text}"]
        err = io.StringIO()
        status = None
        clock = CallCPU()
        try:
            with (_limit(HANG_LIMIT), contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()),
                  call_cpu() as clock):
                status = main(argv)
        except SystemExit as exc:
            status = exc.code
        except _Hang:
            failures.append(f"{option}={pid}: no answer within {HANG_LIMIT} s")
            continue
        cpu = clock.seconds
        created = sorted(os.listdir(tmp_path))
        for name in created:
            os.remove(tmp_path / name)
        if created:
            failures.append(f"{option}={pid}: files appeared: {created}")
        elif status != 2:
            failures.append(f"{option}={pid}: exit status {status}: {err.getvalue()[-200:]}")
        elif cpu > TIME_LIMIT:
            failures.append(f"{option}={pid}: {cpu:.2f} s of CPU")
    assert not failures, f"hyperrotor {' '.join(command)}:\n" + "\n".join(failures)


if __name__ == "__main__":
    sys.exit(pytest.main([__file__, "-q"]))
