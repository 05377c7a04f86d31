"""Studies over many scenes: sweep (uniform or adaptive) and bifurcation diagrams."""

from __future__ import annotations

import json
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Annotated, Any

import typer

import sawdrift as sd

from .._startup import fast_start
from .app import (
    Engine,
    Param,
    Progress,
    Scheduler,
    Workers,
    Yes,
    _fail,
    _parse_param,
    _split_axis,
    _writable,
    app,
    interrupted,
    model_names,
    out_kind,
)
from .scene_options import (
    axis_and_option,
    refuse_unread_cap,
    scene_from_options,
    with_scene_options,
)

#: the help of --m-star and --amplitude
AXIS_HELP = "START:STOP:N (N >= 2 log-spaced values, both ends included) or a,b,c; shorthand for an axis"


@app.command("sweep")
@with_scene_options(exclude=("m-star", "amplitude"))
def sweep_cmd(
    out: Annotated[Path, typer.Option("-o", "--out", help="Parquet table (resumed if it exists)")],
    scene_arg: Annotated[Path | None, typer.Argument(help="base scene TOML (or use --scene)")] = None,
    model: Annotated[str | None, typer.Option("--model", help="model name(s), comma-separated")] = None,
    m_star: Annotated[
        str | None, typer.Option("--m-star", help=AXIS_HELP)
    ] = None,
    amplitude: Annotated[
        str | None, typer.Option("--amplitude", help=AXIS_HELP)
    ] = None,
    axis: Annotated[
        list[str] | None,
        typer.Option("--axis", help="FIELD=SPEC, repeatable: a dotted scene field (material.mu, "
                     "device.amplitude, effects.rotation) and a,b,c | START:STOP:N (log) | "
                     "log:START:STOP:N | lin:START:STOP:N; device values may carry units "
                     "('5 nm,10 nm', '2 MHz:30 MHz:15', units on both ends)"),
    ] = None,
    adaptive: Annotated[
        bool, typer.Option("--adaptive", help="refine only where neighbouring cells disagree in regime "
                           "(m*, A* ranges from --m-star/--amplitude START:STOP:BASE)")
    ] = False,
    budget: Annotated[int | None, typer.Option("--budget", help="adaptive: most cells computed "
                                               "[default: 2000]")] = None,
    levels: Annotated[int | None, typer.Option("--levels", help="adaptive: halvings of a boundary "
                                               "cell [default: 3]")] = None,
    scene_file: Annotated[Path | None, typer.Option("--scene", help="base scene TOML")] = None,
    param: Param = None,
    workers: Workers = None,
    scheduler: Scheduler = None,
    progress: Progress = True,
    engine: Engine = "compiled",
    force: Annotated[
        bool, typer.Option("--force", help="resume a table written by other code or from another "
                           "base scene (rows of both kinds are then mixed)")
    ] = False,
    traces: Annotated[
        bool, typer.Option("--traces", help="also store each cell's last periods (TABLE.traces.parquet) "
                           "for the click panel of `sawdrift explore`")
    ] = False,
    yes: Yes = False,
    *,
    scene_overrides: dict[str, Any],
) -> None:
    """Run a grid (models x axes) into a resumable Parquet table.

    A sweep over one field (e.g. --axis "device.amplitude=10 nm,20 nm,30 nm") also prints its
    points (a device's speed in m/s) and draws them as a line plot beside the table (TABLE.png).

    The grid is the (m*, A*) plane, by default m* in [1e-3, 1e2] and A* in [1e-2, 10] with 11
    log-spaced values each, times every --axis; an axis over particle.m_star or drive.amplitude
    replaces that default. A device scene has no default plane: give its axes (device.*).
    Every other scene field is an option (--mu, --periods, --settle, ...) setting the base scene.
    Exit status 1 if a cell failed (after the table is written: each reason is in its 'error'
    column).
    """
    if scene_arg is not None and scene_file is not None:
        _fail("give the base scene either as an argument or with --scene, not both")
    if out.is_dir() or out.suffix.lower() != ".parquet":  # a name without one ('afile', 'x.pq')
        _fail(f"-o {str(out)!r}: a sweep writes a resumable Parquet table; give NAME.parquet "
              "(`sawdrift export` writes netCDF; pandas.read_parquet reads it for CSV)")
    _writable(out, folder=False)
    scene_file = scene_arg or scene_file
    axes: dict[str, str] = {}
    for item in axis or []:
        field, spec = _split_axis(item, "FIELD=SPEC", "material.mu=0.05,0.1,0.2")
        if field in axes:  # the first was dropped without a word
            _fail(f"--axis {field} is given twice ({axes[field]} and {spec}); give its values "
                  f"in one --axis {field}=a,b,c")
        given = {"particle.m_star": m_star, "drive.amplitude": amplitude}.get(field)
        if given is not None:
            _fail(f"--axis {field}={spec} and --{'m-star' if 'm_star' in field else 'amplitude'} "
                  f"{given} both sweep {field}; give one of them")
        axis_and_option(field, spec, scene_overrides)
        axes[field] = spec
    if not adaptive and (budget is not None or levels is not None):
        _fail(f"{'--budget' if budget is not None else '--levels'} belongs to --adaptive (a grid "
              "sweep computes every cell of its axes); add --adaptive or leave it out")
    named = model_names(model)
    if len(set(named)) != len(named):
        _fail(f"--model {model}: a model is named twice")

    fast_start()
    for name in named:
        sd.get_model(name)
    base = scene_from_options(scene_file, named[0] if named else None, _parse_param(param),
                              scene_overrides, swept=tuple(axes))
    refuse_unread_cap(base, scene_overrides, tuple(axes))  # its cells are sd.run's
    models = named or [base.model]
    with _resume_hint(out):
        if adaptive:
            if axes or len(models) != 1:
                _fail("--adaptive works on the (m*, A*) plane of one model: no --axis, one --model")
            frame = _adaptive(models[0], base, m_star, amplitude, out,
                              budget=2000 if budget is None else budget,
                              levels=3 if levels is None else levels,
                              workers=workers, scheduler=scheduler, progress=progress,
                              engine=engine, force=force, traces=traces, yes=yes)
        else:
            if (base.device is not None and not axes and len(models) == 1 and m_star is None
                    and amplitude is None):  # (those get the derived field's own line)
                # its help says so; a one-cell table was written without a word
                _fail("a device scene has no default plane to sweep: give its axes, e.g. "
                      "--axis \"device.amplitude=5 nm,10 nm\" (or run it: sawdrift run)")
            if base.device is None:
                # the (m*, A*) plane unless an axis replaces it: --axis effects.rotation=false,true
                # alone sweeps rotation over the whole default plane, not over one cell
                if m_star is None and "particle.m_star" not in axes:
                    m_star = "1e-3:1e2:11"
                if amplitude is None and "drive.amplitude" not in axes:
                    amplitude = "1e-2:10:11"
            frame = sd.sweep(models, m_star, amplitude, axes=axes, base=base, table=out,
                             workers=workers, scheduler=scheduler, progress=progress,
                             engine=engine, force=force, traces=traces, size=True, yes=yes)
        # inside: a Ctrl-C while the summary prints (the table written) exited 130 in silence
        _sweep_text(frame, out, adaptive)
    failed_cells(int(frame["error"].notna().sum()), len(frame), "cells", str(out))


def failed_cells(failed: int, total: int, what: str, table: str) -> None:
    """Exit status 1 after a study whose results are all saved but ``failed`` of its ``total``
    cells (or values) failed: one line on stderr saying how many and where their reasons are
    (the ``error`` column of ``table``). A sweep or bifurcation with failed cells exited 0, as
    if every cell had run; the input was valid (not 2) and nothing is lost."""
    if failed:
        typer.echo(f"failed: {failed} of {total} {what}; each one's reason is in the 'error' "
                   f"column of {table} (the results are saved)", err=True)
        raise typer.Exit(1)


@contextmanager
def _resume_hint(out: Path) -> Iterator[None]:
    """A sweep stopped by Ctrl-C: one line on what is kept and how to resume, exit status 130."""
    try:
        yield
    except KeyboardInterrupt:
        from ..study.table import journal_path, read_rows

        try:
            kept = f"{len(read_rows(out))} finished cells are kept"
        except Exception:  # noqa: BLE001 - the hint must not hide the interruption
            kept = "the finished cells are kept"
        journal = journal_path(out)
        # a first sweep interrupted has only its journal: the table it named did not exist
        where = (f"in {out}" + (" and its journal" if journal.exists() else "") if out.exists()
                 else f"in {journal} ({out} is written when the sweep completes)")
        interrupted(f"interrupted: {kept} {where}; run the same command again to resume (only "
                    "the missing cells are computed)")


def _adaptive(model: str, base: Any, m_star: str | None, amplitude: str | None, out: Path, *,
              budget: int, levels: int, yes: bool, **run: Any) -> Any:
    """Run ``sweep --adaptive``: the (m*, A*) ranges and base grid from --m-star/--amplitude."""
    from ..study.estimate import size_check

    if any((spec or "").strip().lower().startswith("lin:") for spec in (m_star, amplitude)):
        _fail("--adaptive spaces its base grid logarithmically: give --m-star and --amplitude "
              "as START:STOP:N (or log:START:STOP:N), not lin:")
    for flag, spec in (("--m-star", m_star), ("--amplitude", amplitude)):
        if spec is not None and ":" not in spec:
            # a list's ends alone were used: 0.1,0.5,1 never ran 0.5
            _fail(f"{flag} = {spec!r}: --adaptive takes a range, START:STOP:N (log-spaced base "
                  "grid, refined where the regime changes), not a list of values")
    m_axis = sd.parse_axis(m_star or "1e-3:1e2:21", "m_star")
    a_axis = sd.parse_axis(amplitude or "1e-2:10:21", "amplitude")
    if m_axis.size != a_axis.size or m_axis.size < 2:
        _fail("--adaptive needs --m-star and --amplitude as START:STOP:N with the same N >= 2")
    corners = [base.with_updates(**{"particle.m_star": m, "drive.amplitude": a})
               for m in (m_axis[0], m_axis[-1]) for a in (a_axis[0], a_axis[-1])]
    # refused above the bound; not printed (the study checks its own options after this)
    size_check("sweep --adaptive", corners, budget, workers=run["workers"], engine=run["engine"],
               yes=yes, show=False, smaller="a smaller --budget")
    return sd.adaptive_sweep(model, (m_axis[0], m_axis[-1]), (a_axis[0], a_axis[-1]),
                             budget=budget, base=int(m_axis.size), levels=levels, scene=base,
                             table=out, **run)


def _sweep_text(frame: Any, out: Path, adaptive: bool) -> None:
    """What a sweep prints: cells per model and regime, the warnings, what it wrote (and the
    line plot of a sweep over one field), and the table's cells from another grid."""
    from ..report.diagrams import unsettled_cells

    frame = frame.assign(_unsettled=unsettled_cells(frame))
    if adaptive:
        # the counts cover the map's points, the inferred ones too: the table holds the computed
        computed = int(frame.attrs["computed"])
        typer.echo(f"regimes of the map's {len(frame)} points ({computed} computed, the ones the "
                   f"table holds; {frame.attrs['inferred']} inferred from their neighbours):")
    counts = frame.groupby(["model", "regime"])["_unsettled"].agg(["size", "sum"])
    for (name, regime), row in counts.iterrows():
        loose = int(row["sum"])
        typer.echo(f"{name:>20} {regime:>14}: {int(row['size'])}"
                   + (f" ({loose} NOT settled)" if loose else ""))
    for text in warning_summary(frame):
        typer.echo(text)
    errors = int(frame["error"].notna().sum())
    line = None if adaptive else _line_plot(frame, out)
    if adaptive:
        _adaptive_text(frame, out, errors)
    else:
        typer.echo(f"wrote {out} ({len(frame)} cells, {errors} with errors)"
                   + (f" and {line} (line plot)" if line is not None else ""))
        other = int(frame.attrs.get("other_cells", 0))
        if other:
            typer.echo(f"{out} now holds {frame.attrs['table_cells']} cells: {other} from an "
                       "earlier sweep outside this grid (the counts above are this grid's; "
                       "give a new -o for a table of this grid only)")


def _adaptive_text(frame: Any, out: Path, errors: int) -> None:
    """What an adaptive sweep wrote: its computed points (run now or found in the table), the
    inferred ones, and the table's cells that are not this map's (an earlier run's)."""
    computed, now = int(frame.attrs["computed"]), int(frame.attrs["computed_now"])
    # the table holds the computed points; the inferred ones only complete the diagram
    typer.echo(f"wrote {out} ({computed} cells computed: {now} in this run, "
               f"{computed - now} already in the table; {errors} with errors; "
               f"{frame.attrs['inferred']} more inferred from their neighbours, "
               f"{frame.attrs['wrong_guesses']} wrong guesses found by the check sample)")
    grid, other = int(frame.attrs.get("grid_cells", 0)), int(frame.attrs.get("other_cells", 0))
    parts = []
    if grid:
        # not necessarily a larger budget: a smaller one at other --levels refines other cells
        parts.append(f"{grid} more of this map's grid from an earlier run that refined other "
                     "cells (another --budget or --levels)")
    if other:
        parts.append(f"{other} from an earlier sweep outside this map (another --m-star/--amplitude "
                     "range, base grid, model or a grid sweep)")
    if parts:
        fresh = "; give a new -o for a table of this map only" if other else ""
        typer.echo(f"{out} now holds {frame.attrs['table_cells']} cells: {' and '.join(parts)} "
                   f"(the counts above are this map's{fresh})")


#: the longest warning a sweep's summary prints (the table's warnings column holds it in full)
WARNING_WIDTH = 160


def warning_summary(frame: Any) -> list[str]:
    """The cells' warnings (a device's validity warnings, a long-time mean's) in a few lines.

    One line per kind of warning, with how many cells carry it; cells whose warnings differ
    only in their numbers (``a0 = 4.45e-14 m``) count as one kind, printed without the
    parenthesized details, and with ``...`` for a number that differs between its cells.
    """
    import re

    if "warnings" not in frame.columns:
        return []
    texts = [str(t) for t in frame["warnings"] if isinstance(t, str) and t]
    kinds: dict[str, list[str]] = {}
    for text in texts:
        short = re.sub(r"\s*\([^()]*\)", "", text)
        kinds.setdefault(re.sub(r"[-+]?\d+(\.\d+)?(e[-+]?\d+)?", "#", short), []).append(short)
    if not kinds:
        return []
    lines = [f"warnings: {len(texts)} of {len(frame)} cells (each in full in the table's "
             "warnings column)"]
    for key, shorts in sorted(kinds.items(), key=lambda kv: -len(kv[1])):
        shown = shorts[0] if len(set(shorts)) == 1 else key.replace("#", "...")
        if len(shown) > WARNING_WIDTH:
            shown = shown[:WARNING_WIDTH - 3].rstrip() + "..."
        lines.append(f"  {len(shorts)} cell{'s' if len(shorts) != 1 else ''}: {shown}")
    return lines


def _line_plot(frame: Any, out: Path) -> Path | None:
    """A sweep over one field: print its points and draw them beside the table (TABLE.png)."""
    from ..report.diagrams import COLOURS
    from ..report.line_plot import line_rows, plot_line, swept_field
    from ..study.export import dimensions

    field = swept_field(frame)
    if field is None:
        # a device swept over several fields: its points in SI units (no line to draw)
        dims = [d for d in dimensions(frame) if d.startswith("device.")]
        if len(dims) > 1 and "drift_speed_m_s" in frame.columns:
            for text in line_rows(frame, dims):
                typer.echo(text)
        return None
    for text in line_rows(frame, field):
        typer.echo(text)
    return plot_line(frame, out.with_suffix(".png"), None, field, colours=COLOURS)


@app.command("bifurcation")
@with_scene_options()
def bifurcation_cmd(
    axis: Annotated[
        str,
        typer.Option("--axis", help="FIELD=SPEC: a numeric dotted scene field (drive.amplitude, "
                     "particle.m_star, material.mu, model_params.restitution) and its values "
                     "a,b,c | START:STOP:N (log) | lin:START:STOP:N, at least two"),
    ],
    out: Annotated[
        Path, typer.Option("-o", "--out", help="output folder: bifurcation.parquet, .json, .png "
                           "and the branches' journals (a stopped run resumes)")
    ],
    scene_arg: Annotated[Path | None, typer.Argument(help="base scene TOML")] = None,
    model: Annotated[
        str | None, typer.Option("--model", help="model name(s), comma-separated: one panel each, "
                                 "on the same axis")
    ] = None,
    param: Param = None,
    samples: Annotated[int, typer.Option("--samples", help="Poincare samples per value (1 to 1e7)")] = 64,
    direction: Annotated[
        str, typer.Option("--direction", help="up, down or both (both marks hysteresis: where the "
                          "two sweeps end on different attractors)")
    ] = "up",
    locate: Annotated[
        bool, typer.Option("--locate", help="bisect every change between neighbouring values "
                           "(period, lift-off, sticking phase)")
    ] = False,
    tolerance: Annotated[
        float, typer.Option("--tolerance", help="--locate: relative width of the final bracket")
    ] = 1e-4,
    workers: Workers = None,
    scheduler: Scheduler = None,
    progress: Progress = True,
    engine: Engine = "compiled",
    force: Annotated[
        bool, typer.Option("--force", help="resume a folder written by other code (values of both "
                           "are then mixed) or restart one holding another diagram")
    ] = False,
    as_json: Annotated[bool, typer.Option("--json", help="print the summary as one JSON object")] = False,
    yes: Yes = False,
    *,
    scene_overrides: dict[str, Any],
) -> None:
    """Bifurcation diagram: each value of --axis run to its attractor, warm-started from the last.

    Records K stroboscopic samples per value (a*, a*', x*' - u_x' at integer t*, lift-off
    phases), the orbit period, its multiplier and the largest Lyapunov exponent; writes the
    table, a JSON summary and the figure to -o DIR. Every other scene field is an option
    (--m-star, --mu, --horizontal-ratio, ...) setting the base scene. Exit status 1 if a value
    failed (after everything is written: each reason is in the table's 'error' column).
    """
    field, spec = _split_axis(axis, "FIELD=SPEC", "drive.amplitude=lin:0.1:1.5:100")
    axis_and_option(field, spec, scene_overrides)
    if tolerance != 1e-4 and not locate:  # it was ignored without a word
        _fail(f"--tolerance {tolerance:g} belongs to --locate (the width of its final bracket); "
              "add --locate or leave it out")
    out_kind(out, (), "")
    named = model_names(model)
    fast_start()
    for name in named:
        sd.get_model(name)
    base = scene_from_options(
        scene_arg, named[0] if named else None, _parse_param(param), scene_overrides,
        swept=(field,))
    from sawdrift.report.bifurcation_plot import plot_bifurcation
    from sawdrift.study.bifurcation import FIGURE, TABLE, bifurcation, check_request

    # every argument checked before the size line and the output folder
    check_request(base, field, spec, samples=samples, direction=direction, tolerance=tolerance,
                  engine=engine, workers=workers)
    _writable(out)
    _bifurcation_size(base, field, spec, len(named) or 1, direction, samples, workers, engine,
                      yes, progress, locate)

    try:
        res = bifurcation(base, field, spec, models=named or None, samples=samples,
                          direction=direction, locate=locate, tolerance=tolerance, out=out,
                          workers=workers, scheduler=scheduler, progress=progress, force=force,
                          engine=engine)
    except KeyboardInterrupt:
        # the branches' journals keep every value done (it exited with no word of them)
        interrupted(f"interrupted: the values done are kept in {out}/journal; run the same "
                    "command again to resume (only the missing values are computed)")
    plot_bifurcation(res, out / FIGURE)
    # the table has a row per sample: the values are the summary's points
    done = [p for branches in res.summary["points"].values() for pts in branches.values()
            for p in pts]
    n_failed = sum(1 for p in done if p.get("error"))
    if as_json:
        typer.echo(json.dumps(res.summary))
    else:
        _bifurcation_text(res, field)
        typer.echo(f"wrote {out}/bifurcation.parquet, bifurcation.json, bifurcation.png "
                   f"({res.computed} values computed)")
    failed_cells(n_failed, len(done), "values", f"{out}/{TABLE}")


def _bifurcation_text(res: Any, field: str) -> None:
    """What a bifurcation prints before its 'wrote' line: the periods of each branch, its
    failed values with their reasons, the bifurcations and the hysteresis."""
    for name, branches in res.summary["points"].items():
        for way, points in branches.items():
            periods: dict[int, int] = {}
            failed = [p for p in points if p.get("error")]
            for p in points:
                if not p.get("error"):
                    periods[p["period"]] = periods.get(p["period"], 0) + 1
            shown = ", ".join(f"period {k}: {n}" if k else f"no period: {n}"
                              for k, n in sorted(periods.items()))
            typer.echo(f"{name:>20} {way:>4}: {shown}" + (f", failed: {len(failed)}"
                                                          if failed else ""))
            for p in failed:  # a failed value is no 'no period': it says why, in its row too
                typer.echo(f"{name:>20} {way:>4}: failed at {field} = {p['value']:.6g}: "
                           f"{p['error']}")
    for b in res.bifurcations:
        where = f"{b['value']:.6g}" if b["located"] else f"{b['bracket'][0]:.6g}..{b['bracket'][1]:.6g}"
        typer.echo(f"{b['model']:>20} {b['direction']:>4}: {b['kind']} {b['from_period']} -> "
                   f"{b['to_period']} at {field} = {where}")
    for h in res.hysteresis:
        typer.echo(hysteresis_line(h))


def hysteresis_line(h: dict[str, Any]) -> str:
    """A hysteresis interval as the console prints it: one value alone may be the step's error
    on a compliant contact rather than two attractors (mmd at A* 0.87: two period-2 orbits 0.036
    apart in a*, one orbit at 1024 steps per period), and says so."""
    if h["values"] > 1:
        return f"{h['model']:>20} both: hysteresis from {h['from']:.6g} to {h['to']:.6g}"
    return (f"{h['model']:>20} both: hysteresis at {h['from']:.6g} only (one value: check it "
            "with a larger --steps-per-period)")


def _bifurcation_size(base: Any, field: str, spec: str, models: int, direction: str,
                      samples: int, workers: int | None, engine: str, yes: bool,
                      show: bool, locate: bool = False) -> None:
    """A bifurcation diagram's size: values x branches, each value a run and its samples; the
    branches (model x direction) run in parallel, each one's values in turn. ``--locate``'s
    bisections, as many as the bifurcations found, are not known before: the line says so (an
    estimate of 1.3 s for a run of 9 to 14 s read as the whole)."""
    from ..dynamics.assembly import steps_per_period
    from ..study.axes import parse_values
    from ..study.estimate import size_check

    values = [v for v in parse_values(spec, field) if isinstance(v, int | float)]
    if not values:
        return  # the study's own checks name what is wrong with the axis
    branches = models * (2 if direction == "both" else 1)
    picks = sorted({0, len(values) // 2, len(values) - 1})
    sample = [sd.bind(base.with_updates(**{field: values[i]})) for i in picks]
    what = "bifurcation (not counted: --locate's bisections at each bifurcation found)" \
        if locate else "bifurcation"
    size_check(what, sample, len(values) * branches,
               workers=min(workers or branches, branches), engine=engine, yes=yes, show=show,
               extra_steps=samples * steps_per_period(sample[0]), unit="value",
               smaller="fewer values or --samples")
