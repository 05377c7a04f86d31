"""Physical units: the device conversion against hand-computed values, and theta of one material.

Two material pairs are converted by sawdrift.scene.device and by hand (the formulas of
docs/physics.md, "Physical units and two materials", written out here):

* a 1 mm steel ball (R = 0.5 mm, 7850 kg/m^3, E = 210 GPa, nu = 0.3) pressed by 7.35 mN onto
  LiNbO3 (E = 170 GPa, nu = 0.25) at 9.6 MHz, 10 nm;
* a 2 mm glass bead (R = 1 mm, 2500 kg/m^3, E = 70 GPa, nu = 0.22) on aluminium (E = 70 GPa,
  nu = 0.33) at 40 kHz, 1 um, gravity only.

And theta = E*/(4 G*) must equal (2 - nu)/(2 (1 - nu)) for identical materials.
"""

from __future__ import annotations

import math

from sawdrift.report.validation import Case, CaseResult
from sawdrift.scene.device import Device, normalized

PAIRS = {
    "steel on LiNbO3": dict(R=0.5e-3, rho=7850, E1=210e9, nu1=0.3, E2=170e9, nu2=0.25,
                            f=9.6e6, A=10e-9, F=7.35e-3),
    "glass on aluminium": dict(R=1e-3, rho=2500, E1=70e9, nu1=0.22, E2=70e9, nu2=0.33,
                               f=40e3, A=1e-6, F=0.0),
}

CASE = Case(
    name="device_conversion",
    group="device",
    title="Device -> normalized scene for two material pairs against hand-computed m*, A*, theta "
    "and a0, and theta of identical materials = (2 - nu)/(2 (1 - nu)) for nu = 0.1..0.45; value: "
    "largest relative error",
    tolerance=1e-12,
    quick=True,
)


def _hand(R, rho, E1, nu1, E2, nu2, f, A, F, g=9.81):
    m = rho * 4.0 / 3.0 * math.pi * R**3
    e_star = 1.0 / ((1 - nu1**2) / E1 + (1 - nu2**2) / E2)
    g_star = 1.0 / ((2 - nu1) / (E1 / (2 * (1 + nu1))) + (2 - nu2) / (E2 / (2 * (1 + nu2))))
    weight = m * g + F
    a0 = (9 * weight**2 / (16 * R * e_star**2)) ** (1.0 / 3.0)
    return {"m_star": a0 * m * f**2 / weight, "amplitude": A / a0,
            "theta": e_star / (4 * g_star), "a0_m": a0}


def _device(R, rho, E1, nu1, E2, nu2, f, A, F) -> Device:
    return Device.model_validate({
        "frequency": f"{f} Hz", "amplitude": f"{A} m", "preload": f"{F} N", "friction": 0.2,
        "particle": {"radius": f"{R * 1e3} mm", "density": f"{rho} kg/m^3",
                     "youngs_modulus": f"{E1 / 1e9} GPa", "poisson": nu1},
        "substrate": {"youngs_modulus": f"{E2 / 1e9} GPa", "poisson": nu2}})


def run() -> CaseResult:
    """Compare every derived quantity; check theta for identical materials."""
    worst, notes = 0.0, []
    for label, p in PAIRS.items():
        got, want = normalized(_device(**p)), _hand(**p)
        err = max(abs(got[k] / want[k] - 1.0) for k in want)
        worst = max(worst, err)
        notes.append(f"{label}: m* = {got['m_star']:.6g}, A* = {got['amplitude']:.6g}, "
                     f"theta = {got['theta']:.6g}, a0 = {got['a0_m']:.4g} m (max rel. error {err:.1e})")
    for nu in (0.1, 0.2, 0.3, 0.45):
        p = dict(PAIRS["steel on LiNbO3"], nu1=nu, nu2=nu, E2=210e9)
        theta = normalized(_device(**p))["theta"]
        worst = max(worst, abs(theta / ((2 - nu) / (2 * (1 - nu))) - 1.0))
    notes.append("identical materials: theta = (2 - nu)/(2 (1 - nu)) at nu = 0.1, 0.2, 0.3, 0.45")
    return CASE.result(worst, message="; ".join(notes))
