"""Commands on one model or one scene: models, check-model, run."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated, Any

import typer

import sawdrift as sd

from .._startup import fast_start
from .app import Engine, Param, _parse_param, _writable, app, check_engine
from .scene_options import scene_from_options, with_scene_options


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
    param: Param = None,
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
    kernel_vs_reference, velocity_independence, split_invariance, contact_loss_reset, replay,
    normal_slot.
    A failing check that the model declares is reported as 'declared'.
    """
    fast_start()
    result = sd.check_model(name, profile=profile, **_parse_param(param))
    typer.echo(json.dumps(result.to_json()) if as_json else result.table())
    if not result.passed:
        raise typer.Exit(1)


@app.command("run")
@with_scene_options()
def run_cmd(
    scene_file: Annotated[Path | None, typer.Argument(help="scene TOML file")] = None,
    model: Annotated[str | None, typer.Option("--model", help="contact model name")] = None,
    param: Param = None,
    engine: Engine = "compiled",
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    out: Annotated[Path | None, typer.Option("-o", "--out", help="write trajectory and figure here")] = None,
    explain: Annotated[bool, typer.Option("--explain", help="print the assembled system only")] = False,
    *,
    scene_overrides: dict[str, Any],
) -> None:
    """Run one scene and report its drift and motion regime.

    Every scene field is an option (--m-star, --amplitude, --mu, --rotation, ...); the values
    override the scene file or the defaults.
    """
    fast_start()
    scene = scene_from_options(scene_file, model, _parse_param(param), scene_overrides)
    check_engine(engine)
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
