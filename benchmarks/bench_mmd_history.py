"""Cost per step of the ``mmd`` kernel versus history length (a script, not a test).

The memory-diagram kernel claims amortized O(1) work per step, independent of how long the
history is (the memory diagrams of Aleshin et al. 2015, IJSS 60-61, held as a stack, see
``sawdrift_builtin.mmd_kernel``). This drives the compiled contact (the slots of
``sawdrift.contact.slots`` composed around the memory-diagram step) through a 1e4-step and a
1e6-step random history (mean-reverting a* around 1, random-walk b*) and prints ns/step for each
and their ratio, which should be within 20 % of 1.

The kernel is timed in a compiled loop over preallocated, already-touched output arrays, so the
figure is the contact law's cost alone; ``ContactHistory.drive`` (which allocates its outputs) is
timed too, for information. Best of several repeats; on a shared machine expect a few ns/step of
noise.

Run: ``python benchmarks/bench_mmd_history.py``
"""

from __future__ import annotations

import time

import numpy as np
from numba import njit

from sawdrift import ContactHistory
from sawdrift_builtin.mmd import MemoryDiagramModel

_KERNEL = MemoryDiagramModel.kernel  # the compiled contact: the slots around mmd's step
_force = _KERNEL.force


def random_history(n: int, seed: int = 2024) -> tuple[np.ndarray, np.ndarray]:
    """a*: Ornstein-Uhlenbeck around 1 (rarely leaves contact); b*: Gaussian random walk.

    The same seed gives the same leading steps, so the short history is the start of the long one.
    """
    a = np.empty(n)
    x = 1.0
    da = np.random.default_rng(seed).normal(0.0, 0.03, n)
    for k in range(n):
        x += 0.02 * (1.0 - x) + da[k]
        a[k] = x
    b = np.cumsum(np.random.default_rng(seed + 1).normal(0.0, 0.05, n))
    return a, b


@njit
def _run(fs, is_, pp, a, b, n_out, t_out):
    for k in range(a.size):
        n_out[k], t_out[k] = _force(fs, is_, pp, a[k], b[k], 0.0, 0.0)


def kernel_ns_per_step(n: int, batch: int, repeats: int = 7) -> tuple[float, int]:
    """Kernel time per step (ns) and the memory-point high-water mark.

    One timing runs ``batch`` fresh histories of ``n`` steps back to back, so short and long
    histories are timed over the same total work (about 1e6 steps) and see the same machine
    noise; the best of ``repeats`` timings is reported.
    """
    model = MemoryDiagramModel()
    a, b = random_history(n)
    nf, ni = model.state_sizes()
    fs = np.zeros(nf)
    is_ = np.zeros(ni, dtype=np.int64)
    pp = model.packed_params()
    n_out = np.ones(n)
    t_out = np.ones(n)
    best = np.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(batch):
            _KERNEL.reset(fs, is_, pp)
            _run(fs, is_, pp, a, b, n_out, t_out)
        best = min(best, time.perf_counter() - t0)
    return 1e9 * best / (n * batch), int(is_[1])


def drive_ns_per_step(n: int, repeats: int) -> float:
    """Best-of-``repeats`` time per step (ns) of ``ContactHistory.drive`` (allocates outputs)."""
    model = MemoryDiagramModel()
    a, b = random_history(n)
    best = np.inf
    for _ in range(repeats):
        history = ContactHistory(model)
        t0 = time.perf_counter()
        history.drive(a, b)
        best = min(best, time.perf_counter() - t0)
    return 1e9 * best / n


def main() -> None:
    kernel_ns_per_step(1000, 1, 1)  # compile
    ContactHistory(MemoryDiagramModel()).drive(np.ones(10), np.zeros(10))
    short, hw_short = kernel_ns_per_step(10_000, batch=100)
    long, hw_long = kernel_ns_per_step(1_000_000, batch=1)
    print(f"kernel, 1e4 steps: {short:6.1f} ns/step  (max memory points {hw_short})")
    print(f"kernel, 1e6 steps: {long:6.1f} ns/step  (max memory points {hw_long})")
    ratio = long / short
    verdict = "PASS" if abs(ratio - 1.0) <= 0.2 else "FAIL"
    print(f"ratio 1e6/1e4: {ratio:.3f}  [{verdict}: within 20 %]")
    d_short = drive_ns_per_step(10_000, repeats=200)
    d_long = drive_ns_per_step(1_000_000, repeats=7)
    print(
        f"ContactHistory.drive: 1e4 {d_short:6.1f} ns/step, 1e6 {d_long:6.1f} ns/step "
        f"(ratio {d_long / d_short:.3f}; includes output allocation)"
    )


if __name__ == "__main__":
    import argparse

    # no options: --help prints what the script does and where it writes, and runs nothing
    argparse.ArgumentParser(description=__doc__,
                            formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    main()
