"""Bit-for-bit fingerprint of 52 scenes: a refactor that claims "results unchanged" checks it here.

Each scene is run with its trajectory; the fingerprint of a run is its drift velocity as
float.hex, its regime, and SHA-1 digests of the trajectory's and the events' bytes. The scenes
span the six models (four regimes each where the model has them), rotation, rolling resistance,
loads, normal damping and restitution, the settle methods, profiles, two-wave fields and direct
runs, prescribed histories and a free impact.

    python benchmarks/fingerprint.py --write benchmarks/results/fingerprint.json   # before
    python benchmarks/fingerprint.py --check benchmarks/results/fingerprint.json   # after

``--check`` prints every scene that differs (and in which part) and exits with status 1 if any
does. Run both with the same numba and numpy; a fingerprint says nothing across machines.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

import sawdrift as sd

#: (name, scene data) of the 52 scenes
SCENES: list[tuple[str, dict[str, Any]]] = []

_REGIMES = {  # (m*, A*): stick, drift, hopping, bouncing for compliant models at mu = 0.1
    "stick": (0.1, 0.01), "drift": (0.1, 0.316), "hop": (0.3, 1.2), "bounce": (0.1, 1.2),
}
for _model in ("mmd", "mdr", "jaeger", "hertz_mindlin_dem", "hertz_tsuji", "material_point"):
    for _label, (_m, _a) in _REGIMES.items():
        if _model == "material_point":
            _m, _a = {"stick": (0.1, 0.01), "drift": (0.1, 0.2), "hop": (0.1, 0.6),
                      "bounce": (0.1, 3.0)}[_label]
        SCENES.append((f"{_model} {_label}", {"model": _model, "particle": {"m_star": _m},
                                              "drive": {"amplitude": _a},
                                              "numerics": {"periods": 30}}))
SCENES += [
    ("mmd rotation", {"effects": {"rotation": True}, "particle": {"m_star": 0.5}}),
    ("mmd rotation hop", {"effects": {"rotation": True}, "particle": {"m_star": 1.0},
                          "drive": {"amplitude": 1.6}, "numerics": {"periods": 30}}),
    ("point rotation", {"model": "material_point", "effects": {"rotation": True},
                        "particle": {"m_star": 0.3}, "drive": {"amplitude": 0.3}}),
    ("point rotation hop", {"model": "material_point", "effects": {"rotation": True},
                            "particle": {"m_star": 0.1}, "drive": {"amplitude": 0.6}}),
    ("mmd rolling resistance", {"effects": {"rotation": True, "rolling_resistance": 0.05},
                                "particle": {"m_star": 0.1}}),
    ("jaeger rolling resistance", {"model": "jaeger", "particle": {"m_star": 0.3},
                                   "effects": {"rotation": True, "rolling_resistance": 0.5}}),
    ("mmd load", {"particle": {"m_star": 0.1, "load": 0.05}}),
    ("point load", {"model": "material_point", "particle": {"m_star": 0.1, "load": -0.05},
                    "drive": {"amplitude": 0.2}}),
    ("point load rotation", {"model": "material_point", "effects": {"rotation": True},
                             "particle": {"m_star": 1.0, "load": 0.05},
                             "drive": {"amplitude": 0.1}}),
    ("mmd load hop", {"particle": {"m_star": 0.3, "load": 0.02}, "drive": {"amplitude": 1.2}}),
    ("mmd damping", {"effects": {"normal_damping": 0.3}, "drive": {"amplitude": 1.0}}),
    ("mmd restitution", {"material": {"restitution": 0.5}, "drive": {"amplitude": 1.2}}),
    ("point restitution", {"model": "material_point", "model_params": {"restitution": 0.5},
                           "particle": {"m_star": 0.1}, "drive": {"amplitude": 1.0}}),
    ("ball vertical", {"model": "material_point", "model_params": {"restitution": 0.0},
                       "particle": {"m_star": 0.1},
                       "drive": {"amplitude": 0.988, "horizontal_ratio": 0.0}}),
    ("mmd settle heavy", {"particle": {"m_star": 300.0}, "drive": {"amplitude": 0.5},
                          "numerics": {"settle": True}}),
    ("mmd settle light", {"numerics": {"settle": True}}),
    ("mmd cone", {"particle": {"profile": {"shape": "cone"}}}),
    ("mmd power", {"particle": {"profile": {"shape": "power", "exponent": 2.5}}}),
    ("jaeger flat", {"model": "jaeger", "particle": {"profile": {"shape": "flat"}}}),
    ("mmd standing wave", {"drive": {"backward": 1.0, "position": 0.1}}),
    ("mmd direct run", {"drive": {"backward": 0.5, "wavelength": 200.0, "position": 0.04},
                        "numerics": {"periods": 40}}),
    ("mmd retrograde linear", {"drive": {"phase": 0.0}, "particle": {"m_star": 0.3}}),
    ("mmd prescribed loop", {"drive": {"kind": "prescribed", "waveform": "mindlin_loop"}}),
    ("mdr prescribed random", {"model": "mdr",
                               "drive": {"kind": "prescribed", "waveform": "random"}}),
    ("mmd impact", {"drive": {"kind": "impact", "velocity": 2.0},
                    "material": {"restitution": 0.7}}),
    ("point no vertical inertia", {"model": "material_point",
                                   "effects": {"vertical_inertia": False},
                                   "particle": {"m_star": 0.1}, "drive": {"amplitude": 0.2}}),
    ("mmd friction off", {"effects": {"friction": False}, "drive": {"amplitude": 0.5}}),
    ("mmd no horizontal wave", {"effects": {"horizontal_wave": False},
                                "drive": {"amplitude": 1.2}, "particle": {"m_star": 0.3}}),
]


def _digest(array: Any) -> str:
    if array is None:
        return "none"
    data = np.ascontiguousarray(np.asarray(array, dtype=float))
    return hashlib.sha1(data.tobytes()).hexdigest()[:16]


def fingerprint(data: dict[str, Any]) -> dict[str, str]:
    """drift (float.hex), regime, trajectory and events digests of one scene."""
    res = sd.run(sd.Scene.model_validate(data), trajectory=True)
    traj = res.trajectory
    return {
        "drift": float(res.drift_velocity).hex(),
        "regime": str(res.regime),
        "trajectory": _digest(traj.to_numpy() if traj is not None else None),
        "events": _digest(res.event_rows),
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    action = parser.add_mutually_exclusive_group(required=True)
    action.add_argument("--write", type=Path, help="write the fingerprints to this JSON file")
    action.add_argument("--check", type=Path, help="compare with the fingerprints in this file")
    args = parser.parse_args(argv)
    assert len(SCENES) == 52, len(SCENES)
    t0 = time.perf_counter()
    prints = {name: fingerprint(data) for name, data in SCENES}
    took = time.perf_counter() - t0
    if args.write:
        args.write.parent.mkdir(parents=True, exist_ok=True)
        args.write.write_text(json.dumps(prints, indent=1) + "\n")
        print(f"wrote {len(prints)} fingerprints to {args.write} ({took:.1f} s)")
        return 0
    before = json.loads(args.check.read_text())
    differ = {name: [k for k in fp if before.get(name, {}).get(k) != fp[k]]
              for name, fp in prints.items()}
    differ = {name: keys for name, keys in differ.items() if keys}
    for name, keys in differ.items():
        print(f"DIFFERS {name}: {', '.join(keys)}")
    print(f"{len(prints) - len(differ)} of {len(prints)} scenes identical bit for bit "
          f"({took:.1f} s)")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
