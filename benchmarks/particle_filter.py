"""SIR and resample-move particle filters on the range-bearing problem: vtrack vs NumPy and the
Python particle-filter libraries, one thread.

Usage: python benchmarks/particle_filter.py [--sizes 1000 10000 100000 1000000] [--repeats 3]
                                            [--budget 60] [--clock cpu|wall]

The problem (issue 10), which every peer can run: state [px, vx, py, vy], T = 1, continuous
white-noise acceleration Q = q [[1/3, 1/2], [1/2, 1]] per axis with q = 0.25; z = [range, bearing]
with sigma 1.0 m and 0.01 rad from a sensor at the origin; truth from [120, 1.0, 60, 1.5] over 100
steps (NumPy seed 0); prior N([120, 1, 60, 1.5], diag(25, 1, 25, 1)) for the state one step
before the first measurement; bootstrap SIR resampling every step (systematic). Every filter runs
the same 100 measurements. Columns: particle-steps per second (N x 100 / the median time of the
100 steps over --repeats runs; construction excluded), the ratio to the NumPy reference at the same
N, and the position RMSE of the weighted-mean estimate against the truth.

Rows:
  vtrack SIR                 vtrack.ParticleFilter, built-in ConstantVelocity + RangeBearingObservation
  vtrack SIR, float32        the same with dtype="float32" (single-precision states and residuals;
                             weights, estimates and evidence in double)
  vtrack SIR, Python obs.    the same with the likelihood as a NumPy callback (called once per step)
  vtrack SIR, Python models  motion and likelihood both NumPy callbacks
  NumPy SIR (reference)      a vectorised NumPy SIR written for speed in this file (structured CV
                             update on four 1-D arrays, SFC64 normals, rotated-frame bearing residual
                             with one arctan2, O(N) systematic resampling by np.repeat)
  NumPy SIR, float32         the reference with float32 states, normals and likelihood (float64
                             weights), the peer of vtrack's float32 row
  NumPy SIR + FilterPy       the reference with filterpy.monte_carlo.systematic_resample
  particles (Chopin)         particles.SMC with a Bootstrap Feynman-Kac model, ESSrmin = 1
  Stone Soup                 ParticlePredictor + ParticleUpdater(SystematicResampler)
  pfilter                    pfilter.ParticleFilter (its systematic resampling, n_eff_threshold 1)
Resample-move rows (SIR then one Metropolis-Hastings move per particle after each resampling):
  vtrack resample-move       ParticleFilter(resample_move_steps=1): a random walk on the particle's
                             process noise (scale 0.5), target p(x_k | x_k-1, z_k)
  NumPy resample-move        the NumPy reference plus the same move, vectorised
  Stone Soup MCMC            ParticleUpdater(..., regulariser=MCMCRegulariser(transition_model))

A peer missing from the environment (requirements/bench.txt) is skipped; a peer whose run at
some N took longer than --budget seconds is not run at larger N.

The machine's floor for this problem is the cost of the random numbers and exponentials alone:
4 normals and 1 exp per particle-step. This script prints NumPy's (standard_normal + exp);
vtrack's is in benchmarks/cpp/smc_micro.cpp (LaneRng normals + core::vmath::exp, and the SIR step
split by stage), whose header holds the measured figures.

Measured 2026-11-28 (an AMD EPYC with AVX-512, 2 vCPUs shared with other agents' builds and
benchmarks, load average 6-10; `--sizes 1000 10000 100000 --repeats 5 --clock cpu`; particle-steps/s,
ratio to the NumPy reference, position RMSE in m):

| N | vtrack SIR | vtrack float32 | Python obs. | Python models | NumPy ref. | NumPy float32 | particles | Stone Soup | floor |
|---|---|---|---|---|---|---|---|---|---|
| 1e3 | 150.3 M (13.6x) | 174.5 M (15.8x) | 50.7 M | 14.0 M | 11.1 M | 11.2 M | 2.9 M | 0.69 M | 32.2 M |
| 1e4 | 153.1 M (9.3x) | 203.2 M (12.3x) | 82.3 M | 15.6 M | 16.5 M | 18.0 M | 5.5 M | 2.1 M | 34.8 M |
| 1e5 | 126.7 M (7.3x) | 181.4 M (10.5x) | 65.1 M | 15.2 M | 17.3 M | 18.9 M | 7.0 M | 2.9 M | 33.2 M |

RMSE 2.12-2.25 m for every filter (2.14-2.15 at 1e5). Resample-move at 1e5: vtrack 48.7 M (float32
77.1 M), NumPy 6.7 M, Stone Soup's MCMC regulariser 1.58 M: vtrack 31x Stone Soup (bar 10x: met).
The issue's bar at 1e5, 10x the NumPy reference at the same RMSE: met by the float32 filter
(10.5x; 9.6x against the NumPy filter in float32 too, the like-for-like comparison), not by the
double one (7.3x). At N = 1e5 the double filter's states (3.2 MB per buffer) no longer fit in L2
and its step is bound by memory traffic (propagation alone 1.2 ns per particle); the float
filter's step is 4.7-4.8 ns per particle-step on these measurements (4.5 with smc_micro's fixed
measurement), against a floor of 1.5 ns for the 4 normals and the exp alone (smc_micro.cpp). What
the float step spends (perf, N = 1e5): normals 19 %, resampling 17 %, weights 15 %, likelihood
14 %, gather 11 %, propagation 8 %, weighted sums 7 %; smc_micro.cpp's header has what changed
since the last table (6.0 -> 4.5 ns). On 2026-11-24's machine (an AVX2 EPYC) the NumPy reference
ran at 9-11 M/s and vtrack's double SIR at 41-50 M/s (4.4x at 1e5); the ratio depends on the
machine, so compare within one run.
"""

import argparse
import os
import sys
import time
from datetime import datetime, timedelta
from statistics import median

# One thread for every peer (BLAS, numba).
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(__file__))
from _table import print_table  # noqa: E402

import vtrack  # noqa: E402
from vtrack import models  # noqa: E402

STEPS = 100
T = 1.0
Q_INTENSITY = 0.25
SIGMA_RANGE, SIGMA_BEARING = 1.0, 0.01
X0 = np.array([120.0, 1.0, 60.0, 1.5])
P0 = np.diag([25.0, 1.0, 25.0, 1.0])
MOVE_SCALE = 0.5

F = np.kron(np.eye(2), np.array([[1.0, T], [0.0, 1.0]]))
Q = np.kron(np.eye(2), Q_INTENSITY * np.array([[T**3 / 3, T**2 / 2], [T**2 / 2, T]]))
L = np.linalg.cholesky(Q)
LA, LB, LC = L[0, 0], L[1, 0], L[1, 1]  # per-axis Cholesky factor [[a, 0], [b, c]]


def simulate(seed=0):
    rng = np.random.default_rng(seed)
    x = X0.copy()
    truth, zs = [], []
    for _ in range(STEPS):
        x = F @ x + L @ rng.standard_normal(4)
        truth.append(x)
        zs.append([np.hypot(x[0], x[2]) + SIGMA_RANGE * rng.standard_normal(),
                   np.arctan2(x[2], x[0]) + SIGMA_BEARING * rng.standard_normal()])
    return np.array(truth), np.array(zs)


def rmse(estimates, truth):
    d = estimates[:, [0, 2]] - truth[:, [0, 2]]
    return float(np.sqrt(np.mean(np.sum(d * d, axis=1))))


# ---- the NumPy reference -------------------------------------------------------------------

def numpy_log_likelihood(px, py, z):
    # Bearing residual as the angle of p rotated by -z_bearing: one arctan2, already wrapped. In
    # the states' precision (the constants cast to it, so float32 states stay float32).
    f = px.dtype.type
    c, s = f(np.cos(z[1])), f(np.sin(z[1]))
    rng_res = np.sqrt(px * px + py * py)
    rng_res -= f(z[0])
    bearing_res = np.arctan2(c * py - s * px, c * px + s * py)
    ll = rng_res * rng_res
    ll *= f(1.0 / SIGMA_RANGE**2)
    ll += (bearing_res * f(1.0 / SIGMA_BEARING)) ** 2
    ll *= f(-0.5)
    return ll


def numpy_systematic(w, u, arange):
    """O(N) systematic resampling: particle i gets ceil(C_i N - u) - ceil(C_{i-1} N - u) copies."""
    n = len(w)
    upto = np.ceil(np.cumsum(w) * n - u)
    np.clip(upto, 0, n, out=upto)
    counts = np.diff(upto, prepend=0.0).astype(np.int64)
    idx = np.repeat(arange, counts)
    if len(idx) < n:  # round-off at the end of the cumulative sum
        idx = np.concatenate([idx, np.full(n - len(idx), np.flatnonzero(w)[-1])])
    return idx


def numpy_sir(n, zs, seed, moves=0, resampler=None, dtype=np.float64):
    """dtype float32: states, normals, likelihood and exp in float32 (NumPy's float32 ziggurat
    normals), weights and estimates in float64, as vtrack's dtype="float32"."""
    rng = np.random.Generator(np.random.SFC64(seed))
    x0 = X0[:, None] + rng.standard_normal((4, n)) * np.sqrt(np.diag(P0))[:, None]
    px, vx, py, vy = (np.ascontiguousarray(r, dtype=dtype) for r in x0)
    t, la, lb, lc = (dtype(v) for v in (T, LA, LB, LC))
    arange = np.arange(n)
    est = np.empty((len(zs), 4))
    start = time.perf_counter(), time.process_time()
    for k, z in enumerate(zs):
        e = rng.standard_normal((4, n), dtype=dtype)
        prev = (px, vx, py, vy)
        px = px + t * vx + la * e[0]
        vx = vx + lb * e[0] + lc * e[1]
        py = py + t * vy + la * e[2]
        vy = vy + lb * e[2] + lc * e[3]
        ll = numpy_log_likelihood(px, py, z)
        w = np.exp(ll - ll.max())
        if w.dtype != np.float64:
            w = w.astype(np.float64)
        w /= w.sum()
        est[k] = (w @ px, w @ vx, w @ py, w @ vy)
        if resampler is None:
            idx = numpy_systematic(w, rng.random(), arange)
        else:
            idx = resampler(w)
        px, vx, py, vy = px[idx], vx[idx], py[idx], vy[idx]
        if moves:
            prev = tuple(a[idx] for a in prev)
            e, ll = e[:, idx], ll[idx]
            for _ in range(moves):
                e2 = e + MOVE_SCALE * rng.standard_normal((4, n))
                qx = prev[0] + T * prev[1] + LA * e2[0]
                qvx = prev[1] + LB * e2[0] + LC * e2[1]
                qy = prev[2] + T * prev[3] + LA * e2[2]
                qvy = prev[3] + LB * e2[2] + LC * e2[3]
                ll2 = numpy_log_likelihood(qx, qy, z)
                log_alpha = ll2 - ll - 0.5 * (np.einsum("ij,ij->j", e2, e2) - np.einsum("ij,ij->j", e, e))
                take = np.log(rng.random(n)) < log_alpha
                px, vx, py, vy = (np.where(take, a, b) for a, b in ((qx, px), (qvx, vx), (qy, py), (qvy, vy)))
                e = np.where(take, e2, e)
                ll = np.where(take, ll2, ll)
    return est, start


# ---- vtrack ------------------------------------------------------------------------------

class NumpyRangeBearing:
    def log_likelihood(self, particles, z):
        return numpy_log_likelihood(particles[:, 0], particles[:, 2], z)


class NumpyConstantVelocity:
    dim = 4

    def propagate(self, particles, rng):
        return particles @ F.T + rng.standard_normal(particles.shape) @ L.T


def vtrack_sir(n, zs, seed, moves=0, python_obs=False, python_motion=False, dtype="float64"):
    motion = NumpyConstantVelocity() if python_motion else models.ConstantVelocity(
        axes=2, period=T, q=Q_INTENSITY)
    obs = NumpyRangeBearing() if python_obs else models.RangeBearingObservation(
        sigma_range=SIGMA_RANGE, sigma_bearing=SIGMA_BEARING)
    pf = vtrack.ParticleFilter(motion, obs, prior=vtrack.Gaussian(X0, P0), n_particles=n,
                               resampling="systematic", ess_threshold=1.0, seed=seed,
                               resample_move_steps=moves, move_scale=MOVE_SCALE, threads=1,
                               dtype=dtype)
    est = np.empty((len(zs), 4))
    start = time.perf_counter(), time.process_time()
    for k, z in enumerate(zs):
        est[k] = pf.step(z)
    return est, start


# ---- peers ---------------------------------------------------------------------------------

def particles_sir(n, zs, seed):
    import particles
    from particles import distributions as dists
    from particles import state_space_models as ssm
    from particles.collectors import Moments

    class RangeBearing(ssm.StateSpaceModel):
        def PX0(self):  # the state at the first measurement: the prior propagated once
            return dists.MvNormal(loc=F @ X0, cov=F @ P0 @ F.T + Q)

        def PX(self, t, xp):
            return dists.MvNormal(loc=xp @ F.T, cov=Q)

        def PY(self, t, xp, x):
            return dists.IndepProd(
                dists.Normal(loc=np.hypot(x[:, 0], x[:, 2]), scale=SIGMA_RANGE),
                dists.Normal(loc=np.arctan2(x[:, 2], x[:, 0]), scale=SIGMA_BEARING))

    np.random.seed(seed)
    alg = particles.SMC(fk=ssm.Bootstrap(ssm=RangeBearing(), data=list(zs)), N=n,
                        resampling="systematic", ESSrmin=1.0, collect=[Moments()],
                        store_history=False, verbose=False)
    start = time.perf_counter(), time.process_time()
    alg.run()
    est = np.array([m["mean"] for m in alg.summaries.moments])
    return est, start


def stonesoup_sir(n, zs, seed, mcmc=False):
    from stonesoup.models.measurement.nonlinear import CartesianToBearingRange
    from stonesoup.models.transition.linear import (CombinedLinearGaussianTransitionModel,
                                                    ConstantVelocity)
    from stonesoup.predictor.particle import ParticlePredictor
    from stonesoup.regulariser.particle import MCMCRegulariser
    from stonesoup.resampler.particle import SystematicResampler
    from stonesoup.types.angle import Bearing
    from stonesoup.types.array import StateVector, StateVectors
    from stonesoup.types.detection import Detection
    from stonesoup.types.hypothesis import SingleHypothesis
    from stonesoup.types.state import ParticleState
    from stonesoup.updater.particle import ParticleUpdater

    np.random.seed(seed)
    transition = CombinedLinearGaussianTransitionModel(
        [ConstantVelocity(Q_INTENSITY), ConstantVelocity(Q_INTENSITY)])
    measurement = CartesianToBearingRange(ndim_state=4, mapping=(0, 2),
                                          noise_covar=np.diag([SIGMA_BEARING**2, SIGMA_RANGE**2]))
    predictor = ParticlePredictor(transition)
    updater = ParticleUpdater(measurement, resampler=SystematicResampler(),
                              regulariser=MCMCRegulariser(transition_model=transition) if mcmc else None)
    t0 = datetime(2024, 1, 1)
    samples = np.random.multivariate_normal(X0, P0, size=n)
    state = ParticleState(state_vector=StateVectors(samples.T), log_weight=np.full(n, -np.log(n)),
                          timestamp=t0)
    est = np.empty((len(zs), 4))
    start = time.perf_counter(), time.process_time()
    for k, z in enumerate(zs):
        ts = t0 + timedelta(seconds=T * (k + 1))
        prediction = predictor.predict(state, timestamp=ts)
        detection = Detection(StateVector([Bearing(z[1]), z[0]]), timestamp=ts,
                              measurement_model=measurement)
        state = updater.update(SingleHypothesis(prediction, detection))
        est[k] = np.average(np.asarray(state.state_vector, dtype=float), axis=1,
                            weights=np.exp(np.asarray(state.log_weight, dtype=float)))
    return est, start


def pfilter_sir(n, zs, seed):
    import pfilter

    np.random.seed(seed)
    rng = np.random.default_rng(seed)

    def weight(hypotheses, observed):
        ll = numpy_log_likelihood(hypotheses[:, 0], hypotheses[:, 1], observed[0])
        return np.exp(ll - ll.max())  # pfilter weighs in the linear domain

    pf = pfilter.ParticleFilter(
        prior_fn=lambda m: rng.multivariate_normal(X0, P0, size=m),
        observe_fn=lambda x: x[:, [0, 2]],
        n_particles=n,
        dynamics_fn=lambda x: x @ F.T,
        noise_fn=lambda x: x + rng.standard_normal(x.shape) @ L.T,
        weight_fn=weight,
        n_eff_threshold=1.0)
    est = np.empty((len(zs), 4))
    start = time.perf_counter(), time.process_time()
    for k, z in enumerate(zs):
        pf.update(np.asarray(z))
        est[k] = pf.mean_state
    return est, start


def filterpy_resampler():
    from filterpy.monte_carlo import systematic_resample
    return systematic_resample


# ---- driver --------------------------------------------------------------------------------

def available(module):
    try:
        __import__(module)
        return True
    except Exception:
        return False


_warmed = set()


def measure(run, n, zs, truth, repeats, clock):
    if run not in _warmed:  # imports, JIT compilation (numba in particles), first-call caches
        run(min(n, 1000), zs[:5], 0)
        _warmed.add(run)
    times, err = [], None
    for r in range(repeats):
        est, (wall0, cpu0) = run(n, zs, r + 1)
        elapsed = (time.process_time() - cpu0) if clock == "cpu" else (time.perf_counter() - wall0)
        times.append(elapsed)
        err = rmse(est, truth) if err is None else err
    return median(times), err


def floor_numpy(n, repeats, clock):
    rng = np.random.Generator(np.random.SFC64(0))
    x = rng.standard_normal(n)
    tick = time.process_time if clock == "cpu" else time.perf_counter
    samples = []
    for _ in range(max(repeats, 5)):
        t0 = tick()
        rng.standard_normal((4, n))
        np.exp(x)
        samples.append(tick() - t0)
    return median(samples)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=float, nargs="+", default=[1e3, 1e4, 1e5, 1e6])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--budget", type=float, default=60.0,
                        help="seconds per run above which a peer is not run at larger N")
    parser.add_argument("--clock", choices=("cpu", "wall"), default="cpu",
                        help="process CPU time (robust to other load; every row is one thread) "
                             "or wall time")
    args = parser.parse_args()

    truth, zs = simulate(0)
    sir = [("vtrack SIR", lambda n, z, s: vtrack_sir(n, z, s)),
           ("vtrack SIR, float32", lambda n, z, s: vtrack_sir(n, z, s, dtype="float32")),
           ("vtrack SIR, Python obs.", lambda n, z, s: vtrack_sir(n, z, s, python_obs=True)),
           ("vtrack SIR, Python models",
            lambda n, z, s: vtrack_sir(n, z, s, python_obs=True, python_motion=True)),
           ("NumPy SIR (reference)", lambda n, z, s: numpy_sir(n, z, s)),
           ("NumPy SIR, float32", lambda n, z, s: numpy_sir(n, z, s, dtype=np.float32))]
    if available("filterpy"):
        resampler = filterpy_resampler()

        def filterpy_run(n, z, s):
            np.random.seed(s)
            return numpy_sir(n, z, s, resampler=resampler)
        sir.append(("NumPy SIR + FilterPy resampling", filterpy_run))
    if available("particles"):
        sir.append(("particles (Chopin)", particles_sir))
    if available("stonesoup"):
        sir.append(("Stone Soup", lambda n, z, s: stonesoup_sir(n, z, s)))
    if available("pfilter"):
        sir.append(("pfilter", pfilter_sir))
    moves = [("vtrack resample-move", lambda n, z, s: vtrack_sir(n, z, s, moves=1)),
             ("vtrack resample-move, float32",
              lambda n, z, s: vtrack_sir(n, z, s, moves=1, dtype="float32")),
             ("NumPy resample-move", lambda n, z, s: numpy_sir(n, z, s, moves=1))]
    if available("stonesoup"):
        moves.append(("Stone Soup MCMC regulariser", lambda n, z, s: stonesoup_sir(n, z, s, mcmc=True)))

    missing = [m for m in ("filterpy", "particles", "stonesoup", "pfilter") if not available(m)]
    print(f"Range-bearing SIR, {STEPS} steps, one thread, {args.clock} time, median of "
          f"{args.repeats}; particle-steps/s = N x {STEPS} / time\n")
    for title, group, reference in (("Bootstrap SIR, systematic resampling every step", sir,
                                     "NumPy SIR (reference)"),
                                    ("Resample-move (one MH move per particle per step)", moves,
                                     "NumPy resample-move")):
        rows, skipped = [], set()
        for n in (int(s) for s in args.sizes):
            results = {}
            for name, run in group:
                if name in skipped:
                    continue
                seconds, err = measure(run, n, zs, truth, args.repeats if n <= 100_000 else 1,
                                       args.clock)
                results[name] = (seconds, err)
                if seconds > args.budget:
                    skipped.add(name)
            ref = results[reference][0]
            for name, (seconds, err) in results.items():
                rate = n * STEPS / seconds
                rows.append([f"{n:,}", name, f"{rate / 1e6:.2f} M", f"{ref / seconds:.2f}x",
                             f"{err:.2f}"])
            floor = floor_numpy(n, args.repeats, args.clock)
            rows.append([f"{n:,}", "(floor: NumPy 4 normals + 1 exp)", f"{n / floor / 1e6:.2f} M",
                         f"{ref / (floor * STEPS):.2f}x", ""])
        print(f"### {title}\n")
        print_table(["N", "filter", "particle-steps/s", "vs NumPy", "position RMSE (m)"], rows)
        if skipped:
            print(f"\nNot run at larger N (a run took more than {args.budget:.0f} s): "
                  + ", ".join(sorted(skipped)))
        print()
    if missing:
        print("Not installed (pip install -r requirements/bench.txt; particles with --no-deps, "
              "see requirements/bench-nodeps.txt): " + ", ".join(missing))


if __name__ == "__main__":
    main()
