"""Sliding and removal thresholds of an adhesive particle: sawdrift threshold."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Annotated

import typer

from .._startup import fast_start
from .app import Engine, _fail, _writable, app, check_engine, write_outputs


@app.command("threshold")
def threshold_cmd(
    scene_arg: Annotated[Path, typer.Argument(help="device scene TOML with effects.adhesion")],
    axis: Annotated[str, typer.Option(
        "--axis", help="device field and values, FIELD=START:STOP:N (log-spaced, with units) or a "
        "comma list, e.g. 'device.particle.radius=1 um:50 um:15'")],
    start: Annotated[float, typer.Option("--start", help="first amplitude of the scan, in units "
                                         "of the rigid removal amplitude")] = 0.01,
    stop: Annotated[str, typer.Option("--stop", help="last amplitude of the scan (a threshold "
                                      "above it is NaN)")] = "10 nm",
    per_decade: Annotated[int, typer.Option("--per-decade", help="scan points per decade")] = 4,
    bisections: Annotated[int, typer.Option("--bisections", help="halvings of each bracket")] = 8,
    periods: Annotated[float, typer.Option("--periods", help="wave periods of each run: removed "
                                           "means thrown off and not back by its end")] = 200.0,
    engine: Engine = "compiled",
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    out: Annotated[Path | None, typer.Option(
        "-o", "--out", help="a folder: threshold.csv, threshold.parquet, threshold.json, "
        "threshold.png, scene.toml")] = None,
) -> None:
    """The amplitude where sliding starts and the amplitude of removal, against a device field.

    For each value (a particle radius, typically) the wave's amplitude is raised on a geometric
    grid from --start times the rigid removal amplitude (F_pull + m g) / (m (2 pi f)^2) until the
    contact first slides as a whole (or loses contact), and until the run first ends 'ejected';
    each first crossing is then located by bisection. Fixed runs of --periods periods. The table
    is in SI; the figure is log-log with the fitted slopes.
    """
    from ..report.threshold_plot import plot_thresholds
    from ..scene.device import to_si
    from ..scene.schema import Scene
    from ..study.threshold import parse_device_axis, thresholds

    fast_start()
    check_engine(engine)
    _check_scan(start, per_decade, bisections, periods)
    try:
        stop_m = to_si(stop, "length")
    except ValueError as exc:
        _fail(f"--stop = {stop!r} {exc}")
    if not stop_m > 0.0:
        _fail(f"--stop = {stop!r} must be a positive amplitude, e.g. '10 nm' (the scan's top)")
    if out is not None:
        _writable(out, folder=True)
    scene = Scene.from_toml(scene_arg)
    name, values = parse_device_axis(axis)
    study = thresholds(scene, name, values, start=start, stop=stop_m, per_decade=per_decade,
                       bisections=bisections, periods=periods, engine=engine)
    # a threshold above --stop is NaN in the table, null in JSON (NaN is not JSON), "> stop" in text
    data = _nulls(study.to_json())
    if out is not None:
        write_outputs(out, "threshold", data, lambda path: plot_thresholds(study, path), scene)
        table = study.table()
        table.to_csv(out / "threshold.csv", index=False)
        table.to_parquet(out / "threshold.parquet")
    if as_json:
        typer.echo(json.dumps(data, indent=1))
        return
    typer.echo(f"{name:>24}  {'slides at (m)':>14}  {'removed at (m)':>14}  {'rigid (m)':>11}")
    above = f"> {stop.strip()}"

    def amp(v: float) -> str:
        return f"{v:>14.4g}" if math.isfinite(v) else f"{above:>14}"

    for r in study.rows:
        typer.echo(f"{r.value:>24.4g}  {amp(r.slide_amplitude_m)}  "
                   f"{amp(r.removal_amplitude_m)}  {r.rigid_removal_m:>11.4g}")
    for column, slope in data["slopes"].items():
        typer.echo(f"slope of log {column} against log {name.rsplit('.', 1)[-1]}: "
                   f"{_g(slope['all'])} (smallest {data['small_rows']} values: "
                   f"{_g(slope['small'])})")
    if any(not math.isfinite(v) for r in study.rows
           for v in (r.slide_amplitude_m, r.removal_amplitude_m)):
        typer.echo(f"'{above}': no crossing up to --stop {stop.strip()} (raise --stop to find it);"
                   " 'n/a': a slope needs two thresholds")


def _check_scan(start: float, per_decade: int, bisections: int, periods: float) -> None:
    """One line naming the first scan option out of its range (exit status 2)."""
    if not 0.0 < start < 1e3:
        _fail(f"--start = {start:g} must be in (0, 1000) (units of the rigid removal amplitude)")
    if per_decade < 1:
        _fail(f"--per-decade = {per_decade} must be >= 1")
    if not 0 <= bisections <= 60:
        _fail(f"--bisections = {bisections} must be in [0, 60]")
    if not periods >= 10:
        _fail(f"--periods = {periods:g} must be >= 10")


def _g(value: float | None) -> str:
    """A slope, or 'n/a' where fewer than two thresholds were found."""
    return f"{value:.3g}" if value is not None else "n/a"


def _nulls(data):
    """``data`` with every NaN float replaced by None (JSON null)."""
    if isinstance(data, dict):
        return {k: _nulls(v) for k, v in data.items()}
    if isinstance(data, list):
        return [_nulls(v) for v in data]
    if isinstance(data, float) and not math.isfinite(data):
        return None
    return data
