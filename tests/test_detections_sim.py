"""vtrack.detsim: the simulated detector's statistics match its model at fixed seeds.

On PETS09-S2L1's ground truth (4,476 scored boxes, 795 frames), each property is compared with
its model value within a tolerance of about four standard errors, so a wrong model (a rate off
by a few per cent, noise scaled by the wrong side) fails and the seeded draw does not.
"""

from pathlib import Path

import numpy as np
import pytest

from vtrack.detsim import LEVELS, DetectorLevel, simulate_detections
from vtrack.io import read_mot

GT_PATH = Path(__file__).resolve().parent.parent / "data" / "pets09-s2l1" / "gt.txt"
IMAGE = (768, 576)


@pytest.fixture(scope="module")
def gt():
    rows = read_mot(GT_PATH)
    return rows[rows[:, 6] != 0]


def match_truth(gt, det, truth):
    """For each true detection, its GT row (same frame and id)."""
    index = {(int(f), int(i)): k for k, (f, i) in enumerate(gt[:, :2])}
    return np.array([index[int(f), int(t)] for f, t in zip(det[:, 0], truth)], np.int64)


@pytest.mark.parametrize("level", ["easy", "medium", "hard"])
def test_detection_and_clutter_rates(gt, level):
    lv = LEVELS[level]
    det, truth = simulate_detections(gt, level, 3, IMAGE, return_truth=True)
    n = len(gt)
    rate = np.count_nonzero(truth >= 0) / n
    se = np.sqrt(lv.detection_probability * (1 - lv.detection_probability) / n)
    assert abs(rate - lv.detection_probability) < 4 * se + 1e-9
    frames = int(gt[:, 0].max())
    clutter = np.count_nonzero(truth < 0) / frames
    assert abs(clutter - lv.clutter_rate) < 4 * np.sqrt(lv.clutter_rate / frames)
    # One detection at most per target and frame, frames sorted, the id column blank.
    pairs = det[truth >= 0][:, 0] * 1e4 + truth[truth >= 0]
    assert len(np.unique(pairs)) == len(pairs)
    assert np.all(np.diff(det[:, 0]) >= 0)
    assert np.all(det[:, 1] == -1)


def test_corner_noise_scales_with_the_box(gt):
    lv = LEVELS["medium"]
    det, truth = simulate_detections(gt, "medium", 4, IMAGE, return_truth=True)
    true = truth >= 0
    g = gt[match_truth(gt, det[true], truth[true])]
    d = det[true]
    # Left / top corner errors in units of the GT width / height: N(0, corner_sd^2).
    ex = (d[:, 2] - g[:, 2]) / g[:, 4]
    ey = (d[:, 3] - g[:, 3]) / g[:, 5]
    # Right edge error: also N(0, corner_sd^2) in width units, independent of the left one.
    er = (d[:, 2] + d[:, 4] - g[:, 2] - g[:, 4]) / g[:, 4]
    n = len(ex)
    for e in (ex, ey, er):
        assert abs(np.mean(e)) < 4 * lv.corner_sd / np.sqrt(n)
        assert abs(np.std(e) / lv.corner_sd - 1) < 4 / np.sqrt(2 * n)
    assert abs(np.corrcoef(ex, er)[0, 1]) < 4 / np.sqrt(n)
    # In pixels the error grows with the box: big boxes' errors are larger than small ones'.
    big = g[:, 5] > np.median(g[:, 5])
    px = d[:, 3] - g[:, 3]
    assert np.std(px[big]) > 1.3 * np.std(px[~big])


def test_scores_and_clutter_boxes(gt):
    lv = LEVELS["hard"]
    det, truth = simulate_detections(gt, "hard", 5, IMAGE, return_truth=True)
    s_true, s_false = det[truth >= 0, 6], det[truth < 0, 6]
    a, b = lv.true_score
    assert abs(s_true.mean() - a / (a + b)) < 0.01
    a, b = lv.false_score
    assert abs(s_false.mean() - a / (a + b)) < 0.01
    assert np.all((det[:, 6] > 0) & (det[:, 6] < 1))
    false = det[truth < 0]
    # Person-sized: the clutter's sizes are the GT's, its centres uniform over the image.
    assert abs(np.median(false[:, 5]) - np.median(gt[:, 5])) < 3
    centre = false[:, 2:4] + false[:, 4:6] / 2
    for axis, size in enumerate(IMAGE):
        u = centre[:, axis] / size
        assert 0 <= u.min() and u.max() <= 1
        assert abs(u.mean() - 0.5) < 4 * np.sqrt(1 / 12 / len(u))


def test_bursts_of_misses(gt):
    lv = LEVELS["bursts"]
    det, truth = simulate_detections(gt, "bursts", 6, IMAGE, return_truth=True)
    detected = set(zip(det[truth >= 0, 0].astype(int), truth[truth >= 0]))
    runs = []
    for tid in np.unique(gt[:, 1]):
        frames = np.sort(gt[gt[:, 1] == tid, 0].astype(int))
        run = 0
        for f in frames:
            if (f, tid) in detected:
                if run:
                    runs.append(run)
                run = 0
            else:
                run += 1
    runs = np.array(runs)
    # Independent misses at p_D 0.9 almost never make a run of 5 (0.1^5 per start); the bursts do.
    long_runs = runs[runs >= 5]
    assert len(long_runs) > 20
    assert np.median(long_runs) >= 7
    # Expected fraction missed: bursts cover r L / (1 + r L) of the frames (L = 10 on average),
    # the rest are missed with 1 - p_D.
    r, mean_len = lv.burst_rate, np.mean(lv.burst_length)
    in_burst = r * mean_len / (1 + r * mean_len)
    expected = in_burst + (1 - in_burst) * (1 - lv.detection_probability)
    missed = 1 - np.count_nonzero(truth >= 0) / len(gt)
    assert abs(missed - expected) < 0.03
    # Without bursts the same p_D gives no such runs.
    plain = DetectorLevel(lv.detection_probability, lv.clutter_rate, lv.corner_sd)
    _, t2 = simulate_detections(gt, plain, 6, IMAGE, return_truth=True)
    assert abs(np.count_nonzero(t2 >= 0) / len(gt) - lv.detection_probability) < 0.02


def test_same_seed_same_detections_and_bad_input(gt):
    a = simulate_detections(gt, "medium", 7, IMAGE)
    b = simulate_detections(gt, "medium", 7, IMAGE)
    c = simulate_detections(gt, "medium", 8, IMAGE)
    np.testing.assert_array_equal(a, b)
    assert a.shape != c.shape or not np.array_equal(a, c)
    # Conf-0 rows of the GT are never detected.
    ignored = read_mot(GT_PATH)
    zero = {(int(f), int(i)) for f, i, *_ in ignored[ignored[:, 6] == 0]}
    det, truth = simulate_detections(ignored, "easy", 7, IMAGE, return_truth=True)
    assert not any((int(f), int(t)) in zero for f, t in zip(det[:, 0], truth) if t >= 0)
    with pytest.raises(ValueError, match="level"):
        simulate_detections(gt, "impossible", 0, IMAGE)
    with pytest.raises(ValueError, match="image_size"):
        simulate_detections(gt, "easy", 0, (0, 576))
    with pytest.raises(ValueError, match="gt_rows"):
        simulate_detections(gt[:, :5], "easy", 0, IMAGE)
    with pytest.raises(ValueError, match="detection_probability"):
        DetectorLevel(1.5, 1.0, 0.05)
