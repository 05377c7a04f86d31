"""Tests of ``hertz_mindlin_dem``: the incremental Mindlin spring with a Coulomb cap of DEM codes.

Facts checked: Mindlin's (1949) initial stiffness, the exact Coulomb cap, the LAMMPS
``mindlin_rescale`` rule, path exactness, and the departure of its hysteresis loop from the
Mindlin & Deresiewicz (1953) / Masing loop of docs/physics.md.

Loop comparison. At fixed a* both laws are driven through the same displacement cycle
b* = B -> -B -> B, with B = B_q the amplitude at which the Mindlin law reaches +-q N*
(sphere: B_q = a* [1 - (1 - q)^(2/3)]). The DEM spring (stiffness k = N*'(a*), cap N*) is
elastic-perfectly-plastic, so its loop is a parallelogram

    W*_DEM = 4 N* (B - N*/k)  if B > N*/k = a*/p,  else 0,

which for the sphere is reached only at q > 1 - (1/3)^(3/2) = 0.8075 (of 0.3, 0.7, 1: only at
q = 1). At q = 1 (B = a*), W*_DEM / W*_Mindlin = (p + 1)/p for every profile: 5/3 for the sphere.
Measured relative departures (W*_DEM - W*_M) / W*_M, sphere: -1 at q = 0.3 and 0.7, +2/3 at q = 1.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from sawdrift import ContactHistory, Profile, get_model
from sawdrift.analytic import loop_area as mindlin_loop_area_sphere
from sawdrift.contact.slots import SlotReference
from sawdrift_builtin.hertz_mindlin_dem import HertzMindlinDEM, HertzMindlinDEMParams
from sawdrift_builtin.jaeger import Jaeger

SPHERE = Profile()
CONE = Profile(shape="cone")
FLAT = Profile(shape="flat")
POWER = Profile(shape="power", exponent=2.7)
RESCALE = HertzMindlinDEMParams(rescale=True)
PLAIN = HertzMindlinDEMParams(rescale=False)  # LAMMPS mindlin/force


def loop_area(model, a: float, amplitude: float, n: int = 20001) -> float:
    """Closed integral of T* db* over b* = B -> -B -> B at fixed a*, after virgin loading to B."""
    down = np.linspace(amplitude, -amplitude, n)
    b = np.concatenate([np.linspace(0.0, amplitude, 101), down[1:], down[::-1][1:]])
    t = ContactHistory(model).drive(np.full_like(b, a), b)[1]
    cb, ct = b[100:], t[100:]
    return float(np.sum(0.5 * (ct[1:] + ct[:-1]) * np.diff(cb)))


def dem_loop_area(a: float, p: float, amplitude: float) -> float:
    """Elastic-perfectly-plastic loop: 4 N* (B - N*/k)^+, k = p a^(p-1), N* = a^p."""
    n, k = a**p, p * a ** (p - 1.0)
    return 4.0 * n * max(amplitude - n / k, 0.0)


# -- Mindlin stiffness and the Coulomb cap -------------------------------------------------------


@pytest.mark.parametrize("profile", [SPHERE, CONE, FLAT, POWER], ids=lambda p: str(p.p))
@pytest.mark.parametrize("a", [0.3, 1.0, 2.5])
def test_initial_stiffness_is_mindlin(profile: Profile, a: float) -> None:
    """dT*/db* at b* = 0 equals N*'(a*) = p a^(p-1), the slope of the Cattaneo-Mindlin curve.

    DEM: exactly linear (T* = k b* to 1e-14 rel) until the cap at b* = a*/p. The Jaeger/Mindlin
    virgin curve has the same initial slope: its secant over 1e-7 a* matches to 1e-6.
    """
    p = profile.p
    k = p * a ** (p - 1.0)
    b = np.linspace(0.0, 0.99 * a / p, 50)
    t = ContactHistory(HertzMindlinDEM(profile=profile)).drive(np.full_like(b, a), b)[1]
    np.testing.assert_allclose(t, k * b, rtol=1e-14, atol=1e-300)
    h = ContactHistory(Jaeger(profile=profile))
    h.advance(a, 0.0)
    eps = 1e-7 * a
    assert h.advance(a, eps)[1] / eps == pytest.approx(k, rel=1e-6)


def test_virgin_curve_is_elastic_then_capped() -> None:
    """T* = min(k b*, N*) on monotonic loading at fixed a* (exact to 1e-14)."""
    a = 1.2
    b = np.linspace(0.0, 2.0, 401)
    t = ContactHistory(HertzMindlinDEM()).drive(np.full_like(b, a), b)[1]
    np.testing.assert_allclose(t, np.minimum(1.5 * a**0.5 * b, a**1.5), rtol=1e-14, atol=0)


@pytest.mark.parametrize("params", [PLAIN, RESCALE], ids=["plain", "rescale"])
@pytest.mark.parametrize("engine", ["compiled", "python"])
def test_coulomb_cap_holds_exactly(params: HertzMindlinDEMParams, engine: str) -> None:
    """|T*| <= N* holds bitwise on a rough history, and the cap is reached (|T*| = N*)."""
    rng = np.random.default_rng(11)
    n = 3000
    a = 0.4 + 0.6 * np.sin(np.linspace(0, 30, n)) + rng.normal(0, 0.05, n)
    b = np.cumsum(rng.normal(0, 0.2, n))
    nn, t = ContactHistory(HertzMindlinDEM(params=params), engine).drive(a, b)
    assert np.all(np.abs(t) <= nn)
    capped = (np.abs(t) == nn) & (nn > 0)
    assert np.count_nonzero(capped) > 100
    assert np.all(t[a <= 0.0] == 0.0) and np.any(a <= 0.0)


def test_oblique_loading_matches_mindlin_deresiewicz() -> None:
    """From (0, 0) along b* = lambda a*: T* = lambda N* for |lambda| <= 1, else +-N* (1e-14)."""
    for lam in (-1.0, -0.4, 0.0, 0.3, 1.0, 1.7):
        for steps in (1, 7):
            h = ContactHistory(HertzMindlinDEM())
            for a in np.linspace(0.0, 1.3, steps + 1)[1:]:
                n, t = h.advance(a, lam * a)
            assert t == pytest.approx(np.clip(lam, -1, 1) * n, rel=1e-14, abs=1e-15)


# -- mindlin_rescale ------------------------------------------------------------------------------


@pytest.mark.parametrize("profile", [SPHERE, CONE, POWER], ids=lambda p: str(p.p))
def test_rescale_on_unloading(profile: Profile) -> None:
    """At fixed b*, unloading scales T* by k(a1)/k(a0) with rescale, and keeps it without."""
    p = profile.p
    plain = ContactHistory(HertzMindlinDEM(params=PLAIN, profile=profile))
    scaled = ContactHistory(HertzMindlinDEM(params=RESCALE, profile=profile))
    for h in (plain, scaled):
        h.advance(1.0, 0.0)
        h.advance(1.0, 0.05)
    t0 = p * 0.05
    for a1 in (0.9, 0.75, 0.6):
        assert plain.advance(a1, 0.05)[1] == pytest.approx(t0, rel=1e-14)
        assert scaled.advance(a1, 0.05)[1] == pytest.approx(t0 * a1 ** (p - 1.0), rel=1e-14)
    # reloading never rescales: T* stays put at fixed b*
    assert scaled.advance(1.0, 0.05)[1] == pytest.approx(t0 * 0.6 ** (p - 1.0), rel=1e-14)
    # without rescaling the cap catches T* once N* < T*
    assert plain.advance(0.1, 0.05)[1] == 0.1**p


def test_rescale_equals_lammps_update() -> None:
    """With rescale, a path-exact step is the LAMMPS update: rescale, add k(a1) db*, cap (1e-14)."""
    rng = np.random.default_rng(5)
    h = ContactHistory(HertzMindlinDEM(params=RESCALE))
    a0, b0 = 1.0, 0.0
    _, t0 = h.advance(a0, b0)
    for _ in range(300):
        a1 = a0 * np.exp(rng.normal(0, 0.1))
        b1 = b0 + rng.normal(0, 0.1)
        k0, k1 = 1.5 * a0**0.5, 1.5 * a1**0.5
        trial = (t0 * k1 / k0 if a1 < a0 else t0) + (b1 - b0) * (
            k1 if a1 < a0 else (a1**1.5 - a0**1.5) / (a1 - a0)
        )
        expected = min(max(trial, -(a1**1.5)), a1**1.5)
        _, t1 = h.advance(a1, b1)
        assert t1 == pytest.approx(expected, rel=1e-12, abs=1e-14)
        a0, b0, t0 = a1, b1, t1


# -- kernel protocol ------------------------------------------------------------------------------


@pytest.mark.parametrize("params", [PLAIN, RESCALE], ids=["plain", "rescale"])
@pytest.mark.parametrize("profile", [SPHERE, FLAT, POWER], ids=lambda p: str(p.p))
def test_kernel_equals_reference(params: HertzMindlinDEMParams, profile: Profile) -> None:
    """Compiled kernel and pure-Python reference agree to 1e-12 on a varying-a* history."""
    rng = np.random.default_rng(3)
    n = 2000
    a = 0.4 + 0.6 * np.sin(np.linspace(0, 20, n)) + rng.normal(0, 0.05, n)
    a[500:520] = a[500]  # constant-a* steps
    b = np.cumsum(rng.normal(0, 0.1, n))
    model = HertzMindlinDEM(params=params, profile=profile)
    n_c, t_c = ContactHistory(model, "compiled").drive(a, b)
    n_p, t_p = ContactHistory(model, "python").drive(a, b)
    np.testing.assert_allclose(n_c, n_p, rtol=1e-14, atol=0)
    np.testing.assert_allclose(t_c, t_p, rtol=0, atol=1e-12)


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    start=st.tuples(st.floats(0.05, 2.0), st.floats(-1.0, 1.0), st.floats(-1.0, 1.0)),
    end=st.tuples(st.floats(-0.5, 2.0), st.floats(-1.5, 1.5)),
    parts=st.integers(2, 12),
    rescale=st.booleans(),
)
def test_straight_path_is_split_invariant(
    start: tuple[float, float, float], end: tuple[float, float], parts: int, rescale: bool
) -> None:
    """force() integrates the spring exactly along straight paths: any subdivision, same T*."""
    a0, b0, frac = start
    model = HertzMindlinDEM(params=HertzMindlinDEMParams(rescale=rescale))
    one = ContactHistory(model)
    one.advance(a0, b0 - 0.1)
    b0 = b0 - 0.1 + frac * a0 / 1.5  # some stored force, below the cap
    one.advance(a0, b0)
    split = one.copy()
    a1, b1 = end[0], b0 + end[1]
    t_one = one.advance(a1, b1)[1]
    for s in np.linspace(0.0, 1.0, parts + 1)[1:]:
        t_split = split.advance(a0 + s * (a1 - a0), b0 + s * (b1 - b0))[1]
    assert t_split == pytest.approx(t_one, rel=1e-10, abs=1e-12)


def test_contact_loss_and_reentry() -> None:
    """a* <= 0 gives zero forces and forgets the spring; re-entry loads from the entry point."""
    h = ContactHistory(HertzMindlinDEM())
    h.advance(1.0, 0.0)
    h.advance(1.0, 0.3)
    assert h.advance(-0.5, 0.3) == (0.0, 0.0)
    # straight path (-0.5, 0.3) -> (1.0, 0.6): enters at a* = 0 with b* = 0.4, lambda = 0.2
    n, t = h.advance(1.0, 0.6)
    assert t == pytest.approx(0.2 * n, rel=1e-14)


# -- departure from the Mindlin hysteresis ------------------------------------------------------


@pytest.mark.parametrize(
    ("q", "departure"), [(0.3, -1.0), (0.7, -1.0), (1.0, 2.0 / 3.0)], ids=["q0.3", "q0.7", "q1"]
)
def test_loop_departure_from_mindlin_sphere(q: float, departure: float) -> None:
    """Measured (W_DEM - W_M)/W_M at the Mindlin amplitude B_q (sphere): -1, -1, +2/3 (to 1e-6).

    The Masing loop is measured on the ``jaeger`` model and checked against docs/physics.md's W*; the
    DEM loop is checked against the elastic-perfectly-plastic area 4 N* (B - N*/k)^+.
    """
    a = 1.0
    amplitude = a * (1.0 - (1.0 - q) ** (2.0 / 3.0))
    w_mindlin = loop_area(Jaeger(), a, amplitude)
    w_dem = loop_area(HertzMindlinDEM(), a, amplitude)
    assert w_mindlin == pytest.approx(mindlin_loop_area_sphere(a, q), rel=2e-7)
    assert w_dem == pytest.approx(dem_loop_area(a, 1.5, amplitude), rel=1e-6, abs=1e-12)
    assert (w_dem - w_mindlin) / w_mindlin == pytest.approx(departure, abs=1e-6)


@pytest.mark.parametrize("profile", [SPHERE, CONE, POWER], ids=lambda p: str(p.p))
@pytest.mark.parametrize("a", [0.5, 1.7])
def test_full_slip_loop_ratio(profile: Profile, a: float) -> None:
    """At q = 1 (B = a*): W_DEM / W_Mindlin = (p + 1)/p for every power-law profile (1e-6)."""
    p = profile.p
    ratio = loop_area(HertzMindlinDEM(profile=profile), a, a) / loop_area(
        Jaeger(profile=profile), a, a
    )
    assert ratio == pytest.approx((p + 1.0) / p, rel=1e-6)


def test_flat_punch_dem_equals_mindlin() -> None:
    """For the flat punch (p = 1) Cattaneo-Mindlin is itself elastic-perfectly-plastic with
    k = N*' = 1: at constant a* the DEM spring and the Jaeger law coincide (to 1e-13)."""
    rng = np.random.default_rng(9)
    b = np.concatenate([[0.0], np.cumsum(rng.normal(0, 0.4, 500))])
    a = np.full_like(b, 0.8)
    t_dem = ContactHistory(HertzMindlinDEM(profile=FLAT)).drive(a, b)[1]
    t_jaeger = ContactHistory(Jaeger(profile=FLAT)).drive(a, b)[1]
    np.testing.assert_allclose(t_dem, t_jaeger, rtol=0, atol=1e-13)
    assert np.count_nonzero(np.abs(t_dem) == 0.8) > 10


def test_no_dissipation_below_the_cap() -> None:
    """Below the Coulomb limit the DEM spring is elastic: a closed cycle returns T* exactly."""
    h = ContactHistory(HertzMindlinDEM())
    h.advance(1.0, 0.0)
    t_start = h.advance(1.0, 0.1)[1]
    for b in np.linspace(0.1, -0.4, 51)[1:]:
        h.advance(1.0, b)
    t_end = h.advance(1.0, 0.1)[1]
    assert t_end == pytest.approx(t_start, abs=1e-15)
    assert loop_area(HertzMindlinDEM(), 1.0, 0.5) == pytest.approx(0.0, abs=1e-12)


def test_registered_and_schema() -> None:
    """Found through its entry point; strict schema with a described ``rescale`` flag."""
    assert get_model("hertz_mindlin_dem") is HertzMindlinDEM
    desc = HertzMindlinDEM.describe()
    # the default is LAMMPS's passive mindlin_rescale/force; plain mindlin/force is declared
    assert desc["parameters"]["rescale"]["default"] is True
    assert HertzMindlinDEM(params=PLAIN).declared_deviations()[0][0] == "passivity"
    assert HertzMindlinDEM().declared_deviations() == ()
    assert desc["parameters"]["rescale"]["description"]
    with pytest.raises(ValueError):
        HertzMindlinDEMParams(rescale=True, damping=1.0)  # type: ignore[call-arg]
    # slots layout: [start of tp, start of dp, normal-law descriptor (p), tp (rescale flag)]
    np.testing.assert_array_equal(HertzMindlinDEM(params=RESCALE).packed_params(), [3, 4, 1.5, 1.0])
    assert isinstance(HertzMindlinDEM(profile=CONE).reference(), SlotReference)


# -- with a normal damping the stored spring is bounded by the total normal force (as LAMMPS) --


def _damped_dem(restitution_c: float, engine: str) -> ContactHistory:
    from sawdrift.contact.scene_damping import damped_law

    model = damped_law(HertzMindlinDEM(), 0.0, restitution_c, 0.25)
    assert model is not None
    return ContactHistory(model, engine)


@pytest.mark.parametrize("engine", ["compiled", "python"])
def test_stored_spring_is_bounded_by_the_total_normal_force(engine: str) -> None:
    """Sphere, damping N* = a^1.5 + C a^(1/4) a', C = 0.5. Loading in gross slip stores the
    total N*, more than the elastic a^1.5; a step back at rest then unloads the spring from there
    by k_t db (k_t = 1.5 a^(1/2)). Unloading fast stores the lowered total. The elastic bound
    would store 1.2^1.5 and 1, and give 0.493 and 0.7 after the steps back."""
    h = _damped_dem(0.5, engine)
    h.advance(1.0, 0.0)
    n, t = h.advance(1.2, 2.0, 1.0)
    total = 1.2**1.5 + 0.5 * 1.2**0.25
    assert n == pytest.approx(total, rel=1e-14) and t == pytest.approx(total, rel=1e-14)
    _, t = h.advance(1.2, 1.5, 0.0)
    assert t == pytest.approx(total - 1.5 * 1.2**0.5 * 0.5, rel=1e-12)  # 1.017; elastic: 0.493
    n, t = h.advance(1.0, 3.0, -1.0)  # rescale, then the bound 1 - 0.5 = 0.5
    assert n == pytest.approx(0.5, rel=1e-14) and t == pytest.approx(0.5, rel=1e-14)
    _, t = h.advance(1.0, 2.8, 0.0)
    assert t == pytest.approx(0.5 - 1.5 * 0.2, rel=1e-12)  # 0.2; elastic: 0.7


def test_only_a_law_that_takes_the_normal_force_gets_the_damping_in_its_slot() -> None:
    """The memory-diagram laws keep their elastic history (the loop adds the damping); the DEM
    spring takes the scene's damping into its slot, and none when nothing damps."""
    from sawdrift.contact.scene_damping import damped_law

    for name in ("mmd", "mdr", "jaeger"):
        assert damped_law(get_model(name)(), 0.0, 0.5, 0.25) is None
    assert damped_law(HertzMindlinDEM(), 0.0, 0.0, 0.25) is None
    viscous = damped_law(HertzMindlinDEM(PLAIN), 0.3, 0.0, 0.25)
    assert viscous is not None and viscous.params.rescale is False
    h = ContactHistory(viscous)
    h.advance(1.0, 0.0)
    assert h.advance(1.0, 5.0, 2.0) == pytest.approx((1.6, 1.6), rel=1e-14)  # 1 + 0.3 * 2
