"""vtrack.assign.linear_assignment and vtrack.assign.murty against brute-force enumeration and SciPy."""

import itertools

import numpy as np
import pytest
from scipy.optimize import linear_sum_assignment

import vtrack


def all_assignments(cost):
    """Every feasible assignment (row i -> cols[i], distinct, finite) with its cost, sorted."""
    n, m = cost.shape
    rows = np.arange(n)
    found = []
    for cols in itertools.permutations(range(m), n):
        total = cost[rows, list(cols)].sum()
        if np.isfinite(total):
            found.append((total, cols))
    found.sort(key=lambda x: x[0])
    return found


def random_cost(rng, n, m, integer, p_inf):
    if integer:  # small integer range: many ties
        cost = rng.integers(-4, 6, size=(n, m)).astype(np.float64)
    else:
        cost = rng.uniform(-10.0, 10.0, size=(n, m))
    cost[rng.random((n, m)) < p_inf] = np.inf
    return cost


def check_against_brute_force(cost, k):
    expected = all_assignments(cost)
    assignments, costs = vtrack.assign.murty(cost, k)
    want = min(k, len(expected))
    n = cost.shape[0]
    assert assignments.shape == (want, n) and assignments.dtype == np.int64
    assert costs.shape == (want,) and costs.dtype == np.float64
    np.testing.assert_allclose(costs, [c for c, _ in expected[:want]], rtol=0, atol=1e-9)
    assert np.all(np.diff(costs) >= 0)
    # Each row is an assignment with the reported cost, and all are distinct.
    np.testing.assert_allclose(cost[np.arange(n), assignments].sum(axis=1), costs, atol=1e-9)
    assert all(len(set(a)) == n for a in assignments.tolist())
    assert len({tuple(a) for a in assignments.tolist()}) == want


@pytest.mark.parametrize("seed", range(8))
def test_murty_matches_brute_force(seed):
    rng = np.random.default_rng(seed)
    for trial in range(40):
        n = int(rng.integers(1, 6))
        m = min(n + int(rng.integers(0, 4)), 7)  # square to wide: 1 x 1 ... 4 x 7
        cost = random_cost(rng, n, m, integer=trial % 2 == 0, p_inf=(trial % 3) * 0.2)
        check_against_brute_force(cost, int(rng.integers(1, 200)))


def test_k_above_the_number_of_feasible_assignments():
    cost = np.array([[1.0, np.inf, 2.0], [np.inf, 3.0, 0.0]])  # 3 feasible: 1+0, 1+3, 2+3
    assignments, costs = vtrack.assign.murty(cost, 10)
    np.testing.assert_array_equal(costs, [1.0, 4.0, 5.0])
    assert sorted(map(tuple, assignments.tolist())) == [(0, 1), (0, 2), (2, 1)]


def test_all_ties_gives_every_assignment_once():
    check_against_brute_force(np.zeros((3, 5)), 1000)  # 5 * 4 * 3 = 60 assignments


def test_glmb_shaped_matrices():
    # n tracks x (m detections + n missed-detection columns); the missed column of track i is
    # allowed for track i only; some detections are gated out. Costs are negative
    # log-likelihood ratios, often negative.
    rng = np.random.default_rng(3)
    for _ in range(40):
        n, m = int(rng.integers(1, 5)), int(rng.integers(0, 5))
        cost = np.full((n, m + n), np.inf)
        det = rng.normal(-1.0, 2.0, size=(n, m))
        det[rng.random((n, m)) < 0.3] = np.inf
        cost[:, :m] = det
        cost[np.arange(n), m + np.arange(n)] = rng.uniform(0.0, 1.0, size=n)
        check_against_brute_force(cost, int(rng.integers(1, 2000)))


def test_first_best_equals_scipy():
    rng = np.random.default_rng(11)
    for n, m in [(1, 1), (10, 10), (30, 45), (60, 60), (80, 100)]:
        cost = rng.normal(size=(n, m))
        cost[rng.random((n, m)) < 0.1] = np.inf
        r, c = linear_sum_assignment(cost)
        rows, cols = vtrack.assign.linear_assignment(cost)
        np.testing.assert_array_equal(rows, np.arange(n))
        assert len(set(cols.tolist())) == n
        assert cost[rows, cols].sum() == pytest.approx(cost[r, c].sum(), abs=1e-9)
        _, costs = vtrack.assign.murty(cost, 20)
        assert costs[0] == pytest.approx(cost[r, c].sum(), abs=1e-9)
        assert np.all(np.diff(costs) >= 0)


def test_infeasible_matrices():
    cost = np.array([[1.0, np.inf, np.inf], [2.0, np.inf, np.inf]])
    with pytest.raises(ValueError, match="no feasible assignment"):
        vtrack.assign.linear_assignment(cost)
    assignments, costs = vtrack.assign.murty(cost, 3)
    assert assignments.shape == (0, 2) and costs.shape == (0,)


def test_empty_problem():
    rows, cols = vtrack.assign.linear_assignment(np.zeros((0, 3)))
    assert rows.shape == cols.shape == (0,)
    assignments, costs = vtrack.assign.murty(np.zeros((0, 3)), 5)
    assert assignments.shape == (1, 0)
    np.testing.assert_array_equal(costs, [0.0])


def test_accepts_integer_and_non_contiguous_input():
    cost = np.arange(12).reshape(4, 3)  # int64, transposed below
    _, c1 = vtrack.assign.murty(cost.T, 4)
    _, c2 = vtrack.assign.murty(np.ascontiguousarray(cost.T, dtype=np.float64), 4)
    np.testing.assert_array_equal(c1, c2)


def test_bad_input():
    with pytest.raises(ValueError, match="cost contains NaN"):
        vtrack.assign.murty(np.array([[0.0, np.nan]]), 1)
    with pytest.raises(ValueError, match="cost contains NaN"):
        vtrack.assign.linear_assignment(np.array([[np.nan]]))
    with pytest.raises(ValueError, match=r"n <= m.*\(3, 2\)"):
        vtrack.assign.linear_assignment(np.zeros((3, 2)))
    with pytest.raises(ValueError, match="k must be >= 1, got 0"):
        vtrack.assign.murty(np.zeros((2, 2)), 0)
    with pytest.raises(ValueError, match="got -2"):
        vtrack.assign.murty(np.zeros((2, 2)), -2)
    with pytest.raises(ValueError, match="-inf"):
        vtrack.assign.murty(np.array([[-np.inf, 0.0]]), 1)
    with pytest.raises(ValueError, match="cost must be 2-D"):
        vtrack.assign.murty(np.zeros(3), 1)
    with pytest.raises(TypeError, match="cost"):
        vtrack.assign.linear_assignment(np.array([["a", "b"]]))
    with pytest.raises(TypeError):
        vtrack.assign.murty(np.zeros((2, 2)), 1.5)


def test_threads_get_the_same_results():
    # The solver keeps no global state and releases the GIL: concurrent calls agree.
    from concurrent.futures import ThreadPoolExecutor

    rng = np.random.default_rng(9)
    costs = [rng.random((30, 40)) for _ in range(8)]
    expected = [vtrack.assign.murty(c, 50)[1] for c in costs]
    with ThreadPoolExecutor(max_workers=4) as pool:
        got = list(pool.map(lambda c: vtrack.assign.murty(c, 50)[1], costs))
    for e, g in zip(expected, got):
        np.testing.assert_array_equal(e, g)


def test_gibbs_visit_frequencies_match_the_assignment_weights():
    """The chain's stationary distribution is pi(a) ~ exp(-cost(a)) (Vo, Vo & Hoang 2017, IV-B):
    visit frequencies of 40 000 sweeps on a 3 x 5 matrix within 5 binomial sd (x3 for the chain's
    autocorrelation) of the exact probabilities from enumeration."""
    rng = np.random.default_rng(4)
    cost = random_cost(rng, 3, 5, integer=False, p_inf=0.2) / 5.0
    expected = all_assignments(cost)
    weights = np.exp(-np.array([c for c, _ in expected]))
    probability = dict(zip([tuple(a) for _, a in expected], weights / weights.sum()))
    sweeps = 40_000
    assignments, costs, visits = vtrack.assign.gibbs_assignments(cost, sweeps, rng=1)
    assert visits.sum() == sweeps and visits.dtype == np.int64
    visited = {tuple(a): v for a, v in zip(assignments.tolist(), visits.tolist())}
    assert set(visited) <= set(probability)
    for a, p in probability.items():
        sd = 3.0 * np.sqrt(p * (1 - p) / sweeps)
        assert abs(visited.get(a, 0) / sweeps - p) <= 5 * sd + 1e-4, a


def test_gibbs_results_are_distinct_sorted_and_start_at_the_optimum():
    rng = np.random.default_rng(9)
    for trial in range(10):
        n = 1 + trial % 4
        cost = random_cost(rng, n, n + 4, integer=trial % 2 == 0, p_inf=0.2)
        expected = all_assignments(cost)
        assignments, costs, visits = vtrack.assign.gibbs_assignments(cost, 150, rng=trial)
        if not expected:
            assert assignments.shape == (0, n) and costs.size == 0
            continue
        assert costs[0] == pytest.approx(expected[0][0], abs=1e-9)
        assert np.all(np.diff(costs) >= 0) and visits.sum() == 150
        np.testing.assert_allclose(cost[np.arange(n), assignments].sum(axis=1), costs, atol=1e-9)
        assert len({tuple(a) for a in assignments.tolist()}) == len(costs)
    same = [vtrack.assign.gibbs_assignments(cost, 100, rng=vtrack.Rng(3)) for _ in range(2)]
    np.testing.assert_array_equal(same[0][0], same[1][0])
    with pytest.raises(ValueError, match="sweeps"):
        vtrack.assign.gibbs_assignments(np.zeros((2, 3)), 0)
    with pytest.raises(ValueError, match="NaN"):
        vtrack.assign.gibbs_assignments(np.array([[np.nan, 1.0]]), 5)
