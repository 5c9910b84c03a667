"""vtrack.track_detections: GLMB tracking of MOTChallenge detection rows (image boxes)."""

import numpy as np
import pytest

import vtrack


def iou(a, b):
    """IoU of (x, y, w, h) boxes a (n, 4) and b (m, 4): (n, m)."""
    x1 = np.maximum(a[:, None, 0], b[None, :, 0])
    y1 = np.maximum(a[:, None, 1], b[None, :, 1])
    x2 = np.minimum(a[:, None, 0] + a[:, None, 2], b[None, :, 0] + b[None, :, 2])
    y2 = np.minimum(a[:, None, 1] + a[:, None, 3], b[None, :, 1] + b[None, :, 3])
    inter = np.clip(x2 - x1, 0, None) * np.clip(y2 - y1, 0, None)
    area = a[:, 2] * a[:, 3]
    return inter / (area[:, None] + (b[:, 2] * b[:, 3])[None, :] - inter)


def synthetic_scene(seed=0, frames=60):
    """Three walkers (40 x 100 px boxes) in a 640 x 480 image, detected with p = 0.9 and
    (3, 3, 5, 5) px noise, plus Poisson(1) false boxes per frame. Returns (truth, det rows)."""
    rng = np.random.default_rng(seed)
    starts = [(50, 100, 3.0, 0.5, 1), (500, 300, -2.5, -1.0, 1), (300, 50, 0.5, 2.0, 15)]
    truth, det = [], []
    for f in range(1, frames + 1):
        for tid, (x, y, vx, vy, born) in enumerate(starts, 1):
            if f < born:
                continue
            box = np.array([x + vx * (f - born), y + vy * (f - born), 40.0, 100.0])
            truth.append([f, tid, *box])
            if rng.random() < 0.9:
                det.append([f, -1, *(box + rng.normal(size=4) * [3, 3, 5, 5]), 1.0])
        for _ in range(rng.poisson(1.0)):
            det.append([f, -1, rng.uniform(0, 600), rng.uniform(0, 380), rng.uniform(20, 60),
                        rng.uniform(50, 150), 0.5])
    return np.array(truth), np.array(det)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_tracks_three_walkers_with_stable_ids(seed):
    truth, det = synthetic_scene(seed)
    out = vtrack.track_detections(det, image_size=(640, 480))
    assert out.shape[1] == 10
    matched, total, false = 0, 0, 0
    ids_of = {1: [], 2: [], 3: []}
    for f in range(6, 61):  # a few frames to confirm new tracks
        t, e = truth[truth[:, 0] == f], out[out[:, 0] == f]
        total += len(t)
        if len(e) == 0:
            continue
        overlap = iou(t[:, 2:6], e[:, 2:6])
        cost = np.where(overlap > 0.5, -overlap, np.inf)
        pairs = 0
        for i in range(len(t)):
            j = int(np.argmin(cost[i]))
            if np.isfinite(cost[i, j]):
                pairs += 1
                ids_of[int(t[i, 1])].append(int(e[j, 1]))
        matched += pairs
        false += len(e) - pairs
    assert matched / total > 0.9
    assert false / total < 0.05
    for tid, ids in ids_of.items():
        dominant = max(set(ids), key=ids.count)
        assert ids.count(dominant) / len(ids) > 0.95, f"target {tid}: ids {ids}"


def test_confidence_filter_and_empty_input():
    _, det = synthetic_scene(frames=10)
    everything = vtrack.track_detections(det, image_size=(640, 480), min_confidence=0.0)
    confident = vtrack.track_detections(det, image_size=(640, 480), min_confidence=0.9)
    assert len(confident) <= len(everything)
    assert vtrack.track_detections(np.empty((0, 10)), image_size=(640, 480)).shape == (0, 10)
    with pytest.raises(ValueError, match="det_rows"):
        vtrack.track_detections(np.ones((3, 4)), image_size=(640, 480))
    with pytest.raises(ValueError, match="image_size"):
        vtrack.track_detections(det, image_size=(0, 480))
