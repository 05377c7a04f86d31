"""A rigid sphere that rolls runs into the trap the field predicts: the drive acts at its centre.

The rigid scheme integrates the contact point x* + R phi / a0 within a step, which is (1 + 1/kappa)
x* for a sphere rolling from rest; the surface motion must be taken where the sphere is, at its
centre x*. Material point with rotation (kappa = 0.4), m* = 0.1, s = 0.5, L* = 200: the 16-point
field's trap nearest to xi = 0.12 against a 1500-period direct run from there. Value: the
sphere's distance from the trap in wavelengths (a drive taken at (1 + 1/kappa) x* = 3.5 x* stops
it 0.083 wavelengths away); required: the trap lies more than 0.05 wavelengths from the start.
"""

from __future__ import annotations

import sawdrift as sd
from sawdrift.study.field import drift_field
from sawdrift.study.field_direct import direct_run, nearest_zero
from sawdrift.validation import Case, CaseResult

CASE = Case(
    name="rolling_sphere_trap",
    group="fields",
    title="A rigid rolling sphere's direct run ends at its field's trap (material point with "
    "rotation, m* = 0.1, s = 0.5, L* = 200, from xi = 0.12); value: miss in wavelengths",
    tolerance=1e-3,
    quick=False,
)


def run() -> CaseResult:
    """The rolling sphere's field, its trap, and the direct run toward it."""
    scene = sd.Scene(model="material_point", particle={"m_star": 0.1}, drive={"backward": 0.5},
                     effects={"rotation": True})
    fld = drift_field(scene, 16).fields[0]
    trap = nearest_zero(fld, 0.12)
    if trap is None:
        return CASE.result(float("inf"), require=False, message="the field has no trap near 0.12")
    got = direct_run(scene, 0.12, 1500, fld, wavelength=200.0)
    miss = abs(got["final_position"] - trap)
    return CASE.result(miss, require=abs(trap - 0.12) > 0.05,
                       message=f"trap {trap:.5f}; the direct run from 0.12 ends at "
                       f"{got['final_position']:.5f}")
