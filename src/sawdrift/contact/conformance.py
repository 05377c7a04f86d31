"""The conformance suite: the checks every contact model is held to, built-in or third-party.

Each check returns a value, the tolerance it is held to and a status:

* ``pass`` - within tolerance;
* ``fail`` - outside it;
* ``declared`` - outside it, and the model declares this deviation in its capabilities
  (``Capabilities.deviations``, a one-line reason per check), so a comparison shows it, never
  hides it;
* ``skipped`` - the check does not apply (a rigid model has no displacement law; split
  invariance is checked only for laws that claim exactness on straight paths; velocity
  independence only for laws that declare ``uses_velocity = False``).

Every check runs once per profile the model declares (``Capabilities.profiles``: the sphere,
cone and flat punch, a power law of exponent :data:`POWER_EXPONENT` for ``power``, and the
tabulated law :func:`table_law` for ``table``), or for the one profile asked for.

Paths are sampled straight sides, each side traversed in unit time t*, so the velocities
(a*', b*') passed with every step are the backward differences of the samples (a side's length
per unit time). Random histories come in two sizes: a* up to 3 and a* up to :data:`LARGE_A`.

Checks (docs/physics.md, "Passivity" and "Contact laws"):

``normalization``
    N* = N / (M g) and a* = a / a0 with a0 the static compression under M g, so a quasi-static
    loading from 0 to a* = 1 gives N* = 1; value |N*(1) - 1|, tolerance 1e-6 (as a profile
    table's N(1)).
``passivity``
    Over a closed path in (a*, b*) a passive contact does no net work on the particle: the loop
    work W = closed integral of (N* da* + T* db*) is >= 0 for every cycle, in both orientations,
    at the cycle's velocities (so a normal damping that adds energy fails, and an elastic normal
    law contributes zero). Eight cycle shapes (a pure normal loading/unloading, rectangle,
    diamond, ellipse, a cycle into full sliding, a cycle through contact loss, a rectangle at
    a* from 5 to 15, a normal loading through contact loss to a* = -0.4), each driven ten times
    round after a straight approach from (0, 0); the
    value is the most negative loop work of a single cycle (the trapezoidal rule on 400 samples
    per side). Tolerance: 1e-6 of the cycle's gross work sum (|N*| |da*| + |T*| |db*|) plus the
    rule's error estimate, sum (|da*| |d2 N*| + |db*| |d2 T*|) / 12 with d2 the second
    differences (an elastic normal law's work is zero up to that error).
``coulomb_bound``
    |T*| <= N* on random histories with contact loss; value: max (|T*| - N*), tolerance
    1e-9 (1 + max N*).
``kernel_vs_reference``
    The compiled kernel and the pure-Python reference give the same (N*, T*) on random
    histories, velocities included; value: max(|dN*|, |dT*|) / (1 + max N*), tolerance 1e-9.
``velocity_independence``
    A model declaring ``uses_velocity = False`` gives the same (N*, T*) whether a random history
    is driven with its velocities or with zero velocities; value: max(|dN*|, |dT*|), tolerance 0.
``split_invariance``
    For a law exact on straight paths: one step equals the same straight segment, at the same
    velocity, cut into 7 sub-steps; value: max(|dN*|, |dT*|) / (1 + max N*), tolerance 1e-9.
``contact_loss_reset``
    After contact is lost (a* <= 0), a new contact behaves as a fresh history; value:
    max(|dN*|, |dT*|) against a fresh history driven over the same path, tolerance 1e-12.
``replay``
    A copy of a history (:meth:`ContactHistory.copy`) replays the rest of the path exactly;
    value: max(|dN*|, |dT*|), tolerance 0.
"""

from __future__ import annotations

import math
import pathlib
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import asdict, dataclass, replace
from typing import Any

import numpy as np

from ..errors import SceneError, first_line
from ..scene.profiles import Profile
from ..scene.schema import format_validation_error
from .adhesion import Adhesion, adhesive_model, pulloff, supports_adhesion
from .base import ContactModel
from .conformance_paths import LARGE_A, Path, cycles, histories, loop_work_parts, path
from .conformance_paths import SIDE as SIDE  # re-exported: the paths are part of this interface
from .conformance_paths import loop_works as loop_works
from .conformance_paths import random_history as random_history
from .history import ContactHistory
from .registry import get_model
from .slots import _SlotKernel

#: exponent of the representative ``power`` profile
POWER_EXPONENT = 2.5
#: order in which a check's statuses over several profiles are reported (the worst first)
_SEVERITY = {"fail": 0, "declared": 1, "pass": 2, "skipped": 3}


@dataclass(frozen=True)
class Check:
    """One conformance check of one model on one profile."""

    name: str
    status: str
    value: float
    tolerance: float
    detail: str
    profile: str = ""

    def to_json(self) -> dict[str, Any]:
        """JSON-ready dict (non-finite floats become None)."""
        out = asdict(self)
        for key in ("value", "tolerance"):
            if not math.isfinite(out[key]):
                out[key] = None
        return out


@dataclass(frozen=True)
class Conformance:
    """The result of :func:`check_model`: every check on every profile checked."""

    model: str
    checks: tuple[Check, ...]
    #: the normal law of each profile checked, ``(profile, "sphere N* = a*^1.5")`` pairs
    laws: tuple[tuple[str, str], ...] = ()

    @property
    def passed(self) -> bool:
        """True if no check failed (declared and skipped checks do not fail)."""
        return all(c.status != "fail" for c in self.checks)

    @property
    def failures(self) -> tuple[Check, ...]:
        """The checks that failed."""
        return tuple(c for c in self.checks if c.status == "fail")

    @property
    def profiles(self) -> tuple[str, ...]:
        """The profiles checked, in order."""
        return tuple(dict.fromkeys(c.profile for c in self.checks))

    def get(self, name: str, profile: str | None = None) -> Check:
        """The check called ``name`` on ``profile``; without a profile, its worst result.

        Worst means the first of ``fail``, ``declared``, ``pass``, ``skipped`` over the profiles
        (the first profile among equals).
        """
        found = [c for c in self.checks if c.name == name and profile in (None, c.profile)]
        if not found:
            raise KeyError(f"no check {name!r}" + (f" on profile {profile!r}" if profile else ""))
        return min(found, key=lambda c: _SEVERITY[c.status])

    def to_json(self) -> dict[str, Any]:
        """``{"model", "profiles", "checks": [{"name", "profile", "status", "value", ...}]}``."""
        return {"model": self.model, "profiles": dict(self.laws),
                "checks": [c.to_json() for c in self.checks]}

    def table(self) -> str:
        """A readable table, one line per check and profile."""
        declared = sorted({c.name for c in self.checks if c.status == "declared"})
        # a deviation the model declares is shown in the verdict, not only in its row
        note = f" (declared deviations: {', '.join(declared)})" if declared else ""
        rows = [f"model {self.model!r}: {'PASS' if self.passed else 'FAIL'}{note}"]
        if self.laws:
            rows.append("  profiles: " + "; ".join(law for _, law in self.laws))
        width = max((len(c.profile) for c in self.checks), default=6)
        for c in self.checks:
            val = "-" if not math.isfinite(c.value) else f"{c.value:.3g}"
            tol = "-" if not math.isfinite(c.tolerance) else f"{c.tolerance:.3g}"
            rows.append(f"  {c.profile:<{width}}  {c.name:<21} {c.status:<9} value {val:>10}  "
                        f"tolerance {tol:>9}  {c.detail}")
        return "\n".join(rows)


# -- profiles ----------------------------------------------------------------------------------


def table_law(a: np.ndarray) -> np.ndarray:
    """The representative tabulated normal law, N* = (a*^1.5 + a*^2) / 2 (N*(1) = 1)."""
    return 0.5 * (a**1.5 + a**2)


@contextmanager
def profiles_for(shapes: tuple[str, ...]) -> Iterator[dict[str, Profile]]:
    """A representative :class:`Profile` of each shape (a table is written to a temporary file).

    ``power`` gets the exponent :data:`POWER_EXPONENT`; ``table`` the law :func:`table_law`
    on a* in [0, 25] (it covers the large histories).
    """
    with tempfile.TemporaryDirectory(prefix="sawdrift-conformance-") as tmp:
        out: dict[str, Profile] = {}
        for shape in shapes:
            if shape == "power":
                out[shape] = Profile(shape="power", exponent=POWER_EXPONENT)
            elif shape == "table":
                file = pathlib.Path(tmp) / "table_law.csv"
                a = np.linspace(0.0, 25.0, 501)
                rows = "\n".join(f"{x!r},{y!r}" for x, y in zip(a.tolist(), table_law(a).tolist(),
                                                               strict=True))
                file.write_text("a,N\n" + rows + "\n", encoding="utf-8")
                out[shape] = Profile(shape="table", file=str(file))
            else:
                out[shape] = Profile(shape=shape)
        yield out


def describe_profile(profile: Profile, representative: bool) -> str:
    """One phrase naming the normal law a profile gives, N*(a*)."""
    if profile.shape == "table":
        return ("table N* = (a*^1.5 + a*^2)/2" if representative
                else f"table {pathlib.Path(profile.file or '').name}")
    return f"{profile.shape} N* = a*^{profile.p:g}"


# -- checks ------------------------------------------------------------------------------------


def _check(model: ContactModel, name: str, ok: bool, value: float, tol: float, detail: str) -> Check:
    """``pass`` if ok, else ``declared`` (with the model's reason) or ``fail``."""
    reason = "" if ok else dict(model.declared_deviations()).get(name, "")
    status = "pass" if ok else ("declared" if reason else "fail")
    return Check(name, status, value, tol, detail + (f"; {reason}" if reason else ""))


def _engine(model: ContactModel) -> str:
    """The engine the dynamics runs the model with: the kernel if it has one."""
    return "compiled" if model.kernel is not None else "python"


def _diff(f1: tuple[np.ndarray, np.ndarray], f2: tuple[np.ndarray, np.ndarray]) -> float:
    """max(|dN*|, |dT*|) between two force histories."""
    return float(max(np.max(np.abs(f1[0] - f2[0])), np.max(np.abs(f1[1] - f2[1]))))


def _normalization(model: ContactModel) -> Check:
    if pulloff(model) > 0.0:
        return _pulloff_normalization(model)
    p = path([(0.0, 0.0), (1.0, 0.0)], 100).still()
    n, _ = p.drive(ContactHistory(model, _engine(model)))
    err = abs(float(n[-1]) - 1.0)
    return _check(model, "normalization", err <= 1e-6, err, 1e-6,
                  f"N*(1) = {float(n[-1]):.9g} after a quasi-static loading from 0; must be 1 "
                  "(N* = N/(M g), a0 the static compression)")


def _pulloff_normalization(model: ContactModel) -> Check:
    """An adhesive law: the largest tensile force of a quasi-static retraction is F*_pull."""
    pull = pulloff(model)
    low = model.adhesion.detach_overlap - 0.05  # type: ignore[attr-defined]
    p = path([(0.0, 0.0), (1.0, 0.0), (low, 0.0)], 20000).still()
    n, _ = p.drive(ContactHistory(model, _engine(model)))
    err = abs(-float(n.min()) - pull)
    tol = 1e-6 * (1.0 + pull)
    return _check(model, "normalization", err <= tol, err, tol,
                  f"pull-off {-float(n.min()):.9g} on a quasi-static retraction; must be the law's "
                  f"F*_pull = {pull:.9g} (material.adhesion, the pull-off over M g)")


def _passivity(model: ContactModel) -> Check:
    worst, worst_where, tol_at_worst = math.inf, "", 0.0
    ok, unfinished = True, 0
    for shape, verts in cycles().items():
        for orient, vv in (("forward", verts), ("reverse", verts[::-1])):
            normal, tangential, gross, quad = loop_work_parts(model, vv, engine=_engine(model))
            works, tol = normal + tangential, 1e-6 * gross + quad + 1e-12
            finite = np.isfinite(works)
            if not finite.all():
                # judged on the finite cycles, the others being finite_forces' failure: a NaN
                # compared false with the bound and failed the check, whose value was a finite
                # cycle's that passed (-5.55e-17 against a tolerance of 3.9e-6)
                unfinished += int((~finite).sum())
                works, tol = works[finite], tol[finite]
                if works.size == 0:
                    continue
            ok &= bool(np.all(works >= -tol))
            k = int(np.argmin(works))
            if works[k] < worst:
                worst, tol_at_worst = float(works[k]), float(tol[k])
                worst_where = (f"{shape} {orient}: normal {normal[k]:.3g}, tangential "
                               f"{tangential[k]:.3g}")
    left = (f"; {unfinished} cycles with non-finite work left to finite_forces"
            if unfinished else "")
    return _check(model, "passivity", ok, worst if math.isfinite(worst) else math.nan,
                  tol_at_worst, f"most negative loop work of N* da* + T* db* {worst:.3g} "
                  f"({worst_where}); passes if >= -tolerance" + left)


def _finite(model: ContactModel) -> Check:
    """N* and T* finite on the random histories the other checks drive: a NaN compares false
    with every bound, so the checks after this one would pass a law that returns it (one that
    returned NaN above a* = 15 passed all nine, and a run later failed on a 'too coarse step')."""
    bad, where = 0, ""
    for p in histories(range(3)):
        n, t = p.drive(ContactHistory(model, _engine(model)))
        wrong = ~(np.isfinite(n) & np.isfinite(t))
        if wrong.any() and not bad:
            k = int(np.argmax(wrong))
            where = f"; first at step {k} (N* = {n[k]:.6g}, T* = {t[k]:.6g})"
        bad += int(wrong.sum())
    return _check(model, "finite_forces", bad == 0, float(bad), 0.0,
                  f"non-finite (N*, T*) on 6 random histories up to a* = {LARGE_A:g}: {bad}"
                  + where)


def _coulomb(model: ContactModel) -> Check:
    excess, n_max, unfinished = -math.inf, 0.0, 0
    pull2 = 2.0 * pulloff(model)  # an adhesive contact slides at |N* + 2 F*_pull|
    for p in histories(range(3)):
        n, t = p.drive(ContactHistory(model, _engine(model)))
        finite = np.isfinite(n) & np.isfinite(t)
        if not finite.all():
            # judged on the finite samples, the others being finite_forces' failure (the value
            # was max(-inf, nan): null, shown beside a pass)
            unfinished += int((~finite).sum())
            n, t = n[finite], t[finite]
            if n.size == 0:
                continue
        limit = np.where((n != 0.0) | (t != 0.0), np.abs(n + pull2), 0.0)
        excess = max(excess, float(np.max(np.abs(t) - limit)))
        n_max = max(n_max, float(n.max()))
    tol = 1e-9 * (1.0 + n_max + pull2)
    bound = "|N* + 2 F*_pull|" if pull2 else "N*"
    left = f"; {unfinished} non-finite samples left to finite_forces" if unfinished else ""
    return _check(model, "coulomb_bound", excess <= tol,
                  excess if math.isfinite(excess) else math.nan, tol,
                  f"max (|T*| - {bound}) on 6 random histories up to a* = {LARGE_A:g}" + left)


def _kernel_vs_reference(model: ContactModel) -> Check:
    if model.kernel is None:
        return Check("kernel_vs_reference", "skipped", math.nan, math.nan, "no compiled kernel")
    err = 0.0
    for p in histories(range(10, 13)):
        compiled = p.drive(ContactHistory(model, "compiled"))
        python = p.drive(ContactHistory(model, "python"))
        err = max(err, _diff(compiled, python) / (1.0 + float(compiled[0].max())))
    return _check(model, "kernel_vs_reference", err <= 1e-9, err, 1e-9,
                  f"(N*, T*) on 6 random histories with contact loss, up to a* = {LARGE_A:g}, "
                  "with their velocities")


def _velocity_independence(model: ContactModel) -> Check:
    if model.capabilities.uses_velocity:
        return Check("velocity_independence", "skipped", math.nan, math.nan,
                     "the model declares uses_velocity; every check drives real velocities")
    err = 0.0
    for p in histories(range(40, 42)):
        moving = p.drive(ContactHistory(model, _engine(model)))
        still = p.still().drive(ContactHistory(model, _engine(model)))
        err = max(err, _diff(moving, still))
    return _check(model, "velocity_independence", err == 0.0, err, 0.0,
                  "uses_velocity = False: 4 random histories driven with and without velocities")


def _split(model: ContactModel) -> Check:
    if not model.capabilities.straight_path_exact:
        return Check("split_invariance", "skipped", math.nan, math.nan,
                     "the model does not claim exactness on straight paths")
    k = 7
    s = np.arange(1, k + 1) / k
    err = 0.0
    for p in histories([21]):
        a, b = p.a, p.b
        fine = Path(
            np.concatenate([[a[0]], *[a[i] + (a[i + 1] - a[i]) * s for i in range(a.size - 1)]]),
            np.concatenate([[b[0]], *[b[i] + (b[i + 1] - b[i]) * s for i in range(b.size - 1)]]),
            np.concatenate([p.adot[:1], np.repeat(p.adot[1:], k)]),
            np.concatenate([p.bdot[:1], np.repeat(p.bdot[1:], k)]), p.dt / k)
        one = p.drive(ContactHistory(model, _engine(model)))
        n7, t7 = fine.drive(ContactHistory(model, _engine(model)))
        err = max(err, _diff(one, (n7[::k], t7[::k])) / (1.0 + float(one[0].max())))
    return _check(model, "split_invariance", err <= 1e-9, err, 1e-9,
                  f"every step cut into {k} sub-steps at its velocity, 2 random histories")


def _contact_loss(model: ContactModel) -> Check:
    # an adhesive contact holds on to its detach overlap: the path goes below it
    out = min(-0.1, getattr(getattr(model, "adhesion", None), "detach_overlap", 0.0) - 0.05)
    p1 = path([(0.0, 0.0), (1.5, 0.4), (1.0, -0.6), (2.0, 0.3), (out, 0.5)], 50)
    p2 = path([(out, 0.5), (0.0, 0.7), (1.2, 1.4), (0.8, 0.2), (1.6, 0.9)], 50)
    used = ContactHistory(model, _engine(model))
    p1.drive(used)
    n_used, t_used = p2[1:].drive(used)
    fresh = ContactHistory(model, _engine(model))
    p2[1:2].still().drive(fresh)
    n_fresh, t_fresh = p2[2:].drive(fresh)
    err = _diff((n_used[1:], t_used[1:]), (n_fresh, t_fresh))
    return _check(model, "contact_loss_reset", err <= 1e-12, err, 1e-12,
                  "re-contact after a* <= 0 vs a fresh history")


def _replay(model: ContactModel) -> Check:
    err = 0.0
    for p in histories([31]):
        half = p.a.size // 2
        h = ContactHistory(model, _engine(model))
        p[:half].drive(h)
        twin = h.copy()
        err = max(err, _diff(p[half:].drive(h), p[half:].drive(twin)))
    return _check(model, "replay", err == 0.0, err, 0.0,
                  "a copy replays the second half of 2 random histories")


def _normal_slot(model: ContactModel) -> Check:
    import inspect

    if not isinstance(inspect.getattr_static(type(model), "kernel", None), _SlotKernel):
        return Check("normal_slot", "skipped", math.nan, math.nan,
                     "a whole contact kernel: its N* is its own")
    normal, pp = model.normal_law()
    fs, is_ = np.zeros(1), np.zeros(1, dtype=np.int64)
    err = 0.0
    for p in histories([41]):
        n, _ = p.still().drive(ContactHistory(model, _engine(model)))
        ref = np.array([normal(fs, is_, pp, a, 0.0, 0.0, 0.0)[0] for a in p.a.tolist()])
        err = max(err, float(np.max(np.abs(n - ref))))
    return _check(model, "normal_slot", err == 0.0, err, 0.0,
                  "N* of the composed contact against the normal slot's N*(a*), bit for bit, on 2 "
                  f"quasi-static random histories with contact loss, up to a* = {LARGE_A:g} (a "
                  "step that hands N* back must hand the slot's)")


CHECKS = (_finite, _normalization, _passivity, _coulomb, _kernel_vs_reference,
          _velocity_independence, _split, _contact_loss, _replay, _normal_slot)
CHECK_NAMES = ("finite_forces", "normalization", "passivity", "coulomb_bound",
               "kernel_vs_reference", "velocity_independence", "split_invariance",
               "contact_loss_reset", "replay", "normal_slot")


def check_model(name: str, profile: str | Profile | None = None,
                adhesion: Adhesion | None = None, **params: Any) -> Conformance:
    """Run the conformance suite on the registered model ``name`` with parameters ``params``.

    Parameters
    ----------
    name
        A registered model.
    profile
        One profile to check: a shape the model declares (``"sphere"``, ``"cone"``, ``"flat"``,
        ``"power"`` (exponent :data:`POWER_EXPONENT`), ``"table"`` (:func:`table_law`)) or a
        :class:`Profile`. Default: every profile in ``capabilities.profiles``.
    adhesion
        An adhesive normal law (:class:`~sawdrift.contact.adhesion.Adhesion`): the model's
        adhesive variant is checked, on the sphere (the suite then holds N* to the pull-off, and
        T* to |N* + 2 F*_pull|). The model must have an adhesive tangential law.
    **params
        The model's parameters.

    Raises
    ------
    ModelNotFoundError
        If no model has that name.
    SceneError
        If a parameter or the profile is unknown or out of range (one line naming it).
    """
    from pydantic import ValidationError

    cls = get_model(name)
    try:
        model_params = cls.Params.model_validate(params)
    except ValidationError as exc:
        known = ", ".join(cls.Params.model_fields) or "no parameters"
        raise SceneError(f"model_params.{format_validation_error(exc)} (model {name!r} takes: "
                         f"{known})") from None
    declared = cls.capabilities.profiles
    if adhesion is not None:
        if not supports_adhesion(cls):
            raise SceneError(f"model {name!r} has no adhesive tangential law")
        cls, declared = adhesive_model(cls), ("sphere",)
    shape = profile.shape if isinstance(profile, Profile) else profile
    if shape is not None and shape not in declared:
        raise SceneError(f"profile = {shape!r} is not declared by model {name!r}; "
                         f"allowed: {', '.join(declared)}")
    if cls.capabilities.rigid:
        return Conformance(name, tuple(
            Check(n, "skipped", math.nan, math.nan, "rigid model: no displacement law", "all")
            for n in CHECK_NAMES))
    checks: list[Check] = []
    laws: list[tuple[str, str]] = []
    with profiles_for(declared if shape is None else (shape,)) as built:
        if isinstance(profile, Profile):
            built = {profile.shape: profile}
        for label, prof in built.items():
            model = (cls(model_params, prof) if adhesion is None
                     else cls(model_params, prof, adhesion))  # type: ignore[call-arg]
            laws.append((label, describe_profile(prof, not isinstance(profile, Profile))))
            checks.extend(replace(_guarded(check, model, check_name), profile=label)
                          for check, check_name in zip(CHECKS, CHECK_NAMES, strict=True))
    return Conformance(name, tuple(checks), tuple(laws))


def _guarded(check: Any, model: ContactModel, name: str) -> Check:
    """``check(model)``, or a failed check saying what the model raised: a kernel that raises,
    one numba cannot compile, a ``reference_step`` of the wrong form ended check-model in an
    "internal failure" instead of failing the suite."""
    try:
        return check(model)
    except Exception as exc:  # noqa: BLE001 - the model's code, whatever it raises, fails the check
        return Check(name, "fail", math.nan, math.nan, f"the model raised {first_line(exc)}")
