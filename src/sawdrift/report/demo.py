"""The main job (``sawdrift demo``): a default scene, the paper's Fig. 2 and Fig. 3, the explorer
page, rotation."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from ..result.runner import run
from ..scene.schema import Scene
from ..study.progress import notice
from ..study.provenance import TableProvenanceError
from ..study.sweep import journal_path, sweep
from ..study.traces import traces_path
from .compare_plot import plot_compare
from .diagrams import (
    HATCH_LABEL,
    plot_drift_map,
    plot_phase_diagram,
    unsettled_cells,
)
from .explore import write_explorer
from .fig2 import plot_fig2
from .marks import creep_cells
from .plots import plot_trajectory


def _sweep(echo: Callable[[str], None], table: Path, *args, **kwargs):
    """``sweep`` into ``table``; a table of other code (an older sawdrift) is computed anew.

    The demo's tables are its own outputs, so running the demo again after an upgrade replaces
    them instead of refusing to mix rows of two versions.
    """
    try:
        return sweep(*args, table=table, **kwargs)
    except TableProvenanceError as exc:
        echo(f"{table.name}: {exc}; computing it anew")
        for path in (table, journal_path(table), traces_path(table)):
            path.unlink(missing_ok=True)
        return sweep(*args, table=table, **kwargs)


def hatch_note(unsettled: int, total: int) -> str:
    """What the hatching of the regime figures means, as the demo prints it.

    One meaning in every figure: the cell's ``settled`` is false. Its drift did not settle
    within its cap on a fixed point, a periodic orbit or a motion that beats without repeating
    (whose window means agree: settled, ``quasi_periodic`` in a sweep table): a slow approach,
    or irregular (chaotic, intermittent) motion, so its drift is a long-time mean with its error
    where the motion is irregular, else the mean of its last window. The colour under the
    hatching is still the cell's regime, whatever it is.
    """
    return (f"{unsettled} of {total} did not within their cap (hatched, in every figure: "
            f"{HATCH_LABEL}; the colour under it is still the cell's regime, and its drift a "
            "long-time mean with its error where the motion is irregular, else the mean of its "
            "last window)")


def demo(out: Path, n: int = 21, workers: int | None = None,
         echo: Callable[[str], None] = print) -> None:
    """Write the demo's figures and tables to ``out``.

    The default scene (mmd, m* = 0.1, A* = 0.316), the phase diagrams of the material point and
    mmd over m* in [1e-3, 1e2] and A* in [1e-2, 10] (n x n cells, each run until its drift has
    settled, at least 40 periods; mu = 0.1, nu = 0.3), their comparison and mmd's drift map, the
    explorer page of their table (``explore.html``), the four regimes' trajectories (Fig. 2), and
    the same plane with rotation off and on ((n + 1)/2 cells per axis, settled likewise).

    Every regime figure marks three things the same way: hatched cells did not settle (see
    :func:`hatch_note`), circled cells creep (a drift with no gross slip), and on an m* axis a
    dashed and a dotted line give the normal and the tangential contact resonance.
    """
    out.mkdir(parents=True, exist_ok=True)
    scene = Scene(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 0.316})
    with notice("demo: compiling the contact models' loops (first run only: a few seconds)"):
        result = run(scene, trajectory=True)
    plot_trajectory(result, out / "default_scene.png")
    scene.to_toml(out / "default_scene.toml")
    echo(f"default scene (mmd, m* = 0.1, A* = 0.316): {result.regime}, "
         f"drift ratio {result.drift_ratio:.4f}; wrote {out / 'default_scene.png'}")
    table = out / "phase_table.parquet"
    settled = Scene(numerics={"periods": 40, "settle": True})
    frame = _sweep(echo, table, ["material_point", "mmd"], f"1e-3:1e2:{n}", f"1e-2:10:{n}",
                   base=settled, workers=workers, traces=True)
    for name in ("material_point", "mmd"):
        plot_phase_diagram(frame, out / f"phase_{name}.png", name)
    path, md = plot_compare(frame, ["material_point", "mmd"], out / "compare.png")
    echo(md)
    echo(f"wrote {table}, phase_material_point.png, phase_mmd.png, {path.name} in {out}")
    drift = plot_drift_map(frame, out / "drift_mmd.png", "mmd")
    mmd = frame[frame["model"] == "mmd"]
    unsettled = int(unsettled_cells(mmd).sum())
    creeping = int(creep_cells(mmd).sum())
    echo(f"wrote {drift.name}: mmd's drift ratio under its regime boundaries; every cell ran "
         f"until its drift settled; {hatch_note(unsettled, len(mmd))}; {creeping} cells creep "
         "(circled: a drift with no gross slip); the dashed and dotted lines are the normal and "
         "tangential contact resonances")
    page = write_explorer(table, out / "explore.html")
    echo(f"wrote {page.name}: both phase diagrams to hover, click and compare in a browser "
         "(one file, works offline)")
    fig2 = plot_fig2(out / "fig2_regimes.png")
    echo(f"wrote {fig2.name}: the four regimes' trajectories (the paper's Fig. 2), each run until "
         "its drift settled")
    # rolling: the same plane with the sphere free to turn (kappa = 2/5), side by side
    rot_table = out / "rotation_table.parquet"
    m_rot = max(2, (n + 1) // 2)
    rot = _sweep(echo, rot_table, ["material_point", "mmd"], f"1e-3:1e2:{m_rot}",
                 f"1e-2:10:{m_rot}", axes={"effects.rotation": "false,true"},
                 base=settled, workers=workers)
    rpath, rmd = plot_compare(rot, ["material_point", "mmd"], out / "rotation_compare.png",
                              by="effects.rotation")
    echo(rmd)
    echo(f"wrote {rot_table.name}, {rpath.name}: rotation off and on, a row per model; the "
         "last column marks where rotation changes a model's regime, the last row where the "
         "models disagree")
