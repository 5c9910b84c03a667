"""The re-clustering SIR's tuning protocol on PETS09-S2L1 (benchmarks/pets09.py's docstring, the
SIR paragraph): the KDE foreground (vtrack.KdeBackground with its defaults and update_static on,
as the `sir` pipeline runs it; --background update_static=false turns it off) of all 795 frames computed once and cached (~/.cache/vtrack/sir-foreground-
768x576.npy, bit-packed masks y < 0.5, which is all the tracker reads), the tracker run on the
cached masks with tracker seeds 0-2, each run's uncalibrated boxes (box_scale 1, offsets 0)
calibrated by benchmarks/_foreground.py's fit on frames 1-397 (the MB protocol), and MOTA, IDF1,
FP, FN, ID switches on 1-397 (fitted and scored there), 398-795 and all frames (with the 1-397
fit); the mean over the seeds. `--box-iou` adds the share of matched pairs (IoU > 0.2, 1-397)
below IoU 0.5.

    python benchmarks/sir_tuning.py [--seeds 0,1,2] [--last 397] [--set name=value ...]

Each --set is a ReclusteringSirTracker keyword (several --set combine); --last 795 also scores
398-795 and all frames. Frames/s is not measured here (benchmarks/pets09.py and `vtrack track`
do, with decoding); this is the masks -> tracker part only.

update_static (the sir pipeline's background, apps/pipeline.hpp), 2026-11-25: PETS09-S2L1 frames
1-397, tracker seeds 0-4, calibrated MOTA / IDF1 0.527 / 0.520 without it, 0.580 / 0.551 with it;
false positives 644 -> 535 (the start-up ghosts of the people in view at frame 0 end at frames
35-43 instead of ~83).
"""

from __future__ import annotations

import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
from _foreground import (CACHE, apply_calibration, default_gt, default_video,  # noqa: E402
                         clear_identity, fit_calibration, read_frames, select)

import vtrack  # noqa: E402
from vtrack.evaluate import box_iou_matrix  # noqa: E402
from vtrack.io import mot_rows, read_mot  # noqa: E402

RAW_BOX = dict(box_scale_w=1.0, box_scale_h=1.0, box_offset_x=0.0, box_offset_y=0.0)


def foreground(video: str, background: dict) -> np.ndarray:
    """(frames, H, W/8) uint8: np.packbits of y < 0.5 along the rows, cached per set of
    KdeBackground keywords (`background`, the defaults when empty)."""
    tag = "".join(f"-{k}={v}" for k, v in sorted(background.items()))
    path = CACHE / f"sir-foreground-768x576{tag}.npy"
    if path.exists():
        return np.load(path)
    kde = vtrack.KdeBackground(**background)
    masks = [np.packbits(kde.apply(f) < 0.5, axis=1) for f in read_frames(video)]
    out = np.stack(masks)
    np.save(path, out)
    return out


def run(masks: np.ndarray, last: int, seed: int, params: dict) -> np.ndarray:
    h, w8 = masks.shape[1:]
    tracker = vtrack.ReclusteringSirTracker((w8 * 8, h), seed=seed, **{**params, **RAW_BOX})
    rows = []
    for k in range(last):
        y = np.where(np.unpackbits(masks[k], axis=1), 0.0, 1.0).astype(np.float32)
        rows.append(mot_rows(k + 1, tracker.step(y)))
    return np.concatenate(rows) if rows else np.zeros((0, 10))


def scores(gt: np.ndarray, tracks: np.ndarray) -> dict:
    clear, ident, data = clear_identity(gt, tracks)
    return {"MOTA": float(clear["MOTA"]), "IDF1": float(ident["IDF1"]),
            "FP": int(clear["CLR_FP"]), "FN": int(clear["CLR_FN"]), "IDSW": int(clear["IDSW"]),
            "IDs": int(data["num_tracker_ids"])}


def low_iou_share(gt: np.ndarray, tracks: np.ndarray) -> float:
    """Of the track / GT pairs matched per frame at IoU > 0.2 (Hungarian), the share below 0.5."""
    from scipy.optimize import linear_sum_assignment
    gt = gt[gt[:, 6] != 0]
    ious = []
    for f in np.unique(tracks[:, 0]):
        a, b = tracks[tracks[:, 0] == f, 2:6], gt[gt[:, 0] == f, 2:6]
        if len(a) and len(b):
            m = box_iou_matrix(a, b)
            r, c = linear_sum_assignment(-m)
            ious += [m[i, j] for i, j in zip(r, c) if m[i, j] > 0.2]
    return float(np.mean(np.array(ious) < 0.5)) if ious else float("nan")


def parse_value(text: str):
    if text.lower() in ("true", "false"):
        return text.lower() == "true"
    for cast in (int, float):
        try:
            return cast(text)
        except ValueError:
            pass
    return text


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", default="0,1,2")
    parser.add_argument("--last", type=int, default=397)
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE")
    parser.add_argument("--background", action="append", default=[], metavar="NAME=VALUE",
                        help="a KdeBackground keyword (the foreground is cached per set)")
    parser.add_argument("--box-iou", action="store_true")
    args = parser.parse_args(argv)
    video, gt_path = default_video(), default_gt()
    if not (os.path.exists(video) and os.path.exists(gt_path)):
        print("sir_tuning: video or ground truth missing; skipped")
        return 0
    params = {k: parse_value(v) for k, v in (s.split("=", 1) for s in args.set)}
    background = {"update_static": True,  # the sir pipeline's background (apps/pipeline.hpp)
                  **{k: parse_value(v) for k, v in (s.split("=", 1) for s in args.background)}}
    masks = foreground(video, background)
    gt = read_mot(gt_path)
    halves = {"1-397": (1, 397)}
    if args.last > 397:
        halves.update({"398-795": (398, args.last), "all": (1, args.last)})
    table, cals, shares = {k: [] for k in halves}, [], []
    start = time.process_time()
    for seed in (int(s) for s in args.seeds.split(",")):
        rows = run(masks, args.last, seed, params)
        cal = fit_calibration(select(rows, 1, 397), select(gt, 1, 397))
        cals.append(cal)
        calibrated = apply_calibration(rows, cal)
        for name, (a, b) in halves.items():
            table[name].append(scores(select(gt, a, b), select(calibrated, a, b)))
        if args.box_iou:
            shares.append(low_iou_share(select(gt, 1, 397), select(calibrated, 1, 397)))
        print(f"seed {seed}: " + "  ".join(
            f"{n} {r[-1]['MOTA']:.3f} / {r[-1]['IDF1']:.3f}" for n, r in table.items()),
            flush=True)
    print(f"params {params} background {background}  ({time.process_time() - start:.0f} s CPU)")
    for name, runs in table.items():
        mean = {k: np.mean([r[k] for r in runs]) for k in runs[0]}
        print(f"  {name:8s} MOTA {mean['MOTA']:.3f}  IDF1 {mean['IDF1']:.3f}  FP {mean['FP']:.0f}"
              f"  FN {mean['FN']:.0f}  IDSW {mean['IDSW']:.0f}  IDs {mean['IDs']:.0f}")
    print("  calibration (median of the seeds' fits): "
          + ", ".join(f"{v:.3f}" for v in np.median(np.array(cals), axis=0)))
    if shares:
        print(f"  matched pairs below IoU 0.5 (1-397): {np.mean(shares):.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
