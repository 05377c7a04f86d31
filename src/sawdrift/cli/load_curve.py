"""Load curves: sawdrift load-curve (drift speed and output power against a load, the stall)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated, Any

import typer

from .._startup import fast_start
from ..study.progress import counter
from .app import (
    Engine,
    Param,
    Progress,
    Yes,
    _fail,
    _parse_param,
    _split_axis,
    _writable,
    app,
    check_engine,
    out_kind,
    write_outputs,
)
from .interrupts import interrupted_curve
from .run_text import curve_warning_lines, pm_text
from .scene_options import refuse_given_load, scene_from_options, with_scene_options


@app.command("load-curve")
@with_scene_options()
def load_curve_cmd(
    scene_arg: Annotated[Path | None, typer.Argument(help="scene TOML (a device scene is reported "
                                                     "in mN, m/s and mW)")] = None,
    model: Annotated[str | None, typer.Option("--model", help="contact model name")] = None,
    param: Param = None,
    loads: Annotated[int, typer.Option("--loads", help="points of the curve, evenly from 0 to the "
                                       "stall load, at least 2")] = 16,
    workers: Annotated[int | None, typer.Option("--workers", help="local processes (default: all "
                                                "cores)")] = None,
    engine: Engine = "compiled",
    progress: Progress = True,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    out: Annotated[Path | None, typer.Option(
        "-o", "--out", help="a folder: load_curve.json, load_curve.png, scene.toml; or NAME.csv: "
        "the curve only (species with --axis, load, drift_velocity, drift_velocity_se, power, regime, "
        "settled; a device's in load_mN, speed_m_s, speed_se_m_s, power_mW)")] = None,
    axis: Annotated[str | None, typer.Option(
        "--axis", help="FIELD=a,b: one curve per value of a particle field, overlaid (sorting), "
        "e.g. particle.m_star=0.05,0.5 or 'device.particle.radius=0.2 mm,1 mm'")] = None,
    yes: Yes = False,
    *,
    scene_overrides: dict[str, Any],
) -> None:
    """Drift speed and output power against a tangential load, up to the stall load.

    The load opposes the unloaded drift (a motor's thrust, or what a conveyor can lift); the stall
    load, where the particle no longer advances, is bracketed and narrowed by k-section (one run
    per worker per round) to 1e-3 of mu M g, then --loads loads from 0 to it are run, each
    settled as a default run is (--settle forces it). A scene given a load of its own
    (particle.load, device.load) is refused; a device's incline stays. Device scenes are
    reported in mN, m/s and mW.
    """
    from ..dynamics.steady import refuse_free_spin
    from ..report.load_curve_plot import plot_load_curve
    from ..study.load_curve import CurveInterrupted, load_curve

    fast_start()
    check_engine(engine)
    if loads < 2:
        _fail(f"--loads = {loads}: a load curve needs at least 2 loads")
    if workers is not None and workers < 1:
        _fail(f"--workers = {workers}: give at least 1")
    name = axis.partition("=")[0].strip() if axis is not None else None
    if name in ("particle.load", "device.load"):  # two identical curves, without a word
        _fail(f"--axis {name}: load-curve runs its own loads, from 0 to the stall load; "
              "sweep another field (e.g. particle.m_star=0.05,0.5)")
    what = "the curve: load, drift velocity and its error, power, regime, settled"
    kind = out_kind(out, (".csv",), what) if out is not None else None
    if out is not None:
        _writable(out, folder=kind == "folder")
    swept = (name,) if name is not None else ()
    scene = scene_from_options(scene_arg, model, _parse_param(param), scene_overrides,
                               swept=swept)
    refuse_given_load(scene, "load-curve", "runs its own loads, from 0 to the stall load")
    refuse_free_spin(scene, "load curve")  # before the estimate's calibration
    species = 1
    if axis is not None:
        from ..study.axes import parse_values

        name, spec = _split_axis(axis, "FIELD=a,b", "particle.m_star=0.05,0.5")
        species = len(parse_values(spec, name))
    _size(scene, axis, loads, workers, engine, yes, progress)
    bar = counter(species * _stages(workers), "load-curve", "stage", enabled=progress)
    note = _noter(bar)
    if axis is not None:
        with bar:
            _species_curves(scene, axis, loads, workers, engine, note, as_json, out)
        return
    try:
        with bar:
            curve = load_curve(scene, loads=loads, workers=workers, engine=engine, progress=note)
    except CurveInterrupted as stop:
        interrupted_curve(stop, out, "load-curve")
    data = curve.to_json()
    if kind == ".csv":
        _curve_csv([("", data)], out)
    elif out is not None:
        write_outputs(out, "load_curve", data, lambda path: plot_load_curve(curve, path), scene)
    if as_json:
        typer.echo(json.dumps(data))
        return
    _print_curve(data, scene)
    _wrote(out)


def _free_line(data: dict[str, Any]) -> str | None:
    """The one line that replaces the curve where the unloaded run gives nothing to load against
    (``free_state`` no_drift, zero_within_error, no_steady_state), else None."""
    regime, state = data["regimes"][0], data["free_state"]
    if state == "no_drift":
        return f"no drift without load ({regime}), so nothing to stall"
    if state == "no_steady_state":
        return f"no steady drift without load ({regime}), so no load curve"
    if state == "zero_within_error":
        dev = data.get("device")
        free = (pm_text(dev["free_speed_m_s"], dev["free_speed_se_m_s"], ".4g") + " m/s"
                if dev is not None else
                pm_text(data["free_drift_velocity"], data["free_drift_velocity_se"], ".6g") + " a0 f")
        return (f"drift without load {free} ({regime}, a long-time mean) is "
                "zero within 3 standard errors: no direction to load against, so no stall load "
                "or power; a longer --mean-periods narrows the error")
    return None


def _print_curve(data: dict[str, Any], scene: Any) -> None:
    """The load curve as text: the free drift (+- its error), the stall, the loads; a caveat
    where the free drift did not settle, and the hint that can help unsettled loads."""
    line = _free_line(data)
    if line is not None:
        typer.echo(line)
        return
    dev = data.get("device")
    if dev is not None:
        typer.echo(f"drift to {data['direction']} without load: "
                   f"{pm_text(dev['free_speed_m_s'], dev['free_speed_se_m_s'], '.4g')} m/s")
        typer.echo(f"stall thrust {pm_text(dev['stall_load_mN'], dev['stall_load_se_mN'], '.4g')} mN "
                   f"(of a normal load "
                   f"{dev['normal_load_mN']:.4g} mN), largest power {dev['max_power_mW']:.4g} mW "
                   f"at {dev['load_at_max_power_mN']:.4g} mN, start-up acceleration "
                   f"{dev['start_acceleration_g']:.3g} g")
        rows = zip(dev["loads_mN"], dev["speed_m_s"], dev["speed_se_m_s"], dev["power_mW"],
                   data["regimes"], data["settled"], strict=True)
        typer.echo(f"{'load (mN)':>12} {'speed (m/s)':>22} {'power (mW)':>12}  regime")
    else:
        typer.echo(f"drift to {data['direction']} without load: "
                   f"{pm_text(data['drift_velocity'][0], data['drift_velocity_se'][0], '.6g')} a0 f")
        typer.echo(f"stall load {pm_text(data['stall_load'], data['stall_load_se'], '.6g')} M g, "
                   "largest power "
                   f"{data['max_power']:.6g} M g a0 f at {data['load_at_max_power']:.6g} M g")
        rows = zip(data["loads"], data["drift_velocity"], data["drift_velocity_se"], data["power"],
                   data["regimes"], data["settled"], strict=True)
        typer.echo(f"{'load (M g)':>12} {'v (a0 f)':>22} {'F v':>12}  regime")
    for f, v, se, p, regime, settled in rows:
        typer.echo(f"{f:12.5g} {pm_text(v, se, '.5g'):>22} {p:12.5g}  {regime}"
                   + ("" if settled else " (not settled)"))
    _notes(data, scene)


def _notes(data: dict[str, Any], scene: Any) -> None:
    """Caveats on stderr: an unsettled free drift, unsettled loads (with the hint that can help
    them: --settle for a run that stopped early, not for a long-time mean), warnings."""
    if data["stall_load_se"] is not None:
        typer.echo("note: the speed at the stall is a long-time mean; the stall load's error is "
                   "that speed's error over the curve's mean slope", err=True)
    if data["free_state"] == "not_settled":
        typer.echo("caveat: the drift without load did not settle, so the stall load and power "
                   "above are those of unsettled runs", err=True)
    means = [not s and se is not None for s, se in zip(data["settled"], data["drift_velocity_se"],
                                                          strict=True)]
    early = [not s and se is None for s, se in zip(data["settled"], data["drift_velocity_se"],
                                                      strict=True)]
    if any(means):
        typer.echo(f"note: {sum(means)} loads are long-time means of irregular motion (+- their "
                   "standard error), with no steady drift to settle to; a longer --mean-periods "
                   "narrows their errors", err=True)
    if any(early):
        hint = ("raise numerics.max_periods" if scene.numerics.settle
                else "use --settle or raise numerics.max_periods")
        typer.echo(f"note: {sum(early)} loads did not settle; {hint}", err=True)
    for line in curve_warning_lines(data["warnings"], "loads", "--json, load_curve.json"):
        typer.echo(line, err=True)


def _wrote(out: Path | None) -> None:
    if out is not None and out.suffix.lower() == ".csv" and not out.is_dir():
        typer.echo(f"wrote {out}")
    elif out is not None:
        typer.echo(f"wrote {out}/load_curve.json, load_curve.png, scene.toml")


def _curve_csv(curves: list[tuple[str, dict[str, Any]]], out: Path) -> None:
    """Load curve(s) as CSV: (species,) load, drift velocity and its standard error (empty where
    the drift settled), power, regime, settled.

    Normalized units (M g, a0 f, M g a0 f), or a device's mN, m/s, mW (columns named so).
    """
    import pandas as pd

    frames = []
    for label, d in curves:
        dev = d.get("device")
        if dev is not None:
            cols = {"load_mN": dev["loads_mN"], "speed_m_s": dev["speed_m_s"],
                    "speed_se_m_s": dev["speed_se_m_s"], "power_mW": dev["power_mW"]}
        else:
            cols = {"load": d["loads"], "drift_velocity": d["drift_velocity"],
                    "drift_velocity_se": d["drift_velocity_se"], "power": d["power"]}
        frame = pd.DataFrame({**cols, "regime": d["regimes"], "settled": d["settled"]})
        if len(curves) > 1:
            frame.insert(0, "species", label)
        frames.append(frame)
    pd.concat(frames, ignore_index=True).to_csv(out, index=False)


def _stages(workers: int | None, tolerance: float = 1e-3) -> int:
    """Stages of one load curve: the unloaded run, the rounds narrowing the stall bracket (each
    divides it by workers + 1, down to ``tolerance``, study.load_curve's default) and the curve."""
    import math
    import os

    k = max(1, workers if workers is not None else (os.cpu_count() or 1)) + 1
    return 2 + math.ceil(math.log(1.0 / tolerance) / math.log(k) - 1e-9)


def _size(scene: Any, axis: str | None, loads: int, workers: int | None, engine: str, yes: bool,
          show: bool) -> None:
    """A load curve's size: per species the unloaded run, the stall rounds (one run per worker
    each) and the curve's loads."""
    import os

    from ..study.estimate import size_check
    from ..study.field import species_scenes

    sample = [scene]
    if axis is not None:
        from ..study.axes import parse_values

        name, spec = _split_axis(axis, "FIELD=a,b", "particle.m_star=0.05,0.5")
        sample = [sp for _, sp in species_scenes(scene, (name, parse_values(spec, name)))]
    k = max(1, workers if workers is not None else (os.cpu_count() or 1))
    runs = 1 + (_stages(workers) - 2) * k + loads
    size_check("load-curve", sample, runs * len(sample), workers=workers, engine=engine, yes=yes,
               show=show, unit="run", smaller="fewer --loads")


def _noter(bar: Any) -> Any:
    """A ``progress`` callback of :func:`load_curve`: each stage's line advances ``bar``."""

    def note(line: str) -> None:
        bar.set_postfix_str(line)
        bar.update(1)

    return note


def _species_curves(scene: Any, axis: str, loads: int, workers: int | None, engine: str, note: Any,
                    as_json: bool, out: Path | None) -> None:
    """One load curve per value of ``axis`` (``FIELD=a,b``), overlaid: which way each species
    goes without load and where it stalls."""
    from ..report.load_curve_plot import plot_load_curves
    from ..study.axes import parse_values
    from ..study.field import species_scenes
    from ..study.load_curve import CurveInterrupted, load_curve

    name, spec = _split_axis(axis, "FIELD=a,b", "particle.m_star=0.05,0.5")
    curves = []
    for label, sp in species_scenes(scene, (name, parse_values(spec, name))):
        try:
            curves.append((label, load_curve(sp, loads=loads, workers=workers, engine=engine,
                                             progress=note)))
        except CurveInterrupted as stop:  # the curves that ended go with the runs that did
            done = {"axis": name, "interrupted_species": label,
                    "species": [{"label": lb, **c.to_json()} for lb, c in curves]}
            interrupted_curve(stop, out, "load-curve", done)
    data = {"axis": name, "species": [{"label": label, **c.to_json()} for label, c in curves]}
    if out is not None and out.suffix.lower() == ".csv" and not out.is_dir():
        _curve_csv([(label, c.to_json()) for label, c in curves], out)
    elif out is not None:
        write_outputs(out, "load_curve", data, lambda path: plot_load_curves(curves, path), scene)
    if as_json:
        typer.echo(json.dumps(data))
        return
    for label, curve in curves:
        d = curve.to_json()
        line = _free_line(d)
        if line is not None:
            typer.echo(f"{label}: {line}")
            continue
        dev = d.get("device")
        stall = (f"{dev['stall_load_mN']:.4g} mN" if dev is not None
                 else f"{d['stall_load']:.4g} M g")
        free = (pm_text(dev["free_speed_m_s"], dev["free_speed_se_m_s"], ".4g") + " m/s"
                if dev is not None else pm_text(d["drift_velocity"][0], d["drift_velocity_se"][0], ".4g")
                + " a0 f")
        caveat = " (the drift without load did not settle)" if d["free_state"] == "not_settled" else ""
        typer.echo(f"{label}: drifts to {d['direction']} at {free} without load, stalls at "
                   f"{stall}{caveat}")
    _wrote(out)
