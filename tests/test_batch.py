"""vtrack batch: many videos on a real local Dask cluster (no mocks), checked against sequential
`vtrack track` runs of the same inputs, byte for byte."""

import csv
import json
import os
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

import vtrack
from vtrack.evaluate import evaluate
from vtrack.io import read_mot, write_mot
from vtrack.synthetic import make_scene

distributed = pytest.importorskip("distributed")
dask = pytest.importorskip("dask")
cv2 = pytest.importorskip("cv2")

from vtrack import batch  # noqa: E402

# People of the 160 x 120 scenes are 8-12 x 20-30 px: the tracker's size prior is given in pixels
# (it would otherwise be learnt from the foreground, which a 40-frame clip barely allows) and the
# output box is the foreground box. A short background period lets the KDE learn within the clip.
# Given as --set names, so both the tracker's and the background's parameters are routed.
SETTINGS = dict(width_mean=10.0, height_mean=25.0, box_scale_w=1.0, box_scale_h=1.0,
                box_offset_x=0.0, box_offset_y=0.0, period=2)
SEED = 3
FRAMES = 40


def _write_scene(path, seed, frames=FRAMES):
    scene = make_scene(160, 120, n_frames=frames, n_people=2, seed=seed, size=((8, 12), (20, 30)),
                       speed=(3.0, 5.0), illumination_amplitude=0.0)
    path.parent.mkdir(parents=True, exist_ok=True)
    writer = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*"MJPG"), 10.0, (160, 120))
    for k in range(len(scene)):
        writer.write(scene.frame(k))
    writer.release()
    return scene


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    """clips/s1.avi and s2.avi, an image folder frames/s3/img1 (MOTChallenge layout), a truncated
    clips/corrupt.avi, ground truth gt/<name>/gt.txt."""
    root = tmp_path_factory.mktemp("batch-data")
    scenes = {}
    for i, name in enumerate(["s1", "s2"]):
        scenes[name] = _write_scene(root / "clips" / f"{name}.avi", seed=10 + i)
    s3 = make_scene(160, 120, n_frames=FRAMES, n_people=2, seed=20, size=((8, 12), (20, 30)),
                    speed=(3.0, 5.0), illumination_amplitude=0.0)
    (root / "frames" / "s3" / "img1").mkdir(parents=True)
    for k in range(len(s3)):
        cv2.imwrite(str(root / "frames" / "s3" / "img1" / f"{k + 1:06d}.png"), s3.frame(k))
    scenes["s3"] = s3
    good = (root / "clips" / "s1.avi").read_bytes()
    (root / "clips" / "corrupt.avi").write_bytes(good[: len(good) // 2])
    for name, scene in scenes.items():
        (root / "gt" / name).mkdir(parents=True)
        write_mot(root / "gt" / name / "gt.txt", scene.gt_rows())
    return root, scenes


def _cli_reference(vtrack_cli, video, out):
    sets = [a for k, v in SETTINGS.items() for a in ("--set", f"{k}={v}")]
    result = vtrack_cli("track", video, "--out", out, "--seed", SEED, *sets)
    assert result.returncode == 0, result.stderr
    return Path(out).read_bytes()


@pytest.fixture(scope="module")
def references(data, vtrack_cli, tmp_path_factory):
    """Sequential `vtrack track` runs of the good inputs: name -> bytes of tracks.txt."""
    root, _ = data
    out = tmp_path_factory.mktemp("reference")
    videos = {"s1": root / "clips" / "s1.avi", "s2": root / "clips" / "s2.avi",
              "s3": root / "frames" / "s3" / "img1"}
    return {name: _cli_reference(vtrack_cli, v, out / f"{name}.txt") for name, v in videos.items()}


@pytest.fixture(scope="module")
def client():
    """A real local cluster: 2 worker processes of one thread each."""
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=":0")
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def _summary(out):
    with open(out / "summary.csv", newline="") as f:
        return list(csv.reader(f))


def _mtimes(folder):
    return {p: p.stat().st_mtime_ns for p in Path(folder).rglob("*") if p.is_file()}


def _leftovers(folder):
    return [p for p in Path(folder).rglob("*")
            if p.name.endswith(".tmp") or ".partial" in p.name or p.name.startswith(".render.")]


def test_batch_equals_sequential_cli_and_reports_bad_inputs(data, references, client, tmp_path):
    root, scenes = data
    listing = root / "inputs.txt"
    listing.write_text("# clips, an image folder, and a file that is not there\n"
                       "clips/*.avi\n\nframes/s3/img1\nmissing.avi\n")
    out = tmp_path / "out"
    runs = batch.track_many([listing], out, client=client, seed=SEED,
                            gt=str(root / "gt" / "{name}" / "gt.txt"), **SETTINGS)
    names = [r["name"] for r in runs]
    assert names == ["corrupt", "s1", "s2", "s3", "missing"]  # the list's order, globs sorted
    rows = _summary(out)
    assert rows[0] == ["input", "name", "status", "frames", "seconds", "fps", "error",
                       "HOTA", "MOTA", "IDF1"]
    by_name = {r[1]: dict(zip(rows[0], r)) for r in rows[1:]}
    assert [r[1] for r in rows[1:]] == names
    for name in ("s1", "s2", "s3"):
        row, folder = by_name[name], out / name
        assert row["status"] == "ok" and row["error"] == "", row
        assert (folder / "tracks.txt").read_bytes() == references[name], name
        assert int(row["frames"]) == FRAMES
        assert float(row["fps"]) == pytest.approx(FRAMES / float(row["seconds"]), rel=0.01)
        # The metric columns are TrackEval's on the written tracks and the scene's exact truth.
        expected = evaluate(scenes[name].gt_rows(), read_mot(folder / "tracks.txt"))
        for metric in ("HOTA", "MOTA", "IDF1"):
            assert float(row[metric]) == pytest.approx(expected[metric], abs=1e-6), (name, metric)
        run = json.loads((folder / "run.json").read_text())
        assert run["status"] == "ok" and run["seed"] == SEED and run["frames"] == FRAMES
        assert run["vtrack_version"] == vtrack.__version__
        # Every parameter in force is recorded: the defaults with SETTINGS routed by name.
        expected_sections = vtrack.pipelines.pipeline_params("mb", seed=SEED, **SETTINGS)
        expected_sections["background"]["threads"] = 1  # the batch's one thread per worker
        assert run["parameters"]["parameters"] == json.loads(json.dumps(expected_sections))
        assert run["parameters"]["method"] == "mb"
        where = "frames/s3/img1" if name == "s3" else f"clips/{name}.avi"
        assert run["input"] == str(root / where)
    # The tracker found people (the comparison above is not of empty files).
    assert float(by_name["s1"]["MOTA"]) > 0.3, by_name["s1"]
    for name, message in (("corrupt", "frame"), ("missing", "no such file")):
        row = by_name[name]
        assert row["status"] == "failed" and message in row["error"], row
        assert row["HOTA"] == "" and row["frames"] == ""
        run = json.loads((out / name / "run.json").read_text())
        assert run["status"] == "failed" and message in run["error"]
        assert not (out / name / "tracks.txt").exists()
    assert _leftovers(out) == []


def test_batch_runs_every_method_as_vtrack_track_does(data, vtrack_cli, client, tmp_path):
    """--method sir through the batch gives `vtrack track --method sir`'s tracks byte for byte
    (the mb method is compared above; glmb needs a detector and is in the usage test)."""
    root, _ = data
    video = root / "clips" / "s1.avi"
    reference = tmp_path / "reference.txt"
    result = vtrack_cli("track", video, "--method", "sir", "--out", reference, "--seed", SEED)
    assert result.returncode == 0, result.stderr
    runs = batch.track_many([video], tmp_path / "out", client=client, method="sir", seed=SEED)
    assert [r["status"] for r in runs] == ["ok"], runs
    tracks = (tmp_path / "out" / "s1" / "tracks.txt").read_bytes()
    assert tracks == reference.read_bytes() and tracks  # and the tracker reported something
    run = json.loads((tmp_path / "out" / "s1" / "run.json").read_text())
    assert run["parameters"]["method"] == "sir"


def test_rerun_skips_complete_redoes_failed_and_changed(data, references, client, tmp_path):
    root, _ = data
    clips = tmp_path / "clips"
    clips.mkdir()
    for name in ("s1", "s2"):
        os.symlink(root / "clips" / f"{name}.avi", clips / f"{name}.avi")
    (clips / "bad.avi").write_bytes((root / "clips" / "corrupt.avi").read_bytes())
    out = tmp_path / "out"
    first = batch.track_many(str(clips / "*.avi"), out, client=client, seed=SEED, **SETTINGS)
    assert [(r["name"], r["status"]) for r in first] == [("bad", "failed"), ("s1", "ok"),
                                                         ("s2", "ok")]
    before = _mtimes(out)
    # The failed input is repaired (now a copy of s1): the re-run redoes it and only it.
    (clips / "bad.avi").write_bytes((root / "clips" / "s1.avi").read_bytes())
    time.sleep(0.01)
    second = batch.track_many(str(clips / "*.avi"), out, client=client, seed=SEED, **SETTINGS)
    assert [(r["name"], r["status"], bool(r.get("skipped"))) for r in second] == [
        ("bad", "ok", False), ("s1", "ok", True), ("s2", "ok", True)]
    after = _mtimes(out)
    for name in ("s1", "s2"):
        for file in ("tracks.txt", "run.json"):
            assert after[out / name / file] == before[out / name / file], (name, file)
    assert (out / "bad" / "tracks.txt").read_bytes() == references["s1"]
    # A third run is a no-op: nothing but summary.csv is rewritten (and no cluster is started).
    third = batch.track_many(str(clips / "*.avi"), out, seed=SEED, **SETTINGS)
    assert all(r.get("skipped") for r in third)
    changed = {p for p, t in _mtimes(out).items() if after.get(p) != t}
    assert changed == {out / "summary.csv"}
    # Other parameters make nothing complete; --force redoes complete inputs.
    fourth = batch.track_many(str(clips / "s1.avi"), out, client=client, seed=SEED + 1,
                              **SETTINGS)
    assert not fourth[0].get("skipped") and fourth[0]["seed"] == SEED + 1
    fifth = batch.track_many(str(clips / "s2.avi"), out, client=client, seed=SEED, force=True,
                             **SETTINGS)
    assert not fifth[0].get("skipped")
    assert (out / "s2" / "tracks.txt").read_bytes() == references["s2"]


def test_config_file_is_read_as_vtrack_track_reads_it(data, vtrack_cli, client, tmp_path):
    """The same YAML config (seed, background and tracker sections) through vtrack track and
    through a batch: the same bytes; --set overrides the file in both."""
    video = data[0] / "clips" / "s2.avi"
    config = tmp_path / "params.yml"
    tracker = {k: v for k, v in SETTINGS.items() if k != "period"}
    config.write_text("seed: 5\nbackground:\n  period: 2\n  n_samples: 8\n"
                      "tracker:\n" + "".join(f"  {k}: {v}\n" for k, v in tracker.items()))
    reference = tmp_path / "reference.txt"
    result = vtrack_cli("track", video, "--out", reference, "--config", config, "--set",
                        "delta_f=0.2")
    assert result.returncode == 0, result.stderr
    runs = batch.track_many([video], tmp_path / "out", client=client, config=config, delta_f=0.2)
    assert runs[0]["status"] == "ok" and runs[0]["seed"] == 5
    background = runs[0]["parameters"]["parameters"]["background"]
    assert (background["period"], background["n_samples"]) == (2, 8)
    assert runs[0]["parameters"]["parameters"]["tracker"]["delta_f"] == 0.2
    assert (tmp_path / "out" / "s2" / "tracks.txt").read_bytes() == reference.read_bytes()


def _sequential_bytes(video, folder):
    """tracks.txt of a plain sequential run: vtrack.track_video then write_mot."""
    path = folder / f"{Path(video).stem}.expected.txt"
    write_mot(path, vtrack.track_video(video, "mb", seed=SEED, **SETTINGS))
    return path.read_bytes()


def _pid_writing(pids, path):
    """Which of `pids` has `path` open (from /proc/PID/fd), or None."""
    for pid in pids:
        try:
            fds = os.listdir(f"/proc/{pid}/fd")
        except OSError:
            continue
        for fd in fds:
            try:
                if os.readlink(f"/proc/{pid}/fd/{fd}") == str(path):
                    return pid
            except OSError:
                pass
    return None


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="finds the worker in /proc")
def test_worker_killed_mid_task_is_retried_and_outputs_are_whole(client, tmp_path):
    """A worker process is SIGKILLed while it writes an input's render; Dask reruns the task on
    a live worker and every output is whole: the tracks equal a sequential run's, the render has
    every frame, no temporary file is left."""
    videos = [tmp_path / "clips" / f"long{i}.avi" for i in range(2)]
    for i, v in enumerate(videos):
        _write_scene(v, seed=30 + i, frames=150)
    out = tmp_path / "out"
    pids = set(client.run(os.getpid).values())
    result = {}
    worker = threading.Thread(target=lambda: result.setdefault("runs", batch.track_many(
        [str(v) for v in videos], out, client=client, seed=SEED, render=True, **SETTINGS)))
    worker.start()
    killed = None
    deadline = time.monotonic() + 60
    while killed is None and time.monotonic() < deadline and worker.is_alive():
        for partial in out.glob("*/.render.*"):
            pid = _pid_writing(pids, partial)
            if pid is not None:
                os.kill(pid, signal.SIGKILL)
                killed = (pid, partial.parent.name)
                break
        time.sleep(0.005)
    worker.join(120)
    assert killed is not None, "no task was caught writing its render"
    assert killed[0] not in set(client.run(os.getpid).values())
    runs = {r["name"]: r for r in result["runs"]}
    assert runs[killed[1]]["status"] == "ok" and runs[killed[1]]["pid"] != killed[0]
    for v in videos:
        name = v.stem
        assert runs[name]["status"] == "ok", runs[name]
        assert (out / name / "tracks.txt").read_bytes() == _sequential_bytes(v, tmp_path)
        assert vtrack.io.probe_video(out / name / "render.mp4").frame_count == 150
    assert _leftovers(out) == []


def _python_batch(args):
    """`python -m vtrack.batch ARGS` in a session of its own, with SIGINT's default disposition
    (a shell running pytest in the background may have left it ignored)."""
    return subprocess.Popen([sys.executable, "-m", "vtrack.batch", *map(str, args)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))


def test_ctrl_c_leaves_whole_files_and_the_cli_rerun_finishes(client, vtrack_cli, tmp_path):
    """Ctrl-C (SIGINT to the process group, as a terminal sends it) stops a run on its own local
    cluster with tasks in flight: exit 130, no temporary or partial file, every tracks.txt whole.
    `vtrack batch` (the C++ CLI handing over to Python) re-runs the command on an existing
    cluster (--scheduler): it does the rest only, and exits 1 because one input is missing."""
    clips = tmp_path / "clips"
    for i in range(4):
        _write_scene(clips / f"c{i}.avi", seed=40 + i, frames=120)
    out = tmp_path / "out"
    sets = [a for k, v in SETTINGS.items() for a in ("--set", f"{k}={v}")]
    args = [clips / "*.avi", tmp_path / "missing.avi", "--out", out, "--workers", 2,
            "--seed", SEED, "--quiet", *sets]
    def complete():
        return {p.parent.name for p in out.glob("*/run.json")
                if json.loads(p.read_text())["status"] == "ok"}

    proc = _python_batch(args)
    deadline = time.monotonic() + 60
    while not complete() and time.monotonic() < deadline:  # (missing.avi fails at once)
        time.sleep(0.01)
    os.killpg(proc.pid, signal.SIGINT)
    _, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 130, stderr
    assert "vtrack: error: interrupted" in stderr
    assert _leftovers(out) == []
    done = complete()
    assert 1 <= len(done) < 4, done

    expected = {f"c{i}": _sequential_bytes(clips / f"c{i}.avi", tmp_path) for i in range(4)}
    for tracks in out.glob("*/tracks.txt"):  # also those of tasks cut short: whole or absent
        assert tracks.read_bytes() == expected[tracks.parent.name], tracks
    summary = _summary(out)
    assert {r[1] for r in summary[1:] if r[2] == "ok"} == done
    before = _mtimes(out)

    at = args.index("--workers")
    args[at:at + 2] = ["--scheduler", client.scheduler.address]
    result = vtrack_cli("batch", *args)
    assert result.returncode == 1, result.stderr
    assert "missing" in result.stderr
    summary = _summary(out)
    assert [(r[1], r[2]) for r in summary[1:]] == [(f"c{i}", "ok") for i in range(4)] + [
        ("missing", "failed")]
    for name in done:
        assert _mtimes(out)[out / name / "run.json"] == before[out / name / "run.json"]
    for name, tracks in expected.items():
        assert (out / name / "tracks.txt").read_bytes() == tracks, name
    assert _leftovers(out) == []


def _page_faults_of_freed_buffers(n=200, nbytes=1 << 20):
    """Minor page faults of allocating, touching and freeing an image-sized buffer n times: a few
    hundred when the C library reuses the freed memory, ~n x nbytes / page when it maps it anew."""
    import resource  # noqa: PLC0415

    import numpy as np  # noqa: PLC0415

    before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    for _ in range(n):
        buffer = np.ones(nbytes, np.uint8)
        del buffer
    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before


def test_local_cluster_workers_reuse_freed_memory(monkeypatch):
    """vtrack's own local cluster starts its workers without Dask's MALLOC_TRIM_THRESHOLD_ (which
    maps every frame's buffers afresh, ~10 % more CPU per frame; see batch.local_cluster), keeping
    Dask's other worker settings. (This module's other clusters leave the variable in
    os.environ: Dask's nannies set it there for good.)"""
    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)
    here = _page_faults_of_freed_buffers()
    cluster = batch.local_cluster(1, dashboard_address=":0")
    with distributed.Client(cluster) as c:
        environ = c.run(lambda: (os.environ.get("MALLOC_TRIM_THRESHOLD_"),
                                 os.environ.get("OMP_NUM_THREADS")))
        faults = c.run(_page_faults_of_freed_buffers)
    cluster.close()
    assert list(environ.values()) == [(None, "1")]
    mapped_afresh = 200 * (1 << 20) // os.sysconf("SC_PAGE_SIZE")
    assert list(faults.values())[0] < max(3 * here, mapped_afresh // 10)


def test_usage_errors_exit_2_before_anything_runs(data, capsys, tmp_path):
    root, _ = data
    video = root / "clips" / "s1.avi"
    out = tmp_path / "out"
    cases = [
        ((video,), "--out"),
        ((video, "--out", out, "--set", "no_such=1"), "no_such"),
        ((video, "--out", out, "--set", "sigma_x=-1"), "sigma_x"),
        ((video, "--out", out, "--set", "novalue"), "name=value"),
        ((video, "--out", out, "--method", "nope"), "--method"),
        ((tmp_path / "*.none", "--out", out), "matches nothing"),
        ((video, "--out", out, "--workers", "0"), "--workers"),
        ((video, "--out", out, "--gt", "{nope}/gt.txt"), "--gt"),
        ((video, "--out", out, "--workers", "2", "--scheduler", "tcp://x:1"), "--scheduler"),
        ((video, "--out", out, "--seed", "-1"), "seed"),
        ((video, "--out", out, "--config", tmp_path / "none.yml"), "none.yml"),
        ((video, "--out", out, "--method", "glmb"), "detector"),
        ((video, "--out", root / "clips"), "overlaps the input"),
        ((root / "frames", "--out", root / "frames" / "s3" / "out"), "overlaps the input"),
        ((video, "--out", video), "not a folder"),
    ]
    for args, message in cases:
        try:
            status = batch.main([str(a) for a in args])
        except SystemExit as exit:  # argparse
            status = exit.code
        err = capsys.readouterr().err
        assert status == 2, (args, err)
        assert "vtrack: error: " in err and message in err, (args, err)
    assert not out.exists()  # found before anything ran
    assert not (root / "frames" / "s3" / "out").exists()


def test_unreachable_scheduler_is_a_clear_error(data, capsys, tmp_path):
    with socket.socket() as s:  # a port nothing listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    with dask.config.set({"distributed.comm.timeouts.connect": "2s"}):
        status = batch.main([str(data[0] / "clips" / "s1.avi"), "--out", str(tmp_path / "out"),
                             "--scheduler", f"tcp://127.0.0.1:{port}", "--quiet"])
    err = capsys.readouterr().err
    assert status == 1 and f"cannot reach the Dask scheduler at tcp://127.0.0.1:{port}" in err, err


def test_cli_hands_batch_to_python(vtrack_cli, data, tmp_path):
    """`vtrack batch` execs `python -m vtrack.batch` (help and errors included), and says what
    is missing when it cannot: no interpreter with vtrack, or no Dask."""
    video = data[0] / "clips" / "s1.avi"
    out = tmp_path / "out"
    help_text = vtrack_cli("batch", "--help")
    assert help_text.returncode == 0 and help_text.stdout.startswith("usage: vtrack batch")
    assert "--scheduler" in help_text.stdout
    result = vtrack_cli("batch", video, "--out", out, "--set", "no_such=1")
    assert result.returncode == 2 and "vtrack: error: " in result.stderr
    assert "no_such" in result.stderr
    env = dict(os.environ, VTRACK_PYTHON=str(tmp_path / "no-python"))
    exe = Path(sys.executable).parent / "vtrack"
    result = subprocess.run([exe, "batch", video, "--out", out], capture_output=True, text=True,
                            env=env, timeout=60)
    assert result.returncode == 2 and "vtrack: error: " in result.stderr
    assert "no-python: cannot run it" in result.stderr and "VTRACK_PYTHON" in result.stderr
    code = ("import runpy, sys; sys.modules['distributed'] = None; "
            "runpy.run_module('vtrack.batch', run_name='__main__')")
    result = subprocess.run([sys.executable, "-c", code, str(video), "--out", str(out)],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 2 and "pip install 'vtrack[batch]'" in result.stderr
    assert not out.exists()


def test_inputs_names_are_unique_and_independent_of_order(tmp_path):
    for rel in ("a/cam.avi", "b/cam.avi", "b/cam.mp4", "x/a__cam.avi", "MOT/SEQ-02/img1/1.png",
                "solo.avi"):
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_bytes(b"")
    listing = tmp_path / "list.lst"
    listing.write_text("a/cam.avi\nb/cam.*\n# comment\n\nMOT/*/img1\nsolo.avi\n./solo.avi\n")
    items = batch.expand_inputs([listing])
    names = {Path(i.path).relative_to(tmp_path).as_posix(): i.name for i in items}
    assert names == {"a/cam.avi": "a__cam", "b/cam.avi": "b__cam", "b/cam.mp4": "cam.mp4",
                     "MOT/SEQ-02/img1": "SEQ-02", "solo.avi": "solo"}
    # A name another input's path also gives ("a__cam"): still all different, whatever the order.
    paths = [str(tmp_path / p) for p in [*names, "x/a__cam.avi"]]
    forward = {i.path: i.name for i in batch.expand_inputs(paths)}
    assert len(set(forward.values())) == len(paths)
    assert {i.path: i.name for i in batch.expand_inputs(paths[::-1])} == forward
    # Paths whose every name candidate collides are told apart by a hash of the path.
    tricky = ["/data/a/b__c.avi", "/data/a/b/c.avi", "/data/z/c.avi"]
    names = batch._unique_names(tricky)
    assert len(set(names)) == 3 and names[2] == "z__c", names
    with pytest.raises(batch.UsageError, match="matches nothing"):
        batch.expand_inputs([str(tmp_path / "*.mkv")])


def test_settings_are_read_by_the_cli_parser_and_override_keywords():
    """--set texts go through the C++ parser (`vtrack params` prints the same values): true/false,
    integers, reals, lists of reals, names; they override keywords, keywords the config."""
    job = batch.make_job("mb", settings=["period=2", "bandwidth=0.01,0.02,0.05",
                                         "resampling=residual", "seed=7"], seed=3, period=5)
    sections = job["parameters"]
    assert sections["background"]["period"] == 2 and sections["tracker"]["seed"] == 7
    assert sections["background"]["bandwidth"] == [0.01, 0.02, 0.05]
    assert sections["tracker"]["resampling"] == "residual"
    assert sections["background"]["threads"] == 1  # left at its default: one per worker
    assert batch.make_job("mb", threads=2)["parameters"]["background"]["threads"] == 2
    with pytest.raises(ValueError, match="name=value"):
        batch.make_job("mb", settings=["novalue"])
    with pytest.raises(TypeError, match="no_such"):
        batch.make_job("mb", settings=["no_such=1"])
    with pytest.raises(ValueError, match="detector"):
        batch.make_job("glmb")
