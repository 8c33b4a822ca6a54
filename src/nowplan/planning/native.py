"""The forward engine's compiled kernel, when it is built and not switched off.

``nowplan.planning._kernel`` (``_kernel.c``, built by ``setup.py`` on
``pip install``; optional) computes the relaxed-plan heuristics, the
successor generator and the lazy GBFS loop with exactly the results of the
Python code in :mod:`nowplan.planning.hff` and :mod:`nowplan.planning.forward`.
Those modules ask :func:`kernel_class` at each search: the kernel when it
imports, else ``None`` (the Python code runs).  ``NOWPLAN_PURE_PYTHON=1``
forces the Python code.  Which one runs is logged once, at debug level.
"""

from __future__ import annotations

import importlib
import logging
import os
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from nowplan.planning._kernel import Kernel

log = logging.getLogger(__name__)

API = 9  # the kernel's interface version this code expects (KERNEL_API in _kernel.c)
ENV = "NOWPLAN_PURE_PYTHON"

_loaded: tuple[type[Kernel] | None, str] | None = None
_logged: set[str] = set()


def _load() -> tuple[type[Kernel] | None, str]:
    global _loaded
    if _loaded is None:
        try:
            mod = importlib.import_module("nowplan.planning._kernel")
        except ImportError as e:
            _loaded = (None, f"the compiled kernel is not available ({e})")
        else:
            if getattr(mod, "API", None) != API:
                _loaded = (None, f"the compiled kernel is stale (API {getattr(mod, 'API', None)}, expected {API};"
                                 " rebuild it with pip install -e .)")
            else:
                _loaded = (mod.Kernel, f"the compiled kernel ({mod.__file__})")
    return _loaded


def pure_python_forced() -> bool:
    return os.environ.get(ENV, "").strip() not in ("", "0")


def kernel_class() -> type[Kernel] | None:
    """The compiled ``Kernel`` type, or ``None``: run the pure-Python code."""
    if pure_python_forced():
        _log_once(f"{ENV} is set: the forward search runs its pure-Python code")
        return None
    cls, why = _load()
    _log_once(f"forward search: {why}" if cls is not None else f"{why}: the forward search runs its Python code")
    return cls


def _log_once(msg: str) -> None:
    if msg not in _logged:
        _logged.add(msg)
        log.debug(msg)
