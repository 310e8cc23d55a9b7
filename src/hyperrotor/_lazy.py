"""Heavy optional libraries, imported on first use (the light ``import hyperrotor``).

``import hyperrotor`` must not pay for SymPy, QuTiP or matplotlib (together
about 2 s) when a user only integrates numerically. Modules that need one of
them at call time write::

    from hyperrotor._lazy import sympy as sp

and use ``sp.Symbol`` etc. as usual: the first attribute access imports the
real module (``importlib.import_module``), later ones read its namespace
directly. Unlike :class:`importlib.util.LazyLoader`, nothing is put into
``sys.modules`` before that first use, so ``"sympy" in sys.modules`` keeps
telling whether SymPy has really been loaded; :func:`loaded` asks exactly that
(used by checks such as :func:`hyperrotor.conventions.is_symbolic`, which
need not load SymPy to know that an object is not a SymPy object).
"""
from __future__ import annotations

import importlib
import sys
from types import ModuleType
from typing import Any, Callable

__all__ = ["LazyModule", "loaded", "lazy_attributes", "sympy", "qutip"]


class LazyModule(ModuleType):
    """A stand-in for module ``name`` that imports it on first attribute access."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.__dict__["_lazy_name"] = name
        self.__dict__["_lazy_module"] = None

    def _load(self) -> ModuleType:
        mod = self.__dict__["_lazy_module"]
        if mod is None:
            mod = importlib.import_module(self.__dict__["_lazy_name"])
            self.__dict__["_lazy_module"] = mod
        return mod

    def __getattr__(self, attr: str) -> Any:
        if attr.startswith("__") and attr.endswith("__"):
            raise AttributeError(attr)
        value = getattr(self._load(), attr)
        self.__dict__[attr] = value  # later accesses skip __getattr__
        return value

    def __repr__(self) -> str:
        state = "loaded" if self.__dict__["_lazy_module"] is not None else "not loaded yet"
        return f"<lazy module {self.__dict__['_lazy_name']!r} ({state})>"


def lazy_attributes(package: str, names: dict[str, tuple[str, str]], modules: tuple[str, ...] = (),
                    fresh: tuple[str, ...] = ()) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """PEP 562 ``__getattr__`` and ``__dir__`` of ``package``, whose heavy names load on first use.

    ``names`` maps an attribute to ``(module, attribute)`` (``module`` may be relative to
    ``package``); the value is imported on first access and kept in the package's namespace,
    except for the names in ``fresh`` (looked up on every access). ``modules`` lists submodules
    imported on first attribute access. Used by ``hyperrotor`` and ``hyperrotor.paper``::

        __getattr__, __dir__ = lazy_attributes(__name__, {"verify_paper": (".verify", "verify")})
    """
    namespace = sys.modules[package].__dict__

    def __getattr__(name: str) -> Any:
        if name in modules:
            return importlib.import_module(f"{package}.{name}")
        if name in names:
            module, attr = names[name]
            value = getattr(importlib.import_module(module, package), attr)
            if name not in fresh:
                namespace[name] = value
            return value
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__() -> list[str]:
        return sorted({*namespace, *modules, *names})

    return __getattr__, __dir__


def loaded(name: str) -> bool:
    """Whether module ``name`` has really been imported (by anyone) in this process."""
    return name in sys.modules


#: SymPy, imported on first attribute access.
sympy = LazyModule("sympy")
#: QuTiP, imported on first attribute access.
qutip = LazyModule("qutip")
