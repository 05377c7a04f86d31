"""Tests of the example third-party plugin ``sawdrift-tsuji`` (model ``hertz_tsuji``).

Skipped unless the plugin is installed (``pip install ./plugins/sawdrift-tsuji``); this file
installs nothing. Physics checked on a free 1-DOF normal impact, m* a*'' = -N*(a*, a*'):
Tsuji, Tanaka & Ishida (1992, Powder Technol. 71) damping dissipates energy (restitution e < 1,
decreasing with the damping), e = 1 without it, and e depends on c / sqrt(m*) only, not on the
impact velocity (the point of the a^(1/4) dashpot).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("sawdrift_tsuji")

from sawdrift import ContactHistory, ContactModel, Profile, get_model, registry  # noqa: E402


def tsuji(damping: float, profile: Profile | None = None) -> ContactModel:
    cls = get_model("hertz_tsuji")
    return cls(params=cls.Params(damping=damping), profile=profile)


def restitution(model: ContactModel, v_in: float, mass: float = 1.0) -> tuple[float, float]:
    """Integrate m* a'' = -N*(a, a') from a = 0, a' = v_in (RK4, stages via ContactHistory.trial).

    Returns the coefficient of restitution -a'_out / v_in and the smallest N* met in contact.
    The step is 1/4000 of the Hertz time scale sqrt(m) a_max^(-1/4) (a_max from the elastic
    energy balance), so the integration error is far below the tolerances used.
    """
    p = model.profile.p
    a_max = ((p + 1.0) * 0.5 * mass * v_in**2) ** (1.0 / (p + 1.0))
    dt = a_max / v_in / 4000.0
    h = ContactHistory(model)
    y, v = 0.0, v_in
    n_min = np.inf

    def acc(y_: float, v_: float) -> float:
        return -h.trial(y_, 0.0, v_, 0.0)[0] / mass

    for _ in range(200_000):
        k1y, k1v = v, acc(y, v)
        k2y, k2v = v + 0.5 * dt * k1v, acc(y + 0.5 * dt * k1y, v + 0.5 * dt * k1v)
        k3y, k3v = v + 0.5 * dt * k2v, acc(y + 0.5 * dt * k2y, v + 0.5 * dt * k2v)
        k4y, k4v = v + dt * k3v, acc(y + dt * k3y, v + dt * k3v)
        y += dt / 6.0 * (k1y + 2 * k2y + 2 * k3y + k4y)
        v += dt / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v)
        n, _ = h.advance(y, 0.0, v, 0.0)
        if y <= 0.0:
            return -v / v_in, n_min
        n_min = min(n_min, n)
    raise AssertionError("the particle never left the contact")


def test_registered_through_its_own_entry_point() -> None:
    """The model comes from the separately installed distribution, through sawdrift.models."""
    entry = registry.models["hertz_tsuji"]
    assert entry.distribution == "sawdrift-tsuji"
    assert entry.cls.capabilities.uses_velocity is True
    desc = entry.cls.describe()
    assert desc["parameters"]["damping"]["default"] == 0.1
    with pytest.raises(ValueError):
        entry.cls.Params(damping=-1.0)


def test_elastic_impact_restitutes_fully() -> None:
    """damping = 0: the Hertz impact is elastic, e = 1 to 1e-9."""
    e, _ = restitution(tsuji(0.0), 0.5)
    assert e == pytest.approx(1.0, abs=1e-9)


def test_damping_dissipates_and_restitution_decreases() -> None:
    """e < 1 and strictly decreasing in the damping c (at least 1e-3 between the levels)."""
    es = [restitution(tsuji(c), 0.5)[0] for c in (0.05, 0.2, 0.6)]
    assert es[0] < 1.0 - 1e-3
    assert es[0] - es[1] > 1e-3 and es[1] - es[2] > 1e-3
    assert es[2] > 0.0


@pytest.mark.parametrize("profile", [Profile(), Profile(shape="cone")], ids=["sphere", "cone"])
def test_restitution_is_velocity_independent(profile: Profile) -> None:
    """Tsuji's a^((p-1)/2) dashpot: e is the same at impact speeds 0.05 and 2 (to 1e-9)."""
    e_slow, _ = restitution(tsuji(0.3, profile), 0.05)
    e_fast, _ = restitution(tsuji(0.3, profile), 2.0)
    assert e_slow < 0.99
    assert e_slow == pytest.approx(e_fast, abs=1e-9)


def test_restitution_depends_on_damping_over_root_mass() -> None:
    """Scaling: (m*, c) = (4, 0.4) gives the same e as (1, 0.2) (to 1e-9)."""
    e1, _ = restitution(tsuji(0.2), 0.5, mass=1.0)
    e4, _ = restitution(tsuji(0.4), 0.5, mass=4.0)
    assert e1 == pytest.approx(e4, abs=1e-9)


def test_contact_cannot_pull() -> None:
    """N* >= 0: a fast retreat clamps the force at exactly 0 instead of an attraction."""
    h = ContactHistory(tsuji(0.5))
    h.advance(0.01, 0.0, 1.0, 0.0)
    n, _ = h.advance(0.01, 0.0, -1.0, 0.0)
    assert n == 0.0  # 0.01^1.5 - 0.5 * 0.01^0.25 < 0
    _, n_min = restitution(tsuji(0.6), 0.5)
    assert n_min >= 0.0


def _dem_spring_bounded_by(a: np.ndarray, b: np.ndarray, bound: np.ndarray) -> np.ndarray:
    """The Hertz DEM spring of LAMMPS mindlin_rescale/force whose stored force is clipped to
    ``bound`` (LAMMPS: Fscrit = mu |Fntot|), written out for a path that stays in contact: the
    secant stiffness [N(a1) - N(a0)]/(a1 - a0) while loading, the rescale by k1/k0 = (a1/a0)^(1/2)
    plus k1 db while unloading (k = 1.5 a^(1/2), N = a^(3/2))."""
    out, t, a0, b0 = np.empty_like(a), 0.0, 0.0, 0.0
    for k, (a1, b1, cap) in enumerate(zip(a, b, bound, strict=True)):
        if a1 < a0:
            t = t * math.sqrt(a1 / a0) + 1.5 * math.sqrt(a1) * (b1 - b0)
        else:
            t += (b1 - b0) * (a1**1.5 - a0**1.5) / (a1 - a0)
        t = min(max(t, -cap), cap)
        out[k], a0, b0 = t, a1, b1
    return out


def test_tangential_law_is_the_dem_spring_bounded_by_the_total_normal_force() -> None:
    """N* differs by the dashpot; T* is the hertz_mindlin_dem spring on the same path with its
    stored force bounded by the total normal force (as LAMMPS bounds its tangential history):
    above the elastic N*(a*) while the contact loads, below it while it unloads fast."""
    rng = np.random.default_rng(1)
    a = 0.5 + 0.4 * np.sin(np.linspace(0, 12, 400))
    b = np.cumsum(rng.normal(0, 0.05, 400))
    adot = np.gradient(a)
    h_t = ContactHistory(tsuji(0.3))
    got = np.array([h_t.advance(ak, bk, vk, 0.0) for ak, bk, vk in zip(a, b, adot, strict=True)])
    expected_n = np.maximum(a**1.5 + 0.3 * a**0.25 * adot, 0.0)
    np.testing.assert_allclose(got[:, 0], expected_n, rtol=1e-14)
    np.testing.assert_allclose(got[:, 1], _dem_spring_bounded_by(a, b, expected_n), rtol=1e-12,
                               atol=1e-14)
    elastic = a**1.5
    # the path slips both ways: beyond the elastic bound while loading, under it while unloading
    assert np.sum(np.abs(got[:, 1]) > elastic * (1 + 1e-9)) > 0
    assert np.sum((np.abs(got[:, 1]) < elastic * (1 - 1e-9)) & (np.abs(got[:, 1]) == got[:, 0])) > 0


def test_kernel_equals_reference() -> None:
    """Compiled kernel and pure-Python reference give the same (N*, T*) to 1e-12."""
    rng = np.random.default_rng(2)
    model = tsuji(0.25, Profile(shape="cone"))
    k, r = ContactHistory(model, "compiled"), ContactHistory(model, "python")
    for ak, bk, vk in zip(
        0.3 + 0.5 * np.sin(np.linspace(0, 15, 500)),
        np.cumsum(rng.normal(0, 0.05, 500)),
        rng.normal(0, 1, 500),
        strict=True,
    ):
        nk, tk = k.advance(ak, bk, vk, 0.0)
        nr, tr = r.advance(ak, bk, vk, 0.0)
        assert nk == pytest.approx(nr, rel=1e-12, abs=1e-14)
        assert tk == pytest.approx(tr, rel=1e-12, abs=1e-14)
