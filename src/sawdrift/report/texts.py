"""The prose of the reports, kept as data in ``sawdrift/report/text/`` (TOML and CSS files)."""

from __future__ import annotations

import tomllib
from functools import cache
from importlib.resources import files
from typing import Any


@cache
def text(name: str) -> dict[str, Any]:
    """The templates of ``text/<name>.toml`` (sections of named ``str.format`` templates)."""
    return tomllib.loads(files("sawdrift.report").joinpath("text", f"{name}.toml").read_text("utf-8"))


@cache
def asset(filename: str) -> str:
    """A static text file of ``text/`` (e.g. the validation report's CSS)."""
    return files("sawdrift.report").joinpath("text", filename).read_text("utf-8")
