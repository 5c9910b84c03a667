"""Tracking metrics with the field's own tool, TrackEval (the MOTChallenge evaluation code).

    python -m vtrack.evaluate --gt gt.txt --tracks tracks.txt

prints MOTA, MOTP, IDF1, HOTA (with DetA, AssA), ID switches, FP, FN and the counts. Both files
are MOTChallenge text (see :mod:`vtrack.io`). Following the MOT15 convention, ground-truth rows
with confidence 0 are ignored. Matching is by box IoU with the standard thresholds (0.5 for
CLEAR-MOT and IDF1; HOTA averages over IoU 0.05 ... 0.95).

TrackEval's metric classes (``CLEAR``, ``Identity``, ``HOTA``) are called directly on the
per-frame IoU matrices, which is what its MOTChallenge dataset loader feeds them for MOT15 (that
benchmark has no distractor classes to remove). Note that TrackEval's MOTP is the mean IoU of the
matches (higher is better), not motmetrics' mean distance 1 - IoU.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import sys
from typing import Dict, Optional, Sequence

import numpy as np

from .io import read_mot

METRICS = ("MOTA", "MOTP", "IDF1", "HOTA", "DetA", "AssA", "IDSW", "FP", "FN", "GT", "Tracks",
           "GT_IDs", "Track_IDs")


def _trackeval():
    try:
        # TrackEval prints a notice when an optional dataset dependency (pycocotools) is missing;
        # none of its datasets is used here, so keep that off our output.
        with contextlib.redirect_stdout(io.StringIO()):
            import trackeval  # noqa: PLC0415
    except ImportError as err:  # pragma: no cover - depends on the environment
        raise ImportError("vtrack.evaluate needs TrackEval: pip install trackeval "
                          "(or pip install 'vtrack[eval]')") from err
    return trackeval


def box_iou_matrix(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """IoU of every box of `a` (n, 4: x, y, w, h) with every box of `b` (k, 4)."""
    a = np.asarray(a, np.float64).reshape(-1, 4)
    b = np.asarray(b, np.float64).reshape(-1, 4)
    ix = np.minimum(a[:, None, 0] + a[:, None, 2], b[None, :, 0] + b[None, :, 2]) - \
        np.maximum(a[:, None, 0], b[None, :, 0])
    iy = np.minimum(a[:, None, 1] + a[:, None, 3], b[None, :, 1] + b[None, :, 3]) - \
        np.maximum(a[:, None, 1], b[None, :, 1])
    inter = np.clip(ix, 0, None) * np.clip(iy, 0, None)
    union = (a[:, None, 2] * a[:, None, 3]) + (b[None, :, 2] * b[None, :, 3]) - inter
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(union > 0, inter / union, 0.0)


def _table(rows, name: str) -> np.ndarray:
    arr = np.asarray(rows, np.float64)
    if arr.size == 0:
        return np.empty((0, 10))
    if arr.ndim != 2 or arr.shape[1] < 7:
        raise ValueError(f"{name} must be a MOT table of at least 7 columns, got shape {arr.shape}")
    return arr


def _sequence_data(gt: np.ndarray, tracks: np.ndarray) -> dict:
    frames = int(max(gt[:, 0].max(initial=0), tracks[:, 0].max(initial=0)))
    gt_ids, gt_idx = np.unique(gt[:, 1].astype(np.int64), return_inverse=True)
    tr_ids, tr_idx = np.unique(tracks[:, 1].astype(np.int64), return_inverse=True)
    data = {"num_timesteps": frames, "num_gt_ids": len(gt_ids), "num_tracker_ids": len(tr_ids),
            "num_gt_dets": len(gt), "num_tracker_dets": len(tracks),
            "gt_ids": [], "tracker_ids": [], "similarity_scores": []}
    for t in range(1, frames + 1):
        g = gt[:, 0] == t
        k = tracks[:, 0] == t
        for name, ids, rows in (("gt_ids", gt_idx, g), ("tracker_ids", tr_idx, k)):
            frame_ids = ids[rows]
            if len(np.unique(frame_ids)) != len(frame_ids):
                which = "ground truth" if name == "gt_ids" else "tracks"
                raise ValueError(f"{which}: an id appears twice in frame {t}")
            data[name].append(frame_ids.astype(int))
        data["similarity_scores"].append(box_iou_matrix(gt[g, 2:6], tracks[k, 2:6]))
    return data


def evaluate(gt: np.ndarray, tracks: np.ndarray) -> Dict[str, float]:
    """Metrics of `tracks` against `gt`, both MOT arrays (N, >= 7) as :func:`vtrack.io.read_mot`
    returns. GT rows with confidence 0 are dropped (MOT15)."""
    gt = _table(gt, "gt")
    tracks = _table(tracks, "tracks")
    gt = gt[gt[:, 6] != 0]
    data = _sequence_data(gt, tracks)
    return {**evaluate_sequence(data), "GT": int(len(gt)), "Tracks": int(len(tracks))}


def evaluate_sequence(data: dict) -> Dict[str, float]:
    """TrackEval's CLEAR, Identity and HOTA on one sequence in TrackEval's own form (a dict with
    num_timesteps, num_gt_ids, num_tracker_ids, num_gt_dets, num_tracker_dets and per-frame
    gt_ids, tracker_ids, similarity_scores; a pair matches when its similarity is >= 0.5). Used
    with box IoU by :func:`evaluate` and with a 3-D distance similarity by
    :func:`vtrack.rgbd.clear_mot`."""
    trackeval = _trackeval()
    with contextlib.redirect_stdout(io.StringIO()):
        clear = trackeval.metrics.CLEAR({"PRINT_CONFIG": False}).eval_sequence(data)
        ident = trackeval.metrics.Identity({"PRINT_CONFIG": False}).eval_sequence(data)
        hota = trackeval.metrics.HOTA().eval_sequence(data)
    return {
        "MOTA": float(clear["MOTA"]), "MOTP": float(clear["MOTP"]), "IDF1": float(ident["IDF1"]),
        "HOTA": float(np.mean(hota["HOTA"])), "DetA": float(np.mean(hota["DetA"])),
        "AssA": float(np.mean(hota["AssA"])), "IDSW": int(clear["IDSW"]),
        "Frag": int(clear["Frag"]), "FP": int(clear["CLR_FP"]), "FN": int(clear["CLR_FN"]),
        "GT_IDs": int(data["num_gt_ids"]), "Track_IDs": int(data["num_tracker_ids"]),
    }


def format_metrics(metrics: Dict[str, float]) -> str:
    lines = []
    for name in METRICS:
        v = metrics[name]
        lines.append(f"{name:<10}{v:>10.4f}" if isinstance(v, float) else f"{name:<10}{v:>10d}")
    return "\n".join(lines)


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m vtrack.evaluate",
        description="CLEAR-MOT, IDF1 and HOTA of MOTChallenge tracks against ground truth "
                    "(TrackEval).")
    parser.add_argument("--gt", required=True, help="ground truth, MOTChallenge text")
    parser.add_argument("--tracks", required=True, help="tracker output, MOTChallenge text")
    args = parser.parse_args(argv)
    try:
        metrics = evaluate(read_mot(args.gt), read_mot(args.tracks))
    except (OSError, ValueError) as err:
        print(f"vtrack.evaluate: error: {err}", file=sys.stderr)
        return 1
    print(format_metrics(metrics))
    return 0


if __name__ == "__main__":
    sys.exit(main())
