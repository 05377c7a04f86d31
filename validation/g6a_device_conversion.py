"""Physical units: the device conversion against hand-computed values, and theta of one material.

Two material pairs are converted by sawdrift.scene.device and by hand (the formulas of
docs/physics.md, "Physical units and two materials", written out here):

* a 1 mm steel ball (R = 0.5 mm, 7850 kg/m^3, E = 210 GPa, nu = 0.3) pressed by 7.35 mN onto
  LiNbO3 (E = 170 GPa, nu = 0.25) at 9.6 MHz, 10 nm;
* a 2 mm glass bead (R = 1 mm, 2500 kg/m^3, E = 70 GPa, nu = 0.22) on aluminium (E = 70 GPa,
  nu = 0.33) at 40 kHz, 1 um, gravity only.

And theta = E*/(4 G*) must equal (2 - nu)/(2 (1 - nu)) for identical materials. A cone (half-angle
75 deg) and a flat punch (R = 0.1 mm), 2 mg, on the steel/LiNbO3 pair give a0 from their own
normal laws (Sneddon 1965): N = (2/pi) E* tan(alpha) a0^2 and N = 2 E* R a0, written out here.
"""

from __future__ import annotations

import math

from sawdrift.scene.device import Device, normalized
from sawdrift.validation import Case, CaseResult

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
    "and a0, theta of identical materials = (2 - nu)/(2 (1 - nu)) for nu = 0.1..0.45, and a0 of a "
    "cone and a flat punch from Sneddon's laws; value: largest relative error",
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


def _punches() -> tuple[float, list[str]]:
    """a0 of a cone and of a flat punch against Sneddon's laws solved by hand."""
    p = PAIRS["steel on LiNbO3"]
    e_star = 1.0 / ((1 - p["nu1"] ** 2) / p["E1"] + (1 - p["nu2"] ** 2) / p["E2"])
    mass, alpha, radius = 2e-6, math.radians(75.0), 0.1e-3
    weight = mass * 9.81 + p["F"]
    want = {"cone": math.sqrt(math.pi * weight / (2 * e_star * math.tan(alpha))),
            "flat": weight / (2 * e_star * radius)}
    shapes = {"cone": {"half_angle": "75 deg"}, "flat": {"radius": "0.1 mm"}}
    worst, notes = 0.0, []
    for shape, extra in shapes.items():
        dev = Device.model_validate({
            "frequency": f"{p['f']} Hz", "amplitude": f"{p['A']} m", "preload": f"{p['F']} N",
            "friction": 0.2, "substrate": {"youngs_modulus": f"{p['E2']} Pa", "poisson": p["nu2"]},
            "particle": {"shape": shape, "mass": "2 mg", "youngs_modulus": f"{p['E1']} Pa",
                         "poisson": p["nu1"], **extra}})
        got = normalized(dev)
        err = max(abs(got["a0_m"] / want[shape] - 1.0),
                  abs(got["m_star"] / (want[shape] * mass * p["f"] ** 2 / weight) - 1.0))
        worst = max(worst, err)
        notes.append(f"{shape}: a0 = {got['a0_m']:.4g} m (max rel. error {err:.1e})")
    return worst, notes


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
    err, more = _punches()
    worst = max(worst, err)
    notes += more
    return CASE.result(worst, message="; ".join(notes))
