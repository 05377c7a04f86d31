"""The native engine against LAMMPS on one scene: drifts, regimes and both wall times."""

from __future__ import annotations

from typing import Any

from ..result.runner import run
from ..scene.schema import Scene, build_scene
from .engine import available
from .single import run_scene


def compare_native(scene: Scene, name: str = "") -> dict[str, Any]:
    """Run ``scene`` natively (compiled) and in LAMMPS, both as fixed runs of ``numerics.periods``.

    ``relative_difference`` is (V_lammps - V_native) / |V_native| of the drift velocities x*'
    (the drift ratio's, as both share the surface speed); ``same_regime`` compares the regimes.
    """
    native = run(scene.with_updates(**{"numerics.settle": False}))  # both: a fixed run
    lammps = run_scene(scene)
    v_n, v_l = native.drift_velocity, lammps.drift_velocity
    rel = (v_l - v_n) / abs(v_n) if v_n != 0.0 else float("inf") if v_l != 0.0 else 0.0
    return {
        "name": name, "native": native.drift_ratio, "lammps": lammps.drift_ratio,
        "native_velocity": v_n, "lammps_velocity": v_l, "relative_difference": rel,
        "native_regime": native.regime, "lammps_regime": lammps.regime,
        "same_regime": native.regime == lammps.regime,
        "native_s": native.wall_time_s, "lammps_s": lammps.wall_time_s,
        "steps": native.steps, "steps_per_period": native.steps_per_period,
        "rotation": scene.effects.rotation,
    }


def _dem(m_star: float, amplitude: float, mu: float, rotation: bool) -> Scene:
    return Scene(model="hertz_mindlin_dem", particle={"m_star": m_star},
                 drive={"amplitude": amplitude}, material={"mu": mu},
                 effects={"rotation": rotation}, numerics={"steps_per_period": 512, "periods": 60})


def saw_motor(periods: float = 200.0) -> Scene:
    """examples/saw_linear_motor.toml with the DEM law, a fixed run at 512 steps per period."""
    return build_scene({
        "model": "hertz_mindlin_dem",
        "device": {"frequency": "9.6 MHz", "amplitude": "10 nm", "orbit": "retrograde",
                   "horizontal_ratio": 0.68, "preload": "7.35 mN", "friction": 0.2,
                   "particle": {"radius": "0.5 mm", "density": "7850 kg/m^3",
                                "youngs_modulus": "210 GPa", "poisson": 0.3},
                   "substrate": {"youngs_modulus": "170 GPa", "poisson": 0.25}},
        "numerics": {"settle": False, "periods": periods, "steps_per_period": 512},
    })


#: the validation scenes (validation/g13*_lammps_*.py): name -> [(label, scene maker)]
VALIDATION_SCENES: dict[str, list[tuple[str, Any]]] = {
    "stick_drift": [
        ("stick m*=0.1 A*=0.002 mu=0.5", lambda: _dem(0.1, 0.002, 0.5, False)),
        ("drift m*=0.1 A*=0.316 mu=0.1", lambda: _dem(0.1, 0.316, 0.1, False)),
        ("drift, rotation on", lambda: _dem(0.1, 0.316, 0.1, True)),
    ],
    "hopping": [
        ("hop m*=0.3 A*=1.2 mu=0.2", lambda: _dem(0.3, 1.2, 0.2, False)),
        ("hop m*=1 A*=1.6 mu=0.2, rotation on", lambda: _dem(1.0, 1.6, 0.2, True)),
    ],
    "device": [(f"SAW motor {amp}, 200 periods",
                lambda amp=amp: saw_motor().with_updates(**{"device.amplitude": amp}))
               for amp in ("2 nm", "10 nm", "20 nm", "30 nm")],
}


def lammps_missing() -> str | None:
    """None if LAMMPS runs here, else the one-line reason."""
    ok, why = available()
    return None if ok else why


def compare_set(key: str) -> list[dict[str, Any]]:
    """:func:`compare_native` on every scene of ``VALIDATION_SCENES[key]``."""
    return [compare_native(make(), label) for label, make in VALIDATION_SCENES[key]]


def describe(rows: list[dict[str, Any]]) -> str:
    """One sentence per scene: regimes, drift ratios, relative difference, both wall times."""
    return "; ".join(
        f"{r['name']}: {r['native_regime']}/{r['lammps_regime']}, drift ratio {r['native']:.6g} "
        f"native vs {r['lammps']:.6g} LAMMPS ({r['relative_difference']:+.2e}), "
        f"{r['native_s']:.3g} s vs {r['lammps_s']:.3g} s" for r in rows)
