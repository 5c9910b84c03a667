"""Fuzz the public Python API: constructors, step functions and the free functions of vtrack's
submodules, called with arrays of random dtype, shape and values and with parameters of random
kind and size. Each input picks one entry point of TARGETS and builds its arguments from the fuzz
data; most arguments are plausible (so calls get past the first check) and some are hostile
(NaN, inf, huge ints, wrong dtypes and shapes, 0-sized arrays, non-contiguous or read-only
arrays, unknown keywords). Sizes stay small: the contract is about correctness, not load.

    .venv/bin/python fuzz/fuzz_api.py -max_total_time=60 fuzz/corpus/api
"""

from __future__ import annotations

import os
import sys

import atheris

# Coverage feedback from vtrack's Python code only: the compiled module is not instrumented, and
# instrumenting NumPy and OpenCV's Python parts took ~20 s per harness start for nothing.
with atheris.instrument_imports(include=["vtrack"]):
    import numpy as np
    import vtrack
    from vtrack import assign, image, io, metrics, models, smc

from _common import SCRATCH, check

SPECIAL_NUMBERS = [0, 1, -1, 2, 0.5, -0.5, 1e-300, 1e300, -1e300, float("nan"), float("inf"),
                   float("-inf"), 2**31, 2**31 - 1, -2**31 - 1, 2**53 + 1, 2**63, 2**64, -2**63 - 1]
ODD_VALUES = [None, True, "x", b"x", [], [1, 2], (1, 2, 3), {"a": 1}, 1j, object()]
DTYPES = [np.uint8, np.float32, np.float64, np.int64, np.int32, np.uint16, np.bool_,
          np.float16, np.complex128]


class Args:
    """Arguments built from the fuzz data."""

    def __init__(self, fdp: atheris.FuzzedDataProvider):
        self.fdp = fdp

    def pick(self, options):
        return options[self.fdp.ConsumeIntInRange(0, len(options) - 1)]

    def hostile(self) -> bool:
        return self.fdp.ConsumeIntInRange(0, 7) == 0

    def number(self, typical: float, integer: bool = False):
        if self.hostile():
            return self.pick(SPECIAL_NUMBERS + ODD_VALUES)
        v = typical * self.fdp.ConsumeFloatInRange(0.0, 3.0)
        return int(round(v)) if integer else v

    def count(self, typical: int):
        """A count (draws, samples, sweeps): small, or hostile but never merely huge -- a valid
        count of 2**31 is slow by right, and the fuzzer's timeout would call it a hang."""
        if self.hostile():
            return self.pick([-1, 0, 2**63, 2**64, 2**70, -2**63 - 1, 1.5, float("nan")] + ODD_VALUES)
        return self.fdp.ConsumeIntInRange(0, 3 * typical)

    def array(self, shape, dtype=np.float64, low=0.0, high=1.0):
        """An array of `shape` (sometimes another), values in [low, high) (sometimes specials)."""
        fdp = self.fdp
        if self.hostile():
            return self.pick(ODD_VALUES + [np.zeros((0,)), np.zeros((0, 0)), np.zeros((1, 1, 1)),
                                           np.array([object()] * 4)])
        if self.hostile():
            dtype = self.pick(DTYPES)
        if self.hostile():
            shape = tuple(fdp.ConsumeIntInRange(0, 6) for _ in range(fdp.ConsumeIntInRange(0, 4)))
        size = int(np.prod(shape)) if shape else 1
        raw = np.frombuffer(fdp.ConsumeBytes(min(size, 4096)).ljust(size, b"\0"), np.uint8)[:size]
        values = low + (high - low) * raw.astype(np.float64) / 255.0
        if self.hostile() and size:
            values[fdp.ConsumeIntInRange(0, size - 1)] = self.pick(
                [np.nan, np.inf, -np.inf, 1e300, -1e300, 2.0**40])
        with np.errstate(all="ignore"):
            a = values.reshape(shape).astype(dtype)
        if self.hostile() and a.ndim >= 2 and a.shape[0] > 1:
            a = a[::2]  # non-contiguous
        if self.hostile():
            a.setflags(write=False)
        return a

    def frame(self, h=48, w=64):
        return self.array((self.fdp.ConsumeIntInRange(1, h), self.fdp.ConsumeIntInRange(1, w), 3),
                          np.uint8, 0, 256)

    def params(self, defaults: dict) -> dict:
        """Some of `defaults` perturbed (and now and then an unknown name)."""
        out = {}
        names = sorted(defaults)
        for _ in range(self.fdp.ConsumeIntInRange(0, 3)):
            name = self.pick(names)
            d = defaults[name]
            if isinstance(d, bool):
                out[name] = self.pick([True, False]) if not self.hostile() else self.pick(ODD_VALUES + [1])
            elif isinstance(d, int):
                out[name] = self.number(max(d, 1), integer=True)
            elif isinstance(d, float):
                out[name] = self.number(d if d else 1.0)
            elif isinstance(d, tuple):
                out[name] = tuple(self.number(v) for v in d) if not self.hostile() else \
                    self.pick(ODD_VALUES)
            else:
                out[name] = d if not self.hostile() else self.pick(ODD_VALUES + ["gibbs", "?"])
        if self.hostile():
            out["no_such_parameter"] = 1
        return out

    def size(self):
        if self.hostile():
            return self.pick(ODD_VALUES + [(0, 5), (-1, 5), (2**40, 5), (1.5, 2), (5,), "ab"])
        return (self.fdp.ConsumeIntInRange(1, 64), self.fdp.ConsumeIntInRange(1, 48))


def t_kde(a: Args):
    bgs = vtrack.KdeBackground(**a.params(vtrack.KdeBackground.default_params()))
    f = a.frame()
    for _ in range(a.fdp.ConsumeIntInRange(1, 3)):
        bgs.apply(f if a.fdp.ConsumeBool() else a.frame())


def t_mb(a: Args):
    size = a.size()
    params = a.params(vtrack.MultiBernoulliTracker.default_params())
    params.setdefault("max_particles", 60)
    params.setdefault("birth_particles", 30)
    params.setdefault("min_particles", 10)
    t = vtrack.MultiBernoulliTracker(size, **params)
    w, h = t.image_size
    for _ in range(a.fdp.ConsumeIntInRange(1, 3)):
        t.step(a.array((h, w), np.float32))
    _ = t.components, t.tracks


def t_box(a: Args):
    params = a.params(vtrack.BoxTracker.default_params())
    params.setdefault("hypothesis_budget", 30)
    t = vtrack.BoxTracker(a.size(), **params)
    for _ in range(a.fdp.ConsumeIntInRange(1, 4)):
        n = a.fdp.ConsumeIntInRange(0, 6)
        t.step(a.array((n, a.pick([4, 5])), np.float64, -10, 80))


def t_glmb(a: Args):
    axes = a.fdp.ConsumeIntInRange(1, 3)
    motion = vtrack.LinearGaussianMotion(a.array((2 * axes, 2 * axes), np.float64, -1, 2),
                                         a.array((2 * axes, 2 * axes), np.float64, -1, 2)) \
        if a.hostile() else vtrack.LinearGaussianMotion.constant_velocity(axes, 1.0, a.number(2.0))
    observation = vtrack.LinearGaussianObservation.position(
        axes, a.array((axes, axes), np.float64, -1, 5) if a.hostile() else np.eye(axes) * a.number(4.0))
    births = [(a.number(0.1), a.array((2 * axes,), np.float64, -5, 5),
               np.eye(2 * axes) * a.number(10.0)) for _ in range(a.fdp.ConsumeIntInRange(0, 2))]
    params = a.params(vtrack.GlmbTracker.default_params())
    params.setdefault("hypothesis_budget", 30)
    params.setdefault("n_particles", 40)
    kw = {"adaptive_birth_cov": np.eye(2 * axes) * a.number(10.0)} if a.fdp.ConsumeBool() else {}
    t = vtrack.GlmbTracker(motion, observation, births, **kw, **params)
    for _ in range(a.fdp.ConsumeIntInRange(1, 3)):
        t.step(a.array((a.fdp.ConsumeIntInRange(0, 5), axes), np.float64, -5, 5))
    t.cardinality_distribution()


def t_hog(a: Args):
    params = a.params(vtrack.HogPeopleDetector.default_params())
    params.setdefault("upscale", 1.0)
    vtrack.HogPeopleDetector(**params).detect(a.frame(160, 96))


def t_smc(a: Args):
    n = a.fdp.ConsumeIntInRange(0, 20)
    w = a.array((n,), np.float64, 0, 1)
    which = a.fdp.ConsumeIntInRange(0, 5)
    if which == 0:
        smc.resample(w, a.number(7, integer=True) if a.hostile() else smc.Rng(3),
                     a.count(n) if a.fdp.ConsumeBool() else None,
                     a.pick(list(smc.RESAMPLING_METHODS) + ["bogus"]))
    elif which == 1:
        smc.normalize_log_weights(w)
    elif which == 2:
        smc.effective_sample_size(w, log=a.fdp.ConsumeBool())
    elif which == 3:
        d = a.fdp.ConsumeIntInRange(1, 4)
        g = smc.Gaussian(a.array((d,)), a.array((d, d), np.float64, -1, 2) if a.hostile() else np.eye(d))
        g.sample(smc.Rng(1), a.count(5))
        g.log_pdf(a.array((a.fdp.ConsumeIntInRange(0, 4), d)))
    elif which == 4:
        r = smc.Rng(a.number(3, integer=True), a.pick([0, 1, 2, -1, None, "x"]) if a.hostile() else 0)
        r.normal(a.count(10))
    else:
        smc.log_sum_exp(w)


def t_image(a: Args):
    which = a.fdp.ConsumeIntInRange(0, 6)
    if which == 0:
        image.bgr_to_rgi(a.frame())
    elif which == 1:
        ii = image.IntegralImage(a.array((a.fdp.ConsumeIntInRange(1, 9),
                                          a.fdp.ConsumeIntInRange(1, 9)), a.pick(DTYPES)))
        ii.sums(a.array((a.fdp.ConsumeIntInRange(0, 4), 4), np.int64, -20, 20))
        ii.sum(a.number(3, True), a.number(3, True), a.number(3, True), a.number(3, True))
    elif which == 2:
        image.close_square(a.array((8, 9), np.float32), a.number(3, True), threads=a.number(1, True))
    elif which == 3:
        image.foreground_mask(a.array((5, 6), np.float32), threshold=a.number(0.5))
    elif which == 4:
        f = a.frame()
        box = a.array((4,), np.float64, -5, 40)
        m = image.ColorModel(f, box, bins=a.pick([(16, 4, 4), (1, 1, 1), (0, 4, 4), (300, 2, 2), (2, 2)]))
        m.log_likelihood(a.frame(), a.array((a.fdp.ConsumeIntInRange(0, 4), 4), np.float64, -5, 40),
                         sigma=a.number(0.45))
    elif which == 5:
        image.hsv_histogram(a.frame(), a.array((4,), np.float64, -5, 40), kernel=a.fdp.ConsumeBool())
    else:
        image.bhattacharyya_coefficient(a.array((16, 4, 4)), a.array((16, 4, 4)))


def t_assign(a: Args):
    n = a.fdp.ConsumeIntInRange(0, 5)
    cost = a.array((n, n + a.fdp.ConsumeIntInRange(0, 3)), np.float64, -5, 5)
    which = a.fdp.ConsumeIntInRange(0, 2)
    if which == 0:
        assign.linear_assignment(cost)
    elif which == 1:
        assign.murty(cost, a.count(5))
    else:
        assign.gibbs_assignments(cost, a.count(10), a.number(3, integer=True))


def t_metrics(a: Args):
    which = a.fdp.ConsumeIntInRange(0, 2)
    if which == 2:
        metrics.ospa2(a.array((2, 4, 2)), a.array((1, 4, 2)), a.number(5.0), a.number(1.0))
    else:
        f = metrics.ospa if which == 0 else metrics.gospa
        f(a.array((a.fdp.ConsumeIntInRange(0, 4), 2)), a.array((a.fdp.ConsumeIntInRange(0, 4), 2)),
          a.number(5.0), a.number(1.0))


def t_models(a: Args):
    d = models.DepthLikelihood(a.number(40, True), a.number(30, True), a.number(30.0),
                               **a.params(models.DepthLikelihood.default_params()))
    d.log_ratio(a.array((d.height, d.width), np.float32, 0, 5),
                a.array((a.fdp.ConsumeIntInRange(0, 4), 3), np.float64, -2, 6))
    models.kinect_raw_to_depth(a.array((3,), np.float64, 0, 2000))


def t_pipelines(a: Args):
    n = a.fdp.ConsumeIntInRange(0, 8)
    rows = a.array((n, a.pick([6, 7, 10])), np.float64, 0, 60)
    if isinstance(rows, np.ndarray) and rows.ndim == 2 and rows.shape[1] >= 6 and rows.dtype.kind == "f":
        rows[:, 0] = np.floor(rows[:, 0] / 6) + 1
        rows[:, 4:6] += 1
    params = a.params(vtrack.BoxTracker.default_params())
    params.setdefault("hypothesis_budget", 20)
    out = vtrack.track_detections(rows, a.size() if a.fdp.ConsumeBool() else None,
                                  last_frame=a.number(12, integer=True), **params)
    tracker = vtrack.BoxTracker((80, 60))
    io.mot_rows(a.number(3, integer=True), tracker.step(np.zeros((0, 4))))
    if isinstance(out, np.ndarray):
        io.write_mot(os.path.join(SCRATCH, "rows.txt"), out)


def t_particle_filters(a: Args):
    """vtrack.smc.ParticleFilter and MCMCParticleFilter: perturbed parameters and models, then
    steps with fuzzed measurements (sizes capped so that one input stays fast)."""
    from vtrack import models  # noqa: PLC0415

    mcmc = a.fdp.ConsumeBool()
    cls = smc.MCMCParticleFilter if mcmc else smc.ParticleFilter
    defaults = dict(cls.default_params(), n_particles=40, **({"burn_in": 20} if mcmc else {}))
    params = {**defaults, **a.params(cls.default_params())}
    for name, cap in (("n_particles", 200), ("burn_in", 200), ("thinning", 5),
                      ("resample_move_steps", 3), ("threads", 2)):
        if isinstance(params.get(name), int) and params[name] > cap:
            params[name] = cap
    motion = models.RandomWalk(a.array((4,), np.float64, 0, 2) if a.hostile() else [1.0, 0.1, 1.0, 0.1])
    observation = models.RangeBearingObservation() if a.fdp.ConsumeBool() else \
        models.LinearGaussianObservation.position(2, np.eye(2) * a.number(1.0))
    prior = smc.Gaussian(a.array((4,), np.float64, -5, 20),
                         a.array((4, 4), np.float64, -1, 2) if a.hostile() else np.eye(4))
    f = cls(motion, observation, prior=prior, **params)
    for _ in range(a.fdp.ConsumeIntInRange(1, 3)):
        f.step(a.array((2,), np.float64, -5, 30))
    _ = f.particles, f.mean, f.map_estimate


def t_follow(a: Args):
    """The single-object trackers: init on a fuzzed frame and box, updates on fuzzed frames."""
    cls = vtrack.ColorParticleTracker if a.fdp.ConsumeBool() else vtrack.PartParticleTracker
    params = a.params(cls.default_params())
    if isinstance(params.get("n_particles"), int) and params["n_particles"] > 200:
        params["n_particles"] = 200
    t = cls(**params)
    frame = a.frame()
    box = tuple(a.number(v) for v in (2.0, 2.0, 12.0, 12.0)) if not a.hostile() else \
        a.pick(ODD_VALUES + [(0, 0, 0, 0), (1, 1, 1e9, 1), (1, 2, 3)])
    t.init(frame, box)
    for _ in range(a.fdp.ConsumeIntInRange(1, 3)):
        t.update(frame if a.fdp.ConsumeBool() else a.frame())
    _ = t.particles, t.weights


def t_sir(a: Args):
    params = a.params(vtrack.ReclusteringSirTracker.default_params())
    if isinstance(params.get("n_particles"), int) and params["n_particles"] > 300:
        params["n_particles"] = 300
    t = vtrack.ReclusteringSirTracker(a.size(), **params)
    w, h = t.image_size
    for _ in range(a.fdp.ConsumeIntInRange(1, 3)):
        t.step(a.array((h, w), np.float32))


def t_vehicles(a: Args):
    from vtrack.synthetic_road import CAMERA_SETUPS  # noqa: PLC0415

    f = CAMERA_SETUPS[a.pick(sorted(CAMERA_SETUPS))].camera_file()
    cam = vtrack.vehicles.Camera(f["K"], f["dist"], f["R"], f["t"], image_size=tuple(f["image_size"]))
    params = a.params(vtrack.vehicles.VehicleDimensionEstimator.default_params())
    for name, cap in (("n_particles", 100), ("burn_in", 100), ("thinning", 3)):
        if isinstance(params.get(name), int) and params[name] > cap:
            params[name] = cap
    est = vtrack.vehicles.VehicleDimensionEstimator(cam, **params)
    for frame in range(a.fdp.ConsumeIntInRange(1, 3)):
        n = a.fdp.ConsumeIntInRange(0, 8)
        shape = a.pick([(n, 2), (4,)])
        est.update(a.fdp.ConsumeIntInRange(0, 2), a.array(shape, np.float64, 0, 960), frame=frame)
    est.estimates()


TARGETS = [t_kde, t_mb, t_box, t_glmb, t_hog, t_smc, t_image, t_assign, t_metrics, t_models,
           t_pipelines, t_particle_filters, t_follow, t_sir, t_vehicles]


def one_input(data: bytes) -> None:
    fdp = atheris.FuzzedDataProvider(data)
    target = TARGETS[fdp.ConsumeIntInRange(0, len(TARGETS) - 1)]
    check(lambda: target(Args(fdp)))


def main() -> None:
    atheris.Setup(sys.argv, one_input)
    atheris.Fuzz()


if __name__ == "__main__":
    main()
