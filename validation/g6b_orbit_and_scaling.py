"""Physical units: the orbit mirror and dimensional consistency of device scenes.

* Orbit: reversing the orbit is the mirror x -> -x, so a retrograde run gives exactly the negated
  drift of the prograde one (mmd, m* = 0.1, A* = 0.316, and the material point at m* = 0.01,
  A* = 2).
* Dimensional consistency: two devices with different frequency, preload and amplitude, chosen so
  that m*, A* and theta coincide, give the same drift ratio, and drift speeds in the ratio of
  their a0 f. Device B doubles the frequency; its preload is raised so that m* = a0 m f^2/(M g)
  is unchanged (solved by bisection on the preload), and its amplitude follows a0.
"""

from __future__ import annotations

import sawdrift as sd
from sawdrift.scene.device import normalized
from sawdrift.validation import Case, CaseResult

CASE = Case(
    name="orbit_and_scaling",
    group="device",
    title="Retrograde = exact mirror of prograde (drift negated); two devices with equal m*, A*, "
    "theta give equal drift ratios and speeds in the ratio of a0 f; value: largest relative "
    "mismatch",
    tolerance=1e-9,
    quick=True,
)

BASE = {
    "frequency": "1 MHz", "amplitude": "10 nm", "friction": 0.2, "preload": "1 mN",
    "orbit": "retrograde",
    "particle": {"radius": "0.5 mm", "density": "7850 kg/m^3", "youngs_modulus": "210 GPa",
                 "poisson": 0.3},
    "substrate": {"youngs_modulus": "170 GPa", "poisson": 0.25},
}


def _scene(device: dict) -> sd.Scene:
    return sd.scene.build_scene({"model": "mmd", "device": device, "numerics": {"periods": 40}})


def _matched_device() -> dict:
    """Device B: 2x the frequency, a preload that restores m*, an amplitude that restores A*."""
    target = normalized(_scene(BASE).device)

    def m_star(preload: float) -> float:
        return normalized(_scene(dict(BASE, frequency="2 MHz", preload=f"{preload} N")).device)["m_star"]

    lo, hi = 1e-3, 1.0
    for _ in range(200):
        mid = (lo * hi) ** 0.5
        lo, hi = (mid, hi) if m_star(mid) > target["m_star"] else (lo, mid)
    dev = dict(BASE, frequency="2 MHz", preload=f"{(lo * hi) ** 0.5!r} N")
    a0_b = normalized(_scene(dev).device)["a0_m"]
    return dict(dev, amplitude=f"{target['amplitude'] * a0_b!r} m")


def run() -> CaseResult:
    """Mirror and scaling checks."""
    errs, notes = [], []
    for fields in (dict(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 0.316}),
                   dict(model="material_point", particle={"m_star": 0.01}, drive={"amplitude": 2.0})):
        pro = sd.run(sd.Scene(**fields))
        retro = sd.run(sd.Scene(**{**fields, "drive": {**fields["drive"], "orbit": "retrograde"}}))
        errs.append(abs(retro.drift_ratio + pro.drift_ratio) / abs(pro.drift_ratio))
        notes.append(f"{fields['model']}: prograde {pro.drift_ratio:+.6f} ({pro.regime}), "
                     f"retrograde {retro.drift_ratio:+.6f} ({retro.regime})")
    a, b = _scene(BASE), _scene(_matched_device())
    na, nb = normalized(a.device), normalized(b.device)
    match = max(abs(nb[k] / na[k] - 1) for k in ("m_star", "amplitude", "theta"))
    ra, rb = sd.run(a), sd.run(b)
    ratio_err = abs(rb.drift_ratio / ra.drift_ratio - 1)
    speed_err = abs((rb.extra["drift_speed_m_s"] / ra.extra["drift_speed_m_s"])
                    / ((nb["a0_m"] * 2e6) / (na["a0_m"] * 1e6)) - 1)
    errs += [ratio_err, speed_err]
    notes.append(f"devices A (1 MHz, 1 mN) and B (2 MHz, {b.device.preload:.4g} N, "
                 f"{b.device.amplitude:.4g} m): m*, A*, theta equal to {match:.1e}; drift ratio "
                 f"{ra.drift_ratio:.6f} vs {rb.drift_ratio:.6f}; speeds {ra.extra['drift_speed_m_s']:.4g}"
                 f" and {rb.extra['drift_speed_m_s']:.4g} m/s")
    return CASE.result(max(errs), require=match < 1e-9, message="; ".join(notes))
