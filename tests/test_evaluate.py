"""vtrack.io (MOTChallenge text) and vtrack.evaluate (TrackEval metrics) on hand-made cases."""

import subprocess
import sys

import numpy as np
import pytest

from vtrack.evaluate import box_iou_matrix, evaluate, main
from vtrack.io import mot_rows, read_mot, write_mot


def row(frame, ident, x, y, w=10, h=20, conf=1):
    return (frame, ident, x, y, w, h, conf, -1, -1, -1)


@pytest.fixture
def hand_case(tmp_path):
    """Two people over 4 frames. Person 1 is tracked exactly as id 10. Person 2 is tracked
    exactly, as id 20 in frames 1-2 and as id 21 in frames 3-4 (one ID switch). One false
    positive in frame 4. A GT row with conf 0 (MOT15: ignored) in frame 2.

    CLEAR: TP 8, FP 1, FN 0, IDSW 1 -> MOTA = 1 - (0 + 1 + 1) / 8 = 0.75, MOTP (mean IoU) = 1.
    IDF1: IDTP = 4 + 2 = 6, IDFP = 9 - 6 = 3, IDFN = 8 - 6 = 2 -> 12 / 17.
    HOTA (all IoUs are 1, so every alpha agrees): DetA = 8 / 9; AssA = (4 * 1 + 4 * 2/4) / 8 =
    0.75; HOTA = sqrt(8/9 * 0.75).
    """
    gt, tr = [], []
    for f in range(1, 5):
        gt += [row(f, 1, 10 * f, 5), row(f, 2, 100, 10 * f)]
        tr += [row(f, 10, 10 * f, 5), row(f, 20 if f <= 2 else 21, 100, 10 * f)]
    gt.append(row(2, 3, 200, 200, conf=0))
    tr.append(row(4, 30, 300, 300))
    gt_path, tr_path = tmp_path / "gt.txt", tmp_path / "tracks.txt"
    write_mot(gt_path, gt)
    write_mot(tr_path, tr)
    return gt_path, tr_path


def test_known_metrics(hand_case):
    gt_path, tr_path = hand_case
    m = evaluate(read_mot(gt_path), read_mot(tr_path))
    assert m["MOTA"] == pytest.approx(0.75)
    assert m["MOTP"] == pytest.approx(1.0)
    assert m["IDF1"] == pytest.approx(12 / 17)
    assert m["HOTA"] == pytest.approx(np.sqrt(8 / 9 * 0.75))
    assert (m["IDSW"], m["FP"], m["FN"], m["GT"]) == (1, 1, 0, 8)


def test_perfect_and_empty_tracks(hand_case):
    gt = read_mot(hand_case[0])
    m = evaluate(gt, gt[gt[:, 6] != 0])
    assert m["MOTA"] == pytest.approx(1.0) and m["IDF1"] == pytest.approx(1.0)
    assert m["HOTA"] == pytest.approx(1.0)
    m = evaluate(gt, np.empty((0, 10)))
    assert m["MOTA"] == 0.0 and m["FN"] == 8 and m["IDF1"] == 0.0


def test_command_line(hand_case):
    gt_path, tr_path = hand_case
    out = subprocess.run([sys.executable, "-m", "vtrack.evaluate", "--gt", str(gt_path),
                          "--tracks", str(tr_path)], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    values = dict(line.split() for line in out.stdout.splitlines())
    assert float(values["MOTA"]) == pytest.approx(0.75)
    assert float(values["IDF1"]) == pytest.approx(12 / 17, abs=1e-4)
    assert set(values) >= {"MOTA", "MOTP", "IDF1", "HOTA", "IDSW", "FP", "FN"}


def test_command_line_error_names_file_and_line(tmp_path, capsys):
    bad = tmp_path / "bad.txt"
    bad.write_text("1,1,0,0,10,10,1,-1,-1,-1\n2,1,zero,0,10,10,1,-1,-1,-1\n")
    assert main(["--gt", str(bad), "--tracks", str(bad)]) == 1
    assert f"{bad}:2" in capsys.readouterr().err


def test_iou_matrix():
    iou = box_iou_matrix([[0, 0, 10, 10]], [[0, 0, 10, 10], [5, 0, 10, 10], [20, 20, 1, 1]])
    assert iou == pytest.approx(np.array([[1.0, 50 / 150, 0.0]]))


def test_mot_round_trip(tmp_path):
    rows = [row(1, 3, 1.5, 2.25, 10.5, 20.75, 0.9), row(2, 4, -3, 4, 5, 6, 1)]
    path = tmp_path / "t.txt"
    write_mot(path, rows)
    # The CLI's format (one writer): boxes to 2 decimals, conf to 4.
    assert path.read_text().splitlines()[0] == "1,3,1.50,2.25,10.50,20.75,0.9000,-1,-1,-1"
    np.testing.assert_allclose(read_mot(path), np.array(rows, float))
    assert list(tmp_path.iterdir()) == [path]  # no temporary file left
    write_mot(path, [])
    assert read_mot(path).shape == (0, 10)


@pytest.mark.parametrize("line, message", [
    ("1,2,3", "expected 6 to 10"),
    ("1,2,3,4,5,x,1", "not a number"),
    ("0,2,3,4,5,6,1", "frame must be an integer >= 1"),
    ("1.5,2,3,4,5,6,1", "frame must be an integer >= 1"),
    ("1,2.5,3,4,5,6,1", "id must be an integer"),
    ("1,2,nan,4,5,6,1", "NaN"),
])
def test_malformed_lines_name_file_and_line(tmp_path, line, message):
    path = tmp_path / "m.txt"
    path.write_text("1,1,0,0,10,10,1,-1,-1,-1\n\n" + line + "\n")
    with pytest.raises(ValueError, match=message) as err:
        read_mot(path)
    assert f"{path}:3:" in str(err.value)


def test_failed_write_keeps_old_file(tmp_path):
    path = tmp_path / "t.txt"
    write_mot(path, [row(1, 1, 0, 0)])
    before = path.read_text()
    with pytest.raises(ValueError):
        write_mot(path, [row(1, 1, float("nan"), 0)])
    with pytest.raises(ValueError):
        write_mot(path, [(1, 2, 3)])
    assert path.read_text() == before
    assert list(tmp_path.iterdir()) == [path]


def test_mot_rows_of_any_tracker():
    import vtrack
    box = vtrack.BoxTracker((640, 480))
    for frame in range(1, 4):
        tracks = box.step(np.array([[100.0 + frame, 100, 40, 100], [400, 200, 40, 100]]))
    assert len(tracks) == 2
    rows = mot_rows(3, tracks)
    assert rows.shape == (2, 10)
    np.testing.assert_array_equal(rows[:, 0], 3)
    np.testing.assert_array_equal(rows[:, 1], tracks.ids)
    np.testing.assert_allclose(rows[:, 2:6], tracks.boxes, rtol=1e-6)  # float32 boxes in rows
    np.testing.assert_array_equal(rows[:, 6], tracks.scores)
    np.testing.assert_array_equal(rows[:, 7:], -1)
    with pytest.raises(ValueError, match="1-based"):
        mot_rows(0, tracks)
    # A tracker on a state space that is no image box has no rows to give.
    scenario = vtrack.scenarios.standard_glmb_scenario(seed=0)
    glmb = scenario.tracker()
    for z in scenario.measurements[:12]:
        points = glmb.step(z)
    assert len(points) > 0 and np.isnan(points.boxes).all()
    with pytest.raises(ValueError, match="no image box"):
        mot_rows(12, points)
