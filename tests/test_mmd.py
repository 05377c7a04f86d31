"""The ``mmd`` contact model (Method of Memory Diagrams, Aleshin et al. 2015, IJSS 60-61).

Oracles: docs/physics.md (Mindlin & Deresiewicz 1953 monotonic and Masing unloading curves,
loop area, proportional loading, general profiles); plus exactness of the straight-path rule,
kernel == readable reference, and precision and bounded memory over a long drifting history.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import simpson

from sawdrift import ContactHistory, Profile, get_model
from sawdrift.analytic import loop_area
from sawdrift_builtin import mmd_kernel
from sawdrift_builtin.mmd import MemoryDiagramModel, MemoryDiagramParams
from sawdrift_builtin.mmd_reference import MemoryDiagramReference

ENGINES = ["compiled", "python"]
SPHERE = MemoryDiagramModel()


def power(p: float) -> Profile:
    return Profile(shape="power", exponent=p)


def load_normally(history: ContactHistory, a: float, steps: int = 8) -> None:
    """Compress from a* = 0 to ``a`` at b* = 0."""
    history.drive(np.linspace(0.0, a, steps + 1)[1:], np.zeros(steps))


def uneven(start: float, stop: float, steps: int, seed: int) -> np.ndarray:
    """``steps`` strictly monotone points from just after ``start`` to ``stop`` (uneven sizes)."""
    w = np.random.default_rng(seed).uniform(0.2, 1.0, steps)
    return start + (stop - start) * np.cumsum(w) / w.sum()


@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("a", [0.7, 1.3])
def test_cattaneo_mindlin_then_masing(engine: str, a: float) -> None:
    """Monotonic T* = a^1.5 - (a - b)^1.5, then Masing unloading and reloading, to 1e-12."""
    h = ContactHistory(SPHERE, engine)
    load_normally(h, a)
    b1 = 0.6 * a
    b = uneven(0.0, b1, 37, seed=1)
    n, t = h.drive(np.full(b.size, a), b)
    np.testing.assert_allclose(n, a**1.5, rtol=0, atol=1e-12)
    np.testing.assert_allclose(t, a**1.5 - (a - b) ** 1.5, rtol=0, atol=1e-12)
    t1 = t[-1]
    b = uneven(b1, -b1, 53, seed=2)
    _, t = h.drive(np.full(b.size, a), b)
    masing = t1 - 2 * a**1.5 * (1 - (1 - (b1 - b) / (2 * a)) ** 1.5)
    np.testing.assert_allclose(t, masing, rtol=0, atol=1e-12)
    assert t[-1] == pytest.approx(-t1, abs=1e-12)
    b = uneven(-b1, b1, 41, seed=3)
    _, t = h.drive(np.full(b.size, a), b)
    np.testing.assert_allclose(
        t, -t1 + 2 * a**1.5 * (1 - (1 - (b + b1) / (2 * a)) ** 1.5), rtol=0, atol=1e-12
    )
    # beyond b* = a* from the virgin curve's end the whole contact slides: T* = N*
    b = uneven(b1, 3 * a, 20, seed=4)
    n, t = h.drive(np.full(b.size, a), b)
    np.testing.assert_allclose(t[b >= b1 + 2 * a], n[b >= b1 + 2 * a], rtol=0, atol=1e-12)


@pytest.mark.parametrize("q", [0.3, 0.7, 1.0])
def test_loop_area(q: float) -> None:
    """Energy dissipated per cycle between T* = +-q N* matches W* within 1e-6 relative.

    The cycle runs between b* = +-b_q with a* (1 - (b_q/a*))^(3/2) = 1 - q, the displacements
    that give T* = +-q N* (Masing). The integral of T* db* over each branch uses the model's own
    T* at 4001 points and Simpson's rule (the branches are smooth; for q = 1 the end of each
    branch behaves like x^(3/2), Simpson's error there is O(h^2.5) ~ 1e-8).
    """
    a = 1.3
    bq = a * (1 - (1 - q) ** (2 / 3))
    m = 4000
    h = ContactHistory(SPHERE)
    load_normally(h, a)
    h.drive(np.full(m // 2, a), np.linspace(0.0, bq, m // 2 + 1)[1:])
    down = np.linspace(bq, -bq, m + 1)
    up = down[::-1]
    _, t_down = h.drive(np.full(m, a), down[1:])
    _, t_up = h.drive(np.full(m, a), up[1:])
    n = a**1.5
    assert t_down[-1] == pytest.approx(-q * n, abs=1e-12)
    assert t_up[-1] == pytest.approx(q * n, abs=1e-12)
    t_down = np.concatenate([[q * n], t_down])
    t_up = np.concatenate([[-q * n], t_up])
    w = simpson(t_down, x=down) + simpson(t_up, x=up)
    assert w == pytest.approx(loop_area(a, q), rel=1e-6)


@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("p", [1.0, 1.5, 2.0])
@pytest.mark.parametrize("lam", [0.3, 0.9])
def test_proportional_loading_never_slips(engine: str, p: float, lam: float) -> None:
    """b* = lambda a* from zero: T* = lambda N*(a*) within 1e-9 (and O(1) memory points)."""
    model = MemoryDiagramModel(profile=power(p))
    h = ContactHistory(model, engine)
    a = uneven(0.0, 1.7, 60, seed=5)
    n, t = h.drive(a, lam * a)
    np.testing.assert_allclose(n, a**p, rtol=1e-13)
    np.testing.assert_allclose(t, lam * n, rtol=0, atol=1e-9)
    if engine == "compiled":
        assert len(model.memory_points(h)) <= 3


@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("shape", ["cone", "flat"])
def test_general_profile_monotonic_and_masing(engine: str, shape: str) -> None:
    """T* = N(a) - N(a - b) (monotonic), Masing T* = T1 - 2 [N(a) - N(a - (b1 - b)/2)]."""
    model = MemoryDiagramModel(profile=Profile(shape=shape))
    p = model.profile.p

    def nlaw(x: np.ndarray) -> np.ndarray:
        return np.maximum(x, 0.0) ** p

    a = 1.1
    h = ContactHistory(model, engine)
    load_normally(h, a)
    b = uneven(0.0, 1.5 * a, 45, seed=6)
    _, t = h.drive(np.full(b.size, a), b)
    np.testing.assert_allclose(t, nlaw(a) - nlaw(a - np.minimum(b, a)), rtol=0, atol=1e-12)

    h = ContactHistory(model, engine)
    load_normally(h, a)
    b1 = 0.5 * a
    _, t = h.drive(np.full(10, a), uneven(0.0, b1, 10, seed=7))
    t1 = t[-1]
    b = uneven(b1, -b1, 30, seed=8)
    _, t = h.drive(np.full(b.size, a), b)
    np.testing.assert_allclose(
        t, t1 - 2 * (nlaw(a) - nlaw(a - (b1 - b) / 2)), rtol=0, atol=1e-12
    )


def random_history(n: int, seed: int, a_low: float = -0.3) -> tuple[np.ndarray, np.ndarray]:
    """Piecewise-linear vertices: a* in [a_low, 1.6], b* a random walk with large steps."""
    rng = np.random.default_rng(seed)
    return rng.uniform(a_low, 1.6, n), np.cumsum(rng.normal(0.0, 0.4, n))


@pytest.mark.parametrize("engine", ENGINES)
def test_contact_loss_forgets_everything(engine: str) -> None:
    """a* <= 0 gives N* = T* = 0; the next contact is that of a fresh history (to 1e-12)."""
    a, b = random_history(40, seed=9, a_low=0.2)
    h = ContactHistory(SPHERE, engine)
    h.drive(a, b)
    assert SPHERE.memory_points(h).shape[0] > 2
    n, t = h.advance(-0.2, 7.0)
    assert (n, t) == (0.0, 0.0)
    assert SPHERE.memory_points(h).shape[0] == 0
    a2, b2 = random_history(30, seed=10, a_low=0.1)
    b2 = b2 + 7.5
    _, t_after = h.drive(a2, b2)
    # the straight path from (-0.2, 7.0) enters contact at a* = 0, where b* = b_c
    bc = 7.0 + (b2[0] - 7.0) * 0.2 / (a2[0] + 0.2)
    _, t_fresh = ContactHistory(SPHERE, engine).drive(a2, b2 - bc)
    np.testing.assert_allclose(t_after, t_fresh, rtol=0, atol=1e-12)


@pytest.mark.parametrize("engine", ENGINES)
def test_straight_path_is_exact(engine: str) -> None:
    """Splitting each straight segment of a history into sub-steps changes nothing (1e-12)."""
    a, b = random_history(25, seed=11)
    coarse = ContactHistory(SPHERE, engine)
    fine = ContactHistory(SPHERE, engine)
    sub = 7
    for k in range(a.size):
        a0, b0 = (0.0, 0.0) if k == 0 else (a[k - 1], b[k - 1])
        s = np.linspace(0.0, 1.0, sub + 1)[1:]
        _, t_fine = fine.drive(a0 + s * (a[k] - a0), b0 + s * (b[k] - b0))
        _, t_coarse = coarse.advance(a[k], b[k])
        assert t_fine[-1] == pytest.approx(t_coarse, abs=1e-12)


@pytest.mark.parametrize("p", [1.0, 1.5, 2.0, 2.5, 3.3])
def test_kernel_matches_reference(p: float) -> None:
    """Compiled stack kernel == readable reference on random histories (1e-12)."""
    model = MemoryDiagramModel(profile=power(p))
    rng = np.random.default_rng(12)
    for kind in range(3):
        n = 400
        if kind == 0:  # big random jumps, contact lost and regained
            a, b = random_history(n, seed=int(rng.integers(1 << 30)))
        elif kind == 1:  # small random walk: deep memory
            a = 1 + np.cumsum(rng.normal(0, 0.02, n))
            b = np.cumsum(rng.normal(0, 0.03, n))
        else:  # oscillation with drift
            k = np.arange(n)
            a = 1 + 0.5 * np.sin(0.3 * k) + rng.normal(0, 0.02, n)
            b = np.cumsum(rng.normal(0, 0.1, n)) + 0.05 * k
        n_c, t_c = ContactHistory(model, "compiled").drive(a, b)
        n_p, t_p = ContactHistory(model, "python").drive(a, b)
        np.testing.assert_allclose(n_c, n_p, rtol=1e-14, atol=0)
        np.testing.assert_allclose(t_c, t_p, rtol=0, atol=1e-12)
        assert np.all(np.abs(t_c) <= n_c * (1 + 1e-12))
        # the readable reference's own force(), entry and loss written out apart from the slots
        oracle = MemoryDiagramReference(p)
        n_o, t_o = np.array([oracle.force(x, y) for x, y in zip(a, b, strict=True)]).T
        np.testing.assert_allclose(n_c, n_o, rtol=1e-14, atol=0)
        np.testing.assert_allclose(t_c, t_o, rtol=0, atol=1e-12)


vertex = st.tuples(
    st.floats(-0.5, 2.0, allow_nan=False), st.floats(-3.0, 3.0, allow_nan=False)
)


@settings(max_examples=60, deadline=None)
@given(
    st.lists(vertex, min_size=1, max_size=25),
    st.sampled_from([1.0, 1.5, 2.0, 2.7]),
)
def test_kernel_matches_reference_property(vertices: list[tuple[float, float]], p: float) -> None:
    """Hypothesis: any piecewise-linear history, any profile: kernel == reference (1e-12)."""
    model = MemoryDiagramModel(profile=power(p))
    a, b = np.array(vertices).T
    _, t_c = ContactHistory(model, "compiled").drive(a, b)
    _, t_p = ContactHistory(model, "python").drive(a, b)
    np.testing.assert_allclose(t_c, t_p, rtol=0, atol=1e-12)


def drifting_history(k: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """a* oscillating around 1; b* advancing in smooth strokes (mean 1.1 per step) with
    superposed small oscillations, so stick, partial slip and sliding all occur."""
    a = 1 + 0.3 * np.sin(2 * np.pi * k / 31.3) + 0.05 * np.sin(2 * np.pi * k / 4.3)
    b = (
        1.1 * (k - 200 / (2 * np.pi) * np.sin(2 * np.pi * k / 200))
        + 0.3 * np.sin(2 * np.pi * k / 13.7)
        + 0.1 * np.sin(2 * np.pi * k / 5.9)
    )
    return a, b


def test_drifting_million_steps_bounded_memory_and_precise() -> None:
    """1e6 steps with b* drifting past 1e6: memory stays bounded and T* stays exact.

    While |b*| > 1e6, the kernel's T* agrees within 1e-9 with a reference rebuilt from the
    stored kinks and then driven alongside it for 2000 more steps.
    """
    h = ContactHistory(SPHERE)
    total = 1_000_000
    chunk = 100_000
    high_water = []
    for start in range(0, total, chunk):
        a, b = drifting_history(np.arange(start, start + chunk, dtype=np.float64))
        n, t = h.drive(a, b)
        high_water.append(int(h._is[1]))
        assert np.all(np.abs(t) <= n * (1 + 1e-12))
    assert b[-1] > 1e6
    assert high_water[-1] <= 32
    assert high_water[-1] == high_water[1]  # no growth after the first 2e5 steps
    assert h._is[2] > 1000  # the offset was re-based many times
    points = SPHERE.memory_points(h)
    ref = MemoryDiagramReference.from_kinks(1.5, a[-1], b[-1], points)
    assert ref.tangential_force() == pytest.approx(t[-1], abs=1e-9)
    a2, b2 = drifting_history(np.arange(total, total + 2000, dtype=np.float64))
    _, t_kernel = h.drive(a2, b2)
    t_ref = np.array([ref.force(x, y)[1] for x, y in zip(a2, b2, strict=True)])
    assert np.all(np.abs(b2) > 1e6)
    np.testing.assert_allclose(t_kernel, t_ref, rtol=0, atol=1e-9)


@pytest.mark.parametrize("engine", ENGINES)
def test_contact_loss_keeps_the_high_water_mark_reset_clears_it(engine: str) -> None:
    """The slots reset the law on contact loss (its memory points go, its high-water mark of
    kinks stays) and on a history reset (both go)."""
    a, b = random_history(60, seed=14, a_low=0.2)
    h = ContactHistory(SPHERE, engine)
    h.drive(a, b)
    h.advance(-0.1, 0.0)
    assert SPHERE.memory_points(h).shape[0] == 0
    if engine == "compiled":
        assert h._is[0] == 0 and h._is[1] > 3
        h.reset()
        assert h._is[1] == 0
    h.reset()
    assert h.advance(0.8, 0.2) == ContactHistory(SPHERE, engine).advance(0.8, 0.2)


def test_capacity_overflow_raises() -> None:
    """More memory points than ``max_memory_points``: a clear SawdriftError, not a crash."""
    model = MemoryDiagramModel(MemoryDiagramParams(max_memory_points=16))
    h = ContactHistory(model)
    k = np.arange(1, 40)
    with pytest.raises(mmd_kernel.MemoryCapacityError, match="max_memory_points"):
        h.drive(0.1 * k, 0.01 * (-1.0) ** k)  # zig-zag entry profiles: one kink per step


def test_copy_replays_identically() -> None:
    """All history lives in the state arrays: a checkpoint replays bit for bit, trials are
    side-effect free."""
    a, b = random_history(200, seed=13)
    h = ContactHistory(SPHERE)
    h.drive(a[:100], b[:100])
    trial = h.trial(a[100], b[100])
    clone = h.copy()
    n_h, t_h = h.drive(a[100:], b[100:])
    _, t_c = clone.drive(a[100:], b[100:])
    np.testing.assert_array_equal(t_h, t_c)
    assert trial == (n_h[0], t_h[0])


def test_registered_through_entry_point() -> None:
    """``mmd`` is found by name through the sawdrift.models entry points."""
    assert get_model("mmd") is MemoryDiagramModel
    info = MemoryDiagramModel.describe()
    assert info["parameters"]["max_memory_points"]["default"] == 65536
