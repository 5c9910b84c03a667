"""The MB tracker's person size by foot row (size_by_row, issue 12) against the one learnt height
on PETS09-S2L1 and its 0.5x / 1.5x variants, over seeds: MOTA / IDF1 / HOTA on frames 1-397
(the tuning split), 398-795 (where the size problem was diagnosed, benchmarks/mb_groups.py) and
all frames, each setting's mean over the seeds.

    python benchmarks/mb_perspective.py [--variants 768x576,0.5x,1.5x] [--seeds 0,1,2]

    python benchmarks/mb_perspective.py --calibrate --setting "min07:size_by_row=true,size_min=0.7"

    python benchmarks/mb_perspective.py --variants 768x576 --cost 5

(each --setting is a row of MultiBernoulliTracker parameters, NAME:key=value,...; without one the
rows are the defaults and "image", the former defaults (delta_b_reference image, size_by_row
off, their calibration). --calibrate
refits the box calibration on frames 1-397 of every run but the defaults'. --cost R prints the MB
step's CPU time per frame instead, median of R interleaved rounds. Variants: pets09.py's, and the
development variants 0.6x and 0.4x of the small-scale work, so that 0.5x stays held out. Each
variant's y, as the mb pipeline feeds its tracker, is computed once into the cache
(~/.cache/vtrack/mb-perspective, 0.2-3.2 GB a variant) and replayed by every run: the same tracks
as running the pipeline, at half the cost.)

CROPS AND ZOOMS (2026-11-28, issue 12 part 2): MB collapsed when the people are large relative
to the image -- held out, seed 0, all frames, MOTA / IDF1: crop (central 512 x 384) 0.393 / 0.420
and zoom (1.5x, central 768 x 576) 0.386 / 0.388, against 0.607 / 0.619 at 768 x 576 and 0.571 /
0.637 at 1.5x. Developed on crop2 (the 576 x 432 at (0, 72)) and zoom1.25 (1.25x, the 768 x 576 at
(48, 36)) of _foreground.VARIANTS, frames 1-397, so that crop and zoom stay held out.

Diagnosis (this script's cached y, tracker seed 0, frames 1-397; per-frame FP / FN by foot row
matched at IoU 0.5): zoom1.25 MOTA 0.315 (FP 464, FN 818) against 0.584 at 768 x 576 (431,
478). Not the size: the learnt h (105 px at frame 397) and line (slope 0.264, intercept 21)
were those of the full 1.25x resize (106 px; the same line within 3 % on the rows people walk),
and the two y agreed to 2e-4 on average. The boxes were too large: the FP boxes' median height
1.21 x the annotations' line at their foot row (0.91 at 768 x 576), the matched ones 0.99-1.23 x
their GT (0.89-0.96). Cause: the "row" reward per pixel was a / (a(row) m delta_b_row), eq.
(20)'s 1 / m still in it, so k (models/tbd_likelihood.hpp) grew with the people's share of the
image -- 1.56 x PETS09's on zoom1.25, 1.78 x on crop2, 2.25 x on crop and zoom -- and the best box
reached over grey background and ghosts. Test of the cause: delta_b and delta_b_row times that
share gave zoom1.25 0.315 -> 0.526 (matched boxes 0.94 x GT), crop2 0.495 -> 0.499. Fix
(tbd_likelihood.hpp): per-pixel weights 1 / (a(row) delta_b_row), delta_b_row 0.52 (3e-3 x
442368 / 2550, PETS09's reward at 768 x 576), so a person-sized box earns (1 - ybar) / 0.52 at any
share of the image (the unit test: the same people in a 4x larger image boxed at 0.82-0.88 of
their size before, within 10 % of it after).

What was left: the full 1.25x run's tracks cropped to zoom1.25's region score 0.636 on 1-397
(seeds 1 / 2: 0.659 / 0.672) against 0.541-0.569 for zoom1.25 itself. GT boxes within 0.2 h of a
side border: FN 83 and FP 90 of 255 (the cropped 1.25x run: 24 and 26); interior FN 490 / FP 220
(433 / 205). The reported box of a person half out of view, scaled by the calibration about the
visible part's centre, reaches beyond the border, while the annotations end at it (clipped to
the crop; MOT15's PETS09 boxes all lie within the image's columns). Fix: box_clip
(filters/person_prior.hpp; MB's default). Tried first on the scaled-delta_B run above by
clipping its rows: seed 0 zoom1.25 0.526 -> 0.559 on 1-397, border FN / FP 83 / 90 -> 52 / 59.

Seeds 0-2 through the real pipeline (colour appearance on; `python benchmarks/pets09_identity.py
--method mb --variant V [--set box_clip=false]`), MOTA / IDF1; "before" is main at 7e5333c:

| variant | setting | all | 1-397 | 398-795 |
|---|---|---|---|---|
| crop2 (dev) | before | 0.513 / 0.494 | 0.490 / 0.574 | 0.535 / 0.485 |
| crop2 (dev) | row reward | 0.503 / 0.514 | 0.487 / 0.564 | 0.519 / 0.527 |
| crop2 (dev) | row reward + box_clip | 0.572 / 0.541 | 0.502 / 0.570 | 0.637 / 0.573 |
| zoom1.25 (dev) | before | 0.462 / 0.540 | 0.363 / 0.546 | 0.559 / 0.614 |
| zoom1.25 (dev) | row reward | 0.526 / 0.515 | 0.526 / 0.565 | 0.525 / 0.536 |
| zoom1.25 (dev) | row reward + box_clip | 0.601 / 0.544 | 0.561 / 0.576 | 0.639 / 0.582 |
| 768x576 | before | 0.613 / 0.670 | 0.571 / 0.709 | 0.654 / 0.694 |
| 768x576 | row reward | 0.610 / 0.672 | 0.581 / 0.717 | 0.639 / 0.694 |
| 768x576 | row reward + box_clip | 0.614 / 0.672 | 0.581 / 0.717 | 0.647 / 0.694 |
| 0.5x | before | 0.618 / 0.674 | 0.589 / 0.735 | 0.646 / 0.698 |
| 0.5x | row reward | 0.616 / 0.659 | 0.575 / 0.684 | 0.656 / 0.707 |
| 0.5x | row reward + box_clip | 0.620 / 0.659 | 0.575 / 0.684 | 0.664 / 0.708 |
| 1.5x | before | 0.576 / 0.644 | 0.504 / 0.691 | 0.645 / 0.680 |
| 1.5x | row reward | 0.577 / 0.664 | 0.497 / 0.691 | 0.656 / 0.718 |
| 1.5x | row reward + box_clip | 0.582 / 0.664 | 0.497 / 0.691 | 0.665 / 0.719 |

At 768x576, 0.5x and 1.5x the people's share of the image is PETS09's, so the reward is the same
up to the learnt area's drift (the former 3e-3 per image pixel was 0.44-0.52 per person as h went
from 93 to 85 px): differences there are the runs' divergence. 0.5x's IDF1 is one seed's (seed
1: 0.682 -> 0.614 on all frames, 0.731 -> 0.601 on 1-397, one identity swap; seeds 0 / 2 0.657
-> 0.687, 0.684 -> 0.676). On zoom1.25 the reward alone lowered 398-795 (0.559 / 0.614 -> 0.525 /
0.536), with box_clip it is above the former on MOTA (0.639) and below on IDF1 (0.582): not
looked into. Held out, run once at the end (benchmarks/pets09.py's RESULTS, seed 0, all frames):
crop MB 0.393 / 0.420 -> 0.585 / 0.488, zoom 0.386 / 0.388 -> 0.578 / 0.487.

THE DEFAULT (2026-11-25, third session): "row" with a line that needs support.

The synthetic scenes of tests/test_track_video.py were worse with "row" (above: seed 3 0.760 /
0.875, seed 4 0.897 / 0.947 against 0.935 / 0.966 and 0.941 / 0.969). Two changes, both where
the scene gives no evidence of perspective: (1) the tracker uses the line
(models::PersonHeightLine::well_supported; the SIR does not ask it, its IDF1 on 1-397 fell from
0.487 to 0.425 with it) only from
five row bands of people or more with 85 % of the components within 15 % of the line
(fit_share; rising_share, the weighted share of band pairs rising with the row, at least 0.6).
Printed on the "row" tracker's closed y: scene 3 with 5 bands fit_share 0.58-0.79 (the 3-band
line of its three people had slope 0.26, later 0.09), PETS09 768 x 576 with 5 bands or more
(frame 11 on) 0.89-1.00. (With rising_share >= 0.85 too PETS09 had its line only from frame 80,
frames 36-41 excepted: MOTA / IDF1 / HOTA on all frames 0.547 / 0.546 / 0.392, seeds 0-2, seed
2's first half 0.364 / 0.412; dropped.) (2) Without a line "row" is "image" with delta_b 2e-3
(the likelihood's delta_b_row, 3e-3, holds only with row areas). So scenes 1-5 of
make_scene(320, 240, 150 frames, 3 people) score exactly as the former defaults (MOTA / IDF1 seed
1 0.940 / 0.969, 2 0.942 / 0.971, 3 0.935 / 0.966, 4 0.941 / 0.969, 5 0.926 / 0.962; no line in
any). PETS09 768 x 576, seeds 0-2, --calibrate (fits 1.665-1.685 x 1.698-1.720, offsets
0.009-0.027, 0.034-0.053; their medians 1.673, 1.706, 0.023, 0.045 are the new default
calibration), against the former defaults in the same run:

| setting | 1-397 | 398-795 | all |
|---|---|---|---|
| image (former default) | 0.529 / 0.534 / 0.389 | 0.490 / 0.415 / 0.356 | 0.510 / 0.455 / 0.364 |
| row (now default) | 0.565 / 0.602 / 0.427 | 0.633 / 0.554 / 0.416 | 0.599 / 0.567 / 0.414 |

(The former default's seed 2 scored 0.432 on 1-397 in this run, so its mean is below the
0.535 / 0.525 of the tables below; "row" is better on the tuning split on every figure.) So
"row" became the default: delta_b_reference row, size_by_row true, delta_b_row 3e-3, the
calibration above.

SMALL SCALES (2026-11-24, second session): the collapse at 0.5x and its fix.

Diagnosis on the development variants (seed 0, "row" 3e-3 with the 768 x 576 calibration kept):
MOTA on all frames 0.333 at 0.6x and 0.444 at 0.4x against 0.490 and 0.570 for the defaults;
first-half false positives 1050 (0.6x) and 719 (0.4x) against 392 and 360. Sorting the FPs (no
GT box within IoU 0.5) by their foot row: at 0.6x 453 of them, on 27 tracks, stand in the top
fifth of the image, where no one walks (walls, windows, tree tops), at 0.5 of the height the
annotations' line gives there; at 768 x 576 only 60. Cause: the person height line. Printed by
ForegroundSizeEstimator.person_height_line on the same y: at 0.6x, slope 0.31 and intercept -2
(far people at 9-21 px where the annotations have 19-27), at 0.4x 0.33 and -4, at 768 x 576 0.28
and +4, against the annotations' 0.228 at every scale. Row bands above the people held blobby
specks that pass the area floor (as wide as they are tall: the floor is an area), their medians
of 8-10 px pulled the Theil-Sen line down at the top, and "rows where people were seen" then
reached the top of the image, so the floor of a(row) at the smallest people was no floor: far
rows got a small size range (boxes down to the specks' size) and large reward weights. The fix
(models/person_size.cpp): a band whose median is under a third of the person height is left
out. Lines after it (frame 397 / 794): 768 x 576 0.241 / 0.249 (+17 / +14), 0.6x 0.242 / 0.249
(+11 / +10), 0.4x 0.256 / 0.247 (+6 / +6), within 6-9 % of the annotations' at the rows where
people walk. The defaults do not fit a line (size_by_row off): their figures are unchanged.

"row" (delta_b 3e-3, size_by_row) after the fix against the defaults, means over seeds 0-2, MOTA /
IDF1 / HOTA. 768 x 576 with the calibration refitted on 1-397 (--calibrate; fits 1.656-1.675 x
1.691-1.750, offsets 0.016-0.025, 0.039-0.057; medians 1.658, 1.712, 0.020, 0.040); the other
variants with those medians kept:

| variant | setting | 1-397 | 398-795 | all |
|---|---|---|---|---|
| 768x576 | default | 0.535 / 0.530 / 0.390 | 0.516 / 0.430 / 0.361 | 0.525 / 0.455 / 0.364 |
| 768x576 | row | 0.560 / 0.602 / 0.429 | 0.632 / 0.523 / 0.396 | 0.597 / 0.554 / 0.405 |
| 0.6x (dev) | default | 0.576 / 0.485 / 0.364 | 0.493 / 0.426 / 0.356 | 0.534 / 0.440 / 0.352 |
| 0.6x (dev) | row | 0.570 / 0.659 / 0.447 | 0.649 / 0.507 / 0.395 | 0.610 / 0.573 / 0.414 |
| 0.4x (dev) | default | 0.566 / 0.498 / 0.371 | 0.499 / 0.431 / 0.358 | 0.532 / 0.441 / 0.354 |
| 0.4x (dev) | row | 0.545 / 0.672 / 0.455 | 0.658 / 0.539 / 0.412 | 0.602 / 0.602 / 0.431 |

(768 x 576 before the fix: row 0.456 / 0.604 / 0.411, 0.543 / 0.550 / 0.410, 0.500 / 0.558 /
0.400; the first half's FPs fell from 639 to 449, seed 0.) So on every variant "row" is better on
all frames on MOTA, IDF1 and HOTA, and the first half's MOTA is level (+0.025 at 768 x 576,
-0.006 and -0.021 at 0.6x / 0.4x). Held out, run once (the same calibration kept):

| variant | setting | 1-397 | 398-795 | all |
|---|---|---|---|---|
| 0.5x | default | 0.580 / 0.531 / 0.391 | 0.455 / 0.420 / 0.351 | 0.517 / 0.458 / 0.365 |
| 0.5x | row | 0.572 / 0.677 / 0.460 | 0.626 / 0.518 / 0.397 | 0.599 / 0.576 / 0.419 |
| 1.5x | default | 0.619 / 0.525 / 0.401 | 0.415 / 0.408 / 0.334 | 0.516 / 0.444 / 0.358 |
| 1.5x | row | 0.505 / 0.660 / 0.445 | 0.645 / 0.562 / 0.421 | 0.576 / 0.594 / 0.425 |

(At 1.5x the first half's MOTA is 0.114 lower, FPs 565 against 339, seed 0: the far people
again; all frames are better on every figure.) And on tests/test_track_video.py's synthetic
scenes (seeds 3 / 4, tracker seed 0, identity box calibration), MOTA / IDF1: default 0.935 /
0.966 and 0.941 / 0.969; row 3e-3 0.760 / 0.875 and 0.897 / 0.947 (row 2e-3, looked at after the fact and not chosen: 0.905 / 0.951 and 0.941 /
0.969). Two causes, both outside PETS09: scene 4 fits no line (3 people, no perspective), so
"row" is eq. (20) as printed with delta_b 3e-3, whose weaker reward boxes the KDE's blobs tighter
than their exact extent (the identity calibration); scene 3's 3 people (36 px at foot row 47,
59 at 137, 51 at 231) fit a spurious line (slope 0.09 by frame 149): three people at three rows
are a line to the fit, which counts components (frames x people), not people. So "row" is not
worse held out on PETS09 (0.5x was the collapse), but it is on the synthetic scenes, and by the
issue's rule it stays off. What is left: a line that needs several people per band before it
is believed (the fit cannot tell 3 people of random heights from 3 in perspective), and a
delta_b for "row" that does not trade the synthetic scenes' clean blobs for PETS09's far people.

Cost (--variants 768x576 --cost 5: MultiBernoulliTracker.step's CPU time per frame over all
795 cached frames, seed 0, median of 5 interleaved rounds, the machine shared and loaded):

| setting | ms / step | ratio to default |
|---|---|---|
| default | 5.75 | 1.00 |
| row3e-3 | 9.14 | 1.59 |

(The first session measured 10.9 against 4.8 ms in another run.) Profiled with perf (row, 300
frames): the closing and both integral images of set_image, the box sums (IntegralImage::sum and
clip, box_to_rect) and, for the line, the row bands' medians each frame. The likelihood took the
explained regions twice per box (once for the sum of y, once for the reward): one pass now, the
same sums in the same order (seed 0's tracks unchanged). The rest of the difference is the
reward image and its integral (one pass each per frame), the finer birth grid of the far rows
and the line fit, not cut in this session.

Results (2026-11-24, 768 x 576, seeds 0, 1, 2; frames 1-397 are the tuning split, 398-795 the
half the size problem was diagnosed on, so neither is held out):

| size_by_row | 1-397 | 398-795 | all |
|---|---|---|---|
| False (default) | 0.535 / 0.530 / 0.390 | 0.516 / 0.430 / 0.361 | 0.525 / 0.455 / 0.364 |
| True | 0.304 / 0.507 / 0.354 | 0.362 / 0.411 / 0.322 | 0.333 / 0.454 / 0.335 |

Seed 0 alone, size_by_row: with the box calibration refitted on 1-397 (1.69, 1.36, -0.03, -0.03)
0.127 / 0.451 / 0.341 on 1-397; with size_min 0.7 and the calibration refitted (1.24, 1.23, 0.00,
-0.05) 0.492 / 0.494 / 0.368 on 1-397 and 0.376 / 0.377 / 0.323 on 398-795 (constant: 0.572 /
0.527 / 0.392 and 0.491 / 0.412 / 0.358). So it stays off; the 0.5x / 1.5x variants were not run.

The data hold a line (PETS09's raw foreground y < 0.5, frames 1-400, components of at least a
third of a person, median height by band of foot rows: 57 px at row 162, 71 at 234, 90 at 306, 115 at 414, a slope of about 0.23 px per row), and
the constant path is unchanged (same figures as before the option). Why it loses: the filter's box
is the dark core of a silhouette and, for far people, sits at the lower end of the size clamp.
Filter box heights by the box's bottom row, seed 0, frames 102-300 (median, px):

| box bottom row | 100-160 | 160-220 | 220-280 | 280-340 | 340-400 |
|---|---|---|---|---|---|
| constant h (clamp >= 38 px) | 42 | 44 | 47 | 67 | 82 |
| size_by_row | 27 | 33 | 44 | 64 | 83 |

With the constant prior the clamp's 0.45 x 85 = 38 px holds far people's boxes near 2/3 of their
height, which is what the default calibration (x 1.47) was fitted to; with h(y) the clamp follows
the row down and the far boxes shrink with it, too small for one calibration (in the first
version below, GT / filter box height 2.0 at 60-80 px against 1.2 at 100-130 px,
benchmarks/mb_groups.py's Table 3). A first version took the scale at the box's own
bottom row, which fed back (a smaller box, a higher bottom, a smaller scale): 0.149 MOTA on all
frames. What is left: a likelihood (or size term) that does not favour the core, so the box size
follows the person, before a row-dependent prior can pay off.

The likelihood that does not favour the core: delta_b_reference "row" (models/tbd_likelihood.hpp,
issue 12). Eq. (20)'s reward m_x (1 - ybar) / (m delta_B) grows with the box's pixel count while
the penalty -ybar / delta_F does not, so the best box takes a border strip of mean y_s iff
y_s < (k + ybar) / (1 + k), k = m_x delta_F / (m delta_B): about 0.14 for a 60 px PETS09 person
and 0.73 for a 130 px one. "row" weights each pixel by a / a(row) (the mean person's area over
that of the person the learnt line expects centred on the row; eq. 14's weighted average, so the
derivation and f(y)'s cancelling hold), which makes k the same for every person-sized box. The
unit tests check it on rendered people of one shape at 80, 160 and 320 px (brute-force best box:
0.54-0.58 of each person with "row", 0.48 far to 0.76 near as printed) and through the tracker
(box height 0.55 / 0.62 / 0.59 of a 50 / 90 / 140 px person, against 0.44 / 0.58 / 0.79).

On PETS09 it needs size_by_row (alone, seed 0, delta_b 0.35 "person"-equivalent: MOTA -0.20 on all
frames: with one size range for the whole image a far box grows over several far people's areas
of faint foreground; validate() now requires it) and a floor on a(row) at the smallest people the
line was fitted on (without it, the line's extrapolation above them made specks on the top
fifth's walls and windows worth 8 mean persons' pixels: 131 of seed 0's 763 first-half FPs).
With both (the calibration refitted on 1-397 for every run, --calibrate; means over seeds 0-2):

| setting | 1-397 | 398-795 | all |
|---|---|---|---|
| default (image, 2e-3) | 0.535 / 0.530 / 0.390 | 0.516 / 0.430 / 0.361 | 0.525 / 0.455 / 0.364 |
| row, size_by_row, delta_b 2e-3 | 0.436 / 0.602 / 0.408 | 0.534 / 0.505 / 0.384 | 0.486 / 0.535 / 0.387 |
| row, size_by_row, delta_b 3e-3 | 0.456 / 0.604 / 0.411 | 0.543 / 0.550 / 0.410 | 0.500 / 0.558 / 0.400 |

(3e-3 chosen on 1-397 among 2e-3, 3e-3 and, in the earlier "person"-relative form of the option,
the equivalents of 1.4e-3 (MOTA 0.173 on 1-397) and 4.3e-3 (seed 0: 0.434); calibrations fitted:
1.69-1.70 x 1.59-1.73 for 3e-3.) The near people of the second half are fitted like the others
now: benchmarks/mb_groups.py, seed 0, "row" 0.35-equivalent, GT / filter box by GT height 1.93 x
1.87 (60-80 px), 1.81 x 1.78, 1.69 x 1.69, 1.61-1.74 x 1.07-1.49 (130+ px, two runs) against
1.73 x 1.56 ... 1.22 x 0.95 with the default; far people (60-80 px) missed 70-94 times per half
instead of 231-289. What costs MOTA on 1-397 are false positives, 639 against 351 (seed 0): the
filter now tracks the far people, and MOT15's ground truth leaves some of them out or marks them
ignore (conf 0), so they count as FP -- a walker on the far path top left (frames 86-174, 89 FP
boxes, no GT row) and two people at the top right (frames 147-375, 171 FP boxes; conf-0 rows for
frames 147-244 only). So "row" is better on identities (IDF1 +0.10, HOTA +0.04 on all frames) and
on the second half's MOTA (+0.03), worse on all frames' MOTA (-0.025, mostly the first half's
unannotated people). On tests/test_track_video.py's synthetic scenes (seeds 3 / 4, tracker seed
0, identity box calibration: their GT is the blob's exact box) MOTA 0.905 / 0.941 with 2e-3 and
0.760 / 0.897 with 3e-3, against 0.935 / 0.941 for the defaults (and 0.931 / 0.941 with
size_by_row alone): a weaker reward boxes their clean blobs tighter than their exact extent. It
stays off by the issue's rule (better on all frames and not worse held out).
Held out (once, seed 0, the 768 x 576 calibration kept: the median of the three fits, 1.692,
1.651, 0.036, 0.032; the defaults' rows are the same run's):

| variant | setting | 1-397 | 398-795 | all |
|---|---|---|---|---|
| 0.5x | default | 0.642 / 0.489 / 0.381 | 0.539 / 0.449 / 0.364 | 0.590 / 0.442 / 0.362 |
| 0.5x | row, size_by_row, 3e-3 | 0.328 / 0.601 / 0.407 | 0.178 / 0.448 / 0.353 | 0.252 / 0.486 / 0.364 |
| 1.5x | default | 0.607 / 0.507 / 0.395 | 0.456 / 0.407 / 0.335 | 0.531 / 0.432 / 0.355 |
| 1.5x | row, size_by_row, 3e-3 | 0.466 / 0.661 / 0.433 | 0.606 / 0.553 / 0.416 | 0.537 / 0.562 / 0.407 |

At 1.5x it is better on every figure of all frames; at 0.5x its MOTA collapses (0.252 against
0.590; not diagnosed yet -- the far people there are 15-30 px tall, where the weights a / a(row)
are largest and the closing, which keeps the one h, is 3 x 3). What is left: that 0.5x failure
(diagnosed and fixed: SMALL SCALES at the top), and a ground truth that counts the far people the
filter now finds before MOTA can judge it.
"""
from __future__ import annotations

import argparse
import os
import sys
import time
from typing import List, Optional

import cv2
import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
from _foreground import (CACHE, VARIANTS, Variant, apply_calibration,  # noqa: E402
                         default_gt, default_video, fit_calibration, load_gt, select,
                         transform_gt, variant_video)
from _table import print_table  # noqa: E402
from mb_groups import parse_value  # noqa: E402
import vtrack  # noqa: E402
from vtrack.evaluate import evaluate  # noqa: E402

SPLITS = (("1-397", 1, 397), ("398-795", 398, 795), ("all", 1, 795))

# Development variants of the small-scale work (issue 12): the "row" reward was diagnosed and
# tuned on these, so that 0.5x stays held out.
DEV_VARIANTS = {"0.6x": Variant("0.6x", 0.6, description="resized to 461 x 346 (development)"),
                "0.4x": Variant("0.4x", 0.4, description="resized to 307 x 230 (development)")}


def pipeline_foreground(video: str, name: str):
    """The y the mb pipeline gives its tracker on every frame, and the tracker's closing after
    each, cached as .npy files: the KDE's selective update reads y closed with the tracker's
    closing, which depends only on the learnt person height (the same for every setting of the
    likelihood and of size_by_row), so every run replays these frames; run_mb_cached checks that
    its tracker's closing follows the recorded one."""
    base = CACHE / "mb-perspective"
    y_path, c_path = base / f"{name}-y.npy", base / f"{name}-closing.npy"
    if not (y_path.exists() and c_path.exists()):
        base.mkdir(parents=True, exist_ok=True)
        cap = cv2.VideoCapture(video)
        ok, frame = cap.read()
        background = vtrack.KdeBackground(threads=1)
        tracker = vtrack.MultiBernoulliTracker((frame.shape[1], frame.shape[0]))
        frames, closings = [], []
        while ok:
            frames.append(background.apply(frame).copy())
            tracker.step(frames[-1])
            closings.append(tracker.closing_pixels)
            background.set_closing(tracker.closing_pixels)
            ok, frame = cap.read()
        cap.release()
        np.save(c_path, np.array(closings))
        tmp = base / f"{name}-y.tmp.npy"
        np.save(tmp, np.stack(frames))
        tmp.rename(y_path)
    return np.load(y_path, mmap_mode="r"), np.load(c_path)


def run_mb_cached(cached, params, last: Optional[int] = None) -> List[dict]:
    """mb_groups.run_mb on pipeline_foreground's frames (the same tracks)."""
    y, closings = cached
    tracker = vtrack.MultiBernoulliTracker((y.shape[2], y.shape[1]), **params)
    out = []
    for k, frame in enumerate(y[:last]):
        tracks = tracker.step(np.ascontiguousarray(frame))
        if tracker.closing_pixels != closings[k]:
            raise RuntimeError(f"frame {k}: closing {tracker.closing_pixels} against the cached "
                               f"{closings[k]}; run this setting through mb_groups.run_mb")
        out.append(dict(ids=np.asarray(tracks.ids), boxes=np.asarray(tracks.boxes).reshape(-1, 4)))
    return out


def step_cost(cached, params) -> float:
    """CPU time (time.process_time: the cores are shared) of MultiBernoulliTracker.step per
    frame over the cached frames, in ms."""
    y = cached[0]
    tracker = vtrack.MultiBernoulliTracker((y.shape[2], y.shape[1]), **params)
    frames = [np.ascontiguousarray(f) for f in y]
    start = time.process_time()
    for frame in frames:
        tracker.step(frame)
    return (time.process_time() - start) / len(frames) * 1e3


def mot_rows(run) -> np.ndarray:
    rows = [[k + 1, i, *b, 1, -1, -1, -1]
            for k, f in enumerate(run) for i, b in zip(f["ids"], f["boxes"])]
    return np.array(rows, float).reshape(-1, 10)


def parse_setting(text: str):
    """NAME or NAME:key=value,key=value -> (name, params)."""
    name, _, rest = text.partition(":")
    params = {}
    for item in filter(None, rest.split(",")):
        key, _, value = item.partition("=")
        params[key] = parse_value(value)
    return name, params


# The former defaults (before "row" became the default), with their box calibration.
DEFAULT_SETTINGS = ("default", "image:delta_b_reference=image,size_by_row=false,box_scale_w=1.75,"
                    "box_scale_h=1.47,box_offset_x=-0.01,box_offset_y=-0.01")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--variants", default="768x576")
    parser.add_argument("--seeds", default="0,1,2")
    parser.add_argument("--setting", action="append", default=[], metavar="NAME[:k=v,...]",
                        help="a row: MultiBernoulliTracker parameters (default: "
                             + " and ".join(DEFAULT_SETTINGS) + ")")
    parser.add_argument("--calibrate", action="store_true",
                        help="refit the box calibration on frames 1-397 of each run but the "
                             "defaults'")
    parser.add_argument("--cost", type=int, default=0, metavar="ROUNDS",
                        help="instead of the scores: the MB step's CPU time per frame of each "
                             "setting, median of ROUNDS rounds over all frames, interleaved")
    args = parser.parse_args()
    video, gt_path = default_video(), default_gt()
    if not (os.path.exists(video) and os.path.exists(gt_path)):
        print(f"needs the video ({video}) and the ground truth ({gt_path}); skipped")
        return
    seeds = [int(s) for s in args.seeds.split(",")]
    settings = [parse_setting(t) for t in (args.setting or DEFAULT_SETTINGS)]
    for name in args.variants.split(","):
        v = {**VARIANTS, **DEV_VARIANTS}[name]
        gt = transform_gt(load_gt(gt_path), v)
        cached = pipeline_foreground(variant_video(video, v), name)
        if args.cost:
            # Interleaved (one round of each setting in turn), so a change in the machine's load
            # falls on every setting alike.
            costs = {label: [] for label, _ in settings}
            for _ in range(args.cost):
                for label, extra in settings:
                    costs[label].append(step_cost(cached, dict(seed=seeds[0], **extra)))
            base = np.median(costs[settings[0][0]])
            print(f"\nPETS09-S2L1 {name}, MB step CPU ms per frame, median of {args.cost} rounds\n")
            print_table(["setting", "ms / step", f"ratio to {settings[0][0]}"],
                        [[label, f"{np.median(c):.2f}", f"{np.median(c) / base:.2f}"]
                         for label, c in costs.items()])
            continue
        table = []
        for label, extra in settings:
            calibrate = args.calibrate and bool(extra)
            scores = []  # [seed][split] = (MOTA, IDF1, HOTA)
            for seed in seeds:
                params = dict(seed=seed, **extra)
                if calibrate:
                    params.update(box_scale_w=1.0, box_scale_h=1.0, box_offset_x=0.0,
                                  box_offset_y=0.0)
                rows = mot_rows(run_mb_cached(cached, params))
                if calibrate:
                    cal = fit_calibration(select(rows, 1, 397), gt)
                    print(f"{label} seed {seed} calibration (1-397):",
                          ", ".join(f"{c:.3f}" for c in cal))
                    rows = apply_calibration(rows, cal)
                m = [evaluate(select(gt, a, b), select(rows, a, b)) for _, a, b in SPLITS]
                scores.append([(s["MOTA"], s["IDF1"], s["HOTA"]) for s in m])
                cells = [f"{sp[0]} {x[0]:.3f}/{x[1]:.3f}/{x[2]:.3f} (FP {s['FP']}, FN "
                         f"{s['FN']})" for sp, x, s in zip(SPLITS, scores[-1], m)]
                print(f"{name} {label} seed {seed}: " + ", ".join(cells), flush=True)
            mean = np.mean(np.array(scores), axis=0)
            table.append([label] + ["%.3f / %.3f / %.3f" % tuple(x) for x in mean])
        print(f"\nPETS09-S2L1 {name}, MB MOTA / IDF1 / HOTA, mean over seeds {args.seeds}\n")
        print_table(["setting"] + [s[0] for s in SPLITS], table)

if __name__ == "__main__":
    main()
