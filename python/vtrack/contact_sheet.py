"""A contact sheet of tracking results: a grid of video frames with the tracks drawn in a colour
per label (and the ground truth, when given, in thin white), as one PNG a person can look at.

    python -m vtrack.contact_sheet --video VIDEO --tracks TRACKS [--gt GT] --out sheet.png
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Optional, Sequence

import numpy as np

from .io import read_mot


def _colour(label: int) -> tuple:
    # The golden-ratio hue walk of the C++ renderer (apps/track_video.cpp), so colours match.
    import cv2

    hue = (label * 0.618033988749895) % 1.0 * 180.0
    bgr = cv2.cvtColor(np.uint8([[[hue, 220, 255]]]), cv2.COLOR_HSV2BGR)[0, 0]
    return tuple(int(c) for c in bgr)


def contact_sheet(video: str, tracks: np.ndarray, frames: Sequence[int],
                  gt: Optional[np.ndarray] = None, columns: int = 3, scale: float = 0.5) -> np.ndarray:
    """The frames (1-based numbers) of `video` with `tracks` (MOT rows) and optional `gt` (MOT
    rows, conf-0 rows drawn dashed-grey) drawn, tiled `columns` wide at `scale`; BGR uint8."""
    import cv2

    wanted = sorted(set(int(f) for f in frames))
    tiles = {}
    cap = cv2.VideoCapture(str(video))
    number = 0
    while wanted and number < wanted[-1]:
        ok, frame = cap.read()
        if not ok:
            raise OSError(f"{video}: cannot decode frame {number + 1}")
        number += 1
        if number not in wanted:
            continue
        if gt is not None:
            for row in gt[gt[:, 0] == number]:
                x, y, w, h = (int(round(v)) for v in row[2:6])
                grey = 255 if row[6] != 0 else 150
                cv2.rectangle(frame, (x, y), (x + w, y + h), (grey, grey, grey), 1)
        for row in tracks[tracks[:, 0] == number]:
            x, y, w, h = (int(round(v)) for v in row[2:6])
            colour = _colour(int(row[1]))
            cv2.rectangle(frame, (x, y), (x + w, y + h), colour, 2)
            cv2.putText(frame, str(int(row[1])), (x + 2, y + 14), cv2.FONT_HERSHEY_SIMPLEX, 0.5,
                        colour, 2)
        cv2.putText(frame, f"frame {number}", (8, 24), cv2.FONT_HERSHEY_SIMPLEX, 0.8,
                    (255, 255, 255), 2)
        tiles[number] = cv2.resize(frame, None, fx=scale, fy=scale, interpolation=cv2.INTER_AREA)
    images = [tiles[f] for f in sorted(tiles)]
    while len(images) % columns:
        images.append(np.zeros_like(images[0]))
    rows = [np.hstack(images[i:i + columns]) for i in range(0, len(images), columns)]
    return np.vstack(rows)


def main(argv: Optional[Sequence[str]] = None) -> int:
    import cv2

    parser = argparse.ArgumentParser(prog="python -m vtrack.contact_sheet", description=__doc__)
    parser.add_argument("--video", required=True)
    parser.add_argument("--tracks", required=True, help="MOTChallenge tracks file")
    parser.add_argument("--gt", help="MOTChallenge ground truth (drawn in white), optional")
    parser.add_argument("--out", required=True, help="PNG to write")
    parser.add_argument("--frames", type=int, nargs="+", help="1-based frame numbers "
                        "(default: six spread over the tracked frames)")
    args = parser.parse_args(argv)
    tracks = read_mot(args.tracks)
    gt = read_mot(args.gt) if args.gt else None
    frames = args.frames
    if not frames:
        last = int(tracks[:, 0].max()) if len(tracks) else 1
        frames = np.linspace(max(1, last // 8), last, 6).astype(int).tolist()
    sheet = contact_sheet(args.video, tracks, frames, gt)
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    partial = out.with_name(out.stem + ".partial.png")
    if not cv2.imwrite(str(partial), sheet):
        raise OSError(f"cannot write {partial}")
    partial.replace(out)
    print(f"contact sheet: {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
