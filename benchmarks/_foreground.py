"""What benchmarks/pets09.py runs: the methods compared (VTRACK_METHODS and BASELINES), the
background-subtraction baselines a user would build from OpenCV and PyPI,
the PETS09-S2L1 variants (resized, cropped) with their ground truth, and scoring.

A method is run on a video file from start to end and returns MOTChallenge rows and its
frames/s (decoding included). vtrack's methods run through vtrack.track_video (the same C++
pipeline as `vtrack track VIDEO --method M`); the baselines decode with OpenCV and run
background subtraction -> morphology -> connected components -> a PyPI tracker in Python.
"""

from __future__ import annotations

import contextlib
import io
import os
import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Callable, Dict, Iterator, List, Optional, Tuple

import cv2
import numpy as np
from scipy.optimize import linear_sum_assignment

import vtrack
from vtrack.evaluate import _sequence_data, _trackeval, box_iou_matrix, evaluate
from vtrack.io import read_mot

REPO = Path(__file__).resolve().parent.parent
CACHE = Path(os.environ.get("VTRACK_CACHE", Path.home() / ".cache" / "vtrack"))


def default_video() -> str:
    return os.environ.get("VTRACK_VIDEO", str(CACHE / "vtest.avi"))


def default_gt() -> str:
    return os.environ.get("VTRACK_PETS_GT", str(REPO / "data" / "pets09-s2l1" / "gt.txt"))


# ---------------------------------------------------------------------------------------------
# Box calibration: (width ratio, height ratio, centre dx in box widths, dy in box heights) that
# maps a method's boxes to the annotation convention. Ratios, so independent of the resolution.

IDENTITY_CALIBRATION = (1.0, 1.0, 0.0, 0.0)


def fit_calibration(tracks: np.ndarray, gt: np.ndarray) -> Tuple[float, float, float, float]:
    """Median GT / track width and height ratios and centre offsets (in track box units), on
    track/GT pairs matched per frame (Hungarian on IoU, IoU > 0.3)."""
    gt = gt[gt[:, 6] != 0]
    pairs = []
    for f in np.unique(tracks[:, 0]):
        a = tracks[tracks[:, 0] == f, 2:6]
        b = gt[gt[:, 0] == f, 2:6]
        if len(a) == 0 or len(b) == 0:
            continue
        iou = box_iou_matrix(a, b)
        r, c = linear_sum_assignment(-iou)
        pairs += [(a[i], b[j]) for i, j in zip(r, c) if iou[i, j] > 0.3]
    if not pairs:
        return IDENTITY_CALIBRATION
    t = np.array([p[0] for p in pairs])
    g = np.array([p[1] for p in pairs])
    return (float(np.median(g[:, 2] / t[:, 2])), float(np.median(g[:, 3] / t[:, 3])),
            float(np.median(((g[:, 0] + g[:, 2] / 2) - (t[:, 0] + t[:, 2] / 2)) / t[:, 2])),
            float(np.median(((g[:, 1] + g[:, 3] / 2) - (t[:, 1] + t[:, 3] / 2)) / t[:, 3])))


def apply_calibration(rows: np.ndarray, cal) -> np.ndarray:
    sw, sh, dx, dy = cal
    out = rows.copy()
    w, h = rows[:, 4], rows[:, 5]
    cx = rows[:, 2] + w / 2 + dx * w
    cy = rows[:, 3] + h / 2 + dy * h
    out[:, 4] = w * sw
    out[:, 5] = h * sh
    out[:, 2] = cx - out[:, 4] / 2
    out[:, 3] = cy - out[:, 5] / 2
    return out


# ---------------------------------------------------------------------------------------------
# Scoring

def select(rows: np.ndarray, first: int, last: int) -> np.ndarray:
    return rows[(rows[:, 0] >= first) & (rows[:, 0] <= last)]


def clear_identity(gt: np.ndarray, tracks: np.ndarray):
    """TrackEval's CLEAR and Identity results and the sequence data (GT rows with conf 0 dropped;
    no HOTA: 10x faster, for the tuning grids)."""
    trackeval = _trackeval()
    gt = gt[gt[:, 6] != 0]
    data = _sequence_data(gt, tracks.reshape(-1, 10) if tracks.size else np.zeros((0, 10)))
    with contextlib.redirect_stdout(io.StringIO()):
        clear = trackeval.metrics.CLEAR({"PRINT_CONFIG": False}).eval_sequence(data)
        ident = trackeval.metrics.Identity({"PRINT_CONFIG": False}).eval_sequence(data)
    return clear, ident, data


def mota_idf1(gt: np.ndarray, tracks: np.ndarray) -> Tuple[float, float]:
    """TrackEval's MOTA and IDF1 only."""
    clear, ident, _ = clear_identity(gt, tracks)
    return float(clear["MOTA"]), float(ident["IDF1"])


def score_halves(gt: np.ndarray, rows: np.ndarray, first: int, last: int, mid: int):
    """TrackEval metrics on frames first-last, first-(mid-1) and mid-last."""
    out = {}
    for key, (a, b) in (("all", (first, last)), ("first", (first, mid - 1)),
                        ("second", (mid, last))):
        out[key] = evaluate(select(gt, a, b), select(rows, a, b))
    return out


# ---------------------------------------------------------------------------------------------
# PETS09-S2L1 variants: the video resized and/or cropped, written once (FFV1, lossless, so every
# method decodes exactly the same frames) into the cache, and the ground truth transformed alike.

@dataclass(frozen=True)
class Variant:
    name: str
    scale: float = 1.0                                  # resize factor of the 768 x 576 video
    crop: Optional[Tuple[int, int, int, int]] = None    # (x, y, w, h) of the resized frame
    description: str = ""

    def size(self) -> Tuple[int, int]:
        if self.crop:
            return self.crop[2], self.crop[3]
        return round(768 * self.scale), round(576 * self.scale)


VARIANTS = {
    "768x576": Variant("768x576", description="the video as shipped (the defaults were tuned on "
                                              "its frames 1-397)"),
    "0.5x": Variant("0.5x", 0.5, description="resized to 384 x 288 (people 0.5x)"),
    "1.5x": Variant("1.5x", 1.5, description="resized to 1152 x 864 (people 1.5x)"),
    "crop": Variant("crop", 1.0, (128, 96, 512, 384),
                    description="central 512 x 384 crop (people as large, image smaller)"),
    "zoom": Variant("zoom", 1.5, (192, 144, 768, 576),
                    description="resized 1.5x, central 768 x 576 crop (image as large, people "
                                "1.5x: a closer camera)"),
    # Development variants of the crop / zoom work (issue 12): MB's collapse on "crop" and "zoom"
    # was diagnosed and fixed on these (frames 1-397), so that crop and zoom stay held out.
    "crop2": Variant("crop2", 1.0, (0, 72, 576, 432),
                     description="left 576 x 432 crop (people as large, image smaller; "
                                 "development)"),
    "zoom1.25": Variant("zoom1.25", 1.25, (48, 36, 768, 576),
                        description="resized 1.25x, the 768 x 576 crop at (48, 36) (development)"),
}


def transform_frame(frame: np.ndarray, v: Variant) -> np.ndarray:
    if v.scale != 1.0:
        size = (round(frame.shape[1] * v.scale), round(frame.shape[0] * v.scale))
        frame = cv2.resize(frame, size, interpolation=cv2.INTER_AREA if v.scale < 1
                           else cv2.INTER_LINEAR)
    if v.crop:
        x, y, w, h = v.crop
        frame = np.ascontiguousarray(frame[y:y + h, x:x + w])
    return frame


def transform_gt(gt: np.ndarray, v: Variant, min_visible: float = 0.5) -> np.ndarray:
    """GT boxes scaled with the video; with a crop, clipped to it and kept when at least
    `min_visible` of the box is inside."""
    g = gt.copy()
    g[:, 2:6] *= v.scale
    if v.crop:
        x, y, w, h = v.crop
        x0 = np.clip(g[:, 2] - x, 0, w)
        y0 = np.clip(g[:, 3] - y, 0, h)
        x1 = np.clip(g[:, 2] + g[:, 4] - x, 0, w)
        y1 = np.clip(g[:, 3] + g[:, 5] - y, 0, h)
        visible = (x1 - x0) * (y1 - y0) / (g[:, 4] * g[:, 5])
        g[:, 2], g[:, 3], g[:, 4], g[:, 5] = x0, y0, x1 - x0, y1 - y0
        g = g[visible >= min_visible]
    return g


def variant_video(source: str, v: Variant) -> str:
    """Path of the variant's video: the source itself for 768x576, else a lossless FFV1 file in
    the cache, written on first use."""
    if v.scale == 1.0 and v.crop is None:
        return source
    path = CACHE / "pets09-variants" / f"{v.name}.mkv"
    if path.exists():
        return str(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp.mkv")
    cap = cv2.VideoCapture(source)
    writer = None
    while True:
        ok, frame = cap.read()
        if not ok:
            break
        frame = transform_frame(frame, v)
        if writer is None:
            writer = cv2.VideoWriter(str(tmp), cv2.VideoWriter_fourcc(*"FFV1"), 7.0,
                                     (frame.shape[1], frame.shape[0]))
        writer.write(frame)
    cap.release()
    writer.release()
    tmp.rename(path)
    return str(path)


# ---------------------------------------------------------------------------------------------
# Background subtraction -> morphology -> connected components -> ByteTrack / SORT.

@dataclass(frozen=True)
class Detector:
    """A foreground-blob detector as a user assembles it from OpenCV."""
    bgs: str = "mog2"           # "mog2" or "knn" (OpenCV's createBackgroundSubtractor*)
    threshold: float = 16.0     # MOG2 varThreshold / KNN dist2Threshold
    shadows: bool = True        # detectShadows; shadow pixels (127) count as background
    open: int = 3               # opening square (0 = none): removes specks
    close: int = 15             # closing square (0 = none): joins a person's fragments
    min_area: int = 400         # connected components smaller than this (px) are dropped
    confidence: str = "one"     # a blob's score: "one", or "fill" (foreground share of its box)

    def scaled(self, s: float) -> "Detector":
        """The same detector with its pixel sizes scaled by s (odd kernels, area by s^2)."""
        def odd(n):
            return 0 if n == 0 else max(1, int(round(n * s)) | 1)
        return replace(self, open=odd(self.open), close=odd(self.close),
                       min_area=max(1, int(round(self.min_area * s * s))))


def make_subtractor(d: Detector):
    if d.bgs == "mog2":
        return cv2.createBackgroundSubtractorMOG2(varThreshold=d.threshold,
                                                  detectShadows=d.shadows)
    if d.bgs == "knn":
        return cv2.createBackgroundSubtractorKNN(dist2Threshold=d.threshold,
                                                 detectShadows=d.shadows)
    raise ValueError(f"unknown background subtractor {d.bgs!r}")


def blobs(mask: np.ndarray, d: Detector) -> np.ndarray:
    """(N, 5) x, y, w, h, score of the connected components of a 0/1 mask after the detector's
    opening and closing and area filter."""
    if d.open > 1:
        mask = cv2.morphologyEx(mask, cv2.MORPH_OPEN,
                                cv2.getStructuringElement(cv2.MORPH_RECT, (d.open, d.open)))
    if d.close > 1:
        mask = cv2.morphologyEx(mask, cv2.MORPH_CLOSE,
                                cv2.getStructuringElement(cv2.MORPH_RECT, (d.close, d.close)))
    _, _, stats, _ = cv2.connectedComponentsWithStats(mask, connectivity=8)
    stats = stats[1:]
    stats = stats[stats[:, cv2.CC_STAT_AREA] >= d.min_area]
    out = np.zeros((len(stats), 5))
    out[:, :4] = stats[:, :4]
    if d.confidence == "fill":
        out[:, 4] = stats[:, cv2.CC_STAT_AREA] / (stats[:, 2] * stats[:, 3])
    else:
        out[:, 4] = 1.0
    return out


def foreground_masks(frames, d: Detector) -> Iterator[np.ndarray]:
    """0/1 uint8 foreground masks (shadows excluded) of the frames."""
    sub = make_subtractor(d)
    for frame in frames:
        yield (sub.apply(frame) == 255).astype(np.uint8)


@dataclass(frozen=True)
class Tracker:
    kind: str = "bytetrack"     # "bytetrack" (Roboflow `trackers`) or "sort" (`sort-track`)
    params: Tuple[Tuple[str, object], ...] = ()

    def kwargs(self) -> dict:
        return dict(self.params)


# The packages' defaults (trackers 2.6.1's ByteTrackTracker with frame_rate 30, so its buffer
# counts frames; the reference SORT's max_age 1, min_hits 3, IoU 0.3).
BYTETRACK_DEFAULTS = dict(lost_track_buffer=30, track_activation_threshold=0.7,
                          minimum_consecutive_frames=2, minimum_iou_threshold=0.1,
                          high_conf_det_threshold=0.6)
SORT_DEFAULTS = dict(max_age=1, min_hits=3, iou_threshold=0.3)


class BoxTrackerRunner:
    """A PyPI box tracker fed per-frame (N, 5) x, y, w, h, score boxes; step returns rows."""

    def __init__(self, t: Tracker):
        self.kind = t.kind
        if t.kind == "bytetrack":
            from trackers import ByteTrackTracker  # noqa: PLC0415
            self.tracker = ByteTrackTracker(frame_rate=30.0, **{**BYTETRACK_DEFAULTS, **t.kwargs()})
        elif t.kind == "sort":
            from sort.tracker import KalmanBoxTracker, SortTracker  # noqa: PLC0415
            KalmanBoxTracker.count = 0  # ids restart for every run
            self.tracker = SortTracker(**{**SORT_DEFAULTS, **t.kwargs()})
        else:
            raise ValueError(f"unknown tracker {t.kind!r}")

    def step(self, frame: int, boxes: np.ndarray) -> List[tuple]:
        xyxy = np.concatenate([boxes[:, 0:2], boxes[:, 0:2] + boxes[:, 2:4]], axis=1)
        if self.kind == "bytetrack":
            import supervision as sv  # noqa: PLC0415
            res = self.tracker.update(sv.Detections(xyxy=xyxy.reshape(-1, 4),
                                                    confidence=boxes[:, 4].copy()))
            keep = res.tracker_id >= 0
            b = res.xyxy[keep]
            return [(frame, int(i), x0, y0, x1 - x0, y1 - y0, 1.0, -1, -1, -1)
                    for i, (x0, y0, x1, y1) in zip(res.tracker_id[keep], b)]
        d = np.zeros((len(boxes), 6))
        d[:, 0:4] = xyxy
        d[:, 4] = boxes[:, 4]
        return [(frame, int(tid), x0, y0, x1 - x0, y1 - y0, 1.0, -1, -1, -1)
                for x0, y0, x1, y1, tid, *_ in self.tracker.update(d, None)]


def track_boxes(per_frame: List[np.ndarray], t: Tracker, first: int = 1) -> np.ndarray:
    runner = BoxTrackerRunner(t)
    rows = []
    for k, boxes in enumerate(per_frame):
        rows += runner.step(first + k, boxes)
    return np.asarray(rows, np.float64).reshape(-1, 10)


@dataclass(frozen=True)
class Baseline:
    detector: Detector
    tracker: Tracker
    calibration: Tuple[float, float, float, float] = IDENTITY_CALIBRATION

    def run(self, video: str, scale: float = 1.0) -> Tuple[np.ndarray, float]:
        """MOT rows (calibrated) and frames/s, decoding included; `scale` multiplies the
        detector's pixel sizes."""
        d = self.detector.scaled(scale) if scale != 1.0 else self.detector
        cap = cv2.VideoCapture(video)
        sub = make_subtractor(d)
        runner = BoxTrackerRunner(self.tracker)
        rows: List[tuple] = []
        k = 0
        start = time.perf_counter()
        while True:
            ok, frame = cap.read()
            if not ok:
                break
            k += 1
            mask = (sub.apply(frame) == 255).astype(np.uint8)
            rows += runner.step(k, blobs(mask, d))
        elapsed = time.perf_counter() - start
        cap.release()
        out = np.asarray(rows, np.float64).reshape(-1, 10)
        return apply_calibration(out, self.calibration), k / max(elapsed, 1e-9)


# ---------------------------------------------------------------------------------------------
# The methods compared, in one place. vtrack's rows need the method in vtrack.pipelines.METHODS
# (the re-clustering SIR of issue 12 part 1 appears once it is there); a baseline's constants are
# the result of `benchmarks/pets09.py --tune` (the grid and the choices are in its docstring).

@dataclass(frozen=True)
class VtrackMethod:
    method: str                                   # vtrack.track_video's method
    one_core: Dict[str, object] = field(default_factory=dict)  # keywords that pin one thread
    # Keywords that make the method report the foreground box (no annotation calibration): for
    # scenes whose ground truth is the foreground box itself (vtrack.synthetic).
    foreground_box: Dict[str, object] = field(default_factory=dict)

    def available(self) -> bool:
        return self.method in vtrack.pipelines.METHODS

    def run(self, video: str, seed: int = 0, foreground_box: bool = False,
            **params) -> Tuple[np.ndarray, float]:
        kwargs = {**self.one_core, **(self.foreground_box if foreground_box else {}), **params}
        start = time.perf_counter()
        rows = vtrack.track_video(video, method=self.method, seed=seed, **kwargs)
        elapsed = time.perf_counter() - start
        frames = vtrack.io.probe_video(video).frame_count
        return rows, frames / max(elapsed, 1e-9)


VTRACK_METHODS: Dict[str, VtrackMethod] = {
    "vtrack MB": VtrackMethod("mb", {"threads": 1}, vtrack.pipelines.SILHOUETTE_BOX["mb"]),
    # Issue 12 part 1: the re-clustering SIR (KDE background -> ReclusteringSir).
    "vtrack SIR": VtrackMethod("sir", {"threads": 1}, vtrack.pipelines.SILHOUETTE_BOX["sir"]),
}

# Tuned on PETS09-S2L1 frames 1-397 at 768 x 576 (benchmarks/pets09.py --tune; the log is in
# its docstring): the best of the grid by MOTA + IDF1 after a box calibration fitted on 1-397.
BASELINES: Dict[str, Baseline] = {
    "MOG2 + ByteTrack": Baseline(
        Detector(bgs="mog2", threshold=16.0, open=3, close=0, min_area=400, confidence="fill"),
        Tracker("bytetrack", (("high_conf_det_threshold", 0.6), ("lost_track_buffer", 30),
                              ("minimum_consecutive_frames", 2), ("minimum_iou_threshold", 0.05),
                              ("track_activation_threshold", 0.4))),
        (0.966, 1.036, -0.019, 0.0)),
    "MOG2 + SORT": Baseline(
        Detector(bgs="mog2", threshold=16.0, open=0, close=0, min_area=800, confidence="one"),
        Tracker("sort", (("iou_threshold", 0.1), ("max_age", 20), ("min_hits", 1))),
        (0.857, 0.993, -0.012, 0.0)),
    "KNN + ByteTrack": Baseline(
        Detector(bgs="knn", threshold=1600.0, open=0, close=0, min_area=400, confidence="fill"),
        Tracker("bytetrack", (("high_conf_det_threshold", 0.4), ("lost_track_buffer", 15),
                              ("minimum_consecutive_frames", 3), ("minimum_iou_threshold", 0.05),
                              ("track_activation_threshold", 0.4))),
        (0.928, 1.02, -0.015, -0.004)),
    "KNN + SORT": Baseline(
        Detector(bgs="knn", threshold=1600.0, open=0, close=0, min_area=400, confidence="one"),
        Tracker("sort", (("iou_threshold", 0.1), ("max_age", 10), ("min_hits", 1))),
        (0.904, 1.015, -0.006, -0.003)),
}


def methods(names: Optional[List[str]] = None) -> Dict[str, object]:
    """Every method (vtrack's first, then the baselines), or those named."""
    every = {**VTRACK_METHODS, **BASELINES}
    if names is None:
        return every
    unknown = [n for n in names if n not in every]
    if unknown:
        raise ValueError(f"unknown methods {unknown}; known: {list(every)}")
    return {n: every[n] for n in names}


def read_frames(path: str, first: int = 1, last: int = 10 ** 9,
                transform: Optional[Callable[[np.ndarray], np.ndarray]] = None) -> List[np.ndarray]:
    """Frames first..last (1-based, inclusive) of a video, BGR uint8."""
    cap = cv2.VideoCapture(path)
    frames = []
    k = 0
    while k < last:
        ok, frame = cap.read()
        if not ok:
            break
        k += 1
        if k >= first:
            frames.append(transform(frame) if transform else frame)
    cap.release()
    return frames


def load_gt(path: str) -> np.ndarray:
    return read_mot(path)


# ---------------------------------------------------------------------------------------------
# Tuning the baselines on frames 1-397 (benchmarks/pets09.py --tune).

def _calibrated_score(rows: np.ndarray, gt: np.ndarray):
    """(MOTA + IDF1, MOTA, IDF1, calibration) of rows calibrated by a fit on the same frames --
    how vtrack's defaults were chosen (its box calibration was fitted on frames 1-397 too)."""
    cal = fit_calibration(rows, gt) if len(rows) else IDENTITY_CALIBRATION
    mota, idf1 = mota_idf1(gt, apply_calibration(rows, cal))
    return mota + idf1, mota, idf1, cal


class BlobCache:
    """Per-frame connected-component boxes of each (subtractor, threshold, open, close) on a fixed
    list of frames, so that min_area and confidence cost nothing in a grid."""

    def __init__(self, frames):
        self.frames = frames
        self.masks: Dict[tuple, List[np.ndarray]] = {}
        self.stats: Dict[tuple, List[np.ndarray]] = {}

    def detections(self, d: Detector) -> List[np.ndarray]:
        mkey = (d.bgs, d.threshold, d.shadows)
        if mkey not in self.masks:
            self.masks[mkey] = list(foreground_masks(self.frames, d))
        skey = mkey + (d.open, d.close)
        if skey not in self.stats:
            self.stats[skey] = [blobs(m, replace(d, min_area=0, confidence="fill"))
                                for m in self.masks[mkey]]
        out = []
        for b in self.stats[skey]:
            b = b[b[:, 2] * b[:, 3] * b[:, 4] >= d.min_area - 0.5].copy()  # area = w h fill
            if d.confidence == "one":
                b[:, 4] = 1.0
            out.append(b)
        return out


DETECTOR_GRID = dict(open=(0, 3, 5), close=(0, 9, 15, 21), min_area=(100, 200, 400, 800))
THRESHOLD_GRID = dict(mog2=(8.0, 16.0, 32.0, 64.0), knn=(200.0, 400.0, 800.0, 1600.0))
TRACKER_GRID = dict(
    sort=dict(max_age=(1, 3, 5, 10, 20), min_hits=(1, 2, 3, 5), iou_threshold=(0.1, 0.2, 0.3, 0.5)),
    bytetrack=dict(lost_track_buffer=(5, 15, 30, 60), minimum_consecutive_frames=(1, 2, 3),
                   minimum_iou_threshold=(0.05, 0.1, 0.2, 0.3),
                   # with confidence "fill" (the two-stage association): thresholds on it
                   high_conf_det_threshold=(0.4, 0.6), track_activation_threshold=(0.4, 0.7)))


def _grid(spec: Dict[str, tuple]) -> Iterator[dict]:
    keys = list(spec)
    for values in np.array(np.meshgrid(*[np.arange(len(spec[k])) for k in keys])).T.reshape(-1, len(keys)):
        yield {k: spec[k][i] for k, i in zip(keys, values)}


def tune_pipeline(cache: BlobCache, gt: np.ndarray, bgs: str, kind: str, log=print):
    """Coordinate-wise grid search of one pipeline on cache's frames: (1) morphology and area
    with the subtractor and the tracker at their defaults, (2) the subtractor's threshold,
    (3) the tracker's parameters (and, for ByteTrack, the blob confidence), (4) step 1 again
    with the tuned tracker. Each configuration is scored by MOTA + IDF1 after a box calibration
    fitted on the same frames. Returns (Baseline, its score, the log of every step's best)."""
    det = Detector(bgs=bgs, threshold=THRESHOLD_GRID[bgs][1] if bgs == "mog2" else 400.0)
    trk = Tracker(kind)
    best = None

    def consider(d, t):
        nonlocal best
        s = _calibrated_score(track_boxes(cache.detections(d), t), gt)
        if best is None or s[0] > best[1][0]:
            best = ((d, t), s)
        return s

    def morphology_step(t):
        base = best[0][0]
        for g in _grid(DETECTOR_GRID):
            consider(replace(base, **g), t)

    consider(det, trk)
    steps = [("defaults", best)]
    morphology_step(trk)
    steps.append(("morphology, min_area", best))
    for th in THRESHOLD_GRID[bgs]:
        consider(replace(best[0][0], threshold=th), trk)
    steps.append(("threshold", best))
    spec = dict(TRACKER_GRID[kind])
    confidences = ("one", "fill") if kind == "bytetrack" else ("one",)
    for conf in confidences:
        d = replace(best[0][0], confidence=conf)
        grid = dict(spec)
        if conf == "one" and kind == "bytetrack":  # all scores 1: the thresholds do nothing
            grid.pop("high_conf_det_threshold")
            grid.pop("track_activation_threshold")
        for g in _grid(grid):
            consider(d, Tracker(kind, tuple(sorted(g.items()))))
    steps.append(("tracker", best))
    morphology_step(best[0][1])
    steps.append(("morphology again", best))
    (d, t), s = best
    for name, (cfg, sc) in steps:
        log(f"  {bgs} + {kind}: after {name}: MOTA + IDF1 {sc[0]:.3f} (MOTA {sc[1]:.3f}, IDF1 "
            f"{sc[2]:.3f}) with {cfg[0]}, {cfg[1]}")
    return Baseline(d, t, tuple(round(c, 3) for c in s[3])), s
