"""Adaptive phase diagrams: refinement follows the regime boundaries, finds thin islands; resumable."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

import sawdrift as sd
from sawdrift.study.adaptive import adaptive_sweep, misclassified_area, regime_map

BASE = sd.Scene(numerics={"periods": 30})


@pytest.mark.slow
def test_adaptive_point_diagram_equals_the_uniform_one_with_fewer_cells(tmp_path):
    """Every region of the material point's diagram holds base points and the refinement ends
    within the budget, so the adaptive map equals the uniform 33 x 33 one except on periodic
    windows one grid cell wide: exact orbits (hop periods 8 to 17) inside the bouncing region,
    which no coarser node touches and which refinement therefore cannot find. Every wrong node
    must be such a window (its two neighbours along m* or along A* on the uniform grid hold
    another motion), or a bouncing node beside one that the adaptive map widens; and the
    adaptive map may miss no more nodes than the uniform map has on one-cell windows. Measured
    on 2026-11-27: 12 of 1089 nodes wrong, all on such windows (6 before unsettled irregular
    cells reported long-time means and more heavy cells settled on their exact orbits).

    The adaptive points are nodes of the uniform grid, so the uniform sweep resumes the adaptive
    sweep's table and runs only the other nodes (a cell's run is deterministic, so a node run
    once is the node run twice): 1089 runs instead of 1555."""
    table = tmp_path / "a.parquet"
    pts = adaptive_sweep("material_point", (1e-3, 1e2), (1e-2, 10.0), budget=700, base=9,
                         levels=2, scene=BASE, workers=1, table=table)
    computed_nodes = len(pd.read_parquet(table))
    # the 33 x 33 nodes exactly as the adaptive sweep spaces them (10 ** linspace of the logs)
    ms = [10.0 ** x for x in np.linspace(math.log10(1e-3), math.log10(1e2), 33)]
    amps = [10.0 ** y for y in np.linspace(math.log10(1e-2), math.log10(10.0), 33)]
    ran = []
    uniform = sd.sweep(["material_point"], points=[(m, a) for m in ms for a in amps], base=BASE,
                       workers=1, progress=False, table=table, on_row=ran.append)
    assert len(uniform) == 33 * 33 and len(ran) == len(uniform) - computed_nodes
    assert pts.attrs["computed"] < 700, "the refinement must end before the budget"
    assert pts.attrs["computed"] <= 0.45 * len(uniform)
    wrong, adaptive = _wrong_nodes(pts, uniform)
    # every wrong node is on a thin periodic window: a hop of period >= 3 in the uniform map,
    # one cell wide, that the adaptive one misses, or bouncing beside one that it widens
    thin = _one_cell_windows(uniform)
    key = list(zip(wrong["m_star"], wrong["amplitude"], strict=True))
    missed = np.array([k in thin for k in key]) & (wrong["hop_period"].to_numpy() >= 3)
    widened = (adaptive == "hopping") & (wrong["regime"].to_numpy() == "bouncing")
    assert (missed | widened).all(), wrong[["m_star", "amplitude", "regime", "hop_period"]]
    assert len(wrong) <= len(thin) + int(widened.sum())
    assert misclassified_area(pts, uniform) <= (len(thin) + int(widened.sum())) / len(uniform)
    # the refined points crowd the contact-loss boundary Gz = 4 pi^2 m* A* = 1 (closed form):
    # far more of them lie within a quarter decade of it than on the uniform grid
    def near(frame):
        gz = 4 * np.pi**2 * frame["m_star"] * frame["amplitude"]
        return float(np.mean(np.abs(np.log10(gz)) < 0.25))

    assert near(pts[~pts["inferred"]]) > 1.3 * near(uniform)


def _one_cell_windows(uniform: pd.DataFrame) -> set[tuple[float, float]]:
    """(m*, A*) of the uniform-grid nodes on an exact orbit (hop period >= 3) whose two
    neighbours along m* or along A* both hold another motion (regime or hop period)."""
    m_values = np.sort(uniform["m_star"].unique())
    a_values = np.sort(uniform["amplitude"].unique())
    grid = {(r.m_star, r.amplitude): (r.regime, r.hop_period) for r in uniform.itertuples()}
    out = set()
    for (m, a), motion in grid.items():
        if motion[0] != "hopping" or motion[1] < 3:
            continue
        i, j = int(np.searchsorted(m_values, m)), int(np.searchsorted(a_values, a))
        for di, dj in ((1, 0), (0, 1)):
            ends = [(i - di, j - dj), (i + di, j + dj)]
            if all(0 <= p < len(m_values) and 0 <= q < len(a_values)
                   and grid[(m_values[p], a_values[q])] != motion for p, q in ends):
                out.add((m, a))
    return out


def _wrong_nodes(pts: pd.DataFrame, uniform: pd.DataFrame) -> tuple[pd.DataFrame, np.ndarray]:
    """Uniform-grid rows whose regime the adaptive map (read as misclassified_area does) gives
    differently, and the adaptive map's regimes there."""
    m_values = np.sort(uniform["m_star"].unique())
    a_values = np.sort(uniform["amplitude"].unique())
    adaptive = regime_map(pts, m_values, a_values)
    i = np.searchsorted(m_values, uniform["m_star"].to_numpy())
    j = np.searchsorted(a_values, uniform["amplitude"].to_numpy())
    got = adaptive[i, j]
    wrong = got != uniform["regime"].to_numpy()
    return uniform[wrong], got[wrong]


#: fixed runs for the tests of the table and the engine: what they check (which rows the table
#: and the frame hold, that a rerun computes nothing, which engine ran) does not depend on how
#: long a cell runs, and settling (the default) ran the heavy cells on for 5e4 periods
FIXED = sd.Scene(numerics={"periods": 30, "settle": False})


@pytest.fixture(scope="module")
def small_adaptive(tmp_path_factory):
    """One adaptive sweep (9 x 9 fine grid from a 5 x 5 base, budget 150) with its table, shared
    by the table and resume tests: the pair took 29 s of wall time, ~3 s now (one quiet core)."""
    table = tmp_path_factory.mktemp("adaptive") / "a.parquet"
    kw = dict(budget=150, base=5, levels=2, scene=FIXED, workers=1, table=table)
    return table, kw, adaptive_sweep("material_point", (1e-3, 1e2), (1e-2, 10.0), **kw)


def test_the_table_holds_the_computed_points_and_the_frame_says_which_are_inferred(small_adaptive):
    table, _, pts = small_adaptive
    stored = pd.read_parquet(table)
    computed = pts[~pts["inferred"]]
    assert pts.attrs["computed"] == len(computed) == len(stored) > 25
    assert pts.attrs["inferred"] == int(pts["inferred"].sum()) > 0
    assert set(computed["cell_id"]) == set(stored["cell_id"])
    assert pts.loc[pts["inferred"], "cell_id"].isna().all()


def test_adaptive_sweep_resumes_without_recomputing(small_adaptive):
    _, kw, first = small_adaptive
    computed = []
    again = adaptive_sweep("material_point", (1e-3, 1e2), (1e-2, 10.0), on_row=computed.append, **kw)
    assert computed == [] and len(again) == len(first)
    assert again["regime"].tolist() == first["regime"].tolist()


def test_adaptive_sweep_starts_its_worker_processes_once(monkeypatch):
    """Every round of an adaptive sweep (base grid, then a confirm and a probe batch per level)
    runs on one process pool: a pool per round started its workers (imports, compiled loops)
    over again, 6 s of the 161 x 161 benchmark map."""
    import concurrent.futures

    from sawdrift.study import executor as ex

    pools = []

    class Counting(concurrent.futures.ProcessPoolExecutor):
        def __init__(self, *args, **kwargs):
            pools.append(1)
            super().__init__(*args, **kwargs)

    monkeypatch.setattr(ex, "ProcessPoolExecutor", Counting)
    rounds = []
    from sawdrift.study import sweep as sw

    original = sw.sweep

    def counting_sweep(*args, **kwargs):
        rounds.append(1)
        return original(*args, **kwargs)

    monkeypatch.setattr(sw, "sweep", counting_sweep)
    pts = adaptive_sweep("material_point", (1e-3, 1e2), (1e-2, 10.0), budget=60, base=5,
                         levels=2, scene=sd.Scene(numerics={"periods": 4, "settle": False}),
                         workers=2, progress=False)
    assert len(rounds) >= 2 and len(pools) == 1
    assert (~pts["inferred"]).sum() > 25


def test_adaptive_sweep_runs_the_engine_it_is_given():
    """Nine cells on the python engine: two fixed periods each show which engine ran (the
    python engine is ~100x slower than the compiled one; 10 settled periods took 9 s)."""
    pts = adaptive_sweep("material_point", (1e-2, 1.0), (0.1, 1.0), budget=9, base=3, levels=1,
                         scene=sd.Scene(numerics={"periods": 2, "settle": False}), workers=1,
                         engine="python")
    assert set(pts.loc[~pts["inferred"], "engine"]) == {"python"}


# -- the method on stand-in diagrams (a function of (m*, A*) instead of runs) -----------------

M, A = (1e-3, 1e4), (1e-2, 10.0)  # the benchmark's plane: 21 x 21 base, 161 x 161 fine grid
N = 161
DM, DA = 7.0 / 20, 3.0 / 20  # base spacings in decades


def _plane(features):
    """A diagram: 'stick' below the contact-loss line Gz = 1, 'drift_with' above, and thin
    features ``(regime, log m*, log A*, half width in m, half width in A)`` on top."""

    def regime_of(m, a):
        x, y = math.log10(m), math.log10(a)
        for name, xc, yc, wx, wy in features:
            if abs(x - xc) < wx and abs(y - yc) < wy:
                return name
        return "stick" if 4 * math.pi**2 * m * a < 1 else "drift_with"

    return regime_of


def _uniform(regime_of, n=N, m=M, a=A):
    ms, amps = np.geomspace(*m, n), np.geomspace(*a, n)
    return pd.DataFrame([(x, y, regime_of(x, y)) for x in ms for y in amps],
                        columns=["m_star", "amplitude", "regime"])


@pytest.mark.parametrize("cell", [(2, 12), (9, 3), (14, 17), (17, 8)])
def test_thin_islands_and_bands_between_the_base_points_are_found(cell):
    """A 0.07-decade island and a 0.07-decade band across the whole plane, each around the centre
    of a base cell and far from every base point (where the corner-only method saw nothing):
    both are found and the adaptive map equals the uniform 161 x 161 one at every node, with
    under 10 % of its points computed (measured 8.3 % for the first)."""
    i, j = cell
    xc, yc = -3.0 + (i + 0.5) * DM, -2.0 + (j + 0.5) * DA
    band_y = -2.0 + ((j + 10) % 20 + 0.5) * DA
    regime_of = _plane([("drift_against", xc, yc, 0.1, 0.035),
                        ("hopping", 0.0, band_y, 10.0, 0.035)])
    uniform = _uniform(regime_of)
    assert (uniform["regime"] == "drift_against").sum() >= 4
    pts = adaptive_sweep("mmd", M, A, budget=int(0.15 * N * N), base=21, levels=3,
                         regime_of=regime_of)
    computed = pts[~pts["inferred"]]
    assert {"drift_against", "hopping"} <= set(computed["regime"])
    assert misclassified_area(pts, uniform) == 0.0
    assert pts.attrs["computed"] < 0.10 * N * N


def test_sampled_inferred_points_are_checked_and_a_wrong_guess_is_refined():
    """A one-node island on the midpoint of a base cell's edge (both ends 'stick', so the
    midpoint is inferred): only the verification sample can see it. With ``verify=0`` it is
    missed (1 node of 33 x 33 wrong), with the default share that node is in the sample, is
    computed, and the map is exact."""
    m, a = (1e-3, 1e2), (1e-2, 10.0)
    key = (16, 22)  # on base column 16, between base rows 20 and 24 (base 9, levels 2)
    xc, yc = -3.0 + key[0] * 5.0 / 32, -2.0 + key[1] * 3.0 / 32
    regime_of = _plane([("drift_against", xc, yc, 0.05, 0.03)])
    uniform = _uniform(regime_of, 33, m, a)
    assert (uniform["regime"] == "drift_against").sum() == 1
    kw = dict(budget=600, base=9, levels=2, regime_of=regime_of)
    blind = adaptive_sweep("mmd", m, a, verify=0.0, **kw)
    assert misclassified_area(blind, uniform) == pytest.approx(1 / 33**2)
    checked = adaptive_sweep("mmd", m, a, **kw)
    assert checked.attrs["wrong_guesses"] >= 1
    assert misclassified_area(checked, uniform) == 0.0


#: a small adaptive map of the material point on the command line (5 x 5 base, 17 x 17 fine grid)
CLI_MAP = ("sweep", "--model", "material_point", "--adaptive", "--levels", "2", "--periods", "30",
           "--no-settle", "--workers", "1", "--no-progress", "--amplitude", "1e-2:10:5")


def test_adaptive_rerun_says_what_it_computed_and_what_the_table_holds(tmp_path):
    from .cli_call import run_main

    out = tmp_path / "adx.parquet"
    first = run_main(*CLI_MAP, "--m-star", "1e-3:1e2:5", "--budget", "60", "-o", out, check=True)
    held = len(pd.read_parquet(out))
    assert f"({held} cells computed: {held} in this run, 0 already in the table;" in first.stdout
    assert "now holds" not in first.stdout
    # a smaller budget computes nothing: it used to print "(25 cells computed, ...)"
    again = run_main(*CLI_MAP, "--m-star", "1e-3:1e2:5", "--budget", "25", "-o", out, check=True)
    assert "(25 cells computed: 0 in this run, 25 already in the table;" in again.stdout
    assert (f"{out} now holds {held} cells: {held - 25} more of this map's grid from an earlier "
            "run that refined other cells (another --budget or --levels)") in again.stdout
    assert len(pd.read_parquet(out)) == held
    # another m* range: a second map in the same table is said, not silently appended
    other = run_main(*CLI_MAP, "--m-star", "1e-1:1e3:5", "--budget", "25", "-o", out, check=True)
    total = len(pd.read_parquet(out))
    assert total > held
    line = next(t for t in other.stdout.splitlines() if "now holds" in t)
    assert line.startswith(f"{out} now holds {total} cells:")
    assert "from an earlier sweep outside this map" in line and "give a new -o" in line


def test_interrupted_adaptive_sweep_says_so_and_resumes(tmp_path, monkeypatch):
    from sawdrift.study.adaptive import Refinement

    from .cli_call import run_main

    original = Refinement._compute
    rounds = []

    def stop_in_second_round(self, keys):
        rounds.append(1)
        if len(rounds) > 1:
            raise KeyboardInterrupt
        original(self, keys)

    monkeypatch.setattr(Refinement, "_compute", stop_in_second_round)
    out = tmp_path / "ad.parquet"
    args = (*CLI_MAP, "--m-star", "1e-3:1e2:5", "--budget", "40", "-o", out)
    stopped = run_main(*args)
    assert stopped.returncode == 130 and "Traceback" not in stopped.stderr
    # the first round's table, no journal yet: the line names what is there
    assert not (tmp_path / "ad.parquet.journal.jsonl").exists()
    assert (f"interrupted: 25 finished cells are kept in {out}; run the same "
            "command again to resume") in stopped.stderr
    monkeypatch.setattr(Refinement, "_compute", original)
    resumed = run_main(*args, check=True)
    assert "already in the table;" in resumed.stdout
    assert ": 25 in this run" not in resumed.stdout


# -- bad arguments: one plain SceneError line naming the argument --------------------------------


def _stick(m: float, a: float) -> str:
    """A fake classifier: nothing runs."""
    return "stick"


@pytest.mark.parametrize("m_range", [(0, 1e2), (-1, 1e2), (1, 1), (1e2, 1e-3), (1, math.inf)])
def test_a_bad_m_range_is_one_plain_line(m_range):
    """Zero or negative ends used to raise a bare 'math domain error'; an empty range (1, 1) made
    999 cells at m* = 1 and a reversed one was silently accepted."""
    with pytest.raises(sd.SceneError, match=r"^adaptive: m_range = .* must be two positive "
                       r"numbers \(low, high\) with low < high"):
        adaptive_sweep("mmd", m_range, (1e-2, 10.0), budget=1000, regime_of=_stick)


def test_a_bad_a_range_is_one_plain_line():
    with pytest.raises(sd.SceneError, match=r"^adaptive: a_range = "):
        adaptive_sweep("mmd", (1e-3, 1e2), (0.0, 10.0), budget=1000, regime_of=_stick)


def test_an_unknown_model_is_refused_as_elsewhere_in_the_api():
    with pytest.raises(sd.ModelNotFoundError) as adaptive:
        adaptive_sweep("nope", (1e-3, 1e2), (1e-2, 10.0), budget=1000, regime_of=_stick)
    with pytest.raises(sd.ModelNotFoundError) as sweep:
        sd.sweep("nope", "0.1", "0.3")
    assert str(adaptive.value) == str(sweep.value)
    assert "\n" not in str(adaptive.value)


@pytest.mark.parametrize("budget", [0, 2_000_000])
def test_the_budget_error_names_the_argument_not_the_cli_flag(budget):
    with pytest.raises(sd.SceneError, match=rf"^adaptive: budget = {budget} ") as err:
        adaptive_sweep("mmd", (1e-3, 1e2), (1e-2, 10.0), budget=budget, regime_of=_stick)
    assert "--" not in str(err.value)


def test_adaptive_counts_say_they_cover_the_inferred_points(tmp_path):
    # the regime counts summed to the map's points (computed and inferred) while the table
    # holds the computed ones only, and nothing said so
    import re

    from .cli_call import run_main

    out = tmp_path / "ad.parquet"
    done = run_main(*CLI_MAP, "--m-star", "1e-3:1e2:5", "--budget", "60", "-o", out, check=True)
    held = len(pd.read_parquet(out))
    head = re.search(r"regimes of the map's (\d+) points \((\d+) computed, the ones the table "
                     r"holds; (\d+) inferred", done.stdout)
    assert head is not None, done.stdout
    points, computed, inferred = (int(g) for g in head.groups())
    assert computed == held and points == computed + inferred
    counts = [int(m) for m in re.findall(r"^\s+material_point\s+\w+: (\d+)", done.stdout, re.M)]
    assert sum(counts) == points


@pytest.mark.parametrize(("args", "needle"), [
    (["--adaptive", "--m-star", "0.1,0.5,1", "--amplitude", "0.3:1:3"], "not a list of values"),
    (["--levels", "2", "--m-star", "0.1,1", "--amplitude", "0.3,1"], "--levels belongs to --adaptive"),
    (["--budget", "50", "--m-star", "0.1,1", "--amplitude", "0.3,1"], "--budget belongs to --adaptive"),
])
def test_adaptive_options_given_where_they_would_be_ignored_are_one_line(args, needle, sawdrift_main,
                                                                          tmp_path):
    """sweep --adaptive took a comma list's two ends and never ran its middle values (0.5 of
    0.1,0.5,1), and --levels or --budget without --adaptive were ignored without a word."""
    proc = sawdrift_main("sweep", "--model", "mmd", *args, "-o", str(tmp_path / "t.parquet"))
    assert proc.returncode == 2 and needle in proc.stderr
    assert proc.stderr.strip().count("\n") == 0
    assert not (tmp_path / "t.parquet").exists()


def test_an_adaptive_map_counts_its_cells_on_one_counter_against_its_budget(tmp_path, capsys):
    """Each round's sweep drew its own counter, which restarted at 0 % and reached 100 % with
    "ETA 0.0 s" before the next round began; one counter now counts every cell the map runs,
    out of its budget, never going back."""
    import re

    base = sd.Scene(model="mmd", numerics={"periods": 20, "settle": False})
    sd.adaptive_sweep("mmd", (1e-2, 1.0), (0.05, 2.0), budget=30, base=3, levels=1, scene=base,
                      table=tmp_path / "a.parquet", workers=1, progress=True)
    counts = [int(m) for m in re.findall(r"(\d+)/30 cell", capsys.readouterr().err)]
    assert counts and counts == sorted(counts) and counts[-1] <= 30


@pytest.mark.parametrize(("kw", "said", "not_said"), [
    ({"levels": -1}, "levels = -1 must be in [0, 10]", "base ="),
    ({"base": 1}, "base = 1 must be in [2, 401]", "levels ="),
])
def test_an_adaptive_bound_names_only_the_value_outside_it(kw, said, not_said):
    """--levels -1 was told 'base = 21 must be in [2, 401] ... and levels = -1 in [0, 10]',
    quoting a base that was valid."""
    with pytest.raises(sd.SceneError) as err:
        adaptive_sweep("mmd", (1e-3, 1e2), (1e-2, 10.0), budget=2000, **kw)
    assert said in str(err.value) and not_said not in str(err.value)
