"""vtrack's foreground trackers on synthetic scenes they were not tuned on, at several scales and
densities, against the background-subtraction baselines of benchmarks/pets09.py (issue 12 part 2).

Scenes: vtrack.synthetic.make_scene (textured people crossing a textured background, sensor noise,
a slow illumination change), rendered losslessly (FFV1) to a video, at
  * scale s: the image and the people s times the 320 x 240 scene's (people 14-24 x 36-60 px);
  * far: a 640 x 480 image with the 320 x 240 scene's people (a farther camera);
  * density n: n people in the scene's frames.
Scene seeds --scene-seeds (default 11, 12: the tests use 1-5). Every method keeps its defaults:
vtrack MB and vtrack SIR (vtrack.track_video, tracker seed 0, one thread), reporting their
foreground boxes (the scenes' ground truth is the blob's exact box, so the PETS09 annotation
calibration is off, as in tests/test_track_video.py); MOG2 + ByteTrack and KNN + SORT with their
constants tuned on PETS09 frames 1-397 and no box calibration. Scores: TrackEval MOTA / IDF1 over
the whole scene, the mean over the scene seeds.

    python benchmarks/synthetic_people.py [--scene-seeds 11 12] [--frames 200]
                                          [--methods "vtrack MB,vtrack SIR"]

RESULTS (2026-11-28, the first run, defaults of that day; `python benchmarks/synthetic_people.py`,
scene seeds 11 and 12, 200 frames; MOTA / IDF1, mean of the two scenes):

| scene | vtrack MB | vtrack SIR | MOG2 + ByteTrack | KNN + SORT |
|---|---|---|---|---|
| 0.5x (160 x 120), 4 people | -1.308 / 0.261 | 0.936 / 0.930 | 0.005 / 0.016 | -0.002 / 0.016 |
| 1x (320 x 240), 4 people | 0.435 / 0.747 | 0.964 / 0.982 | 0.924 / 0.960 | 0.933 / 0.966 |
| 2x (640 x 480), 4 people | 0.970 / 0.985 | 0.963 / 0.981 | 0.985 / 0.992 | 0.988 / 0.994 |
| 3x (960 x 720), 4 people | 0.961 / 0.980 | 0.967 / 0.983 | 0.969 / 0.984 | 0.953 / 0.977 |
| far (640 x 480, 1x people), 8 people | -0.025 / 0.517 | 0.956 / 0.976 | 0.938 / 0.968 | 0.958 / 0.979 |
| 2x, 8 people | 0.754 / 0.865 | 0.800 / 0.882 | 0.654 / 0.793 | 0.643 / 0.776 |
| 2x, 16 people | 0.286 / 0.525 | 0.639 / 0.615 | 0.466 / 0.613 | 0.399 / 0.525 |

The SIR holds at every scale and density: it beats both baselines' MOTA and IDF1 at 0.5x, 1x,
3x and with 8 and 16 people (IDF1 with 16 tied with MOG2 + ByteTrack), and is within 0.025 of
them at 2x with 4 people; the baselines' PETS09 pixel constants collapse at 0.5x. MB fails on the
small-people scenes: scene seed 12 at 1x scores -0.086 / 0.518 (408 false positives) where seed 11
scores 0.955 / 0.977. Diagnosis: the scenes' 8 % global light change. Without it
(illumination_amplitude 0) seed 12 scores 0.962 / 0.980; with the MB pipeline's KDE
illumination_compensation on, 0.962 / 0.980 too (the sir pipeline's KDE differs by update_static
only, which alone changes nothing here: its tracker is what holds). From frame ~140 the
uncompensated y turns grey over the background, the learnt person size doubles (MB's boxes
38 x 108 against 14 x 52 people) and births fill the image. illumination_compensation stays off
by default: on PETS09 (seeds 0-2, `benchmarks/pets09_identity.py --method mb --set
illumination_compensation=true`) it cost MOTA / IDF1 0.613 / 0.670 -> 0.604 / 0.630 on all
frames (1-397 0.571 / 0.709 -> 0.567 / 0.667): its gain was the ratio of whole-image means, which
moves with the people in view. Its gain is now the median of per-pixel ratios over a grid (the
people a minority of the pixels): seed 12 at 1x still 0.962 / 0.980, PETS09 0.614 / 0.672 (off)
against 0.609 / 0.653 (1-397: 0.581 / 0.717 against 0.568 / 0.683), so still off by default: on
the tuning half it costs 0.03 IDF1. Left: why a near-1 gain changes PETS09's tracks that much (the
camera's small exposure changes?), and then compensation on by default.
The "far" scenes (640 x 480, people 36-60 px: a tenth of the image height) fail MB for another
reason: compensation does not help there (scene seed 11 0.333 / 0.658 -> 0.016 / 0.496, seed 12
-0.384 / 0.376 -> -0.721 / 0.264), while the SIR scores 0.956 / 0.976. Seed 11, frames 20-180:
MB holds a track on every person, centred on them, but its boxes are ~0.7 x theirs (median 11 x
36 against 17 x 49; IoU < 0.5, so each counts as a miss and a false positive). The scenes have no
perspective, so no person height line and MB's "image" reward, eq. (20) per image pixel: the box
takes a strip of mean y_s only if y_s < (k + ybar) / (1 + k) with k = m_x delta_F / (m delta_B)
(tbd_likelihood.hpp), and k shrinks with the people's share of the image (m_x / m), so in a large
image boxes shrink to the people's dark core, as the crop fix found for the "row" reward. The fix
to make: the per-person reward also without a line (the learnt person area for a(row)), with a
delta_B that keeps the synthetic tests' exact boxes and PETS09's calibration.
Measured for it (MB, `delta_b_reference=person size_by_row=false delta_b=0.35`, PETS09's
equivalent of "image" 2e-3; MOTA, scene seeds 11 / 12; default -> person -> person with
illumination_compensation): far 0.333 / -0.384 -> 0.954 / 0.960; 1x 0.955 / -0.086 -> 0.953 /
0.953 -> 0.949 / 0.937; 0.5x -1.364 / -1.251 -> 0.331 / -0.465 -> 0.329 / 0.578; 2x with 8 people
0.580 / 0.928 -> 0.708 / 0.869 -> 0.591 / 0.571. So the per-person reward fixes the far scenes and
1x seed 12 (whose collapse the light change starts), not the 0.5x scenes (people 7-12 x 18-30 px),
and trades seeds at 2x; compensation on top helps 0.5x seed 12 only. Not yet a default.

Later the same day, three changes to MB, all now defaults: (1) the mb pipeline's KDE compensates
global light changes (illumination_compensation); (2) the KDE's own 3 x 3 closing stays a floor
under the tracker's person-relative one, which had fallen to none for people under ~33 px (the
0.5x scenes' sensor specks fed tracks); (3) without a person height line (these scenes have no
perspective) the reward is per the prior's person area, delta_b_no_line, instead of eq. (20) per
image pixel, whose reward fell with the people's share of the image (the far scenes' boxes 0.7 x
the people). MB's own box is then the silhouette's core: it reports the silhouette's box with
vtrack.pipelines.SILHOUETTE_BOX (1.092 x 1.078, fitted on scene seeds 21-25), as every vtrack row
here does. Each of (1) and (2) alone at 0.5x: MOTA 0.644 / 0.250 and 0.565 / -0.017 for seeds
11 / 12; both, 0.949 / 0.966.

delta_b_no_line was chosen on a tuning split of scenes without perspective that this table does
not score: the tests' 320 x 240 crossing scenes 3 and 4 (MJPG), tests/test_multi_bernoulli.py's
768 x 576 scene of 70-140 px people (rendered y), and scene seeds 21 and 22 of "2x, 8 people" and
"far" (MB MOTA, the silhouette box refitted on seeds 21-25 for each value; /tmp script, not kept):

| delta_b_no_line | test 3 | test 4 | 768 x 576 | 2x8 s21 | far s21 | 2x8 s22 | far s22 | mean |
|---|---|---|---|---|---|---|---|---|
| 0.17 | 0.935 | 0.937 | 0.951 | 0.842 | 0.954 | 0.956 | 0.960 | 0.933 |
| 0.2 (default) | 0.935 | 0.941 | 0.946 | 0.875 | 0.955 | 0.959 | 0.959 | 0.938 |
| 0.25 | 0.869 | 0.937 | 0.932 | 0.902 | 0.954 | 0.959 | 0.957 | 0.930 |
| 0.3 | 0.895 | 0.933 | 0.905 | 0.914 | 0.953 | 0.952 | 0.956 | 0.930 |
| 0.35 | 0.931 | 0.929 | 0.797 | 0.913 | 0.953 | 0.951 | 0.956 | 0.919 |
| 0.52 (delta_b_row) | | | 0.565 | | | | | |

(The smaller, the more small people found; the larger, the fewer pairs boxed as one.) On
PETS09-S2L1, which has its line from frame ~15, the three changes cost MB over tracker seeds 0-15
(`benchmarks/pets09_identity.py --method mb`, MOTA / IDF1 all frames) 0.613 / 0.659 -> 0.607 /
0.647, all of it (1)'s on frames 1-397, the tuned half (398-795 IDF1 0.680 -> 0.688).

Then this file with the new defaults, every method (`python benchmarks/synthetic_people.py
--scene-seeds 11 12`: the scenes above, which the diagnosis of these changes looked at):

| scene (MOTA / IDF1) | vtrack MB | vtrack SIR | MOG2 + ByteTrack | KNN + SORT |
|---|---|---|---|---|
| 0.5x, 4 people | 0.961 / 0.980 | 0.936 / 0.930 | 0.005 / 0.016 | -0.002 / 0.016 |
| 1x, 4 people | 0.959 / 0.979 | 0.964 / 0.982 | 0.924 / 0.960 | 0.933 / 0.966 |
| 2x, 4 people | 0.970 / 0.985 | 0.963 / 0.981 | 0.985 / 0.992 | 0.988 / 0.994 |
| 3x, 4 people | 0.960 / 0.980 | 0.967 / 0.983 | 0.969 / 0.984 | 0.953 / 0.977 |
| far (640 x 480, 1x people), 8 people | 0.962 / 0.981 | 0.956 / 0.976 | 0.938 / 0.968 | 0.958 / 0.979 |
| 2x, 8 people | 0.756 / 0.873 | 0.800 / 0.882 | 0.654 / 0.793 | 0.643 / 0.776 |
| 2x, 16 people | 0.610 / 0.704 | 0.639 / 0.615 | 0.466 / 0.613 | 0.399 / 0.525 |

Held out (`--scene-seeds 31 32`, never looked at before this run):

| scene (MOTA / IDF1) | vtrack MB | vtrack SIR | MOG2 + ByteTrack | KNN + SORT |
|---|---|---|---|---|
| 0.5x, 4 people | 0.930 / 0.880 | 0.891 / 0.942 | 0.001 / 0.016 | -0.012 / 0.012 |
| 1x, 4 people | 0.953 / 0.976 | 0.912 / 0.955 | 0.925 / 0.961 | 0.956 / 0.978 |
| 2x, 4 people | 0.691 / 0.858 | 0.954 / 0.976 | 0.994 / 0.978 | 0.986 / 0.974 |
| 3x, 4 people | 0.963 / 0.981 | 0.969 / 0.984 | 0.975 / 0.937 | 0.975 / 0.988 |
| far (640 x 480, 1x people), 8 people | 0.962 / 0.981 | 0.951 / 0.975 | 0.951 / 0.975 | 0.960 / 0.980 |
| 2x, 8 people | 0.857 / 0.925 | 0.888 / 0.937 | 0.612 / 0.685 | 0.610 / 0.713 |
| 2x, 16 people | 0.727 / 0.800 | 0.707 / 0.696 | 0.456 / 0.627 | 0.408 / 0.583 |

MB now holds at every scale and distance and beats both baselines with 8 and 16 people; what is
left is a person much wider than the prior's aspect (0.35): at 2x scene seed 31 (MOTA 0.420) a
46 x 77 px person is held by two boxes side by side, the second born on the strip the first
leaves (eq. 20's box is the core, and the strip is foreground no box explains); eq. (20) per
image pixel split it too (0.284). 0.5x seed 31's IDF1 0.781 is an identity change (0.977 with
the former reward). The SIR: within 0.05 of the best baseline at 1x and 2x with 4 people.

MB after max_particles 400 -> 1600 (benchmarks/pets09_identity.py has why; `--scene-seeds 31 32
--methods "vtrack MB"`): 0.5x 0.928 / 0.879, 1x 0.955 / 0.977, 2x 0.961 / 0.980 (the wide person
is now one box: it widens over the person before the strip is born as a second target), 3x 0.963
/ 0.981, far 0.962 / 0.981, 2x with 8 people 0.807 / 0.897, with 16 people 0.714 / 0.754 (on
scene seeds 11, 12, 21, 22 the dense scenes went 0.837 -> 0.892 and 0.616 -> 0.614: their spread
over scene seeds is wider than the change).
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import sys
import tempfile
from statistics import mean

import cv2

sys.path.insert(0, os.path.dirname(__file__))
from _foreground import (BASELINES, IDENTITY_CALIBRATION, VTRACK_METHODS,  # noqa: E402
                         mota_idf1)
from _table import print_table  # noqa: E402

from vtrack.synthetic import make_scene  # noqa: E402

BASE_SIZE = ((14, 24), (36, 60))

# name: (width, height, people scale, n_people)
SCENES = {
    "0.5x, 4 people": (160, 120, 0.5, 4),
    "1x, 4 people": (320, 240, 1.0, 4),
    "2x, 4 people": (640, 480, 2.0, 4),
    "3x, 4 people": (960, 720, 3.0, 4),
    "far (640 x 480, 1x people), 8 people": (640, 480, 1.0, 8),
    "2x, 8 people": (640, 480, 2.0, 8),
    "2x, 16 people": (640, 480, 2.0, 16),
}

METHODS = ["vtrack MB", "vtrack SIR", "MOG2 + ByteTrack", "KNN + SORT"]


def render(path: str, width: int, height: int, scale: float, n_people: int, seed: int,
           frames: int):
    size = tuple(tuple(int(round(v * scale)) for v in r) for r in BASE_SIZE)
    scene = make_scene(width, height, frames, n_people, seed=seed, size=size,
                       speed=(1.0 * scale, 2.5 * scale))
    writer = cv2.VideoWriter(path, cv2.VideoWriter_fourcc(*"FFV1"), 10.0, (width, height))
    if not writer.isOpened():
        raise SystemExit("OpenCV cannot write FFV1 video here")
    for k in range(len(scene)):
        writer.write(scene.frame(k))
    writer.release()
    return scene.gt_rows()


def run(name: str, video: str, seed: int = 0):
    if name in VTRACK_METHODS:
        rows, _ = VTRACK_METHODS[name].run(video, seed=seed, foreground_box=True)
    else:
        baseline = dataclasses.replace(BASELINES[name], calibration=IDENTITY_CALIBRATION)
        rows, _ = baseline.run(video)
    return rows


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene-seeds", type=int, nargs="+", default=[11, 12])
    parser.add_argument("--frames", type=int, default=200)
    parser.add_argument("--methods", default=",".join(METHODS),
                        help="comma-separated subset of " + ", ".join(METHODS))
    args = parser.parse_args(argv)
    methods = [m.strip() for m in args.methods.split(",")]
    unknown = sorted(set(methods) - set(METHODS))
    if unknown:
        parser.error(f"unknown methods {unknown}; choose from {METHODS}")
    table = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene_name, (w, h, scale, n) in SCENES.items():
            scores = {m: [] for m in methods}
            for s in args.scene_seeds:
                video = os.path.join(tmp, f"scene_{s}.avi")
                gt = render(video, w, h, scale, n, s, args.frames)
                for m in methods:
                    scores[m].append(mota_idf1(gt, run(m, video)))
            table.append([scene_name] + [
                f"{mean(v[0] for v in scores[m]):.3f} / {mean(v[1] for v in scores[m]):.3f}"
                for m in methods])
            print(table[-1], flush=True)
    print()
    print_table(["scene (MOTA / IDF1)"] + methods, table)
    return 0


if __name__ == "__main__":
    sys.exit(main())
