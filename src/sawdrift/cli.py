"""The ``sawdrift`` command line: a thin layer over the public Python API.

Every user error (bad field, unknown model, malformed TOML or grid, broken plugin, an output path
that cannot be written) ends in one line on stderr and exit status 2, never a traceback. Exit
status 1 means a check failed (check-model, validate, bench speed); an internal failure (a bug:
please report it) exits with :data:`INTERNAL_FAILURE`.
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path
from typing import Annotated, Any

import typer

import sawdrift as sd

from ._startup import fast_start

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    help="Compare frictional contact models on a particle driven by a Rayleigh wave.",
    pretty_exceptions_enable=False,
)


#: exit status of an unexpected internal failure (1 is a failed check, 2 bad input)
INTERNAL_FAILURE = 3


def _fail(message: str, code: int = 2) -> None:
    typer.echo(f"error: {message}", err=True)
    raise typer.Exit(code)


def _one_line_warnings(message, category, filename, lineno, file=None, line=None):  # noqa: ARG001
    sys.stderr.write(f"warning: {message}\n")


def _writable(path: Path, option: str = "-o", folder: bool = True) -> Path:
    """Check before any work that ``path`` (a folder, or a file's folder) can be written.

    A run or a sweep must not compute for minutes and then lose its results to a bad path.
    """
    import os
    import tempfile

    where = path if folder else path.parent
    if not folder and path.is_dir():
        _fail(f"{option} {str(path)!r} is a directory; give a file name")
    if folder and path.exists() and not path.is_dir():
        _fail(f"{option} {str(path)!r} exists and is not a folder")
    try:
        where.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(dir=where, prefix=".sawdrift-probe-")
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        _fail(f"{option} {str(path)!r} cannot be written ({exc.strerror or exc})")
    return path


def _parse_param(items: list[str] | None) -> dict[str, Any]:
    params: dict[str, Any] = {}
    for item in items or []:
        if "=" not in item:
            _fail(f"--param {item!r} must look like NAME=VALUE")
        key, raw = item.split("=", 1)
        if not key.strip():
            _fail(f"--param {item!r} has no parameter name; it must look like NAME=VALUE")
        try:
            value: Any = json.loads(raw)
        except json.JSONDecodeError:
            value = raw
        params[key.strip()] = value
    return params


def scene_from_options(scene_file: Path | None, **options: Any) -> sd.Scene:
    """Load a scene file (or the defaults) and apply the command-line overrides."""
    base = sd.Scene.from_toml(scene_file) if scene_file is not None else None
    data = base.model_dump(exclude_none=True) if base is not None else {}
    mapping = {
        "model": "model",
        "m_star": "particle.m_star",
        "amplitude": "drive.amplitude",
        "horizontal_ratio": "drive.horizontal_ratio",
        "ramp_periods": "drive.ramp_periods",
        "mu": "material.mu",
        "nu": "material.nu",
        "periods": "numerics.periods",
        "steps_per_period": "numerics.steps_per_period",
        "order": "numerics.order",
        "settle": "numerics.settle",
        "profile": "particle.profile.shape",
        "friction": "effects.friction",
        "vertical_inertia": "effects.vertical_inertia",
        "normal_damping": "effects.normal_damping",
        "horizontal_wave": "effects.horizontal_wave",
        "vertical_wave": "effects.vertical_wave",
        "rotation": "effects.rotation",
        "gyration": "particle.gyration",
        "rolling_resistance": "effects.rolling_resistance",
        "orbit": "drive.orbit",
        "theta": "material.theta",
    }
    # one rule for every path: on a device scene a derived (normalized) field is an error
    # naming the device field to set instead (sawdrift.scene.apply_overrides)
    data = sd.scene.apply_overrides(data, {dotted: options.get(key) for key, dotted in mapping.items()})
    if base is not None and options.get("model") not in (None, base.model):
        data["model_params"] = {}  # the file's parameters belong to the file's model
    params = options.get("params") or {}
    if params:
        data.setdefault("model_params", {}).update(params)
    return sd.scene.build_scene(data, source=str(scene_file) if scene_file else None)


@app.command("models")
def models_cmd(
    as_json: Annotated[bool, typer.Option("--json", help="machine-readable output")] = False,
) -> None:
    """List the registered contact models and the distribution providing each."""
    entries = sd.registry.models
    rows = []
    for name in sorted(entries):
        entry = entries[name]
        info = entry.cls.describe()
        info["distribution"] = entry.distribution
        rows.append(info)
    if as_json:
        typer.echo(json.dumps(rows, indent=2))
        return
    width = max((len(r["name"]) for r in rows), default=4)
    for r in rows:
        typer.echo(f"{r['name']:<{width}}  {r['summary']}  [{r['distribution']}]")
        for check, reason in r["deviations"].items():
            typer.echo(f"{'':<{width}}  declared deviation, {check}: {reason}")
    for name, reason in sorted(sd.registry.failed.items()):
        typer.echo(f"{name:<{width}}  unavailable: {reason}")


@app.command("check-model")
def check_model_cmd(
    name: Annotated[str, typer.Argument(help="registered model name")],
    param: Annotated[list[str] | None, typer.Option("--param", help="model parameter NAME=VALUE")] = None,
    profile: Annotated[
        str | None,
        typer.Option("--profile", help="one declared profile: sphere, cone, flat, power (p = 2.5) or "
                     "table; default: every profile the model declares"),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="machine-readable output")] = False,
) -> None:
    """Run the conformance suite on one model; exit status 1 if a check fails.

    Checks, on every declared profile: normalization (N*(1) = 1), passivity (loop work of
    N* da* + T* db* >= 0 on closed (a*, b*) cycles, both orientations), coulomb_bound,
    kernel_vs_reference, velocity_independence, split_invariance, contact_loss_reset, replay.
    A failing check that the model declares is reported as 'declared'.
    """
    fast_start()
    result = sd.check_model(name, profile=profile, **_parse_param(param))
    typer.echo(json.dumps(result.to_json()) if as_json else result.table())
    if not result.passed:
        raise typer.Exit(1)


@app.command("run")
def run_cmd(
    scene_file: Annotated[Path | None, typer.Argument(help="scene TOML file")] = None,
    model: Annotated[str | None, typer.Option("--model", help="contact model name")] = None,
    m_star: Annotated[float | None, typer.Option("--m-star", help="m* > 0")] = None,
    amplitude: Annotated[float | None, typer.Option("--amplitude", help="A* >= 0")] = None,
    mu: Annotated[float | None, typer.Option("--mu", help="friction coefficient, (0, 10]")] = None,
    nu: Annotated[float | None, typer.Option("--nu", help="Poisson's ratio, (-1, 0.5)")] = None,
    horizontal_ratio: Annotated[
        float | None, typer.Option("--horizontal-ratio", help="r; default r(nu)")
    ] = None,
    periods: Annotated[float | None, typer.Option("--periods", help="periods to simulate")] = None,
    steps_per_period: Annotated[int | None, typer.Option("--steps-per-period")] = None,
    order: Annotated[int | None, typer.Option("--order", help="Adams-Bashforth order 1-4")] = None,
    profile: Annotated[str | None, typer.Option("--profile", help="sphere, cone, flat")] = None,
    settle: Annotated[bool | None, typer.Option("--settle", help="run until the drift settles")] = None,
    param: Annotated[list[str] | None, typer.Option("--param", help="model parameter NAME=VALUE")] = None,
    engine: Annotated[str, typer.Option("--engine", help="compiled or python")] = "compiled",
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    out: Annotated[Path | None, typer.Option("-o", "--out", help="write trajectory and figure here")] = None,
    friction: Annotated[bool | None, typer.Option("--friction/--no-friction")] = None,
    vertical_inertia: Annotated[
        bool | None, typer.Option("--vertical-inertia/--no-vertical-inertia", help="rigid point only")
    ] = None,
    normal_damping: Annotated[float | None, typer.Option("--normal-damping", help="viscous c >= 0")] = None,
    horizontal_wave: Annotated[bool | None, typer.Option("--horizontal-wave/--no-horizontal-wave")] = None,
    vertical_wave: Annotated[bool | None, typer.Option("--vertical-wave/--no-vertical-wave")] = None,
    rotation: Annotated[
        bool | None, typer.Option("--rotation/--no-rotation", help="the sphere may turn (rolling)")
    ] = None,
    gyration: Annotated[
        float | None, typer.Option("--gyration", help="kappa = I/(m R^2) in (0, 1]; 0.4 solid sphere; "
                                   "needs --rotation")
    ] = None,
    rolling_resistance: Annotated[
        float | None,
        typer.Option("--rolling-resistance", help="mu_r >= 0 of the rolling spring (with --rotation)"),
    ] = None,
    orbit: Annotated[
        str | None, typer.Option("--orbit", help="prograde (eq. 1 as printed) or retrograde")
    ] = None,
    theta: Annotated[
        float | None, typer.Option("--theta", help="E*/(4 G*) of the contact; default from nu")
    ] = None,
    explain: Annotated[bool, typer.Option("--explain", help="print the assembled system only")] = False,
) -> None:
    """Run one scene and report its drift and motion regime."""
    fast_start()
    scene = scene_from_options(
        scene_file, model=model, m_star=m_star, amplitude=amplitude, mu=mu, nu=nu,
        horizontal_ratio=horizontal_ratio, periods=periods, steps_per_period=steps_per_period,
        order=order, settle=settle, profile=profile, params=_parse_param(param),
        friction=friction, vertical_inertia=vertical_inertia, normal_damping=normal_damping,
        horizontal_wave=horizontal_wave, vertical_wave=vertical_wave, rotation=rotation,
        gyration=gyration, rolling_resistance=rolling_resistance, orbit=orbit, theta=theta,
    )
    if engine not in ("compiled", "python"):
        _fail(f"--engine = {engine!r} is not allowed; use 'compiled' or 'python'")
    if explain:
        typer.echo(sd.explain(scene, engine))  # type: ignore[arg-type]
        return
    if out is not None:
        _writable(out)
    result = sd.run(scene, trajectory=out is not None, engine=engine)  # type: ignore[arg-type]
    summary = result.summary()
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        result.trajectory.to_parquet(out / "trajectory.parquet", index=False)
        if result.events is not None:
            result.events.to_parquet(out / "events.parquet", index=False)
        sd.plot_trajectory(result, out / "trajectory.png")
        scene.to_toml(out / "scene.toml")
        (out / "result.json").write_text(json.dumps(summary, indent=2) + "\n")
    if as_json:
        typer.echo(json.dumps(summary))
        return
    for key, value in summary.items():
        if key != "scene":  # the whole scene is in --json and in -o DIR/scene.toml
            typer.echo(f"{key:>24}: {value}")
    if summary.get("settled") is False:
        typer.echo(_unsettled_note(summary, scene.particle.m_star / scene.material.mu), err=True)
    if out is not None:
        typer.echo(f"wrote {out}/trajectory.parquet, events.parquet, trajectory.png, scene.toml, "
                   "result.json")


def _unsettled_note(summary: dict[str, Any], tau: float) -> str:
    """One line on why a run's drift is not the steady one, and what to do about it."""
    fix = ("raise --periods or use --settle" if summary.get("settle_method") == "fixed"
           else "raise numerics.max_periods")
    periods = summary["periods"]
    if summary.get("chaotic"):
        return (f"note: the motion is chaotic (lyapunov > 0): the drift is an average over the "
                f"window, not a steady value; {fix} for a longer average")
    if 3.0 * tau > periods:
        return (f"note: the drift has not settled after {periods:g} periods (a heavy particle "
                f"needs of order m*/mu = {tau:g} periods); {fix}")
    return f"note: the drift still changed within the measuring window; {fix}"


def _load_table(path: Path):
    import pandas as pd

    if not path.exists():
        _fail(f"table {str(path)!r} does not exist")
    if path.is_dir():
        _fail(f"table {str(path)!r} is a directory, not a Parquet file")
    try:
        return pd.read_parquet(path)
    except Exception as exc:  # noqa: BLE001
        _fail(f"table {str(path)!r} is not a readable Parquet file ({exc})".splitlines()[0])


@app.command("sweep")
def sweep_cmd(
    out: Annotated[Path, typer.Option("-o", "--out", help="Parquet table (resumed if it exists)")],
    scene_arg: Annotated[Path | None, typer.Argument(help="base scene TOML (or use --scene)")] = None,
    model: Annotated[str | None, typer.Option("--model", help="model name(s), comma-separated")] = None,
    m_star: Annotated[
        str | None, typer.Option("--m-star", help="START:STOP:N (log) or a,b,c; shorthand for an axis")
    ] = None,
    amplitude: Annotated[
        str | None, typer.Option("--amplitude", help="START:STOP:N (log) or a,b,c; shorthand for an axis")
    ] = None,
    axis: Annotated[
        list[str] | None,
        typer.Option("--axis", help="FIELD=SPEC, repeatable: a dotted scene field (material.mu, "
                     "device.amplitude, effects.rotation) and a,b,c | START:STOP:N (log) | "
                     "lin:START:STOP:N; device values may carry units ('5 nm,10 nm')"),
    ] = None,
    settle: Annotated[bool, typer.Option("--settle", help="every cell runs until its drift settles")] = False,
    adaptive: Annotated[
        bool, typer.Option("--adaptive", help="refine only where neighbouring cells disagree in regime "
                           "(m*, A* ranges from --m-star/--amplitude START:STOP:BASE)")
    ] = False,
    budget: Annotated[int, typer.Option("--budget", help="adaptive: most cells computed")] = 2000,
    levels: Annotated[int, typer.Option("--levels", help="adaptive: halvings of a boundary cell")] = 3,
    scene_file: Annotated[Path | None, typer.Option("--scene", help="base scene TOML")] = None,
    mu: Annotated[float | None, typer.Option("--mu")] = None,
    nu: Annotated[float | None, typer.Option("--nu")] = None,
    horizontal_ratio: Annotated[float | None, typer.Option("--horizontal-ratio")] = None,
    periods: Annotated[float | None, typer.Option("--periods")] = None,
    steps_per_period: Annotated[int | None, typer.Option("--steps-per-period")] = None,
    order: Annotated[int | None, typer.Option("--order")] = None,
    profile: Annotated[str | None, typer.Option("--profile")] = None,
    param: Annotated[list[str] | None, typer.Option("--param", help="model parameter NAME=VALUE")] = None,
    workers: Annotated[int | None, typer.Option("--workers", help="local processes")] = None,
    scheduler: Annotated[str | None, typer.Option("--scheduler", help="dask.distributed address")] = None,
    progress: Annotated[bool, typer.Option("--progress/--no-progress")] = True,
    engine: Annotated[str, typer.Option("--engine", help="compiled or python")] = "compiled",
) -> None:
    """Run a grid (models x axes) into a resumable Parquet table.

    The grid is the (m*, A*) plane, by default m* in [1e-3, 1e2] and A* in [1e-2, 10] with 11
    log-spaced values each, times every --axis; an axis over particle.m_star or drive.amplitude
    replaces that default. A device scene has no default plane: give its axes (device.*).
    """
    if scene_arg is not None and scene_file is not None:
        _fail("give the base scene either as an argument or with --scene, not both")
    _writable(out, folder=False)
    scene_file = scene_arg or scene_file
    axes: dict[str, str] = {}
    for item in axis or []:
        field, sep, spec = item.partition("=")
        if not sep or not field.strip() or not spec.strip():
            _fail(f"--axis {item!r} must look like FIELD=SPEC (e.g. material.mu=0.05,0.1,0.2)")
        axes[field.strip()] = spec.strip()
    named = [m.strip() for m in model.split(",") if m.strip()] if model else []
    fast_start()
    for name in named:
        sd.get_model(name)
    base = scene_from_options(
        scene_file, model=named[0] if named else None, mu=mu, nu=nu,
        horizontal_ratio=horizontal_ratio, periods=periods, steps_per_period=steps_per_period,
        order=order, profile=profile, params=_parse_param(param), settle=True if settle else None,
    )
    models = named or [base.model]
    if adaptive:
        if axes or len(models) != 1:
            _fail("--adaptive works on the (m*, A*) plane of one model: no --axis, one --model")
        m_axis = sd.parse_axis(m_star or "1e-3:1e2:21", "m_star")
        a_axis = sd.parse_axis(amplitude or "1e-2:10:21", "amplitude")
        if m_axis.size != a_axis.size or m_axis.size < 2:
            _fail("--adaptive needs --m-star and --amplitude as START:STOP:N with the same N >= 2")
        frame = sd.adaptive_sweep(models[0], (m_axis[0], m_axis[-1]), (a_axis[0], a_axis[-1]),
                               budget=budget, base=int(m_axis.size), levels=levels, scene=base,
                               table=out, workers=workers, scheduler=scheduler, progress=progress)
    else:
        if base.device is None:
            # the (m*, A*) plane unless an axis replaces it: --axis effects.rotation=false,true
            # alone sweeps rotation over the whole default plane, not over one cell
            if m_star is None and "particle.m_star" not in axes:
                m_star = "1e-3:1e2:11"
            if amplitude is None and "drive.amplitude" not in axes:
                amplitude = "1e-2:10:11"
        frame = sd.sweep(models, m_star, amplitude, axes=axes, base=base, table=out,
                         workers=workers, scheduler=scheduler, progress=progress, engine=engine)
    counts = frame.groupby(["model", "regime"]).size()
    for (name, regime), n in counts.items():
        typer.echo(f"{name:>20} {regime:>14}: {n}")
    errors = int(frame["error"].notna().sum())
    typer.echo(f"wrote {out} ({len(frame)} cells, {errors} with errors)")


@app.command("phase-diagram")
def phase_diagram_cmd(
    table: Annotated[Path, typer.Argument(help="sweep table (Parquet)")],
    out: Annotated[Path, typer.Option("-o", "--out", help="figure (PNG)")],
    model: Annotated[str | None, typer.Option("--model", help="model to draw")] = None,
    x: Annotated[str, typer.Option("--x", help="column on the horizontal axis")] = "amplitude",
    y: Annotated[str, typer.Option("--y", help="column on the vertical axis")] = "m_star",
    drift: Annotated[
        bool, typer.Option("--drift", help="regimes beside the drift ratio, boundaries drawn over it "
                           "(uniform or adaptive tables)")
    ] = False,
) -> None:
    """Draw the regime phase diagram of one model over two swept axes (default A*, m*)."""
    frame = _load_table(table)
    _writable(out, folder=False)
    if drift:
        path = sd.plot_drift_map(frame, out, model, x, y)
    else:
        path = sd.plot_phase_diagram(frame, out, model, x, y)
    typer.echo(f"wrote {path}")


@app.command("compare")
def compare_cmd(
    table: Annotated[Path, typer.Argument(help="sweep table (Parquet)")],
    models: Annotated[str, typer.Option("--models", help="comma-separated model names")],
    out: Annotated[Path, typer.Option("-o", "--out", help="figure (PNG)")],
    by: Annotated[
        str | None, typer.Option("--by", help="a swept column: one panel per model and value "
                                 "(e.g. effects.rotation)")
    ] = None,
    x: Annotated[str, typer.Option("--x", help="column on the horizontal axis")] = "amplitude",
    y: Annotated[str, typer.Option("--y", help="column on the vertical axis")] = "m_star",
) -> None:
    """Side-by-side phase diagrams, the cells where they disagree, and an agreement table.

    Compare models (--models a,b), or the values of a swept field for each model
    (--by effects.rotation after a sweep with --axis effects.rotation=false,true).
    """
    frame = _load_table(table)
    _writable(out, folder=False)
    path, md = sd.plot_compare(frame, [m.strip() for m in models.split(",") if m.strip()], out, by,
                            x, y)
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
    progress: Annotated[bool, typer.Option("--progress/--no-progress")] = True,
) -> None:
    """Run the validation cases and write an HTML report; exit status 1 if any case fails."""
    _writable(out)
    fast_start()
    report = sd.validate(out, quick=quick, cases_dir=cases, progress=progress)
    typer.echo(report.summary_line() if hasattr(report, "summary_line") else str(report))
    typer.echo(f"wrote {out / 'index.html'} and {out / 'results.json'}")
    if not report.passed:
        raise typer.Exit(1)


bench_app = typer.Typer(help="Performance: work-precision study and speed targets.", no_args_is_help=True)
app.add_typer(bench_app, name="bench")


@bench_app.command("work-precision")
def bench_work_precision_cmd(
    out: Annotated[Path, typer.Option("-o", "--out", help="output folder")] = Path("work_precision"),
    models: Annotated[str | None, typer.Option("--models", help="comma-separated model names")] = None,
    quick: Annotated[bool, typer.Option("--quick", help="a short ladder (seconds)")] = False,
) -> None:
    """Error against wall time for every model, order and step (figures, CSV, observed order)."""
    names = [m.strip() for m in models.split(",")] if models else None
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


def main() -> None:
    """Console entry point: one-line errors and exit status 2 for user errors."""
    warnings.showwarning = _one_line_warnings
    try:
        # standalone_mode=False makes click return a typer.Exit's code instead of raising it
        code = app(standalone_mode=False)
        sys.exit(code if isinstance(code, int) else 0)
    except typer.Exit as exc:
        sys.exit(exc.exit_code)
    except sd.SawdriftError as exc:
        typer.echo(f"error: {exc}", err=True)
        sys.exit(2)
    except OSError as exc:
        # a path given on the command line (or a folder it names) cannot be read or written
        name = f" {str(exc.filename)!r}" if exc.filename else ""
        typer.echo(f"error: cannot use{name}: {exc.strerror or exc}", err=True)
        sys.exit(2)
    except Exception as exc:  # noqa: BLE001 - usage errors and anything unexpected
        # typer vendors click: its usage errors carry format_message() and an exit code
        if hasattr(exc, "format_message") and hasattr(exc, "exit_code"):
            typer.echo(f"error: {exc.format_message()}", err=True)
            sys.exit(exc.exit_code)
        if type(exc).__name__ == "Abort":
            sys.exit(130)
        text = str(exc).splitlines()[0] if str(exc) else "no details"
        typer.echo(f"error: internal failure ({text}); please report it with the command line",
                   err=True)
        sys.exit(INTERNAL_FAILURE)


if __name__ == "__main__":
    main()
