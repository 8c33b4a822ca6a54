"""nowplan: hierarchical planning and acting under uncertainty."""

from __future__ import annotations

__all__ = ["__version__"]

# the one place the version is written (pyproject.toml reads it: [tool.setuptools.dynamic]); a
# constant, not importlib.metadata.version(), which costs ~40-70 ms of every run's start-up
__version__ = "0.1.0"
