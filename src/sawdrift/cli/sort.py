"""sawdrift sort: sorting times of a two-size mixture from the slow model of touching chains."""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path
from typing import Annotated, Any

import typer

import sawdrift as sd

from .._startup import fast_start
from .app import _fail, _writable, app, interrupted_placements, json_nulls, out_kind
from .lammps import _scene_and_particles, with_particle_sets
from .scene_options import with_scene_options


@app.command("sort")
@with_particle_sets
@with_scene_options()
def sort_cmd(
    scene_file: Annotated[Path, typer.Argument(help="device scene TOML with a \\[particles] "
                                               "table of two radii")],
    # max: sawdrift.mixture.sort.MAX_SEEDS (not imported here: --help stays fast)
    seeds: Annotated[int, typer.Option("--seeds", min=1, max=10_000, help="random placements (seeds seed, "
                                       "seed+1, ...); at least 20 for a spread")] = 20,
    until: Annotated[float, typer.Option("--until", help="length of each run in wave periods "
                                         "(beads that touch nothing cost nothing)")] = 1e9,
    purity: Annotated[float, typer.Option("--purity", help="report the time from which the "
                                          "purity (each species on its driven side) stays at or "
                                          "above this, in (0.5, 1]")] = 0.9,
    curves: Annotated[str, typer.Option("--curves", help="force-velocity curves: 'native' (the "
                                        "engine) or 'lammps_rule' (LAMMPS's Coulomb rule)")] = "native",
    geometry: Annotated[str, typer.Option("--geometry", help="'plane': beads in 2-D on the plate, "
                                          "sliding round each other; 'line': lanes along the "
                                          "wave, beads cannot pass (1-D)")] = "plane",
    transverse: Annotated[float, typer.Option("--transverse", help="plane: factor on the "
                                              "assumed transverse mobility, in (0, 100] "
                                              "(docs/mixtures.md)")] = 1.0,
    jitter: Annotated[float, typer.Option("--jitter", help="plane: beads moved across the wave "
                                          "by this many small radii (seeded), in [0, 1], "
                                          "which breaks exactly head-on rows")] = 1e-3,
    check: Annotated[int, typer.Option("--check", min=0, help="also run the first placement in "
                                       "LAMMPS for N periods and print both (the slow model "
                                       "in lanes along the wave)")] = 0,
    progress: Annotated[bool | None, typer.Option(
        "--progress/--no-progress", help="a line per curve and placement on stderr (default: "
        "on a terminal)")] = None,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    out: Annotated[Path | None, typer.Option("-o", "--out", help="write sort.json, sort.png and "
                                             "the scene here")] = None,
    *,
    scene_overrides: dict[str, Any],
    particle_sets: dict[str, Any],
) -> None:
    r"""Sorting times of a two-size mixture: random placements moved by the slow model.

    Each bead drifts at the speed its force-velocity curves give under the loads of the beads it
    touches (pair forces along the inclined contact normals, which press the smaller bead onto
    the plate and lift the larger). --geometry plane (default): beads move in 2-D, the sideways
    part of an off-centre contact pushes a small bead round a large one (the sideways response
    is an assumption, stated in the output). --geometry line: beads in lanes along the wave
    move as chains at a common speed, merge on contact and split where the front runs ahead,
    event by event in slow time (1-D). Reports the segregation of the positions (purity of the
    best interface with each species on the side the wave drives it to, its index, Lacey)
    against time with its spread over the placements, the time from which the purity stays at
    --purity or above, the final state, and the accuracy the checks against LAMMPS showed
    (docs/mixtures.md).
    """
    fast_start()
    from ..mixture.sort import sort_mixture

    _check_options(curves, geometry, transverse, jitter)
    scene, particles = _scene_and_particles(scene_file, None, {}, scene_overrides,
                                            particle_sets)
    if particles is None:
        _fail(f"{scene_file}: sort needs a [particles] table (two radii)")
    _say_rounded(particles)
    why = slow_model_refusal(scene)
    if why is not None:
        _fail(why)
    if out is not None:
        out_kind(out, (), "")  # a folder: -o s.txt made a folder named s.txt
        _writable(out)
    # a terminal sees each placement end (the default was off: 15 to 30 s in silence)
    shown = sys.stderr.isatty() if progress is None else progress
    note = (lambda line: typer.echo(line, err=True)) if shown else None
    result = sort_mixture(scene, particles, seeds=seeds, periods=until, target=purity,
                          source=curves, geometry=geometry, perp=transverse,
                          jitter_radii=jitter, progress=note)  # type: ignore[arg-type]
    data = result.summary()
    if particles.get("positions") is not None and seeds > 1:  # it ran one, labelled seeds 0-0
        typer.echo(f"note: explicit positions are one placement; --seeds {seeds} does not apply "
                   "to them", err=True)
    if check and not result.interrupted:
        data["check"] = _check(scene, particles, result, check)
    if out is not None:
        from ..report.sort_plot import plot_sort

        out.mkdir(parents=True, exist_ok=True)
        (out / "sort.json").write_text(json.dumps(json_nulls(data), indent=1) + "\n")
        plot_sort(result, out / "sort.png")
        _write_scene(scene, particles, out / "scene.toml")
    if as_json:
        typer.echo(json.dumps(json_nulls(data)))
    else:
        for line in _lines(data):
            typer.echo(line)
        if out is not None:
            typer.echo(f"wrote {out}/sort.json, sort.png, scene.toml")
    if result.interrupted:
        interrupted_placements(len(result.seeds), seeds, out)


def _write_scene(scene: sd.Scene, particles: dict[str, Any], path: Path) -> None:
    """The scene with its ``[particles]`` table (the --set particles.FIELD values in it): the
    file a sort is run again from."""
    import tomli_w

    path.write_text(scene.to_toml() + "\n" + tomli_w.dumps({"particles": particles}))


#: the largest --transverse factor
MAX_TRANSVERSE = 100.0


def _check_options(curves: str, geometry: str, transverse: float, jitter: float = 1e-3) -> None:
    """One line (exit 2) for a bad --curves, --geometry or --transverse (--jitter: the study's
    own check, before any run), or a plane-only option given with --geometry line."""
    if curves not in ("native", "lammps_rule"):
        _fail(f"--curves = {curves!r}: use 'native' or 'lammps_rule'")
    if geometry not in ("plane", "line"):
        _fail(f"--geometry = {geometry!r}: use 'plane' or 'line'")
    if not (0.0 < transverse <= MAX_TRANSVERSE):
        # a stiffer sideways motion takes steps its factor times finer: 1e5 took 16 s a
        # placement, 1e9 did not end (nor stop on Ctrl-C, which waits for the placement)
        _fail(f"--transverse = {transverse!r}: give a factor in (0, {MAX_TRANSVERSE:g}] (the "
              "documented sensitivity runs 0.3 to 3)")
    if geometry == "line" and (transverse != 1.0 or jitter != 1e-3):
        # the lanes' beads do not move across the wave: both were ignored without a word
        given = "--transverse" if transverse != 1.0 else "--jitter"
        _fail(f"{given} belongs to --geometry plane (beads in lanes do not move across the "
              "wave); leave it out or use the plane")


#: where docs/mixtures.md lists what the slow model leaves out
NOT_INCLUDED = "docs/mixtures.md, 'Not included'"


def slow_model_refusal(scene: sd.Scene) -> str | None:
    """What the slow model of chains cannot run (one line naming the field), or None.

    Rotation, a second wave and adhesion are not in the model (:data:`NOT_INCLUDED`); the rest
    is what the SI realization it shares with LAMMPS refuses (:func:`sawdrift.lammps.refusal`).
    """
    from ..lammps import refusal
    from ..scene.schema import Wave

    eff = scene.effects
    if eff.rotation:
        return (f"effects.rotation = true: the slow sorting model has no rotation ({NOT_INCLUDED}); "
                "drop --rotation")
    d = scene.drive
    if isinstance(d, Wave) and d.amplitude == 0.0:
        field = "device.amplitude" if scene.device is not None else "drive.amplitude"
        return f"{field} = 0: no wave moves the beads; give an amplitude > 0"
    if isinstance(d, Wave):
        extra = {"backward": d.backward > 0.0, "wavelength": d.wavelength is not None,
                 "position": d.position != 0.0, "backward_phase_rate": bool(d.backward_phase_rate)}
        for name, given in extra.items():
            if given:
                return (f"drive.{name} = {getattr(d, name)!r}: the slow sorting model runs one "
                        f"travelling wave's local orbit ({NOT_INCLUDED}): no backward wave, position, "
                        "wavelength or phase rate")
    if eff.adhesion != "none":
        return (f"effects.adhesion = {eff.adhesion!r}: the slow sorting model has no adhesion "
                f"({NOT_INCLUDED}); set effects.adhesion = 'none'")
    why = refusal(scene)
    return None if why is None else f"{why} (sort sizes its beads as the LAMMPS engine does)"


def _check(scene: sd.Scene, particles: dict[str, Any], result: Any, periods: int) -> dict[str, Any]:
    """The first placement in LAMMPS for ``periods`` periods, against the slow model's run."""
    from ..lammps import refusal
    from ..lammps.many import parse_particles, run_particles
    from ..mixture.segregation import purity as position_purity

    why = refusal(scene)
    if why is not None:
        _fail(why)
    spec = parse_particles(particles).model_copy(update={"seed": result.seeds[0]})
    lmp = run_particles(scene.with_updates(**{"numerics.periods": float(periods),
                                              "numerics.measure_periods": max(1, periods // 2)}),
                        spec, progress=False)
    from ..mixture.sort import slow_window

    model = slow_window(scene, spec, result, periods)
    rows = []
    for k, row in enumerate(lmp.species):
        rows.append({"radius_m": row["radius_m"], "lammps_drift_ratio": row["drift_ratio"],
                     "model_drift_ratio": model["drift_ratio"][k]})
    return {"periods": periods, "species": rows, "lammps_wall_time_s": lmp.wall_time_s,
            "lammps_purity": position_purity(lmp.final_x, lmp.kinds, result.right),
            "model_purity": model["purity"],
            "model_wall_time_s": model["wall_time_s"], "model_geometry": "line",
            "lammps_touching_pairs": lmp.window_pairs, "model_chains": model["chains"],
            "transient": periods < CHECK_PERIODS}


def _say_rounded(particles: dict[str, Any]) -> None:
    """A note on stderr where the placements' counts are not round(fraction count): each species
    keeps at least one bead (count 10, fraction 0.01 placed 1 small and 9 large, silently)."""
    from ..lammps.placement import parse_particles

    spec = parse_particles(particles)
    if len(spec.radius) != 2 or spec.positions is not None:
        return
    first = spec.counts()[0]
    share = spec.fraction * spec.count
    if first != round(share):
        typer.echo(f"note: particles.fraction = {spec.fraction:g} of {spec.count} beads is "
                   f"{share:.3g} of a bead of the first radius; each species keeps at least one: "
                   f"{first} and {spec.count - first} (a share of {first / spec.count:.3g})",
                   err=True)

def _fmt(x: float | None, spec: str = ".3g") -> str:
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x, spec)


def _pm(mean: float | None, std: float | None) -> str:
    """``mean +- std``: the spread to two significant digits, the mean to the same decimal place
    (``196.50 +- 0.71``, not ``196 +- 0.707`` for 196.5); a zero spread leaves the mean at up
    to six significant digits."""
    if mean is None or std is None or not (math.isfinite(mean) and math.isfinite(std)):
        return f"{_fmt(mean)} +- {_fmt(std)}"
    if std == 0.0:
        return f"{mean:.6g} +- 0"
    places = 1 - math.floor(math.log10(abs(std)))  # decimals of the spread's second digit
    if places > 0:
        return f"{mean:.{places}f} +- {std:.{places}f}"
    if abs(mean) >= 1e5:  # large: in powers of ten, the mean's digits down to the spread's
        digits = math.floor(math.log10(abs(mean))) + places
        return f"{mean:.{max(digits, 0)}e} +- {std:.1e}"
    step = 10.0 ** -places
    return f"{round(mean / step) * step:.0f} +- {round(std / step) * step:.0f}"


def _lines(data: dict[str, Any]) -> list[str]:
    """The text report of a sorting ensemble."""
    import numpy as np  # kept out of the command line's start-up
    f = data["frequency_hz"]
    periods = data["periods"]
    seeds = data["seeds"]
    model = ("slow model in 2-D on the plate" if data["geometry"] == "plane"
             else "slow model of chains in lanes along the wave (1-D)")
    lines = [f"{data['count']} beads, {len(seeds)} placement(s) (seeds {seeds[0]}-{seeds[-1]}), "
             f"{model}, {periods[-1]:.3g} periods = "
             f"{periods[-1] / f:.3g} s of device time at {f:.4g} Hz; {data['wall_time_s']:.3g} s "
             f"(curves '{data['curve_source']}': {data['curve_wall_time_s']:.3g} s)"]
    for row in data["species"]:
        lines.append(f"  R = {row['radius_m'] * 1e3:.3g} mm ({row['count']}): free drift ratio "
                     f"{row['free_drift_ratio']:+.4f} ({row['free_speed_m_s'] * 1e6:+.3g} um/s); "
                     f"at the end {row['final_mean_drift_ratio']:+.4f} on average, "
                     f"{row['carried_against_own_drift']:.0%} carried against their own drift")
    lines.append("  segregation of positions, mean +- spread over the placements (0 random, 1 "
                 "sorted with each species on the side the wave drives it to; Lacey 1 only where "
                 "the interface falls between its bins):")
    lines.append(f"  {'periods':>10} {'seconds':>10} {'purity':>16} {'purity index':>16} "
                 f"{'Lacey':>16}")
    over = data["over_time"]
    wanted = [0] + [int(abs(np.log10(np.maximum(periods, 1e-300)) - d).argmin())
                    for d in range(0, int(np.log10(periods[-1])) + 1)] + [len(periods) - 1]
    for k in sorted(set(wanted)):
        cells = [f"{_fmt(over[m]['mean'][k], '.3f')} +- "
                 f"{_fmt(over[m]['std'][k] if over[m]['std'] else None, '.3f')}"
                 for m in ("purity", "purity_index", "lacey")]
        lines.append(f"  {periods[k]:>10.3g} {periods[k] / f:>10.3g} {cells[0]:>16} "
                     f"{cells[1]:>16} {cells[2]:>16}")
    hit = data["time_to_target"]
    target = data["target_purity"]
    if hit["reached"]:
        p, s = hit["periods"], hit["seconds"]
        lines.append(f"  time to purity {target:g}: {_pm(p['mean'], p['std'])} periods "
                     f"= {_pm(s['mean'], s['std'])} s (reached in {hit['reached']} "
                     f"of {hit['of']} placements)")
    else:
        fin = data["final"]["purity"]
        lines.append(f"  time to purity {target:g}: not reached within {periods[-1]:.3g} periods "
                     f"in any placement (purity at the end {_fmt(fin['mean'], '.3f')} +- "
                     f"{_fmt(fin['std'], '.3f')})")
    fin = data["final"]
    if data["geometry"] == "line":
        cost = (f"{_fmt(fin['merges']['mean'])} merges and {_fmt(fin['splits']['mean'])} splits "
                "per placement")
    else:
        cost = (f"{_fmt(fin['steps']['mean'])} steps per placement, largest overlap "
                f"{fin['largest_overlap_over_tolerance']:.2g} of the tolerance")
    lines.append(f"  final: {_pm(fin['chains']['mean'], fin['chains']['std'])} "
                 f"groups of touching beads (mean size {_fmt(fin['mean_chain_size'])}, largest "
                 f"{fin['largest_chain']}), {cost}")
    lines.extend(f"  WARNING: {w}" for w in data.get("warnings", ()))
    lines.append(f"  {data['validated']}")
    lines.append(f"  model: {data['assumed']}")
    if "check" in data:
        c = data["check"]
        lines.append(f"  check, placement seed {seeds[0]}, {c['periods']} periods: LAMMPS "
                     f"{c['lammps_wall_time_s']:.3g} s, slow model in lanes along the wave "
                     f"{c['model_wall_time_s']:.2g} s (over so few periods no bead gets round "
                     "another)")
        for row in c["species"]:
            lines.append(f"    R = {row['radius_m'] * 1e3:.3g} mm: mean drift ratio LAMMPS "
                         f"{_fmt(row['lammps_drift_ratio'], '+.4f')}, slow model "
                         f"{_fmt(row['model_drift_ratio'], '+.4f')}")
        lines.append(f"    purity LAMMPS {c['lammps_purity']:.3f}, slow model "
                     f"{c['model_purity']:.3f}; touching pairs (LAMMPS) "
                     f"{c['lammps_touching_pairs']:.3g}, chains (model) {c['model_chains']}")
        if c["periods"] < CHECK_PERIODS:
            lines.append(f"    note: over {c['periods']} periods LAMMPS's first impacts have not "
                         f"rung out (at {CHECK_PERIODS} they still show): its speeds are no "
                         f"steady drift to compare; --check {CHECK_PERIODS} or more")
    return lines


#: periods of LAMMPS below which --check compares a transient (--check 1 set -0.0085 against the
#: model's -0.3160 for the 1 mm beads without a word)
CHECK_PERIODS = 100

