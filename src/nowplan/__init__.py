"""nowplan: hierarchical planning and acting under uncertainty."""

from __future__ import annotations

__all__ = ["__version__"]


def __getattr__(name: str) -> str:
    # looked up on first use: importlib.metadata costs ~40 ms of every command's start-up
    if name == "__version__":
        from importlib.metadata import PackageNotFoundError, version

        try:
            v = version("nowplan")
        except PackageNotFoundError:  # pragma: no cover - running from a source tree
            v = "0.0.0+local"
        globals()["__version__"] = v
        return v
    raise AttributeError(f"module 'nowplan' has no attribute {name!r}")
