"""The ``sawdrift`` command line: a thin layer over the public Python API.

:mod:`.app` holds the application, its one-line errors and exit statuses; the commands live in
:mod:`.run` (models, check-model, run), :mod:`.study` (sweeps), :mod:`.report` (diagrams,
comparison, export, demo, validation, benchmarks), :mod:`.field` (two-wave drift fields) and
:mod:`.load_curve` (speed and power against a load), :mod:`.force_velocity` (the mean friction
force against the steady speed), :mod:`.sort` (sorting times of a mixture).
Scene options are generated from the Scene schema (:mod:`.scene_options`).

The command modules register on first use (:func:`.app.load_commands`): ``sawdrift run``
imports and builds only the module of ``run``, ``sawdrift --help`` all of them, and
``sawdrift.cli.app`` (the Typer application of tests and of ``typer ... utils docs``) is the
application with every command, in the order of ``--help``.
"""

from __future__ import annotations

from typing import Any

from .app import INTERNAL_FAILURE, load_commands, main
from .scene_options import scene_from_options

__all__ = ["INTERNAL_FAILURE", "app", "main", "scene_from_options"]

# importing the submodule .app bound it to the name ``app`` here; the name means the Typer
# application, completed with every command on first access (``__getattr__`` below)
globals().pop("app", None)


def __getattr__(name: str) -> Any:
    if name == "app":
        value = load_commands()
        globals()["app"] = value
        return value
    raise AttributeError(f"module 'sawdrift.cli' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
