"""Quality of background subtraction on PETS09-S2L1 (vtest.avi) against its ground-truth boxes:
vtrack's KDE (eq. 10) vs OpenCV's MOG2 and KNN, after the same closing and threshold.

Every method's output is turned into a background image y in [0, 1] (vtrack: its y; MOG2/KNN:
1 where their mask says background or shadow, 0 where it says foreground), closed with the same
square (vtrack.image.close_square) and thresholded the same way (vtrack.image.foreground_mask, y < threshold).
Over the frames after a warm-up, with the considered GT boxes (conf 1; the conf-0 boxes are
"don't care": their pixels are excluded from the precision proxy):
  * recall proxy: share of GT boxes that are mostly foreground (at least half their pixels);
  * mean foreground fraction inside GT boxes;
  * precision proxy: share of foreground pixels that lie inside some GT box;
  * foreground share of the image.
People fill roughly half to two thirds of their box, so neither proxy can reach 1, and some
people far away are not annotated at all (see SOURCE.md of the GT), which lowers precision.
Also writes a contact sheet PNG: per row one frame, with the GT boxes drawn on the frame, on
vtrack's y, on vtrack's foreground mask and on the MOG2 and KNN foreground masks.

    python benchmarks/bgs_quality.py [--video PATH] [--gt PATH] [--out PNG] [--threshold T]

The GT defaults to $VTRACK_PETS_GT, else data/pets09-s2l1/gt.txt of the repository (shipped with vtrack,
data/pets09-s2l1/SOURCE.md); without it the script says so and exits 0.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections import defaultdict
from pathlib import Path

import cv2
import numpy as np

import vtrack

REPO = Path(__file__).resolve().parent.parent


def default_video() -> str:
    return os.environ.get("VTRACK_VIDEO", str(Path.home() / ".cache" / "vtrack" / "vtest.avi"))


def default_gt() -> str:
    return os.environ.get("VTRACK_PETS_GT", str(REPO / "data" / "pets09-s2l1" / "gt.txt"))


def load_gt(path: str):
    """{0-based frame index: [(x0, y0, x1, y1, conf)]} from a MOTChallenge gt.txt (1-based frames)."""
    boxes = defaultdict(list)
    for row in np.loadtxt(path, delimiter=",", ndmin=2):
        frame, _, left, top, width, height, conf = row[:7]
        boxes[int(frame) - 1].append((left, top, left + width, top + height, int(conf)))
    return boxes


def box_mask(shape, boxes, conf):
    mask = np.zeros(shape, bool)
    for x0, y0, x1, y1, c in boxes:
        if c == conf:
            mask[max(0, int(round(y0))):max(0, int(round(y1))), max(0, int(round(x0))):max(0, int(round(x1)))] = True
    return mask


class Method:
    def __init__(self, name, to_y):
        self.name = name
        self.to_y = to_y  # frame -> background image y (float32, 1 = background)
        self.boxes_total = self.boxes_mostly_fg = 0
        self.box_fractions = []
        self.fg_inside = self.fg_counted = self.fg_all = self.pixels = 0


def opencv_y(subtractor):
    def to_y(frame):
        mask = subtractor.apply(frame)
        return (mask != 255).astype(np.float32)  # 127 = shadow counts as background
    return to_y


def draw_boxes(image, boxes):
    out = image if image.ndim == 3 else cv2.cvtColor(image, cv2.COLOR_GRAY2BGR)
    for x0, y0, x1, y1, conf in boxes:
        colour = (0, 220, 0) if conf else (0, 200, 255)
        cv2.rectangle(out, (int(x0), int(y0)), (int(x1), int(y1)), colour, 2)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--video", default=default_video())
    parser.add_argument("--gt", default=default_gt())
    parser.add_argument("--out", default=str(REPO / "demo-output" / "bgs_contact_sheet.png"))
    parser.add_argument("--threshold", type=float, default=0.5)
    parser.add_argument("--closing", type=int, default=3)
    parser.add_argument("--samples", type=int, default=10)
    parser.add_argument("--period", type=int, default=10)
    parser.add_argument("--bandwidth", default="0.03,0.03,0.06")
    parser.add_argument("--warmup", type=int, default=100, help="frames not evaluated (default 100)")
    parser.add_argument("--sheet-frames", default="150,330,520,700")
    args = parser.parse_args()

    if not Path(args.gt).is_file():
        print(f"ground truth not found at {args.gt} (set VTRACK_PETS_GT): quality not measured")
        return
    if not Path(args.video).is_file():
        sys.exit(f"video not found at {args.video} (set VTRACK_VIDEO or run make demo)")
    gt = load_gt(args.gt)
    bandwidth = tuple(float(v) for v in args.bandwidth.split(","))
    kde = vtrack.KdeBackground(n_samples=args.samples, period=args.period, bandwidth=bandwidth, closing=0)
    methods = [
        Method(f"vtrack KDE (N0={args.samples}, K0={args.period}, bandwidth={bandwidth})", kde.apply),
        Method("OpenCV MOG2 (defaults)", opencv_y(cv2.createBackgroundSubtractorMOG2())),
        Method("OpenCV KNN (defaults)", opencv_y(cv2.createBackgroundSubtractorKNN())),
    ]
    sheet_frames = [int(v) for v in args.sheet_frames.split(",")]
    sheet_rows = []

    cap = cv2.VideoCapture(args.video)
    k = 0
    while True:
        ok, frame = cap.read()
        if not ok:
            break
        boxes = gt.get(k, [])
        considered = box_mask(frame.shape[:2], boxes, 1)
        dont_care = box_mask(frame.shape[:2], boxes, 0) & ~considered
        tiles = [draw_boxes(frame.copy(), boxes)]
        for m in methods:
            y = vtrack.image.close_square(m.to_y(frame), args.closing)
            fg = vtrack.image.foreground_mask(y, threshold=args.threshold) > 0
            if k in sheet_frames:
                shown = ([y] if m is methods[0] else []) + [(~fg).astype(np.float32)]
                tiles += [draw_boxes((image * 255).astype(np.uint8), boxes) for image in shown]
            if k < args.warmup:
                continue
            for x0, y0, x1, y1, conf in boxes:
                if conf != 1:
                    continue
                region = fg[max(0, int(round(y0))):max(0, int(round(y1))), max(0, int(round(x0))):max(0, int(round(x1)))]
                if region.size == 0:
                    continue
                fraction = region.mean()
                m.box_fractions.append(fraction)
                m.boxes_total += 1
                m.boxes_mostly_fg += fraction >= 0.5
            m.fg_inside += np.count_nonzero(fg & considered)
            m.fg_counted += np.count_nonzero(fg & ~dont_care)
            m.fg_all += np.count_nonzero(fg)
            m.pixels += fg.size
        if k in sheet_frames:
            row = np.hstack([cv2.resize(t, (t.shape[1] // 2, t.shape[0] // 2), interpolation=cv2.INTER_AREA)
                             for t in tiles])
            cv2.putText(row, f"frame {k}", (8, 24), cv2.FONT_HERSHEY_SIMPLEX, 0.7, (255, 255, 255), 2)
            sheet_rows.append(row)
        k += 1

    print(f"{k} frames of {args.video}; evaluated frames {args.warmup}..{k - 1}; closing "
          f"{args.closing}x{args.closing}, foreground = y < {args.threshold}; GT {args.gt}\n")
    print("| method | GT boxes mostly foreground (recall proxy) | mean fg fraction in GT boxes "
          "| fg pixels inside GT boxes (precision proxy) | fg share of image |")
    print("|---|---:|---:|---:|---:|")
    for m in methods:
        print(f"| {m.name} | {m.boxes_mostly_fg / m.boxes_total:.3f} ({m.boxes_mostly_fg}/{m.boxes_total}) "
              f"| {np.mean(m.box_fractions):.3f} | {m.fg_inside / max(m.fg_counted, 1):.3f} "
              f"| {m.fg_all / m.pixels:.4f} |")

    if sheet_rows:
        titles = ["frame + GT (green; orange = conf 0)", "vtrack KDE y, closed (white = bg)",
                  f"vtrack KDE y < {args.threshold} (black = fg)", "MOG2, closed (black = fg)",
                  "KNN, closed (black = fg)"]
        header = np.zeros((36, sheet_rows[0].shape[1], 3), np.uint8)
        width = sheet_rows[0].shape[1] // len(titles)
        for i, title in enumerate(titles):
            cv2.putText(header, title, (i * width + 8, 24), cv2.FONT_HERSHEY_SIMPLEX, 0.5, (255, 255, 255), 1)
        out = Path(args.out)
        out.parent.mkdir(parents=True, exist_ok=True)
        cv2.imwrite(str(out), np.vstack([header, *sheet_rows]))
        print(f"\ncontact sheet: {out}")


if __name__ == "__main__":
    main()
