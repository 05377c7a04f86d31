"""Reports: phase diagrams, comparisons, export, the demo, validation and benchmarks."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Annotated

import typer

import sawdrift as sd

from .._startup import fast_start
from .app import (
    Progress,
    _fail,
    _load_table,
    _writable,
    app,
    bench_app,
    figure_path,
    model_names,
)

#: the help of a figure's -o
FIGURE_HELP = "figure: NAME.png (or .pdf, .svg, .jpg, .tif, .webp, .eps, .ps; no suffix: .png)"
#: the help of --where
WHERE_HELP = ("FIELD=VALUE: only the cells with this value of another swept column (e.g. "
              "particle.load=0.2); needed where the table holds several (repeatable)")
#: the suffixes of the explorer page
PAGE_SUFFIXES = (".html", ".htm")

Where = Annotated[list[str] | None, typer.Option("--where", help=WHERE_HELP)]


def parse_where(items: list[str] | None) -> dict[str, str]:
    """``{FIELD: VALUE}`` of the ``--where FIELD=VALUE`` options, or one line and exit 2."""
    where: dict[str, str] = {}
    for item in items or []:
        field, sep, value = item.partition("=")
        if not sep or not field.strip() or not value.strip():
            _fail(f"--where {item!r} must look like FIELD=VALUE (e.g. particle.load=0.2)")
        if field.strip() in where:
            _fail(f"--where {field.strip()} is given twice; give each column one value")
        where[field.strip()] = value.strip()
    return where


def page_path(path: Path) -> Path:
    """The file the explorer page given as ``path`` is written to, or one line and exit 2.

    A name without a file suffix gets ``.html`` (``-o explore`` writes ``explore.html``, and
    the command says so); another suffix than .html or .htm is refused. A folder is refused
    (:func:`sawdrift.cli.app._writable`): the page is one file.
    """
    if path.is_dir():
        _fail(f"-o {str(path)!r} is a directory; give a file name ending in .html")
    if not path.suffix:
        return path.with_name(path.name + ".html")
    if path.suffix.lower() not in PAGE_SUFFIXES:
        _fail(f"-o {str(path)!r}: {path.suffix} is not a page format; give a name ending in "
              ".html or .htm (no suffix: .html)")
    return path


@app.command("phase-diagram")
def phase_diagram_cmd(
    table: Annotated[Path, typer.Argument(help="sweep table (Parquet)")],
    out: Annotated[Path, typer.Option("-o", "--out", help=FIGURE_HELP)],
    model: Annotated[str | None, typer.Option("--model", help="model to draw")] = None,
    x: Annotated[str, typer.Option("--x", help="column on the horizontal axis")] = "amplitude",
    y: Annotated[str, typer.Option("--y", help="column on the vertical axis")] = "m_star",
    drift: Annotated[
        bool, typer.Option("--drift", help="regimes beside the drift ratio, boundaries drawn over it "
                           "(uniform or adaptive tables)")
    ] = False,
    where: Where = None,
) -> None:
    """Draw the regime phase diagram of one model over two swept axes (default A*, m*).

    A table swept over another column too (--axis particle.load=0,0.2) is drawn for one value
    of it: --where particle.load=0.2.
    """
    out = figure_path(out)
    picked = parse_where(where)
    # the columns the figure reads (a table without one failed as an internal error)
    frame = _load_table(table, ("model", "regime") + (("drift_ratio",) if drift else ()))
    _axes_in(frame, table, x, y)
    _writable(out, folder=False)
    if drift:
        path = sd.plot_drift_map(frame, out, model, x, y, where=picked)
    else:
        path = sd.plot_phase_diagram(frame, out, model, x, y, where=picked)
    typer.echo(f"wrote {path}")


def _axes_in(frame, table: Path, x: str, y: str) -> None:
    """One line (exit 2) naming --x or --y where the table has no such column, with the columns
    it can draw (the table was said not to be a sweep table)."""
    for option, column in (("--x", x), ("--y", y)):
        if column not in frame.columns:
            numeric = [c for c in frame.columns if frame[c].dtype.kind in "fiu"
                       and frame[c].nunique() > 1]
            _fail(f"{option} = {column!r}: table {str(table)!r} has no such column; columns that "
                  f"vary in it: {', '.join(numeric) or 'none'}")


@app.command("compare")
def compare_cmd(
    table: Annotated[Path, typer.Argument(help="sweep table (Parquet)")],
    models: Annotated[str, typer.Option("--models", help="comma-separated model names")],
    out: Annotated[Path, typer.Option("-o", "--out", help=FIGURE_HELP)],
    by: Annotated[
        str | None, typer.Option("--by", help="a swept column: one panel per model and value "
                                 "(e.g. effects.rotation)")
    ] = None,
    x: Annotated[str, typer.Option("--x", help="column on the horizontal axis")] = "amplitude",
    y: Annotated[str, typer.Option("--y", help="column on the vertical axis")] = "m_star",
    where: Where = None,
) -> None:
    """Side-by-side phase diagrams, the cells where they disagree, and an agreement table.

    Compare models (--models a,b), or the values of a swept field for each model
    (--by effects.rotation after a sweep with --axis effects.rotation=false,true). Any other
    swept column is held at one value: --where particle.load=0.2.
    """
    out = figure_path(out)
    picked = parse_where(where)
    names = model_names(models, "--models")
    twice = sorted({m for m in names if names.count(m) > 1})
    if twice:  # a model against itself agreed 100 %
        _fail(f"--models {models!r} names {', '.join(twice)} twice: give each model once")
    frame = _load_table(table, ("model", "regime"))
    _axes_in(frame, table, x, y)
    _writable(out, folder=False)
    path, md = sd.plot_compare(frame, names, out, by, x, y, where=picked)
    typer.echo(md)
    typer.echo(f"wrote {path} and {path.with_suffix('.md')}")


@app.command("export")
def export_cmd(
    table: Annotated[Path, typer.Argument(help="sweep table (Parquet)")],
    out: Annotated[Path, typer.Option("-o", "--out", help="grid file: .nc (netCDF) or .zarr")],
) -> None:
    """Export a sweep table to a gridded dataset (xarray; CF regime flags; provenance in attrs)."""
    _load_table(table)  # one-line errors for a missing or unreadable table
    _writable(out.parent if out.suffix == ".zarr" else out, folder=out.suffix == ".zarr")
    ds = sd.write_grid(table, out)
    dims = ", ".join(f"{d} ({n})" for d, n in ds.sizes.items())
    typer.echo(f"wrote {out}: dimensions {dims}; variables {', '.join(ds.data_vars)}")
    if "regime" in ds.data_vars:
        # a point of the grid no cell of the table is at: NaN in every variable (an adaptive map,
        # or tables of two grids), said in the file's attributes only
        empty = int((ds["regime"].values == -1).sum())
        if empty:
            typer.echo(f"  {empty} of {ds['regime'].size} grid points hold no cell of the table "
                       "(regime -1, NaN values): an adaptive map's unrefined points, or cells of "
                       "another grid")


@app.command("explore")
def explore_cmd(
    table: Annotated[Path, typer.Argument(help="sweep table (Parquet)")],
    out: Annotated[Path, typer.Option("-o", "--out", help="page: NAME.html (or .htm; no suffix: "
                                      ".html), one self-contained file")] = Path("explore.html"),
    traces: Annotated[
        Path | None, typer.Option("--traces", help="traces file (default: TABLE.traces.parquet beside "
                                  "the table, if any)")
    ] = None,
    x: Annotated[str | None, typer.Option("--x", help="column on the horizontal axis (default: A*, "
                                          "or a swept device field)")] = None,
    y: Annotated[str | None, typer.Option("--y", help="column on the vertical axis (default: m*, "
                                          "or a swept device field)")] = None,
    where: Where = None,
) -> None:
    """An offline page of a table's phase diagrams: hover a cell for its metrics, click it for its
    last periods (tables swept with --traces), compare the models' regimes. Every other swept
    column gets a panel per value; --where keeps one.
    """
    out = page_path(out)
    _writable(out, folder=False)
    picked = parse_where(where)
    path = sd.write_explorer(table, out, traces, x=x, y=y, where=picked)
    typer.echo(f"wrote {path} ({path.stat().st_size / 1e6:.1f} MB): open it in a browser")


@app.command("demo")
def demo_cmd(
    out: Annotated[Path, typer.Option("-o", "--out", help="output folder")] = Path("sawdrift_out"),
    n: Annotated[int, typer.Option("--n", help="grid points per axis")] = 21,
    workers: Annotated[int | None, typer.Option("--workers")] = None,
) -> None:
    """The main job: a default scene, and the phase diagrams of material_point and mmd.

    The grid is the paper's Fig. 3 plane, m* in [1e-3, 1e2] and A* in [1e-2, 10], at mu = 0.1,
    nu = 0.3; the figures and the table go to OUT.
    """
    if not 2 <= n <= 401:
        _fail(f"--n = {n} is not allowed; use 2 to 401 grid points per axis")
    _writable(out)
    fast_start()
    sd.demo(out, n, workers, echo=typer.echo)


@app.command("validate")
def validate_cmd(
    out: Annotated[Path, typer.Option("-o", "--out", help="report folder (index.html, results.json)")] = Path(
        "validation_report"
    ),
    quick: Annotated[bool, typer.Option("--quick", help="the fast subset CI runs")] = False,
    cases: Annotated[Path | None, typer.Option("--cases", help="folder of validation cases")] = None,
    progress: Progress = True,
) -> None:
    """Run the validation cases and write an HTML report; exit status 1 if any case fails."""
    _writable(out)
    fast_start()
    report = sd.validate(out, quick=quick, cases_dir=cases, progress=progress)
    typer.echo(report.summary_line() if hasattr(report, "summary_line") else str(report))
    typer.echo(f"wrote {out / 'index.html'} and {out / 'results.json'}")
    # a case that could not run is named here, not only in the report (the terminal said
    # "1 errors counted as failed" and nothing of which file or why)
    broken = False
    for res in report.results:
        if res.status == "error":
            loads = res.group == "?"  # the case file itself did not load (validation.load_cases)
            what = res.title if loads else f"case {res.case}"
            why = _EXCEPTION_NAME.sub("", res.message.removeprefix("error: "), count=1)
            typer.echo(f"error: {what}: {why}", err=True)
            broken = broken or loads
    if broken:  # a case file that does not load is bad input, as a malformed scene file is
        raise typer.Exit(2)
    if not report.passed:
        raise typer.Exit(1)


#: a Python exception's class name at the start of a case's error message, left out of the
#: terminal's line (the report keeps it)
_EXCEPTION_NAME = re.compile(r"^[A-Z][A-Za-z]*(Error|Exception): ")


@bench_app.command("work-precision")
def bench_work_precision_cmd(
    out: Annotated[Path, typer.Option("-o", "--out", help="output folder")] = Path("work_precision"),
    models: Annotated[str | None, typer.Option("--models", help="comma-separated model names")] = None,
    quick: Annotated[bool, typer.Option("--quick", help="a short ladder (seconds)")] = False,
) -> None:
    """Error against wall time for every model, order and step (figures, CSV, observed order)."""
    names = [m.strip() for m in models.split(",")] if models is not None else None
    if names is not None and not any(names):  # --models '' ran every model
        _fail(f"--models {models!r} names no model: give model names (sawdrift models lists "
              "them), or leave --models out for every model")
    for name in names or []:
        sd.get_model(name)
    _writable(out)
    sd.work_precision(names, out, quick=quick)
    typer.echo(f"wrote {out}")


@bench_app.command("speed")
def bench_speed_cmd(
    quick: Annotated[bool, typer.Option("--quick", help="small sizes (seconds)")] = False,
) -> None:
    """Measure the performance targets and print each with PASS/FAIL; exit 1 if one fails."""
    result = sd.bench_speed(quick=quick)
    if not result["all_passed"]:
        raise typer.Exit(1)
