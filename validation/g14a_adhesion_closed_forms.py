"""DMT and JKR against their closed forms on the silica sphere of the example (R = 5 um, SI).

JKR (Johnson, Kendall and Roberts 1971): pull-off 1.5 pi R w, zero-load contact radius
(9 pi w R^2 / (2 E*))^(1/3), the loading curve F(c), d(c) through its tensile branch; DMT
(Derjaguin, Muller and Toporov 1975): pull-off 2 pi R w. The laws run as the compiled adhesive
contact of ``hertz_mindlin_dem``, driven quasi-statically. Value: the largest relative error.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from sawdrift.contact.adhesion_law import adhesive_normal
from sawdrift.contact.binding import model_for
from sawdrift.contact.history import ContactHistory
from sawdrift.scene.device import normalized
from sawdrift.scene.schema import build_scene
from sawdrift.validation import Case, CaseResult

CASE = Case(
    name="adhesion_closed_forms",
    group="adhesion",
    title="JKR pull-off 1.5 pi R w, DMT pull-off 2 pi R w, JKR zero-load contact radius and "
    "quasi-static JKR loading curve against their closed forms (silica sphere of radius 5 um, "
    "10 um diameter; w = 0.05 J/m^2)",
    tolerance=1e-8,
    quick=True,
)

W = 0.05


def scene(law: str):
    """The silica sphere of examples/micro_silica_on_linbo3.toml with the adhesive ``law``."""
    return build_scene({"model": "hertz_mindlin_dem", "effects": {"adhesion": law}, "device": {
        "frequency": "20 MHz", "amplitude": "0.01 nm", "friction": 0.3, "adhesion": f"{W} J/m^2",
        "particle": {"radius": "5 um", "density": "2200 kg/m^3", "youngs_modulus": "73 GPa",
                     "poisson": 0.17},
        "substrate": {"youngs_modulus": "200 GPa", "poisson": 0.3}}})


def run() -> CaseResult:
    """Four closed forms."""
    jkr = scene("jkr")
    n = normalized(jkr.device)
    r, e, a0, mg = 5e-6, n["e_star_pa"], n["a0_m"], n["weight_n"]
    ad = model_for(jkr).adhesion.descriptor()
    low = minimize_scalar(lambda a: adhesive_normal(a, ad)[0], bounds=(ad[2], 0.0),
                          method="bounded", options={"xatol": 1e-12})
    errors = {"jkr_pulloff": abs(-low.fun * mg / (1.5 * math.pi * r * W) - 1.0)}
    ad_dmt = model_for(scene("dmt")).adhesion.descriptor()
    errors["dmt_pulloff"] = abs(-adhesive_normal(1e-300, ad_dmt)[0] * mg / (2 * math.pi * r * W) - 1)
    a_zero = brentq(lambda a: adhesive_normal(a, ad)[0], 0.0, 1e5, xtol=1e-13, rtol=1e-15)
    c_zero = adhesive_normal(a_zero, ad)[1] * math.sqrt(r * a0)
    errors["zero_load_radius"] = abs(c_zero / (9 * math.pi * W * r * r / (2 * e)) ** (1 / 3) - 1)
    c = np.linspace(1e-9, 3e-7, 400)
    d = c * c / r - np.sqrt(2 * math.pi * W * c / e)
    force = 4 * e * c**3 / (3 * r) - np.sqrt(8 * math.pi * W * e * c**3)
    stable = np.gradient(d, c) > 0.0
    hist = ContactHistory(model_for(jkr), "compiled")
    hist.advance(1.0, 0.0)
    got, _ = hist.drive(d[stable][::-1] / a0, np.zeros(stable.sum()))
    errors["loading_curve"] = float(np.abs(got[::-1] * mg - force[stable]).max()
                                    / np.abs(force).max())
    worst = max(errors.values())
    return CASE.result(worst, message=", ".join(f"{k} {v:.1e}" for k, v in errors.items())
                       + f"; zero-load contact radius {c_zero * 1e9:.1f} nm", details=errors)
