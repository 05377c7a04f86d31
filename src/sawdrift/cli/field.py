"""The drift field of two waves: sawdrift field (traps, direct runs, sorting)."""

from __future__ import annotations

import json
from contextlib import nullcontext
from pathlib import Path
from typing import Annotated, Any

import typer

from .._startup import fast_start
from ..errors import SawdriftError
from ..study.progress import notice, run_progress
from .app import (
    Engine,
    Param,
    Progress,
    Workers,
    Yes,
    _fail,
    _parse_param,
    _split_axis,
    _writable,
    app,
    check_engine,
    interrupted,
    json_nulls,
    out_kind,
    write_outputs,
)
from .scene_options import axis_and_option, scene_from_options, typed_as, with_scene_options


@app.command("field")
@with_scene_options()
def field_cmd(
    scene_arg: Annotated[Path | None, typer.Argument(help="scene TOML (or the defaults)")] = None,
    model: Annotated[str | None, typer.Option("--model", help="contact model name")] = None,
    param: Param = None,
    points: Annotated[int, typer.Option("--points", help="positions over one period of the field "
                                        "(1/2 wavelength), at least 4")] = 32,
    refine: Annotated[int, typer.Option("--refine", help="regula-falsi runs per zero, 0 to 60")] = 2,
    axis: Annotated[str | None, typer.Option(
        "--axis", help="FIELD=a,b: one field per value of a particle field, overlaid (sorting), "
        "e.g. particle.m_star=0.05,0.5 or 'device.particle.radius=5 um,40 um'")] = None,
    direct: Annotated[bool, typer.Option(
        "--direct", help="also integrate the particle with the drive at its own position "
        "(needs --wavelength or a device wavelength); --periods is then its length")] = False,
    start: Annotated[float | None, typer.Option("--start", help="direct run: start position "
                                                "xi = X / wavelength (default 0)")] = None,
    workers: Workers = None,
    engine: Engine = "compiled",
    progress: Progress = True,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    out: Annotated[Path | None, typer.Option(
        "-o", "--out", help="a folder: field.json, field.png, scene.toml; or NAME.csv: the field "
        "only (species with --axis, position, drift_velocity, drift_velocity_se, with a device "
        "also drift_velocity_m_s and drift_velocity_se_m_s, regime, settled)")] = None,
    yes: Yes = False,
    *,
    scene_overrides: dict[str, Any],
) -> None:
    """The drift field of two counter-propagating waves: V(xi), its traps and repellers.

    Each of --points positions over one period (1/2 wavelength) is a full run of the local
    orbit there (settled with --settle); zeros with V' < 0 are traps. --backward S and
    --backward-phase PSI set the second wave. --direct runs the particle through the field from
    --start for --periods periods (a phase ramp with --backward-phase-rate moves the traps) and
    reports it beside the field's prediction.
    """
    from ..study.field import FieldInterrupted, drift_field
    from ..study.field_direct import direct_run

    fast_start()
    check_engine(engine)
    kind = (out_kind(out, (".csv",), "the field: position, drift velocity and its error, regime, settled")
            if out is not None else None)
    species = None
    if axis is not None:
        name, spec = _split_axis(axis, "FIELD=a,b", "particle.m_star=0.05,0.5")
        axis_and_option(name, spec, scene_overrides)
        from ..study.axes import parse_values

        species = (name, parse_values(spec, name))
    _check_start(start, direct, scene_overrides)
    start = 0.0 if start is None else start
    direct_periods = scene_overrides.pop("numerics.periods", None) if direct else None
    scene = scene_from_options(scene_arg, model, _parse_param(param), scene_overrides,
                               swept=(species[0],) if species is not None else ())
    if direct:
        from ..study.field import wavelength_star

        if wavelength_star(scene) is None:
            _fail("--direct needs the wavelength: --wavelength L* (wavelength / a0), or a device "
                  "with device.wavelength or device.substrate.density")
        if direct_periods is not None and not float(direct_periods) >= 1.0:
            _fail(f"--periods = {direct_periods!r}: a direct run needs at least 1 period")
    from ..study.estimate import cell_steps, size_check
    from ..study.field import MAX_REFINE, MIN_POINTS, ZEROS_PER_FIELD, species_scenes

    if points < MIN_POINTS or not 0 <= refine <= MAX_REFINE:  # the study's own one-line errors
        drift_field(scene, points, refine=refine, progress=False)

    sample = [sp for _, sp in species_scenes(scene, species)]
    # the refinement's runs, ZEROS_PER_FIELD zeros a species, counted in the size (--refine 20000
    # was estimated under 1 s and ran 26 s)
    extra = refine * ZEROS_PER_FIELD * sum(cell_steps(sp)[0] for sp in sample) / (
        points * len(sample))
    if direct:
        from ..study.field_direct import direct_scenes

        # checked before the field, and counted in its size (the estimate left it out)
        direct_periods = float(2000.0 if direct_periods is None else direct_periods)
        try:
            extra += direct_scenes(scene, start, direct_periods)[2] / (points * len(sample))
        except SawdriftError as exc:
            _fail(str(exc).replace("periods = ", "--periods = ", 1))
    size_check("field", sample, points * len(sample), workers=workers, engine=engine, yes=yes,
               show=progress, unit="point", smaller="fewer --points", extra_steps=extra)
    if out is not None:  # after every check: a refused command leaves no folder behind
        _writable(out, folder=kind == "folder")
    try:
        study = drift_field(scene, points, axis=species, refine=refine, workers=workers,
                            progress=progress, engine=engine)
    except FieldInterrupted as stopped:
        study = stopped.study  # what ended, shown and written, then exit 130
    if direct and study.interrupted is None:
        periods = float(direct_periods)
        with notice(f"field: direct run of {periods:g} periods through the field", 2.0, progress), \
                (run_progress("field: direct run") if progress else nullcontext()):
            study.direct = direct_run(scene, start, periods, study.fields[0], engine=engine)
    data = study.to_json()
    if kind == ".csv":
        _field_csv(study, out)
    elif out is not None:
        from ..report.field_plot import plot_field

        write_outputs(out, "field", data, lambda path: plot_field(study, path), scene)
    if as_json:
        typer.echo(json.dumps(json_nulls(data)))  # a failed or ejected position's V: null
        _end_if_interrupted(study, out, direct)
        return
    _print_fields(study, scene.numerics.settle is False)
    if kind == ".csv":
        typer.echo(f"wrote {out}")
    elif out is not None:
        typer.echo(f"wrote {out}/field.json, field.png, scene.toml")
    _end_if_interrupted(study, out, direct)


def _print_fields(study: Any, fixed: bool) -> None:
    """The text output of a drift field: per field its summary, traps and repellers, the
    positions ejected or not settled (``fixed``: a run of fixed length, hint --settle), run
    errors and warnings; then a direct run against the field's prediction."""
    for fld in study.fields:
        head = f"{fld.label}: " if fld.label else ""
        typer.echo(f"{head}{fld.summary}")
        for z in fld.zeros:
            typer.echo(f"  {z['kind']:>9} at xi = {z['position']:.5f} (+ k/2)")
        ejected = sum(r == "ejected" for r in fld.regimes)
        if 0 < ejected < len(fld.regimes):
            typer.echo(f"  {ejected} of {len(fld.regimes)} positions ejected: thrown off, no "
                       "drift speed there")
        loose = sum(1 for ok, r in zip(fld.settled, fld.regimes, strict=True)
                    if ok is False and r != "ejected")
        if loose:
            hint = (" (use --settle)" if fixed else
                    " (irregular motion: a long-time mean, or not settled within the period cap)")
            typer.echo(f"  {loose} of {len(fld.settled)} positions NOT settled: their drift is "
                       f"not a steady one{hint}")
        if fld.errors:
            typer.echo(f"  {len(fld.errors)} kinds of run errors, e.g. {fld.errors[0]}", err=True)
        for warning in fld.warnings:
            typer.echo(f"  WARNING: {warning}")
    if study.direct is not None:
        d = study.direct
        pred = d.get("predicted", {})
        where = pred.get("final_position", float("nan"))
        typer.echo(f"direct run from xi = {d['start']:g}, {d['periods']:g} periods: ends at xi = "
                   f"{d['final_position']:.5f}; the field predicts {where:.5f}"
                   + (f" (trap at {pred['trap']:.5f})" if pred.get("trap") is not None else ""))


def _check_start(start: float | None, direct: bool, scene_overrides: dict[str, Any]) -> None:
    """One line and exit status 2 for a --start without --direct or out of range, and for a
    --position (the field runs every position itself)."""
    if start is not None and not direct:  # it was ignored without a word
        _fail(f"--start {start:g} is the start of the direct run: add --direct (or drop --start)")
    if start is not None and not -1e6 <= start <= 1e6:  # it was reported as drive.position
        _fail(f"--start = {start!r}: the direct run's start, in wavelengths; allowed: -1e6 to 1e6")
    if "drive.position" in scene_overrides:  # it was ignored without a word
        given = typed_as(scene_overrides, "drive.position",
                         f"--position {scene_overrides['drive.position']!r}")
        _fail(f"{given}: the field runs every position over half a wavelength itself (a direct "
              "run starts at --start): drop it")


def _end_if_interrupted(study: Any, out: Path | None, direct: bool) -> None:
    """End a field Ctrl-C stopped (its fields of the positions that ended, printed and written)
    with one line and exit status 130; nothing for a field that ran to its end."""
    if study.interrupted is None:
        return
    done, total = study.interrupted
    kept = f"; written to {out}" if out is not None else ""
    left = " and no direct run" if direct else ""
    if done == total:
        interrupted(f"interrupted (Ctrl-C) while refining the zeros: the field printed has all "
                    f"{total} positions, its zeros as the sign changes place them{left}{kept}")
    interrupted(f"interrupted (Ctrl-C) after {done} of {total} positions: the field printed is "
                f"of those, no zeros located{left}{kept}")


def _field_csv(study: Any, out: Path) -> None:
    """The field(s) as CSV: (species,) position xi, drift velocity and its standard error (a
    long-time mean's; empty where the drift settled), a device's also in m/s, regime, settled."""
    import pandas as pd

    frames = []
    for fld in study.fields:
        se = fld.velocity_errors()
        frame = pd.DataFrame({"position": fld.positions, "drift_velocity": fld.drift_velocity,
                              "drift_velocity_se": se, "regime": fld.regimes,
                              "settled": fld.settled})
        scale = fld.speed_scale()
        if scale is not None:  # a device: the speeds in m/s too (the figure's, in mm/s)
            frame.insert(3, "drift_velocity_m_s", fld.drift_velocity * scale)
            frame.insert(4, "drift_velocity_se_m_s", se * scale)
        if study.axis is not None:
            frame.insert(0, "species", fld.label)
        frames.append(frame)
    pd.concat(frames, ignore_index=True).to_csv(out, index=False)
