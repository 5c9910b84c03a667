"""OSPA, GOSPA and OSPA(2) on hand-computed cases, and OSPA against brute force."""

import itertools
import math

import numpy as np
import pytest

import vtrack

NAN = np.nan


def brute_force_ospa(x, y, c, p):
    if len(x) > len(y):
        x, y = y, x
    n, m = len(y), len(x)
    if n == 0:
        return 0.0
    best = min(
        (sum(min(c, np.linalg.norm(x[i] - y[perm[i]])) ** p for i in range(m))
         for perm in itertools.permutations(range(n), m)),
        default=0.0,
    )
    return ((best + c**p * (n - m)) / n) ** (1.0 / p)


def test_ospa_hand_computed():
    assert vtrack.ospa([[0.0, 0.0]], [[3.0, 4.0]], c=10.0).distance == pytest.approx(5.0)
    assert float(vtrack.ospa([[0.0, 0.0]], [[3.0, 4.0]], c=2.0)) == pytest.approx(2.0)
    r = vtrack.ospa([[0.0, 0.0], [10.0, 0.0]], [[1.0, 0.0]], c=5.0, p=2.0)
    assert r.distance == pytest.approx(math.sqrt(13.0))  # sqrt((1 + 5^2) / 2)
    assert r.localisation == pytest.approx(math.sqrt(0.5))
    assert r.cardinality == pytest.approx(math.sqrt(12.5))
    assert r.distance**2 == pytest.approx(r.localisation**2 + r.cardinality**2)


def test_ospa_empty_sets():
    empty = np.zeros((0, 2))
    assert vtrack.ospa(empty, empty, c=3.0).distance == 0.0
    assert vtrack.ospa(empty, [[1.0, 1.0]], c=3.0).distance == pytest.approx(3.0)


def test_ospa_matches_brute_force():
    rng = np.random.default_rng(5)
    for trial in range(60):
        x = rng.uniform(0, 10, size=(int(rng.integers(0, 6)), 2))
        y = rng.uniform(0, 10, size=(int(rng.integers(0, 6)), 2))
        c, p = rng.uniform(1, 6), (1.0, 2.0, 3.5)[trial % 3]
        d = vtrack.ospa(x, y, c=c, p=p).distance
        assert d == pytest.approx(brute_force_ospa(x, y, c, p), abs=1e-10)
        assert d == pytest.approx(vtrack.ospa(y, x, c=c, p=p).distance, abs=1e-12)


def test_gospa_decomposition():
    truth = [[0.0, 0.0], [5.0, 0.0]]
    estimates = [[0.0, 1.0], [5.0, 3.0], [9.0, 9.0]]
    g = vtrack.gospa(truth, estimates, c=2.0, p=1.0)
    # (0,0)-(0,1) assigned at distance 1; (5,0)-(5,3) is 3 >= c apart: one miss and one false
    # (c/2 each) beat assigning it; (9,9) is false.
    assert (g.localisation, g.missed, g.false_targets, g.distance) == pytest.approx((1, 1, 2, 4))
    assert (g.n_assigned, g.n_missed, g.n_false) == (1, 1, 2)
    g2 = vtrack.gospa(truth, estimates, c=2.0, p=2.0)
    assert g2.distance == pytest.approx(math.sqrt(1 + 2 + 4))
    assert vtrack.gospa(np.zeros((0, 2)), np.zeros((0, 2)), c=1.0).distance == 0.0
    assert "n_missed=1" in repr(g)


def test_ospa2_hand_computed():
    # One truth track, three estimated tracks over 4 steps (1-D states, NaN = absent), c = 10.
    x = np.array([[[0.0], [1.0], [2.0], [NAN]]])
    y = np.array([
        [[0.0], [1.0], [5.0], [3.0]],   # errors 0, 0, 3, then only y exists: c -> mean 13/4
        [[NAN], [NAN], [NAN], [NAN]],   # never exists: ignored
    ])
    assert vtrack.ospa2(x, y, c=10.0).distance == pytest.approx(3.25)
    # y3 exists at step 1 only, 99 away: distance to x over steps {0,1,2} is c; x matches y1 and
    # y3 is an extra track: (3.25 + 10) / 2 with p = 1.
    y3 = np.array([[[NAN], [100.0], [NAN], [NAN]]])
    y = np.concatenate([y, y3])
    assert vtrack.ospa2(x, y, c=10.0, p=1.0).distance == pytest.approx(6.625)
    assert vtrack.ospa2(x, y, c=10.0, p=2.0).distance == pytest.approx(math.sqrt((3.25**2 + 100) / 2))
    assert vtrack.ospa2(y, x, c=10.0).distance == pytest.approx(6.625)
    assert vtrack.ospa2(np.zeros((0, 4, 1)), np.zeros((0, 4, 1)), c=10.0).distance == 0.0


def test_ospa2_of_always_present_tracks_averages_per_step_distances():
    # With one track each, present at every step, OSPA(2) is the mean cut-off distance.
    rng = np.random.default_rng(2)
    x, y = rng.normal(size=(1, 6, 2)), rng.normal(size=(1, 6, 2))
    per_step = np.minimum(1.5, np.linalg.norm(x[0] - y[0], axis=1))
    assert vtrack.ospa2(x, y, c=1.5, p=3.0).distance == pytest.approx(per_step.mean())


def test_metrics_bad_input():
    with pytest.raises(ValueError, match="c"):
        vtrack.ospa([[0.0]], [[1.0]], c=0.0)
    with pytest.raises(ValueError, match="p"):
        vtrack.gospa([[0.0]], [[1.0]], c=1.0, p=0.5)
    with pytest.raises(ValueError, match="same dimension"):
        vtrack.ospa([[0.0, 1.0]], [[1.0]], c=1.0)
    with pytest.raises(ValueError, match="x contains NaN"):
        vtrack.ospa([[NAN]], [[1.0]], c=1.0)
    with pytest.raises(ValueError, match="estimates has a non-finite entry"):
        vtrack.gospa([[0.0]], [[np.inf]], c=1.0)
    with pytest.raises(ValueError, match="partly NaN"):
        vtrack.ospa2(np.array([[[0.0, NAN]]]), np.zeros((0, 1, 2)), c=1.0)
    with pytest.raises(ValueError, match="3-D"):
        vtrack.ospa2(np.zeros((2, 2)), np.zeros((2, 2)), c=1.0)
    with pytest.raises(TypeError, match="truth"):
        vtrack.gospa(np.array([["a"]]), [[1.0]], c=1.0)
