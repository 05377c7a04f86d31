"""Sliding and removal thresholds of an adhesive particle: sawdrift threshold."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated, Any

import typer

from .._startup import fast_start
from .app import (
    Engine,
    Progress,
    _fail,
    _writable,
    app,
    check_engine,
    json_nulls,
    out_kind,
    write_outputs,
)
from .scene_options import scene_from_options, with_scene_options


@app.command("threshold")
@with_scene_options(exclude=("periods",))
def threshold_cmd(
    scene_arg: Annotated[Path, typer.Argument(help="device scene TOML with effects.adhesion")],
    axis: Annotated[str, typer.Option(
        "--axis", help="device field and values, FIELD=START:STOP:N (log-spaced, with units) or a "
        "comma list, e.g. 'device.particle.radius=1 um:50 um:15'")],
    start: Annotated[float, typer.Option("--start", help="first amplitude of the scan, in units "
                                         "of the rigid removal amplitude")] = 0.01,
    stop: Annotated[str, typer.Option("--stop", help="last amplitude of the scan (a threshold "
                                      "above it: '> STOP', above_stop, empty in the CSV)")] = "10 nm",
    per_decade: Annotated[int, typer.Option("--per-decade", help="scan points per decade, "
                                             "1 to 100")] = 4,
    bisections: Annotated[int, typer.Option("--bisections", help="halvings of each bracket")] = 8,
    periods: Annotated[float, typer.Option("--periods", help="wave periods of each run, at "
                                           "least 10: removed means thrown off and not back by "
                                           "its end")] = 200.0,
    engine: Engine = "compiled",
    progress: Progress = True,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    out: Annotated[Path | None, typer.Option(
        "-o", "--out", help="a folder: threshold.csv, threshold.parquet, threshold.json, "
        "threshold.png, scene.toml")] = None,
    *,
    scene_overrides: dict[str, Any],
) -> None:
    """The amplitude where sliding starts and the amplitude of removal, against a device field.

    For each value (a particle radius, typically) the wave's amplitude is raised on a geometric
    grid from --start times the rigid removal amplitude (F_pull + m g) / (m (2 pi f)^2) until the
    contact first slides as a whole (or loses contact), and until the run first ends 'ejected';
    each first crossing is then located by bisection. Fixed runs of --periods periods. The table
    is in SI; the figure is log-log with the fitted slopes. A threshold not located is shown as
    '< A' (crossed already at the scan's first amplitude A), '> STOP' (not up to --stop) or
    '> bound' (not up to the largest amplitude the device may have: its wave's strain or speed
    bound, or the largest A* the model integrates).
    """
    from ..report.threshold_plot import plot_thresholds
    from ..scene.device import to_si
    from ..scene.units import in_range
    from ..study.threshold import parse_device_axis, thresholds

    fast_start()
    check_engine(engine)
    _check_scan(start, per_decade, bisections, periods)
    try:
        stop_m = to_si(stop, "length")
        if stop_m > 0.0:  # a device amplitude's range, and the hint for a bare number in m
            in_range("amplitude", stop_m, "m", _bare_number(stop))
    except ValueError as exc:
        _fail(f"--stop = {stop!r} {exc}")
    if not stop_m > 0.0:
        _fail(f"--stop = {stop!r} must be a positive amplitude, e.g. '10 nm' (the scan's top)")
    if "device.amplitude" in scene_overrides:  # the scan's own variable: it was ignored
        _fail("--set device.amplitude: threshold scans the amplitude itself (--start, --stop); "
              "leave it out")
    if out is not None:
        out_kind(out, (), "")  # a folder: -o t.txt made a folder named t.txt
        _writable(out, folder=True)
    scene = scene_from_options(scene_arg, None, {}, scene_overrides)
    name, values = parse_device_axis(axis)
    study = thresholds(scene, name, values, start=start, stop=stop_m, per_decade=per_decade,
                       bisections=bisections, periods=periods, engine=engine, show=progress)
    # a threshold not located is NaN in the table, null in JSON (NaN is not JSON), with its
    # *_found saying where it lies ("> STOP", "< A", "> bound" in the text)
    data = json_nulls(study.to_json())
    if out is not None:
        write_outputs(out, "threshold", data, lambda path: plot_thresholds(study, path), scene)
        table = study.table()
        table.to_csv(out / "threshold.csv", index=False)
        table.to_parquet(out / "threshold.parquet")
    if as_json:
        typer.echo(json.dumps(data, indent=1))
        return
    _print_rows(study, name, stop.strip(), data)


def _bare_number(text: str) -> Any:
    """``text`` as a float where it is a bare number (in m, which the range's message then
    says), else as given: --stop 10 was read as 10 m and run."""
    try:
        return float(text)
    except ValueError:
        return text


#: the text of a threshold not located (ThresholdRow.*_found), and the note explaining it
_UNFOUND = {
    "below_start": "'< A': crossed already at the scan's first amplitude A (lower --start)",
    "above_stop": "'> STOP': no crossing up to --stop (raise --stop to find it)",
    "above_bound": ("'> bound': no crossing up to the largest amplitude the device may have "
                    "(its wave's surface strain or speed bound, or the largest A* = A / a0, "
                    "1e9, the model integrates)"),
}


def _print_rows(study, name: str, stop: str, data: dict) -> None:
    """The study as text: one row per value, the slopes, notes for thresholds not located and
    the scenes' warnings."""
    typer.echo(f"{name:>24}  {'slides at (m)':>14}  {'removed at (m)':>14}  {'rigid (m)':>11}")
    seen: set[str] = set()

    def amp(v: float, found: str, start: float) -> str:
        seen.add(found)
        text = {"found": f"{v:.4g}", "below_start": f"< {start:.4g}", "above_stop": f"> {stop}",
                "above_bound": "> bound"}[found]
        return f"{text:>14}"

    for r in study.rows:
        typer.echo(f"{r.value:>24.4g}  {amp(r.slide_amplitude_m, r.slide_found, r.scan_start_m)}"
                   f"  {amp(r.removal_amplitude_m, r.removal_found, r.scan_start_m)}  "
                   f"{r.rigid_removal_m:>11.4g}")
    for column, slope in data["slopes"].items():
        typer.echo(f"slope of log {column} against log {name.rsplit('.', 1)[-1]}: "
                   f"{_g(slope['all'])} (smallest {data['small_rows']} values: "
                   f"{_g(slope['small'])})")
    notes = [_UNFOUND[k] for k in _UNFOUND if k in seen]
    if notes:
        typer.echo("; ".join(notes) + "; 'n/a': a slope needs two thresholds")
    for r in study.rows:
        for warning in r.warnings:
            typer.echo(f"WARNING at {name} = {r.value:.4g}: {warning}")


def _check_scan(start: float, per_decade: int, bisections: int, periods: float) -> None:
    """One line naming the first scan option out of its range (exit status 2)."""
    if not 0.0 < start < 1e3:
        _fail(f"--start = {start:g} must be in (0, 1000) (units of the rigid removal amplitude)")
    if not 1 <= per_decade <= 100:
        _fail(f"--per-decade = {per_decade} must be in [1, 100]")
    if not 0 <= bisections <= 60:
        _fail(f"--bisections = {bisections} must be in [0, 60]")
    if not periods >= 10:
        _fail(f"--periods = {periods:g} must be >= 10")


def _g(value: float | None) -> str:
    """A slope, or 'n/a' where fewer than two thresholds were found."""
    return f"{value:.3g}" if value is not None else "n/a"
