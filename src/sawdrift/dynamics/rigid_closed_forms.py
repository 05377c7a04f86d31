"""The rigid point's motion within a step in closed form, and the parameter slots it reads.

In contact the substrate motion is known, so the rigid scheme of :mod:`.rigid` needs no
integration there: with the normalization of docs/physics.md and L the tangential load,

    N*(t) = 1 - m* u_y''(t)                        (1 with the vertical inertia switched off)
    int N* dt = dt - m* (u_y'(t) - u_y'(t0))       (so the slip velocity is exact)
    T_req = (L - m* u_x'') / mu                    (the friction that keeps the point stuck)
    a*(t) = y0 + v0 dt + dt^2 / (2 m*) - u_y(t)    (the gap of a flight)

This module holds those expressions (:func:`_normal`, :func:`_t_req`, :func:`_slip_state`,
:func:`_gap`), the stick condition, and the search for where contact is lost inside a step
(N* below -``_GRAZE`` at the step's end or in a dip within it). They read the drive through
``drive_kinematics``, bound per drive in the generated module (:mod:`.rigid_bind`), and change no
state: the events that act on the state (flight, impact, landing, lift-off, stick and slip) and
the step are :mod:`.rigid`'s.
"""

from __future__ import annotations

import math

from .adams_bashforth import N_PRM, P_LOAD, P_M, P_MU, P_ROLL

#: Extra slots of the parameter vector used by the rigid scheme, after the compliant loop's
#: :data:`~.adams_bashforth.PRM_NAMES`; the drive's own parameters follow from N_PRM_RIGID on.
RIGID_PRM_NAMES = (
    "restitution",  # Newton restitution e of an impact
    "vertical_inertia",  # 1: N* = 1 - m* u_y'', 0: N* = 1
    "x_q",  # the centre's x* at the step's start, where the drive is evaluated (set by the loop)
    "u_y",  # the drive's vertical amplitude (the impact-speed floor)
)
P_RESTITUTION, P_VINERTIA, P_XQ, P_UY = range(N_PRM, N_PRM + len(RIGID_PRM_NAMES))
N_PRM_RIGID = N_PRM + len(RIGID_PRM_NAMES)

#: bisection steps that locate an event (a landing, a break-away, the end of a slip) in a step
_BISECT = 60
#: A grazing dip of N* below zero by less than this is contact with N* = 0: the flight it would
#: start rises less than ~1e-20 / m* (|N*|^2 / (16 pi^2 m*)), below what the gap function
#: resolves, and a lift-off and landing it cannot resolve would repeat without end (1e-12 did, in
#: tests/test_material_point.py's bouncing ball at Gamma = 2.78). It is far above the rounding
#: of N* = 1 - m* u_y'' (1e-16 Gz) and puts the hopping onset of the point at Gz = 1 + 1e-9 (the
#: rule: contact is lost iff Gz > 1).
_GRAZE = 1e-9
#: golden-section iterations that locate the least N* within a step (shrinks it by 0.618^60)
_GOLDEN = 60


def _tangential_mass(prm):
    """m* of the tangential motion: m*/c for a rolling sphere (c = 1 + 1/kappa), else m*.

    With rotation the closed forms within a step integrate the contact point s = x + R phi, which
    moves like a particle of mass m kappa / (1 + kappa) (docs/physics.md, Rotation).
    """
    c = prm[P_ROLL]
    return prm[P_M] / c if c > 0.0 else prm[P_M]


def _tangential_load(prm):
    """The load on the tangential motion: L/c on a rolling sphere's contact point, else L.

    The load acts on the centre and exerts no torque: m x'' = -mu T + L and
    I phi'' = -R mu T give for s = x + R phi the equation (m/c) s'' = -mu T + L/c.
    """
    c = prm[P_ROLL]
    return prm[P_LOAD] / c if c > 0.0 else prm[P_LOAD]


def _normal(t, prm):
    """N*(t) in permanent contact (1 - m* u_y'' with vertical inertia, else 1)."""
    if prm[P_VINERTIA] <= 0.0:
        return 1.0
    k = drive_kinematics(t, prm[P_XQ], prm[N_PRM_RIGID:])  # noqa: F821
    return 1.0 - prm[P_M] * k[5]


def _least_normal_inside(t0, t1, n0, n1, prm):
    """The time in (t0, t1) where N* dips below ``-_GRAZE`` first, or -1.0 if it does not.

    N*(t) = 1 - m* u_y''(t) may dip below zero inside a step and be positive again at both ends
    (just above the hopping onset the dip lasts ~sqrt(Gz - 1) / pi periods, shorter than a step):
    a lift-off is then missed unless the step looks inside. Within one step N* differs from its
    chord by at most max|N*''| h^2 / 8 <= 2 m* (2 pi)^4 A h^2 / 8 (factor 2: the ramp and a
    second wave), so steps whose ends both stand higher are skipped at the cost of one
    comparison; otherwise a parabola through the ends and the midpoint says whether a minimum
    lies inside, and a golden-section search locates it before a bisection finds the crossing.
    """
    h = t1 - t0
    reach = 0.25 * prm[P_M] * (2.0 * math.pi) ** 4 * prm[P_UY] * h * h + 1e-9
    if min(n0, n1) > reach:
        return -1.0
    nm = _normal(0.5 * (t0 + t1), prm)
    c = 2.0 * (n0 - 2.0 * nm + n1)
    b = 4.0 * nm - 3.0 * n0 - n1
    if c <= 0.0 or not (0.0 < -b < 2.0 * c):
        return -1.0  # no minimum inside the step (concave, or the vertex beyond an end)
    lo, hi = t0, t1
    g = 0.5 * (math.sqrt(5.0) - 1.0)
    a_ = hi - g * (hi - lo)
    b_ = lo + g * (hi - lo)
    na, nb = _normal(a_, prm), _normal(b_, prm)
    for _i in range(_GOLDEN):
        if na < nb:
            hi, b_, nb = b_, a_, na
            a_ = hi - g * (hi - lo)
            na = _normal(a_, prm)
        else:
            lo, a_, na = a_, b_, nb
            b_ = lo + g * (hi - lo)
            nb = _normal(b_, prm)
    tmin = a_ if na < nb else b_
    if min(na, nb) >= -_GRAZE:
        return -1.0
    return _contact_lost_at(t0, tmin, prm)


def _contact_lost_at(lo, hi, prm):
    """Bisection for where N* falls below -_GRAZE in [lo, hi] (it holds at lo, not at hi)."""
    for _i in range(_BISECT):
        mid = 0.5 * (lo + hi)
        if _normal(mid, prm) >= -_GRAZE:
            lo = mid
        else:
            hi = mid
    return lo


def _stick_margin(t, prm):
    """N* - |T_req| with T_req = (L - m* u_x'')/mu: stick holds while this is >= 0."""
    return _normal(t, prm) - abs(_t_req(t, prm))


def _sticks(t, prm):
    """Stick holds: |T_req| <= N*, or nothing pulls the point along (T_req = 0, e.g. r = 0).

    The second case matters where N* <= 0 (the point is about to lift): with no horizontal
    forcing there is nothing to slip, and no slip may be logged or integrated.
    """
    return _stick_margin(t, prm) >= 0.0 or _t_req(t, prm) == 0.0


def _t_req(t, prm):
    """The friction T* that keeps the point stuck: mu T* = L - m* u_x'' (the load included)."""
    k = drive_kinematics(t, prm[P_XQ], prm[N_PRM_RIGID:])  # noqa: F821
    load = _tangential_load(prm)
    if load == 0.0:
        return -_tangential_mass(prm) * k[2] / prm[P_MU]
    return (load - _tangential_mass(prm) * k[2]) / prm[P_MU]


def _slip_state(t0, x0, v0, t, sigma, prm):
    """Exact (x*, x*') at t after slipping with sgn(s) = sigma from (t0, x0, v0).

    In contact int N* dt = dt - m* (u_y'(t) - u_y'(t0)), so the slip motion has a closed form;
    the load adds the constant acceleration L/m* (L/c over m*/c on a rolling contact point).
    """
    m = prm[P_M]
    c = prm[P_MU] * sigma / _tangential_mass(prm)
    dt = t - t0
    if prm[P_VINERTIA] > 0.0:
        k0 = drive_kinematics(t0, prm[P_XQ], prm[N_PRM_RIGID:])  # noqa: F821
        k1 = drive_kinematics(t, prm[P_XQ], prm[N_PRM_RIGID:])  # noqa: F821
        int_n = dt - m * (k1[4] - k0[4])
        int2_n = 0.5 * dt * dt - m * (k1[3] - k0[3] - k0[4] * dt)
    else:
        int_n = dt
        int2_n = 0.5 * dt * dt
    g = prm[P_LOAD] / m
    if g == 0.0:
        return x0 + v0 * dt - c * int2_n, v0 - c * int_n
    return x0 + v0 * dt - c * int2_n + 0.5 * g * dt * dt, v0 - c * int_n + g * dt


def _slip_velocity(t0, x0, v0, t, sigma, prm):
    """The slip velocity s = x*' - u_x' at t after slipping with sgn(s) = sigma from (t0, x0, v0)."""
    k = drive_kinematics(t, prm[P_XQ], prm[N_PRM_RIGID:])  # noqa: F821
    return _slip_state(t0, x0, v0, t, sigma, prm)[1] - k[1]


def _gap(t0, y0, v0, t, prm):
    """a* = y* - u_y at t in flight from (t0, y0, v0): negative while separated."""
    dt = t - t0
    k = drive_kinematics(t, prm[P_XQ], prm[N_PRM_RIGID:])  # noqa: F821
    return y0 + v0 * dt + 0.5 * dt * dt / prm[P_M] - k[3]


def _contact_end(prm, tau, t_end, n_tau):
    """(end, lift): where contact holds until in [tau, t_end] (N* >= -_GRAZE), and whether it is
    lost there (N* below -_GRAZE at the step's end, or dipping inside it)."""
    n_end = _normal(t_end, prm)
    if n_end < -_GRAZE:
        return _contact_lost_at(tau, t_end, prm), True
    if prm[P_VINERTIA] > 0.0:
        dip = _least_normal_inside(tau, t_end, n_tau, n_end, prm)
        if dip >= 0.0:
            return dip, True
    return t_end, False
