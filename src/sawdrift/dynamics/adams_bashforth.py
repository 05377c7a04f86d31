"""Adams-Bashforth integration of paper eq. 5 for compliant contact models.

The loop is written once, in plain Python; the compiled engine is the same function compiled by
numba with the model's kernel bound in (one specialization per kernel, built on first use), the
python engine runs it as it is with the model's pure-Python reference. Per step it does O(1) work
plus one call of the contact law, allocates nothing, and evaluates the (history-dependent) force
exactly once, at the committed state: Adams-Bashforth needs no trial evaluations.

Equations (normalized, docs/physics.md)::

    m* x''  = -mu T*(b*, a*)              theta mu b* = x* - u_x(t*)
    m* y''  = 1 - N*(a*)                   a*          = y* - u_y(t*)
    u_x = -A* r R(t*) sin(2 pi t*)         u_y = A* R(t*) cos(2 pi t*)

with the substrate motion of the scene's drive (:mod:`sawdrift.dynamics.drives`): the loop calls
``drive_surface(t, x, dp)``, bound per drive like the kernel ``force``.
"""

from __future__ import annotations

import math
import sys
import types
from collections.abc import Callable
from typing import Any

import numpy as np
from numba import njit

from ..codegen import Generated, generate, rebind
from ..contact.slot_kernels import damped_contact
from . import evidence
from .air_drag import drag_acceleration
from .evidence import (
    BAD_NONFINITE,
    EV_MARGIN,
    S_BAD,
    S_BADSTEP,
    SLIP_RTOL,
    log_full,
    observe_contact,
    observe_step,
)
from .flight import (  # noqa: F401 - loop globals
    count_flight,
    flight_body,
    flight_skip,
    on_parabola,
    parabola,
)
from .rolling import (  # noqa: F401 - ROLL_DAMPING: the rolling spring's, named here too
    JIT,
    ROLL_DAMPING,
    contact_point,
    integrates_psi,
    rolling_torque,
    rotational_inertia,
    slide_spring,
)

#: Adams-Bashforth coefficients, row k-1 for order k (Hairer, Norsett, Wanner, *Solving ODEs I*,
#: section III.1, table 1.1), newest derivative first.
AB_COEFFS = np.array(
    [
        [1.0, 0.0, 0.0, 0.0],
        [3.0 / 2.0, -1.0 / 2.0, 0.0, 0.0],
        [23.0 / 12.0, -16.0 / 12.0, 5.0 / 12.0, 0.0],
        [55.0 / 24.0, -59.0 / 24.0, 37.0 / 24.0, -9.0 / 24.0],
    ]
)

#: Names of the scheme's parameter vector ``prm`` (the drive's own are in ``dp``), in order;
#: :func:`pack` builds it from a dict of these names.
PRM_NAMES = (
    "m",  # m* of the normal equation
    "mu",  # friction coefficient
    "theta",  # E*/(4 G*) of the contact: theta mu b* = x* - u_x
    "h",  # step in t*
    "order",  # Adams-Bashforth order 1-4
    "friction",  # 1: integrate x* with the tangential law, 0: friction off
    "damping",  # viscous normal damping c (0: off)
    "p",  # exponent of the profile's normal law (rolling spring stiffness)
    "k_ramp",  # first step after the drive's start-up ramp (evidence is taken from there)
    "roll",  # rotation: c = 1 + 1/kappa with the sphere free to turn, 0 without rotation
    "rolling_resistance",  # mu_r of the elastic-plastic rolling spring (0: off)
    "m_x",  # horizontal inertia m*_x (m* itself, except in steady.settle's reduced inertia)
    "load",  # constant external tangential force L on the centre, in M g (0: off)
    "restitution_damping",  # C of the restitution damping C a*^((p-1)/2) a*' (0: off)
    "air_drag",  # c of the linear air drag -c v on the centre (0: off), dynamics.air_drag
    "pulloff",  # F*_pull of an adhesive contact: it slides at |T*| = N* + 2 F*_pull (0: none)
    "surface_bound",  # U >= |u_y| at every t*, x* (the drive's; -1: none), dynamics.flight
)
(P_M, P_MU, P_THETA, P_H, P_ORDER, P_FRICTION, P_DAMP, P_P, P_KRAMP, P_ROLL, P_RR,
 P_MX, P_LOAD, P_REST, P_DRAG, P_PULL, P_SURF) = range(len(PRM_NAMES))
N_PRM = len(PRM_NAMES)

#: the horizontal inertia m*_x (P_MX) that ``numerics.settle`` integrates a heavier particle
#: with (:mod:`.steady`); the step's air-drag bound reads it too (:func:`~.assembly.drag_inertia`)
HEAVY_MASS = 100.0


def horizontal_inertia(m_star: float, rigid: bool) -> float:
    """m*_x of the reduced-inertia method: min(m*, HEAVY_MASS) for compliant models.

    A rigid point keeps m*: its stick condition |m* u_x''| <= mu N* contains the horizontal
    inertia itself, so reducing it would change where the point sticks.
    """
    return m_star if rigid else min(m_star, HEAVY_MASS)


def pack(values: dict[str, float], names: tuple[str, ...] = PRM_NAMES) -> np.ndarray:
    """The parameter vector of ``names`` (all required) from a dict of named values."""
    missing = [n for n in names if n not in values]
    if missing:
        raise KeyError(f"parameters without a value: {missing}")
    return np.array([float(values[n]) for n in names], dtype=np.float64)

def restitution_of_damping_ratio(zeta: float) -> float:
    """Rebound speed ratio e of a free impact on a linear spring-dashpot of damping ratio zeta.

    x'' = -x - 2 zeta x' from x = 0, x' = 1, with the force clamped at zero (the contact does not
    pull: it ends where x + 2 zeta x' = 0). Closed form of Schwager and Poeschel (2007, Granular
    Matter 9, 465-469): for zeta < 1, e = exp(-zeta (pi - phi) / w) with w = sqrt(1 - zeta^2),
    phi = atan2(2 zeta w, 1 - 2 zeta^2); e = exp(-2) at zeta = 1; for zeta > 1 the overdamped
    solution evaluated where the force vanishes, t_c = ln(2 zeta^2 - 1 + 2 zeta s) / s,
    s = sqrt(zeta^2 - 1).
    """
    if zeta <= 0.0:
        return 1.0
    if zeta < 1.0:
        w = math.sqrt(1.0 - zeta * zeta)
        phi = math.atan2(2.0 * zeta * w, 1.0 - 2.0 * zeta * zeta)
        return math.exp(-zeta * (math.pi - phi) / w)
    if zeta == 1.0:
        return math.exp(-2.0)
    s = math.sqrt(zeta * zeta - 1.0)
    l1, l2 = -zeta + s, -zeta - s
    t = math.log(2.0 * zeta * zeta - 1.0 + 2.0 * zeta * s) / s
    return -(l1 * math.exp(l1 * t) - l2 * math.exp(l2 * t)) / (l1 - l2)


#: the smallest restitution a compliant contact takes: its damping ratio zeta = 1.95 stays inside
#: the explicit scheme's stability at the default step (h omega <= 0.06, damping rate
#: 2 zeta omega: h 2 zeta omega <= 0.24 against AB4's real stability bound 0.3)
MIN_RESTITUTION = 0.05


def damping_ratio(e: float) -> float:
    """The damping ratio zeta whose clamped linear impact rebounds with ratio ``e`` in (0, 1].

    Inverts :func:`restitution_of_damping_ratio` (monotone decreasing) by bisection to 1e-15.
    """
    if not 0.0 < e <= 1.0:
        raise ValueError(f"restitution e = {e!r} is outside (0, 1]")
    if e == 1.0:
        return 0.0
    lo, hi = 0.0, 1.0
    while restitution_of_damping_ratio(hi) > e:
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if restitution_of_damping_ratio(mid) > e:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-15 * hi:
            break
    return 0.5 * (lo + hi)


def restitution_damping(e: float, p: float, m_star: float) -> float:
    """C of the restitution damping N* += C a*^((p-1)/2) a*' for the normal law N* = a*^p.

    The damping force is beta sqrt(m* dN*/da*) a*' (stiffness-proportional, as in DEM codes after
    Tsuji, Tanaka and Ishida 1992, Powder Technol. 71, 239-250), so C = beta sqrt(p m*). In the
    phase plane of the free impact, m* v dv/da = -a^p - C a^((p-1)/2) v, the substitution
    a = A x^(2/(p+1)) with A^(p+1) = (p+1)/2 gives exactly the linear spring-dashpot
    v dv/dx = -x - 2 zeta v (with time in units of sqrt(m*)) of damping ratio
    zeta = beta sqrt(p / (2 (p + 1))), and the clamp N* = 0 maps onto x + 2 zeta v = 0 (Antypov
    and Elliott 2011, EPL 94, 50004, for p = 3/2). The rebound ratio is therefore that of the
    clamped linear dashpot, independent of the impact speed and of m*: C = zeta(e)
    sqrt(2 (p + 1) m*) with zeta from :func:`damping_ratio`. Gravity, left out of this impact,
    changes the rebound by a part that falls with the impact speed (docs/physics.md).
    """
    return damping_ratio(e) * math.sqrt(2.0 * (p + 1.0) * m_star)


#: State vector: x*, x*', y*, y*', then, with rolling resistance, psi = R phi / a0, psi' and the
#: elastic rolling displacement psi_e of the spring.
N_STATE = 7


# The statistics vector ``st`` and its event log: see :mod:`sawdrift.dynamics.evidence`.

# Columns of the trajectory record: N_star and T_star are N* and T* (T* would shadow a
# DataFrame's transpose ``.T``); psi = R phi / a0 and spin = psi' are the rolling angle and its
# rate (kept in the table only when the sphere may turn).
REC_COLUMNS = ("t", "x", "vx", "y", "vy", "a", "b", "N_star", "T_star", "psi", "spin")
N_REC = len(REC_COLUMNS)

@njit(cache=True)
def record(rec, ctr, t, y, a, b, nf, tf):
    """Append one trajectory row (columns :data:`REC_COLUMNS`) at ``rec[ctr[2]]`` if it fits."""
    i = ctr[2]
    if i < rec.shape[0]:
        rec[i, 0] = t
        rec[i, 1] = y[0]
        rec[i, 2] = y[1]
        rec[i, 3] = y[2]
        rec[i, 4] = y[3]
        rec[i, 5] = a
        rec[i, 6] = b
        rec[i, 7] = nf
        rec[i, 8] = tf
        rec[i, 9] = y[4]
        rec[i, 10] = y[5]
        ctr[2] = i + 1


@njit(cache=True)
def next_record(k, every):
    """The first step from ``k`` on whose trajectory row is recorded (a multiple of ``every``),
    or -1 where none is (``every`` <= 0). The loops compare the step with it instead of taking
    ``k % every`` at every step: an integer division a step cost a measuring window of 27
    periods (its strobe rows, every 128 steps) about 35 us of its 95 (mmd, m* = 0.1, A* = 1,
    on the benchmarks' 2-core machine)."""
    if every <= 0:
        return -1
    r = k % every
    return k if r == 0 else k + every - r


#: The loop body reads ``force`` (the kernel) and ``ab`` as globals, bound per kernel in the
#: generated module (sawdrift.codegen) or the python engine's function (_python_loop); the values here
#: only name them.
force: Callable[..., Any] | None = None
ab = AB_COEFFS


@njit(**JIT)
def push_derivatives(fh, y, ax, ay, ncomp, move_x):
    """Shift the derivative history ``fh`` one step back and put the new derivatives in row 0.

    Row 0 is (x*', x*'', y*', y*''): x*' only where x* moves (``move_x``: friction or a load);
    a rolling sphere's (psi', psi'') follow in columns 4-5 (:func:`~.rolling.rolling_torque`).
    """
    for j in range(3, 0, -1):
        for c in range(ncomp):
            fh[j, c] = fh[j - 1, c]
    fh[0, 0] = y[1] if move_x else 0.0
    fh[0, 1] = ax
    fh[0, 2] = y[3]
    fh[0, 3] = ay


@njit(**JIT)
def ab_advance(y, fh, ctr, ab_coeffs, h, order, ncomp):
    """y += h sum_j beta_j f_{n-j}: the Adams-Bashforth step of the order reached (at most
    ``order``; Hairer, Norsett, Wanner, *Solving ODEs I*, III.1), ``ab_coeffs`` :data:`AB_COEFFS`."""
    q = ctr[1] + 1
    if q > order:
        q = order
    for c in range(ncomp):
        acc = 0.0
        for j in range(q):
            acc += ab_coeffs[q - 1, j] * fh[j, c]
        y[c] += h * acc
    if ctr[1] < 4:
        ctr[1] += 1


@njit(**JIT)
def accelerations(y, nf, tf, mu, load, mx, m, drag):
    """(x*'', y*'') of eq. 5: m*_x x*'' = -mu T* + L, m* y*'' = 1 - N*, with the air drag."""
    ax = (-mu * tf + load) / mx if load != 0.0 else -mu * tf / mx
    ay = (1.0 - nf) / m
    if drag > 0.0:
        dax, day = drag_acceleration(y, drag, mx, m)
        ax += dax
        ay += day
    return ax, ay


@njit(**JIT)
def nonfinite(st, y, forces, k):
    """Mark step ``k`` bad in ``st`` (and return True) if the state or the forces are not finite."""
    if math.isfinite(y[0] + y[1] + y[2] + y[3]) and math.isfinite(forces):
        return False
    st[S_BAD] = BAD_NONFINITE
    st[S_BADSTEP] = k
    return True


def wave_loop_body(y, fh, ctr, contact, prm, dp, n_steps, rec, rec_every, st):
    """One integration segment of eq. 5 (module docstring): ``n_steps`` Adams-Bashforth steps.

    ``contact`` = (fs, is_, pp), the contact history's arrays that ``force`` reads and commits;
    ``dp`` is the drive's parameter vector. ``force``, ``drive_surface`` and ``ab`` are globals
    bound per kernel and drive. With rotation the contact point is s* = x* + psi
    (:mod:`.rolling`); a constant load L acts on the centre, m* x*'' = -mu T* + L; the normal
    damping and the Coulomb cap of the loop are :func:`~sawdrift.contact.slot_kernels.damped_contact`.
    """
    fs, is_, pp = contact
    m, mx, mu = prm[P_M], prm[P_MX], prm[P_MU]
    scale_b = 1.0 / (prm[P_THETA] * mu)
    h = prm[P_H]
    friction = prm[P_FRICTION] > 0.0
    damp = prm[P_DAMP]
    k_ramp = int(prm[P_KRAMP])
    roll = prm[P_ROLL]
    rr = prm[P_RR]
    load = prm[P_LOAD]
    spin = integrates_psi(roll, rr, load, y, prm[P_DRAG])
    kappa_m = rotational_inertia(mx, roll)
    p_exp = prm[P_P]
    rest = prm[P_REST]
    q_rest = 0.5 * (p_exp - 1.0)
    order = int(prm[P_ORDER])
    drag = prm[P_DRAG]
    pull2 = 2.0 * prm[P_PULL]
    ncomp = 6 if spin else 4
    move_x = friction or load != 0.0 or drag > 0.0
    # a free flight in closed form (dynamics.flight): no adhesion, air drag or rolling, order >= 2
    fly = pull2 == 0.0 and drag == 0.0 and not spin and order >= 2
    k_end = ctr[0] + n_steps
    k_rec = next_record(ctr[0], rec_every)
    while ctr[0] < k_end:
        k = ctr[0]
        t = k * h
        ux, uxd, uy, uyd = drive_surface(t, y[0], dp)  # noqa: F821
        a = y[2] - uy
        adot = y[3] - uyd
        if friction:
            s, sv = contact_point(y, roll, spin)
            b = (s - ux) * scale_b
            nf, tf = force(fs, is_, pp, a, b, adot, (sv - uxd) * scale_b)
        else:
            # friction off: ``force`` is the model's normal law alone (its normal slot)
            b = 0.0
            nf, tf = force(fs, is_, pp, a, 0.0, adot, 0.0)
            tf = 0.0
        if (damp > 0.0 or rest > 0.0) and a > 0.0:
            nf, tf = damped_contact(nf, tf, a, adot, damp, rest, q_rest)
        ax, ay = accelerations(y, nf, tf, mu, load, mx, m, drag)
        # adhesion holds on while it pulls (N* < 0 at a* <= 0) and slides at N* + 2 F*_pull
        inside = a > 0.0 or nf != 0.0
        slipping = (friction and inside and nf + pull2 > 0.0
                    and abs(tf) >= (1.0 - SLIP_RTOL) * (nf + pull2))
        observe_contact(st, t, y, a, inside, slipping)
        if k >= k_ramp:
            observe_step(st, 0.0 if inside else 1.0, 1.0 if slipping else 0.0, a)
        if k == k_rec:
            record(rec, ctr, t, y, a, b, nf, tf)
            k_rec += rec_every
        push_derivatives(fh, y, ax, ay, ncomp, move_x)
        if spin:
            mr, kr, cap = rolling_torque(y, a, nf + pull2, rr, p_exp, kappa_m)
            fh[0, 4] = y[5]
            fh[0, 5] = (-mu * tf + mr) / kappa_m
            psi_old = y[4]
        ab_advance(y, fh, ctr, ab, h, order, ncomp)
        if spin:
            slide_spring(y, psi_old, kr, cap)
        ctr[0] = k + 1
        if nonfinite(st, y, nf + tf, k):
            return
        if log_full(st, EV_MARGIN):
            return  # the stepper grows the event log and goes on from the next step
        if fly and count_flight(st, y, ctr[0], not inside and nf == 0.0 and tf == 0.0):
            flight_body(y, fh, ctr, dp, k_end, rec, rec_every, st,
                        (h, m, ax, k_ramp, scale_b if friction else 0.0, roll, move_x,
                         prm[P_SURF]))
            k_rec = next_record(ctr[0], rec_every)


_COMPILED: dict[Any, Callable[..., None]] = {}

#: import lines of the generated loop module: the loop body's global names (see sawdrift.codegen)
_LOOP_IMPORTS = (
    "from sawdrift.dynamics.adams_bashforth import *  # noqa: F403\n"
    "from sawdrift.dynamics.adams_bashforth import AB_COEFFS as ab  # noqa: F401\n"
    "from sawdrift.dynamics.evidence import *  # noqa: F403\n"
)


def _public(module: types.ModuleType) -> dict[str, Any]:
    names = getattr(module, "__all__", None) or [n for n in vars(module) if not n.startswith("_")]
    return {n: getattr(module, n) for n in names}


def _loop_namespace(force: Callable[..., Any], drive_surface: Callable[..., Any]) -> dict[str, Any]:
    """The global names the loop body runs with (the values of the generated module's imports)."""
    ns = {**_public(sys.modules[__name__]), **_public(evidence)}
    ns.update(drive_surface=drive_surface, force=force, ab=AB_COEFFS)
    return ns


def wave_loop(force: Callable[..., Any], drive: Any, compiled: bool) -> Callable[..., None]:
    """The integration loop for a force function and a drive (:mod:`sawdrift.dynamics.drives`).

    The compiled loop is cached on disk across processes (see :mod:`sawdrift.codegen`): it is
    generated, once per kernel and drive, as a small module that imports the kernel and the
    drive's ``surface`` by name, so that numba's ``cache=True`` applies; a kernel that cannot be
    imported by name (defined in ``__main__`` or a notebook) is compiled in memory instead.
    Compiled loops are also cached per process. The python engine runs the same body as plain
    Python with the same functions bound in.
    """
    surface = drive.functions()[0]
    if not compiled:
        scope = dict(_loop_namespace(force, surface), force=force)
        return rebind((flight_body, wave_loop_body), scope)["wave_loop_body"]
    key = (force, drive.module)
    fn = _COMPILED.get(key)
    if fn is None:
        fn = generate(Generated(
            prefix="sawdrift_loop_", doc=f"the wave loop bound to a kernel and to {drive.module}",
            templates=(flight_body, wave_loop_body), namespace=_loop_namespace(force, surface),
            imports=_LOOP_IMPORTS, bind={"force": force, "drive_surface": (drive.module, "surface")},
            decorator="njit(cache=True, _nrt=False)", memory_options={"_nrt": False},
        ))["wave_loop_body"]
        _COMPILED[key] = fn
    return fn
