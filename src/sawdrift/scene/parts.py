"""The parts of a scene: material, particle, drives, numerics, effects (frozen pydantic models).

All quantities are the normalized ones of docs/physics.md (paper eq. 4-5): t* = f t, one
wave period is one unit of t*; m* = a0 m f^2 / (M g); A* = A_y / a0. The whole scene that holds
them is :class:`sawdrift.scene.schema.Scene`; this module also holds the helpers every layer of
the scene uses (dotted paths); its one-line validation messages are :mod:`.messages`.
"""

from __future__ import annotations

import math
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    WrapValidator,
    model_serializer,
    model_validator,
)

from .bounds import AMPLITUDE_MAX, M_STAR_RANGE, Number, bounded, count, not_bool
from .profiles import Profile

#: The largest tangential load |L| over what friction can hold at mu = 1, M g + 2 F_pull (M g
#: without adhesion): beyond it friction holds nothing and the particle is simply pushed. The
#: range of ``particle.load`` is this times 1 + 2 ``material.adhesion``
#: (:func:`sawdrift.scene.adhesion.load_bound`), a device's ``load`` the same in newtons.
MAX_LOAD_RATIO = 100.0

#: how the range of ``particle.load`` reads in its option's help and its error
LOAD_RANGE = (f"[-{MAX_LOAD_RATIO:g}, {MAX_LOAD_RATIO:g}], with adhesion {MAX_LOAD_RATIO:g} "
              "(1 + 2 material.adhesion)")


def _finite_load(value: Any, handler: Any) -> float:
    """particle.load is a finite number; its range depends on material.adhesion (checked by the
    scene)."""
    value = not_bool(value, handler)
    if not math.isfinite(value):
        raise ValueError(f"is not finite: give a load in {LOAD_RANGE} (in M g)")
    return value


Positive = Annotated[float, bounded(0.0, None, lo_open=True)]
NonNegative = Annotated[float, bounded(0.0, None)]

FROZEN = ConfigDict(frozen=True, extra="forbid")

#: the most steps per period a scene may ask for (numerics.steps_per_period)
FINEST_STEPS = 10_000_000


class Material(BaseModel):
    """Friction coefficient, Poisson's ratio and, for two materials, the contact's theta."""

    model_config = FROZEN

    mu: Annotated[float, bounded(1e-6, 10.0)] = Field(
        0.1, description="Coulomb friction coefficient mu, in [1e-06, 10]"
    )
    nu: Annotated[float, bounded(-1.0, 0.5, lo_open=True, hi_open=True)] = Field(
        0.3, description="Poisson's ratio nu, in (-1, 0.5) (the substrate's, for r(nu))"
    )
    theta: Annotated[float, bounded(0.01, 10.0)] | None = Field(
        None,
        description=(
            "theta = E*/(4 G*) of the contact, in [0.01, 10]; default (2 - nu)/(2 (1 - nu)) for "
            "identical materials"
        ),
    )
    restitution: Annotated[float, bounded(0.0, 1.0)] | None = Field(
        None,
        description=(
            "coefficient of restitution e of a free normal impact, in [0, 1] (at least 0.05 "
            "for a compliant model, whose damping the explicit scheme must resolve): a normal "
            "damping that gives the rebound speed ratio e independent of impact speed "
            "(compliant models); default none, the undamped contact"
        ),
    )
    adhesion: Annotated[float, bounded(0.0, 1e12)] = Field(
        0.0,
        description=(
            "adhesion as the pull-off force of the law in effects.adhesion over the static "
            "normal load M g (JKR 1.5 pi R w, DMT 2 pi R w, w the work of adhesion), >= 0; "
            "needs effects.adhesion = 'dmt' or 'jkr'; on a device scene derived from "
            "device.adhesion"
        ),
    )


class Particle(BaseModel):
    """The particle: normalized mass, profile, and optional external preload."""

    model_config = FROZEN

    m_star: Annotated[float, bounded(*M_STAR_RANGE)] = Field(
        0.1, description="m* = a0 m f^2 / (M g) (paper eq. 4), in [1e-12, 1e+10]")
    profile: Profile = Field(default_factory=Profile)
    gyration: Annotated[float, bounded(0.0, 1.0, lo_open=True)] = Field(
        0.4,
        description=(
            "kappa = I / (m R^2), in (0, 1]: 2/5 solid sphere, 2/3 thin shell; only with "
            "effects.rotation = true (another value without rotation is an error)"
        ),
    )
    preload: NonNegative = Field(
        0.0,
        description=(
            "F_ext / (m g). It enters the normalized equations only through M = m + F_ext/g in "
            "m*; kept for conversion from dimensional inputs"
        ),
    )
    load: Annotated[float, WrapValidator(_finite_load)] = Field(
        0.0,
        description=(
            "constant external tangential force on the particle, in units of its static normal "
            "load M g, positive along +x (a motor's thrust, gravity along an incline); in "
            f"{LOAD_RANGE}"
        ),
    )


class Wave(BaseModel):
    """Rayleigh wave drive (paper eq. 1 with the ramp R(t*) of docs/physics.md)."""

    model_config = FROZEN

    kind: Literal["wave"] = "wave"
    amplitude: Annotated[float, bounded(0.0, AMPLITUDE_MAX)] = Field(
        0.316, description="A* = A_y / a0, in [0, 1e+09]")
    horizontal_ratio: Annotated[float, bounded(0.0, 100.0)] | None = Field(
        None,
        description="r = horizontal / vertical surface amplitude; default r(nu) (Rayleigh eq.)",
    )
    ramp_periods: Annotated[float, bounded(0.0, 1e6)] = Field(
        5.0, description="length of the smooth ramp R(t*) = sin^2(pi t* / (2 T_ramp)), periods"
    )
    orbit: Literal["prograde", "retrograde"] = Field(
        "prograde",
        description=(
            "prograde: eq. 1 as printed with y* into the substrate (the crest moves with the "
            "wave, the paper's figures); retrograde: a Rayleigh wave on an isotropic half-space "
            "(the mirror x -> -x: every drift changes sign)"
        ),
    )
    backward: Annotated[float, bounded(0.0, 1.0)] = Field(
        0.0,
        description=(
            "amplitude ratio s of a second, counter-propagating wave (travelling to -x), in "
            "[0, 1]; 1: a standing wave"
        ),
    )
    backward_phase: Annotated[float, bounded(-3600.0, 3600.0)] = Field(
        0.0, description="phase psi of the counter-propagating wave, degrees"
    )
    backward_phase_rate: Annotated[float, bounded(-3600.0, 3600.0)] = Field(
        0.0, description="change of backward_phase per wave period, degrees (a moving trap)"
    )
    position: Annotated[float, bounded(-1e6, 1e6)] = Field(
        0.0,
        description=(
            "where the particle sits, xi = X / wavelength: with two waves the local orbit "
            "depends on it"
        ),
    )
    wavelength: Annotated[float, bounded(1.0, 1e15)] | None = Field(
        None,
        description=(
            "L* = wavelength / a0: given, the drive is evaluated at the particle's own "
            "position (phase 2 pi (t* -+ x*/L*), a direct run); default: at drive.position; "
            "at least 1 (a wave shorter than the static compression a0 is no surface wave)"
        ),
    )
    phase: Annotated[float, bounded(-360.0, 360.0)] | None = Field(
        None,
        description=(
            "phase of u_x against u_y in degrees, u_x = r A* cos(2 pi t* + phase): 90 is the "
            "prograde orbit, -90 the retrograde one, 0 and 180 a linear vibration; default from "
            "orbit; phase + 180 mirrors x"
        ),
    )

    @model_serializer(mode="wrap")
    def _dump(self, handler: Any) -> Any:
        """A phase given sets the orbit: the default orbit is left out of the dump, or reading
        it back (a sweep's cell, ``with_updates``) would take it for a second, conflicting
        choice (``--phase 0`` was refused by every sweep and ``lammps --compare``)."""
        out = handler(self)
        if self.phase is not None and "orbit" not in self.model_fields_set and isinstance(out,
                                                                                         dict):
            out.pop("orbit", None)
        return out

    @model_validator(mode="after")
    def _phase_and_orbit_agree(self) -> Wave:
        if self.phase is not None and "orbit" in self.model_fields_set:
            named = 90.0 if self.orbit == "prograde" else -90.0
            if math.fmod(self.phase - named, 360.0) != 0.0:
                raise ValueError(f"drive.phase = {self.phase:g} and drive.orbit = {self.orbit!r} "
                                 f"disagree ({self.orbit} is phase {named:g}); give one of them")
        return self


class Biharmonic(BaseModel):
    """A vibrating plate, not a wave: the first two harmonics on each axis (Blekhman's asymmetric
    excitation of vibrational transport)::

        u_x = R(t*) (X1 cos(2 pi t*) + X2 cos(4 pi t* + phi_x))
        u_y = R(t*) (Y1 cos(2 pi t*) + Y2 cos(4 pi t* + phi_y))

    in units of a0, t* in periods of the fundamental, y* into the substrate, R(t*) the start-up
    ramp. A horizontal harmonic alone transports nothing: t* -> t* + 1/2 with the mirror x -> -x
    maps its motion onto itself. An inclined fundamental (X1 and Y1 both non-zero) transports,
    gravity making the vertical axis one-sided (the vibratory conveyor); a second harmonic breaks
    the symmetry in time and transports on a horizontal vibration alone (I. I. Blekhman,
    Vibrational Mechanics, 2000, ch. 5).
    """

    model_config = FROZEN

    kind: Literal["biharmonic"] = "biharmonic"
    amplitude: Annotated[float, bounded(0.0, 1e6)] = Field(
        0.316, description="Y1: vertical fundamental amplitude / a0, in [0, 1e+06]")
    horizontal: Annotated[float, bounded(-1e6, 1e6)] = Field(
        0.0, description="X1: horizontal fundamental amplitude / a0 (in phase with Y1)")
    second: Annotated[float, bounded(-1e6, 1e6)] = Field(
        0.0, description="Y2: vertical second-harmonic amplitude / a0")
    second_horizontal: Annotated[float, bounded(-1e6, 1e6)] = Field(
        0.0, description="X2: horizontal second-harmonic amplitude / a0")
    second_phase: Annotated[float, bounded(-360.0, 360.0)] = Field(
        0.0, description="phi_y: phase of the vertical second harmonic, degrees")
    second_horizontal_phase: Annotated[float, bounded(-360.0, 360.0)] = Field(
        0.0, description="phi_x: phase of the horizontal second harmonic, degrees")
    ramp_periods: Annotated[float, bounded(0.0, 1e6)] = Field(
        5.0, description="length of the smooth ramp R(t*) = sin^2(pi t* / (2 T_ramp)), periods"
    )


#: the largest |a*|, |b*| of a prescribed history (units of the static compression a0)
PRESCRIBED_MAX = 1e6


class Prescribed(BaseModel):
    """A prescribed contact history a*(t*), b*(t*): the contact law alone, no dynamics.

    Either sampled arrays (``waveform = "samples"`` with ``a`` and ``b``) or a built-in waveform:

    * ``mindlin_loop``: load to a* = ``a_max`` at b* = 0, then cycle b* between
      +-``b_amplitude`` for ``cycles`` cycles at constant a*;
    * ``proportional``: b* = ``slope`` a* from zero up to ``a_max``;
    * ``random``: a random piecewise-linear walk in (a*, b*) (seeded), a* crossing zero.
    """

    model_config = FROZEN

    kind: Literal["prescribed"] = "prescribed"
    waveform: Literal["samples", "mindlin_loop", "proportional", "random"] = "mindlin_loop"
    a: list[Number] | None = None
    b: list[Number] | None = None
    # a* and b* in units of the static compression: 1e308 overflowed the force and was blamed
    # on the contact model
    a_max: Annotated[float, bounded(0.0, PRESCRIBED_MAX, lo_open=True)] = 1.0
    b_amplitude: Annotated[float, bounded(0.0, PRESCRIBED_MAX)] = 0.5
    slope: Annotated[float, bounded(-10.0, 10.0)] = 0.5
    cycles: count(1, 100000) = 2
    samples_per_segment: count(1, 1_000_000) = 200
    seed: count(0, 2**32 - 1) = 0

    @model_validator(mode="after")
    def _samples_given(self) -> Prescribed:
        if self.waveform == "samples":
            if self.a is None or self.b is None:
                raise ValueError("waveform 'samples' needs both 'a' and 'b' arrays")
            if len(self.a) != len(self.b) or len(self.a) < 1:
                raise ValueError("'a' and 'b' must be non-empty and of equal length")
            if not all(math.isfinite(v) and abs(v) <= PRESCRIBED_MAX for v in [*self.a, *self.b]):
                raise ValueError(f"'a' and 'b' must be finite, within +-{PRESCRIBED_MAX:g} "
                                 "(a* and b* in units of the static compression)")
        return self


def polyline(vertices: list[tuple[float, float]], per_side: int) -> tuple[np.ndarray, np.ndarray]:
    """Samples a*(k), b*(k) along straight sides through ``vertices``, ``per_side`` per side."""
    av, bv = [vertices[0][0]], [vertices[0][1]]
    s = np.arange(1, per_side + 1) / per_side
    for (a0, b0), (a1, b1) in zip(vertices[:-1], vertices[1:], strict=True):
        av.extend(a0 + (a1 - a0) * s)
        bv.extend(b0 + (b1 - b0) * s)
    return np.asarray(av), np.asarray(bv)


class Impact(BaseModel):
    """A free normal impact: the particle touches the substrate (a* = 0) moving into it.

    The substrate is at rest (no wave); the run ends when contact is lost again. The result
    carries the rebound speed ratio |a*'_out| / |a*'_in| (1 for an elastic, undamped contact).
    """

    model_config = FROZEN

    kind: Literal["impact"] = "impact"
    velocity: Annotated[float, bounded(0.0, 1e3, lo_open=True)] = Field(
        1.0, description="approach speed a*' at first touch, > 0"
    )
    tangential_velocity: Annotated[float, bounded(-1e3, 1e3)] = Field(
        0.0, description="tangential speed x*' at first touch"
    )


class Numerics(BaseModel):
    """Integrator and measurement settings."""

    model_config = FROZEN

    order: count(1, 4) = Field(
        4,
        description=(
            "Adams-Bashforth order 1-4 (default 4: on the undamped normal oscillation its "
            "amplitude error per step is O((h omega)^6), AB3's is (3/8)(h omega)^4, which over "
            "thousands of periods changes the drift). The first order-1 steps use the lower "
            "orders (start-up from rest at the static compression, where the derivative "
            "history is exact)"
        ),
    )
    steps_per_period: count(8, FINEST_STEPS) | None = Field(
        None, description="steps per wave period; default resolves sqrt(1.5/m*) and the wave"
    )
    periods: Annotated[float, bounded(0.0, 1e7, lo_open=True)] = Field(
        60.0, description="simulated periods (with settle: the minimum)"
    )
    measure_periods: count(1, 10_000_000) | None = Field(
        None, description="whole periods at the end over which the drift is measured"
    )
    drift_tolerance: Annotated[float, bounded(0.0, 1.0)] = Field(
        1e-3, description="|drift_ratio| below this is 'stick' (no steady drift)"
    )
    settle: bool | None = Field(
        None, description="run on, in chunks of measure_periods, until the drift has settled; "
        "default: on where the drift needs longer than periods/3 to relax (of order m*/mu "
        "periods: a heavy particle), else a fixed run of periods"
    )
    settle_tolerance: Annotated[float, bounded(0.0, 1.0, lo_open=True)] = Field(
        1e-3, description="relative accuracy a settled drift ratio is asked for: successive "
        "full-inertia windows agree within half of it, a fixed window's last two thirds within "
        "it (relative to the drift ratio, taken as at least 0.02); the zero of a force-velocity "
        "curve is found to a hundredth of it"
    )
    max_periods: Annotated[float, bounded(1.0, 1e7)] | None = Field(
        None, description="settle: stop after this many periods even if not settled (the "
        "full-inertia stage stops after 60 windows in any case; a motion still approaching then "
        "says so); default max(5000, 50 m*_x/mu + 20 windows), m*_x the horizontal inertia of "
        "the settle method"
    )
    mean_periods: count(100, 10_000_000) = Field(
        500, description="irregular motions (chaotic, quasi-periodic, irregular heavy "
        "bouncing): periods of the long-time mean drift and its batch-means standard error "
        "(a chaotic light bouncer: about +-0.1 in drift ratio at 500, +-0.07 at 2000; an "
        "irregular heavy bouncer +-0.008 at 500, +-1e-4 to 5e-4 where its record is "
        "quasi-periodic); a mean known to settle_tolerance stops earlier; "
        "a mean of bounces runs over at least 16 of its longest flights (at most 100 times this)"
    )
    confirm_solved: bool = Field(
        False, description="settle, m* >= 5: confirm a drift solved directly (force-velocity "
        "curve at full inertia) with full-inertia windows of three free vertical periods each "
        "(cost grows as sqrt(m*)) instead of one evidence window"
    )

    @model_validator(mode="after")
    def _window_and_cap_within_run(self) -> Numerics:
        # the window is the run's last periods: a longer one lengthened a fixed run unasked
        if self.measure_periods is not None and self.measure_periods > self.periods:
            raise ValueError(
                f"measure_periods = {self.measure_periods} is longer than periods = "
                f"{self.periods:g}: the drift is measured over the run's last periods; allowed: "
                f"1 to {int(self.periods)} (or a longer run)")
        if (self.max_periods is not None and self.max_periods < self.periods
                and self.settle is not False):  # a fixed run reads no cap
            # the run takes its periods first: a smaller cap was passed over without a word
            raise ValueError(
                f"max_periods = {self.max_periods:g} is below periods = {self.periods:g}: a run "
                f"takes its periods before any cap; allowed: {self.periods:g} to 1e+07 (or "
                f"fewer periods)")
        return self


class Effects(BaseModel):
    """Which physics is on (LAMMPS-style slots; an off slot is never computed)."""

    model_config = FROZEN

    friction: bool = Field(
        True, description="tangential friction; off: x* is not integrated, no tangential law"
    )
    vertical_inertia: bool = Field(
        True, description="rigid models only: off gives N* = 1 (no vertical inertia)"
    )
    normal_damping: NonNegative = Field(
        0.0, description="viscous normal damping c: N* += c a*' while in contact"
    )
    horizontal_wave: bool = Field(True, description="the horizontal wave component u_x")
    rolling_resistance: NonNegative = Field(
        0.0,
        description=(
            "rolling friction coefficient mu_r of an elastic-plastic rolling spring (needs "
            "rotation and a compliant model; 0: off); physically mu_r ~ (contact radius)/R = "
            "sqrt(a0/R) times a factor of order 1"
        ),
    )
    rotation: bool = Field(
        False,
        description=(
            "the sphere turns: I phi'' = -R T with I = kappa m R^2 (particle.gyration); the "
            "contact point then moves like a mass m kappa / (1 + kappa). With a rigid model the "
            "particle is then a rigid sphere (a rigid point cannot turn)"
        ),
    )
    vertical_wave: bool = Field(True, description="the vertical wave component u_y")
    air_drag: NonNegative = Field(
        0.0,
        description=(
            "linear air drag c on the centre, relative to still air (compliant models; 0: off): "
            "m* x*'' += -c x*', m* y*'' += -c y*'; c = c_d a0 f / (M g), c_d = 6 pi eta R for "
            "Stokes drag"
        ),
    )
    adhesion: Literal["none", "dmt", "jkr"] = Field(
        "none",
        description=(
            "adhesive normal law of a compliant sphere (material.adhesion > 0): 'dmt' Hertz minus "
            "the constant pull-off while in contact (stiff, small particles), 'jkr' the "
            "Johnson-Kendall-Roberts contact with its hysteresis (soft, large ones); 'none' "
            "computes nothing adhesive"
        ),
    )
    adhesion_detach: Literal["instability", "pulloff"] = Field(
        "instability",
        description=(
            "JKR only: where a receding contact breaks: 'instability' at the overlap where the "
            "contact radius can shrink no further (JKR's fixed-grip limit), 'pulloff' at the "
            "overlap of the largest tensile force (the LAMMPS convention)"
        ),
    )
