"""Direct runs: a light particle ends at the trap the field predicts, and a phase ramp carries it.

The direct run evaluates both waves at the particle's own position (L* = 200 wavelength / a0).
mmd, m* = 0.1, s = 0.5: from xi = 0.12 (between the trap and the repeller of the 16-point field)
for 1500 periods; then from the trap with psi growing by 0.5 degrees per period for 3000 periods,
which moves the trap by -0.5 x 3000 / 720 = -2.08 wavelengths; the particle follows it with a
lag where V(xi) / L* equals the trap's speed, which the field's prediction dxi/dt =
V(xi + rate t*/720) / L* contains. Value: the largest distance (wavelengths) between the direct
run's end and the field's prediction (the trap itself for the resting run); required: the resting
run within 1e-3 of the trap and the conveyed one carried more than 1.5 wavelengths.
"""

from __future__ import annotations

import sawdrift as sd
from sawdrift.study.field import drift_field
from sawdrift.study.field_direct import direct_run, nearest_zero
from sawdrift.validation import Case, CaseResult

CASE = Case(
    name="direct_run_trap",
    group="fields",
    title="A light particle's direct run ends at the field's trap; a 0.5 deg/period phase ramp "
    "carries it 2.08 wavelengths as predicted (mmd, m* = 0.1, s = 0.5, L* = 200); value: largest "
    "miss in wavelengths",
    tolerance=0.01,
    quick=False,
)


def run() -> CaseResult:
    """A field, a resting direct run and a conveyed one."""
    scene = sd.Scene(model="mmd", particle={"m_star": 0.1}, drive={"backward": 0.5})
    fld = drift_field(scene, 16).fields[0]
    trap = nearest_zero(fld, 0.12)
    rest = direct_run(scene, 0.12, 1500, fld, wavelength=200.0)
    rate, periods = 0.5, 3000.0
    moving = direct_run(scene.with_updates(**{"drive.backward_phase_rate": rate}), trap, periods,
                        fld, wavelength=200.0)
    target = trap - rate * periods / 720.0
    miss_rest = abs(rest["final_position"] - trap)
    miss_moving = abs(moving["final_position"] - moving["predicted"]["final_position"])
    carried = trap - moving["final_position"]
    return CASE.result(max(miss_rest, miss_moving), require=miss_rest < 1e-3 and carried > 1.5,
                       message=f"trap {trap:.5f}: resting run ends at {rest['final_position']:.5f}; "
                       f"conveyed run ends at {moving['final_position']:.4f}, predicted "
                       f"{moving['predicted']['final_position']:.4f} (the trap is at {target:.4f})")
