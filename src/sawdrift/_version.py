"""The installed sawdrift version, single-sourced from ``pyproject.toml`` through the package metadata.

A module of its own, below every layer, so that the package's ``__init__``, the result's
provenance, the studies' tables and the key of generated modules (:mod:`sawdrift.codegen`) read
the same value without importing the public API.
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("sawdrift")
except PackageNotFoundError:  # pragma: no cover - running from a source tree without metadata
    __version__ = "0+unknown"

__all__ = ["__version__"]
