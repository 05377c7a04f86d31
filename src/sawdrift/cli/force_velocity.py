"""Force-velocity curves: sawdrift force-velocity (the mean friction force against the speed)."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Annotated, Any

import typer

from .._startup import fast_start
from .app import Engine, Param, Yes, _fail, _parse_param, _writable, app, check_engine, write_outputs
from .scene_options import scene_from_options, with_scene_options


@app.command("force-velocity")
@with_scene_options()
def force_velocity_cmd(
    scene_arg: Annotated[Path | None, typer.Argument(help="scene TOML (a device scene is reported "
                                                     "in mN and m/s)")] = None,
    model: Annotated[str | None, typer.Option("--model", help="contact model name")] = None,
    param: Param = None,
    points: Annotated[int, typer.Option("--points", help="loads, evenly inside (-mu, mu) M g, "
                                        "at least 3 (the unloaded run is added)")] = 21,
    workers: Annotated[int | None, typer.Option("--workers", help="local processes (default: all "
                                                "cores)")] = None,
    engine: Engine = "compiled",
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    out: Annotated[Path | None, typer.Option(
        "-o", "--out", help="a folder: force_velocity.json, force_velocity.png, scene.toml")] = None,
    yes: Yes = False,
    *,
    scene_overrides: dict[str, Any],
) -> None:
    """The mean friction force against the steady drift speed it allows (force-velocity curve).

    Each point holds the particle under a constant tangential load L inside (-mu, mu) M g and
    reports its steady drift at full inertia: at that speed the period-averaged friction force
    equals L. The free drift is the curve's zero; a load curve is the same curve read the other
    way, the stall load its value at zero speed. Where the contact sticks, a range of loads holds
    the particle at rest (a vertical segment).
    """
    from ..report.force_velocity_plot import plot_force_velocity
    from ..study.force_velocity import force_velocity

    fast_start()
    check_engine(engine)
    if points < 3:
        _fail(f"--points = {points}: a force-velocity curve needs at least 3")
    if workers is not None and workers < 1:
        _fail(f"--workers = {workers}: give at least 1")
    scene = scene_from_options(scene_arg, model, _parse_param(param), scene_overrides)
    if scene.particle.load != 0.0:
        _fail(f"particle.load = {scene.particle.load:g}: force-velocity samples the loads itself "
              "(--points of them inside (-mu, mu) M g), so a given load would be ignored; the "
              "speed under one load is where the curve crosses it, or `sawdrift run --load`")
    from ..study.estimate import size_check

    size_check("force-velocity", [scene], points + 1, workers=workers, engine=engine, yes=yes,
               unit="steady run", smaller="fewer --points")
    if out is not None:  # after every check: a refused command leaves no folder behind
        _writable(out, folder=True)
    curve = force_velocity(scene, points=points, workers=workers, engine=engine)
    data = curve.to_json()
    if out is not None:
        write_outputs(out, "force_velocity", data, lambda path: plot_force_velocity(curve, path),
                      scene)
    if as_json:
        typer.echo(json.dumps(data))
        return
    dev = data.get("device")
    zero = curve.zero
    if dev is not None:
        speed = curve.device["speed_m_s"]  # type: ignore[index]
        typer.echo(f"free drift {curve.free_drift * speed:.4g} m/s; the curve crosses zero force "
                   f"at {zero * speed:.4g} m/s" if math.isfinite(zero) else "")
        rows = zip(dev["force_mN"], dev["speed_m_s"], data["regimes"], data["settled"], strict=True)
        typer.echo(f"{'force (mN)':>12} {'speed (m/s)':>12}  regime")
    else:
        typer.echo(f"free drift {curve.free_drift:.6g} a0 f"
                   + (f"; the curve crosses zero force at {zero:.6g} a0 f"
                      if math.isfinite(zero) else ""))
        rows = zip(data["force"], data["drift_velocity"], data["regimes"], data["settled"],
                   strict=True)
        typer.echo(f"{'<F> (M g)':>12} {'v (a0 f)':>12}  regime")
    for f, v, regime, settled in rows:
        v_text = f"{v:12.5g}" if v is not None else f"{'none':>12}"
        typer.echo(f"{f:12.5g} {v_text}  {regime}" + ("" if settled else " (not settled)"))
    if out is not None:
        typer.echo(f"wrote {out}/force_velocity.json, force_velocity.png, scene.toml")
