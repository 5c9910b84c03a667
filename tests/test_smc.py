"""vtrack.ParticleFilter and vtrack.MCMCParticleFilter against a NumPy Kalman filter, NumPy
transcriptions of the models, and the documented failure behaviour."""

import numpy as np
import pytest

import vtrack
from vtrack import models

T, Q_INTENSITY = 1.0, 0.5
H = np.array([[1.0, 0, 0, 0], [0, 0, 1.0, 0]])
R = 4.0 * np.eye(2)
M0 = np.array([0.0, 1.0, 0.0, -0.5])
P0 = np.diag([10.0, 1.0, 10.0, 1.0])


def cv_matrices(q=Q_INTENSITY, period=T):
    f = np.array([[1.0, period], [0.0, 1.0]])
    qc = q * np.array([[period**3 / 3, period**2 / 2], [period**2 / 2, period]])
    return np.kron(np.eye(2), f), np.kron(np.eye(2), qc)


def simulate(seed, steps=10):
    F, Q = cv_matrices()
    rng = np.random.default_rng(seed)
    x = rng.multivariate_normal(M0, P0)
    zs = []
    for _ in range(steps):
        x = F @ x + rng.multivariate_normal(np.zeros(4), Q)
        zs.append(H @ x + rng.multivariate_normal(np.zeros(2), R))
    return np.array(zs)


def kalman(zs):
    """The exact posteriors and log p(z_1:k) of the linear-Gaussian model (NumPy transcription)."""
    F, Q = cv_matrices()
    m, P = M0.copy(), P0.copy()
    out, log_evidence = [], 0.0
    for z in zs:
        m, P = F @ m, F @ P @ F.T + Q
        S = H @ P @ H.T + R
        v = z - H @ m
        log_evidence += -0.5 * (v @ np.linalg.solve(S, v) + np.log(np.linalg.det(2 * np.pi * S)))
        K = P @ H.T @ np.linalg.inv(S)
        m, P = m + K @ v, (np.eye(4) - K @ H) @ P
        out.append((m, P))
    return out, log_evidence


def make_pf(seed=0, n=20000, motion=None, observation=None, **kwargs):
    return vtrack.ParticleFilter(
        motion if motion is not None else models.ConstantVelocity(axes=2, period=T, q=Q_INTENSITY),
        observation if observation is not None else vtrack.LinearGaussianObservation(H, R),
        prior=vtrack.Gaussian(M0, P0), n_particles=n, seed=seed, **kwargs)


def assert_matches_kalman(make, zs, runs=20, what=""):
    """Over `runs` seeded filters on the same measurements: the mean of their estimates is within
    5 standard errors (their own spread / sqrt(runs)) of the Kalman mean at every step, the spread
    is at most 10 sqrt(P_ii / N_eff), N_eff the smallest mean ESS so far (resampling noise
    accumulates after a degenerate update: measured up to 6 with that N_eff), the particle
    covariance averages to P within 15% (after a degenerate update, ESS/N ~ 0.05, a finite
    resampled cloud underestimates it: measured 12% low at N = 4000, 3% at N = 40000), and
    log_evidence averages to the Kalman marginal log-likelihood within 4 standard errors."""
    exact, log_evidence = kalman(zs)
    means = np.empty((runs, len(zs), 4))
    covs = np.zeros((len(zs), 4, 4))
    evidence = np.empty(runs)
    ess = np.zeros(len(zs))
    for r in range(runs):
        pf = make(1000 + r)
        for k, z in enumerate(zs):
            means[r, k] = pf.step(z)
            ess[k] += pf.ess / runs
            covs[k] += np.cov(pf.particles.T, aweights=pf.weights, bias=True) / runs
        evidence[r] = pf.log_evidence
    sd = means.std(axis=0, ddof=1)
    n_eff = np.minimum.accumulate(ess)
    for k, (m, P) in enumerate(exact):
        assert np.all(np.abs(means[:, k].mean(axis=0) - m) <= 5 * sd[k] / np.sqrt(runs)), (what, k)
        assert np.all(sd[k] < 10 * np.sqrt(np.diag(P) / n_eff[k])), (what, k)
        assert np.allclose(np.diag(covs[k]), np.diag(P), rtol=0.15), (what, k)
    e_sd = evidence.std(ddof=1)
    assert abs(evidence.mean() - log_evidence) <= 4 * e_sd / np.sqrt(runs), what
    assert e_sd < 0.5
    return pf


# ---- the SIR filter against the Kalman filter ------------------------------------------------

def test_sir_matches_kalman_and_its_evidence():
    assert_matches_kalman(lambda seed: make_pf(seed, n=4000), simulate(1), what="sir")


def test_resample_move_and_selective_resampling_match_kalman():
    zs = simulate(4)
    pf = assert_matches_kalman(lambda seed: make_pf(seed, n=10000, resample_move_steps=2), zs,
                               what="resample-move")
    assert 0.05 < pf.acceptance_rate < 0.95
    assert_matches_kalman(lambda seed: make_pf(seed, n=10000, ess_threshold=0.3), zs,
                          what="selective")


def test_selective_resampling_triggers_exactly_at_the_threshold():
    zs = simulate(5, steps=30)
    pf = make_pf(5, n=2000, ess_threshold=0.5)
    outcomes = []
    for z in zs:
        pf.step(z)
        assert pf.resampled == (pf.ess <= 0.5 * 2000)
        outcomes.append(pf.resampled)
    assert any(outcomes) and not all(outcomes)
    if pf.resampled:
        assert np.allclose(pf.weights, 1 / 2000)


def test_same_seed_same_particles_and_threads_do_not_matter():
    zs = simulate(6)
    runs = []
    for seed, threads in ((7, 1), (7, 2), (7, 0), (8, 1)):
        pf = make_pf(seed, n=5000, threads=threads)
        for z in zs:
            pf.step(z)
        runs.append((pf.particles, pf.log_evidence))
    for particles, evidence in runs[1:3]:
        assert np.array_equal(particles, runs[0][0]) and evidence == runs[0][1]
    assert not np.array_equal(runs[3][0], runs[0][0])
    # Seeds are unsigned 64-bit.
    make_pf(2**64 - 1, n=10).step(zs[0])
    with pytest.raises(ValueError, match="seed must be an int in"):
        make_pf(-1, n=10)


def test_float32_states_match_kalman_and_draw_the_float64_numbers():
    zs = simulate(10)
    pf = assert_matches_kalman(lambda seed: make_pf(seed, n=4000, dtype="float32"), zs,
                               what="float32")
    assert pf.particles.dtype == np.float32 and pf.weights.dtype == np.float64
    # Same seed: the same random draws, so the first estimate agrees to float round-off.
    single, double = make_pf(3, n=3000, dtype=np.float32), make_pf(3, n=3000)
    assert np.allclose(single.particles, double.particles, rtol=0, atol=1e-5)
    assert np.allclose(single.step(zs[0]), double.step(zs[0]), rtol=0, atol=1e-5)
    # Range-bearing too (the benchmark's problem): it filters as well as float64.
    truth, rb = range_bearing_problem()
    prior = vtrack.Gaussian([120, 1, 60, 1.5], np.diag([25.0, 1, 25, 1]))
    est = {}
    for dtype in ("float32", "float64"):
        f = vtrack.ParticleFilter(models.ConstantVelocity(q=0.25), models.RangeBearingObservation(),
                                  prior=prior, n_particles=5000, seed=4, dtype=dtype)
        est[dtype] = np.array([f.step(z) for z in rb])
    errors = {d: np.sqrt(np.mean((e[:, 0] - truth[:, 0]) ** 2 + (e[:, 2] - truth[:, 2]) ** 2))
              for d, e in est.items()}
    assert errors["float32"] < 5.0 and abs(errors["float32"] - errors["float64"]) < 0.5
    with pytest.raises(TypeError, match="float32.*built-in"):
        vtrack.ParticleFilter(models.ConstantVelocity(q=0.25), NumpyRangeBearing(), prior=prior,
                              dtype="float32")
    with pytest.raises(ValueError, match="dtype must be float64 or float32, got int32"):
        make_pf(dtype="int32")


# ---- models ---------------------------------------------------------------------------------

def test_motion_models_are_the_papers_matrices():
    F, Q = cv_matrices(q=0.25, period=0.5)
    cv = models.ConstantVelocity(axes=2, period=0.5, q=0.25)
    assert np.allclose(cv.F, F) and np.allclose(cv.Q, Q)
    g = np.array([0.5**2 / 2, 0.5])
    discrete = models.ConstantVelocity(axes=3, period=0.5, q=0.25, noise="discrete")
    assert np.allclose(discrete.Q, np.kron(np.eye(3), 0.25 * np.outer(g, g)))
    assert discrete.noise_dim == 3
    ar = models.SecondOrderAutoRegressive(sigma=[1.0, 2.0])  # eq. 13 on [X_k, X_k-1]
    assert np.allclose(ar.F, [[2, 0, -1, 0], [0, 2, 0, -1], [1, 0, 0, 0], [0, 1, 0, 0]])
    assert np.allclose(ar.Q, np.diag([1.0, 4.0, 0, 0]))
    rw = models.RandomWalk(sigma=2.0, dims=3)
    assert np.allclose(rw.Q, 4 * np.eye(3)) and rw.dim == 3
    assert models.RandomWalk(sigma=[1.0, 2.0]).dim == 2
    with pytest.raises(ValueError):
        models.ConstantVelocity(noise="white")
    with pytest.raises(ValueError):
        models.RandomWalk(sigma=[1.0, -1.0])


def range_bearing_log_likelihood(particles, z, sigma_range=1.0, sigma_bearing=0.01):
    """NumPy transcription of the range-bearing likelihood (sensor at the origin)."""
    dx, dy = particles[:, 0], particles[:, 2]
    dr = np.hypot(dx, dy) - z[0]
    db = np.angle(np.exp(1j * (np.arctan2(dy, dx) - z[1])))  # wrapped to (-pi, pi]
    return (-np.log(2 * np.pi * sigma_range * sigma_bearing)
            - 0.5 * (dr / sigma_range) ** 2 - 0.5 * (db / sigma_bearing) ** 2)


def test_range_bearing_likelihood_matches_numpy():
    rng = np.random.default_rng(1)
    x = rng.normal(size=(500, 4)) * 80
    obs = models.RangeBearingObservation(sigma_range=1.0, sigma_bearing=0.01)
    for z in ([100.0, 0.3], [80.0, np.pi - 1e-3], [80.0, -np.pi + 1e-3]):
        assert np.allclose(obs.log_likelihood(x, z), range_bearing_log_likelihood(x, np.array(z)),
                           rtol=1e-9)


class NumpyRangeBearing:
    def log_likelihood(self, particles, z):
        return range_bearing_log_likelihood(particles, z)


class NumpyConstantVelocity:
    dim = 4

    def __init__(self, q=0.25):
        self.F, Q = cv_matrices(q=q)
        self.L = np.linalg.cholesky(Q)

    def propagate(self, particles, rng):
        return particles @ self.F.T + rng.standard_normal(particles.shape) @ self.L.T


def range_bearing_problem(seed=0, steps=30):
    F, Q = cv_matrices(q=0.25)
    rng = np.random.default_rng(seed)
    x = np.array([120.0, 1.0, 60.0, 1.5])
    truth, zs = [], []
    for _ in range(steps):
        x = F @ x + rng.multivariate_normal(np.zeros(4), Q)
        truth.append(x)
        zs.append([np.hypot(x[0], x[2]) + rng.normal(), np.arctan2(x[2], x[0]) + 0.01 * rng.normal()])
    return np.array(truth), np.array(zs)


def test_python_observation_gives_the_builtin_results():
    # Same motion noise (same seed, built-in motion): a NumPy likelihood equal to the built-in one
    # up to rounding gives the same estimates.
    truth, zs = range_bearing_problem()
    prior = vtrack.Gaussian([120, 1, 60, 1.5], np.diag([25.0, 1, 25, 1]))
    motion = models.ConstantVelocity(q=0.25)
    builtin = vtrack.ParticleFilter(motion, models.RangeBearingObservation(), prior=prior,
                                    n_particles=5000, seed=3)
    python = vtrack.ParticleFilter(motion, NumpyRangeBearing(), prior=prior, n_particles=5000, seed=3)
    a = np.array([builtin.step(z) for z in zs])
    b = np.array([python.step(z) for z in zs])
    assert np.allclose(a, b, rtol=1e-6, atol=1e-6)
    rmse = np.sqrt(np.mean((a[:, 0] - truth[:, 0]) ** 2 + (a[:, 2] - truth[:, 2]) ** 2))
    assert rmse < 5.0
    assert builtin.log_evidence == pytest.approx(python.log_evidence, abs=1e-6)


def test_python_motion_filters_like_the_builtin_one():
    assert_matches_kalman(
        lambda seed: make_pf(seed, n=2000, motion=NumpyConstantVelocity(q=Q_INTENSITY)),
        simulate(9), what="python motion")
    # Both models in Python.
    both = vtrack.ParticleFilter(NumpyConstantVelocity(), NumpyRangeBearing(),
                                 prior=vtrack.Gaussian([120, 1, 60, 1.5], np.diag([25.0, 1, 25, 1])),
                                 n_particles=2000, seed=1)
    truth, rb = range_bearing_problem()
    est = np.array([both.step(z) for z in rb])
    assert np.sqrt(np.mean((est[:, 0] - truth[:, 0]) ** 2 + (est[:, 2] - truth[:, 2]) ** 2)) < 5.0


def test_linear_gaussian_motion_and_second_order_models_filter():
    F, Q = cv_matrices()
    assert_matches_kalman(
        lambda seed: make_pf(seed, n=2000, motion=vtrack.LinearGaussianMotion(F, Q)),
        simulate(10), what="LinearGaussianMotion")
    ar = vtrack.ParticleFilter(models.SecondOrderAutoRegressive(sigma=0.5, dims=2),
                               vtrack.LinearGaussianObservation(np.eye(2, 4), np.eye(2)),
                               prior=vtrack.Gaussian(np.zeros(4), np.eye(4)), n_particles=1000,
                               resample_move_steps=1)
    assert ar.step([0.5, -0.5]).shape == (4,)
    assert ar.predict().shape == (4,)


# ---- failure behaviour ----------------------------------------------------------------------

def test_bad_arguments_raise_named_errors():
    prior = vtrack.Gaussian(M0, P0)
    cv, obs = models.ConstantVelocity(), vtrack.LinearGaussianObservation(H, R)
    with pytest.raises(TypeError, match="motion"):
        vtrack.ParticleFilter(3, obs, prior=prior)
    with pytest.raises(TypeError, match="observation"):
        vtrack.ParticleFilter(cv, "x", prior=prior)
    with pytest.raises(ValueError, match="n_particles"):
        vtrack.ParticleFilter(cv, obs, prior=prior, n_particles=0)
    with pytest.raises(ValueError, match="ess_threshold"):
        vtrack.ParticleFilter(cv, obs, prior=prior, ess_threshold=1.5)
    with pytest.raises(ValueError, match="resampling"):
        vtrack.ParticleFilter(cv, obs, prior=prior, resampling="best")
    with pytest.raises(ValueError, match="dimension"):
        vtrack.ParticleFilter(cv, obs, prior=vtrack.Gaussian([0.0], [[1.0]]))
    with pytest.raises(ValueError, match="positive"):
        vtrack.Gaussian(M0, -P0)
    with pytest.raises(ValueError, match="Q"):
        vtrack.ParticleFilter(vtrack.LinearGaussianMotion(np.eye(4), -np.eye(4)), obs, prior=prior)
    with pytest.raises(ValueError, match="R"):
        vtrack.ParticleFilter(cv, vtrack.LinearGaussianObservation(H, -R), prior=prior)
    pf = vtrack.ParticleFilter(cv, obs, prior=prior, n_particles=100)
    with pytest.raises(ValueError, match="z"):
        pf.step([1.0, np.nan])
    with pytest.raises(ValueError, match="z"):
        pf.step([1.0, 2.0, 3.0])
    assert pf.steps == 0


def test_python_models_with_wrong_output_raise():
    prior = vtrack.Gaussian(M0, P0)

    class WrongShape:
        dim = 4

        def propagate(self, particles, rng):
            return particles[:-1]

    class NanLikelihood:
        def log_likelihood(self, particles, z):
            out = np.zeros(len(particles))
            out[3] = np.nan
            return out

    with pytest.raises(ValueError, match="propagate"):
        vtrack.ParticleFilter(WrongShape(), vtrack.LinearGaussianObservation(H, R), prior=prior,
                              n_particles=50).step([0.0, 0.0])
    with pytest.raises(ValueError, match="particle 3"):
        vtrack.ParticleFilter(models.ConstantVelocity(), NanLikelihood(), prior=prior,
                              n_particles=50).step([0.0, 0.0])
    with pytest.raises(ValueError, match="resample_move"):
        vtrack.ParticleFilter(NumpyConstantVelocity(), vtrack.LinearGaussianObservation(H, R),
                              prior=prior, resample_move_steps=1)


def test_all_likelihoods_zero_keeps_the_weights_and_gives_no_nan():
    class Nowhere:
        def log_likelihood(self, particles, z):
            return np.full(len(particles), -np.inf)

    pf = vtrack.ParticleFilter(models.ConstantVelocity(), Nowhere(), prior=vtrack.Gaussian(M0, P0),
                               n_particles=300)
    mean = pf.step([0.0])
    assert np.all(np.isfinite(mean)) and np.all(np.isfinite(pf.map_estimate))
    assert pf.log_evidence == -np.inf
    assert np.allclose(pf.weights, 1 / 300)


# ---- the MCMC particle filter ---------------------------------------------------------------

@pytest.mark.parametrize("reference", ["all", "random", "map", "mean"])
def test_mcmc_filter_tracks_and_counts_its_proposals(reference):
    zs = simulate(11)
    exact, _ = kalman(zs)
    mc = vtrack.MCMCParticleFilter(models.ConstantVelocity(period=T, q=Q_INTENSITY),
                                   vtrack.LinearGaussianObservation(H, R),
                                   prior=vtrack.Gaussian(M0, P0), n_particles=1000, burn_in=200,
                                   thinning=3, reference=reference, proposal_scale=1.0, seed=2)
    for k, z in enumerate(zs):
        mean = mc.step(z)
        assert mc.proposals == 200 + 3 * 1000
        assert mc.particles.shape == (1000, 4)
        assert 0.05 < mc.acceptance_rate < 0.95
        assert np.allclose(mean, mc.particles.mean(axis=0))
    if reference == "all":  # the exact filtering recursion: the Kalman posterior, within MC error
        m, P = exact[-1]
        assert np.all(np.abs(mean - m) < 6 * np.sqrt(np.diag(P) * 8 / 1000))
    # (The x* variants condition on one previous sample as if it were exact, so they are not
    # consistent filters; cpp/tests/test_smc_mcmc.cpp checks that each samples its own target.)


def test_mcmc_filter_refusals():
    prior = vtrack.Gaussian(M0, P0)
    obs = vtrack.LinearGaussianObservation(H, R)
    with pytest.raises(ValueError, match="singular"):
        vtrack.MCMCParticleFilter(models.ConstantVelocity(noise="discrete"), obs, prior=prior,
                                  reference="all")
    with pytest.raises(TypeError, match="built-in motion"):
        vtrack.MCMCParticleFilter(NumpyConstantVelocity(), obs, prior=prior)
    with pytest.raises(ValueError, match="reference"):
        vtrack.MCMCParticleFilter(models.ConstantVelocity(), obs, prior=prior, reference="best")
    mc = vtrack.MCMCParticleFilter(models.ConstantVelocity(noise="discrete"), NumpyRangeBearing(),
                                   prior=vtrack.Gaussian([120, 1, 60, 1.5], np.diag([25.0, 1, 25, 1])),
                                   n_particles=50, burn_in=10, thinning=1, reference="map")
    assert np.all(np.isfinite(mc.step([134.0, 0.46])))
    with pytest.raises(ValueError, match="z"):
        mc.step([np.nan, 0.0])


# ---- the tracker surface (issue 9): parameter tables, keywords, default_params -------------

def test_keywords_go_through_the_parameter_tables():
    assert vtrack.ParticleFilter.default_params() == {
        "n_particles": 1000, "resampling": "systematic", "ess_threshold": 1.0,
        "resample_move_steps": 0, "move_scale": 0.5, "threads": 1, "seed": 0}
    assert vtrack.MCMCParticleFilter.default_params() == {
        "n_particles": 1000, "burn_in": 500, "thinning": 2, "reference": "all",
        "proposal_scale": 0.5, "seed": 0}
    pf = make_pf(3, n=10, ess_threshold=0.5, resampling="residual")
    assert pf.params == {**vtrack.ParticleFilter.default_params(), "n_particles": 10,
                         "ess_threshold": 0.5, "resampling": "residual", "seed": 3}
    with pytest.raises(TypeError, match="did you mean 'ess_threshold'"):
        make_pf(n=10, ess_treshold=0.5)
    with pytest.raises(TypeError, match="burn_in"):
        make_pf(n=10, burn_in=3)  # an MCMC parameter
    with pytest.raises(TypeError, match="n_particles"):
        make_pf(n=10.5)
    mc = vtrack.MCMCParticleFilter(models.ConstantVelocity(), vtrack.LinearGaussianObservation(H, R),
                                   prior=vtrack.Gaussian(M0, P0), reference="map", burn_in=7)
    assert mc.params["reference"] == "map" and mc.params["burn_in"] == 7
    with pytest.raises(ValueError, match="reference"):
        vtrack.MCMCParticleFilter(models.ConstantVelocity(), vtrack.LinearGaussianObservation(H, R),
                                  prior=vtrack.Gaussian(M0, P0), reference="best")
