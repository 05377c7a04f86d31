"""Segregation of positions (sawdrift.mixture.segregation): 0 within its spread for random
placements, 1 for sorted ones, and the purity of a hand-counted line."""

from __future__ import annotations

import numpy as np
import pytest

from sawdrift.mixture.segregation import lacey_segregation, measures, purity, purity_index


def test_purity_counts_each_species_on_its_own_side():
    # 0 0 1 0 | 1 1: the best cut leaves 3 of 3 zeros left and 2 of 3 ones right: (1 + 2/3)/2
    x = np.arange(6.0)
    kinds = np.array([0, 0, 1, 0, 1, 1])
    assert purity(x, kinds) == pytest.approx((1.0 + 2.0 / 3.0) / 2.0, rel=1e-12)
    # the mirror image (species 0 on the right) has the same purity
    assert purity(-x, kinds) == pytest.approx(purity(x, kinds), rel=1e-12)


@pytest.mark.parametrize(("n0", "n1"), [(50, 50), (30, 70)])
def test_sorted_line_is_one(n0, n1):
    rng = np.random.default_rng(1)
    x = np.sort(rng.uniform(0, 1, n0 + n1))
    kinds = np.repeat([0, 1], [n0, n1])
    m = measures(x, kinds)
    assert m["purity"] == 1.0 and m["purity_index"] == pytest.approx(1.0, abs=1e-12)
    assert m["lacey"] == pytest.approx(1.0, abs=1e-12)  # 10 bins of 10: the interface on a boundary
    # sorted the other way round: the same
    assert measures(-x, kinds)["purity_index"] == pytest.approx(1.0, abs=1e-12)


def test_random_placements_are_zero_within_their_spread():
    """200 random placements of 100 + 100 (seeds 0-199, independent of the null's own seed):
    the mean of each index lies within 3 standard errors of 0, and the spread (standard
    deviation) is below 0.15 (measured: P = 0.557 +- 0.017, purity index -0.006 +- 0.039,
    Lacey -0.003 +- 0.027)."""
    n = 200
    kinds = np.repeat([0, 1], [100, 100])
    vals = {"purity_index": [], "lacey": []}
    for seed in range(n):
        x = np.random.default_rng(seed).uniform(0.0, 1.0, kinds.size)
        m = measures(x, kinds)
        for key in vals:
            vals[key].append(m[key])
    for key, v in vals.items():
        v = np.asarray(v)
        sd = v.std(ddof=1)
        assert abs(v.mean()) < 3.0 * sd / np.sqrt(n), (key, v.mean(), sd)
        assert sd < 0.15, (key, sd)


def test_partly_sorted_lies_between():
    kinds = np.repeat([0, 1], [50, 50])
    x = np.arange(100.0)
    rng = np.random.default_rng(3)
    half = kinds.copy()
    idx = rng.choice(100, 40, replace=False)  # shuffle 40 of the 100 places
    half[idx] = rng.permutation(half[idx])
    assert 0.2 < purity_index(x, half) < 0.95 and 0.2 < lacey_segregation(x, half) < 0.95


def test_lacey_takes_every_particle_and_refuses_a_species_smaller_than_a_bin():
    """A sorted 10 + 1 gave -0.227 (its lone bead fell outside bins of 3 and counted only in p):
    a species smaller than a bin cannot fill one, no value. Bins of n or n + 1 take every
    particle: a sorted 15 + 5 (bins 5, 5, 5, 5... of 20 in 4) is 1 either way round, and random
    orders of 20 + 10 average 0 within their standard error (4000 orders, seeded)."""
    x = np.arange(11.0)
    assert np.isnan(lacey_segregation(x, np.array([0] * 10 + [1])))
    x = np.arange(20.0)
    sorted_line = np.array([0] * 15 + [1] * 5)
    assert lacey_segregation(x, sorted_line) == pytest.approx(1.0, abs=1e-12)
    assert lacey_segregation(x, sorted_line[::-1]) == pytest.approx(1.0, abs=1e-12)
    rng = np.random.default_rng(7)
    seq = np.repeat([0, 1], [20, 10])
    vals = np.array([lacey_segregation(np.arange(30.0), rng.permutation(seq))
                     for _ in range(4000)])
    assert abs(vals.mean()) < 3.0 * vals.std(ddof=1) / np.sqrt(vals.size)
