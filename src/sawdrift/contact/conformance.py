"""The conformance suite: the checks every contact model is held to, built-in or third-party.

Each check returns a value, the tolerance it is held to and a status:

* ``pass`` - within tolerance;
* ``fail`` - outside it;
* ``declared`` - outside it, and the model declares this deviation in its capabilities
  (``Capabilities.deviations``, a one-line reason per check), so a comparison shows it, never
  hides it;
* ``skipped`` - the check does not apply (a rigid model has no displacement law; split
  invariance is checked only for laws that claim exactness on straight paths).

Checks (docs/physics.md, "Passivity" and "Contact laws"):

``passivity``
    The normal law is elastic, so over a closed path in (a*, b*) a passive contact dissipates:
    the loop work W = closed integral of T* db* is >= 0 for every cycle, in both orientations.
    Five cycle shapes with a* varying (rectangle, diamond, ellipse, a cycle into full sliding,
    a cycle through contact loss), each driven ten times round after a straight approach from
    (0, 0); the value is the most negative loop work of a single cycle. Tolerance: 1e-6 of the
    cycle's gross work sum |T*| |db*| (the trapezoidal rule on 400 samples per side).
``coulomb_bound``
    |T*| <= N* on random histories with contact loss; value: max (|T*| - N*), tolerance
    1e-9 (1 + max N*).
``kernel_vs_reference``
    The compiled kernel and the pure-Python reference agree on random histories; value:
    max |T*_compiled - T*_python| / (1 + max N*), tolerance 1e-9.
``split_invariance``
    For a law exact on straight paths: one step equals the same straight segment cut into
    7 sub-steps; value: max |dT*| / (1 + max N*), tolerance 1e-9.
``contact_loss_reset``
    After contact is lost (a* <= 0), a new contact behaves as a fresh history; value: max |dT*|
    against a fresh history driven over the same path, tolerance 1e-12.
``replay``
    A copy of a history (:meth:`ContactHistory.copy`) replays the rest of the path exactly;
    value: max |dT*|, tolerance 0.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from ..errors import SceneError
from .base import ContactHistory, ContactModel

#: samples per straight side of a cycle
SIDE = 400


@dataclass(frozen=True)
class Check:
    """One conformance check of one model."""

    name: str
    status: str
    value: float
    tolerance: float
    detail: str

    def to_json(self) -> dict[str, Any]:
        """JSON-ready dict (non-finite floats become None)."""
        out = asdict(self)
        for key in ("value", "tolerance"):
            if not math.isfinite(out[key]):
                out[key] = None
        return out


@dataclass(frozen=True)
class Conformance:
    """The result of :func:`check_model`."""

    model: str
    checks: tuple[Check, ...]

    @property
    def passed(self) -> bool:
        """True if no check failed (declared and skipped checks do not fail)."""
        return all(c.status != "fail" for c in self.checks)

    def get(self, name: str) -> Check:
        """The check called ``name``."""
        return next(c for c in self.checks if c.name == name)

    def to_json(self) -> dict[str, Any]:
        """``{"model": ..., "checks": [{"name", "status", "value", "tolerance", "detail"}]}``."""
        return {"model": self.model, "checks": [c.to_json() for c in self.checks]}

    def table(self) -> str:
        """A readable table, one line per check."""
        rows = [f"model {self.model!r}: {'PASS' if self.passed else 'FAIL'}"]
        for c in self.checks:
            val = "-" if not math.isfinite(c.value) else f"{c.value:.3g}"
            tol = "-" if not math.isfinite(c.tolerance) else f"{c.tolerance:.3g}"
            rows.append(f"  {c.name:<20} {c.status:<9} value {val:>10}  tolerance {tol:>9}  {c.detail}")
        return "\n".join(rows)


# -- paths -------------------------------------------------------------------------------------


def _polyline(vertices: list[tuple[float, float]], per_side: int = SIDE) -> tuple[np.ndarray, np.ndarray]:
    from ..dynamics.prescribed import polyline

    return polyline(vertices, per_side)


def cycles() -> dict[str, list[tuple[float, float]]]:
    """Closed (a*, b*) cycles of the passivity check, each as its vertices (first = last)."""
    theta = np.linspace(0.0, 2.0 * np.pi, 17)
    ellipse = [(1.5 + 0.5 * math.cos(t), 0.3 * math.sin(t)) for t in theta]
    return {
        "rectangle": [(1.0, 0.0), (1.0, 0.2), (2.0, 0.2), (2.0, 0.0), (1.0, 0.0)],
        "diamond": [(1.5, -0.3), (2.0, 0.0), (1.5, 0.3), (1.0, 0.0), (1.5, -0.3)],
        "ellipse": ellipse,
        "full_slip": [(1.0, 0.0), (1.0, 3.0), (2.0, 3.0), (2.0, -3.0), (1.0, -3.0), (1.0, 0.0)],
        "contact_loss": [(1.0, 0.0), (1.0, 0.5), (-0.2, 0.5), (-0.2, -0.5), (1.5, -0.5),
                         (1.0, 0.0)],
    }


def loop_works(model: ContactModel, vertices: list[tuple[float, float]], laps: int = 10,
               engine: str = "compiled") -> tuple[np.ndarray, np.ndarray]:
    """Loop work sum of T* db* (trapezoidal) of each lap, and each lap's gross work sum |T*||db*|."""
    start = vertices[0]
    approach = _polyline([(0.0, 0.0), start])
    lap_a, lap_b = _polyline(vertices)
    a = np.concatenate([approach[0], *[lap_a[1:]] * laps])
    b = np.concatenate([approach[1], *[lap_b[1:]] * laps])
    _, t = ContactHistory(model, engine).drive(a, b)
    n0 = approach[0].size - 1
    per = lap_a.size - 1
    works, gross = np.empty(laps), np.empty(laps)
    for k in range(laps):
        sl = slice(n0 + k * per, n0 + (k + 1) * per + 1)
        tb, db = t[sl], np.diff(b[sl])
        mid = 0.5 * (tb[1:] + tb[:-1])
        works[k] = float(np.sum(mid * db))
        gross[k] = float(np.sum(np.abs(mid) * np.abs(db)))
    return works, gross


def random_history(seed: int, n: int = 600) -> tuple[np.ndarray, np.ndarray]:
    """A random piecewise-linear (a*, b*) walk that loses and regains contact."""
    rng = np.random.default_rng(seed)
    av = np.clip(np.cumsum(rng.normal(0.0, 0.25, 40)) + 1.0, -0.4, 3.0)
    bv = np.cumsum(rng.normal(0.0, 0.4, 40))
    return _polyline([(0.0, 0.0), *zip(av.tolist(), bv.tolist(), strict=True)], n // 40)


# -- checks ------------------------------------------------------------------------------------


def _status(name: str, ok: bool, model: ContactModel) -> tuple[str, str]:
    if ok:
        return "pass", ""
    reason = dict(model.declared_deviations()).get(name)
    return ("declared", reason) if reason else ("fail", "")


def _passivity(model: ContactModel) -> Check:
    worst, worst_where, tol_at_worst = math.inf, "", 0.0
    ok = True
    for shape, verts in cycles().items():
        for orient, vv in (("forward", verts), ("reverse", verts[::-1])):
            works, gross = loop_works(model, vv)
            tol = 1e-6 * gross + 1e-12
            ok &= bool(np.all(works >= -tol))
            k = int(np.argmin(works))
            if works[k] < worst:
                worst, worst_where, tol_at_worst = float(works[k]), f"{shape} {orient}", float(tol[k])
    status, reason = _status("passivity", ok, model)
    detail = (f"most negative loop work {worst:.3g} ({worst_where}); passes if >= -tolerance"
              + (f"; {reason}" if reason else ""))
    return Check("passivity", status, worst, tol_at_worst, detail)


def _coulomb(model: ContactModel) -> Check:
    excess, n_max = -math.inf, 0.0
    for seed in range(3):
        a, b = random_history(seed)
        n, t = ContactHistory(model).drive(a, b)
        excess = max(excess, float(np.max(np.abs(t) - n)))
        n_max = max(n_max, float(n.max()))
    tol = 1e-9 * (1.0 + n_max)
    status, reason = _status("coulomb_bound", excess <= tol, model)
    return Check("coulomb_bound", status, excess, tol, "max (|T*| - N*) on 3 random histories"
                 + (f"; {reason}" if reason else ""))


def _kernel_vs_reference(model: ContactModel) -> Check:
    if model.kernel is None:
        return Check("kernel_vs_reference", "skipped", math.nan, math.nan, "no compiled kernel")
    err = 0.0
    for seed in range(3):
        a, b = random_history(seed + 10)
        nc, tc = ContactHistory(model, "compiled").drive(a, b)
        npy, tpy = ContactHistory(model, "python").drive(a, b)
        err = max(err, float(np.max(np.abs(tc - tpy)) / (1.0 + nc.max())))
    status, reason = _status("kernel_vs_reference", err <= 1e-9, model)
    return Check("kernel_vs_reference", status, err, 1e-9, "3 random histories with contact loss"
                 + (f"; {reason}" if reason else ""))


def _split(model: ContactModel) -> Check:
    if not model.capabilities.straight_path_exact:
        return Check("split_invariance", "skipped", math.nan, math.nan,
                     "the model does not claim exactness on straight paths")
    a, b = random_history(21, 200)
    k = 7
    s = np.arange(1, k + 1) / k
    fine_a = np.concatenate([[a[0]], *[a[i] + (a[i + 1] - a[i]) * s for i in range(a.size - 1)]])
    fine_b = np.concatenate([[b[0]], *[b[i] + (b[i + 1] - b[i]) * s for i in range(b.size - 1)]])
    n1, t1 = ContactHistory(model).drive(a, b)
    _, t7 = ContactHistory(model).drive(fine_a, fine_b)
    err = float(np.max(np.abs(t1 - t7[::k])) / (1.0 + n1.max()))
    status, reason = _status("split_invariance", err <= 1e-9, model)
    return Check("split_invariance", status, err, 1e-9, f"every step cut into {k} sub-steps"
                 + (f"; {reason}" if reason else ""))


def _contact_loss(model: ContactModel) -> Check:
    a1, b1 = _polyline([(0.0, 0.0), (1.5, 0.4), (1.0, -0.6), (2.0, 0.3), (-0.1, 0.5)], 50)
    a2, b2 = _polyline([(-0.1, 0.5), (0.0, 0.7), (1.2, 1.4), (0.8, 0.2), (1.6, 0.9)], 50)
    used = ContactHistory(model)
    used.drive(a1, b1)
    _, t_used = used.drive(a2[1:], b2[1:])
    fresh = ContactHistory(model)
    fresh.drive(np.array([0.0]), np.array([0.7]))
    _, t_fresh = fresh.drive(a2[2:], b2[2:])
    err = float(np.max(np.abs(t_used[1:] - t_fresh)))
    status, reason = _status("contact_loss_reset", err <= 1e-12, model)
    return Check("contact_loss_reset", status, err, 1e-12, "re-contact after a* <= 0 vs a fresh history"
                 + (f"; {reason}" if reason else ""))


def _replay(model: ContactModel) -> Check:
    a, b = random_history(31)
    half = a.size // 2
    h = ContactHistory(model)
    h.drive(a[:half], b[:half])
    twin = h.copy()
    _, t1 = h.drive(a[half:], b[half:])
    _, t2 = twin.drive(a[half:], b[half:])
    err = float(np.max(np.abs(t1 - t2)))
    status, reason = _status("replay", err == 0.0, model)
    return Check("replay", status, err, 0.0, "a copy replays the second half of a random history"
                 + (f"; {reason}" if reason else ""))


CHECKS = (_passivity, _coulomb, _kernel_vs_reference, _split, _contact_loss, _replay)
CHECK_NAMES = ("passivity", "coulomb_bound", "kernel_vs_reference", "split_invariance",
               "contact_loss_reset", "replay")


def check_model(name: str, **params: Any) -> Conformance:
    """Run the conformance suite on the registered model ``name`` with parameters ``params``.

    Raises
    ------
    ModelNotFoundError
        If no model has that name.
    SceneError
        If a parameter is unknown or out of range (one line naming it).
    """
    from pydantic import ValidationError

    from ..scene.schema import format_validation_error
    from .registry import get_model

    cls = get_model(name)
    try:
        model = cls(cls.Params.model_validate(params))
    except ValidationError as exc:
        raise SceneError("model_params." + format_validation_error(exc)) from None
    if cls.capabilities.rigid:
        skipped = tuple(Check(n, "skipped", math.nan, math.nan, "rigid model: no displacement law")
                        for n in CHECK_NAMES)
        return Conformance(name, skipped)
    return Conformance(name, tuple(check(model) for check in CHECKS))
