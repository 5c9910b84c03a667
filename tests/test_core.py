"""The SMC core through Python, checked against SciPy / NumPy and closed forms."""

import numpy as np
import pytest
from scipy import special, stats

import vtrack

METHODS = vtrack.smc.RESAMPLING_METHODS


def test_rng_same_seed_same_draws_and_streams_differ():
    a, b = vtrack.Rng(seed=5), vtrack.Rng(seed=5)
    np.testing.assert_array_equal(a.uniform(100), b.uniform(100))
    np.testing.assert_array_equal(a.normal(101), b.normal(101))
    s0, s1 = vtrack.Rng(5, stream=0).uniform(1000), vtrack.Rng(5, stream=1).uniform(1000)
    assert not np.intersect1d(s0, s1).size
    jumped = vtrack.Rng(5)
    jumped.jump()
    np.testing.assert_array_equal(jumped.uniform(10), vtrack.Rng(5, stream=1).uniform(10))


def test_rng_distributions_pass_kolmogorov_smirnov():
    rng = vtrack.Rng(seed=3)
    u = rng.uniform(200_000)
    assert u.min() >= 0.0 and u.max() < 1.0
    assert stats.kstest(u, "uniform").pvalue > 1e-4
    z = rng.normal(200_001)
    assert stats.kstest(z, "norm").pvalue > 1e-4


def test_log_sum_exp_matches_scipy():
    x = vtrack.Rng(1).normal(1000) * 50
    assert vtrack.smc.log_sum_exp(x) == pytest.approx(special.logsumexp(x), rel=1e-13)
    assert vtrack.smc.log_sum_exp([]) == -np.inf
    assert vtrack.smc.log_sum_exp([-np.inf, -np.inf]) == -np.inf


def test_normalize_log_weights_and_all_vanishing_case():
    x = np.array([np.log(1.0), np.log(3.0), -np.inf]) - 800.0
    w, total = vtrack.smc.normalize_log_weights(x)
    np.testing.assert_allclose(w, [0.25, 0.75, 0.0], atol=1e-15)
    assert total == pytest.approx(np.log(4.0) - 800.0)
    w, total = vtrack.smc.normalize_log_weights(np.full(4, -np.inf))
    assert total == -np.inf and not np.isnan(w).any()
    np.testing.assert_array_equal(w, np.full(4, 0.25))


def test_effective_sample_size_is_eq7():
    w = np.array([0.1, 0.2, 0.7])
    assert vtrack.smc.effective_sample_size(w) == pytest.approx(1.0 / np.sum(w**2))
    assert vtrack.smc.effective_sample_size(np.log(w) + 300, log=True) == pytest.approx(1 / 0.54)
    assert vtrack.smc.effective_sample_size(np.zeros(3)) == 0.0
    assert vtrack.smc.effective_sample_size(np.full(3, -np.inf), log=True) == 0.0


@pytest.mark.parametrize("method", METHODS)
def test_resampling_is_unbiased(method):
    # Mean offspring count of each particle over T seeded trials is within 5 multinomial
    # standard errors of N * w_i (the other schemes have lower variance than multinomial).
    rng = vtrack.Rng(seed=17)
    w = rng.uniform(12)
    w[[0, 5]] = 0.0
    w /= w.sum()
    n, trials = 12, 20_000
    counts = np.zeros(n)
    for _ in range(trials):
        counts += np.bincount(vtrack.smc.resample(w, rng, method=method), minlength=n)
    mean = counts / trials
    tolerance = 5 * np.sqrt(n * w * (1 - w) / trials) + 1e-12
    assert np.all(np.abs(mean - n * w) <= tolerance)
    assert mean[0] == 0 and mean[5] == 0


@pytest.mark.parametrize("method", METHODS)
def test_resample_count_order_and_reproducibility(method):
    w = np.linspace(0.0, 1.0, 30)
    a = vtrack.smc.resample(w, 7, count=95, method=method)
    assert a.dtype == np.int64 and a.shape == (95,)
    assert np.all(np.diff(a) >= 0) and a.min() >= 1 and a.max() <= 29
    np.testing.assert_array_equal(a, vtrack.smc.resample(w, 7, count=95, method=method))


def test_resample_rejects_bad_input():
    rng = vtrack.Rng(0)
    with pytest.raises(TypeError, match="weights"):
        vtrack.smc.resample(np.array(["a", "b"]), rng)
    with pytest.raises(ValueError, match="weights"):
        vtrack.smc.resample(np.ones((2, 2)), rng)
    with pytest.raises(ValueError, match="NaN"):
        vtrack.smc.resample([0.5, np.nan], rng)
    with pytest.raises(ValueError, match="non-negative"):
        vtrack.smc.resample([0.5, -0.5, 1.0], rng)
    with pytest.raises(ValueError, match="all zero"):
        vtrack.smc.resample([0.0, 0.0], rng)
    with pytest.raises(ValueError, match="unknown resampling scheme"):
        vtrack.smc.resample([1.0], rng, method="bogus")
    with pytest.raises(ValueError, match="count"):
        vtrack.smc.resample([1.0], rng, count=-1)
    with pytest.raises(TypeError, match="rng"):
        vtrack.smc.resample([1.0], rng="seed")
    assert issubclass(vtrack.InvalidArgument, ValueError)


def test_gaussian_log_pdf_matches_scipy_and_samples_match_moments():
    mean = np.array([1.0, -2.0, 0.5])
    cov = np.array([[4.0, 1.2, -0.3], [1.2, 2.0, 0.4], [-0.3, 0.4, 1.0]])
    g = vtrack.Gaussian(mean, cov)
    reference = stats.multivariate_normal(mean, cov)
    x = np.random.default_rng(0).normal(size=(50, 3)) * 3
    np.testing.assert_allclose(g.log_pdf(x), reference.logpdf(x), rtol=1e-12)
    assert g.log_pdf(x[0]) == pytest.approx(reference.logpdf(x[0]), rel=1e-12)
    samples = g.sample(vtrack.Rng(4), n=200_000)
    assert samples.shape == (200_000, 3)
    np.testing.assert_allclose(samples.mean(axis=0), mean, atol=0.03)
    np.testing.assert_allclose(np.cov(samples.T), cov, atol=0.05)
    assert g.sample(vtrack.Rng(4)).shape == (3,)
    np.testing.assert_allclose(g.cholesky @ g.cholesky.T, cov, rtol=1e-12)


def test_gaussian_rejects_bad_covariances():
    with pytest.raises(ValueError, match="positive definite"):
        vtrack.Gaussian([0.0, 0.0], [[1.0, 2.0], [2.0, 1.0]])
    with pytest.raises(ValueError, match="symmetric"):
        vtrack.Gaussian([0.0, 0.0], [[1.0, 0.5], [-0.5, 1.0]])
    with pytest.raises(ValueError, match="covariance must be 2x2"):
        vtrack.Gaussian([0.0, 0.0], np.eye(3))
    with pytest.raises(ValueError, match="cov"):
        vtrack.Gaussian([0.0, 0.0], [[np.nan, 0.0], [0.0, 1.0]])
    with pytest.raises(ValueError, match="x has dimension"):
        vtrack.Gaussian([0.0, 0.0], np.eye(2)).log_pdf([1.0, 2.0, 3.0])
