"""Many videos at once on Dask: ``vtrack batch`` (the C++ CLI runs ``python -m vtrack.batch``).

    vtrack batch INPUTS... --out DIR [--method mb|glmb] [--detector hog] [--config FILE]
                 [--set name=value ...] [--seed N] [--render] [--gt PATTERN]
                 [--workers N | --scheduler ADDRESS] [--force]

and from Python ``vtrack.batch.track_many(inputs, out_dir, client=None, **params)``. One Dask
task tracks one input with :func:`vtrack.track_video`, exactly as ``vtrack track`` would (same
parameters, same seed, same bytes in ``tracks.txt``, written by the same C++ writer). The
parameters are resolved once, in the client, by :func:`vtrack.pipelines.pipeline_params` (the
C++ parameter tables: defaults, ``--config``, ``--seed``, ``--set``, as ``vtrack track`` and
``vtrack params`` resolve them), and every task gets all of them. docs/batch.md is the user's
guide; the definitions:

INPUTS    video files, image folders, glob patterns (expanded here, ``**`` included) and text files
          (``.txt``, ``.lst``, ``.list``) listing them one per line (blank lines and ``#`` comments
          skipped, relative paths relative to the list). A path given twice runs once. A missing
          or unreadable input fails its own task; a pattern matching nothing is a usage error.
names     results go to ``DIR/<name>/``: a video's file stem, an image folder's name (MOTChallenge's
          ``SEQ/img1`` is named ``SEQ``). Colliding names are replaced by names built from the end
          of their paths: ``a/cam.avi``, ``b/cam.avi`` -> ``a__cam``, ``b__cam``; ``cam.avi``,
          ``cam.mp4`` -> ``cam.avi``, ``cam.mp4`` (a hash of the path when nothing else
          separates them). The rule depends on the set of inputs, not on their order.
outputs   ``tracks.txt`` (MOTChallenge), ``render.mp4`` (--render), ``run.json`` (input,
          method, detector, every parameter in force, vtrack version, seed, frames, seconds,
          fps, status, error, metrics, worker), and ``DIR/summary.csv``
          (``input,name,status,frames,seconds,fps,error`` and, with --gt, ``HOTA,MOTA,IDF1``; one
          row per finished input, in input order), rewritten as results arrive (at most once a
          second, and at the end). Every file is written under a temporary name and renamed when
          whole.
complete  an input is complete when its ``run.json`` says ``ok`` for the same input path and the
          same parameters and its outputs are there. The worker renames ``tracks.txt`` (and the
          render) into place, then the client writes ``run.json``, last. A re-run skips complete
          inputs and redoes the rest (failed, interrupted, parameters changed); ``--force`` redoes
          all. The vtrack version is recorded, not compared: re-run with --force after upgrading.
faults    an input's error (OSError from the reader: missing, corrupt, truncated) is caught in its
          task and reported in ``run.json`` and ``summary.csv`` (status ``failed``); a worker that
          dies mid-task is replaced and the task rerun by Dask (the scheduler's
          ``distributed.scheduler.allowed-failures``, default 3, after which the input fails with
          ``KilledWorker``). Ctrl-C cancels the tasks, stops a cluster we started and removes the
          temporary files of the unfinished inputs; an attempt's leftovers are also removed when
          its input is next tracked.
--gt      a path pattern with ``{name}`` (the output name), ``{stem}`` (file stem or folder name),
          ``{dir}`` (the input's folder) or ``{input}``, e.g. ``MOT15/train/{name}/gt/gt.txt``;
          metrics by :func:`vtrack.evaluate.evaluate` (TrackEval). A missing ground-truth file
          leaves the metrics empty and says so in the error column; the input stays ``ok``.
exit      0 every input ok, 1 some input failed or the scheduler cannot be reached, 2 a usage
          error (bad option or parameter, no inputs, an output folder that overlaps an input,
          Dask or TrackEval missing), 130 interrupted.

One task per input. A very long video is one long task; to spread it, cut it into segments (e.g.
``ffmpeg -ss START -t LENGTH -c copy``, or image folders of frame ranges) that overlap by at least
the background model's warm-up (N0 * K0 = 100 frames with the defaults) and batch the segments;
each segment's ids start at 1, so stitch them across the overlap (IoU matching of the shared
frames). vtrack does not stitch.
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import glob
import hashlib
import io
import json
import os
import signal
import socket
import sys
import threading
import time
import uuid
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Dict, Iterable, List, Optional, Sequence, Tuple, Union

import numpy as np

from ._files import atomic_open, is_temporary
from .pipelines import METHODS

PathLike = Union[str, "os.PathLike[str]"]

TRACKS = "tracks.txt"
RENDER = "render.mp4"
RUN = "run.json"
SUMMARY = "summary.csv"
SUMMARY_COLUMNS = ("input", "name", "status", "frames", "seconds", "fps", "error")
METRIC_COLUMNS = ("HOTA", "MOTA", "IDF1")
LIST_SUFFIXES = (".txt", ".lst", ".list")
_RESERVED_NAMES = {SUMMARY, ".", ".."}
EXIT_OK, EXIT_FAILED, EXIT_USAGE, EXIT_INTERRUPTED = 0, 1, 2, 130


class UsageError(ValueError):
    """A mistake in what was asked (exit status 2 from the command line)."""


# ---- the one call into vtrack's per-video tracking ------------------------------------------


def _track_one(video: str, job: Dict[str, Any], render: Optional[str]) -> Tuple[np.ndarray, int]:
    """Track one input as ``vtrack track`` would: ``(rows (N, 10) MOT, frames decoded)``.

    `job` is :func:`make_job`'s: the method, the detector and every section's parameters (what
    :func:`vtrack.pipelines.pipeline_params` resolved), passed back as the config.
    """
    from .pipelines import track_video  # noqa: PLC0415 - imported on the worker

    frames = [0]

    def count(done: int, total: int) -> None:  # the pipeline reports every frame it tracked
        frames[0] = done

    rows = track_video(video, job["method"], detector=job["detector"], config=job["parameters"],
                       render=render, progress=count)
    return rows, frames[0]


# ---- inputs -----------------------------------------------------------------------------------


@dataclass(frozen=True)
class Input:
    """One video file or image folder, and the name of its output folder."""

    path: str  # absolute
    name: str


def _expand(item: str, from_list: Optional[str] = None) -> List[str]:
    if os.path.isdir(item):
        return [os.path.abspath(item)]
    if os.path.isfile(item) and item.lower().endswith(LIST_SUFFIXES):
        if from_list is not None:
            raise UsageError(f"{from_list}: a list cannot name another list ('{item}')")
        folder = os.path.dirname(os.path.abspath(item))
        out: List[str] = []
        with open(item) as f:
            for line in f:
                line = line.strip()
                if line and not line.startswith("#"):
                    out.extend(_expand(os.path.join(folder, os.path.expanduser(line)), item))
        return out
    if os.path.exists(item) or not glob.has_magic(item):
        return [os.path.abspath(item)]  # a video, or missing: its task reports it
    matches = sorted(glob.glob(item, recursive=True))
    if not matches:
        where = f" (in {from_list})" if from_list else ""
        raise UsageError(f"pattern '{item}'{where} matches nothing")
    return [os.path.abspath(m) for m in matches]


def _name_candidates(path: str) -> List[str]:
    """Ever more specific names for `path`'s output folder, the plain one first."""
    p = Path(path)
    if p.is_dir():
        if p.name == "img1" and p.parent.name:  # MOTChallenge: SEQ/img1
            p = p.parent
        short, full = p.name, p.name
    else:
        short, full = p.stem or p.name, p.name
    parents = [part for part in p.parent.parts if part not in (p.anchor, "")]
    out = []
    for k in range(len(parents) + 1):
        prefix = parents[len(parents) - k:]
        out += ["__".join(prefix + [short]), "__".join(prefix + [full])]
    return list(dict.fromkeys(out))  # drop repeats (folders: short == full)


def _unique_names(paths: Sequence[str]) -> List[str]:
    """Output names: plain unless two inputs share one; then each of those takes its next
    candidate, until all differ. Depends on the set of paths only, not their order."""
    candidates = [_name_candidates(p) for p in paths]
    level = [0] * len(paths)
    while True:
        names = [c[min(k, len(c) - 1)] for c, k in zip(candidates, level)]
        seen: Dict[str, List[int]] = {}
        for i, n in enumerate(names):
            seen.setdefault(n, []).append(i)
        clashes = [ids for n, ids in seen.items() if len(ids) > 1 or n in _RESERVED_NAMES]
        if not clashes:
            return names
        progressed = False
        for ids in clashes:
            for i in ids:
                if level[i] < len(candidates[i]) - 1:
                    level[i] += 1
                    progressed = True
        if not progressed:  # e.g. /x/a/cam.avi vs /x/a__cam.avi: the path's hash settles it
            for ids in clashes:
                for i in ids:
                    digest = hashlib.sha1(paths[i].encode()).hexdigest()[:12]
                    hashed = f"{candidates[i][0]}-{digest}"
                    if candidates[i][-1] == hashed:
                        raise RuntimeError(f"no unique output name for {paths[i]}")
                    candidates[i].append(hashed)
                    level[i] = len(candidates[i]) - 1


def expand_inputs(items: Union[PathLike, Iterable[PathLike]]) -> List[Input]:
    """The inputs named by `items` (paths, glob patterns, list files), each with its output name.
    Raises :class:`UsageError` for a pattern matching nothing or no inputs at all."""
    if isinstance(items, (str, os.PathLike)):
        items = [items]
    paths: List[str] = []
    seen = set()
    for item in items:
        for path in _expand(os.fspath(item)):
            key = os.path.realpath(path)
            if key not in seen:
                seen.add(key)
                paths.append(path)
    if not paths:
        raise UsageError("no inputs")
    return [Input(p, n) for p, n in zip(paths, _unique_names(paths))]


# ---- parameters --------------------------------------------------------------------------------


def make_job(method: str = "mb", detector: Optional[str] = None, config: Optional[PathLike] = None,
             settings: Sequence[str] = (), render: bool = False, **params) -> Dict[str, Any]:
    """What every task runs with, as recorded in run.json: the method, the detector and every
    parameter of the method's sections, resolved as ``vtrack track`` resolves them (defaults, the
    config file, `params`, then `settings` -- ``"name=value"`` texts of ``--set``) by
    :func:`vtrack.pipelines.pipeline_params`; TypeError / ValueError naming a bad parameter.

    One batch policy on top: a KDE background's ``threads`` left at its default (0, OpenCV's
    choice) becomes 1, since the cores are already shared out one worker process each (the
    tracks do not depend on it)."""
    from .pipelines import pipeline_params  # noqa: PLC0415

    if method not in METHODS:
        raise UsageError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    if config is not None and not os.path.isfile(config):
        raise UsageError(f"config file '{os.fspath(config)}' does not exist")
    try:
        sections = pipeline_params(method, detector=detector, config=config, settings=settings,
                                   **params)
    except OSError as err:  # an unreadable or unparsable config file
        raise UsageError(str(err)) from None
    background = sections.get("background")
    if background is not None and background.get("threads") == 0:  # 0: the default
        background["threads"] = 1
    job = {"method": method, "detector": detector, "parameters": sections, "render": bool(render)}
    return json.loads(json.dumps(job))  # as it will read back from run.json


def _seed(job: Dict[str, Any]) -> Optional[int]:
    return job["parameters"].get("tracker", {}).get("seed")


# ---- one task ------------------------------------------------------------------------------------


def _remove_leftovers(folder: Path) -> None:
    """Temporary files of an earlier attempt on this input (killed, or interrupted)."""
    if folder.is_dir():
        for entry in folder.iterdir():
            # atomic_open's, the C++ text writers' (NAME.<pid>-<n>.partial) and this batch's renders.
            if (is_temporary(entry.name) or entry.name.endswith(".partial")
                    or entry.name.startswith(".render.")):
                entry.unlink(missing_ok=True)


def _metrics(tracks: np.ndarray, gt_path: Optional[str]) -> Tuple[Optional[dict], Optional[str]]:
    if gt_path is None:
        return None, None
    from .evaluate import evaluate  # noqa: PLC0415
    from .io import read_mot  # noqa: PLC0415

    try:
        found = evaluate(read_mot(gt_path), tracks)
    except (OSError, ValueError) as err:
        return None, f"ground truth: {err}"
    return {k: found[k] for k in METRIC_COLUMNS}, None


def _worker_address() -> Optional[str]:
    try:
        from distributed import get_worker  # noqa: PLC0415

        return get_worker().address
    except (ImportError, ValueError):  # not in a Dask worker
        return None


def run_input(path: str, folder: str, job: Dict[str, Any], gt_path: Optional[str]) -> dict:
    """The task: track one input into `folder` (tracks.txt, render), never raising for a bad
    input. Returns the outcome that the client writes to run.json."""
    import vtrack  # noqa: PLC0415

    from .io import read_mot, write_mot  # noqa: PLC0415 - the C++ writer (atomic: .partial, renamed)

    out = Path(folder)
    out.mkdir(parents=True, exist_ok=True)
    _remove_leftovers(out)
    where = {"host": socket.gethostname(), "pid": os.getpid(), "worker": _worker_address(),
             "vtrack_version": vtrack.__version__}
    # A render name of this attempt's own: a stray earlier attempt (a worker presumed dead that
    # still runs) cannot write into the file this one renames.
    render = (str(out / f".render.{uuid.uuid4().hex[:12]}{Path(RENDER).suffix}")
              if job["render"] else None)
    start = time.perf_counter()
    try:
        rows, frames = _track_one(path, job, render)
        seconds = time.perf_counter() - start
        write_mot(out / TRACKS, rows)
        if render is not None:
            os.replace(render, out / RENDER)
    except Exception as err:  # noqa: BLE001 - every failure of an input is that input's outcome
        message = str(err) if isinstance(err, OSError) else f"{type(err).__name__}: {err}"
        return {"status": "failed", "error": message, "frames": None,
                "seconds": time.perf_counter() - start, **where}
    finally:
        if render is not None:
            Path(render).unlink(missing_ok=True)
    # The metrics of the rows as written (two-decimal boxes), as a re-run's recomputation sees them.
    metrics, gt_error = _metrics(read_mot(out / TRACKS), gt_path) if gt_path else (None, None)
    return {"status": "ok", "error": gt_error, "frames": int(frames), "seconds": seconds,
            "metrics": metrics, **where}


# ---- the client's bookkeeping ------------------------------------------------------------------


def _write_json(path: Path, data: dict) -> None:
    with atomic_open(path) as f:
        json.dump(data, f, indent=2, sort_keys=True)
        f.write("\n")


def _read_run(folder: Path) -> Optional[dict]:
    try:
        with open(folder / RUN) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def _is_complete(run: Optional[dict], item: Input, job: Dict[str, Any], folder: Path) -> bool:
    return (run is not None and run.get("status") == "ok" and run.get("input") == item.path
            and run.get("parameters") == job and (folder / TRACKS).is_file()
            and (not job["render"] or (folder / RENDER).is_file()))


def _gt_path(pattern: Optional[str], item: Input) -> Optional[str]:
    if pattern is None:
        return None
    p = Path(item.path)
    try:
        path = pattern.format(name=item.name, stem=p.stem if p.suffix else p.name,
                              dir=str(p.parent), input=item.path)
    except (KeyError, IndexError, ValueError) as err:
        raise UsageError(f"--gt pattern '{pattern}': {err!r} (use {{name}}, {{stem}}, {{dir}}, "
                         "{input})") from None
    return os.path.abspath(path)


def _record(item: Input, job: Dict[str, Any], outcome: dict, gt_path: Optional[str],
            config_path: Optional[str]) -> dict:
    frames, seconds = outcome.get("frames"), outcome.get("seconds")
    fps = frames / seconds if frames and seconds else None
    return {"input": item.path, "name": item.name, "status": outcome["status"],
            "error": outcome.get("error"), "parameters": job, "seed": _seed(job),
            "config_file": config_path, "frames": frames, "seconds": seconds, "fps": fps,
            "outputs": {"tracks": TRACKS if outcome["status"] == "ok" else None,
                        "render": RENDER if job["render"] and outcome["status"] == "ok" else None},
            "gt": gt_path, "metrics": outcome.get("metrics"),
            "vtrack_version": outcome.get("vtrack_version"), "host": outcome.get("host"),
            "pid": outcome.get("pid"), "worker": outcome.get("worker"),
            "finished": time.strftime("%Y-%m-%dT%H:%M:%S%z")}


def _summary_row(run: dict, with_metrics: bool) -> List[str]:
    def number(v, fmt):
        return "" if v is None else format(v, fmt)

    row = [run["input"], run["name"], run["status"], number(run.get("frames"), "d"),
           number(run.get("seconds"), ".6f"), number(run.get("fps"), ".2f"), run.get("error") or ""]
    if with_metrics:
        metrics = run.get("metrics") or {}
        row += [number(metrics.get(k), ".6f") for k in METRIC_COLUMNS]
    return row


class _Summary:
    """DIR/summary.csv over `runs` (a list filled in as results arrive), rewritten atomically at
    most once a second and by :meth:`write` (a rewrite costs O(inputs))."""

    def __init__(self, path: Path, runs: Sequence[Optional[dict]], with_metrics: bool,
                 interrupts: "_Interrupts"):
        self.path, self.runs, self.with_metrics = path, runs, with_metrics
        self.interrupts = interrupts
        self.write()

    def changed(self) -> None:
        if time.monotonic() - self.written > 1.0:
            self.write()

    def write(self) -> None:
        text = io.StringIO()
        writer = csv.writer(text, lineterminator="\n")
        writer.writerow(SUMMARY_COLUMNS + (METRIC_COLUMNS if self.with_metrics else ()))
        for run in self.runs:
            if run is not None:
                writer.writerow(_summary_row(run, self.with_metrics))
        with self.interrupts.protect(), atomic_open(self.path) as f:
            f.write(text.getvalue())
        self.written = time.monotonic()


class _Progress:
    """A live bar over inputs: tqdm when installed, else one stderr line (rewritten in place on a
    terminal)."""

    def __init__(self, total: int, done: int, enabled: bool):
        self.total, self.done, self.failed, self.frames = total, done, 0, 0
        self.enabled, self.start, self.bar = enabled, time.perf_counter(), None
        if enabled:
            try:
                from tqdm import tqdm  # noqa: PLC0415
            except ImportError:
                tqdm = None
            if tqdm is not None:
                self.bar = tqdm(total=total, initial=done, unit="input", desc="vtrack batch",
                                file=sys.stderr)
            else:
                self.tty = sys.stderr.isatty()
                self._line()

    def _stats(self) -> str:
        rate = self.frames / max(time.perf_counter() - self.start, 1e-9)
        return f"{self.failed} failed, {self.frames} frames, {rate:.1f} frames/s"

    def _line(self) -> None:
        end = "" if self.tty else "\n"
        print(f"{chr(13) if self.tty else ''}vtrack batch: {self.done}/{self.total} inputs "
              f"({self._stats()})", end=end, file=sys.stderr, flush=True)

    def update(self, run: dict) -> None:
        self.done += 1
        self.failed += run["status"] != "ok"
        self.frames += run.get("frames") or 0
        if not self.enabled:
            return
        if self.bar is not None:
            self.bar.set_postfix_str(self._stats(), refresh=False)
            self.bar.update(1)
        else:
            self._line()

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
        elif self.enabled and self.tty:
            print(file=sys.stderr)


def local_cluster(workers: Optional[int] = None, **kwargs):
    """A ``distributed.LocalCluster`` for tracking: `workers` single-threaded worker processes
    (default one per core) whose C library keeps the memory it frees.

    Dask's nannies start workers with ``MALLOC_TRIM_THRESHOLD_=65536`` (config
    ``distributed.nanny.pre-spawn-environ``), which returns freed memory to the system at once
    and turns off glibc's adaptive mmap threshold: every frame's image buffers are then mapped
    and unmapped afresh. Measured on the batch benchmark's clips (1 worker, 12 inputs): 190 000
    page faults instead of a few thousand, +0.65 s system and +0.3 s user CPU time per 10 s of
    tracking. The workers here start without it (Dask's documented way: the variable set to None
    in that config; the other pre-spawn variables are kept), unless this process's environment
    has it -- set by the user, or left there by the nanny of a Dask cluster started earlier in
    this process, which updates os.environ for good. docs/batch.md says how to do the same on a
    cluster of one's own. Dask's statistical profiler is off in these workers
    (``distributed.worker.profile.enabled``): it samples the task thread's Python stack every 10
    ms, and a tracking task's stack is one C++ call, so the dashboard's profile page would only
    ever show track_video (batch.py's docstring has the CPU it costs). The event loops' health
    check (``distributed.admin.tick.interval``, 20 ms by default), the workers' memory monitor
    (100 ms) and the system monitor behind the dashboard's plots (500 ms) run every 1 s, 1 s and
    5 s instead: a tracking task runs for seconds, so nothing needs watching 50 times a second,
    and the idle cost of a 2-worker cluster fell from 2.7 % of a core in the workers and 2.7 %
    in this process (scheduler and client) to 0.4 % and 0.5 % (benchmarks/batch.py's docstring).
    `kwargs` go to LocalCluster."""
    import dask  # noqa: PLC0415
    from distributed import LocalCluster  # noqa: PLC0415

    if workers is None:
        workers = (len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity")
                   else os.cpu_count())
    environ = dict(dask.config.get("distributed.nanny.pre-spawn-environ", {}))
    environ["MALLOC_TRIM_THRESHOLD_"] = None
    with dask.config.set({"distributed.nanny.pre-spawn-environ": environ,
                          "distributed.worker.profile.enabled": False,
                          "distributed.admin.tick.interval": "1s",
                          "distributed.worker.memory.monitor-interval": "1s",
                          "distributed.admin.system-monitor.interval": "5s"}):
        return LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, **kwargs)


def _start_cluster(workers: Optional[int], scheduler: Optional[str], quiet: bool):
    """(client, cluster-or-None): a local cluster of one single-threaded worker process per core
    (`workers` to choose), or a connection to the scheduler at `scheduler`."""
    import logging  # noqa: PLC0415

    from distributed import Client  # noqa: PLC0415

    if scheduler is not None:
        try:
            return Client(scheduler), None
        except OSError as err:
            raise OSError(f"cannot reach the Dask scheduler at {scheduler}: {err}") from None
    dashboard = ":8787" if _has_bokeh() else ":0"  # without bokeh: a bare HTTP server, any port
    cluster = local_cluster(workers, dashboard_address=dashboard,
                            silence_logs=logging.ERROR if quiet else logging.WARNING)
    client = Client(cluster)
    client.register_plugin(_ignore_sigint_plugin())
    return client, cluster


def _ignore_sigint_plugin():
    """Makes our local workers ignore SIGINT. Ctrl-C reaches the whole process group; the client
    handles it (cancels, stops the cluster, removes temporary files), so the workers need not
    -- otherwise each prints a KeyboardInterrupt traceback as it dies. Registered with the
    scheduler, so workers restarted after a crash get it too."""
    from distributed.diagnostics.plugin import WorkerPlugin  # noqa: PLC0415

    class IgnoreSigint(WorkerPlugin):
        name = "vtrack-batch-ignore-sigint"

        def setup(self, worker):
            import signal  # noqa: PLC0415
            import threading  # noqa: PLC0415

            if threading.current_thread() is threading.main_thread():
                signal.signal(signal.SIGINT, signal.SIG_IGN)

    return IgnoreSigint()


def _has_bokeh() -> bool:
    """Whether Dask's dashboard can run here (it needs bokeh)."""
    import importlib.util  # noqa: PLC0415

    return importlib.util.find_spec("bokeh") is not None


def _describe_task_error(err: BaseException) -> str:
    name = type(err).__name__
    if name == "KilledWorker":
        return ("KilledWorker: the worker process died on every attempt at this input "
                "(distributed.scheduler.allowed-failures)")
    return f"{name}: {err}"


def track_many(inputs, out_dir: PathLike, client=None, *, method: str = "mb",
               detector: Optional[str] = None, config: Optional[PathLike] = None,
               settings: Sequence[str] = (), render: bool = False, gt: Optional[str] = None,
               force: bool = False, workers: Optional[int] = None,
               scheduler: Optional[str] = None, progress: bool = False, **params) -> List[dict]:
    """Track every input (see :func:`expand_inputs`) into ``out_dir/<name>/`` on Dask.

    `client` is a ``dask.distributed.Client`` to use; without one, a local cluster of `workers`
    single-threaded processes (default: one per core) is started and stopped, or `scheduler`
    (``tcp://host:8786``) is connected to. `method`, `detector`, `config` and the other keyword
    arguments (tracking parameters by name, ``seed`` included) are :func:`vtrack.track_video`'s;
    `settings` are ``"name=value"`` texts as ``vtrack track --set`` takes them (they override
    the keywords). Returns each input's run.json record, in input order
    (``skipped`` True for inputs found complete). Raises :class:`UsageError` (a ValueError) or
    the TypeError / ValueError of a bad parameter before anything runs; KeyboardInterrupt after
    cleaning up.
    """
    items = expand_inputs(inputs)
    out = Path(os.path.abspath(out_dir))  # the workers may run elsewhere, from another folder
    _check_out_dir(out, items)
    job = make_job(method, detector, config, settings, render, **params)
    if gt is not None:
        from .evaluate import _trackeval  # noqa: PLC0415

        try:
            _trackeval()
        except ImportError as err:
            raise UsageError(f"--gt: {err}") from None
    gt_paths = [_gt_path(gt, item) for item in items]
    out.mkdir(parents=True, exist_ok=True)
    config_path = os.path.abspath(config) if config is not None else None

    with _Interrupts() as interrupts:
        return _run(items, job, out, gt_paths, config_path, client, force, workers, scheduler,
                    progress, gt is not None, interrupts)


def _check_out_dir(out: Path, items: Sequence[Input]) -> None:
    """UsageError when the output folder is not a folder, is an input, lies inside an input
    (an image folder would gain files) or holds an input (DIR/<name>/ could overwrite it)."""
    if out.exists() and not out.is_dir():
        raise UsageError(f"--out '{out}' exists and is not a folder")
    real_out = Path(os.path.realpath(out))
    for item in items:
        real = Path(os.path.realpath(item.path))
        if real_out == real or real in real_out.parents or real_out in real.parents:
            raise UsageError(f"--out '{out}' overlaps the input '{item.path}': the outputs "
                             "must go to a folder of their own, outside the inputs")


def _run(items, job, out: Path, gt_paths, config_path, client, force, workers, scheduler,
         progress: bool, with_metrics: bool, interrupts: _Interrupts) -> List[dict]:
    """track_many once its arguments are checked: skip what is complete, submit the rest,
    record results as they come; on any exception cancel, stop our cluster, clean up."""
    work = _Batch(items, job, out, gt_paths, config_path, interrupts)
    todo = work.plan(force)
    summary = _Summary(out / SUMMARY, work.runs, with_metrics, interrupts)
    if not todo:
        return work.runs
    own = client is None
    cluster = None
    if own:
        client, cluster = _start_cluster(workers, scheduler, quiet=progress)
    futures: Dict[Any, int] = {}
    bar = None
    try:
        if progress:
            _announce(client, cluster, len(todo), len(items))
        bar = _Progress(len(items), len(items) - len(todo), progress)
        for i in todo:
            future = client.submit(run_input, items[i].path, str(out / items[i].name), job,
                                   gt_paths[i], key=f"vtrack-track-{uuid.uuid4().hex}", pure=False)
            futures[future] = i
        work.collect(futures, summary, bar, client if cluster is not None else None)
    except BaseException:
        for future in futures:
            future.cancel()
        if own:
            _stop(client, cluster)
            own = False
            if scheduler is None:  # our own workers are gone: nothing writes there any more
                for i in futures.values():
                    _remove_leftovers(out / items[i].name)
        raise
    finally:
        summary.write()
        if bar is not None:
            bar.close()
        if own:
            _stop(client, cluster)
    return work.runs


class ClusterError(RuntimeError):
    """The local cluster lost all its workers and got none back."""


class _Batch:
    """One track_many call: its inputs, their run.json records (`runs`, in input order), and
    what happens as tasks finish."""

    WORKERLESS_SECONDS = 60.0

    def __init__(self, items: Sequence[Input], job: Dict[str, Any], out: Path,
                 gt_paths: Sequence[Optional[str]], config_path: Optional[str],
                 interrupts: _Interrupts):
        self.items, self.job, self.out = items, job, out
        self.gt_paths, self.config_path = gt_paths, config_path
        self.interrupts = interrupts
        self.runs: List[Optional[dict]] = [None] * len(items)

    def plan(self, force: bool) -> List[int]:
        """The indices of the inputs to track; the others are complete and get their records.
        The former lose their run.json: until the new one, their folders are incomplete."""
        todo = []
        for i, item in enumerate(self.items):
            folder = self.out / item.name
            run = None if force else _read_run(folder)
            if not _is_complete(run, item, self.job, folder):
                (folder / RUN).unlink(missing_ok=True)
                todo.append(i)
                continue
            gt_path = self.gt_paths[i]
            if gt_path is not None and run.get("gt") != gt_path:  # metrics asked for later
                from .io import read_mot  # noqa: PLC0415

                run["metrics"], run["error"] = _metrics(read_mot(folder / TRACKS), gt_path)
                run["gt"] = gt_path
                with self.interrupts.protect():
                    _write_json(folder / RUN, run)
            self.runs[i] = dict(run, skipped=True)
        return todo

    def collect(self, futures: Dict[Any, int], summary: "_Summary", bar: _Progress,
                local_client=None) -> None:
        """Records each task as it finishes (removing it from `futures`). Polls, so that a Ctrl-C
        that Python delivered where it is lost (see :class:`_Interrupts`) is still seen, and so
        that a local cluster left without workers fails instead of waiting for ever."""
        from distributed import as_completed  # noqa: PLC0415

        finished = as_completed(list(futures))
        workers_seen = checked = time.monotonic()
        while futures:
            self.interrupts.check()
            ready = finished.next_batch(block=False)
            for future in ready:
                i = futures.pop(future)
                with self.interrupts.protect():
                    self.runs[i] = self.finish(future, i)
                summary.changed()
                bar.update(self.runs[i])
            if ready:
                continue
            time.sleep(0.05)
            now = time.monotonic()
            if local_client is not None and now - checked > 5.0:
                checked = now
                if local_client.nthreads():
                    workers_seen = now
                elif now - workers_seen > self.WORKERLESS_SECONDS:
                    raise ClusterError("the local Dask workers died and none came back")

    def finish(self, future, i: int) -> dict:
        """Writes input `i`'s run.json from its finished task (a failure also removes its
        outputs, as `vtrack track` leaves none) and returns it."""
        if future.status == "error":  # the task did not return: its worker died every time
            outcome = {"status": "failed", "error": _describe_task_error(future.exception())}
        else:
            outcome = future.result()
        item = self.items[i]
        folder = self.out / item.name
        folder.mkdir(parents=True, exist_ok=True)
        if outcome["status"] != "ok":
            for name in (TRACKS, RENDER):
                (folder / name).unlink(missing_ok=True)
        run = _record(item, self.job, outcome, self.gt_paths[i], self.config_path)
        _write_json(folder / RUN, run)
        return run


class _Interrupts:
    """Ctrl-C while a batch runs. In the main thread, over Python's default handler: SIGINT raises
    KeyboardInterrupt at once, except inside :meth:`protect` (the client's file writes), where
    it waits for the block to end -- so an interrupted write never leaves its temporary file --;
    and it is remembered (:meth:`check`), since Python may deliver it inside a ``__del__`` (a Dask
    Future's, say), where the exception is printed and lost."""

    def __init__(self):
        self.flag = threading.Event()
        self.depth = 0
        self.installed = False

    def __enter__(self) -> "_Interrupts":
        if (threading.current_thread() is threading.main_thread()
                and signal.getsignal(signal.SIGINT) is signal.default_int_handler):
            signal.signal(signal.SIGINT, self._handler)
            self.installed = True
        return self

    def __exit__(self, *exc) -> None:
        if self.installed:
            signal.signal(signal.SIGINT, signal.default_int_handler)

    def _handler(self, signum, frame):
        self.flag.set()
        if self.depth == 0:
            raise KeyboardInterrupt

    @contextlib.contextmanager
    def protect(self):
        already = self.flag.is_set()  # cleaning up after a Ctrl-C: do not raise again
        self.depth += 1
        try:
            yield
        finally:
            self.depth -= 1
        if not already and self.depth == 0:
            self.check()

    def check(self) -> None:
        if self.flag.is_set():
            raise KeyboardInterrupt


def _announce(client, cluster, todo: int, total: int) -> None:
    """What runs where, and Dask's dashboard when there is one (stderr)."""
    info = client.scheduler_info()
    where = (f"{len(info.get('workers', {}))} local worker process(es)" if cluster is not None
             else f"the cluster at {client.scheduler.address}")
    print(f"vtrack batch: {todo} of {total} inputs to track ({total - todo} already complete) "
          f"on {where}", file=sys.stderr)
    if "dashboard" in info.get("services", {}) and (cluster is None or _has_bokeh()):
        print(f"vtrack batch: Dask dashboard at {client.dashboard_link}", file=sys.stderr)


def _stop(client, cluster) -> None:
    client.close()
    if cluster is not None:
        cluster.close()


# ---- command line --------------------------------------------------------------------------------


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # argparse's usage errors, in vtrack's form (exit 2)
        self.print_usage(sys.stderr)
        print(f"vtrack: error: {message}", file=sys.stderr)
        sys.exit(EXIT_USAGE)


def _parser() -> argparse.ArgumentParser:
    prog = os.environ.get("VTRACK_PROG", "python -m vtrack.batch")
    p = _Parser(prog=prog, description=(
        "Track many videos at once on Dask: one task per input, a local cluster of one worker "
        "process per core unless --scheduler names a cluster. Results go to DIR/<name>/ "
        "(tracks.txt, run.json, render.mp4 with --render) and DIR/summary.csv. Re-running skips "
        "complete inputs. Exit status: 0 all ok, 1 some input failed, 2 usage error, "
        "130 interrupted."))
    p.add_argument("inputs", nargs="+", metavar="INPUT",
                   help="video file, image folder, glob pattern (quote it) or a .txt/.lst/.list "
                        "file listing them, one per line")
    p.add_argument("--out", required=True, metavar="DIR", help="output folder")
    p.add_argument("--method", default="mb", choices=METHODS, help="tracker (default mb)")
    p.add_argument("--detector", help="what gives glmb its boxes: hog (needed by glmb)")
    p.add_argument("--config", metavar="FILE", help="parameters, YAML or JSON (as vtrack track)")
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="one parameter, overriding the config file (repeatable)")
    p.add_argument("--seed", help="the tracker's seed, 0 to 2^64-1 (default: the config's, "
                                  "else 0)")
    p.add_argument("--render", action="store_true", help="also write DIR/<name>/render.mp4")
    p.add_argument("--gt", metavar="PATTERN",
                   help="ground truth per input, e.g. 'MOT15/train/{name}/gt/gt.txt' "
                        "({name}, {stem}, {dir}, {input}); adds HOTA, MOTA, IDF1 to the summary")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, metavar="N",
                       help="local worker processes, one thread each (default: one per core)")
    where.add_argument("--scheduler", metavar="ADDRESS",
                       help="run on an existing Dask cluster, e.g. tcp://host:8786")
    p.add_argument("--force", action="store_true", help="redo inputs that are complete")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    return p


def main(argv: Optional[Sequence[str]] = None) -> int:
    args = _parser().parse_args(argv)

    def fail(message: str, status: int) -> int:
        print(f"vtrack: error: {message}", file=sys.stderr)
        return status

    try:
        import distributed  # noqa: F401, PLC0415
    except ImportError:
        return fail("vtrack batch needs Dask: pip install 'vtrack[batch]' "
                    "(or pip install 'dask[distributed]')", EXIT_USAGE)
    if args.workers is not None and args.workers < 1:
        return fail(f"--workers must be >= 1, got {args.workers}", EXIT_USAGE)
    try:
        # --seed as a setting read by the C++ parser, before the --set ones (vtrack track's order)
        settings = ([f"seed={args.seed}"] if args.seed is not None else []) + args.set
        runs = track_many(args.inputs, args.out, method=args.method, detector=args.detector,
                          config=args.config, settings=settings, render=args.render, gt=args.gt,
                          force=args.force, workers=args.workers, scheduler=args.scheduler,
                          progress=not args.quiet)
    except KeyboardInterrupt:
        done = sum(1 for _ in _finished(args.out))
        return fail(f"interrupted; {args.out} holds {done} complete input(s): run the same "
                    "command again to do the rest", EXIT_INTERRUPTED)
    except (UsageError, TypeError, ValueError) as err:
        return fail(str(err), EXIT_USAGE)
    except (OSError, ClusterError) as err:
        return fail(str(err), EXIT_FAILED)
    failed = [r for r in runs if r["status"] != "ok"]
    skipped = sum(1 for r in runs if r.get("skipped"))
    print(f"vtrack batch: {len(runs) - len(failed)} of {len(runs)} inputs ok ({skipped} already "
          f"complete), {len(failed)} failed; summary in {Path(args.out) / SUMMARY}")
    for r in failed:
        print(f"vtrack batch: {r['name']}: {r['error']}", file=sys.stderr)
    return EXIT_FAILED if failed else EXIT_OK


def _finished(out_dir: PathLike):
    for entry in Path(out_dir).iterdir() if Path(out_dir).is_dir() else ():
        run = _read_run(entry) if entry.is_dir() else None
        if run is not None and run.get("status") == "ok":
            yield entry.name


if __name__ == "__main__":
    sys.exit(main())
