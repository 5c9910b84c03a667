"""Vehicle dimensions and light/heavy classification (particle-filters-human-vehicle §3, issue 13)
on generated road scenes (vtrack.synthetic_road), per method.

Usage: python benchmarks/vehicles.py [--vehicles N] [--seed S] [--step K] [--noise PX ...]
                                     [--video-vehicles M] [--video-setups NAME ...] [--video-seed S2]
                                     [--video-scale F] [--video-set NAME=VALUE ...]
                                     [--video-class-mix CLASS=SHARE ...] [--video-mean-gap SECONDS]
                                     [--scene-dir DIR] [--video-only]

From observations: for every camera set-up of vtrack.synthetic_road, a scene of N vehicles (seed
S, the generator's class mix: cars, vans, motorbikes, cars with trailers, trucks, articulated
lorries, buses, with dimensions drawn from ranges, not Table 1's means), observed every K-th
frame while fully in view through the exact silhouette polygon (the generator's projected cuboid
outline) plus independent Gaussian noise of PX pixels on each outline point. No occlusion in
this mode (the silhouette of a vehicle hidden behind another is given whole). Methods, each a
VehicleDimensionEstimator with the defaults but for the named parameters:
  * ray (paper): §3.3's samples on the ray, x* = the most likely previous sample;
  * mh: Metropolis-Hastings in W-H-L space with the likelihood, x* = the most likely sample;
  * mh all: the full acceptance ratio (sum over the previous samples), n_particles 100;
  * discrete: §3.3's projected class models;
  * rays (extension): the exact rigid posterior given every frame's ray (two running sums);
  * rays, no far views: the same with far_view_gate 0 (only the views within the resolution cut);
  * ... decision=last / mean: the last frame's posterior / the mean over the frames used, instead
    of the default "auto" (last for rays, mean for the others);
  * ... rule=class: heavy when the MAP class is (Table 1: truck, bus), instead of the default
    W H L >= heavy_volume (45 m^3);
  * naive 2-D: light/heavy from the rectified silhouette's length alone (the along-road extent
    of its road-plane bounding box, averaged over the frames), with the threshold that is best
    on this very data (an oracle: the baseline at its best).
--ablations runs the open choices (dynamic_sigma, x*, chain length, heavy_volume, S) instead.
Reported: light and heavy accuracy and their mean, MAE of W, H, L over vehicles (metres), and
the estimator's time per vehicle-frame (update() from Python: the silhouette's projection, the
ray, the chain; median over set-ups, this machine, one thread).

From video (--video-vehicles M > 0): a scene of M vehicles per --video-setups, rendered to a
lossless video, then vtrack.vehicles.measure_vehicles with the defaults end to end (KDE
background, blobs, tracker, estimator); a reported vehicle is matched to the ground-truth vehicle
whose image boxes its boxes overlap most (IoU > 0.5) over its frames; "found" = ground-truth
vehicles with a visible frame that some reported vehicle matches; "found of those seen apart" counts
only the vehicles whose image box is, in 5 frames or more, clear of every other vehicle's while they
are fully in view and 90 % visible (seen_apart(); the others share one blob with another vehicle for
their whole passage, which the silhouettes alone can seldom part). Time per frame is the whole
pipeline's. Table 3 says what the reported vehicles beyond one per ground-truth vehicle are.

Issue 13's tuning log (the blob tracker's road-plane prediction, this session): diagnosed on the
video scenes of seed 100 with 20 vehicles on mast_high, gantry and side (the "tuning split");
reported on seed 500 with 40 vehicles on all five set-ups (held out: never looked at while
fixing; `--video-only --video-vehicles 40 --video-seed 500 --video-setups mast_low mast_high
gantry side wide_distorted`). Held out, with the road-plane prediction: found 95-100 %, light
90.6-100 %, heavy 100 % but on gantry (3/7: trucks called light, L off by 1.8 m on average), and
1-9 extra reported vehicles per set-up (most a second track of a vehicle, or one track over
several vehicles in one blob). Below the bar: vehicles that stay in one blob (following in one
lane at the same speed, side by side) still reach the estimator as one outline.

Pixel sizes that follow the camera (blob_closing, min_area = 0: 5 px and 150 px at focal length
900 px, scaled by f/900 and (f/900)^2; before, fixed 5 px and 150 px). --video-scale F renders the
set-ups at F times their resolution (focal length and image size scaled together, the same field
of view); --video-set passes pipeline parameters. Tuning-split scenes (seed 100, 20 vehicles),
light / heavy correct, found, fixed sizes -> auto:
  0.5x mast_high   100 / 100 %, 20/20  ->  100 / 100 %, 20/20
  0.5x gantry      93.3 / 80 %, 20/20  ->  100 / 100 %, 20/20   (MAE L 1.31 -> 0.86 m)
  1x wide_distorted (f = 560) 93.3 / 100 %, 20/20  ->  100 / 100 %, 20/20   (MAE L 0.99 -> 0.76 m)
  2x mast_high     100 / 80 %, 20/20   ->  100 / 75 %, 19/20   (a bus "not fully in view" in both)
  2x gantry        100 / 80 %, 20/20   ->  100 / 100 %, 20/20
(the 960x540 set-ups at f = 900 are unchanged). Gantry, seed 300 (40 vehicles, tuning): found
38/40, light 100 %, heavy 8/9: the track reported for the missed 8.0 m truck also followed
another vehicle (59 of its 123 matched frames went to vehicle 19: their blobs joined and the
track changed vehicle), and its estimate says L 1.0 m; a later second track on the truck called
it heavy. The blob tracker's identity through joins, not the estimator, is what fails there.

Issue 13, gantry heavies called light (this session; developed on tuning seeds 100, 200, 300 and a
new 400, never on 500/600). Cause: under the gantry (7.5 m, looking along its lane) approaching
vehicles emerge from the distance one behind the other as one blob for tens of frames (a pixel row
is ~7 m of road at 200 m); those views' far, shallow rays read the tens of metres of extra length
as a taller vehicle and, S being metres in every view, outvoted the near views, whose rays then
put L at min_size: cars came out L 1.0-1.3 m with H 2.2-2.6 m (light by luck), the 8.0 m truck of
seed 300 L 1.0 m. With the exact silhouettes (silhouettes.csv) the same vehicles come out right:
the segmentation's merged blobs, not the geometry, feed the error. Option (off by default, see
below): views whose length is resolved worse than max_length_resolution = 2 m of road per pixel
are not used (`--video-set max_length_resolution=2.0`). Gantry, 40
vehicles, before -> after (found / light / heavy / MAE W H L m):
  seed 200  40/40  100 % / 6 of 6 / 0.11 0.15 0.75  ->  40/40  100 % / 6 of 6 / 0.07 0.08 0.42
  seed 300  38/40  100 % / 8 of 9 / 0.11 0.16 1.00  ->  38/40  100 % / 8 of 9 / 0.10 0.12 0.79
  seed 400  39/40  100 % / 4 of 6 / 0.22 0.32 1.45  ->  39/40  100 % / 6 of 6 / 0.09 0.09 0.64
  seed 100 (20 vehicles)  ->  20/20  100 % / 5 of 5 / 0.07 0.14 0.58 (naive 2-D: 73.3 / 100 %)
Tried and dropped: weighing each view by its pixel footprint instead of dropping it (S + the far
corner's metres per pixel, the ray's precision as the pseudo-inverse of P (S + E) P): seed 300 MAE
L 1.00 -> 0.89 m, the L = 1 m collapses stayed; with the exact silhouettes it was worse than the
paper's S alone (MAE L 0.31 -> 0.39 m: the prior pulls harder). 1 m per pixel instead of 2: too
few views of receding vehicles (seed 300 MAE L 0.89 m). Restarting a track's estimate when a
vehicle splits off its blob (a new blob inside its predicted box): fixed one car on seed 300 and
lost the near views of two trucks when a vehicle behind them appeared; not kept. Left: the truck
of seed 300 whose track changes vehicle through a blob join (issue 13's identity item).
Held out, once, with max_length_resolution 2 (then the default) (`--video-only --video-vehicles 40 --video-seed 500|600`;
seed 600 rendered for gantry, mast_low, mast_high only; found / light / heavy / MAE W H L m /
naive 2-D light-heavy from the boxes at its oracle threshold):
  500 gantry          40/40  100.0 % / 7 of 7 (was 3 of 7)  / 0.12 0.10 0.84
  500 mast_low        38/40   93.5 % / 5 of 7 / 0.28 0.07 0.96   every view: 93.5 % / 7 of 7 / 0.48 0.15 1.29
  500 mast_high       39/40  100.0 % / 7 of 7 / 0.21 0.11 0.48
  500 side            39/40   96.9 % / 7 of 7 / 0.29 0.09 0.41
  500 wide_distorted  38/40   96.9 % / 6 of 6 / 0.21 0.08 0.38
  600 gantry          40/40  100.0 % / 8 of 8 / 0.10 0.12 0.58   naive 87.5 / 100 %
  600 mast_low        37/40   89.7 % / 7 of 8 / 0.29 0.08 0.88   naive 82.8 / 100 %; every view:
                                                                  89.7 % / 7 of 8 / 0.46 0.10 1.26
  600 mast_high       38/40   93.3 % / 8 of 8 / 0.23 0.13 0.57   naive 100 / 100 %; every view: the same
The rule fixed the gantry and cut MAE L elsewhere, but on the low mast (6 m, pitch 12 deg) it lost
two heavies of seed 500 (an articulated lorry with no view resolved to 2 m per pixel is reported
not fully in view; a truck called light): a hard cut can leave a long vehicle seen by a low camera
no view at all. Next (to develop on tuning seeds of mast_low): keep a vehicle's best-resolved
views when none passes. Tuning seed 100 re-run with it: gantry 100 % / 5 of 5, mast_high 100 % /
5 of 5, side 100 % / 3 of 5 (a truck and a bus called light, a van not in view; every view, last
session: at or near 100 %), so max_length_resolution was left off by default (0: every view; superseded by the per-vehicle factor below, and the side figure corrected there). Still below the bar: light accuracy 89.7-96.9 % on mast_low, side, wide,
mast_high (cars called heavy), found 92-95 % on mast_low and wide_distorted.
Estimator cost (exact silhouettes, every 2nd frame, update() from Python, CPU time, median of 5):
gantry seed 300 23.7 us per vehicle-frame (every view: 47.4 us, same run), mast_high seed 100
47.4 us (47.3 us): the resolution test costs nothing measurable, and dropped views skip the chain.

Issue 13, views by resolution per vehicle (this session; tuning seeds 100-400 only while choosing).
The cut is now per vehicle: a view is used when its length's resolution is at most
max(max_length_resolution, length_resolution_factor x the vehicle's best view). Correction to the
log above: "every view" on side seed 100 is 3 of 5 heavies with today's build too (run here, same
build as the rows below: truck and bus as light), so the fixed cut did not cost side anything;
the older 5 of 5 was an earlier pipeline's. Found / light / heavy / MAE W H L m, same scenes
(--scene-dir), `--video-set max_length_resolution=X length_resolution_factor=Y`:
  scene (tuning)     every view (0, 0)         cut 2 m (2, 0)            cut 2 m + factor 2 (2, 2)  factor 4 alone (0, 4)
  gantry 300 (40)    38/40 8 of 9 0.11 0.16 1.00  8 of 9 0.10 0.12 0.79  38/40 8 of 9 0.10 0.13 0.80  38/40 9 of 9 0.13 0.11 0.76
  gantry 400 (40)    39/40 4 of 6 0.22 0.32 1.45  6 of 6 0.09 0.09 0.64  = the cut (best views < 1 m)  39/40 5 of 6 0.15 0.12 0.95
  side 100 (20)      20/20 3 of 5 0.34 0.17 0.50  3 of 5 0.34 0.17 0.50  20/20 3 of 5 0.34 0.17 0.50  20/20 4 of 5 0.32 0.17 0.50
  gantry 100 (20)    (earlier) 5 of 5             5 of 5 0.07 0.14 0.58  20/20 5 of 5 0.07 0.14 0.52  20/20 5 of 5 0.09 0.13 0.56
  mast_high 100 (20) (earlier) 5 of 5             5 of 5 0.17 0.19 0.54  20/20 5 of 5 0.17 0.19 0.54  20/20 5 of 5 0.18 0.13 0.39
Light vehicles 100 % in every cell. side 100 with factor 10 alone: 3 of 5 (0.36 0.17 0.53); the factor
trades the gantry's far views against the low/oblique cameras' few good ones, 4 measured best of 4
and 10 on side.
(every view and the cut on gantry 300/400: last session's rows above; the relaxed cut equals the
cut wherever a vehicle's best view is finer than 1 m, as under the gantry.) A low camera at low
resolution (tests/test_vehicle_estimator.py: mast_low at 320x180, exact silhouettes): the fixed
2 m cut leaves two articulated lorries no view and calls a truck light; the relaxed cut and the
factor alone call all four right. The fixed cut is in metres per pixel, so at a third of the
resolution it keeps three times fewer views: a pixel constant in disguise. The default is
therefore the factor alone, 4 (max_length_resolution 0): a ratio of one vehicle's own views, the
same at any resolution; it measured better than every view on each tuning scene it was run on.
Not run for lack of time: mast_low and wide_distorted tuning scenes (seed 700 was being rendered).

Held out, once, with these defaults (factor 4 alone), seed 500, 40 vehicles, all five set-ups
(`--video-only --video-vehicles 40 --video-seed 500 --video-setups S`, one set-up per process);
found / light / heavy / MAE W H L m / naive 2-D light / heavy at its oracle threshold (same run) /
last session's cut 2 m and, where measured, every view:
  mast_low        38/40  93.5 % / 6 of 7 / 0.28 0.08 1.05  naive 67.7 / 100 %   cut: 93.5 % / 5 of 7 / 0.28 0.07 0.96; every view: 93.5 % / 7 of 7 / 0.48 0.15 1.29
  gantry          40/40  97.0 % / 7 of 7 / 0.16 0.21 1.00  naive 81.8 / 100 %   cut: 100 % / 7 of 7 / 0.12 0.10 0.84; every view: heavy 3 of 7
  side            39/40 100.0 % / 7 of 7 / 0.19 0.10 0.35  naive 100 / 100 %    cut: 96.9 % / 7 of 7 / 0.29 0.09 0.41
  wide_distorted  38/40 100.0 % / 6 of 6 / 0.18 0.12 0.51  naive 96.9 / 100 %   cut: 96.9 % / 6 of 6 / 0.21 0.08 0.38
  mast_high       39/40  96.9 % / 7 of 7 / 0.21 0.11 0.49  naive 100 / 100 %    cut: 100 % / 7 of 7 / 0.21 0.11 0.48
Wrong: mast_low a truck as light and two cars as heavy, gantry a car with trailer as heavy,
mast_high a car as heavy. Against every view the factor keeps the gantry's heavies (3 -> 7 of 7)
and mast_low's MAE down (L 1.29 -> 1.05 m) but loses mast_low's one truck (7 -> 6 of 7); against
the fixed cut it wins side and wide_distorted's light (96.9 -> 100 %) and a mast_low heavy, loses
a car on gantry and mast_high. Still below the bar: found 95 % on mast_low and wide_distorted,
light 93.5-97 % on mast_low, gantry, mast_high; naive 2-D ties on side and mast_high (100 / 100 %,
an oracle threshold). Seeds 600 (side, wide_distorted) and 900 were not rendered (~10-20 min each
on this machine under load): not run.

Estimator cost with the per-vehicle cut (exact silhouettes, even frames, update() from Python,
CPU time, median of 3, same run; the machine loaded by other jobs): gantry seed 300 (3404
vehicle-frames) every view 47.1 us, cut 2 m 52.0, cut 2 m + factor 2 53.9, factor 4 (default)
47.8 us; mast_high seed 100 (869) 33.8, 44.8, 45.2, 35.4 us. Keeping each used view's ray term
(to drop it when a better view tightens the bound) costs nothing measurable; under 0.1 ms.

Identity through blob joins (tried, not kept). Diagnosis, gantry seed 300: the truck of lane 1
emerges from the distance behind a car already tracked, the two one blob from the truck's first
frame (its image box 20 px tall reaches down onto the car's), so no second track exists and the
"covers the predicted boxes of two tracks" test cannot fire; the car's track takes the pair's
outline for ~60 frames and, when they part, continues with the truck. Tried: a blob covering half
or more of a road-predicted track box with 2x its area (off the image border) is a join: the track
coasts, no estimator update. On 3 small gantry scenes (480x270, 3 vehicles in 2 lanes, 0.2 s gaps,
seeds 0-2, old vs join rule): one better (fewer frames of no single vehicle), one unchanged, one
worse: receding followers (lane 1 under the gantry drives away from it) never part, the coasting
track drifted and took a second truck (L 1.02 m, light). A join rule must tell approaching from
receding pairs and re-acquire after long coasts; left for the next session.

Issue 13, large vehicles never tracked (this session; tuning scenes of seeds 300 and 700 only, 40
vehicles, `--scene-dir`). Diagnosis, gantry seed 300: its 13.5 m bus (receding from under the
gantry) got no track at all: in every frame its blob covered half or more of the predicted boxes of
two or more small tracks (distant vehicles ahead of it, and tracks coasting behind it, which a
"merge" keeps alive), so the blob was a "merge" and went to no track. Change: only tracks whose
predicted box is at least merge_min_share (0.2) of the blob's box count as members of a merge; a
blob whose pixels cover half or more of a smaller track's predicted box is "joined": it continues
its own track, the small track coasts, and its outline goes to a second estimator used only for a
vehicle with no clean view. merge_min_share = 0 is the old tracker. Found / light / heavy / MAE W H
L m / reported (diag of the pipeline on the same rendered scenes):
  scene (tuning)  old tracker                          share 0.2 alone (joined outlines estimated)  kept (share 0.2 + joined)
  gantry 300      38/40 29/29 9/9  0.13 0.11 0.77 41   39/40 29/29 9/10 0.18 0.21 0.87 47           39/40 29/29 10/10 0.12 0.11 0.84 43
  mast_low 300    40/40 30/30 9/10 0.21 0.09 0.96 44   -                                            40/40 30/30 9/10 0.17 0.06 1.12 51
  mast_low 700    40/40 37/37 3/3  0.24 0.08 0.70 45   -                                            40/40 37/37 3/3  0.26 0.08 0.71 47
  wide_dist. 700  40/40 37/37 3/3  0.17 0.09 0.35 43   -                                            40/40 37/37 3/3  0.17 0.09 0.34 44
(gantry 300, old: the bus and a car joined with a truck from its first frame missed; kept: the car
still missed. mast_low 300: old, an articulated lorry "not fully in view" (its frames all merges);
kept, that one right and another lorry called light, its track split in four at joins with cars.)
Tried and dropped: a joined blob's track coasting on its prediction instead of following the blob
(gantry 300: 56 vehicles reported, mast_low 300: a bus called light); following the blob but not
taking its lowest point as a ground point (mast_low 300: 7 of 10 heavies, MAE L 1.29 m). Seed 700
draws few heavies (3 of 40): all right before and after; mast_high and gantry 700 were right with
the old tracker and were not re-run.
Held out, once, with these defaults (`--video-only --video-vehicles 40 --video-seed 500 --video-setups
mast_low gantry side wide_distorted mast_high --scene-dir DIR`; found / light / heavy / MAE W H L m /
naive 2-D light / heavy at its oracle threshold, same run / last session's figures):
  mast_low        39/40  93.8 % of 32 / 6 of 7 / 0.33 0.08 0.95  naive 65.6 / 100 %   was 38/40 93.5 % 6 of 7 0.28 0.08 1.05
  gantry          40/40 100.0 % of 33 / 7 of 7 / 0.16 0.16 0.89  naive 78.8 / 100 %   was 40/40 97.0 % 7 of 7 0.16 0.21 1.00
  side            39/40 100.0 % of 32 / 7 of 7 / 0.17 0.09 0.32  naive 100 / 100 %    was 39/40 100 % 7 of 7 0.19 0.10 0.35
  wide_distorted  38/40 100.0 % of 32 / 6 of 6 / 0.19 0.08 0.41  naive 100 / 100 %    was 38/40 100 % 6 of 6 0.18 0.12 0.51
  mast_high       39/40  96.9 % of 32 / 7 of 7 / 0.23 0.13 0.52  naive 100 / 100 %    was 39/40 96.9 % 7 of 7 0.21 0.11 0.49
Wrong: mast_low a truck as light, a car and a car with trailer as heavy; mast_high a car as heavy.
Reported beyond one per vehicle: 1-11 per set-up (mast_low 11: 5 second tracks, 6 tracks over
several vehicles). Still below the bar: found 95-98 % on four set-ups, light 93.8 % (mast_low) and
96.9 % (mast_high).
Seeds 600 and 900, once each, 20 vehicles per set-up (rendering time; `--video-vehicles 20
--video-seed 600|900`), same columns; no old-tracker run on these scenes:
  600 mast_low        18/20  92.3 % of 13 / 3 of 5 / 0.44 0.21 1.74  naive 61.5 / 100 %
  600 gantry          20/20 100.0 % of 15 / 5 of 5 / 0.23 0.41 1.52  naive 73.3 / 100 %
  600 side            17/20 100.0 % of 12 / 4 of 5 / 0.28 0.16 0.47  naive 100 / 100 %
  600 wide_distorted  19/20 100.0 % of 14 / 5 of 5 / 0.34 0.36 0.98  naive 78.6 / 100 %
  600 mast_high       19/20 100.0 % of 14 / 5 of 5 / 0.23 0.26 1.13  naive 100 / 100 %
  900 mast_low        20/20 100.0 % of 18 / 2 of 2 / 0.21 0.09 0.71  naive 66.7 / 100 %
  900 gantry          20/20 100.0 % of 18 / 2 of 2 / 0.14 0.13 0.45  naive 72.2 / 100 %
  900 side            19/20  94.1 % of 17 / 2 of 2 / 0.23 0.16 0.23  naive 100 / 100 %
  900 wide_distorted  20/20 100.0 % of 18 / 2 of 2 / 0.16 0.09 0.41  naive 83.3 / 100 %
  900 mast_high       20/20 100.0 % of 18 / 2 of 2 / 0.09 0.12 0.35  naive 100 / 100 %
Wrong: 600 mast_low a van as heavy, a truck and a bus as light; 600 side a truck as light; 900 side
a car as heavy. Seed 600 (a quarter heavies) is the hardest draw: mast_low's heavies and found
on mast_low and side are the gaps; the naive 2-D oracle ties on side and mast_high.

Issue 13, front end or estimator (this session; tuning seeds 100, 300, 700 only, 40 vehicles, all
five set-ups, 600 vehicles; scored as Table 2 scores). Start: found 594/600, light 481/484, heavy
105/110, MAE W H L 0.20 0.11 0.65 m, 687 reported. For each of the 14 failures (6 missed, 3 light
and 5 heavy wrong) the estimator was also fed the generator's exact silhouettes (silhouettes.csv,
whole even where a nearer vehicle hides part) of that vehicle: over its passage, the defaults
call all 14 right, and over just the frames of the track that was scored, every one that had
such frames; so the estimator and its decision rule are not what fails, the outlines reaching it
are. By the views of the scored track (IoU with the
vehicle's true box): 7 failures are two or more vehicles in one blob for most of a track with no
clean view (side 300 x2, side 700 x4: cars side by side in lanes 0 and 1; mast_low 100: a bus with
the car ahead of it showing above its roof); 4 a track passing from one vehicle to another where a
blob splits (mast_low 100 car 9, gantry 100 car 38 and the articulated lorry 39 behind it,
gantry 300 car 19: a near car and the far vehicle stacked above it in the image are one blob, the
track follows the car's foot, and when the blob parts the track jumps to the far vehicle's, its
lowest point 30-35 m further down the road, or coasts and takes the wrong one); 3 a fragment of a
heavy vehicle's passage with poor views winning the match (gantry 100 bus: a receding track that
ran into a background ghost near the horizon; wide_distorted 100 articulated lorry: the same,
while its clean views went to the joined estimator, a one-frame track of its own first sliver
coasting inside it; mast_low 300 articulated lorry: 46 views of which 10 carry another vehicle's
pixels, L 2.5 m); 1 a mostly clean track with a minority of such views (gantry 700 van: 23 of 151,
L 8.4 m, heavy). In the last two kinds the least-squares product of the rays is pulled far off by
a few views: gantry 700's truck after the change below, 80 clean views and 14 contaminated ones,
came out L 1.1 m; its clean views alone 6.9 m.
Changes (library): the blob tracker's foot gate (apps/vehicles.hpp, foot_gate 0.5: a blob whose
lowest point lies more than half the track's predicted image height, plus a pixel, from the image
of the track's predicted ground point does not continue it; a ratio of the vehicle's own image
size) and the
estimator's outlier refit ("rays": the answer refitted twice without views whose ray lies more than
outlier_gate = 3 sigma of S from the fit; filters/vehicle_dimensions.hpp). Tuning totals (found /
light / heavy / MAE W H L m / reported; /tmp prototype of the pipeline on the KDE masks of the
same videos, equal to measure_vehicles on mast_low and gantry 100: 40/40 31/31 9/9 and 39/40
30/30 8/9, MAE and reported identical):
  before                         594  481/484  105/110  0.20 0.11 0.65  687
  refit alone                    594  481/484  105/110  0.19 0.11 0.63  687
  foot gate 0.25 alone           598  487/488  105/110  0.20 0.11 0.71  829
  foot gate 0.35 alone           597  485/487  104/110  0.19 0.11 0.61  729
  foot gate 0.5 alone            596  483/486  105/110  0.20 0.11 0.61  710
  foot gate 0.35 + refit         597  485/487  105/110  0.19 0.11 0.60  729
  foot gate 0.5 + refit          596  483/486  107/110  0.19 0.11 0.58  710
  the same + 1 px (kept)         596  483/486  107/110  0.19 0.11 0.58  715
  foot gate 0.75 + refit         594  483/485  105/109  0.19 0.11 0.61  686
(the refit in Python, re-feeding the kept views, with gate 0.5: 596 484/486 108/110 0.19 0.11 0.60.)
Kept: 0.5 + refit, fewer extra tracks than 0.35 at the same number of failures (10) and two more
heavies. The pixel was added after the first held-out run below, for tests/test_vehicle_estimator.py
at 160x90: blobs 2 px tall at the image's top edge made the gate finer than the pixel grid and cut
a car's track in two (a second track, not in view); tuning totals unchanged, 5 more reported. Also
a cost seen in that file's gantry test (480x270, three vehicles receding as one blob that never
parts): with the gate the car's track keeps the union (its lowest point is the car's) and the IoU
match scores the union as the truck, so the car counts as not found there (estimates unchanged);
that test, about the resolution cut, runs with foot_gate 0. Kept anyway: on the tuning scenes the
gate fixed more such identity errors than it made. Per set-up after (foot gate 0.5 + refit, before
the pixel; found / light / heavy / MAE W H L): mast_low 100 40/40 31/31 9/9
0.28 0.12 1.00, gantry 100 39/40 30/30 8/9 0.20 0.26 0.97, side 100 40/40 31/31 9/9, wide 100
40/40 31/31 9/9, mast_high 100 40/40 31/31 9/9; mast_low 300 40/40 30/30 10/10 0.20 0.05 0.82,
gantry 300 39/40 29/29 9/10, side 300 39/40 29/29 10/10, wide 300 40/40 30/30 9/10, mast_high 300
40/40 30/30 10/10; seed 700 (3 heavies each) 40/40 37/37, 40/40 36/37, 39/40 34/36, 40/40 37/37,
40/40 37/37. Fixed: mast_low 100 bus and car 9, wide_distorted 100 and mast_low 300 articulated
lorries, side 700 car 22 found (as not fully in view); new failures: a truck of gantry 300 and one
of wide_distorted 300 called light. Left: the side-by-side pairs of side 300/700 (one blob all along), the stacked
pairs of gantry 100/300 whose joint outline is scored as the far vehicle, the gantry 700 van.
Tried and not kept (same totals): marking a blob joined only when the small track's predicted box
sticks out of the large one's (594 482/484 100/110 0.72); only confirmed tracks as merge or join
members (595 483/486 103/109 0.66); skipping a view whose rectified box repeats the last used one
(a repeated quantisation error is no new evidence; 594 482/484 103/110 0.67); outlines along pixel
edges (each vertex moved to its pixel's outer corner; 594 482/484 104/110 0.66); the KDE's
update_static (594 482/484 105/110 0.67, 690 reported); the refit in Python without the foot gate
(594 482/484 104/110 0.65); reporting a vehicle whose used rays leave a direction undetermined
(1/sqrt(lambda_min(sum P S^-1 P)) > 2 m) as not fully in view: 91/110 heavies (many heavies are
found only from the distance), or taking the joined views' estimate then: 102/110.
Held out, seeds 1100 and 1300 (rendered by the last session, not looked at before this one's
changes were chosen), 40 vehicles, five set-ups: `python benchmarks/vehicles.py --video-only
--video-vehicles 40 --video-seed 1100|1300 --video-setups mast_low gantry side wide_distorted
mast_high --scene-dir DIR`, and the same with `--video-set foot_gate=0.0 outlier_gate=0.0` for
"before". Three runs, all after the choice on the tuning scenes: the final defaults; the first run
(foot gate without the pixel, which was added after it for a unit test, see above); before. Found
/ light / heavy / MAE W H L m / reported / naive 2-D light / heavy at its oracle threshold (same
run as the final):
  1100 mast_low        final 38/40 32/32 5/6 0.26 0.13 0.89 54  first 38/40 32/32 6/6 55  before 38/40 32/32 5/6 0.27 0.13 0.97 52  naive 59.4 / 100 %
  1100 gantry          final 40/40 34/34 5/6 0.15 0.20 1.04 55  first 40/40 34/34 5/6 56  before 40/40 34/34 5/6 0.16 0.23 1.07 52  naive 58.8 / 100 %
  1100 side            final 37/40 30/31 6/6 0.24 0.20 0.61 43  first 37/40 30/31 6/6 43  before 36/40 29/30 6/6 0.25 0.19 0.70 42  naive 100 / 100 %
  1100 wide_distorted  final 39/40 33/34 4/5 0.26 0.20 0.91 52  first 39/40 33/34 4/5 52  before 39/40 33/34 4/5 0.26 0.23 0.99 49  naive 85.3 / 100 %
  1100 mast_high       final 38/40 32/32 5/6 0.23 0.16 0.70 44  first 38/40 32/32 5/6 46  before 38/40 32/32 5/6 0.27 0.21 0.87 41  naive 100 / 100 %
  1300 mast_low        final 40/40 33/33 6/7 0.19 0.07 0.80 51  first the same         before 40/40 31/33 6/7 0.33 0.12 1.34 53  naive 87.9 / 100 %
  1300 gantry          final 40/40 33/33 6/7 0.15 0.19 0.88 47  first the same         before 40/40 33/33 5/7 0.16 0.26 1.02 46  naive 81.8 / 85.7 %
  1300 side            final 40/40 33/33 7/7 0.18 0.07 0.27 46  first 40/40 33/33 7/7 45  before 40/40 33/33 7/7 0.18 0.07 0.25 45  naive 100 / 100 %
  1300 wide_distorted  final 40/40 33/33 6/7 0.17 0.18 0.54 45  first the same         before 40/40 32/33 6/7 0.21 0.20 0.60 49  naive 93.9 / 100 %
  1300 mast_high       final 40/40 33/33 6/7 0.14 0.11 0.52 42  first the same         before 40/40 33/33 6/7 0.14 0.11 0.51 43  naive 100 / 100 %
Totals, final: found 392/400 (98.0 %), light 326/328 (99.4 %), heavy 56/64 (87.5 %), 479
reported; first: 392/400, 326/328, 57/64, 482; before: 391/400, 322/327 (98.5 %), 55/64 (85.9 %),
472. Wrong, final: trucks called light on every set-up but side (6), a bus (gantry 1300) and an
articulated lorry (mast_low 1100) called light, a van and a car called heavy (wide_distorted,
side 1100), a car not fully in view (side 1100; score() counts a light vehicle with no estimate
as light, so it is not in the 2 light errors). The bar is met for found (98.0 %) and light
(99.4 %) over the two seeds but not per set-up (found 92-95 % on side, mast_low and mast_high
1100) and not for heavy vehicles (87.5 % against 99 %): heavies called light are what is left,
as on the tuning scenes (the diagnosis above: outlines of two vehicles, fragments). vtrack beats
the naive 2-D oracle on mast_low, gantry and wide_distorted light vehicles; the oracle (its
threshold chosen on the very data) ties or wins on side and mast_high and on heavies.
Estimator cost with the refit (exact silhouettes of even frames, update() from Python, CPU time,
median of 3, machine shared; /tmp script): gantry 300, 3404 vehicle-frames: update() 19.3 us per
vehicle-frame with outlier_gate 0 and 3, estimates() (where the refit runs, once per vehicle)
0.1 us per vehicle-frame more; mast_high 100, 1739: 21.8 / 25.0 us (gate 0 / 3; the refit is not
in update(), so that difference is the machine's), estimates() 0.1 us. Under the 0.1 ms bar.

Issue 13, outlines holding a vehicle found later (session vehicles9; tuning seeds 100, 300, 700 and
a new heavy-rich tuning seed 1500: `--video-seed 1500 --video-class-mix car=0.40 van=0.08
motorbike=0.04 car_trailer=0.04 truck=0.20 articulated=0.12 bus=0.12`, 55 heavies in 200 vehicles;
diagnosed on a Python copy of the pipeline over cached KDE masks, equal to measure_vehicles on every
tuning scene run with both). Diagnosis: the three heavies called light on seeds 100/300 (gantry 100
articulated lorry 39, gantry 300 truck 20, wide_distorted 300 truck 20) were one case (the change
below also fixed three of seed 1500's five, not traced one by one): the heavy emerges from the
distance behind a car of its lane, above it in the image, the two one blob for 50-70 frames, tracked
as one vehicle by the car's foot. The heavy has no track yet, so nothing marks the blob as two
vehicles' (no merge, no join): the union's outline went to the car's estimator and its box, mostly
the heavy's, to the car's rows. The IoU match then scored the car's track as the heavy (car
"missed", heavy "called light" with the car's dimensions) while the heavy's own track, started where
the blob parted, was right but had fewer frames used (gantry 100: 17 used, 67 union rows, against
14). Change (apps/vehicles.hpp, hidden_horizon 1.0): the views are kept to the end of the video; a
view is hidden when another confirmed track, with no blob of its own in that frame and within one
length of its own passage of it, has its road-predicted box (from its first or last view) inside the
image and half or more inside the view's blob box; hidden views go to the fallback estimator and
have no track row (as a merge's). `--video-set hidden_horizon=0.0` is the pipeline before. Found /
light / heavy / MAE W H L m / reported (prototype figures; measure_vehicles with the change:
identical per set-up on all four seeds):
  tuning scenes          before (0)                              after (1.0, kept)
  100+300+700 (600)      596 483/486 107/110 0.19 0.11 0.58 715   597 486/488 109/109 0.18 0.09 0.57 715
  1500 heavy-rich (200)  199 144/144  50/55  0.23 0.14 0.76 251   199 144/144  53/55  0.21 0.13 0.67 251
  horizon 2.0 (all 800)  796 630/632 161/164 0.18 0.10 0.59 966   (1.0: 796 630/632 162/164)
  horizon 4.0 (all 800)  796 630/632 160/164 0.18 0.10 0.59 966
  contiguous, 1.0 (800)  796 630/632 162/164 0.19 0.10 0.59 966
  contiguous, no cap     796 630/632 161/164 0.18 0.10 0.59 966
Fixed: the gantry 100/300 and wide_distorted 300 heavies and their cars (found now), the gantry 700
van (called heavy before, not traced), seed 1500's mast_low articulated lorry and both
wide_distorted trucks. New: side 100's truck 22 (seed 100), in a tangle of side-by-side vehicles
with no clean track, was matched through a 7-frame fragment; those rows are now hidden and no track
matches it (missed; found 39/40 there). Longer horizons reach further back and mark views that were
the track's own (horizon 2: wide_distorted 300's bus light, a mast_low 1500 truck). (Contiguous:
before and after the other track's passage only the unbroken run of views next to it that it lies
in.) Tried and dropped: hidden only when the other vehicle's box also sticks out of the track's own
box extrapolated from its first view after the split, by half its area (to spare a clean outline
with a vehicle wholly behind it): 598/600 486/488 108/110 (a track that ends at the split has no
view after it: wide_distorted 300's truck light again; mast_high 700's truck light); stitching a
track's fragments (one continues another when each one's road prediction overlaps the other's
nearest blobs; the vehicles7 prototype) on top: 794/800 628/630 160/164 over the four seeds (a
mast_low 300 bus and a second gantry 1500 truck light, two more missed); predicting the other track
from its first/last view not joined with another vehicle (mast_low 1500's truck track starts on such
a view): 796/800 630/632 161/164 (a mast_low 100 truck light, the mast_low 1500 truck still light);
hidden views kept in the rows (estimator only): 596/600 484/486 108/110 (the union's rows still make
the car's track the heavy's match). Left on the tuning scenes: the side-by-side pairs of side
300/700 (one blob all along; 2 cars "not fully in view", a van and a car heavy, 2 missed), side
100's truck (missed), mast_low 1500's truck 5 (car 4's track, 68 of whose rows match the truck's
box, still wins the truck's match; longer horizons do not fix it) and gantry 1500's truck 28 (its
passage split in two tracks, the first's outlines W 0.42 m, with more frames used; horizon 2 fixes
it and breaks two others).
Held out, once, with hidden_horizon 1.0 (after the choice above; `--video-only --video-vehicles 40
--video-seed S --video-setups mast_low gantry side wide_distorted mast_high --scene-dir DIR`). Seeds
1100/1300 were the last session's held-out seeds: their figures had been seen, not their scenes
traced. Seed 1900 is new (rendered for this run, the default class mix, never looked at before), run
also with `--video-set hidden_horizon=0.0` (before). Found / light / heavy / MAE W H L m, per set-up
mast_low, gantry, side, wide_distorted, mast_high:
  1100  38/40 32/32 5/6 0.25 0.12 0.87 | 40/40 34/34 6/6 0.12 0.12 0.88 | 37/40 30/31 6/6 0.23 0.17 0.60
        | 39/40 33/34 4/5 0.25 0.16 0.87 | 38/40 32/32 5/6 0.24 0.16 0.71
  1300  40/40 33/33 6/7 0.19 0.08 0.84 | 40/40 33/33 5/7 0.15 0.19 0.95 | 40/40 33/33 7/7 0.18 0.07 0.28
        | 40/40 33/33 6/7 0.15 0.15 0.51 | 40/40 33/33 7/7 0.12 0.10 0.36
  1900  38/40 30/30 8/8 0.21 0.07 1.02 | 40/40 32/32 8/8 0.16 0.15 1.08 | 39/40 31/31 7/8 0.25 0.12 0.62
        | 40/40 32/32 8/8 0.22 0.13 0.71 | 39/40 31/31 8/8 0.18 0.13 0.60
  1900, before (hidden_horizon 0): 38/40 30/30 7/8 0.27 0.08 1.09 | 40/40 32/32 8/8 0.18 0.20 1.21
        | 39/40 31/31 7/8 0.24 0.12 0.59 | 40/40 32/32 8/8 0.23 0.14 0.71 | 39/40 31/31 8/8 0.17 0.11 0.53
Totals: 1100+1300 found 392/400 (98.0 %), light 326/328 (99.4 %), heavy 57/64 (89.1 %; the last
session's final defaults: 392/400, 326/328, 56/64: gantry 1100 and mast_high 1300 gained a heavy,
gantry 1300 lost one, a truck); 1900 found 196/200 (98.0 %), light 156/156, heavy 39/40 (97.5 %;
before 38/40). Wrong: 1100 an articulated lorry (mast_low) and trucks (wide_distorted, mast_high)
light, a car and a van heavy (side, wide_distorted), a car not fully in view (side); 1300 trucks
light (mast_low, gantry, wide_distorted) and a bus light (gantry); 1900 a truck light and a car not
fully in view (side). Still below the bar for heavy vehicles (89.1 % and 97.5 % against 99 %);
found and light at the bar over the seeds, not on every set-up. Pipeline time per frame: the same
with and without the check (28.5-30.6 ms on 1900, the machine shared); the views kept to the end
of the video cost memory (not measured: every blob's outline, 8 bytes per point, until the end).

Issue 13, the memory of the held views (session vehicles10). The views (outlines) are no longer
kept to the end of the video: a track's are finalised once every passage that could hide in them
is known (apps/vehicles.cpp, HeldViews). The bound first tried, the longest passage seen so far
times hidden_horizon, is not one: on a gantry stream (tests/test_vehicle_estimator.py's, 250
vehicles at a sixth of the resolution) a 481-frame track came after passages of at most 107
frames and reached back into views already finalised (rows differed from holding them all; 4 x
the longest so far failed on the same stream). Passages have no bound a video proves (a vehicle
stops, a ghost stays), so one is chosen: only passages of at most hidden_max_passage = 120 s hide
(longer ones are stopped vehicles or ghosts, whose constant-velocity road line says nothing of
where they were), and views are finalised once every running track of at most that span and every
track yet to start is provably too far to reach them. Exact: the answer equals holding every view
to the end under the same rule (hold_views=true; the test asserts it on the stream), and the rule
equals the previous one wherever no passage is longer than 120 s. Byte-identical vehicles.csv and
tracks to main's build (`vtrack vehicles VIDEO --camera camera.json --out v.csv --tracks t.txt`)
on gantry 300 (44 lines, 4116 rows), mast_low 1500 (55, 3143) and side 700 (45, 2910), 40
vehicles each, and on a long scene: gantry at 480x270, 300 vehicles, seed 4242, 8747 frames (350
s at 25 frames/s; render: make_road_scene(dataclasses.replace(CAMERA_SETUPS["gantry"], focal=450,
image_width=480, image_height=270), n_vehicles=300, seed=4242)): 378 vehicles, 30810 rows,
identical. Peak RSS (`/usr/bin/time -f %M vtrack vehicles ...`, same run): main 107.7 MB, streaming
97.3 MB, 67 s each. At 480x270 an outline is small (CHAIN_APPROX_SIMPLE keeps the corners), so
the views held to the end cost ~10 MB over the 8747 frames. Views held at once (`vtrack._core.
_measure_vehicles(...)[2]`, counts of the same scene): streaming at most 15898 of the 33312 views,
hold_views=true 33115 (the unconfirmed flickers go as they end). The bound is (1 + hidden_horizon)
x 120 s = 240 s of views, most of this 350 s scene; on an hour of video it is 7 % of the views
(~18 MB at 960x540 and ~3 vehicles in view), and it does not grow with the video. Pipeline time:
the same (67.1 s main, 67.7 s streaming on the long scene; 19.4 / 19.5 s on gantry 300).

Issue 13, heavies held out (session vehicles10). Seeds 1100 and 1300 are tuning seeds from now on
(their failures were traced this session); the tuning seeds are 100, 300, 700, 1100, 1300, 1500.
New held-out seeds 2100 and 2300 (default class mix, 40 vehicles, five set-ups, never rendered
before) were run once before any change: `python benchmarks/vehicles.py --seed S --vehicles 40
--noise 1 --video-vehicles 40 --video-seed S --video-setups mast_low gantry side wide_distorted
mast_high` (Table 1 from observations on the same scenes, with the naive 2-D baseline; Table 2
from video, with the naive 2-D baseline on the pipeline's boxes). Found / light / heavy / MAE W H L
m / naive 2-D from video light / heavy at its oracle threshold:
  2100 mast_low        39/40 33/33 6/6 0.19 0.09 0.70   naive 66.7 / 100 %
  2100 gantry          40/40 34/34 5/6 0.10 0.11 0.78   naive 79.4 / 100 %   (a bus light)
  2100 side            39/40 33/33 6/6 0.18 0.08 0.28   naive 100 / 100 %
  2100 wide_distorted  40/40 34/34 6/6 0.15 0.10 0.47   naive 84.8 / 100 %   (a car not fully in view)
  2100 mast_high       40/40 34/34 6/6 0.12 0.08 0.32   naive 100 / 100 %
  2300 mast_low        40/40 36/36 3/4 0.18 0.08 0.80   naive 75.0 / 100 %   (a truck light)
  2300 gantry          40/40 36/36 4/4 0.10 0.11 0.58   naive 88.9 / 100 %
  2300 side            40/40 35/36 3/4 0.22 0.09 0.34   naive 100 / 100 %    (a car with trailer heavy, a truck
                                                                              light, 2 cars not fully in view)
  2300 wide_distorted  40/40 35/36 4/4 0.17 0.10 0.47   naive 97.2 / 100 %   (a car with trailer heavy)
  2300 mast_high       40/40 36/36 4/4 0.11 0.08 0.35   naive 100 / 100 %
Totals: found 398/400 (99.5 %), light 346/348 (99.4 %), heavy 47/50 (94.0 %). From observations
(exact outlines + 1 px noise, same scenes): the default rays 100 / 100 % on both seeds, the paper's
ray 100 / 100 %, the naive 2-D oracle 39.4 / 100 % (2100) and 40.0 / 100 % (2300).
Diagnosis (tuning seeds 1100/1300; a copy of last session's per-vehicle script: the matched track,
every track voting for the vehicle, its runs of frames): of the 7 heavies called light, 4 are one
case -- the volume fails while the height holds. 1100 truck 23 (2.43 x 2.94 x 9.57 m) on
wide_distorted and mast_high (partly hidden by a nearer vehicle in a third and a quarter of its
frames; tracks of 52 and 30 views) came out 1.94 x 3.09 x 7.32 and 1.95 x 3.28 x 6.84 m (44 and 44 m^3, light by 1 m^3); 1300
truck 18 (2.53 x 3.90 x 10.67 m) on mast_low and gantry: the matched track starts on the union of
the truck and another vehicle (29-31 frames matching no vehicle), and the truck's last 31-36
frames go to a second track (heavy, fewer frames used): L 3.38 and 2.74 m, H 4.18 and 4.47 m.
The other 3 are not the estimator's: 1100 mast_low articulated lorry 21 split over four tracks (the
three on it heavy; the one scored, mostly over other vehicles, W 0.65 m), 1300 gantry bus 40 (two
tracks mostly over other vehicles: H 0.96 m), 1300 wide_distorted truck 6 (the track follows the
truck, then car 17: a car's answer). Change (filters/vehicle_dimensions.hpp, heavy_height 3.0 m):
the "volume" rule also calls a vehicle heavy when H >= 3.0 m, about the rigid trucks' height (the
tallest light vehicles ~2.8-2.9 m; the same sources as heavy_volume), a model-level rule, not a fit:
H is the dimension a partial outline keeps. Offline over every tuning scene's matched estimates
(light/heavy is applied to the estimate's W, H, L only, so it is exact to re-decide them; /tmp
script), found / light / heavy:
  heavy_height       0 (before)         2.75          2.8           2.85          2.9           3.0 (kept)
  100+300+700        597 486/488 109/109  484/488 109  485/488 109   485/488 109   486/488 109   486/488 109
  1100+1300          392 326/328 57/64    323/328 61   325/328 61    326/328 61    326/328 61    326/328 61
  1500 (heavy-rich)  199 144/144 53/55    144/144 54   144/144 54    144/144 54    144/144 54    144/144 54
(2.85: a side 700 van at H 2.87 m heavy; 2.9 and 3.0 alike on tuning and, re-decided offline, on
held-out 2100 / 2300; 3.0 kept for its margin: the vans' estimated heights over all eight seeds
reach 2.86 m at their 99th percentile, and real high-roof vans ~2.9 m.) Fixed: the four trucks above and 1500's gantry truck 28 (W 0.42 H 5.21 L 12.29
m, the split passage of vehicles9's log). Left on the tuning seeds: the three tracking failures
above, 1500 mast_low truck 5 (a car's track wins its match: 1.80 x 1.66 x 3.95 m), and the light
vehicles called heavy on side 700 (a van and a car, one blob with a neighbour all along) and 1100 (a
car on side, a van on wide_distorted: 3.55 and 3.75 m wide, two vehicles' outlines).
Held out, once, after the choice (the same scenes: each seed's five set-ups re-rendered and run
through measure_vehicles again; 2300 by the new build itself, 2100 re-decided from its W, H, L,
which is exact -- the rule reads nothing else, and the volume re-computed from W, H, L agreed with
the pipeline's decision on all 1224 tuning estimates): found / light / heavy,
  2100  before 198/200 168/168 29/30   after 198/200 168/168 30/30   (gantry's bus: H 4.62, L 1.57 m)
  2300  before 200/200 178/180 18/20   after 200/200 178/180 20/20   (mast_low's truck: H 3.89, L 3.24 m;
                                                                     side's truck: H 4.10, W 1.17 m)
  both  found 398/400 (99.5 %), light 346/348 (99.4 %), heavy 47/50 (94.0 %) -> 50/50 (100 %)
No light vehicle changed (the two wrong, cars with trailers on side and wide_distorted 2300, were
heavy by volume before: 3.18 x 2.62 x 6.71 and 3.16 x 2.91 x 5.86 m, W off by 1.2-1.5 m: two
vehicles' outlines). Against the naive 2-D baseline in the same runs (above): it ties at 100 / 100 %
on side and mast_high (its threshold chosen on the very data), and trails on mast_low, gantry and
wide_distorted lights (66.7-97.2 %). Tuning seeds, all six (1200 vehicles): found 1188, light
956/960, heavy 219/228 (96.1 %) -> 224/228 (98.2 %). Still below the bar on the tuning seeds
(heavy 98.2 % < 99 %: the tracking failures listed above) and in the per-set-up figures (found
39/40 on two 2100 set-ups); 50 held-out heavies are too few to claim 99 % (one miss is 2 %).
heavy_height then 2.9 -> 3.0 m (the same answers on all eight seeds re-decided offline; the vans'
estimated heights reach 2.86 m at their 99th percentile). Seed 1900 (held out last session, scored
only), re-run from video with that build (the matching above, per vehicle): found 196/200, light
155/155, heavy 40/40 (39/40 without heavy_height: a side truck at 2.07 x 3.30 x 6.61 m).

New camera set-ups, never used before (held out; HELD_OUT_SETUPS below, `--video-only
--video-vehicles 40 --video-seed 2500 --video-setups pole_hd far_side_right`): "pole_hd" CameraSetup(height=7.0, pitch=14.0, yaw=20.0,
lateral=-4.0, focal=1200.0, image_width=1280, image_height=720) found 39/40, light 31/31, heavy
8/8, MAE W H L 0.19 0.07 0.87 m, naive 2-D 80.6 / 100 %; "far_side_right" CameraSetup(height=11.0,
pitch=18.0, yaw=-24.0, lateral=20.0) (a camera beyond the road's right edge looking across all
four lanes) found 37/40 (92.5 %), light 28/28, heavy 9/9, MAE 0.26 0.18 0.78 m, naive 92.9 / 100 %.
The three not found are cars in the far lanes, ~25 x 20 px, each abreast of a vehicle in the
adjacent lane, which a camera across the road sees overlapping it: car 31 beside truck 30 for its
whole passage (their lanes at 29.03 and 29.06 m/s), cars 20 and 24 beside others for most of
theirs. One blob, one track (the blob tracker's limitation, src/apps/vehicles.hpp): the tracks'
best IoU with them 0.24-0.39, or matched in 3 frames. Below the found bar (98 %): left open.

The same two set-ups on two more seeds, never tuned on (`... --video-seed S --video-setups pole_hd
far_side_right`, S = 2700, 2900; found / light / heavy): pole_hd 36/40 28/28 7/8 and 40/40 37/37
3/3; far_side_right 39/40 29/29 10/10 and 38/40 35/35 3/3. Over seeds 2500-2900: pole_hd 115/120
(95.8 %), far_side_right 114/120 (95.0 %), light 188/188, heavy 40/41. pole_hd 2700's misses: a
truck and a car of the slow lane overtaken by the fast lane's vehicles for most of their passage
(one blob with them), a motorbike beside a car, a truck matched in 8 frames. What the missed
vehicles share: their ground-truth box touches another vehicle's (within 2 px) in a median 99 % of
their frames (7 missed on the new set-ups, seeds 2700 and 2900) and 94 % (12 missed on the tuning
seeds), against 31 % and 29 % for the vehicles found (153 and 1188): one blob with a neighbour for
nearly their whole passage. The tuning seeds
(100-1500) re-run with the same build: found 1188/1200, light 953/960 (99.3 %), heavy 224/228
(98.2 %), 1445 reported.

Tried and not kept: cutting a blob in two across lanes. A cuboid's lower outline (each column's
lowest pixel, on the road) lies within its width across the road, so a gap across the road of
>= 0.8 m between two runs of columns, each within 3 m, was read as two lanes' vehicles (parts >= 4
x min_area, blobs off the image's border, a merge of tracked vehicles left whole; the parts tracked
as blobs, their outlines to the joined estimator). Tuning seeds: found 1188 -> 1192, light 953/960
-> 956/963, heavy 224/228 -> 223/229, 1445 -> 1449 reported (4 vehicles right that were wrong, 4
wrong that were right). Set-ups 2500-2900: found 229/240 both. Without the border condition a
bus cut by the image's edge was split (its lowest pixels beside the cut lie on its sides) and 26
more vehicles were reported. It did not find the cars it was for: the near vehicle's part holds the
far vehicle's body above it (the binary mask is the same union for any roof height of the near
vehicle within the taller far one's image), so its box matched at IoU 0.47. Telling them apart
needs appearance, not the silhouette the paper's method observes. A first try at it, on branch
lane-split-colour (not on main): the near part's pixels above its lowest quarter whose colour is
twice as likely under the far part's colour histogram (8^3 BGR bins) as under the near part's lowest
quarter go back to the far part, and parts are never merges. far_side_right 2500's car 31 is then
found, with its own box. Tuning seeds: found 1188 -> 1193, light 953/960 -> 962/964 (99.8 %), heavy
224/228 -> 223/229, reported 1445 -> 1496. New set-ups 2500-2900: found 229 -> 233/240 (97.1 %),
light 190/191, heavy 40/42, reported 265 -> 290. Not merged: 51 more vehicles reported and 2 more
heavies wrong; it needs those fixed, and tests. Nor do the blob tracker's
parameters help (set-ups 2500 and 2700, found of 160; this benchmark with `--video-set NAME=VALUE`):
defaults 151, min_overlap 0.1 151, merge_min_share 0.1 150, 0.3 152 (13 more
reported, a heavy more wrong), foot_gate 0.8 151.

The lane cut with the colour step, made precise and kept (session 14). Two changes to the branch
above. (1) lane_split_hold: a blob of at most one tracked vehicle is taken in its parts only after
it has been cut in every frame for that long (a blob of two tracked vehicles at once). Gantry 100's
bus was lost to a far clump of a bus and four cars cut for a frame or two at a time (splits in
runs of 1-9 frames); an abreast pair is cut in every frame. (2) A blob cut but tracked whole has
its outline go to the second estimator, as the parts' do. And, separately, min_travel: a track
whose ground points never move 1 m along the road is a ghost of the background (gantry 100: three
static boxes of 45-57 frames where a purple truck had stood; 0.5, 1 and 2 m removed the same three
and nothing else there). Tuning seeds (100-1500 x 5 set-ups, 1200 vehicles), found / light /
heavy / reported, per-scene runs of measure_vehicles with this file's matching:
  before (main at 8fe6119)                       1188  953/960  224/228  1445
  cut + colour, parts at once (the branch)       1193  962/964  223/229  1496
  held 3 frames (0.12 s at 25 fps)               1194  963/965  222/229  1488
  held 6 frames (0.25 s)                         1194  962/965  225/229  1483   <- chosen
  min_travel 1 m alone                           1189  953/960  225/229  1378
  held 0.25 s, cut-whole joined, min_travel 1 m  1195  962/965  226/230  1417   (the defaults)
Held out after the choice (the new set-ups' failures were examined in sessions 12-13, but nothing
was tuned on them): set-ups pole_hd and far_side_right, seeds 2500-2900 (240 vehicles):
  before                                         229   188/188  40/41    265
  min_travel alone                               229   188/188  40/41    251
  the defaults                                   232   188/191  40/41    269
Found 95.4 -> 96.7 %, still short of 98 %. Vehicles right (light + heavy) 228 either way: of the
three light vehicles now wrong, two are found only with the cut (far_side_right 2500 car 31 and
2900 car 18, estimated 1.8 x 4.0 x 7.0 and 2.3 x 3.4 x 7.6 m: the near part keeps some of the far
vehicle above it, and heavy_height calls it heavy), and one (2900 car 32, 2.0 x 2.9 x 1.2 -> 1.7
x 3.1 x 1.5 m) was a poor estimate on either side of 3.0 m. With the parts taken at once car 18
came out 1.7 x 1.6 x 4.2 m, light, but tuning lost heavies that way. Seed 1900 of the tuned
set-ups (held out): mast_low, side, wide_distorted with the cut off / on: found 117 / 117, light
92/93 / 93/93, heavy 24/24 / 23/24 (wide_distorted's articulated lorry 31, a two-vehicle outline
either way: 3.6 x 4.8 x 4.3 m heavy, now 2.3 x 2.5 x 2.7 m light); gantry and mast_high 80/80
found, 64/64 light, 16/16 heavy with it. This benchmark, seed 2900, the new set-ups (Table 2,
`--video-set lane_split_gap=0` for off): far_side_right found 38 -> 39/40, light 35/35 -> 34/36,
MAE W H L 0.19 0.16 0.45 -> 0.17 0.20 0.52 m, 15.5 -> 15.8 ms per frame; pole_hd unchanged, 28.2
-> 28.5 ms per frame; the naive 2-D baseline 77.8-80.0 % light with its oracle threshold.
Tried and not kept: heavy_height off for the second estimator (outlines of more than one vehicle,
the parts of a cut): tuning heavy 226/230 -> 225/230, set-ups 2500-2900 heavy 40/41 -> 39/41,
light unchanged on both (the cars called heavy above are not decided there).

Session 15. A third held-out camera set-up, roadside_4x3 (HELD_OUT_SETUPS: a low 4:3 camera 4.5 m
up beside the road, 10 degrees down, 800 x 600, focal 700 px), and fresh seeds never run before
for all three held-out set-ups, scored once with the defaults (`--video-only --video-vehicles 40
--video-seed S --video-setups pole_hd far_side_right roadside_4x3`, S = 3100, 3300; found / light /
heavy / reported, MAE W H L in m):
  3100 pole_hd         38/40  28/28  10/10  45   0.26 0.11 1.13
  3100 far_side_right  39/40  28/28  11/11  46   0.23 0.21 1.02   (a car found but never fully in view)
  3100 roadside_4x3    38/40  28/28  10/10  51   0.26 0.07 1.40
  3300 pole_hd         39/40  31/31   8/8   42   0.16 0.05 0.61
  3300 far_side_right  40/40  32/32   7/8   47   0.17 0.16 0.78
  3300 roadside_4x3    39/40  31/31   8/8   43   0.15 0.04 0.81
  total               233/240 (97.1 %)  178/178  54/55 (98.2 %)  274
The naive 2-D baseline in the same runs: 18.5-100 % of lights right with its oracle threshold
(18.5 and 29.0 % on roadside_4x3, whose low view stretches a far vehicle's road projection). The
heavy called light, far_side_right 3300 truck 33 (2.54 x 3.05 x 8.64 m), is estimated 2.48 x 0.70 x
8.37 m: a grey truck on a grey road. Its sides differ from the road by ~9 levels in blue and ~1 in
green and red ((82, 90, 96) against (91, 91, 94) BGR), within the KDE background's spread, so only
its light top face is foreground; the same holds for mast_high 1300's grey bus 40 (a mask with
holes). Background subtraction alone cannot see a vehicle the colour of the road; edges or a
detector would.

Tried and not kept (branch stacked-cut, not on main): the lane cut for a near vehicle inside a far
one's columns. far_side_right 2500's car 20 (fully visible in 153 frames) sits before an articulated
lorry whose lower outline shows on both sides of it, so the cut above, which wants two runs of
columns, never fires. The try: (1) three runs, the near lane's (the lane nearer the camera) in the
middle, the far part then split into its connected pieces (two far vehicles, one either side of a
near one, in a clump of traffic) or kept whole (one far vehicle whose body shows above the near
one); (2) a twentieth of the columns at either end left out of the rule (a blob's outermost
columns may end on a vertical edge above the road: 5 m off in far_side_right 2500, up to 13 m in
pole_hd 2700's bus); (3) the widest gap whose sides are each one vehicle, not the widest gap (a far
bus's own outline shows a 1.04 m gap where the car before it hides its corner). Per-scene runs with
this file's matching, found / light / heavy / reported:
  tuning seeds (1200)               main 1195  962/965  226/230  1417   the try 1194  961/964  224/230  1459
  set-ups 2500-2900 (240)           main  232  188/191   40/41    269   the try  234  189/191   41/43    293
  fresh seeds 3100/3300 above (240) main  233  176/178   54/55    274   the try  235  178/178   53/57    301
It finds the vehicles it was for (far_side_right 2500 car 20; pole_hd 2700 trucks 14 and 23;
fresh: three more, one other lost) but loses heavies: more blobs are cut, among them single grey vehicles whose mask has
holes (mast_high 1300's bus 40, cut in every frame where main cut it in a few, so the hold let it
through), and a heavy seen only in cut parts gets its height from outlines short of its body
(fresh: a bus at 1.6 x 1.4 x 9.9 m, two trucks at 1.3-2.5 m high, all called light). With the
convex hull of the far pieces as its outline instead of splitting them the figures were the same
on the tuning seeds (224/229 heavy). Kept out: 3 more heavies wrong and 27 more reported on the
fresh seeds for 2 more found. A single vehicle with holes in its mask must be told from two first,
and the binary mask alone cannot (the hole's pixels are the vehicle's, coloured like the road).

Kept: the three runs only where main's two-run rule (the widest gap, all columns) finds no cut; the
two-run cuts are then exactly main's (src/apps/vehicles.cpp, lane_cut()). Scored after the choice,
per-scene runs as above, found / light / heavy / reported:
  tuning seeds (1200)               1195  962/965  225/230  1419   (main 1195 962/965 226/230 1417)
  set-ups 2500-2900 (240)            234  191/192   41/42    278   (main  232 188/191  40/41   269)
  fresh seeds 3100/3300 (240)        233  176/178   54/55    278   (main  233 176/178  54/55   274)
Found on 2500-2900: far_side_right 2500 car 20 (light) and pole_hd 2700 truck 23 (heavy); and
far_side_right 2900's cars 18 and 32, called heavy before, are light now. The tuning heavy lost, mast_low 1500 truck 28 (2.44 x 3.38 x
9.48 m), was a poor estimate before (1.22 x 4.06 x 9.94 m, heavy) and is 1.16 x 1.03 x 8.09 m now:
no cut touches its blob; a cut elsewhere in that scene changed which outlines its track got. The
fresh seeds get the same answers (4 more reports).

Session 16. "Found of those seen apart" (Table 2, seen_apart()): of the misses, which vehicles were
ever clear of the others in the image. On the fresh seeds 3100/3300 above, 12 of the 240 never
are (a truck at most 44 % visible behind another for its whole passage, a car beside a van all
along); found among the rest: 225/228. The three the pipeline could have found are a car
beside a bus on pole_hd and roadside_4x3 (seed 3300, three pixels apart at first: the closing,
7 px at f = 1200, joins them; their lower outlines then differ by 0.65 m across the road, the
closing's fill at the junction eating the 1.36 m between the lanes) and far_side_right 3100 car 1
(its blob's last column ends on a vertical edge, 9.9 m off across the road, so the widest-gap
rule sees one blob wider than a vehicle).

Tried and not kept (per-scene runs with this file's matching, found / light / heavy / reported):
  lane_split_gap 0.5 or 0.6 (for the junction): no vehicle more on 3100's pole_hd, far_side_right
    and roadside_4x3 (115/120, as main), 149 reports against 142; stopped there.
  blob_closing off (1), with the stitching below, against the stitching alone:
    tuning seeds (1200)           1195 965/967 225/228 1388   (1195 962/965 225/230 1390)
    set-ups 2500-2900 (240)        233 191/192  39/41   261   ( 234 190/192  41/42   274)
    fresh seeds 3100/3300 (240)    235 180/180  54/55   270   ( 232 176/178  54/55   269)
    It finds the car beside the bus (3300) and far_side_right 3100's car 1, but wide_distorted 100
    (f = 560) loses a bus and a truck (their pieces no longer joined), and two more heavies of
    2500-2900 are called light. A lead, not a default: the closing joins a heavy's pieces and far
    vehicles alike; a closing that tells them apart (by the pieces' lower outlines, say) is next.
  dropping the end columns that jump by more than the gap across the road from the next one in
    (up to a twentieth): tuning 1159 -> 1155 found of 1160 scored, light unchanged; 2500-2900
    235 found (+1) but a bus called light; fresh 3100/3300 235 found (+2: car 1 and a truck) but
    two heavies called light (3300's truck 33 on pole_hd and roadside_4x3, cut apart). Not kept.

Kept: track stitching (header: stitch_gap). Most extra reports are a second track of a vehicle
found (Table 3): a merge that lasts longer than lost_memory ends the track, and a new one starts
when the vehicle shows again. Per-scene runs, main -> stitched:
  tuning seeds (1200)            1195 962/965 225/230 1419  ->  1195 962/965 225/230 1390
  set-ups 2500-2900 (240)         234 191/192  41/42   278  ->   234 190/192  41/42   274
  fresh seeds 3100/3300 (240)     233 176/178  54/55   274  ->   232 176/178  54/55   269
The light lost (far_side_right 2900 car 32, beside another car in its blob for most of its
passage) was a poor estimate either way: 2.04 x 2.90 x 3.11 m on main (light), 1.79 x 3.03 x 1.99 m
stitched with its first frames (heavy). The vehicle lost (pole_hd 3100 car 3, in one blob with car 4
for all but one frame) was found on main by that one frame's box; stitched, its track's votes go to
car 4. With a mean overlap of 0.3 instead of 0.5, 65 fewer reports on 18 tuning scenes against 20,
but 2 vehicles lost there and 2 heavies called light (gantry 1300, roadside_4x3 3300).

Fresh seeds never run before, scored once after the choices above (`--video-only --video-vehicles
40 --video-seed S --video-setups pole_hd far_side_right roadside_4x3`, S = 3500, 3700), found /
seen apart / light / heavy / reported, main (5eb66eb's defaults + the lane cut) -> with stitching:
  3500 pole_hd         39/40 37/38 32/33 6/6 47 -> 46
  3500 far_side_right  40/40 40/40 34/34 6/6 48 -> 48
  3500 roadside_4x3    39/40 37/38 32/33 6/6 50 -> 48
  3700 pole_hd         38/40 37/38 32/32 5/6 48 -> 48
  3700 far_side_right  40/40 40/40 34/34 6/6 49 -> 49
  3700 roadside_4x3    38/40 38/39 32/32 6/6 46 -> 45
  total  234/240 (97.5 %), seen apart 229/233 (98.3 %), light 196/198 (99.0 %), heavy 35/36
  (97.2 %), reported 288 -> 284; the found, light and heavy answers identical with and without.
The lights called heavy are one tall van (3500's van 3, 2.07 x 2.73 x 5.70 m) seen by two cameras,
its track's outlines running into the vehicle behind it (estimated 9.7 m long); the heavy called
light is 3700's articulated lorry on pole_hd. Still below the bar: found (97.5 %; two of the six
misses share one blob with another vehicle all along, four were seen apart) and heavy (97.2 %).

Session 17. The auto blob closing, 3 px at f = 900 instead of 5 (header: blob_sizes_for()). Per-scene
runs with this file's matching, found / light / heavy / reported, 5 px -> 3 px:
  tuning seeds (1200)             1195 962/965 225/230 1390  ->  1197 964/967 227/230 1390
  dev seeds 2500-3700 (720)        700 561/567 130/133  827  ->   700 561/567 131/133  809
On the tuning seeds it finds two cars beside other vehicles (mast_high and mast_low 1100) and gets
three heavies right that the wider closing had joined with a neighbour (mast_high 1100 truck 33,
mast_low 1100 articulated 21, mast_low 1500 truck 28) and a van (mast_high 1100 van 32, 12.3 m long
before); it loses a truck (mast_low 1100 truck 33, now light) and a car (side 300 car 23, now heavy).
On the dev seeds pole_hd 3700's articulated lorry, a car-sized estimate with 5 px, is heavy (2.03 x
4.04 x 10.59 m). The car beside the bus (pole_hd 3300) is still one blob with it at 5 px (f = 1200).
Also tried: the outlines of a view that holds another vehicle's passage (hidden) used after the
joined ones, not with them. That lorry's track was handed to a car entering the image as it left,
and with the handed-over views, nearer, the resolution cut kept the car's outlines only (1.56 x
1.47 x 4.25 m). Heavy on its own (2.65 x 4.75 x 5.32 m), no other answer changed on the 48 tuning
and dev scenes; not kept for want of a test that reproduces the hand-over.

Fresh seeds never run before, scored once after the choice above (`--video-only --video-vehicles
40 --video-seed S --video-setups pole_hd far_side_right roadside_4x3`, S = 3900, 4100), found /
seen apart / light / heavy / reported, and the naive 2-D baseline's light correct (heavy 100 %):
  3900 pole_hd         39/40 39/39 32/32  7/7  47   baseline light  78.1 %
  3900 far_side_right  39/40 39/39 31/31  8/8  44   baseline light  93.5 %
  3900 roadside_4x3    40/40 39/39 31/32  8/8  45   baseline light  28.1 %
  4100 pole_hd         38/40 37/37 26/28 10/10 41   baseline light  92.6 %
  4100 far_side_right  40/40 40/40 29/30 10/10 47   baseline light 100.0 %
  4100 roadside_4x3    37/40 36/37 27/27 10/10 47   baseline light  40.7 %
  total  233/240 (97.1 %), seen apart 230/231 (99.6 %), light 176/180 (97.8 %), heavy 53/53 (100 %)
(4100 pole_hd's light 27/28 as the table first printed it: a car found but never fully in view as one
vehicle counted as light; it is counted wrong now, as by the per-scene runs, so 26/28.)
Main (5 px) on the same scenes, per-scene runs: found 234, light 178/181, heavy 52/53, reported
272 (3 px: 233, 176/180, 53/53, 271): 3900 roadside_4x3 van 31 (2.85 x 2.47 x 6.49 m) and 4100
far_side_right car 11 are called heavy with 3 px, 4100 roadside_4x3 truck 13 is right, and that
scene's car 1, never fully in view as one vehicle with 5 px, is not found. Over the 2160 vehicles
of tuning, dev and fresh seeds: found +1, heavies right +4, lights wrong 12 -> 13. Still below the
bar on the fresh seeds: found (97.1 %; a van and a car with a trailer on 4100 are missed by two
cameras each, in one blob with their neighbours) and light (97.8 %: two vans and a car called
heavy, their outlines running into a neighbour's -- 3900 roadside_4x3 van 31 estimated 0.93 m too
wide, 45.7 m^3 against the 45 m^3 rule -- and a car never fully in view as one vehicle).

Session 18. Traffic density: --video-mean-gap sets the generator's mean_gap and Table 2 prints the
flow. The default scenes carry 2900-3400 vehicles/h over the 4 lanes (mean_gap 2.5 s + min_gap
0.8 s per lane), about six times the paper's roads (2585 vehicles in over 5 hours). Fresh seeds
never run before, scored once with main's defaults before anything was looked at (`--video-only
--video-vehicles 40 --video-seed S --video-setups pole_hd far_side_right roadside_4x3`, S = 4300,
4500), found / seen apart / light / heavy / reported, and the same vehicles spaced out
(`--video-mean-gap 6`: 1500-1800 vehicles/h; the seed draws the same vehicles, lanes and speeds,
ids in order of entry):
                       default (~3000/h)                 mean_gap 6 (~1600/h)
  4300 pole_hd         40/40 40/40 36/36 4/4 47          40/40 40/40 36/36 4/4 43
  4300 far_side_right  40/40 38/38 36/36 4/4 45          40/40 40/40 36/36 4/4 43
  4300 roadside_4x3    40/40 39/39 36/36 4/4 52          40/40 40/40 36/36 4/4 47
  4500 pole_hd         39/40 39/40 33/33 6/6 52          40/40 40/40 34/34 6/6 44
  4500 far_side_right  37/40 36/36 30/31 6/6 41          38/40 36/36 33/33 5/5 39
  4500 roadside_4x3    40/40 38/38 34/34 5/6 48          40/40 40/40 34/34 6/6 49
  total  236/240 (98.3 %), 230/231, 205/206 (99.5 %), 29/30 (96.7 %), 285;  spaced out 238/240
  (99.2 %), 236/236, 209/209, 29/29, 265 (the two missed, spaced out, a car and an articulated lorry
  on far_side_right 4500, each drive abreast of an articulated lorry in the next lane for their whole
  passage). The naive 2-D baseline in the same runs, light correct at its oracle threshold (heavy
  100 %): 4300 pole_hd 91.7 %, far_side_right 94.4 %, roadside_4x3 36.1 %; 4500 78.8, 93.5, 23.5 %.
  MAE W H L (m) at the default density: 0.15-0.26, 0.06-0.18, 0.54-1.55.
Over the four fresh pairs scored once (3100-4500, each with its session's main; 960 vehicles):
found 936/960 (97.5 %), light 755/762 (99.1 %), heavy 171/174 (98.3 %). Half the traffic takes
found and heavy over the bar on these 240 vehicles; at the default density they stay under it.
The heavy called light, roadside_4x3 4500 truck 6 (2.47 x 3.23 x 11.69 m; diagnosed after the
score, so seeds 4300/4500 are dev now): it overtakes a car with a trailer and a car in the next
lane, far and small; the lane cut finds their gap (two runs, no column misplaced) but their part,
~250 px, is under the parts' minimum of 4 x min_area (363 px at f = 700), so the blob stays whole,
its views hold the cars' passages (hidden views, to the fallback estimator) and one frame is used:
2.12 x 2.91 x 7.06 m. Spaced out, it is right.

Tried and not kept: parts of a lane cut down to min_area (1x instead of 4x). Per-scene runs with
this file's matching on the dev seeds 3900-4500 (12 scenes, 480 vehicles), main -> 1x: found 469 ->
471 (pole_hd 3900 truck 3, far_side_right 4500 car 2), lights wrong 5 -> 5 (roadside_4x3 3900 van
31 right, pole_hd 4300 van 3 wrong: 4.08 m wide), heavies wrong 1 -> 2 (roadside_4x3 4500 truck 6
right; roadside_4x3 3900 truck 30 and far_side_right 4500 articulated lorry 22 called light,
estimated 1.83 x 1.59 x 1.95 m and 1.28 x 2.44 x 11.30 m), reported 556 -> 617 (+11 %); tuning
gantry 100 the same answers, 51 -> 54 reports. More small cuts find a vehicle and lose a heavy, as
the wider cuts of session 15 did.

Session 19. Fresh seeds 4700/4900, never run before, scored once with main (d403a85, pipeline as in
session 18), same command as session 18; found / seen apart / light / heavy / reported, traffic
3500 and 3090 vehicles/h:
  4700 pole_hd         40/40 40/40 32/32 8/8 46
  4700 far_side_right  39/40 38/38 31/31 7/8 47
  4700 roadside_4x3    40/40 40/40 31/32 7/8 49
  4900 pole_hd         39/40 36/36 35/35 4/4 44
  4900 far_side_right  39/40 39/39 35/35 4/4 43
  4900 roadside_4x3    39/40 36/36 35/35 3/4 54
  total  236/240 (98.3 %), 229/229, 199/200 (99.5 %), 33/36 (91.7 %), 283. Naive 2-D baseline,
  light at its oracle threshold: 4700 75.0, 93.5, 18.8 %; 4900 88.6, 97.1, 37.1 %. MAE W H L (m):
  0.16-0.27, 0.08-0.14, 0.32-1.17.
Over the five fresh pairs scored once (3100-4900, 1200 vehicles): found 1172/1200 (97.7 %), light
954/962 (99.2 %), heavy 204/210 (97.1 %). Light meets the bar, found is at it, heavy is not. The
three heavies called light (seen in frames after scoring; 4700/4900 are dev seeds now), three
different causes:
  - far_side_right 4700 articulated lorry 36 (grey, 2.50 x 3.96 x 13.71 m): camouflage. Its lower
    body is the asphalt's grey, so the background subtraction keeps only its upper half; the
    silhouette's lowest point is then not on the road and the cuboid comes out low and long:
    1.27 x 1.38 x 20.08 m.
  - roadside_4x3 4700 truck 13 (2.41 x 3.77 x 10.67 m): its track begins far away, in one blob with
    a neighbour, and the views the estimator keeps are those merged ones: 0.56 x 1.86 x 19.81 m,
    though it later passes the camera alone and whole.
  - roadside_4x3 4900 bus 22 (2.54 x 3.39 x 10.63 m): its passage is split into three tracks near
    this low camera (4.5 m); the one with the most views (9) gives 2.19 x 1.99 x 7.67 m.

Session 20. max_aspect (apps/vehicles.hpp): an answer from a vehicle's own views longer than 10
times its width is no one road vehicle's, and its joined views answer instead when theirs is one.
Truck 13 above, looked at view by view: its clean views (IoU 0.9-1.0 with its true box) were the
parts of a lane cut, so they went to the second (joined) estimator; its own views were 17 of a far
blob of it and the truck ahead of it before either had a track, and two near views. For a tall
vehicle under a low camera the near views' length resolution (4.3 m per pixel: the roof's far
edge projects far down the road) is within resolution_factor 4 of the far ones' (12-13 m), so the
far ones stayed. Its joined answer: 2.09 x 3.49 x 10.02 m, heavy. The grey lorry 36's own answer
(1.27 x 1.38 x 20.1 m) is replaced by its joined one, 1.60 x 2.81 x 14.12 m, heavy. Dev seeds
4300-4900 (12 scenes, 480 vehicles; per-scene CLI runs, this file's matching), found / light /
heavy / reported:
  main (e0fc080)     472/480  404/406  62/66  568
  max_aspect 7       472/480  404/406  63/66  568   (the lorry's joined answer, 8.8 x its width, refused)
  max_aspect 10      472/480  404/406  64/66  568   <- the default
  max_aspect 14      472/480  404/406  64/66  568
Nothing else changed on dev. Held out, fresh seeds 5100/5300 never run before, scored once with
main and with the change in the same session (this command, --scene-dir for the cached scenes):
both the same, found 238/240 (99.2 %; 234/234 of those seen apart), light 189/189, heavy 49/49,
276 reported, MAE W H L 0.14-0.32, 0.04-0.13, 0.28-0.93 m; traffic 3074 and 2918 vehicles/h.
Naive 2-D baseline, light at its oracle threshold: 5100 77.4, 77.4, 29.0 %; 5300 78.1, 96.9, 34.4 %.
Then fresh seeds 5500/5700, never run before, scored once with main before and after the change
(the same answers): found 233/240 (97.1 %; 222/225 of those seen apart), light 184/185, heavy
46/48, 305 reported; traffic 3241 and 3005 vehicles/h:
  5500 pole_hd         37/40 34/34 29/29 7/8 51   articulated lorry 7 (18.59 m) as 1.59 x 1.49 x 4.25
  5500 far_side_right  40/40 40/40 32/32 7/8 47   truck 1 (2.41 x 3.12 x 10.77) as 1.48 x 1.10 x 12.31
  5500 roadside_4x3    38/40 32/33 29/30 8/8 53   van 4 (2.06 x 2.14 x 5.89) as 3.37 x 2.39 x 10.40
  5700 pole_hd         39/40 39/40 31/31 8/8 51
  5700 far_side_right  39/40 38/39 31/31 8/8 48
  5700 roadside_4x3    40/40 39/39 32/32 8/8 55
  MAE W H L (m): 0.18-0.34, 0.07-0.17, 0.46-1.49. Naive 2-D baseline, light at its oracle
  threshold: 5500 93.1, 96.9, 53.3 %; 5700 80.6, 100.0, 46.9 %.
Over the seven fresh pairs scored once (3100-5700, 1680 vehicles): found 1643/1680 (97.8 %), light
1327/1336 (99.3 %), heavy 299/307 (97.4 %). Still wrong on dev: roadside_4x3 4900 bus 22 (split,
above); roadside_4x3 4500 truck 6 (2.47 x 3.23 x 11.69 m) as 2.12 x 2.91 x 7.06 m, light: its own
answer rests on 1 view, its joined one (9 views) is 1.46 x 3.53 x 10.43 m, heavy. A rule taking the
joined answer when the own one rests on at most 2 views and the joined one on 3 or more times as
many was scored offline on every matched vehicle of dev 3300 (far_side_right) and 4300-4900 (512):
it fixes truck 6 and changes no other light/heavy answer -- one case, so not adopted; a lead.

Session 21. thin_views (apps/vehicles.hpp): an own answer resting on one used view gives way to a
joined one of one vehicle's shape resting on 3 times as many or more. One view's ray fixes two of
W, H, L (the far corner lies on it), and along the ray the answer is the class prior's -- Table 1's
truck is 2.0 x 2.5 x 7 m, a real one ~2.5 x 3.5 x 10 m. Dev seeds 3300 (far_side_right) and
4300-4900 (13 scenes, 520 vehicles; per-scene CLI runs, this file's matching), found / light /
heavy / reported:
  main (c924bfa)     512/520  436/438  71/74  614
  thin_views 1       512/520  436/438  72/74  614   <- the default (truck 6 heavy)
  thin_views 2       512/520  436/438  72/74  614
  thin_views 4       512/520  436/438  72/74  614
The same light/heavy answers with and without it on the x0.5 scenes of seed 7100 (pole_hd,
far_side_right, roadside_4x3, mast_low, gantry; 200 vehicles: 199/200 found, 147/149 light, 50/50
heavy) and on fresh seeds 5900/6100 (never run before, scored once with main and thin_views 2).
1 or 2 was chosen on the dimensions of the tracks whose answer changes, over all these scenes
(the sum of |error| of W, H, L against the vehicle the track follows): with one own view the
joined answer is the nearer in 7 of 9 (a 12.7 m bus's second track from 2.07 x 3.11 x 10.09 to
2.38 x 3.03 x 12.00 m), with two own views in 0 of 5 (a car from 1.66 x 1.55 x 3.97 to 1.80 x 1.93 x
6.86 m): a second view from elsewhere on the road fixes the third dimension, and the joined views
(lane-cut parts, merges) hold other vehicles' pixels. So 1. Fresh seeds 5900/6100: found 232/240
(96.7 %; 223/227 of those seen apart), light 191/191, heavy 38/41, 277 reported; traffic 3362 and
3398 vehicles/h:
  5900 pole_hd         39/40 37/38 31/31 8/8 47
  5900 far_side_right  39/40 38/39 31/31 8/8 43
  5900 roadside_4x3    37/40 33/35 29/29 7/8 51   articulated 23 (17.98 m) as 1.66 x 2.83 x 7.65
  6100 pole_hd         38/40 38/38 33/33 5/5 41
  6100 far_side_right  40/40 40/40 34/34 5/6 44   bus 25 (12.70 m) as 2.61 x 2.75 x 5.70, 48 views
  6100 roadside_4x3    39/40 37/37 33/33 5/6 51   truck 26 (2.53 x 2.93 x 7.26) as 2.14 x 2.90 x 6.61
  MAE W H L (m): 0.16-0.26, 0.06-0.12, 0.56-1.38. Naive 2-D baseline at its oracle threshold,
  light / heavy: 5900 96.8/100, 100/100, 41.4/100 %; 6100 75.8/100, 94.1/100, 30.3/100 %.
Over the eight fresh pairs scored once (3100-6100, 1920 vehicles): found 1875/1920 (97.7 %), light
1518/1527 (99.4 %), heavy 337/348 (96.8 %). Car 25 of 5900, missed on all three set-ups, is in
clear view only while far off and smaller than min_area (16 x 11 px under pole_hd), then hidden.
Signed errors over the matched dev vehicles (estimate - truth, medians): W -0.12 m for cars, -0.18
for trucks, -0.41 for articulated lorries; L -0.51, -2.41 and -2.96 m for trucks, articulated
lorries and buses; motorbikes +0.62 m W (Table 1's motorbike is 1.6 m wide). From the exact
silhouettes (observations, 60 vehicles per set-up) the same signs: the class prior pulls the
heavies towards Table 1's small truck and bus. A likelihood S of 0.125 m instead of 0.25 (the
outlier gate kept at 0.75 m) halves the bias (W -0.08, -0.07, -0.27 m) but on dev scores 512/520,
435/438, 71/74: no better, so S stays. Camouflage (far_side_right 3300 truck 33) is not a matter
of the KDE's intensity bandwidth: the truck's sides are within 0.02 of the asphalt's chromaticity
and within a few levels of its intensity; with sigma_I 0.03 or 0.04 (instead of 0.06) it is still
light or lost.
Lead, not adopted this session: the size bias is the resolution cut's more than the prior's. From
the exact silhouettes, length_resolution_factor 0 (every view) takes it almost away (trucks W
-0.27 -> -0.02 m, L -0.64 -> +0.04 m on pole_hd), 16 halves it: the far views' shallow rays fix the
scale that the few near ones leave to the prior. From video, dev (520 vehicles), found / light /
heavy, thin_views 1:
  factor 4 (default)   512/520  436/438  72/74
  factor 8             512/520  437/438  72/74
  factor 16            512/520  437/438  73/74
  factor 0             512/520  433/438  73/74   (far outlines of two vehicles: cars as heavy)
With 16 on scenes seen before but not tuned on (x0.5 seed 7100, 5900/6100; 440 vehicles): light
337/340 against 338/340, heavy 90/91 against 88/91 (5900 articulated 23 and 6100 truck 26 right);
on fresh seed 6300 (pole_hd, far_side_right, roadside_4x3; 120 vehicles, scored once): found
116/120 both, light 99/101 against 100/101 (far_side_right car 25 as 3.68 x 2.34 x 7.39 m, heavy),
heavy 15/15 both. MAE W H L over every matched vehicle of these 27 scenes (1059): 0.207, 0.097,
0.831 m with 4; 0.171, 0.078, 0.761 with 16 (heavies: W 0.36 -> 0.42, H 0.17 -> 0.15, L 2.78 ->
2.72). Three heavies gained for one light lost over 1059 vehicles, but the fresh seed shows the
light lost and no heavy gained. Then fresh seed 6500 (120 vehicles, scored once): the same answers
with 4 and 16, found 118/120, light 94/94, heavy 22/24 (far_side_right truck 24, 2.46 x 3.59 x
8.43 m, as 1.51 x 1.83 x 9.92 m; roadside_4x3 articulated 1, 18.06 m, as 5.69 m long). Over the two
fresh seeds 16 gains nothing and loses a light, so 4 stays; the lead is the far views, used with
a guard against their merged outlines rather than a wider cut.

Session 22. Three changes, measured on the 30 scenes of sessions 20-21 (dev 3300 far_side_right and
4300-4900 x pole_hd far_side_right roadside_4x3; x0.5 seed 7100 x five set-ups; seeds 5900-6500 x
three set-ups, all scored before; 1200 vehicles) by per-scene CLI runs (`vtrack vehicles VIDEO
--camera camera.json --out vehicles.csv --tracks tracks.txt`) scored with this file's matching,
then on fresh seeds. Found / light / heavy / reported, and MAE W / H / L (m) of the matched:
  main (48f6a1f)                                   1177/1200  968/973  197/204  1419
  + foot gate after border-cut views               1178/1200  970/974  199/204  1416  0.206 0.094 0.789
  + far views, S as the near views'                1178/1200  971/974  199/204  1416  0.134 0.081 0.681
  + max_vehicle_width 2.6                          1178/1200  972/974  199/204  1416  0.134 0.081 0.681
  far views with S widened by r / r_cut (default)  1178/1200  972/974  199/204  1416  0.166 0.081 0.713
1. The blob tracker's foot gate held only while a track's last view had a ground point. A lorry
   leaving past roadside_4x3 (seed 6500, articulated 1, 18.06 m) had views cut by the border, and
   then a van entering from that border the other way continued its track for 38 frames: the
   lorry's answer was the van's, 2.17 x 2.30 x 5.69 m, light. The road line holds after border-cut
   views too, and a track whose predicted foot is behind the camera takes no blob with a ground
   point: 1.53 x 3.68 x 14.97 m, heavy. Also roadside_4x3 5900 articulated 23 heavy and
   far_side_right 4500 car 14 light again (both through the same switch). A blob tracker change
   tried next: a view not "joined" when the small tracks inside the blob lie inside the big
   track's predicted box (vehicles hidden behind a lorry made its clean views joined): the same
   light/heavy answers on all 30 scenes, so not kept.
2. Far views. From exact silhouettes (5 set-ups x 60 vehicles, seed 11) the estimator is biased
   small for heavies: W -0.2 to -0.6 m, L -0.4 to -3.2 m (medians by class); the views within the
   resolution cut are the near ones, whose rays leave one direction of W-H-L to Table 1's narrow
   models. The far views whose ray lies within far_view_gate (3 sigma of S, the outlier gate's) of
   the refitted answer now join it: with S as the near views', trucks' median W error on pole_hd
   -0.27 -> +0.01 m, on roadside_4x3 -0.32 -> -0.08 m (gate 6: the same answers), and on video the
   MAE above. But Table 1 below (from observations, 1-2 px of noise on every outline point) then
   lost 2-4 lights of 245 (cars too tall: a pixel of a far outline is metres): 99.2 % / 98.4 %
   light at 1 / 2 px, MAE H 0.33 / 0.48 m against 0.14 / 0.24 m without far views. So each far view
   joins with S widened by (r / r_cut)^2, its resolution over the cut's, and is gated under S
   itself (gated under the widened S, an 8 m longer far outline joined: the gtest). `python
   benchmarks/vehicles.py --noise 0 1 2`, rays default against far_view_gate 0: 100 % light and
   heavy at every noise level, MAE W / H / L 0.15 / 0.07 / 0.53 against 0.19 / 0.09 / 0.58 m at 0 px,
   0.13 / 0.17 / 0.53 against 0.17 / 0.14 / 0.56 at 1 px, 0.16 / 0.31 / 0.53 against 0.18 / 0.24 /
   0.59 at 2 px (H a little worse with noise, W and L better).
3. max_vehicle_width. Fresh seeds 6700/6900 (pole_hd far_side_right roadside_4x3, 240 vehicles),
   scored once with main and with the far views (S as the near views'): found 231/240 both, light
   194/194 (main) and 193/194 (far views), heavy 36/37 both (far_side_right 6900 bus 4, 12.2 m, as
   2.28 x 2.08 x 9.41 m: light). MAE W / H / L 0.205 / 0.105 / 0.821 -> 0.132 / 0.081 / 0.674 m; of
   the 202 tracks whose answer changed, 125 came nearer the truth (sum of |error| of W, H, L), 43
   farther. The light lost: pole_hd 6700 car 10, abreast with car 9 receding from the pole as one
   blob for its whole passage: 2.54 x 2.33 x 6.06 m (light by 36 m^3) before, 3.15 x 2.14 x 6.99 m
   (heavy) with the far views, which fix the width -- of the two cars. No road vehicle is wider
   than 2.55 m (2.60 m refrigerated, EU Directive 96/53/EC), so the volume now counts W up to 2.6
   m: car 10 light, and mast_low x0.5 7100 car 18 (3.72 x 2.15 x 7.41 m) light on the 30 scenes. A
   heavy reaches 45 m^3 at 2.2 m wide from 2.9 x 7 m, so none turns light. With the cap, 6700/6900:
   found 231/240, light 194/194, heavy 36/37.
Fresh seeds 7300/7500 (pole_hd far_side_right roadside_4x3, 240 vehicles; heavy-rich), scored once
with main and with the far views (S as the near views') and the cap: the same answers, found
233/240 (97.1 %), light 173/173, heavy 60/60; MAE W / H / L 0.263 / 0.108 / 0.932 -> 0.196 / 0.087 /
0.858 m. Fresh seed 7700 (the same three set-ups, 120 vehicles), scored once with main and the
shipped defaults (widened far views, the cap): the same answers, found 119/120, light 101/101,
heavy 18/18; MAE W / H / L 0.173 / 0.062 / 0.523 -> 0.139 / 0.051 / 0.472 m (heavies' W 0.36 ->
0.27 m). Over every fresh pair scored once (3100-6500 as before, 6700/6900, 7300/7500 and 7700
with main; on 7300/7500 the unwidened far views and on 7700 the shipped defaults gave main's
answers; 2760 vehicles): found 2692 (97.5
%), light 2180/2190 (99.5 %), heavy 488/502 (97.2 %). The next fresh seeds are 7900 and up.
Still wrong on the 30 scenes: the two camouflaged heavies (far_side_right 3300 truck 33, 6500
truck 24), far_side_right 6100 bus 25 (merged with bus 23, then far views: 5.70 m), roadside_4x3
4900 bus 22 (split) and 6100 truck 26 (2.53 x 2.93 x 7.26 m as 2.05 x 2.96 x 6.28 m = 38 m^3;
from its exact silhouettes 2.16 x 3.01 x 6.60 m, heavy by its height alone); lights mast_low x0.5
van 25 (H 4.12 m from 12 views) and pole_hd 6300 car 30 (one view, H 3.07 m).
"""

import argparse
import csv
import dataclasses
import inspect
import json
import os
import sys
import tempfile
import time
from collections import defaultdict

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
from _table import print_table  # noqa: E402

import vtrack  # noqa: E402
from vtrack.synthetic_road import CAMERA_SETUPS, CameraSetup, make_road_scene  # noqa: E402

METHODS = {
    "ray (paper)": {"sampler": "ray"},
    "ray, decision=last": {"sampler": "ray", "decision": "last"},
    "ray, rule=class": {"sampler": "ray", "light_heavy_rule": "class"},
    "mh (x* = map)": {"sampler": "mh"},
    "mh all (n_particles 100)": {"sampler": "mh", "reference": "all", "n_particles": 100},
    "discrete": {"sampler": "discrete"},
    "rays (extension, default)": {},
    "rays, no far views": {"sampler": "rays", "far_view_gate": 0.0},
    "rays, decision=mean": {"sampler": "rays", "decision": "mean"},
    "rays, rule=class": {"sampler": "rays", "light_heavy_rule": "class"},
}

# --ablations: the choices the paper leaves open, one at a time around the defaults.
ABLATIONS = {
    "ray, dynamic_sigma 0.1": {"sampler": "ray", "dynamic_sigma": 0.1},
    "ray, dynamic_sigma 0.3 (default)": {"sampler": "ray"},
    "ray, dynamic_sigma 1.0": {"sampler": "ray", "dynamic_sigma": 1.0},
    "ray, reference mean": {"sampler": "ray", "reference": "mean"},
    "ray, reference random": {"sampler": "ray", "reference": "random"},
    "ray, n_particles 50, burn_in 25": {"sampler": "ray", "n_particles": 50, "burn_in": 25},
    "ray, n_particles 1000, burn_in 500": {"sampler": "ray", "n_particles": 1000, "burn_in": 500},
    "ray, rule=class": {"sampler": "ray", "light_heavy_rule": "class"},
    "rays, n_particles 200, burn_in 100": {"sampler": "rays", "n_particles": 200, "burn_in": 100},
    "rays, n_particles 50, burn_in 25": {"sampler": "rays", "n_particles": 50, "burn_in": 25},
    "ray, heavy_volume 40": {"sampler": "ray", "heavy_volume": 40.0},
    "ray, heavy_volume 50": {"sampler": "ray", "heavy_volume": 50.0},
    "rays, max_vehicle_width 0 (off)": {"sampler": "rays", "max_vehicle_width": 0.0},
    "mh, sigma 0.1": {"sampler": "mh", "sigma_w": 0.1, "sigma_h": 0.1, "sigma_l": 0.1},
    "mh, sigma 0.5": {"sampler": "mh", "sigma_w": 0.5, "sigma_h": 0.5, "sigma_l": 0.5},
    "rays, sigma 0.1": {"sampler": "rays", "sigma_w": 0.1, "sigma_h": 0.1, "sigma_l": 0.1},
    "rays, sigma 0.5": {"sampler": "rays", "sigma_w": 0.5, "sigma_h": 0.5, "sigma_l": 0.5},
}


def camera_of(scene):
    c = scene.camera_file()
    return vtrack.vehicles.Camera(c["K"], c["dist"], c["R"], c["t"], image_size=tuple(c["image_size"]))


def observations(scene, step, noise, rng):
    out = []
    for k in range(0, scene.n_frames, step):
        for v in scene.present(k):
            poly = scene.silhouette(v, k)
            if poly is not None:
                out.append((k + 1, v.id, poly + rng.normal(0.0, noise, poly.shape) if noise > 0 else poly))
    return out


def run_method(cam, obs, params):
    est = vtrack.vehicles.VehicleDimensionEstimator(cam, **params)
    used = 0
    start = time.perf_counter()
    for frame, vid, poly in obs:
        try:
            used += est.update(vid, poly, frame=frame)
        except ValueError:  # a noisy outline point above the horizon
            pass
    seconds = time.perf_counter() - start
    return est.estimates(), seconds / max(len(obs), 1)


def naive_lengths(cam, obs):
    """Mean along-road extent of the rectified silhouette per vehicle."""
    lengths = defaultdict(list)
    for _, vid, poly in obs:
        try:
            o = vtrack.vehicles.observe_vehicle(cam, poly)
        except ValueError:
            continue
        lat0, lat1, al0, al1 = o.box
        lengths[vid].append(al1 - al0)
    return {vid: float(np.mean(v)) for vid, v in lengths.items()}


def score(pairs):
    """pairs: (truth vehicle, estimate dict or heavy bool). -> light acc, heavy acc, counts."""
    light = [p for p in pairs if not p[0].heavy]
    heavy = [p for p in pairs if p[0].heavy]
    acc = lambda ps: float(np.mean([p[1] == p[0].heavy for p in ps])) if ps else float("nan")
    return acc(light), acc(heavy), len(light), len(heavy)


def fmt_acc(a, n):
    return f"{100 * a:.1f} % of {n}"


def from_observations(args):
    rows = []
    for noise in args.noise:
        per_method = defaultdict(lambda: {"pairs": [], "err": [], "time": []})
        naive_pairs = []
        for name in CAMERA_SETUPS:
            scene = make_road_scene(name, n_vehicles=args.vehicles, seed=args.seed)
            cam = camera_of(scene)
            obs = observations(scene, args.step, noise, np.random.default_rng(args.seed))
            truth = {v.id: v for v in scene.vehicles}
            for method, params in (ABLATIONS if args.ablations else METHODS).items():
                estimates, per_obs = run_method(cam, obs, params)
                m = per_method[method]
                m["time"].append(per_obs)
                for e in estimates:
                    v = truth[e["vehicle_id"]]
                    m["pairs"].append((v, e["valid"] and e["light_heavy"] == "heavy"))
                    if e["valid"]:
                        m["err"].append(np.abs([e["W"] - v.W, e["H"] - v.H, e["L"] - v.L]))
            for vid, length in naive_lengths(cam, obs).items():
                naive_pairs.append((truth[vid], length))
        for method, m in per_method.items():
            la, ha, nl, nh = score(m["pairs"])
            err = np.mean(m["err"], axis=0)
            rows.append((f"{noise:g}", method, fmt_acc(la, nl), fmt_acc(ha, nh), f"{50 * (la + ha):.1f} %",
                         *(f"{x:.2f}" for x in err), f"{1e6 * np.median(m['time']):.0f}"))
        # The naive baseline at its best threshold on this data.
        best = max(np.arange(3.0, 25.0, 0.1),
                   key=lambda t: sum(score([(v, l >= t) for v, l in naive_pairs])[:2]))
        la, ha, nl, nh = score([(v, l >= best) for v, l in naive_pairs])
        rows.append((f"{noise:g}", f"naive 2-D (length >= {best:.1f} m, oracle)", fmt_acc(la, nl), fmt_acc(ha, nh),
                     f"{50 * (la + ha):.1f} %", "", "", "", ""))
    print(f"Table 1: from observations, {len(CAMERA_SETUPS)} camera set-ups x {args.vehicles} vehicles, "
          f"seed {args.seed}, every {args.step}th frame\n")
    print_table(["outline noise px", "method", "light correct", "heavy correct", "mean", "MAE W (m)", "MAE H (m)",
                 "MAE L (m)", "us per vehicle-frame"], rows)


# A vehicle "seen apart" (Table 2): in SEEN_APART_FRAMES frames or more fully in view, at least
# SEEN_APART_VISIBLE of it not hidden, and its image box overlapping no other vehicle's box. One
# never seen apart is in one blob with others for its whole passage (abreast at the same speed,
# stacked in the same image columns, behind a bus): a property of the scene, not of the method,
# which finds some of them all the same (a lane cut, a track that emerges).
SEEN_APART_FRAMES = 5
SEEN_APART_VISIBLE = 0.9

# The video scenes' frame rate and the generator's default traffic (make_road_scene's mean_gap).
VIDEO_FPS = 25.0
DEFAULT_MEAN_GAP = inspect.signature(make_road_scene).parameters["mean_gap"].default


def seen_apart(frames):
    """The vehicles seen apart, from {frame: [(id, box, fully in view and visible), ...]}."""
    count = defaultdict(int)
    for rows in frames.values():
        for vid, box, clear in rows:
            if clear and all(iou(box, other) == 0.0 for o, other, _ in rows if o != vid):
                count[vid] += 1
    return {vid for vid, n in count.items() if n >= SEEN_APART_FRAMES}


def iou(a, b):
    ix = max(0.0, min(a[0] + a[2], b[0] + b[2]) - max(a[0], b[0]))
    iy = max(0.0, min(a[1] + a[3], b[1] + b[3]) - max(a[1], b[1]))
    inter = ix * iy
    return inter / (a[2] * a[3] + b[2] * b[3] - inter)


# Camera set-ups held out of every tuning, for the video runs only (--video-setups NAME): kept out of
# vtrack.synthetic_road.CAMERA_SETUPS, which the tests and the observation tables run.
HELD_OUT_SETUPS = {
    "pole_hd": CameraSetup(height=7.0, pitch=14.0, yaw=20.0, lateral=-4.0, focal=1200.0,
                           image_width=1280, image_height=720),
    "far_side_right": CameraSetup(height=11.0, pitch=18.0, yaw=-24.0, lateral=20.0),
    "roadside_4x3": CameraSetup(height=4.5, pitch=10.0, yaw=30.0, lateral=-3.0, focal=700.0,
                                image_width=800, image_height=600),
}
VIDEO_SETUPS = {**CAMERA_SETUPS, **HELD_OUT_SETUPS}


def scaled_setup(name, scale):
    """Set-up `name` at `scale` times its resolution: the same field of view (the focal length and
    the image size scaled together), so the same scene in `scale`^2 times the pixels."""
    setup = VIDEO_SETUPS[name]
    if scale == 1.0:
        return setup
    return dataclasses.replace(setup, focal=setup.focal * scale,
                               image_width=round(setup.image_width * scale),
                               image_height=round(setup.image_height * scale))


def written_scene(name, args, folder):
    """The video scene of set-up `name` written to `folder` (--scene-dir: reused when it is there,
    the generator being seeded; else a temporary folder)."""
    paths = {k: os.path.join(folder, f) for k, f in
             (("video", "video.mkv"), ("camera", "camera.json"), ("vehicles", "vehicles.csv"), ("boxes", "boxes.csv"))}
    if not all(os.path.exists(p) for p in paths.values()):
        scene = make_road_scene(scaled_setup(name, args.video_scale), n_vehicles=args.video_vehicles,
                                seed=args.video_seed, class_mix=args.video_class_mix, fps=VIDEO_FPS,
                                mean_gap=args.video_mean_gap)
        scene.write(folder, video="video.mkv")
    return paths


def video_scene(name, args):
    """(measured vehicles, their track rows, seconds, ground-truth vehicles by id, boxes by frame)."""
    def run(folder):
        paths = written_scene(name, args, folder)
        start = time.perf_counter()
        vehicles, tracks = vtrack.vehicles.measure_vehicles(paths["video"], paths["camera"], return_tracks=True,
                                                            **args.video_set)
        seconds = time.perf_counter() - start
        with open(paths["vehicles"]) as f:
            truth = {int(r["vehicle_id"]): argparse.Namespace(heavy=r["light_heavy"] == "heavy", W=float(r["W"]),
                                                              H=float(r["H"]), L=float(r["L"]), cls=r["class"],
                                                              seen_apart=False, first_frame=int(r["first_frame"]))
                     for r in csv.DictReader(f)}
        boxes, clear = defaultdict(list), defaultdict(list)
        with open(paths["boxes"]) as f:
            for r in csv.DictReader(f):
                box = (float(r["x"]), float(r["y"]), float(r["w"]), float(r["h"]))
                boxes[int(r["frame"])].append((int(r["vehicle_id"]), box))
                clear[int(r["frame"])].append((int(r["vehicle_id"]), box, r["in_view"] == "1" and
                                               float(r["visible"]) >= SEEN_APART_VISIBLE))
        for vid in seen_apart(clear):
            truth[vid].seen_apart = True
        n_frames = max(boxes) if boxes else 1
        with open(paths["camera"]) as f:
            image_size = json.load(f)["image_size"]
        return vehicles, tracks, seconds / n_frames, truth, boxes, (vtrack.vehicles.read_camera_file(paths["camera"]),
                                                                     image_size)

    if args.scene_dir:
        scale = "" if args.video_scale == 1.0 else f"_x{args.video_scale:g}"
        gap = "" if args.video_mean_gap == DEFAULT_MEAN_GAP else f"_gap{args.video_mean_gap:g}"
        return run(os.path.join(args.scene_dir, f"{name}{scale}_{args.video_vehicles}_{args.video_seed}{gap}"))
    with tempfile.TemporaryDirectory() as folder:
        return run(folder)


def naive_video(camera, tracks, matched, truth):
    """The naive 2-D baseline from video: per matched vehicle, the mean along-road extent of the
    road projection of its image boxes (the pipeline's track rows) off the image border, light/heavy
    by a length threshold, the best one on this very data (an oracle). -> (light acc, heavy acc)."""
    cam, (width, height) = camera
    lengths = defaultdict(list)
    for _, tid, x, y, w, h, *_ in tracks:
        if x > 1.0 and y > 1.0 and x + w < width - 2.0 and y + h < height - 2.0:
            try:
                box = vtrack.vehicles.observe_vehicle(cam, (x, y, w, h)).box
            except ValueError:
                continue
            lengths[int(tid)].append(box[3] - box[2])
    pairs = [(truth[gt], float(np.mean(lengths[e["vehicle_id"]]))) for gt, e in matched.items()
             if lengths.get(e["vehicle_id"])]
    best = max(np.arange(3.0, 40.0, 0.1), key=lambda t: sum(score([(v, l >= t) for v, l in pairs])[:2]))
    return score([(v, l >= best) for v, l in pairs])[:2], best


def flow_per_hour(truth):
    """The scene's traffic over all its lanes, vehicles per hour: the vehicles less one over the time
    between the first and the last one coming into view."""
    first = sorted(v.first_frame for v in truth)
    return 3600.0 * VIDEO_FPS * (len(first) - 1) / max(first[-1] - first[0], 1)


def from_video(args):
    rows, extra_rows, flows = [], [], []
    for name in args.video_setups:
        vehicles, tracks, per_frame, truth, truth_boxes, camera = video_scene(name, args)
        votes = defaultdict(lambda: defaultdict(int))
        for f, tid, x, y, w, h, *_ in tracks:
            cands = [(iou(b, (x, y, w, h)), vid) for vid, b in truth_boxes.get(int(f), [])]
            if cands and max(cands)[0] > 0.5:
                votes[int(tid)][max(cands)[1]] += 1
        visible = {vid for frame in truth_boxes.values() for vid, _ in frame}
        matched = {}
        for e in vehicles:
            if votes.get(e["vehicle_id"]):
                gt = max(votes[e["vehicle_id"]].items(), key=lambda kv: kv[1])[0]
                if gt not in matched or e["frames_used"] > matched[gt]["frames_used"]:
                    matched[gt] = e
        # A vehicle never fully in view has no class (None): wrong, light or heavy.
        pairs = [(truth[gt], e["light_heavy"] == "heavy" if e["valid"] else None) for gt, e in matched.items()]
        la, ha, nl, nh = score(pairs)
        flows.append(flow_per_hour(truth.values()))
        err = np.mean([np.abs([e["W"] - truth[g].W, e["H"] - truth[g].H, e["L"] - truth[g].L])
                       for g, e in matched.items() if e["valid"]], axis=0)
        (nla, nha), threshold = naive_video(camera, tracks, matched, truth)
        apart = [vid for vid in visible if truth[vid].seen_apart]
        rows.append((name, f"{len(matched)}/{len(visible)} ({100 * len(matched) / len(visible):.0f} %)",
                     f"{sum(vid in matched for vid in apart)}/{len(apart)}", len(vehicles), fmt_acc(la, nl), fmt_acc(ha, nh), f"{50 * (la + ha):.1f} %",
                     *(f"{x:.2f}" for x in err), f"{1e3 * per_frame:.1f}",
                     f"{100 * nla:.1f} / {100 * nha:.1f} % (>= {threshold:.1f} m)"))
        # What the reported vehicles beyond one per ground-truth vehicle are.
        kept = {id(e) for e in matched.values()}
        extra = [e for e in vehicles if id(e) not in kept]
        second = [e for e in extra if votes.get(e["vehicle_id"])]
        unmatched = [e for e in extra if not votes.get(e["vehicle_id"])]
        wrong = [(truth[g].cls, "not in view" if not e["valid"] else e["light_heavy"]) for g, e in matched.items()
                 if not (e["valid"] and (e["light_heavy"] == "heavy") == truth[g].heavy)]
        extra_rows.append((name, len(extra), sum(not e["valid"] for e in second), sum(e["valid"] for e in second),
                           sum(not e["valid"] for e in unmatched), sum(e["valid"] for e in unmatched),
                           ", ".join(f"{c} as {w}" for c, w in wrong) or "-"))
    print(f"\nTable 2: end to end from video (the defaults), {args.video_vehicles} vehicles per set-up, "
          f"scene seed {args.video_seed}, resolution x{args.video_scale:g}, traffic {np.median(flows):.0f} vehicles/h "
          f"over the 4 lanes (median over set-ups; --video-mean-gap {args.video_mean_gap:g} s)\n")
    print_table(["set-up", "found", "found of those seen apart", "reported", "light correct", "heavy correct", "mean", "MAE W (m)", "MAE H (m)",
                 "MAE L (m)", "ms per frame", "naive 2-D light / heavy (oracle threshold)"], rows)
    print("\nTable 3: the reported vehicles beyond one per ground-truth vehicle (a second track of a vehicle "
          "found: not fully in view / with an estimate; a track matching no vehicle (IoU <= 0.5: several "
          "vehicles in one blob): not fully in view / with an estimate), and the found vehicles classified "
          "wrong\n")
    print_table(["set-up", "extra", "2nd track, not in view", "2nd track, estimated", "no match, not in view",
                 "no match, estimated", "wrong"], extra_rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--vehicles", type=int, default=60)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--step", type=int, default=2)
    parser.add_argument("--noise", type=float, nargs="+", default=[0.0, 1.0, 2.0])
    parser.add_argument("--video-vehicles", type=int, default=0)
    parser.add_argument("--video-setups", nargs="+", default=["mast_high", "gantry"], choices=sorted(VIDEO_SETUPS),
                        metavar="NAME", help="of " + ", ".join(sorted(VIDEO_SETUPS)))
    parser.add_argument("--video-seed", type=int, default=None, help="the video scenes' seed (default: --seed + 100)")
    parser.add_argument("--video-set", nargs="+", default=[], metavar="NAME=VALUE",
                        help="pipeline parameters other than the defaults (measure_vehicles' keywords)")
    parser.add_argument("--video-scale", type=float, default=1.0,
                        help="render the video scenes at this multiple of the set-ups' resolution (960x540)")
    parser.add_argument("--video-class-mix", nargs="+", default=None, metavar="CLASS=SHARE",
                        help="the video scenes' class mix (default: the generator's; e.g. more heavies)")
    parser.add_argument("--video-mean-gap", type=float, default=DEFAULT_MEAN_GAP,
                        help="seconds: the generator's mean time gap between one lane's vehicles beyond its "
                             "minimum (its default gives ~3000 vehicles/h over the 4 lanes, the paper's roads ~500)")
    parser.add_argument("--scene-dir", default=None,
                        help="write the video scenes here and reuse them on later runs (rendering is slow)")
    parser.add_argument("--video-only", action="store_true", help="skip Table 1 (from observations)")
    parser.add_argument("--ablations", action="store_true", help="the ABLATIONS table instead of METHODS")
    args = parser.parse_args()
    args.video_set = {name: float(value) if "." in value else int(value)
                      for name, value in (item.split("=", 1) for item in args.video_set)}
    if args.video_class_mix is not None:
        args.video_class_mix = {c: float(share) for c, share in (item.split("=", 1) for item in args.video_class_mix)}
    if args.video_seed is None:
        args.video_seed = args.seed + 100
    if not args.video_only:
        from_observations(args)
    if args.video_vehicles > 0:
        from_video(args)


if __name__ == "__main__":
    main()
