"""vtrack's pipelines as Python calls: the same C++ code as ``vtrack track``, so the same
parameters give the same rows.

- :func:`track_video`: video (or image folder) -> background model or detector -> tracker ->
  MOTChallenge rows. ``method="mb"``: the KDE background model and the multi-Bernoulli
  track-before-detect tracker (config sections ``background``, ``tracker``); ``method="sir"``:
  the same background model (with ``update_static`` on) and the re-clustering SIR of particle-filters-human-vehicle §2
  (``background``, ``tracker``: ``ReclusteringSirTracker.default_params()``); ``method="glmb"``
  with ``detector="hog"``: OpenCV's HOG people detector and the box GLMB tracker (sections
  ``detector``, ``tracker``).
- :func:`track_detections`: a MOTChallenge detection file (or rows) -> the box GLMB tracker.

Parameters come, lowest precedence first, from the components' defaults, ``config`` (a YAML or
JSON file, or the dict :func:`vtrack.io.load_config` returns) and keyword arguments, each name
going to the one section of the method that has it (as ``--set name=value`` does).
"""

from __future__ import annotations

import os
import sys
import time
from typing import Any, Callable, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core

PathLike = Union[str, "os.PathLike[str]"]
Progress = Union[bool, Callable[[int, int], None], None]

METHODS = ("mb", "sir", "glmb")

# Keywords that make a foreground method report the box of the person's silhouette instead of the
# annotation convention its defaults are calibrated to (MOTChallenge's PETS09-S2L1 boxes, which
# frame the person with a margin): for ground truth that boxes the foreground itself, as
# vtrack.synthetic's scenes do. The SIR's own box is its ellipse's bounding box, the silhouette's.
# The multi-Bernoulli filter's own box is the core of the silhouette that eq. (20) scores best,
# a constant fraction of a person-sized silhouette under the per-person reward; its scales are the
# medians of benchmarks/_foreground.py's fit_calibration on synthetic scenes without perspective
# of their own seeds (21-25, 320 x 240 and 640 x 480, three people), which neither the tests nor
# benchmarks/synthetic_people.py score on.
SILHOUETTE_BOX: Dict[str, Dict[str, float]] = {
    "mb": dict(box_scale_w=1.092, box_scale_h=1.078, box_offset_x=0.0, box_offset_y=0.0),
    "sir": dict(box_scale_w=1.0, box_scale_h=1.0, box_offset_x=0.0, box_offset_y=0.0),
}

__all__ = ["METHODS", "SILHOUETTE_BOX", "follow", "pipeline_params", "track_detections", "track_video"]


class _ProgressLine:
    """Frames done on stderr, rewritten in place on a terminal (the CLI's progress line)."""

    def __init__(self, job: str):
        self.job, self.start, self.printed = job, time.monotonic(), False
        self.tty = sys.stderr.isatty()

    def __call__(self, done: int, total: int) -> None:
        if done % 25 and done != total:
            return
        rate = done / max(time.monotonic() - self.start, 1e-9)
        of = f"/{total}" if total > 0 else ""
        end = "" if self.tty else "\n"
        sys.stderr.write(f"{chr(13) if self.tty else ''}{self.job}: frame {done}{of} "
                         f"({rate:.1f} frames/s){end}")
        sys.stderr.flush()
        self.printed = True

    def close(self) -> None:
        if self.printed and self.tty:
            sys.stderr.write("\n")


class _ProgressBar:
    """tqdm's bar over frames."""

    def __init__(self, job: str, tqdm: Any):
        self.bar = tqdm(desc=job, unit="frame")

    def __call__(self, done: int, total: int) -> None:
        if total > 0 and self.bar.total != total:
            self.bar.total = total
        self.bar.update(done - self.bar.n)

    def close(self) -> None:
        self.bar.close()


def _reporter(progress: Progress, job: str):
    """(callback for the C++ job, close) for progress=False/True/a callable(done, total)."""
    if progress is None or progress is False:
        return None, lambda: None
    if callable(progress):
        return progress, lambda: None
    if progress is not True:
        raise TypeError(f"progress must be a bool or a callable(done, total), got "
                        f"{type(progress).__name__}")
    try:
        from tqdm.auto import tqdm
        reporter: Any = _ProgressBar(job, tqdm)
    except ImportError:
        reporter = _ProgressLine(job)
    return reporter, reporter.close


def _config_sections(config: Union[None, PathLike, Mapping[str, Any]]) -> Dict[str, Any]:
    if config is None:
        return {}
    if isinstance(config, (str, os.PathLike)):
        return _core.load_config(config)
    if isinstance(config, Mapping):
        return dict(config)
    raise TypeError(f"config must be a path or a dict of sections, got {type(config).__name__}")


def pipeline_params(method: str = "mb", *, detector: Optional[str] = None,
                    config: Union[None, PathLike, Mapping[str, Any]] = None,
                    settings: Sequence[str] = (), **params: Any) -> Dict[str, Dict[str, Any]]:
    """The parameters :func:`track_video` would run with, as ``vtrack params`` prints them: every
    section of the method (``{"background": {...}, "tracker": {...}}`` for mb) with every
    parameter, the tracker's ``seed`` included.

    Precedence, lowest first: the defaults, ``config`` (a file or sections), keyword ``params``,
    then ``settings``, texts ``"name=value"`` read as ``vtrack track --set`` reads them (the
    C++ parser: true/false, an integer, a real, a comma-separated list of reals, else a name).
    The result passed back as ``config`` gives the same run. Raises TypeError for an unknown
    name or a value of the wrong type, ValueError for a value out of range or a malformed
    setting.
    """
    if isinstance(settings, str):
        raise TypeError("settings must be a sequence of 'name=value' strings, not one string")
    return _core.pipeline_params(method, detector or "", _config_sections(config), params,
                                 list(settings))


def track_video(video: PathLike, method: str = "mb", *, detector: Optional[str] = None,
                config: Union[None, PathLike, Mapping[str, Any]] = None,
                progress: Progress = False, render: Optional[PathLike] = None,
                return_detections: bool = False,
                **params: Any) -> Union[np.ndarray, Tuple[np.ndarray, np.ndarray]]:
    """Track the people in a video file or image folder with one of vtrack's pipelines.

    method: ``"mb"`` (KDE background + multi-Bernoulli TBD, the mb-tbd paper), ``"sir"`` (KDE
    background + the re-clustering SIR, particle-filters-human-vehicle §2) or ``"glmb"``
    (a detector + the box GLMB; needs ``detector="hog"``). config: a YAML/JSON file or a dict of
    sections as :func:`vtrack.io.load_config` returns. params: any parameter of the method's
    sections by name (e.g. ``seed=3, delta_b=2e-3, bandwidth=(0.03, 0.03, 0.06)``; see
    ``KdeBackground.default_params()``, ``MultiBernoulliTracker.default_params()``,
    ``HogPeopleDetector.default_params()``, ``BoxTracker.default_params()``). progress: True for
    a progress bar (tqdm if installed, else a line on stderr), or a callable(done, total).
    render: also write the annotated video (.avi, .mp4 or .mkv).

    Returns the MOTChallenge rows of every frame, an (N, 10) float64 array frame, id, x, y, w, h,
    conf, -1, -1, -1 (frames from 1; conf = the track's score), and with return_detections the
    detector's rows too (glmb). The same seed gives the same rows; Ctrl-C interrupts.
    """
    callback, close = _reporter(progress, "track")
    try:
        rows, detections, _ = _core.track_video(
            video, method, detector or "", _config_sections(config), params,
            None if render is None else render, callback)
    finally:
        close()
    return (rows, detections) if return_detections else rows


def follow(video: PathLike, init_box: Sequence[float], method: str = "color", first: int = 1,
           last: Optional[int] = None, render: Optional[PathLike] = None, *,
           config: Union[None, PathLike, Mapping[str, Any]] = None, progress: Progress = False,
           **params: Any) -> np.ndarray:
    """Follow one object through a video from its box -- ``vtrack follow`` (the same arguments
    give the same rows).

    init_box: (x, y, w, h) of the object on frame ``first`` (1-based, the video's numbering),
    inside the image. method: ``"color"`` (:class:`vtrack.ColorParticleTracker`, the conventional
    colour-histogram particle filter) or ``"parts"`` (:class:`vtrack.PartParticleTracker`, the
    part-based particle filter on a graphical model); part-based-graphical-model-pf.txt. last: the
    last frame (default: the end). render: also write the video with the box (and each part's, red
    when judged occluded). config: a file or dict whose ``tracker`` section (and top-level seed)
    applies; params: the tracker's keyword parameters (``n_particles``, ``seed``, ``sigma``, ...;
    its ``default_params()``). progress: True for a progress bar, or a callable(done, total).

    Returns an (N, 5) float64 array frame, x, y, w, h from ``first`` on, the first row the init
    box; x, y, w, h are NaN where the tracker reported the target lost (``ok = False``).
    ValueError for a box that leaves the image or has no area, ``first`` past the end, ``last`` <
    ``first``; OSError for an unreadable video.
    """
    sections = _config_sections(config)
    unknown = set(sections) - {"seed", "tracker"}
    if unknown:
        raise ValueError(f"config: follow reads the sections seed and tracker, got {sorted(unknown)}")
    merged: Dict[str, Any] = dict(sections.get("tracker", {}))
    if "seed" in sections:
        merged["seed"] = sections["seed"]
    merged.update(params)
    callback, close = _reporter(progress, "follow")
    try:
        return _core.follow_video(video, init_box, method, first, last,
                                  None if render is None else render, merged, callback)
    finally:
        close()


def track_detections(detections: Union[PathLike, np.ndarray], image_size: Optional[Tuple[int, int]] = None,
                     *, last_frame: int = 0, config: Union[None, PathLike, Mapping[str, Any]] = None,
                     progress: Progress = False, **params: Any) -> np.ndarray:
    """Track the image boxes of MOTChallenge detections with the box GLMB tracker (state [cx, vcx,
    cy, vcy, w, h]: constant-velocity centre, random-walk size, adaptive birth from the
    detections, uniform clutter over the image) -- ``vtrack track --detections DET --method
    glmb``: the same file and parameters give the same rows.

    detections: a detection file path, or an (N, 6..10) array of rows frame, id, x, y, w, h[,
    conf, ...] (frames from 1, id ignored). image_size: (width, height) for the clutter model;
    default the extent of the boxes. last_frame: track at least up to this frame. config: a file
    or dict whose ``tracker`` section applies; params: tracker parameters by name
    (``BoxTracker.default_params()``). Returns an (K, 10) float64 array of MOTChallenge rows for
    frames 1 .. max(last_frame, the last detection's frame), ids 1, 2, ... in order of first
    appearance, conf = the track's existence probability.
    """
    sections = _config_sections(config)
    unknown = set(sections) - {"seed", "tracker", "detector"}
    if unknown:
        raise ValueError(f"config: track_detections reads the sections seed and tracker, got "
                         f"{sorted(unknown)}")
    merged: Dict[str, Any] = dict(sections.get("tracker", {}))
    if "seed" in sections:
        merged["seed"] = sections["seed"]
    merged.update(params)
    callback, close = _reporter(progress, "track")
    try:
        return _core.track_detections(detections, image_size, last_frame, merged, callback)
    finally:
        close()
