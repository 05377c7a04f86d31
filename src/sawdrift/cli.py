"""The ``sawdrift`` command line: a thin layer over the public Python API.

Every user error (bad field, unknown model, malformed TOML or grid, broken plugin) ends in one line
on stderr and exit status 2, never a traceback.
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path
from typing import Annotated, Any

import typer

import sawdrift as sd

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    help="Compare frictional contact models on a particle driven by a Rayleigh wave.",
    pretty_exceptions_enable=False,
)


def _fail(message: str, code: int = 2) -> None:
    typer.echo(f"error: {message}", err=True)
    raise typer.Exit(code)


def _one_line_warnings(message, category, filename, lineno, file=None, line=None):  # noqa: ARG001
    sys.stderr.write(f"warning: {message}\n")


def _parse_param(items: list[str] | None) -> dict[str, Any]:
    params: dict[str, Any] = {}
    for item in items or []:
        if "=" not in item:
            _fail(f"--param {item!r} must look like NAME=VALUE")
        key, raw = item.split("=", 1)
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
    }
    for key, dotted in mapping.items():
        value = options.get(key)
        if value is not None:
            sd.scene.set_dotted(data, dotted, value)
    params = options.get("params") or {}
    if params:
        if options.get("model") is not None and base is not None and base.model != options["model"]:
            data["model_params"] = {}
        data.setdefault("model_params", {}).update(params)
    elif options.get("model") is not None and base is not None and base.model != options["model"]:
        data["model_params"] = {}
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
) -> None:
    """Run one scene and report its drift and motion regime."""
    scene = scene_from_options(
        scene_file, model=model, m_star=m_star, amplitude=amplitude, mu=mu, nu=nu,
        horizontal_ratio=horizontal_ratio, periods=periods, steps_per_period=steps_per_period,
        order=order, settle=settle, profile=profile, params=_parse_param(param),
    )
    if engine not in ("compiled", "python"):
        _fail(f"--engine = {engine!r} is not allowed; use 'compiled' or 'python'")
    result = sd.run(scene, trajectory=out is not None, engine=engine)  # type: ignore[arg-type]
    summary = result.summary()
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        result.trajectory.to_parquet(out / "trajectory.parquet", index=False)
        sd.plot_trajectory(result, out / "trajectory.png")
        scene.to_toml(out / "scene.toml")
        (out / "result.json").write_text(json.dumps(summary, indent=2) + "\n")
    if as_json:
        typer.echo(json.dumps(summary))
        return
    for key, value in summary.items():
        typer.echo(f"{key:>24}: {value}")
    if out is not None:
        typer.echo(f"wrote {out}/trajectory.parquet, trajectory.png, scene.toml, result.json")


def main() -> None:
    """Console entry point: one-line errors and exit status 2 for user errors."""
    warnings.showwarning = _one_line_warnings
    try:
        app(standalone_mode=False)
    except typer.Exit as exc:
        sys.exit(exc.exit_code)
    except sd.SawdriftError as exc:
        typer.echo(f"error: {exc}", err=True)
        sys.exit(2)
    except Exception as exc:  # noqa: BLE001 - usage errors and anything unexpected
        # typer vendors click: its usage errors carry format_message() and an exit code
        if hasattr(exc, "format_message") and hasattr(exc, "exit_code"):
            typer.echo(f"error: {exc.format_message()}", err=True)
            sys.exit(exc.exit_code)
        if type(exc).__name__ == "Abort":
            sys.exit(130)
        typer.echo(f"error: {type(exc).__name__}: {exc}".splitlines()[0], err=True)
        sys.exit(1)


if __name__ == "__main__":
    main()
