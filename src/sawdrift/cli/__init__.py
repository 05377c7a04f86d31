"""The ``sawdrift`` command line: a thin layer over the public Python API.

:mod:`.app` holds the application, its one-line errors and exit statuses; the commands live in
:mod:`.run` (models, check-model, run), :mod:`.study` (sweeps), :mod:`.report` (diagrams,
comparison, export, demo, validation, benchmarks), :mod:`.field` (two-wave drift fields) and
:mod:`.load_curve` (speed and power against a load), :mod:`.force_velocity` (the mean friction
force against the steady speed), :mod:`.sort` (sorting times of a mixture).
Scene options are generated from the Scene schema (:mod:`.scene_options`).
"""

# the commands register in this order, which is the order of --help
# isort: off
from . import run  # noqa: F401
from . import study  # noqa: F401
from . import report  # noqa: F401
from . import field  # noqa: F401
from . import load_curve  # noqa: F401
from . import force_velocity  # noqa: F401
from . import lammps  # noqa: F401
from . import sort  # noqa: F401
from . import threshold  # noqa: F401
# isort: on
from .app import INTERNAL_FAILURE, app, main
from .scene_options import scene_from_options

__all__ = ["INTERNAL_FAILURE", "app", "main", "scene_from_options"]
