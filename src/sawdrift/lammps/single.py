"""One particle on the wave-driven plane through LAMMPS: the input, the run and its Result.

The LAMMPS model is the law the native ``hertz_mindlin_dem`` integrates
(plugins/sawdrift_builtin/hertz_mindlin_dem.py): ``fix wall/gran/region granular hertz/material
E_w 0 nu_w tangential mindlin_rescale/force k_t 0 mu`` (Hertz normal force, Mindlin's initial
tangential stiffness 8 G* a, the stored force rescaled by a/a_old while the contact shrinks, the
Coulomb cap mu N; damped by the scene's restitution, see :mod:`.realize`) against a plane
region moved by ``region ... move v_dx NULL v_dz`` with the scene's orbit and ramp
(docs/physics.md, "The wave and its orbit"):

    u_y* = A* R(t*) cos(2 pi t*)        u_x* = r A* R(t*) cos(2 pi t* + phase)

y* points into the substrate, so the wall's height is dz = -a0 u_y* and dx = a0 u_x*. Gravity
(the normal part) and the preload act as one constant force -M g along z, the scene's load as
L M g along x (``fix addforce``); ``fix nve`` keeps the sphere from turning, ``fix nve/sphere``
turns it (a solid sphere, kappa = 2/5). LAMMPS integrates with velocity Verlet, the native
engine with Adams-Bashforth; both start at rest at x* = 0, y* = 1 (a* = 1 under the ramp).

The Result has the native columns: the drift over the last ``measure_periods`` whole periods
(x* at the same phase at both ends), contact loss, gross slip (|T*| at the cap N*), lift-offs
and their synchrony, the stroboscopic periodicity and the fixed-run settledness, classified by
:func:`sawdrift.result.regimes.classify`. Not computed: the Lyapunov estimate (no twin run;
``lyapunov`` is NaN, ``chaotic`` False) and the ``settle`` continuation (LAMMPS always runs
``numerics.periods`` as a fixed run; where the native engine would settle, ``extra["lammps_note"]``
says so).
"""

from __future__ import annotations

import math
import tempfile
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..contact.binding import bind
from ..dynamics import evidence as ev
from ..dynamics.assembly import steps_per_period
from ..dynamics.drives.travelling import TravellingWave
from ..dynamics.steady import assess_fixed, relaxation_periods, settles
from ..dynamics.window import Window, orbit_period, periodicity
from ..errors import SawdriftError
from ..result.regimes import classify
from ..result.result import Result
from ..scene.device import device_outputs
from ..scene.schema import Scene
from ..study.progress import counter
from .engine import open_lammps
from .realize import LAMMPS_EQUIVALENT, WALL_NU, Realization, lammps_restitution, realize

if TYPE_CHECKING:
    import pandas as pd

#: chunks of a run between two progress updates (at most)
CHUNKS = 100

#: steps from which a run shows its progress unless told (progress=None)
LONG_RUN = 200_000

#: relative distance below which |T*| counts as on the Coulomb cap N* (gross slip)
CAP_TOL = 1e-9

#: columns of the per-step record (in this order; LAMMPS writes them after the step number, and
#: ``wy`` only with rotation): t* and the wall's height follow from the step (wave_variables)
RECORD = ("ts", "x", "vx", "z", "vz", "fx", "wy")


def wave_variables(real: Realization, k_per: int) -> list[str]:
    """LAMMPS equal-style variables: t* (``ts``), R(t*) (``rr``), the wall's ``dx`` and ``dz``."""
    tr = real.ramp_periods
    amp = real.amplitude
    bx = -amp * real.ratio * real.sin_phase * real.horizontal  # u_x coefficient of sin(2 pi t*)
    cx = amp * real.ratio * real.cos_phase * real.horizontal  # of cos(2 pi t*)
    ay = amp * real.vertical
    two_pi = 2.0 * math.pi
    ramp = (f"ternary(v_ts<{tr!r},sin({math.pi / (2.0 * tr)!r}*v_ts)^2,1.0)" if tr > 0.0 else "1.0")
    return [
        f"variable ts equal step/{k_per}",
        f"variable rr equal {ramp}",
        f"variable dx equal v_rr*({bx!r}*sin({two_pi!r}*v_ts)+{cx!r}*cos({two_pi!r}*v_ts))",
        f"variable dz equal -v_rr*{ay!r}*cos({two_pi!r}*v_ts)",
    ]


def granular_model(real: Realization, rescale: bool = True) -> str:
    """The pair granular / fix wall/gran contact: hertz/material + Mindlin, damped or not.

    Undamped: the normal model's damping coefficient is 0. With a restitution e: ``damping
    coeff_restitution`` with e' = :func:`~sawdrift.lammps.realize.lammps_restitution` (e) as the
    coefficient; with ``effects.normal_damping``: ``damping velocity`` with eta_n (N s/m); both
    with ``limit_damping`` (the total normal force is clamped at zero, as natively). No
    tangential damping (x_gamma_t = 0).
    """
    tangential = "mindlin_rescale/force" if rescale else "mindlin/force"
    damp, damping = 0.0, ""
    if real.restitution is not None:
        damp, damping = lammps_restitution(real.restitution), " damping coeff_restitution"
    elif real.normal_damping > 0.0:
        damp, damping = real.normal_damping, " damping velocity"
    limit = " limit_damping" if damping else ""
    return (f"hertz/material {real.wall_modulus!r} {damp!r} {WALL_NU!r}{damping} tangential "
            f"{tangential} {real.k_t!r} 0.0 {real.mu!r}{limit}")


def input_script(scene: Scene, real: Realization | None = None, k_per: int | None = None) -> str:
    """The LAMMPS input (units SI) of one particle of ``scene``, without the run commands."""
    real = realize(scene) if real is None else real
    k_per = steps_per_period(scene) if k_per is None else k_per
    rescale = bool(scene.model_params.get("rescale", True))
    dt = 1.0 / (real.frequency * k_per)
    big = 1e3 * real.radius
    # start as the native engine does: x* = 0, y* = 1 (the static compression of the surface at
    # rest, a* = 1 with the ramp; without a ramp the surface starts at u_y*(0) = A*), at rest
    z0 = real.radius - real.a0
    lines = [
        "# sawdrift: one particle on the wave-driven plane (units SI)",
        f"# m* = {real.m_star!r}, A* = {real.amplitude / real.a0!r}, theta = {real.theta!r}, "
        f"mu = {real.mu!r}, r = {real.ratio!r}, a0 = {real.a0!r} m, f = {real.frequency!r} Hz",
        "units si",
        "atom_style sphere",
        "atom_modify map array",
        "dimension 3",
        "boundary p p f",
        "newton off",
        "comm_modify vel yes",
        f"region box block {-big!r} {big!r} {-big!r} {big!r} {-10 * real.radius!r} "
        f"{10 * real.radius!r}",
        "create_box 1 box",
        f"create_atoms 1 single 0.0 0.0 {z0!r}",
        f"set atom 1 diameter {2.0 * real.radius!r} density {real.density!r}",
        "velocity all set 0.0 0.0 0.0",
        "pair_style granular",
        f"pair_coeff * * {granular_model(real, rescale)}",
        *wave_variables(real, k_per),
        "region wall plane 0.0 0.0 0.0 0.0 0.0 1.0 side in move v_dx NULL v_dz",
        f"fix wall all wall/gran/region granular {granular_model(real, rescale)} region wall",
        f"fix load all addforce {real.load!r} 0.0 {-real.weight!r}",
        "fix move all nve/sphere" if real.rotation else "fix move all nve",
        f"timestep {dt!r}",
        "variable x equal x[1]",
        "variable vx equal vx[1]",
        "variable z equal z[1]",
        "variable vz equal vz[1]",
        "variable fx equal fx[1]",
        "variable fz equal fz[1]",
        "compute spin all property/atom omegay",
        "compute spinsum all reduce sum c_spin",
        "variable wy equal c_spinsum",
        "variable wz equal v_dz",
        "thermo 0",
    ]
    return "\n".join(lines) + "\n"


def _record_fix(path: Path, rotation: bool) -> str:
    names = " ".join(f"v_{c}" for c in RECORD[1:] if rotation or c != "wy")
    return f"fix rec all ave/time 1 1 1 {names} file {path} format ' %.17g'"


def _run_steps(lmp: Any, n: int, first: bool, bar: Any) -> bool:
    """Advance ``n`` steps in up to :data:`CHUNKS` runs; True once LAMMPS has been set up."""
    chunk = max(1, -(-n // CHUNKS))
    done = 0
    while done < n:
        k = min(chunk, n - done)
        lmp.command(f"run {k}" if first else f"run {k} pre no post no")
        first = False
        done += k
        bar.update(k)
    return first


def simulate(scene: Scene, *, record_from: int | None = None, progress: bool | None = None
             ) -> tuple[np.ndarray, dict[str, Any]]:
    """Run ``scene`` in LAMMPS; the per-step record from step ``record_from`` (default: the window).

    Returns
    -------
    (rows, info)
        ``rows`` has the columns :data:`RECORD` (SI; ``ts`` is t*), one row per step from
        ``record_from`` (included) to the end; ``info`` holds the realization, ``k_per``, the
        steps, the window's first step, the wall time and the input script.
    """
    real = realize(scene)
    k_per = steps_per_period(scene)
    n_measure = scene.measure_periods() * k_per
    n_total = max(int(round(scene.numerics.periods * k_per)), n_measure)
    start = n_total - n_measure if record_from is None else max(0, min(record_from, n_total))
    script = input_script(scene, real, k_per)
    lmp = open_lammps()
    with tempfile.TemporaryDirectory(prefix="sawdrift-lammps-") as tmp:
        path = Path(tmp) / "record.txt"
        show = n_total >= LONG_RUN if progress is None else progress
        bar = counter(n_total, "lammps", "step", enabled=show)
        t0 = time.perf_counter()
        try:
            lmp.commands_string(script)
            if start > 0:
                _run_steps(lmp, start, True, bar)
            lmp.command(_record_fix(path, real.rotation))
            _run_steps(lmp, n_total - start, True, bar)  # set-up again: the new fix joins
            lmp.command("unfix rec")
        except Exception as exc:  # noqa: BLE001 - LAMMPS reports its errors as Exception
            raise SawdriftError(f"LAMMPS failed: {str(exc).splitlines()[0]}") from None
        finally:
            wall = time.perf_counter() - t0
            bar.close()
            lmp.close()
        table = np.loadtxt(path, comments="#", ndmin=2)
    # one row per step (a run's set-up may write its first step again), from record_from on
    _, first_rows = np.unique(table[:, 0], return_index=True)
    table = table[first_rows]
    if table.shape[0] != n_total - table[0, 0] + 1 or table[0, 0] > start:
        raise SawdriftError(f"LAMMPS wrote {table.shape[0]} records for steps {start} to "
                            f"{n_total}; the run did not complete")
    start = int(table[0, 0])
    ts = table[:, 0:1] / k_per
    spin = table[:, 6:7] if real.rotation else np.zeros_like(ts)
    rows = np.hstack([ts, table[:, 1:6], spin])
    info = {"real": real, "k_per": k_per, "steps": n_total, "window_start": n_total - n_measure,
            "record_from": start, "wall_time_s": wall, "script": script}
    return rows, info


def normalized_record(rows: np.ndarray, real: Realization) -> dict[str, np.ndarray]:
    """The record in the normalized variables of docs/physics.md.

    t*, x* = x/a0, x*' = vx/(a0 f), y* = (R - z)/a0 (into the substrate), y*' = -vz/(a0 f),
    a* = (R - z + z_wall)/a0, N* = a*^(3/2) (a* > 0), T* = -(F_x - L M g)/(mu M g) (the friction
    force against +x, m x'' = -T + load), psi' = -R omega_y/(a0 f) (R phi', the contact point's
    velocity relative to the centre), u_x* and b* = (x* - u_x*)/(theta mu).
    """
    ts, x, vx, z, vz, fx, wy = rows.T
    a0, v = real.a0, real.speed
    two_pi = 2.0 * math.pi
    tr = real.ramp_periods
    rr = np.where(ts < tr, np.sin(math.pi / (2.0 * tr) * ts) ** 2, 1.0) if tr > 0.0 else np.ones_like(ts)
    wz = -rr * real.amplitude * real.vertical * np.cos(two_pi * ts)  # the wall's height (v_dz)
    a = (real.radius - z + wz) / a0
    amp = real.amplitude / a0
    ux = rr * amp * real.ratio * real.horizontal * (
        -real.sin_phase * np.sin(two_pi * ts) + real.cos_phase * np.cos(two_pi * ts))
    n_star = np.where(a > 0.0, np.maximum(a, 0.0) ** 1.5, 0.0)
    t_star = -(fx - real.load) / (real.mu * real.weight)
    return {"t": ts, "x": x / a0, "vx": vx / v, "y": (real.radius - z) / a0, "vy": -vz / v,
            "a": a, "b": (x / a0 - ux) / (real.theta * real.mu), "N_star": n_star, "T_star": t_star,
            "spin": -real.radius * wy / v}


def _events(rec: dict[str, np.ndarray]) -> np.ndarray:
    """Lift-off and landing rows (t*, kind, x*, x*', y*, y*', a*), times interpolated in a*."""
    a = rec["a"]
    inside = a > 0.0
    change = np.nonzero(inside[1:] != inside[:-1])[0]
    out = np.empty((change.size, ev.EV_W))
    for row, i in enumerate(change):
        frac = a[i] / (a[i] - a[i + 1]) if a[i] != a[i + 1] else 1.0
        t = rec["t"][i] + frac * (rec["t"][i + 1] - rec["t"][i])
        kind = ev.EV_LIFT_OFF if inside[i] else ev.EV_LANDING
        out[row] = (t, kind, rec["x"][i + 1], rec["vx"][i + 1], rec["y"][i + 1], rec["vy"][i + 1], 0.0)
    return out


def to_result(scene: Scene, rows: np.ndarray, info: dict[str, Any], trajectory: bool = False
              ) -> Result:
    """The native :class:`~sawdrift.result.Result` of a LAMMPS record (module docstring)."""
    real: Realization = info["real"]
    k_per = info["k_per"]
    rec_all = normalized_record(rows, real)
    w0 = info["window_start"] - info["record_from"]  # row j is step record_from + j
    rec = {k: v[w0 + 1:] for k, v in rec_all.items()}  # the window's steps
    periods = scene.measure_periods()
    drive = TravellingWave()
    speed = drive.horizontal_speed(scene)
    scale = drive.state_scale(scene)
    t_start = info["window_start"] / k_per
    x_start = rec_all["x"][w0]
    ends = np.arange(1, periods + 1) * k_per - 1
    samples = np.column_stack([rec["x"][ends], rec["vx"][ends], rec["y"][ends], rec["vy"][ends]])
    positions = np.concatenate(([x_start], samples[:, 0]))
    orbit = orbit_period(samples, scale)
    whole = (periods // orbit) * orbit if orbit > 1 else periods
    drift = float((positions[-1] - positions[periods - whole]) / whole)
    a = rec["a"]
    inside = a > 0.0
    slipping = inside & (np.abs(rec["T_star"]) >= rec["N_star"] * (1.0 - CAP_TOL))
    events = _events(rec)
    contact_lost = bool((~inside).any())
    n = a.size
    win = Window(
        periods=periods, t_start=t_start, drift=drift,
        spin_rate=float(rec["spin"].mean()) if real.rotation else math.nan,
        drift_ratio=drift / speed if speed > 0.0 else 0.0, samples=samples,
        contact_lost=contact_lost, out_of_contact_fraction=float((~inside).sum() / n),
        min_compression=float(a.min()), gross_slip_fraction=float(slipping.sum() / n),
        liftoffs_per_period=float((events[:, 1] == ev.EV_LIFT_OFF).sum()) / periods,
        periodicity=periodicity(samples, scale), events=events, events_dropped=0,
        orbit_period=orbit, positions=positions,
    )
    sync = win.sync
    num = scene.numerics
    settling = assess_fixed(win, speed, num.settle_tolerance,
                            relaxation_periods(scene, scene.particle.m_star, speed),
                            info["steps"] / k_per, False)
    hop_period = sync.hop_period
    vertical = 2.0 * math.pi * drive.vertical_amplitude(scene)
    ratio_for_regime = win.drift_ratio if speed > 0.0 else (drift / vertical if vertical > 0.0 else 0.0)
    regime = classify(contact_lost, ratio_for_regime, num.drift_tolerance,
                      gross_slip_fraction=win.gross_slip_fraction, hop_period=hop_period)
    extra: dict[str, Any] = {
        "lammps": {"model": LAMMPS_EQUIVALENT[scene.model], "a0_m": real.a0,
                   "frequency_hz": real.frequency, "radius_m": real.radius,
                   "e_star_pa": real.e_star, "g_star_pa": real.g_star},
    }
    if settles(scene, speed, rigid=False):
        extra["lammps_note"] = (f"numerics.settle is not continued in LAMMPS: a fixed run of "
                                f"{info['steps'] / k_per:g} periods")
    if scene.device is not None:
        extra.update(device_outputs(scene.device, drift, regime, None))
    frame = _trajectory_frame(rec_all, real, k_per) if trajectory else None
    return Result(
        model=scene.model, engine="lammps", m_star=scene.particle.m_star,
        amplitude=scene.drive.amplitude, mu=scene.material.mu, nu=scene.material.nu,
        horizontal_ratio=scene.horizontal_ratio, profile=scene.particle.profile.shape,
        steps_per_period=k_per, periods=info["steps"] / k_per, ramp_periods=scene.drive.ramp_periods,
        measure_periods=periods, drift_velocity=drift,
        drift_ratio=win.drift_ratio if speed > 0.0 else math.nan, regime=regime,
        orbit=drive.orbit_name(scene), contact_lost=contact_lost,
        out_of_contact_fraction=win.out_of_contact_fraction, min_compression=win.min_compression,
        steps=info["steps"], wall_time_s=info["wall_time_s"],
        gross_slip_fraction=win.gross_slip_fraction, liftoffs_per_period=win.liftoffs_per_period,
        hop_period=hop_period, liftoff_phase=sync.phase, liftoff_phase_spread=sync.spread,
        lyapunov=math.nan, periodicity=win.periodicity, spin_rate=win.spin_rate,
        scene=scene.model_dump(mode="json"), trajectory=frame, event_rows=events, chaotic=False,
        events_dropped=0, compile_s=0.0, orbit_period=orbit, settled=settling.settled,
        settle_method=settling.method, settle_periods=settling.periods,
        liftoffs_per_hop=sync.liftoffs_per_hop if sync.hop_period else math.nan, extra=extra,
    )


def _trajectory_frame(rec_all: dict[str, np.ndarray], real: Realization, k_per: int
                      ) -> pd.DataFrame:
    """The trajectory of a LAMMPS record as the native run gives it (about 200 rows a period):
    t*, x*, x*', y*, y*', a*, b*, N*, T*, and with rotation psi and its rate."""
    import pandas as pd

    every = max(1, k_per // 200)
    cols = ["t", "x", "vx", "y", "vy", "a", "b", "N_star", "T_star"]
    data = dict(rec_all)
    if real.rotation:
        # psi = R phi / a0 from rest (the record starts at t* = 0 here), by the trapezoidal
        # rule on psi' (LAMMPS keeps no angle); the contact point moves with x* + psi, so
        # b* = (x* + psi - u_x*) / (theta mu), as in the native trajectory
        spin = data["spin"]
        psi = np.concatenate(([0.0], np.cumsum(0.5 * (spin[1:] + spin[:-1]) / k_per)))
        data["psi"] = psi
        data["b"] = data["b"] + psi / (real.theta * real.mu)
        cols += ["psi", "spin"]
    return pd.DataFrame({c: data[c][::every] for c in cols})


def run_scene(scene: Scene, *, trajectory: bool = False, progress: bool | None = None) -> Result:
    """Run one particle of ``scene`` through LAMMPS and return the native Result columns.

    Parameters
    ----------
    scene
        A scene with a LAMMPS equivalent (:func:`sawdrift.lammps.realize.refusal`): model
        ``hertz_mindlin_dem``, a wave drive, a sphere, damped (restitution above 0.135) or
        not; rotation on or off.
    trajectory
        Also return the time series (t, x, vx, y, vy, a, b, N_star, T_star), about 200 rows per
        period, as ``Result.trajectory``.
    progress
        Show a progress bar (tqdm on a terminal, plain lines elsewhere) over the steps; None (the
        default): only for runs of at least :data:`LONG_RUN` steps.

    Raises
    ------
    SceneError
        The scene has no LAMMPS equivalent (one line).
    LammpsUnavailableError
        LAMMPS or its MPI library is missing (one line naming ``pip install -e ".[lammps]"``).
    """
    scene = bind(scene)  # its model's checks, and Result.scene with the parameters' defaults
    rows, info = simulate(scene, record_from=0 if trajectory else None, progress=progress)
    return to_result(scene, rows, info, trajectory)
