"""Time stepping for a rigid material point: unilateral contact with Coulomb friction.

Paper section 4 (after Verma and DasGupta, Phys. Rev. E 88, 052915, 2013), normalized as in
docs/physics.md: a* = 0 while in contact, and then

    N*(t*) = 1 - m* u_y''(t*)          (N* = 1 with the vertical inertia switched off)
    stick:  x*'' = u_x''   while |T_req| = |m* u_x'' - L| / mu <= N*
    slip:   m* x*'' = -mu N* sgn(s) + L,   s = x*' - u_x'
    flight: m* y*'' = 1, m* x*'' = L    (contact lost when N* would turn negative)

with L the constant tangential load (``particle.load``, 0 by default; docs/physics.md, "Loads,
inclines and restitution"); with L = 0 every expression is the one without the load.

Re-contact is an impact with a Newton restitution coefficient e (default 0) and a Coulomb-limited
tangential impulse. Within a fixed step, events (break-away, slip reversal or stick, lift-off,
impact) are located by bisection on closed-form expressions: in contact the substrate motion is
known, so N*(t) and its integral are exact and the slip velocity is integrated exactly. The only
approximation is that a stick or contact violation that begins and ends inside one step is missed.

The closed forms within a step (N*, the stick condition, the slip motion, the flight's gap, where
contact is lost) and the scheme's parameter slots are in :mod:`.rigid_closed_forms`; this module
holds the events that act on the state (flight, impact, landing, lift-off, stick and slip in
contact), the step's bookkeeping and the loop.
"""

from __future__ import annotations

import math

from .adams_bashforth import (
    P_FRICTION,
    P_H,
    P_KRAMP,
    P_LOAD,
    P_M,
    P_MU,
    P_ROLL,
    record,
)
from .evidence import (
    BAD_EVENTS,
    BAD_NONFINITE,
    EV_LANDING,
    EV_LIFT_OFF,
    EV_SLIP_END,
    EV_SLIP_START,
    EV_STICK_START,
    S_BAD,
    S_BADSTEP,
    S_LIFTS,
    event,
    log_full,
    observe_step,
)
from .rigid_closed_forms import (
    _BISECT,
    _GRAZE,
    N_PRM_RIGID,
    P_RESTITUTION,
    P_UY,
    P_XQ,
    _contact_end,
    _gap,
    _normal,
    _slip_state,
    _slip_velocity,
    _sticks,
    _t_req,
    _tangential_mass,
)
from .rigid_closed_forms import RIGID_PRM_NAMES as RIGID_PRM_NAMES  # re-exported: the stepper's
from .rolling import centre_at, integrates_psi, to_centre, to_contact_point

#: events (impacts, lift-offs, stick and slip changes) one step may hold before it is an error
_MAX_EVENTS = 4096
#: free rows of the event log a step may need (up to three events per resolved event), below
#: which the loop returns and the stepper grows the log (see Stepper.advance)
EV_MARGIN_RIGID = 3 * _MAX_EVENTS + 8
#: shortest rebound flight, in steps, before an inelastic collapse counts as landed
_ZENO = 1e-6


def _log(st, kind, tc, y, frame):
    """Log an event at ``tc`` at the centre, from the contact point held in ``y``.

    ``frame`` = (od, od', od'', c, t): the step's start t and the offset od = c x* - s* there
    (:func:`~.rolling.centre_at`); without rotation (c = 0) ``y`` holds the point itself.
    ``y`` is restored exactly.
    """
    if frame[3] <= 0.0:
        event(st, kind, tc, y, 0.0)
        return
    xs = y[0]
    vs = y[1]
    y[0], y[1] = centre_at(xs, vs, frame, tc)
    event(st, kind, tc, y, 0.0)
    y[0] = xs
    y[1] = vs


def _free_tangential(y, prm, dt):
    """Advance the tangential motion by ``dt`` without friction: m* x*'' = L (flight, friction off)."""
    g_load = prm[P_LOAD] / prm[P_M]
    y[0] += y[1] * dt
    if g_load != 0.0:
        y[0] += 0.5 * g_load * dt * dt
        y[1] += g_load * dt


def _flight(y, ctr, st, prm, tau, t_end, frame):
    """Fly from ``tau`` to the landing (then the impact) or to ``t_end``; (time reached, flight time).

    m* y*'' = 1 and m* x*'' = L in flight (module docstring); the landing is located by bisection
    on the gap (:func:`_gap`).
    """
    m = prm[P_M]
    tc = t_end
    if _gap(tau, y[2], y[3], t_end, prm) >= 0.0:
        lo, hi = tau, t_end
        for _i in range(_BISECT):
            mid = 0.5 * (lo + hi)
            if _gap(tau, y[2], y[3], mid, prm) < 0.0:
                lo = mid
            else:
                hi = mid
        tc = hi
        kk = drive_kinematics(tc, prm[P_XQ], prm[N_PRM_RIGID:])  # noqa: F821
        if y[3] + (tc - tau) / m - kk[4] <= 0.0 and _normal(tc, prm) < 0.0:
            # a 'landing' that rounding finds right after a lift-off: the point does not
            # approach the surface, which accelerates away (N* < 0): no landing
            tc = t_end
    dt = tc - tau if tc < t_end else t_end - tau
    _free_tangential(y, prm, dt)
    if tc >= t_end:
        y[2] += y[3] * dt + 0.5 * dt * dt / m
        y[3] += dt / m
        return t_end, dt
    _impact(y, ctr, st, prm, y[3] + dt / m, tc, frame)
    return tc, dt


def _impact(y, ctr, st, prm, vy, tc, frame):
    """The impact at ``tc`` with vertical velocity ``vy``: Newton restitution e and a
    Coulomb-limited tangential impulse, then a rebound or the landing (:func:`_land`).

    Restitution applies to every impact, also where N* <= 0 would lift at once. An inelastic
    collapse (rebounds shrinking geometrically) ends in landing once the next flight 2 e vn m*/N*
    is shorter than _ZENO steps (the remaining flights sum to less than _ZENO h / (1 - e)), or once
    e vn is below the speed that the gap function resolves: its rounding error eps
    (:func:`_gap_rounding`, growing with t*) puts a floor sqrt(eps N*/m*) under located impact
    speeds; 10x that floor is kept.
    """
    m = prm[P_M]
    e = prm[P_RESTITUTION]
    kk = drive_kinematics(tc, prm[P_XQ], prm[N_PRM_RIGID:])  # noqa: F821
    vn = vy - kk[4]
    if vn < 0.0:
        vn = 0.0
    y[2] = kk[3]
    if prm[P_FRICTION] > 0.0:
        # a tangential impulse J moves the contact point by J / (tangential mass)
        s = y[1] - kk[1]
        jv = min(abs(s), prm[P_MU] * (1.0 + e) * vn * m / _tangential_mass(prm))
        y[1] -= math.copysign(jv, s) if s != 0.0 else 0.0
    _log(st, EV_LANDING, tc, y, frame)
    n_imp = _normal(tc, prm)
    ev_n = e * vn
    if ev_n > 0.0 and (
        n_imp <= 0.0
        or (2.0 * ev_n * m > _ZENO * prm[P_H] * n_imp
            and ev_n * ev_n * m > 100.0 * _gap_rounding(tc, prm[P_UY]) * n_imp)
    ):
        y[3] = kk[4] - e * vn
        _log(st, EV_LIFT_OFF, tc, y, frame)
        st[S_LIFTS] += 1.0
    else:
        _land(y, ctr, st, prm, tc, kk, frame)


def _slip_rounding(t, v):
    """The rounding error of a slip velocity at ``t`` (x*' about ``v``): a slip velocity within it
    of zero has not reversed. Just after a stick breaks the slip velocity grows as the square of
    the time since (slowly where the drive's force nearly balances friction, near a trap of a
    two-wave field): below its rounding its sign is noise, and a slip judged reversed there at
    once made no progress, until a step held 4096 events."""
    return 1e-14 * (1.0 + abs(v)) + 2.8e-15 * abs(t) * (1.0 + abs(v))


def _gap_rounding(tc, uy):
    """The rounding error of the gap function at ``tc``: 1e-14 (1 + A*), and the drive's phase
    2 pi t*, known to about two ulps of t*, times the amplitude (2 pi 4.4e-16 |t*| A*): at
    t* = 1e4 that is 1.4e-11 A*, a hundred times the first, and an inelastic ball
    (e = 0.8, Gamma = 1.01) that collapsed onto the plate every period kept bouncing on the
    rounding until a step held 4096 events."""
    return 1e-14 * (1.0 + uy) + 2.8e-15 * abs(tc) * uy


def _land(y, ctr, st, prm, tc, kk, frame):
    """Stay on the surface after the impact at ``tc`` (``kk`` its kinematics): stick or slip."""
    ctr[1] = 0
    y[3] = kk[4]
    s = y[1] - kk[1]
    if not prm[P_FRICTION] > 0.0:
        ctr[3] = 0
    elif abs(s) <= 1e-14 and _sticks(tc, prm):
        ctr[3] = 1
        y[1] = kk[1]
        _log(st, EV_STICK_START, tc, y, frame)
    else:
        ctr[3] = 0
        ctr[4] = 1 if (s > 0.0 or (s == 0.0 and _t_req(tc, prm) > 0.0)) else -1
        _log(st, EV_SLIP_START, tc, y, frame)


def _lift(y, ctr, st, prm, tc, frame):
    """Contact is lost at ``tc``: a slip ends there, and the flight begins."""
    if prm[P_FRICTION] > 0.0 and ctr[3] == 0:
        _log(st, EV_SLIP_END, tc, y, frame)
    ctr[1] = 1
    _log(st, EV_LIFT_OFF, tc, y, frame)
    st[S_LIFTS] += 1.0


def _stick(y, ctr, st, prm, tau, seg_end, frame):
    """Stick from ``tau`` towards ``seg_end``; (time reached, whether the stick broke there)."""
    stopped = not _sticks(seg_end, prm)
    hi = seg_end
    if stopped:
        lo, hi = tau, seg_end
        for _i in range(_BISECT):
            mid = 0.5 * (lo + hi)
            if _sticks(mid, prm):
                lo = mid
            else:
                hi = mid
    # the point follows the substrate
    k0 = drive_kinematics(tau, prm[P_XQ], prm[N_PRM_RIGID:])  # noqa: F821
    k1 = drive_kinematics(hi, prm[P_XQ], prm[N_PRM_RIGID:])  # noqa: F821
    y[0] += k1[0] - k0[0]
    y[1] = k1[1]
    if not stopped:
        return seg_end, False
    ctr[3] = 0
    ctr[4] = 1 if _t_req(hi, prm) > 0.0 else -1
    _log(st, EV_SLIP_START, hi, y, frame)
    return hi, True


def _slip(y, ctr, st, prm, tau, seg_end, frame):
    """Slip with sgn(s) = sigma from ``tau`` towards ``seg_end``; (time reached, whether the slip
    stopped there: then it sticks or reverses)."""
    sigma = float(ctr[4])
    tol = 0.0
    hi = seg_end
    for _attempt in range(2):
        if sigma * _slip_velocity(tau, y[0], y[1], seg_end, sigma, prm) > -tol:
            xs, vs = _slip_state(tau, y[0], y[1], seg_end, sigma, prm)
            y[0] = xs
            y[1] = vs
            return seg_end, False
        lo, hi = tau, seg_end
        for _i in range(_BISECT):
            mid = 0.5 * (lo + hi)
            if sigma * _slip_velocity(tau, y[0], y[1], mid, sigma, prm) > -tol:
                lo = mid
            else:
                hi = mid
        if hi - tau > _ZENO * prm[P_H]:
            break
        # a slip that reversed at once: its velocity was at rounding level, judged again with
        # that rounding allowed (:func:`_slip_rounding`)
        tol = _slip_rounding(seg_end, y[1])
    xs, _vs = _slip_state(tau, y[0], y[1], hi, sigma, prm)
    k1 = drive_kinematics(hi, prm[P_XQ], prm[N_PRM_RIGID:])  # noqa: F821
    y[0] = xs
    y[1] = k1[1]
    if _sticks(hi, prm):
        ctr[3] = 1
        _log(st, EV_SLIP_END, hi, y, frame)
        _log(st, EV_STICK_START, hi, y, frame)
    else:
        ctr[4] = 1 if _t_req(hi, prm) > 0.0 else -1
    return hi, True


def _contact(y, ctr, st, prm, tau, t_end, frame):
    """In contact from ``tau``: stick, slip or (friction off) the free tangential motion until the
    next event, contact loss or ``t_end``; (time reached, time slipped)."""
    n_tau = _normal(tau, prm)
    if n_tau < -_GRAZE:
        _lift(y, ctr, st, prm, tau, frame)
        return tau, 0.0
    seg_end, lift = _contact_end(prm, tau, t_end, n_tau)
    slipped = 0.0
    if not prm[P_FRICTION] > 0.0:
        _free_tangential(y, prm, seg_end - tau)
    else:
        if ctr[3] == 1:
            reached, stopped = _stick(y, ctr, st, prm, tau, seg_end, frame)
        else:
            reached, stopped = _slip(y, ctr, st, prm, tau, seg_end, frame)
            slipped = reached - tau
        if stopped:
            return reached, slipped
    kk = drive_kinematics(seg_end, prm[P_XQ], prm[N_PRM_RIGID:])  # noqa: F821
    y[2] = kk[3]
    y[3] = kk[4]
    if lift:
        _lift(y, ctr, st, prm, seg_end, frame)
    return seg_end, slipped


def _end_step(y, ctr, st, prm, t_end, times, rec, rec_every):
    """The step's bookkeeping at ``t_end``: evidence, trajectory row, the step counter; True if the
    loop must return (a non-finite state, or an event log to grow). ``times`` = (out of contact,
    slipped) within the step."""
    k = ctr[0]
    h = prm[P_H]
    kk = drive_kinematics(t_end, prm[P_XQ], prm[N_PRM_RIGID:])  # noqa: F821
    a = y[2] - kk[3] if ctr[1] == 1 else 0.0
    # (N*, T*): zero in flight, T* = T_req while stuck, sigma N* in slip
    nf = 0.0 if ctr[1] == 1 else max(_normal(t_end, prm), 0.0)
    if ctr[1] == 1 or not prm[P_FRICTION] > 0.0:
        tf = 0.0
    elif ctr[3] == 1:
        tf = _t_req(t_end, prm)
    else:
        tf = nf * ctr[4]
    if k >= int(prm[P_KRAMP]):
        out_time, slip_time = times
        out = min(1.0, out_time / h) if out_time > 0.0 else (1.0 if ctr[1] == 1 else 0.0)
        observe_step(st, out, slip_time / h, a)
    if rec_every > 0 and (k + 1) % rec_every == 0:
        record(rec, ctr, t_end, y, a, math.nan, nf, tf)
    ctr[0] = k + 1
    if not math.isfinite(y[0] + y[1] + y[2] + y[3]):
        st[S_BAD] = BAD_NONFINITE
        st[S_BADSTEP] = k
        return True
    return log_full(st, EV_MARGIN_RIGID)  # the stepper grows the event log and goes on


def rigid_loop(y, ctr, prm, n_steps, rec, rec_every, st):
    """Advance the material point ``n_steps`` fixed steps; state in ``y`` = (x, x', y, y', psi, psi').

    The state is the compliant loop's: the centre's x*, and with rotation the rolling angle psi =
    R phi / a0 where it is integrated (else psi = (c - 1) x*, the rolling constraint from rest).
    ``ctr`` = (step index, mode 0 contact / 1 flight, record index, stick flag, sigma). The drive
    (``drive_kinematics``, bound per drive in the generated module) is evaluated at the centre's
    x* at the step's start: within a step the closed forms take the surface motion at one place.
    Within a step a rolling sphere's contact point s* = x* + psi is integrated, a particle of mass
    m*/c (:mod:`.rolling`).
    """
    h = prm[P_H]
    roll = prm[P_ROLL]
    g_load = prm[P_LOAD] / prm[P_M]  # the load's acceleration L/m* of the free tangential motion
    for _ in range(n_steps):
        k = ctr[0]
        t = k * h
        t_end = t + h
        prm[P_XQ] = y[0]  # the centre: the drive acts where the sphere is
        turning = integrates_psi(roll, 0.0, g_load, y)
        od, odv, gd = to_contact_point(y, roll, turning, g_load) if roll > 0.0 else (0.0, 0.0, 0.0)
        frame = (od, odv, gd, roll, t)
        tau = t
        out_time = 0.0
        slip_time = 0.0
        guard = 0
        while tau < t_end and guard < _MAX_EVENTS:  # the step's events, one at a time
            guard += 1
            if ctr[1] == 1:
                tau, flown = _flight(y, ctr, st, prm, tau, t_end, frame)
                out_time += flown
            else:
                tau, slipped = _contact(y, ctr, st, prm, tau, t_end, frame)
                slip_time += slipped
        if roll > 0.0:
            # back to the centre (and psi, where it is integrated), at tau: the step's end, or
            # where a step with too many events stopped
            to_centre(y, roll, turning, (od, odv, gd), h if tau >= t_end else tau - t)
        if tau < t_end:
            # more events in one step than the scheme resolves: never fall behind silently
            st[S_BAD] = BAD_EVENTS
            st[S_BADSTEP] = k
            return
        if _end_step(y, ctr, st, prm, t_end, (out_time, slip_time), rec, rec_every):
            return
