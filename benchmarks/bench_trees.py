"""Compare the speed of source trees (e.g. before and after a refactor), alternating them.

Each measurement runs in its own process with ``PYTHONPATH`` set to one tree, so any checkout can
be measured (``git worktree add /tmp/base <commit>``); this script imports nothing of sawdrift.
Per round and tree, in an order that reverses every round (A B, B A, A B, ...):

* ``cold``: empty compile caches (``SAWDRIFT_CACHE_DIR`` and ``NUMBA_CACHE_DIR`` a fresh folder),
  one process per model: import time, the first short run (compile) and the same run again;
  ``compile_s`` = first - second;
* ``warm``: the same caches, a new process: the first short run now loads the cache
  (``load_s`` = first - second), then the best of 5 wall times per step of a 200-period wave run
  (what ``sawdrift bench speed`` reports), and for the contact kernels the best per-sample time
  along the prescribed random history of 50 cycles x 50 samples (``vs_mdr``);
* ``process``: ``python -m sawdrift run --model M --json`` as a whole process, warm caches;
* ``sweep`` (with ``--sweep``): the serial 15 x 15 material point sweep of the validation's
  regime diagrams (m* 1e-3..1e2, A* 1e-2..10, 40 periods, mu 0.1, nu 0.3, one worker), warm;
* ``sweep41`` (with ``--mmd-sweep``): the 41 x 41 mmd sweep of ``bench speed`` (default executor,
  warm caches), with the default settle and with fixed 60-period runs (``_nosettle``).

Run: ``python benchmarks/bench_trees.py base=/tmp/wtbase new=/tmp/wtB --rounds 3 [--sweep]``;
the medians over rounds and each tree's ratio to the first one are printed, every sample is
appended to ``--out`` (JSON lines).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

CHILD = r'''
import json, math, sys, time
t0 = time.perf_counter()
import numpy as np
import sawdrift
from sawdrift import Scene, run
t_import = time.perf_counter() - t0
what, model, mode = sys.argv[1], sys.argv[2], sys.argv[3]
out = {"file": sawdrift.__file__, "import_s": t_import}

def best(fn, n):
    b = math.inf
    for _ in range(n):
        t = time.perf_counter(); r = fn(); b = min(b, time.perf_counter() - t)
    return b, r

def wave(model, periods):
    return Scene(model=model, particle={"m_star": 0.1}, drive={"amplitude": 0.316},
                 numerics={"periods": periods})

def history(model, params):
    from sawdrift.contact.base import ContactHistory
    scene = Scene(model=model, model_params=params, drive={"kind": "prescribed"})
    try:  # the scene binds to its model in the contact layer (trees after 2026-11-25)
        from sawdrift.contact.binding import model_for
    except ImportError:
        return ContactHistory(scene.model_instance(), "compiled")
    return ContactHistory(model_for(scene), "compiled")

if what == "wave":
    short = wave(model, 2.0)
    t = time.perf_counter(); run(short); first = time.perf_counter() - t
    t = time.perf_counter(); run(short); again = time.perf_counter() - t
    out.update(first_s=first, again_s=again, compile_s=first - again)
    if mode == "warm":
        long = wave(model, 200.0)
        w, r = best(lambda: run(long), 5)
        out.update(ns_per_step=1e9 * w / r.steps, steps=r.steps)
        if model == "mmd":
            py = wave("mmd", 20.0)
            run(py, engine="python")
            out["python_20_periods_s"] = best(lambda: run(py, engine="python"), 2)[0]
elif what == "history":
    from sawdrift.scene.schema import Prescribed
    try:
        from sawdrift.dynamics.prescribed import prescribed_history
    except ImportError:
        from sawdrift.dynamics.runner import prescribed_history
    params = {"strips": 1024} if model == "mdr" else {}
    a, b = prescribed_history(Prescribed(waveform="random", cycles=50, samples_per_segment=50,
                                         seed=11))
    t = time.perf_counter(); history(model, params).drive(a[:200], b[:200])
    first = time.perf_counter() - t
    t = time.perf_counter(); history(model, params).drive(a[:200], b[:200])
    again = time.perf_counter() - t
    out.update(first_s=first, again_s=again, compile_s=first - again)
    if mode == "warm":
        def one():
            h = history(model, params)
            t = time.perf_counter(); h.drive(a, b); return time.perf_counter() - t
        out["ns_per_step"] = 1e9 * min(one() for _ in range(5 if model == "mdr" else 25)) / a.size
elif what == "sweep":
    from sawdrift import sweep
    base = Scene(model=model, material={"mu": 0.1, "nu": 0.3}, numerics={"periods": 40.0})
    run(base.with_updates(**{"numerics.periods": 2.0}))
    t = time.perf_counter()
    table = sweep([model], "1e-3:1e2:15", "1e-2:10:15", base=base, progress=False, workers=1)
    out.update(sweep_s=time.perf_counter() - t, cells=len(table),
               cpu_s_in_runs=float(table["wall_time_s"].sum()),
               steps=int(table["steps"].sum()))
elif what == "sweep41":
    from sawdrift import sweep
    for settle in (None, False):  # the default, and fixed 60-period runs
        base = Scene(model=model) if settle is None else Scene(model=model, numerics={"settle": False})
        t = time.perf_counter()
        table = sweep(model, "1e-3:1e2:41", "1e-2:10:41", base=base, progress=False)
        tag = "" if settle is None else "_nosettle"
        out.update({f"sweep41{tag}_s": time.perf_counter() - t,
                    f"sweep41{tag}_steps": int(table["steps"].sum()),
                    f"sweep41{tag}_cpu_in_runs_s": float(table["wall_time_s"].sum())})
print("RESULT " + json.dumps(out))
'''

#: (kind, model) measured per round; the cold ones get their own empty caches
ITEMS = (("wave", "material_point"), ("wave", "mmd"), ("history", "mmd"), ("history", "mdr"))


def child(tree: Path, cache: Path, args: list[str]) -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(str(tree / p) for p in
                                        ("src", "plugins", "plugins/sawdrift-tsuji"))
    env["SAWDRIFT_CACHE_DIR"] = str(cache / "sawdrift")
    env["NUMBA_CACHE_DIR"] = str(cache / "numba")
    proc = subprocess.run([sys.executable, "-c", CHILD, *args], cwd=tree, env=env,
                          capture_output=True, text=True)
    line = [ln for ln in proc.stdout.splitlines() if ln.startswith("RESULT ")]
    if proc.returncode or not line:
        raise RuntimeError(f"{tree} {args}: {proc.stderr[-2000:]}")
    got = json.loads(line[0][7:])
    if not got["file"].startswith(str(tree)):
        raise RuntimeError(f"{tree}: imported {got['file']}")
    return got


def whole_process(tree: Path, cache: Path, model: str, repeats: int = 3) -> float:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(str(tree / p) for p in
                                        ("src", "plugins", "plugins/sawdrift-tsuji"))
    env["SAWDRIFT_CACHE_DIR"] = str(cache / "sawdrift")
    env["NUMBA_CACHE_DIR"] = str(cache / "numba")
    cmd = [sys.executable, "-m", "sawdrift", "run", "--model", model, "--json"]
    subprocess.run(cmd, cwd=tree, env=env, capture_output=True, check=True)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run(cmd, cwd=tree, env=env, capture_output=True, check=True)
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def measure(name: str, tree: Path, work: Path, rnd: int, sweep: bool, only: set[str],
            mmd_sweep: bool = False) -> list[dict]:
    rows = []
    for kind, model in ITEMS:
        key = f"{kind}:{model}"
        if only and key not in only:
            continue
        cache = work / f"{name}-{rnd}-{kind}-{model}"
        shutil.rmtree(cache, ignore_errors=True)
        cold = child(tree, cache, [kind, model, "cold"])
        warm = child(tree, cache, [kind, model, "warm"])
        row = {"tree": name, "round": rnd, "item": key, "cold_import_s": cold["import_s"],
               "compile_s": cold["compile_s"], "load_s": warm["compile_s"],
               "warm_import_s": warm["import_s"], "ns_per_step": warm["ns_per_step"]}
        if "python_20_periods_s" in warm:
            row["python_20_periods_s"] = warm["python_20_periods_s"]
        if kind == "wave":
            row["process_run_s"] = whole_process(tree, cache, model)
        if mmd_sweep and key == "wave:mmd":
            got = child(tree, cache, ["sweep41", model, "warm"])
            row.update({k: v for k, v in got.items() if k.startswith("sweep41")})
        if sweep and key == "wave:material_point":
            got = child(tree, cache, ["sweep", model, "warm"])
            row.update(sweep_s=got["sweep_s"], sweep_cpu_in_runs_s=got["cpu_s_in_runs"],
                       sweep_steps=got["steps"])
        shutil.rmtree(cache, ignore_errors=True)
        rows.append(row)
        print(json.dumps(row), flush=True)
    return rows


def summary(rows: list[dict], names: list[str]) -> str:
    metrics = ("compile_s", "load_s", "ns_per_step", "process_run_s", "python_20_periods_s",
               "sweep_s", "sweep_cpu_in_runs_s", "sweep41_s", "sweep41_steps", "sweep41_nosettle_s",
               "sweep41_nosettle_steps", "warm_import_s")
    items = list(dict.fromkeys(r["item"] for r in rows))
    lines = ["| item | metric | " + " | ".join(names) + " | " +
             " | ".join(f"{n}/{names[0]}" for n in names[1:]) + " |",
             "|---|---|" + "---|" * (2 * len(names) - 1)]
    for item in items:
        for m in metrics:
            med = {}
            ratios = {}
            for n in names:
                vals = [r[m] for r in rows if r["item"] == item and r["tree"] == n and m in r]
                if vals:
                    med[n] = statistics.median(vals)
            if len(med) != len(names):
                continue
            for n in names[1:]:  # the ratio within each round, then its median
                per = []
                for rnd in sorted({r["round"] for r in rows}):
                    a = [r[m] for r in rows if r["item"] == item and r["tree"] == names[0]
                         and r["round"] == rnd and m in r]
                    b = [r[m] for r in rows if r["item"] == item and r["tree"] == n
                         and r["round"] == rnd and m in r]
                    if a and b and a[0] > 0:
                        per.append(b[0] / a[0])
                ratios[n] = statistics.median(per) if per else float("nan")
            fmt = "{:.1f}" if m == "ns_per_step" else "{:.4g}" if m.endswith("_steps") else "{:.3f}"
            lines.append(f"| {item} | {m} | " + " | ".join(fmt.format(med[n]) for n in names)
                         + " | " + " | ".join(f"{ratios[n]:.3f}" for n in names[1:]) + " |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("trees", nargs="+", help="NAME=PATH of a source tree (the first is the reference)")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--sweep", action="store_true", help="also the serial 15 x 15 material point sweep")
    parser.add_argument("--mmd-sweep", action="store_true",
                        help="also the 41 x 41 mmd sweep of `bench speed` (default executor), with "
                             "the default settle and with fixed 60-period runs")
    parser.add_argument("--only", default="", help="comma-separated items, e.g. wave:material_point")
    parser.add_argument("--out", default="bench_trees.jsonl", help="JSON lines of every sample")
    args = parser.parse_args(argv)
    trees = [(t.split("=", 1)[0], Path(t.split("=", 1)[1]).resolve()) for t in args.trees]
    only = {s for s in args.only.split(",") if s}
    rows: list[dict] = []
    work = Path(tempfile.mkdtemp(prefix="bench_trees_"))
    try:
        for rnd in range(args.rounds):
            order = trees if rnd % 2 == 0 else trees[::-1]
            for name, tree in order:
                got = measure(name, tree, work, rnd, args.sweep, only, args.mmd_sweep)
                rows += got
                with open(args.out, "a") as fh:
                    for r in got:
                        fh.write(json.dumps(r) + "\n")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print(summary(rows, [n for n, _ in trees]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
