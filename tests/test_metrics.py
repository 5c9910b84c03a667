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
    assert vtrack.metrics.ospa([[0.0, 0.0]], [[3.0, 4.0]], c=10.0).distance == pytest.approx(5.0)
    assert float(vtrack.metrics.ospa([[0.0, 0.0]], [[3.0, 4.0]], c=2.0)) == pytest.approx(2.0)
    r = vtrack.metrics.ospa([[0.0, 0.0], [10.0, 0.0]], [[1.0, 0.0]], c=5.0, p=2.0)
    assert r.distance == pytest.approx(math.sqrt(13.0))  # sqrt((1 + 5^2) / 2)
    assert r.localisation == pytest.approx(math.sqrt(0.5))
    assert r.cardinality == pytest.approx(math.sqrt(12.5))
    assert r.distance**2 == pytest.approx(r.localisation**2 + r.cardinality**2)


def test_ospa_empty_sets():
    empty = np.zeros((0, 2))
    assert vtrack.metrics.ospa(empty, empty, c=3.0).distance == 0.0
    assert vtrack.metrics.ospa(empty, [[1.0, 1.0]], c=3.0).distance == pytest.approx(3.0)


def test_ospa_matches_brute_force():
    rng = np.random.default_rng(5)
    for trial in range(60):
        x = rng.uniform(0, 10, size=(int(rng.integers(0, 6)), 2))
        y = rng.uniform(0, 10, size=(int(rng.integers(0, 6)), 2))
        c, p = rng.uniform(1, 6), (1.0, 2.0, 3.5)[trial % 3]
        d = vtrack.metrics.ospa(x, y, c=c, p=p).distance
        assert d == pytest.approx(brute_force_ospa(x, y, c, p), abs=1e-10)
        assert d == pytest.approx(vtrack.metrics.ospa(y, x, c=c, p=p).distance, abs=1e-12)


def test_gospa_decomposition():
    truth = [[0.0, 0.0], [5.0, 0.0]]
    estimates = [[0.0, 1.0], [5.0, 3.0], [9.0, 9.0]]
    g = vtrack.metrics.gospa(truth, estimates, c=2.0, p=1.0)
    # (0,0)-(0,1) assigned at distance 1; (5,0)-(5,3) is 3 >= c apart: one miss and one false
    # (c/2 each) beat assigning it; (9,9) is false.
    assert (g.localisation, g.missed, g.false_targets, g.distance) == pytest.approx((1, 1, 2, 4))
    assert (g.n_assigned, g.n_missed, g.n_false) == (1, 1, 2)
    g2 = vtrack.metrics.gospa(truth, estimates, c=2.0, p=2.0)
    assert g2.distance == pytest.approx(math.sqrt(1 + 2 + 4))
    assert vtrack.metrics.gospa(np.zeros((0, 2)), np.zeros((0, 2)), c=1.0).distance == 0.0
    assert "n_missed=1" in repr(g)


def brute_force_gospa(x, y, c, p):
    """min over partial assignments (truth i -> estimate or None, injective) of the GOSPA sum."""
    best = np.inf
    for targets in itertools.product([None, *range(len(y))], repeat=len(x)):
        used = [j for j in targets if j is not None]
        if len(used) != len(set(used)):
            continue
        loc = sum(np.linalg.norm(x[i] - y[j]) ** p for i, j in enumerate(targets) if j is not None)
        best = min(best, loc + c**p / 2 * (len(x) + len(y) - 2 * len(used)))
    return best ** (1.0 / p)


def test_gospa_matches_brute_force_over_partial_assignments():
    rng = np.random.default_rng(8)
    for trial in range(60):
        x = rng.uniform(0, 6, size=(int(rng.integers(0, 5)), 2))
        y = rng.uniform(0, 6, size=(int(rng.integers(0, 5)), 2))
        c, p = rng.uniform(0.5, 4), (1.0, 2.0)[trial % 2]
        g = vtrack.metrics.gospa(x, y, c=c, p=p)
        assert g.distance == pytest.approx(brute_force_gospa(x, y, c, p), abs=1e-10)
        assert g.distance**p == pytest.approx(g.localisation + g.missed + g.false_targets)
        assert g.n_missed == len(x) - g.n_assigned and g.n_false == len(y) - g.n_assigned


def brute_force_ospa2(x, y, c, p):
    """NumPy transcription of OSPA(2): time-averaged base distance, then OSPA over tracks."""
    def exists(track):
        return ~np.isnan(track[:, 0])

    x = [t for t in x if exists(t).any()]
    y = [t for t in y if exists(t).any()]
    if len(x) > len(y):
        x, y = y, x
    n, m = len(y), len(x)
    if n == 0:
        return 0.0

    def base(a, b):
        ea, eb = exists(a), exists(b)
        either = ea | eb
        d = np.where(ea & eb, np.minimum(c, np.linalg.norm(np.nan_to_num(a - b), axis=1)), c)
        return d[either].mean()

    best = min(sum(base(x[i], y[perm[i]]) ** p for i in range(m))
               for perm in itertools.permutations(range(n), m))
    return ((best + c**p * (n - m)) / n) ** (1.0 / p)


def test_ospa2_matches_a_numpy_transcription():
    rng = np.random.default_rng(4)
    for trial in range(40):
        steps = int(rng.integers(1, 7))

        def tracks(count):
            t = rng.normal(0, 3, size=(count, steps, 2))
            t[rng.random((count, steps)) < 0.4] = np.nan  # absent at ~40% of the steps
            return t

        x, y = tracks(int(rng.integers(0, 5))), tracks(int(rng.integers(0, 5)))
        c, p = rng.uniform(1, 5), (1.0, 2.0)[trial % 2]
        assert vtrack.metrics.ospa2(x, y, c=c, p=p).distance == pytest.approx(
            brute_force_ospa2(x, y, c, p), abs=1e-10)


def test_ospa2_hand_computed():
    # One truth track, three estimated tracks over 4 steps (1-D states, NaN = absent), c = 10.
    x = np.array([[[0.0], [1.0], [2.0], [NAN]]])
    y = np.array([
        [[0.0], [1.0], [5.0], [3.0]],   # errors 0, 0, 3, then only y exists: c -> mean 13/4
        [[NAN], [NAN], [NAN], [NAN]],   # never exists: ignored
    ])
    assert vtrack.metrics.ospa2(x, y, c=10.0).distance == pytest.approx(3.25)
    # y3 exists at step 1 only, 99 away: distance to x over steps {0,1,2} is c; x matches y1 and
    # y3 is an extra track: (3.25 + 10) / 2 with p = 1.
    y3 = np.array([[[NAN], [100.0], [NAN], [NAN]]])
    y = np.concatenate([y, y3])
    assert vtrack.metrics.ospa2(x, y, c=10.0, p=1.0).distance == pytest.approx(6.625)
    assert vtrack.metrics.ospa2(x, y, c=10.0, p=2.0).distance == pytest.approx(math.sqrt((3.25**2 + 100) / 2))
    assert vtrack.metrics.ospa2(y, x, c=10.0).distance == pytest.approx(6.625)
    assert vtrack.metrics.ospa2(np.zeros((0, 4, 1)), np.zeros((0, 4, 1)), c=10.0).distance == 0.0


def test_ospa2_of_always_present_tracks_averages_per_step_distances():
    # With one track each, present at every step, OSPA(2) is the mean cut-off distance.
    rng = np.random.default_rng(2)
    x, y = rng.normal(size=(1, 6, 2)), rng.normal(size=(1, 6, 2))
    per_step = np.minimum(1.5, np.linalg.norm(x[0] - y[0], axis=1))
    assert vtrack.metrics.ospa2(x, y, c=1.5, p=3.0).distance == pytest.approx(per_step.mean())


def test_metrics_bad_input():
    with pytest.raises(ValueError, match="c"):
        vtrack.metrics.ospa([[0.0]], [[1.0]], c=0.0)
    with pytest.raises(ValueError, match="p"):
        vtrack.metrics.gospa([[0.0]], [[1.0]], c=1.0, p=0.5)
    with pytest.raises(ValueError, match="same dimension"):
        vtrack.metrics.ospa([[0.0, 1.0]], [[1.0]], c=1.0)
    with pytest.raises(ValueError, match="x contains NaN"):
        vtrack.metrics.ospa([[NAN]], [[1.0]], c=1.0)
    with pytest.raises(ValueError, match="estimates has a non-finite entry"):
        vtrack.metrics.gospa([[0.0]], [[np.inf]], c=1.0)
    with pytest.raises(ValueError, match="partly NaN"):
        vtrack.metrics.ospa2(np.array([[[0.0, NAN]]]), np.zeros((0, 1, 2)), c=1.0)
    with pytest.raises(ValueError, match="3-D"):
        vtrack.metrics.ospa2(np.zeros((2, 2)), np.zeros((2, 2)), c=1.0)
    with pytest.raises(TypeError, match="truth"):
        vtrack.metrics.gospa(np.array([["a"]]), [[1.0]], c=1.0)
