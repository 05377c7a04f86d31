"""Force-velocity curves: sawdrift force-velocity (the mean friction force against the speed)."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Annotated, Any

import typer

from .._startup import fast_start
from .app import (
    Engine,
    Param,
    Progress,
    Yes,
    _fail,
    _parse_param,
    _writable,
    app,
    check_engine,
    new_folders,
    out_kind,
    remove_new,
    write_outputs,
)
from .interrupts import interrupted_curve
from .run_text import curve_warning_lines, pm_text
from .scene_options import refuse_given_load, scene_from_options, with_scene_options


@app.command("force-velocity")
@with_scene_options()
def force_velocity_cmd(
    scene_arg: Annotated[Path | None, typer.Argument(help="scene TOML (a device scene is reported "
                                                     "in mN and m/s)")] = None,
    model: Annotated[str | None, typer.Option("--model", help="contact model name")] = None,
    param: Param = None,
    points: Annotated[int, typer.Option("--points", help="loads, evenly inside (-mu, mu) M g (a "
                                        "sphere free to turn: (-mu_r, mu_r)), at least 3 (the "
                                        "unloaded run is added)")] = 21,
    workers: Annotated[int | None, typer.Option("--workers", help="local processes (default: all "
                                                "cores)")] = None,
    engine: Engine = "compiled",
    progress: Progress = True,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    out: Annotated[Path | None, typer.Option(
        "-o", "--out", help="a folder: force_velocity.json, force_velocity.png, scene.toml")] = None,
    yes: Yes = False,
    *,
    scene_overrides: dict[str, Any],
) -> None:
    """The mean friction force against the steady drift speed it allows (force-velocity curve).

    Each point holds the particle under a constant tangential load L inside (-mu, mu) M g
    (mu (1 + 2 F*_pull) with adhesion) and reports its steady drift at full inertia: at that
    speed the period-averaged friction balances it, mu <T*> = L (the friction force on the
    particle is -L). The free drift is the curve's zero; a load curve is the same curve read the
    other way, the stall load its value at zero speed. Where the contact sticks, a range of loads
    holds the particle at rest (a vertical segment).
    """
    from ..report.force_velocity_plot import plot_force_velocity
    from ..study.force_velocity import force_velocity
    from ..study.load_curve import CurveInterrupted

    fast_start()
    check_engine(engine)
    if points < 3:
        _fail(f"--points = {points}: a force-velocity curve needs at least 3")
    if workers is not None and workers < 1:
        _fail(f"--workers = {workers}: give at least 1")
    scene = scene_from_options(scene_arg, model, _parse_param(param), scene_overrides)
    refuse_given_load(scene, "force-velocity", "samples the loads itself (--points of them "
                      "inside (-mu, mu) M g, mu (1 + 2 F*_pull) with adhesion)")
    from ..study.estimate import size_check

    created = _prepare_out(out)  # before the calibration and the runs, as sweep does
    try:
        size_check("force-velocity", [scene], points + 1, workers=workers, engine=engine,
                   yes=yes, show=progress, unit="steady run", smaller="fewer --points")
    except BaseException:
        remove_new(created)  # a refused command leaves no folder behind
        raise
    try:
        curve = force_velocity(scene, points=points, workers=workers, engine=engine)
    except CurveInterrupted as stop:
        interrupted_curve(stop, out, "force-velocity")
    data = curve.to_json()
    if out is not None:
        write_outputs(out, "force_velocity", data, lambda path: plot_force_velocity(curve, path),
                      scene)
    if as_json:
        typer.echo(json.dumps(data))
        return
    _print_curve(curve, data)
    if out is not None:
        typer.echo(f"wrote {out}/force_velocity.json, force_velocity.png, scene.toml")


def _prepare_out(out: Path | None) -> list[Path]:
    """Check before any work that ``out`` is a folder that can be written (one line, exit 2 if
    not: a name with a file suffix is refused, since the command writes a folder); return the
    folders this check created, for removal if the command is refused later."""
    if out is None:
        return []
    out_kind(out, (), "")  # NAME.csv, NAME.png, ...: this command writes a folder only
    created = new_folders(out)
    _writable(out, folder=True)
    return created


def _print_curve(curve: Any, data: dict[str, Any]) -> None:
    """The curve as text: the free drift (with its error), then force, speed +- error, regime."""
    dev = data.get("device")
    zero = curve.zero
    scale, unit = (curve.device["speed_m_s"], "m/s") if dev is not None else (1.0, "a0 f")
    free = pm_text(curve.free_drift * scale, curve.free_drift_se * scale)
    line = f"free drift {free} {unit}"
    if not math.isfinite(curve.free_drift):
        line += " (no steady drift without load)"
    elif not curve.free_drift_resolved:
        line += " (a long-time mean: zero within 3 standard errors)"
    if math.isfinite(zero):
        line += f"; the curve crosses zero force at {zero * scale:.4g} {unit}"
    typer.echo(line)
    if dev is not None:
        forces, speeds, errors = dev["force_mN"], dev["speed_m_s"], dev["speed_se_m_s"]
        typer.echo(f"{'load L (mN)':>12} {'speed (m/s)':>22}  regime")
    else:
        forces, speeds, errors = data["force"], data["drift_velocity"], data["drift_velocity_se"]
        typer.echo(f"{'load L (M g)':>12} {'v (a0 f)':>22}  regime")
    rows = zip(forces, speeds, errors, data["regimes"], data["settled"], strict=True)
    for f, v, se, regime, settled in rows:
        typer.echo(f"{f:12.5g} {pm_text(v, se, '.5g'):>22}  {regime}" + ("" if settled else " (not settled)"))
    for line in curve_warning_lines(data["warnings"], "points", "--json, force_velocity.json"):
        typer.echo(line, err=True)
