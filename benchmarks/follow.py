"""Single-object tracking through partial occlusion on PETS09-S2L1: OTB one-pass evaluation of
single-object trackers initialised with a box (the job of OpenCV's CSRT/KCF/MIL).

Sequences. Single-object segments are cut from PETS09-S2L1 (vtest.avi) with its MOT15 ground
truth (data/pets09-s2l1/gt.txt; GT rows with confidence 0 are not targets, but their boxes still
occlude). Depth order comes from the boxes' bottom edges: of two overlapping people, the one whose
box reaches lower in the image stands nearer the camera and is in front. The occluded fraction of
a target in a frame is the fraction of its box covered by the union of the boxes in front of it.
The selection rule, per person id, over each run of consecutive frames in which it is annotated
with confidence 1 and its box lies inside the image (at most 2 px outside any border):

* an occlusion event is a maximal stretch of frames with occluded fraction >= OCCLUDED (0.25) --
  stretches separated by fewer than MERGE_GAP (5) frames are one event -- whose peak fraction
  stays below FULL (0.9, partial occlusion) and whose length is at least MIN_EVENT (3) frames;
* an occluded segment starts PRE (10) to PRE_MAX (20) frames before an event -- the latest such
  frame that is clean (fraction < CLEAN, 0.05), so the tracker starts on an unoccluded view, with
  no occluded frame between it and the event -- and ends POST (20) frames after the event (or
  after the last of the events that start within that span, which then belong to the same
  segment), or where the run ends; segments shorter than MIN_LENGTH (30) frames are dropped;
* a clean segment is, per person, the longest stretch of frames with fraction < CLEAN
  throughout, cut to at most CLEAN_LENGTH (80) frames from its start, kept if at least
  MIN_LENGTH long.

Occluded segments may hold occluded frames that are not events (a full occlusion, a short
overlap) in their PRE or POST frames; every frame with fraction >= OCCLUDED counts as occluded.

Protocol (OTB one-pass): each tracker is initialised on the GT box of the segment's first frame
and never re-initialised; frames are decoded once into memory, so timing excludes decoding; the
first frame is not scored. A tracker that reports ok = False scores that frame as lost.

Metrics, per segment, then averaged over segments (each segment counts once):

* success AUC: the mean over the IoU thresholds 0, 0.05, ..., 1 (OTB's 21) of the fraction of
  frames whose IoU with the GT box exceeds the threshold (about the mean IoU);
* precision@20: the fraction of frames whose box centre is within 20 px of the GT centre;
* failure rate: the fraction of frames with IoU = 0 (the box does not touch the target) or no
  box;
* the same three over the occluded frames only (fraction >= OCCLUDED) and over the recovery
  frames (the POST frames after each event, less those that are occluded), on the occluded
  segments;
* ms/frame: the median over all scored frames of the time of one update() call, as the calling
  thread's CPU time (robust when other jobs share the cores) and as wall time, with OpenCV
  (cv2.setNumThreads(1)) and NumPy (OMP/OpenBLAS/MKL_NUM_THREADS=1) on one thread.

Peers. OpenCV's CSRT and KCF (opencv-contrib) and MIL with their default parameters; KCF also with
detect_thresh 0.1 (its default 0.5 makes it declare the target lost within ~8 frames on most
segments -- its peak response on walking people falls below 0.5 -- after which it never moves
again: clean-segment AUC 0.05 at 0.5, 0.25 at 0.3, 0.35 at 0.2, 0.50 at 0.1; the row shows KCF at
its best of those). And the paper's conventional color-histogram particle filter (part-based-
graphical-model-pf.txt sections 2-3.2, Nummiaro et al.) written here in vectorised NumPy
(NumpyColorPF): state (cx, cy, h, w) with the previous state for the second-order AR dynamics of
eq. 13, SIR with selective resampling when N_eff (eq. 7) <= 0.5 N (systematic), the weighted-mean
estimate of eq. 8, the 16 x 4 x 4 HSV histogram of the box (OpenCV HSV_FULL, binned as
vtrack.image.hsv_bins), the Bhattacharyya coefficient (eq. 10) and the likelihood of eq. 11 with sigma a
parameter; the template is the histogram of the init box, never updated. Per frame it converts only
the region holding every particle's box, once, and counts each particle's box with np.bincount over
its slice of the region's bin indices. With kernel=True (vtrack's default histogram) the counts are
Nummiaro et al.'s Epanechnikov weights, a row term minus a column term, one broadcast subtraction
and one weighted np.bincount per box (equal to vtrack.image.hsv_histogram(kernel=True) within
2e-15); the unweighted filter is the one the accuracy tables' "NumPy color PF" rows run. The
particle filters run at several seeds; tables give the
mean over seeds and the spread (min-max). vtrack's color and part-based trackers join as rows of
trackers() (a name -> factory(seed) mapping; a tracker has OpenCV's init(frame, box) /
update(frame) -> (ok, box)) and of speed_trackers() (factory(n_particles, seed) and the NumPy row
with the same histogram it is compared with) for the table of time against N.

The NumPy filter's noise U of eq. 13 is N(0, diag(2, 2, 0.2, 0.1)^2) px on (cx, cy, h, w): the
paper gives no value. Measured on these segments (N = 30, sigma = 0.2, seeds 0-2; success AUC on
the occluded / clean segments): U std (3, 2, 1, 0.5) 0.355 / 0.311; (3, 2, 0.5, 0.25) 0.392 /
0.332; (2, 2, 0.2, 0.1) 0.438 / 0.394; (4, 3, 0.2, 0.1) 0.440 / 0.398; (3, 2, 0, 0) 0.463 / 0.452.
Eq. 13 makes the size's velocity a random walk, and a normalised color histogram barely
penalises a box that grows over the background or shrinks inside the person, so sizes drift (h
reached 1046 px with (3, 2, 1, 0.5)); a small size noise is kept rather than none because the
paper's state includes the size. The two readings of eq. 11's sigma at the same settings: sigma =
0.2 against sigma^2 = 0.2 (sigma = 0.447), 0.355 / 0.311 vs 0.257 / 0.175; 0.392 / 0.332 vs 0.270
/ 0.227; 0.438 / 0.394 vs 0.291 / 0.252; 0.440 / 0.398 vs 0.251 / 0.206; 0.463 / 0.452 vs 0.294
/ 0.267 -- sigma = 0.2 tracks better at every setting: with sigma^2 = 0.2 the likelihood
exp(-2.5 d^2) hardly separates particles (rho from 0.6 to 0.9 changes the weight by 2.1x, against
42x with sigma = 0.2), so the cloud diffuses.

Result (this script: 23 occluded and 18 clean segments; particle filters N = 30, seeds 0-4, mean
(min-max); 2 cores shared with other jobs, so wall times are inflated and CPU times are the ones to
compare). Success AUC / precision@20 / failure rate on the occluded segments, the clean ones, the
occluded frames and the recovery frames; CPU ms per frame:

| tracker | occluded seg. | clean seg. | occluded frames | recovery | ms |
|---|---|---|---|---|---|
| OpenCV CSRT | 0.492 / 0.673 / 0.280 | 0.542 / 0.838 / 0.124 | 0.480 / 0.641 / 0.217 | 0.403 / 0.587 / 0.399 | 25.6 |
| OpenCV KCF | 0.136 / 0.192 / 0.801 | 0.049 / 0.067 / 0.931 | 0.087 / 0.124 / 0.863 | 0.059 / 0.098 / 0.902 | 1.3 |
| OpenCV KCF, detect_thresh 0.1 | 0.363 / 0.551 / 0.390 | 0.496 / 0.793 / 0.180 | 0.368 / 0.567 / 0.318 | 0.257 / 0.414 / 0.547 | 2.5 |
| OpenCV MIL | 0.358 / 0.492 / 0.426 | 0.466 / 0.734 / 0.235 | 0.346 / 0.505 / 0.350 | 0.246 / 0.349 / 0.581 | 33.3 |
| NumPy color PF, sigma = 0.2 | 0.430 (0.41-0.45) / 0.636 / 0.164 | 0.393 (0.37-0.41) / 0.572 / 0.148 | 0.459 (0.43-0.50) / 0.622 / 0.090 | 0.361 (0.31-0.39) / 0.544 / 0.250 | 0.63 |
| NumPy color PF, sigma^2 = 0.2 | 0.298 (0.25-0.32) / 0.480 / 0.285 | 0.258 (0.25-0.27) / 0.356 / 0.338 | 0.328 (0.22-0.40) / 0.491 / 0.216 | 0.229 (0.19-0.27) / 0.356 / 0.384 | 1.05 |
| NumPy color PF, sigma = 0.2, kernel | 0.480 (0.47-0.49) / 0.716 / 0.115 | 0.415 (0.38-0.46) / 0.674 / 0.130 | 0.485 (0.48-0.49) / 0.662 / 0.058 | 0.428 (0.41-0.44) / 0.661 / 0.177 | 1.31 |
| vtrack color PF, N = 30 | 0.502 (0.48-0.53) / 0.727 / 0.123 | 0.474 (0.46-0.49) / 0.709 / 0.141 | 0.507 (0.50-0.52) / 0.664 / 0.063 | 0.445 (0.40-0.49) / 0.656 / 0.193 | 0.04 |
| vtrack part-based PF, 2 x 15 | 0.506 (0.46-0.54) / 0.759 / 0.123 | 0.472 (0.45-0.49) / 0.720 / 0.128 | 0.528 (0.50-0.55) / 0.749 / 0.073 | 0.452 (0.39-0.51) / 0.680 / 0.186 | 0.03 |
| vtrack part-based PF, 2 x 30 | 0.540 (0.52-0.57) / 0.771 / 0.114 | 0.497 (0.48-0.51) / 0.739 / 0.128 | 0.565 (0.51-0.60) / 0.777 / 0.052 | 0.481 (0.46-0.51) / 0.688 / 0.180 | 0.04 |

(vtrack rows: the run that added them, the OpenCV and NumPy rows unchanged within 0.01 in it; the
ms of the NumPy kernel row: the run after issue 11's first speed work; of the vtrack rows: the run
`--figure "" --trackers vtrack --speed-particles` after its second (colorspeed2), whose accuracy
figures were, as the first's, the same to the last digit.)
The bar of issue 11: on the occluded segments the part-based PF with 30 particles per part beats
the conventional PF (0.540 vs 0.502) and every OpenCV tracker (CSRT 0.492), and is not worse on
the clean ones (0.497 vs 0.474); with 15 per part it ties the conventional PF (0.506 / 0.472 vs
0.502 / 0.474, within the seeds' spread). Per frame at 30 per part: 0.04 ms CPU (<= 1 ms: met).
Speed: the colour PF against the NumPy filter with the same histogram at the same N (issue 11 asks
>= 10x). Time table, seed 0, CPU ms per frame, two runs of `--figure "" --trackers NONE --seeds 0
--speed-particles 30 90 210` on the loaded machine (an AMD EPYC, Zen 5 with AVX-512; NumPy /
vtrack, ratio), after issue 11's second speed session (colorspeed2, below):

| histogram | N = 30 | N = 90 | N = 210 |
|---|---|---|---|
| kernel-weighted (vtrack's default), run 1 | 0.552 / 0.038, 14.5x | 1.434 / 0.080, 17.9x | 3.054 / 0.152, 20.1x |
| kernel-weighted, run 2 | 0.538 / 0.037, 14.5x | 1.391 / 0.078, 17.8x | 2.986 / 0.149, 20.1x |
| unweighted, run 1 | 0.340 / 0.026, 12.9x | 0.779 / 0.054, 14.5x | 1.606 / 0.106, 15.1x |
| unweighted, run 2 | 0.335 / 0.026, 12.8x | 0.788 / 0.053, 14.8x | 1.625 / 0.104, 15.6x |
| part-based 2 x N (vs NumPy kernel at N), runs 1 / 2 | 0.043 / 0.042, 12.9x / 13.0x | 0.097 / 0.096, 14.8x / 14.6x | 0.193 / 0.190, 15.8x / 15.7x |

The bar is met at every N, for the default filter (14.5-20x) and the unweighted one (12.8-15.6x).
In the same session main's filter measured 7.7x / 9.6x / 10.8x and 7.4x / 9.3x / 10.5x (kernel),
6.7x / 8.1x / 8.6x and 6.9x / 8.1x / 8.4x (unweighted), 7.4x / 8.0x / 8.3x and 6.9x / 7.6x / 7.9x
(part-based) at N = 30 / 90 / 210; the NumPy rows the same within 5 %. The first session's table
(another day's load, NumPy then ~2x slower):

| histogram | N = 30 | N = 90 | N = 210 |
|---|---|---|---|
| kernel-weighted (vtrack's default), run 1 | 1.17 / 0.16, 7.2x | 3.38 / 0.34, 10.0x | 6.17 / 0.65, 9.5x |
| kernel-weighted, run 2 | 1.14 / 0.17, 6.7x | 3.41 / 0.33, 10.3x | 6.57 / 0.53, 12.4x |
| unweighted, run 1 | 0.75 / 0.11, 6.7x | 1.73 / 0.21, 8.3x | 2.84 / 0.36, 7.9x |
| unweighted, run 2 | 0.73 / 0.10, 7.0x | 1.40 / 0.19, 7.2x | 3.05 / 0.38, 7.9x |
| part-based 2 x N (vs NumPy kernel at N), runs 1 / 2 | 0.15 / 0.14, 7.7x / 8.4x | 0.37 / 0.31, 9.1x / 10.9x | 0.70 / 0.63, 8.8x / 10.4x |

It met the bar for the default filter at N = 90 and 210 (10-12x) and not at N = 30 (7x); the
unweighted filter was at 7-8x. Before issue 11's speed work the table compared vtrack's
kernel-weighted filter with the unweighted NumPy filter (unfair to vtrack: NumPy's weights cost it
1.5-2.2x) and vtrack took 0.20 / 0.49 / 1.03 ms (kernel) and 0.11 / 0.18 / 0.33 ms (unweighted)
at N = 30 / 90 / 210. What changed, measured with benchmarks/cpp/color_micro.cpp (the filter on
150 frames of person 15, thread CPU time, medians; the machine's noise is ~ +-7 %) and perf; every
step keeps the histograms and the tracks (boxes equal to 1e-12 on every segment; the accuracy
tables above are unchanged to the last digit):

* kernel-weighted histograms were counted per box and pixel (a double weight each; perf: 3/4 of
  the library's time in a kernel-weighted update); they are now updated from box to box like the unweighted counts,
  through four per-bin moments of the pixels' coordinates (count, sum x, sum y, sum x^2 + y^2:
  the Epanechnikov weight is a quadratic in them; image/color_histogram.cpp's PixelMoments, exact
  integers in doubles): 0.232 -> 0.190 ms per update at N = 30, 1.10 -> 0.75 at N = 210;
* the moments as one 32-byte vector per bin, in two copies by the parity of row + column (perf:
  the stores of neighbouring same-bin pixels waited on each other), rho over the template's
  non-empty bins only, the total weight in closed form: 244 -> 178 us (color_micro), 0.154 /
  0.67 ms;
* the boxes counted in a greedy chain (each next box the cheapest from the last among the next 64
  in Morton order) rather than Morton order alone, which jumps between quadrants of the cloud and
  counts those boxes afresh: 50.9k -> 38.7k pixel updates per frame at N = 30, 262k -> 170k at
  N = 210; 0.143 / 0.51 ms;
* the unweighted counts' strips in two copies by parity too: unweighted update at N = 210 400 ->
  377 us (color_micro, medians of three runs each; at N = 30 within the noise).

Tried and dropped (color_micro, no gain beyond the noise): four copies of the moments instead of
two; a per-column table of (1, x, 0, x^2) instead of building each pixel's vector; skipping pixels
whose bin the template lacks (slower: the branch mispredicts); a greedy window of 16 (11 % more
pixels at N = 210, as fast). Where an update's time goes now (N = 30, kernel, ~165 us in
color_micro): quantising the region the cloud covers, HsvBinImage::assign (~12900 pixels at ~2.6
ns, 35-45 us with the new frame cold in cache), the moment updates (~39k at ~2.5 ns, ~60 %),
the rest (ordering, rho, the SIR step, 3 us of Python call) small. Earlier work on the quantiser
(same machine): quantising only each row's span of the boxes (17 % fewer pixels: not worth it), an
AVX2 quantise_row with gathers for the division tables (bit-exact, 1.1x on this AMD EPYC, whose
gathers are slow) and one that does the tables' divisions exactly in registers (float quotient
corrected by the integer remainder; bit-exact over all 2^24 colours, 1.35-1.7x on the conversion
but 10 % on a whole update, 116 -> 105 us): both dropped then; with the cheaper counting the
conversion is now a larger share (a third of a kernel-weighted update at N = 30), so that
vectorised quantiser is the next thing to measure for the N = 30 bar.

2026-11-25 (session 8, an AVX-512 Xeon; other sessions' machines differ, so compare ratios within
one run only): perf of an update on the frames decoded beforehand (as this benchmark feeds them)
put 36 % of it on the first load of each region row of the frame (DRAM: each row is a new
stretch a stride away, which the hardware prefetcher does not foresee). HsvBinImage::assign now
prefetches the row four ahead (hint T0; 2 or 8 rows ahead and hint T1 were no better in
color_micro). One run of `--figure "" --trackers NONE --seeds 0 --speed-particles 30 90` before
and after (CPU ms per frame, NumPy kernel filter / vtrack default, ratio): N = 30 0.80 / 0.14
(5.7x) -> 0.69 / 0.09 (7.7x); N = 90 1.89 / 0.24 (7.8x) -> 1.72 / 0.18 (9.5x); the unweighted
filter at N = 30 4.2x -> 7.7x; AUCs identical. The bar (10x) is still not met at N = 30: what is
left of an update is the moment counting (~52 %) and the quantiser (~39 %).

Second speed session (colorspeed2, the AMD EPYC above). color_micro's update (medians of 3-7
alternating runs of the builds before and after each step) and, where named, the coefficients
alone on the clouds the filter scored (dumped from its likelihood); every step keeps the
histograms (bins bit-exact; counts and moments exact integers whatever the order or copy they
are summed in), and only the vectorised rho changes the tracks, by summing bins in another order
(rho within 1e-15; colour PF boxes within 5.7e-13 of before on every segment, seeds 0-4, N = 30
and 90; part-based within 1.3e-12); the accuracy tables are unchanged to the last digit:

* an AVX-512 quantiser (image/color_histogram.cpp's RowQuantiser, BW + VBMI; the scalar loop
  stays as the fallback): 16 pixels per vector, B, G, R picked by vpermb, the reciprocal tables'
  entries computed in the lanes (a correctly rounded float quotient rounds to each entry: all 2^24
  colours tested), each row's tail masked rather than a scalar loop: quantising a hot frame 16.4
  -> 4.5 us (1.27 -> 0.35 ns/px), update 86.3 -> 75.6 us (kernel), 50.9 -> 44.6 us (unweighted);
* strips walked along their longer side (most are 1-6 px wide and a box tall: per-row set-up on
  3100 of 4559 strip rows per frame): 75.9 -> 71.1 us; the unweighted counts walked the same way,
  45.5 -> 44.7 us (coefficients 24.9 -> 22.4 us);
* rho over the template's bins four at a time (their weights transposed into one vector, vector
  square roots): 70.4 -> 63.1 us (N = 210: 296 -> 254 us);
* the row prefetch covering every cache line of the row (64-byte steps from its first byte missed
  the last line whenever the row started mid-line; perf put 30 % of the quantiser on that line's
  load): kernel 62.1 -> 54.7 us, unweighted 44.6 -> 39.1 us;
* the quantiser's loads reading only their pixels' bytes: the tail as the 64 bytes ending with the
  row's last byte (a masked load still fetches every line of its 64 bytes, and the line after the
  row waited on DRAM), the 16-pixel loads as 32 + 16 bytes: kernel 54.9 -> 49.9 us, unweighted
  37.5 -> 32.6 us;
* counting_order's window costs in one vectorised int32 loop, counted rects masked instead of
  erased from a list: kernel 49.6 -> 48.3 us, unweighted 33.7 -> 32.1 us; N = 210 233 -> 198 us
  and 173 -> 134 us (it was a third of the unweighted coefficients there);
* four copies of the per-bin sums, pixel (x, y) in copy (x + y) mod 4 (was two, by parity):
  kernel 50.1 -> 46.7 us, unweighted 32.1 -> 29.0 us (eight copies: 46 -> 54 us, 31 -> 34 us).

In all, color_micro's update at N = 30 / 90 / 210 (medians of 3 alternating runs of main and this
branch): kernel 83.3 / 162.5 / 324.5 -> 43.4 / 86.6 / 181.2 us, unweighted 50.1 / 113.1 / 205.4 ->
27.8 / 64.9 / 120.0 us. Tried and dropped: prefetching 8 or 16 rows ahead, every row up front, or
with hints T1/T2 (no better; the frame, cold in cache, still costs ~8-10 us of an update: perf puts
the quantiser's remaining time on the prefetches and loads of the frame, memory-level parallelism
rather than arithmetic); starting the greedy chain elsewhere (the smallest box, the most isolated,
the most central) or restoring a central box's histogram for outliers (offline on the dumped
clouds: no fewer pixels; a minimum spanning tree would count 13 % fewer at N = 30, 23 % at N =
210, but with snapshots to restore and an O(N^2) tree). What is left at N = 30: the frame's
memory wait, the box-to-box counting (~38.7k pixel updates per frame for 30 boxes, 4.8 of them
counted afresh) and ~6-8 us of fixed cost per update (Python call, SIR step, ordering).

The NumPy color PF (sigma = 0.2, seed 0) at N = 30 / 90 / 210: 0.64 / 1.36 / 2.75 CPU ms per
frame, AUC occluded 0.439 / 0.454 / 0.473, clean 0.407 / 0.438 / 0.435. CSRT is the tracker to
beat on both kinds of segment; the color PF loses less than CSRT on the occluded frames
themselves (failure 0.09 against 0.22) but recovers worse and drifts on clean segments (a color
histogram does not pin the box's size or position within a uniformly colored region).

vtrack's trackers (vtrack.ColorParticleTracker, vtrack.PartParticleTracker; docs/follow.md). Their
defaults were tuned on the even-indexed segments of find_segments' list only (12 occluded, 9
clean; success AUC occluded / clean, mean over seeds 0-2 unless noted); every table reports all
segments. Colour PF, N = 30: the first defaults (noise (0.08, 0.03, 0.005, 0.005) of the box,
scales [0.5, 2], sigma 0.2, unweighted) 0.430 / 0.427; size noise 0 0.456 / 0.470, 0.002 0.426 /
0.455, 0.01 0.372 / 0.414; position noise (0.05, 0.02) 0.428 / 0.412, (0.12, 0.05) 0.448 / 0.407;
kernel-weighted 0.467 / 0.440; sigma^2 = 0.2 (sigma 0.447) 0.238 / 0.277, sigma 0.1 0.408 / 0.449;
scales [0.8, 1.25] 0.463 / 0.478, with size noise 0.002 0.435 / 0.484, and kernel-weighted 0.501 /
0.504 (seeds 0-4: 0.504 / 0.499; size noise 0: 0.497 / 0.513) -- the defaults: noise (0.08, 0.03,
0.002, 0.002), scales [0.8, 1.25], kernel on, sigma 0.2 (sigma = 0.2 confirmed over sigma^2 = 0.2
with this filter too). A little size noise is kept, rather than none, so that the box can follow
the object's scale. Part-based PF at those defaults (seeds 0-4): 15 per part 0.494 / 0.491, 30 per
part 0.552 / 0.529; position noise (0.05, 0.02) 0.449 / 0.455, (0.12, 0.05) 0.466 / 0.492 (15 per
part); sigma 0.15 0.484 / 0.515; message weights (30 per part) eq. 26 "neighbour" 0.552 / 0.529,
eq. 20 "target" 0.540 / 0.540, eq. 19 "product" 0.533 / 0.541 (15 per part: 0.494 / 0.491, 0.518 /
0.526, -); occlusion_threshold 0, 0.6, 0.75, 0.85 (15 per part, unweighted, seeds 0-2): 0.471 /
0.476, 0.466 / 0.482, 0.456 / 0.474, 0.470 / 0.479 -- no setting stands out, 0.75 is kept for the
synthetic scenes, where it judges every hidden frame occluded. The colour PF at N = 60 (0.496 /
0.529) does not reach the part-based PF at 2 x 30. The colour PF's ess_threshold (seeds 0-4,
defaults otherwise): 0.2 0.448 / 0.484, 0.5 0.504 / 0.499, 1.0 0.498 / 0.524 -- 0.5 kept (no
difference in time either).

OpenCV contrib. CSRT and KCF live in opencv-contrib, and opencv-contrib-python-headless ships the
same top-level module cv2 as the opencv-python-headless the project installs: pip would install
both into site-packages with the later one's files over the other's, and uninstalling either
breaks cv2. `make bench` therefore installs the contrib wheel of the same version with
`pip install --no-deps --target .venv/opencv-contrib`, and this script puts that folder first on
sys.path before importing cv2 (a superset of the main wheel's cv2, so nothing else changes). vtrack
itself links the system OpenCV, not cv2, so it is unaffected. Without the folder, CSRT and KCF
rows are skipped.

    python benchmarks/follow.py [--video PATH] [--gt PATH] [--seeds 0 1 2 3 4] [--particles 30]
                                [--trackers NAME ...] [--speed-particles 30 90 210]
                                [--segments-only] [--figure PATH] [--scenes-only]
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from statistics import median
from typing import Callable, Dict, List, Optional, Tuple

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):  # one thread
    os.environ.setdefault(_var, "1")
CONTRIB = Path(sys.prefix) / "opencv-contrib"
if CONTRIB.is_dir():  # before any import of cv2: see "OpenCV contrib" above
    sys.path.insert(0, str(CONTRIB))

import cv2  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(__file__))
from _table import print_table  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
IMAGE_W, IMAGE_H = 768, 576

# Segment selection (module docstring).
OCCLUDED, FULL, CLEAN = 0.25, 0.9, 0.05
MERGE_GAP, MIN_EVENT, PRE, PRE_MAX, POST = 5, 3, 10, 20, 20
MIN_LENGTH, CLEAN_LENGTH = 30, 80
SUCCESS_THRESHOLDS = np.linspace(0.0, 1.0, 21)


def default_video() -> str:
    return os.environ.get("VTRACK_VIDEO", str(Path.home() / ".cache" / "vtrack" / "vtest.avi"))


def default_gt() -> str:
    return os.environ.get("VTRACK_PETS_GT", str(REPO / "data" / "pets09-s2l1" / "gt.txt"))


# ---- segments ------------------------------------------------------------------------------------

@dataclass
class Segment:
    person: int
    kind: str                 # "occluded" or "clean"
    frames: np.ndarray        # 1-based frame numbers, consecutive
    boxes: np.ndarray         # (len, 4) GT x, y, w, h
    fraction: np.ndarray      # (len,) occluded fraction
    recovery: np.ndarray      # (len,) bool: within POST frames after an occlusion event

    @property
    def occluded(self) -> np.ndarray:
        return self.fraction >= OCCLUDED


def occluded_fraction(box, others) -> float:
    """Fraction of `box` (x, y, w, h) covered by the union of the boxes `others`, exactly on a
    1/4-pixel grid of the box."""
    x, y, w, h = box
    if len(others) == 0 or w <= 0 or h <= 0:
        return 0.0
    gx = x + (np.arange(int(np.ceil(4 * w))) + 0.5) / 4
    gy = y + (np.arange(int(np.ceil(4 * h))) + 0.5) / 4
    covered = np.zeros((len(gy), len(gx)), bool)
    for ox, oy, ow, oh in others:
        cols = (gx >= ox) & (gx < ox + ow)
        rows = (gy >= oy) & (gy < oy + oh)
        covered |= rows[:, None] & cols[None, :]
    return float(covered.mean())


def gt_tables(gt: np.ndarray):
    """Per person id: {frame: box}, its confidence, and the per-frame occluded fraction."""
    by_frame: Dict[int, np.ndarray] = {}
    for f in np.unique(gt[:, 0]).astype(int):
        by_frame[f] = gt[gt[:, 0] == f]
    tracks: Dict[int, Dict[int, Tuple[np.ndarray, float]]] = {}
    for f, rows in by_frame.items():
        bottoms = rows[:, 3] + rows[:, 5]
        for i, r in enumerate(rows):
            front = [rows[j, 2:6] for j in range(len(rows)) if j != i and bottoms[j] > bottoms[i]]
            tracks.setdefault(int(r[1]), {})[f] = (r[2:6].copy(), float(r[6]),
                                                   occluded_fraction(r[2:6], front))
    return tracks


def inside_image(box, margin: float = 2.0) -> bool:
    x, y, w, h = box
    return x >= -margin and y >= -margin and x + w <= IMAGE_W + margin and y + h <= IMAGE_H + margin


def runs(track) -> List[List[int]]:
    """Maximal runs of consecutive frames with confidence 1 and the box inside the image."""
    out, cur = [], []
    for f in sorted(track):
        box, conf, _ = track[f]
        good = conf > 0 and inside_image(box)
        if good and cur and f == cur[-1] + 1:
            cur.append(f)
        else:
            if cur:
                out.append(cur)
            cur = [f] if good else []
    if cur:
        out.append(cur)
    return out


def events(frac: np.ndarray) -> List[Tuple[int, int]]:
    """(start, end) index pairs (end exclusive) of the occlusion events of a run."""
    idx = np.flatnonzero(frac >= OCCLUDED)
    spans: List[List[int]] = []
    for i in idx:
        if spans and i - spans[-1][1] < MERGE_GAP:
            spans[-1][1] = i + 1
        elif not spans or i >= spans[-1][1]:
            spans.append([i, i + 1])
    return [(a, b) for a, b in spans if b - a >= MIN_EVENT and frac[a:b].max() < FULL]


def make_segment(pid, kind, track, frames, recovery) -> Segment:
    boxes = np.array([track[f][0] for f in frames])
    frac = np.array([track[f][2] for f in frames])
    return Segment(pid, kind, np.asarray(frames), boxes, frac, np.asarray(recovery, bool))


def find_segments(gt: np.ndarray) -> List[Segment]:
    """The occluded and clean segments of the selection rule (module docstring)."""
    segments = []
    for pid, track in sorted(gt_tables(gt).items()):
        best_clean: List[int] = []
        for run in runs(track):
            frac = np.array([track[f][2] for f in run])
            evs = events(frac)
            i = 0
            while i < len(evs):
                a, b = evs[i]
                end = min(b + POST, len(run))
                j = i + 1
                while j < len(evs) and evs[j][0] < end:  # the next event starts inside: merge
                    end = min(evs[j][1] + POST, len(run))
                    j += 1
                # The latest start PRE..PRE_MAX frames before the event on a clean frame, with no
                # occluded frame between it and the event.
                starts = [st for st in range(a - PRE, a - PRE_MAX - 1, -1)
                          if st >= 0 and frac[st] < CLEAN and frac[st:a].max() < OCCLUDED]
                start = starts[0] if starts else None
                if start is not None and end - start >= MIN_LENGTH:
                    recovery = np.zeros(end - start, bool)
                    for a2, b2 in evs[i:j]:
                        recovery[b2 - start:min(b2 + POST, end) - start] = True
                    recovery &= frac[start:end] < OCCLUDED
                    segments.append(make_segment(pid, "occluded", track, run[start:end], recovery))
                i = j
            # The longest clean stretch of this person.
            clean = frac < CLEAN
            k = 0
            while k < len(run):
                if clean[k]:
                    m = k
                    while m < len(run) and clean[m]:
                        m += 1
                    if m - k > len(best_clean):
                        best_clean = run[k:m]
                    k = m
                else:
                    k += 1
        if len(best_clean) >= MIN_LENGTH:
            frames = best_clean[:CLEAN_LENGTH]
            segments.append(make_segment(pid, "clean", track, frames, np.zeros(len(frames), bool)))
    return segments


def spans_text(frames: np.ndarray, mask: np.ndarray) -> str:
    """'a-b, c-d' ranges of the frames where mask holds."""
    out, start = [], None
    for f, m in zip(list(frames) + [None], list(mask) + [False]):
        if m and start is None:
            start = f
        if not m and start is not None:
            out.append(f"{start}-{prev}" if prev != start else f"{start}")
            start = None
        prev = f
    return ", ".join(out) or "-"


def print_segments(segments: List[Segment]) -> None:
    rows = []
    for s in segments:
        rows.append([s.kind, s.person, f"{s.frames[0]}-{s.frames[-1]}", len(s.frames),
                     spans_text(s.frames, s.occluded), int(s.occluded.sum()),
                     f"{s.fraction.max():.2f}", f"{s.boxes[0, 2]:.0f}x{s.boxes[0, 3]:.0f}"])
    print_table(["kind", "person", "frames", "length", "occluded frames", "n occluded",
                 "max fraction", "init box w x h"], rows)


# ---- metrics -----------------------------------------------------------------------------------

def iou(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise IoU of (N, 4) x, y, w, h boxes; NaN rows (no box) give 0."""
    x0 = np.maximum(a[:, 0], b[:, 0])
    y0 = np.maximum(a[:, 1], b[:, 1])
    x1 = np.minimum(a[:, 0] + a[:, 2], b[:, 0] + b[:, 2])
    y1 = np.minimum(a[:, 1] + a[:, 3], b[:, 1] + b[:, 3])
    inter = np.clip(x1 - x0, 0, None) * np.clip(y1 - y0, 0, None)
    union = a[:, 2] * a[:, 3] + b[:, 2] * b[:, 3] - inter
    out = np.where(union > 0, inter / np.where(union > 0, union, 1), 0.0)
    return np.nan_to_num(out, nan=0.0)


def centre_error(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    d = np.hypot(a[:, 0] + a[:, 2] / 2 - b[:, 0] - b[:, 2] / 2,
                 a[:, 1] + a[:, 3] / 2 - b[:, 1] - b[:, 3] / 2)
    return np.nan_to_num(d, nan=np.inf)


def scores(overlap: np.ndarray, error: np.ndarray) -> Optional[Tuple[float, float, float]]:
    """(success AUC, precision@20, failure rate) of some frames, None when there are none."""
    if len(overlap) == 0:
        return None
    auc = float(np.mean([(overlap > t).mean() for t in SUCCESS_THRESHOLDS]))
    return auc, float((error <= 20.0).mean()), float((overlap <= 0.0).mean())


# ---- the NumPy color-histogram particle filter (the paper's conventional method) ----------------

class NumpyColorPF:
    """Color-histogram SIR particle filter of part-based-graphical-model-pf.txt sections 2-3.2
    (module docstring), vectorised NumPy. OpenCV-like: init(frame, box), update(frame) -> (ok,
    box). `noise` is the standard deviation of U in eq. 13 for (cx, cy, h, w)."""

    def __init__(self, n_particles: int = 30, seed: int = 0, sigma: float = 0.2,
                 noise=(2.0, 2.0, 0.2, 0.1), ess_threshold: float = 0.5, bins=(16, 4, 4),
                 kernel: bool = False):
        self.n = n_particles
        self.kernel = kernel
        self.rng = np.random.default_rng(seed)
        self.sigma = sigma
        self.noise = np.asarray(noise, np.float64)
        self.ess_threshold = ess_threshold
        self.bins = bins
        self.m = bins[0] * bins[1] * bins[2]
        self.lut = self._luts(bins)

    @staticmethod
    def _luts(bins):
        c = np.arange(256)
        return (c * bins[0] // 256 * bins[1] * bins[2], c * bins[1] // 256 * bins[2],
                c * bins[2] // 256)

    def _bin_image(self, frame, x0, y0, x1, y1):
        hsv = cv2.cvtColor(frame[y0:y1, x0:x1], cv2.COLOR_BGR2HSV_FULL)
        lh, ls, lv = self.lut
        return lh[hsv[..., 0]] + ls[hsv[..., 1]] + lv[hsv[..., 2]]

    def _rects(self, states, cols, rows):
        """Clipped integer pixel rects (x0, y0, x1, y1) of (cx, cy, h, w) states, rounded as
        vtrack.image.hsv_histogram rounds boxes."""
        cx, cy, h, w = states.T
        x0 = np.clip(np.floor(cx - w / 2 + 0.5), 0, cols).astype(np.int64)
        x1 = np.clip(np.floor(cx + w / 2 + 0.5), 0, cols).astype(np.int64)
        y0 = np.clip(np.floor(cy - h / 2 + 0.5), 0, rows).astype(np.int64)
        y1 = np.clip(np.floor(cy + h / 2 + 0.5), 0, rows).astype(np.int64)
        return x0, y0, np.maximum(x1, x0), np.maximum(y1, y0)

    def _histograms(self, frame, states):
        """(N, m) normalised histograms of the particles' boxes (all zeros for an empty box)."""
        rows, cols = frame.shape[:2]
        x0, y0, x1, y1 = self._rects(states, cols, rows)
        area = (x1 - x0) * (y1 - y0)
        out = np.zeros((len(states), self.m))
        live = np.flatnonzero(area > 0)
        if len(live) == 0:
            return out
        rx0, ry0 = x0[live].min(), y0[live].min()
        bins = self._bin_image(frame, rx0, ry0, x1[live].max(), y1[live].max())
        # One np.bincount per box over its slice of the region's bin image: measured 5-20x faster
        # than one bincount over the gathered (particle, bin) keys of all boxes, whose index
        # arithmetic costs more than the counting.
        if not self.kernel:
            for i in live:
                out[i] = np.bincount(
                    bins[y0[i] - ry0:y1[i] - ry0, x0[i] - rx0:x1[i] - rx0].ravel(),
                    minlength=self.m)
            out[live] /= area[live, None]
            return out
        # Nummiaro et al.'s Epanechnikov weights, as vtrack.image.hsv_histogram(kernel=True):
        # k = 1 - (dx^2 + dy^2) / a^2 from the pixel centres to the box's centre, a^2 = (w^2 +
        # h^2) / 4: a row term minus a column term, one broadcast subtraction per box. No weight
        # is negative (every pixel centre of a box lies in the box), so the bins are clipped at 0
        # only against rounding, once for all boxes, and each histogram is normalised by its sum.
        cx, cy, h, w = states.T
        a2 = (w * w + h * h) / 4
        ys = np.arange(ry0, y1[live].max()) + 0.5
        xs = np.arange(rx0, x1[live].max()) + 0.5
        for i in live:
            row = 1.0 - (ys[y0[i] - ry0:y1[i] - ry0] - cy[i]) ** 2 / a2[i]
            col = (xs[x0[i] - rx0:x1[i] - rx0] - cx[i]) ** 2 / a2[i]
            out[i] = np.bincount(bins[y0[i] - ry0:y1[i] - ry0, x0[i] - rx0:x1[i] - rx0].ravel(),
                                 weights=(row[:, None] - col).ravel(), minlength=self.m)
        np.maximum(out, 0.0, out=out)
        total = out.sum(axis=1)
        good = total > 0
        out[good] /= total[good, None]
        out[~good] = 0.0
        return out

    def init(self, frame, box):
        x, y, w, h = (float(v) for v in box)
        state = np.array([x + w / 2, y + h / 2, h, w])
        self.q = self._histograms(frame, state[None, :])[0]
        if not self.q.any():
            raise ValueError(f"box {box} has no pixel in the frame")
        self.sqrt_q = np.sqrt(self.q)
        self.x = np.repeat(state[None, :], self.n, axis=0)
        self.x_prev = self.x.copy()
        self.log_w = np.full(self.n, -np.log(self.n))
        return True

    def update(self, frame):
        # Eq. 13: X_k = 2 X_{k-1} - X_{k-2} + U_{k-1}; sizes kept >= 2 px.
        new = 2 * self.x - self.x_prev + self.rng.normal(0.0, 1.0, self.x.shape) * self.noise
        new[:, 2:] = np.maximum(new[:, 2:], 2.0)
        self.x_prev, self.x = self.x, new
        rho = np.sqrt(self._histograms(frame, self.x)) @ self.sqrt_q                      # eq. 10
        log_l = (-np.log(np.sqrt(2 * np.pi) * self.sigma)                                 # eq. 11
                 - (1 - rho) / (2 * self.sigma ** 2))
        self.log_w = self.log_w + log_l                                                  # eq. 5
        self.log_w -= self.log_w.max()
        w = np.exp(self.log_w)
        w /= w.sum()                                                                     # eq. 6
        est = w @ self.x                                                                 # eq. 8
        if 1.0 / np.sum(w ** 2) <= self.ess_threshold * self.n:                          # eq. 7
            u = (self.rng.random() + np.arange(self.n)) / self.n  # systematic resampling
            idx = np.minimum(np.searchsorted(np.cumsum(w), u), self.n - 1)
            self.x, self.x_prev = self.x[idx], self.x_prev[idx]
            self.log_w = np.full(self.n, -np.log(self.n))
        else:
            self.log_w = np.log(w)
        cx, cy, h, w_ = est
        box = (cx - w_ / 2, cy - h / 2, w_, h)
        rows, cols = frame.shape[:2]
        ok = box[0] < cols and box[1] < rows and box[0] + w_ > 0 and box[1] + h > 0
        return ok, box


# ---- trackers ------------------------------------------------------------------------------------

def opencv_tracker(name: str, **params) -> Optional[Callable[[int], object]]:
    """Factory of OpenCV's tracker `name` (CSRT, KCF, MIL) with `params` set on its Params (the
    defaults otherwise), None when this cv2 lacks it."""
    cls = getattr(cv2, f"Tracker{name}", None)
    if cls is None or not hasattr(cls, "create"):
        return None

    class Wrapped:
        def __init__(self):
            p = getattr(cv2, f"Tracker{name}_Params")()
            for key, value in params.items():
                setattr(p, key, value)
            self.t = cls.create(p)

        def init(self, frame, box):
            self.t.init(frame, tuple(int(round(v)) for v in box))

        def update(self, frame):
            ok, box = self.t.update(frame)
            return bool(ok), tuple(float(v) for v in box)

    return lambda seed: Wrapped()


def trackers(particles: int) -> Dict[str, Tuple[Callable[[int], object], bool]]:
    """name -> (factory(seed) -> tracker, seeded). vtrack's trackers join here."""
    out: Dict[str, Tuple[Callable[[int], object], bool]] = {}
    for label, name, params in (("CSRT", "CSRT", {}), ("KCF", "KCF", {}),
                                ("KCF, detect_thresh 0.1", "KCF", {"detect_thresh": 0.1}),
                                ("MIL", "MIL", {})):
        factory = opencv_tracker(name, **params)
        if factory is None:
            print(f"(OpenCV {name} not available in this cv2 {cv2.__version__}: row skipped)")
        else:
            out[f"OpenCV {label}"] = (factory, False)
    vtrack = vtrack_module()
    if vtrack is not None:
        out[f"vtrack color PF, N={particles}"] = (
            lambda seed: vtrack.ColorParticleTracker(n_particles=particles, seed=seed), True)
        out[f"vtrack part-based PF, 2 parts x {particles // 2}"] = (
            lambda seed: vtrack.PartParticleTracker(n_particles=particles // 2, seed=seed), True)
        out[f"vtrack part-based PF, 2 parts x {particles}"] = (
            lambda seed: vtrack.PartParticleTracker(n_particles=particles, seed=seed), True)
    out[f"NumPy color PF, N={particles}, sigma=0.2"] = (
        lambda seed: NumpyColorPF(particles, seed, sigma=0.2), True)
    out[f"NumPy color PF, N={particles}, sigma^2=0.2"] = (
        lambda seed: NumpyColorPF(particles, seed, sigma=0.2 ** 0.5), True)
    out[f"NumPy color PF, N={particles}, sigma=0.2, kernel"] = (
        lambda seed: NumpyColorPF(particles, seed, sigma=0.2, kernel=True), True)
    return out


def speed_trackers() -> Dict[str, Tuple[Callable[[int, int], object], Optional[str]]]:
    """name -> (factory(n_particles, seed), the row it is compared with or None) for the table of
    time against N (the paper's Table 1). vtrack's particle filters join here, each against the
    NumPy filter with the same histogram: kernel-weighted (vtrack's default) or not."""
    out: Dict[str, Tuple[Callable[[int, int], object], Optional[str]]] = {
        "NumPy color PF, sigma=0.2": (lambda n, seed: NumpyColorPF(n, seed, sigma=0.2), None),
        "NumPy color PF, sigma=0.2, kernel": (
            lambda n, seed: NumpyColorPF(n, seed, sigma=0.2, kernel=True), None)}
    vtrack = vtrack_module()
    if vtrack is not None:
        out["vtrack color PF (kernel, the default)"] = (
            lambda n, seed: vtrack.ColorParticleTracker(n_particles=n, seed=seed),
            "NumPy color PF, sigma=0.2, kernel")
        out["vtrack color PF, kernel=False"] = (
            lambda n, seed: vtrack.ColorParticleTracker(n_particles=n, seed=seed, kernel=False),
            "NumPy color PF, sigma=0.2")
        out["vtrack part-based PF, 2 parts, N per part"] = (
            lambda n, seed: vtrack.PartParticleTracker(n_particles=n, seed=seed),
            "NumPy color PF, sigma=0.2, kernel")
    return out


def vtrack_module():
    """The installed vtrack, or None (its rows are then skipped)."""
    try:
        import vtrack
    except ImportError:
        print("(vtrack is not installed: its rows are skipped)")
        return None
    return vtrack


# ---- running -------------------------------------------------------------------------------------

def read_frames(path: str, last: int) -> List[np.ndarray]:
    """Frames 1..last of the video (index k holds frame k + 1)."""
    cap = cv2.VideoCapture(path)
    frames = []
    while len(frames) < last:
        ok, frame = cap.read()
        if not ok:
            break
        frames.append(frame)
    cap.release()
    if len(frames) < last:
        sys.exit(f"{path}: only {len(frames)} frames decoded, the segments need {last}")
    return frames


def run_segment(tracker, frames: List[np.ndarray], seg: Segment):
    """(boxes (len - 1, 4) for the scored frames, [(wall, CPU) seconds of each update])."""
    tracker.init(frames[seg.frames[0] - 1], tuple(seg.boxes[0]))
    boxes, times = [], []
    for f in seg.frames[1:]:
        frame = frames[f - 1]
        wall, cpu = time.perf_counter(), time.thread_time()
        ok, box = tracker.update(frame)
        times.append((time.perf_counter() - wall, time.thread_time() - cpu))
        boxes.append(box if ok else (np.nan,) * 4)
    return np.asarray(boxes, np.float64), times


def segment_scores(seg: Segment, boxes: np.ndarray):
    """{"all" | "occluded" | "recovery": (auc, precision, failure) or None}."""
    gt = seg.boxes[1:]
    overlap, error = iou(boxes, gt), centre_error(boxes, gt)
    return {"all": scores(overlap, error),
            "occluded": scores(overlap[seg.occluded[1:]], error[seg.occluded[1:]]),
            "recovery": scores(overlap[seg.recovery[1:]], error[seg.recovery[1:]])}


def evaluate(factory, seeds, frames, segments):
    """Per seed: {(kind, subset): [per-segment (auc, precision, failure)]}, and all update times."""
    per_seed, times = [], []
    for seed in seeds:
        table: Dict[Tuple[str, str], List[Tuple[float, float, float]]] = {}
        for seg in segments:
            boxes, t = run_segment(factory(seed), frames, seg)
            times += t
            for subset, value in segment_scores(seg, boxes).items():
                if value is not None:
                    table.setdefault((seg.kind, subset), []).append(value)
        per_seed.append(table)
    return per_seed, times


def cell(per_seed, key, metric: int) -> str:
    """Mean over segments of one metric, then mean (min-max) over seeds."""
    values = [np.mean([v[metric] for v in t[key]]) for t in per_seed if key in t]
    if not values:
        return "-"
    if len(values) == 1:
        return f"{values[0]:.3f}"
    return f"{np.mean(values):.3f} ({min(values):.2f}-{max(values):.2f})"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--video", default=default_video())
    parser.add_argument("--gt", default=default_gt())
    parser.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2, 3, 4])
    parser.add_argument("--particles", type=int, default=30)
    parser.add_argument("--trackers", nargs="*",
                        help="only the rows whose name contains one of these")
    parser.add_argument("--segments-only", action="store_true", help="list the segments and stop")
    parser.add_argument("--figure", default="demo-output/follow_occlusion.png",
                        help="the synthetic occlusion figure ('' to skip the synthetic scenes)")
    parser.add_argument("--scenes-only", action="store_true",
                        help="only the synthetic occlusion scenes and their figure")
    parser.add_argument("--speed-particles", type=int, nargs="*", default=[30, 90, 210],
                        help="particle counts of the time table (none: skip it)")
    args = parser.parse_args()
    cv2.setNumThreads(1)
    if args.figure and vtrack_module() is not None:
        keep = print_scenes(args.seeds)
        scene_figure(keep, args.figure)
        print()
        if args.scenes_only:
            return

    gt = np.loadtxt(args.gt, delimiter=",", ndmin=2)
    segments = find_segments(gt)
    print(f"PETS09-S2L1 single-object segments ({len(segments)}): occluded fraction >= {OCCLUDED} "
          f"counts as occluded; depth order by the boxes' bottom edges")
    print()
    print_segments(segments)
    if args.segments_only:
        return
    frames = read_frames(args.video, int(max(s.frames[-1] for s in segments)))
    print()
    rows_all, rows_occ = [], []
    for name, (factory, seeded) in trackers(args.particles).items():
        if args.trackers and not any(t in name for t in args.trackers):
            continue
        per_seed, times = evaluate(factory, args.seeds if seeded else [0], frames, segments)
        ms = f"{1e3 * median(t[1] for t in times):.2f} / {1e3 * median(t[0] for t in times):.2f}"
        rows_all.append([name, *(cell(per_seed, ("occluded", "all"), i) for i in range(3)),
                         *(cell(per_seed, ("clean", "all"), i) for i in range(3)), ms])
        rows_occ.append([name, *(cell(per_seed, ("occluded", "occluded"), i) for i in range(3)),
                         *(cell(per_seed, ("occluded", "recovery"), i) for i in range(3))])
    n_occ = sum(s.kind == "occluded" for s in segments)
    print(f"Whole segments ({n_occ} occluded, {len(segments) - n_occ} clean); particle filters: "
          f"mean over seeds {args.seeds} (min-max); ms/frame: median CPU / wall time of update(), "
          "one thread")
    print()
    print_table(["tracker", "occluded: AUC", "prec@20", "failure", "clean: AUC", "prec@20",
                 "failure", "ms/frame CPU / wall"], rows_all)
    print()
    print("Occluded segments: the occluded frames only, and the recovery frames (the "
          f"{POST} frames after each occlusion event)")
    print()
    print_table(["tracker", "occluded frames: AUC", "prec@20", "failure", "recovery: AUC",
                 "prec@20", "failure"], rows_occ)
    if args.speed_particles:
        print()
        print_speed(args.speed_particles, frames, segments)


# ---- the synthetic occlusion scene (exact truth of every part) ----------------------------------

SCENES = [("person", "lower"), ("person", "upper"), ("face", "lower"), ("face", "upper")]


def scene_run(layout: str, occlude: str, seed: int, n_parts_particles: int = 30):
    """The part-based and the conventional filter on vtrack.synthetic_occlusion's scene: per frame
    1..n-1 the hidden part's truth centre, the part-based estimate of it, and the conventional
    filter's box (for the same part: the part's box at its place in the filter's box)."""
    import vtrack
    from vtrack.synthetic_occlusion import make_occlusion_scene
    scene = make_occlusion_scene(layout, seed=seed, occlude=occlude, noise_std=4.0)
    parts = vtrack.PartParticleTracker(parts=scene.n_parts, n_particles=n_parts_particles, seed=seed)
    color = vtrack.ColorParticleTracker(seed=seed)
    parts.init(scene.frame(0), scene.boxes[0])
    color.init(scene.frame(0), scene.boxes[0])
    hidden_part = int(np.argmax(scene.occluded_fraction.max(axis=0)))
    x0, y0, w0, h0 = scene.boxes[0]
    px, py, pw, ph = scene.part_boxes[0, hidden_part]
    fx, fy, fw, fh = (px - x0) / w0, (py - y0) / h0, pw / w0, ph / h0  # the part in the box
    rows = []
    for k in range(1, len(scene)):
        frame = scene.frame(k)
        parts.update(frame)
        _, (cx, cy, cw, ch) = color.update(frame)
        truth = scene.part_boxes[k, hidden_part]
        est = parts.parts[hidden_part]
        conv = (cx + fx * cw, cy + fy * ch, fw * cw, fh * ch)
        rows.append((k, scene.occluded_fraction[k, hidden_part], truth, est, conv,
                     bool(parts.occluded[hidden_part]), parts.box, (cx, cy, cw, ch),
                     scene.boxes[k]))
    return scene, hidden_part, rows


def centre_of(b):
    return np.array([b[0] + b[2] / 2, b[1] + b[3] / 2])


def print_scenes(seeds: List[int]) -> Dict[str, object]:
    """Error of the hidden part's estimate while it is hidden (occluded fraction > 0.9), and of
    the object box over the occlusion, part-based vs conventional."""
    table, keep = [], {}
    for layout, occlude in SCENES:
        errs = {"part": [], "conv": [], "obj_part": [], "obj_conv": [], "judged": []}
        for seed in seeds:
            scene, hidden, rows = scene_run(layout, occlude, seed)
            if seed == seeds[0]:
                keep[f"{layout}-{occlude}"] = (scene, hidden, rows)
            for k, frac, truth, est, conv, judged, pbox, cbox, obox in rows:
                if frac > 0.9:
                    errs["part"].append(np.linalg.norm(centre_of(est) - centre_of(truth)))
                    errs["conv"].append(np.linalg.norm(centre_of(conv) - centre_of(truth)))
                    errs["judged"].append(judged)
                if scene.occluded_fraction[k].max() > 0.25:
                    errs["obj_part"].append(np.linalg.norm(centre_of(pbox) - centre_of(obox)))
                    errs["obj_conv"].append(np.linalg.norm(centre_of(cbox) - centre_of(obox)))
        e = {k: np.asarray(v, float) for k, v in errs.items()}
        table.append([f"{layout}, {occlude} part hidden", len(e["part"]),
                      f"{np.median(e['part']):.1f} / {e['part'].max():.1f}",
                      f"{np.median(e['conv']):.1f} / {e['conv'].max():.1f}",
                      f"{e['judged'].mean():.2f}",
                      f"{np.median(e['obj_part']):.1f} / {e['obj_part'].max():.1f}",
                      f"{np.median(e['obj_conv']):.1f} / {e['obj_conv'].max():.1f}"])
    print(f"Synthetic occlusion scenes (vtrack.synthetic_occlusion, noise_std 4, seeds {seeds}; "
          "part-based 30 per part, conventional N = 30): centre error (px, median / max) of the "
          "hidden part while hidden (> 90 %) and of the object box while any part is occluded "
          "(> 25 %)")
    print()
    print_table(["scene", "hidden frames", "hidden part: part-based", "conventional",
                 "judged occluded", "object: part-based", "conventional"], table)
    return keep


def scene_figure(keep, path: str) -> None:
    """One panel per scene: the hidden part's centre error against frame, part-based (green) vs
    conventional (magenta), the hidden span shaded; on the right the frame at mid-occlusion with
    the truth (white), the part-based parts (cyan; the hidden one red) and the conventional box
    (magenta)."""
    panel_h, plot_w, left, top = 220, 560, 50, 28
    thumbs = []
    for scene, hidden, rows in keep.values():
        thumbs.append(scene.frame(0).shape)
    thumb_w = max(s[1] for s in thumbs)
    width = left + plot_w + 20 + thumb_w + 10
    img = np.full((len(keep) * (panel_h + top) + 24, width, 3), 255, np.uint8)
    for row, (name, (scene, hidden, rows)) in enumerate(keep.items()):
        y0 = top + row * (panel_h + top)
        ks = np.array([r[0] for r in rows])
        e_part = np.array([np.linalg.norm(centre_of(r[3]) - centre_of(r[2])) for r in rows])
        e_conv = np.array([np.linalg.norm(centre_of(r[4]) - centre_of(r[2])) for r in rows])
        top_err = max(40.0, float(np.ceil(max(e_part.max(), e_conv.max()) / 10) * 10))

        def pt(k, e):
            return (int(left + plot_w * (k - ks[0]) / (ks[-1] - ks[0])),
                    int(y0 + panel_h - panel_h * min(e, top_err) / top_err))

        hidden_ks = ks[[r[1] > 0.9 for r in rows]]
        if len(hidden_ks):
            cv2.rectangle(img, (pt(hidden_ks[0], 0)[0], y0), (pt(hidden_ks[-1], 0)[0], y0 + panel_h),
                          (225, 225, 255), -1)
        cv2.rectangle(img, (left, y0), (left + plot_w, y0 + panel_h), (0, 0, 0), 1)
        for e, colour in ((e_conv, (200, 0, 200)), (e_part, (0, 160, 0))):
            pts = np.array([pt(k, v) for k, v in zip(ks, e)], np.int32)
            cv2.polylines(img, [pts], False, colour, 2, cv2.LINE_AA)
        for v in np.arange(0, top_err + 1, 10 if top_err <= 60 else 20):
            p = pt(ks[0], v)
            cv2.putText(img, f"{v:.0f}", (8, p[1] + 4), cv2.FONT_HERSHEY_SIMPLEX, 0.4, (0, 0, 0), 1,
                        cv2.LINE_AA)
        part_name = scene.part_names[hidden]
        cv2.putText(img, f"{name}: error of the {part_name} part's centre (px) vs frame; "
                    "green part-based, magenta conventional", (left, y0 - 8),
                    cv2.FONT_HERSHEY_SIMPLEX, 0.45, (0, 0, 0), 1, cv2.LINE_AA)
        mid = int(hidden_ks[len(hidden_ks) // 2]) if len(hidden_ks) else int(ks[len(ks) // 2])
        r = rows[mid - 1]
        thumb = scene.frame(mid).copy()

        def box(b, colour, t=1):
            cv2.rectangle(thumb, (int(round(b[0])), int(round(b[1]))),
                          (int(round(b[0] + b[2])), int(round(b[1] + b[3]))), colour, t)

        box(r[2], (255, 255, 255), 1)
        box(r[4], (200, 0, 200), 1)
        box(r[3], (0, 0, 255), 2)
        scale = min(1.0, panel_h / thumb.shape[0])
        thumb = cv2.resize(thumb, None, fx=scale, fy=scale, interpolation=cv2.INTER_AREA)
        x_t = left + plot_w + 20
        img[y0:y0 + thumb.shape[0], x_t:x_t + thumb.shape[1]] = thumb
        cv2.putText(img, f"frame {mid}", (x_t + 4, y0 + 14), cv2.FONT_HERSHEY_SIMPLEX, 0.4,
                    (255, 255, 255), 1, cv2.LINE_AA)
    cv2.putText(img, "shaded: the part hidden (> 90 %). Right: truth white, part-based estimate of "
                "the hidden part red, conventional filter's part magenta", (left, img.shape[0] - 8),
                cv2.FONT_HERSHEY_SIMPLEX, 0.4, (0, 0, 0), 1, cv2.LINE_AA)
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    if not cv2.imwrite(str(path), img):
        raise OSError(f"could not write {path}")
    print(f"\nwrote {path}")


def print_speed(counts: List[int], frames, segments) -> None:
    """Time per frame (and AUC) against the number of particles, seed 0, every segment."""
    rows, cpu_times = [], {}
    for name, (factory, peer) in speed_trackers().items():
        for n in counts:
            per_seed, times = evaluate(lambda seed: factory(n, seed), [0], frames, segments)
            cpu = median(t[1] for t in times)
            cpu_times[name, n] = cpu
            ratio = f"{cpu_times[peer, n] / cpu:.1f}" if peer else "-"
            rows.append([name, n, f"{1e3 * cpu:.3f}", f"{1e3 * median(t[0] for t in times):.3f}",
                         ratio, cell(per_seed, ("occluded", "all"), 0),
                         cell(per_seed, ("clean", "all"), 0)])
    print("Time per frame against the number of particles (seed 0, every segment; the ratio is the "
          "CPU time of the NumPy filter with the same histogram, kernel-weighted or not, at the "
          "same N over this row's, measured in this run)")
    print()
    print_table(["tracker", "N", "ms/frame CPU", "ms/frame wall", "ratio", "occluded: AUC",
                 "clean: AUC"], rows)


if __name__ == "__main__":
    main()
