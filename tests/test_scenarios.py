"""vtrack.scenarios: the standard GLMB scenario generator and the shared fixed draws."""

import numpy as np
import pytest

from vtrack.scenarios import load_standard_glmb_draw, standard_glmb_scenario


def test_generated_truth_equals_the_shared_truth_exactly(glmb_standard_dir):
    shared = load_standard_glmb_draw(glmb_standard_dir / "seed0")
    generated = standard_glmb_scenario(seed=123)
    assert generated.scans == shared.scans == 100
    for k in range(100):
        np.testing.assert_array_equal(generated.truth_states[k], shared.truth_states[k])
        np.testing.assert_array_equal(generated.truth_ids[k], shared.truth_ids[k])
    card = np.loadtxt(glmb_standard_dir / "truth_card.csv", delimiter=",", skiprows=1)
    np.testing.assert_array_equal([len(x) for x in generated.truth_states], card[:, 1])


def excess_counts(scenario):
    """Per scan: measurement count minus the expected number of detections."""
    return np.array([len(z) - scenario.detection_probability * len(x)
                     for z, x in zip(scenario.measurements, scenario.truth_states)])


@pytest.mark.parametrize("rate", [10.0, 30.0])
def test_mean_clutter_count_is_the_rate(rate):
    # 5 draws x 100 scans; the excess count has variance rate + N p_D (1 - p_D) per scan, so its
    # mean's standard deviation is about sqrt(rate / 500) (0.25 at rate 30): 4 sd tolerance.
    excess = np.concatenate([excess_counts(standard_glmb_scenario(s, clutter_rate=rate))
                             for s in range(5)])
    assert abs(excess.mean() - rate) < 4 * np.sqrt(rate / excess.size) + 0.05
    assert abs(excess.var() - rate) < 0.25 * rate  # Poisson: variance = mean


def test_detections_without_clutter_are_near_the_truth():
    scenario = standard_glmb_scenario(7, clutter_rate=0.0, detection_probability=1.0)
    for z, x in zip(scenario.measurements, scenario.truth_states):
        assert len(z) == len(x)
        errors = z - x[:, [0, 2]]  # detections come in target order
        assert np.abs(errors).max() < 60.0  # 6 sd of R = 100 I
    all_errors = np.concatenate([z - x[:, [0, 2]] for z, x in
                                 zip(scenario.measurements, scenario.truth_states)])
    assert all_errors.std() == pytest.approx(10.0, rel=0.05)


def test_same_seed_same_draw():
    a, b = standard_glmb_scenario(3), standard_glmb_scenario(3)
    assert all(np.array_equal(x, y) for x, y in zip(a.measurements, b.measurements))
    c = standard_glmb_scenario(4)
    assert not all(np.array_equal(x, y) for x, y in zip(a.measurements, c.measurements))


def test_shared_draws_have_the_scenario_clutter_rate(glmb_standard_dir):
    draws = [load_standard_glmb_draw(glmb_standard_dir / f"seed{s}") for s in range(10)]
    excess = np.concatenate([excess_counts(d) for d in draws])
    assert abs(excess.mean() - 30.0) < 4 * np.sqrt(30.0 / excess.size) + 0.05


def test_bad_arguments():
    with pytest.raises(ValueError, match="clutter_rate"):
        standard_glmb_scenario(0, clutter_rate=-1.0)
    with pytest.raises(FileNotFoundError):
        load_standard_glmb_draw("/nonexistent/seed0")
