"""The bad-input matrix (issue 16): every CLI subcommand and every public Python entry point against
missing, empty, truncated and corrupt files, wrong dtypes and shapes, NaN/inf/negative/huge
parameters and colliding outputs. Each case asserts the exit code (2 for a malformed command line,
1 for bad data, as the README says) or the exception type (TypeError, ValueError, OSError -- never
RuntimeError, SystemError or a crash), that the message names the problem, and that nothing
partial is left behind."""

import json
import math
import os
import subprocess
import sysconfig
from pathlib import Path

import numpy as np
import pytest

import vtrack

EXE = Path(sysconfig.get_path("scripts")) / "vtrack"
MOTION = vtrack.LinearGaussianMotion.constant_velocity(axes=2, period=1.0, sigma_v=5.0)
OBSERVATION = vtrack.LinearGaussianObservation.position(axes=2, R=np.eye(2) * 100.0)
GOOD_DET = b"".join(b"%d,-1,%d,100,40,100,0.9\n" % (k, 100 + 3 * k) for k in range(1, 6))


def _video_bytes(frames=3, size=(48, 32)):
    import cv2
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "v.avi")
        w = cv2.VideoWriter(path, cv2.VideoWriter_fourcc(*"MJPG"), 10, size)
        rng = np.random.default_rng(0)
        for _ in range(frames):
            w.write(rng.integers(0, 255, (size[1], size[0], 3), dtype=np.uint8))
        w.release()
        return Path(path).read_bytes()


VIDEO = _video_bytes()

# Input files, by kind: (name, bytes or None for "missing", or "dir" for a folder).
FILES = {
    "missing": ("none.txt", None),
    "folder": ("folder", "dir"),
    "empty": ("empty.txt", b""),
    "binary": ("noise.txt", bytes(range(256)) * 4),
    "non_utf8": ("latin1.txt", b"1,-1,1,2,3,4,0.9\n2,-1,\xe9,2,3,4,0.9\n"),
}
VIDEOS = {
    "missing": ("none.avi", None),
    "empty": ("empty.avi", b""),
    "truncated": ("cut.avi", VIDEO[: len(VIDEO) // 2]),
    "corrupt": ("noise.avi", bytes(np.random.default_rng(1).integers(0, 256, 4096, dtype=np.uint8))),
    "empty_folder": ("frames", "dir"),
}
DETS = {
    **FILES,
    "nan": ("nan.txt", b"1,-1,nan,2,3,4,0.9\n"),
    "inf": ("inf.txt", b"1,-1,1,2,inf,4,0.9\n"),
    "negative_size": ("neg.txt", b"1,-1,1,2,-3,4,0.9\n"),
    "frame_zero": ("f0.txt", b"0,-1,1,2,3,4,0.9\n"),
    "frame_fraction": ("ff.txt", b"1.5,-1,1,2,3,4,0.9\n"),
    "frame_huge": ("fh.txt", b"1e16,-1,1,2,3,4,0.9\n"),
    "coordinate_huge": ("ch.txt", b"1,-1,1e12,2,3,4,0.9\n"),
    "too_few_fields": ("short.txt", b"1,-1,1,2,3\n"),
    "truncated_line": ("cutline.txt", GOOD_DET + b"6,-1,1"),
}
# A road camera (vtrack.synthetic_road's gantry set-up), an observations file of one vehicle's
# silhouettes, and bad camera and observations files for `vtrack vehicles`.
CAMERA_JSON = (b'{"K": [[900, 0, 479.5], [0, 900, 269.5], [0, 0, 1]], "dist": [], '
               b'"R": [[1, 0, 0], [0, -0.27563735581699916, -0.9612616959383189], '
               b'[0, 0.9612616959383189, -0.27563735581699916]], '
               b'"t": [-5.25, 7.209462719537392, 2.0672801686274935], "image_size": [960, 540]}')
GOOD_OBS = b"frame,vehicle_id,x,y,w,h\n" + b"".join(
    b"%d,1,%d,300,60,50\n" % (k, 400 + 5 * k) for k in range(1, 6))
CAMERA_CONTENTS = {
    "missing_key": ("nokey.json", b'{"K": [[900, 0, 479.5], [0, 900, 269.5], [0, 0, 1]], "dist": []}'),
    "singular_R": ("singular.json", CAMERA_JSON.replace(b'"R": [[1, 0, 0]', b'"R": [[0, 0, 0]')),
    "non_orthonormal_R": ("skewR.json", CAMERA_JSON.replace(b'"R": [[1, 0, 0]', b'"R": [[1, 0.2, 0]')),
    "looking_up": ("up.json", CAMERA_JSON.replace(b'0.9612616959383189, -0.27563735581699916]]',
                                                 b'-0.9612616959383189, 0.27563735581699916]]')),
}
CAMERAS = {**FILES, **CAMERA_CONTENTS}
OBSERVATIONS = {
    **FILES,
    "nan": ("nan.csv", b"1,1,nan,300,60,50\n"),
    "frame_zero": ("f0.csv", b"0,1,400,300,60,50\n"),
    "frame_fraction": ("ff.csv", b"1.5,1,400,300,60,50\n"),
    "negative_size": ("neg.csv", b"1,1,400,300,-60,50\n"),
    "odd_coordinates": ("odd.csv", b"1,1,400,300,460,300,460\n"),
    "too_few_fields": ("short.csv", b"1,1,400,300\n"),
    "above_horizon": ("sky.csv", b"1,1,400,-900,60,50\n"),
    "frames_backwards": ("back.csv", b"2,1,400,300,60,50\n1,1,400,300,60,50\n"),
    "truncated_line": ("cut.csv", GOOD_OBS + b"6,1,4"),
}
_camera_file = json.loads(CAMERA_JSON)
_CAMERA = vtrack.vehicles.Camera(_camera_file["K"], _camera_file["dist"], _camera_file["R"], _camera_file["t"],
                                 image_size=tuple(_camera_file["image_size"]))
CONFIGS = {
    **FILES,
    "syntax": ("syntax.yml", b"tracker:\n  a: 1\n b: [\n"),
    "deep": ("deep.yml", b"tracker: " + b"[" * 5000 + b"]" * 5000 + b"\n"),
    "unknown_section": ("section.yml", b"trackr: {}\n"),
    "unknown_name": ("name.yml", b"tracker: {n_particle: 3}\n"),
    "wrong_kind": ("kind.yml", b"tracker: {birth_particles: abc}\n"),
    "int_overflow": ("big.yml", b"tracker: {birth_particles: 99999999999}\n"),
    "nan": ("nan.yml", b"tracker: {delta_f: .nan}\n"),
    "negative": ("neg.yml", b"tracker: {delta_f: -1}\n"),
    "two_documents": ("two.yml", b"seed: 1\n---\nseed: 2\n"),
    "list_as_name": ("key.yml", b"tracker: {[a]: 1}\n"),
}


def make(tmp_path, spec):
    name, content = spec
    path = tmp_path / "in" / name
    path.parent.mkdir(exist_ok=True)
    if content == "dir":
        path.mkdir()
    elif content is not None:
        path.write_bytes(content)
    return path


def cli(tmp_path, *args):
    out = tmp_path / "out"
    out.mkdir(exist_ok=True)
    # Messages quote the bytes they name (a det file's stray byte): decoded leniently here.
    result = subprocess.run([str(EXE), *map(str, args)], capture_output=True, text=True, timeout=300,
                            cwd=out, errors="backslashreplace")
    # Nothing partial: a failed run leaves its output folder as it found it (empty).
    left = sorted(p.name for p in out.iterdir())
    return result, left


def good_det(tmp_path):
    path = tmp_path / "in" / "good.txt"
    path.parent.mkdir(exist_ok=True)
    path.write_bytes(GOOD_DET)
    return path


# ---------------------------------------------------------------------------------------------
# CLI: bad files (exit 1, the message names the file)

CLI_FILE_CASES = (
    [("info", kind) for kind in VIDEOS]
    + [("bgs", kind) for kind in VIDEOS]
    + [("track-mb", kind) for kind in VIDEOS]
    + [("track-sir", kind) for kind in VIDEOS]
    + [("track-hog", kind) for kind in VIDEOS]
    + [("track-det", kind) for kind in DETS]
    + [("track-config", kind) for kind in CONFIGS]
    + [("bgs-config", kind) for kind in CONFIGS]
    + [("params-config", kind) for kind in CONFIGS]
    + [("follow", kind) for kind in VIDEOS]
    + [("follow-config", kind) for kind in CONFIGS]
    + [("vehicles-obs", kind) for kind in OBSERVATIONS]
    + [("vehicles-video", kind) for kind in VIDEOS]
    + [("vehicles-camera", kind) for kind in CAMERAS]
    + [("vehicles-config", kind) for kind in CONFIGS]
)


@pytest.mark.parametrize("command,kind", CLI_FILE_CASES, ids=[f"{c}-{k}" for c, k in CLI_FILE_CASES])
def test_cli_bad_files(tmp_path, command, kind):
    out = tmp_path / "out"
    if command.endswith("config"):
        spec = CONFIGS[kind]
    elif command == "vehicles-video":
        spec = VIDEOS[kind]
    elif command == "vehicles-obs":
        spec = OBSERVATIONS[kind]
    elif command == "vehicles-camera":
        spec = CAMERAS[kind]
    elif command == "track-det":
        spec = DETS[kind]
    else:
        spec = VIDEOS[kind]
    bad = make(tmp_path, spec)
    args = {
        "info": ["info", bad],
        "bgs": ["bgs", bad, "--out", out / "y.avi"],
        "track-mb": ["track", bad, "--out", out / "t.txt", "--render", out / "r.avi"],
        "track-sir": ["track", bad, "--method", "sir", "--out", out / "t.txt", "--render",
                      out / "r.avi"],
        "track-hog": ["track", bad, "--method", "glmb", "--detector", "hog", "--out", out / "t.txt",
                      "--save-detections", out / "d.txt"],
        "track-det": ["track", "--detections", bad, "--method", "glmb", "--out", out / "t.txt"],
        "track-config": ["track", "--detections", good_det(tmp_path), "--method", "glmb",
                         "--config", bad, "--out", out / "t.txt"],
        "bgs-config": ["bgs", make(tmp_path, ("v.avi", VIDEO)), "--config", bad, "--out",
                       out / "y.avi"],
        "params-config": ["params", "--config", bad],
        "follow": ["follow", bad, "--init", "1,1,8,8", "--out", out / "t.txt", "--render",
                   out / "r.avi"],
        "follow-config": ["follow", make(tmp_path, ("v.avi", VIDEO)), "--init", "1,1,8,8",
                          "--config", bad, "--out", out / "t.txt"],
        "vehicles-obs": ["vehicles", "--observations", bad, "--camera", make(tmp_path, ("cam.json", CAMERA_JSON)),
                         "--out", out / "v.csv"],
        "vehicles-video": ["vehicles", bad, "--camera", make(tmp_path, ("cam.json", CAMERA_JSON)), "--out",
                           out / "v.csv", "--tracks", out / "t.txt", "--render", out / "r.avi"],
        "vehicles-camera": ["vehicles", "--observations", make(tmp_path, ("obs.csv", GOOD_OBS)), "--camera", bad,
                            "--out", out / "v.csv"],
        "vehicles-config": ["vehicles", "--observations", make(tmp_path, ("obs.csv", GOOD_OBS)), "--camera",
                            make(tmp_path, ("cam.json", CAMERA_JSON)), "--config", bad, "--out", out / "v.csv"],
    }[command]
    result, left = cli(tmp_path, *args)
    if kind == "empty" and command in ("track-det", "track-config", "bgs-config", "params-config",
                                       "follow-config", "vehicles-obs", "vehicles-config"):
        # Valid: a det file without rows tracks nothing, an empty config changes nothing, an
        # observations file without rows has no vehicles.
        assert result.returncode == 0, result.stderr
        return
    assert result.returncode == 1, (args, result.returncode, result.stderr)
    assert result.stderr.startswith("vtrack: error: "), result.stderr
    message = result.stderr
    assert bad.name in message or "frame" in message or "parameter" in message or \
        any(word in message for word in ("section", "name", "nested", "line", "delta_f",
                                         "birth_particles", "vehicle")), message
    assert "Traceback" not in message and "terminate called" not in message
    assert left == [], left


# ---------------------------------------------------------------------------------------------
# CLI: malformed command lines (exit 2, the message names the option)

USAGE_CASES = [
    (["track"], "needs"),
    (["track", "{video}"], "--out"),
    (["track", "{video}", "--out"], "--out"),
    (["track", "{video}", "--out", "{out}", "--method", "sort"], "method must be one of"),
    (["track", "{video}", "--out", "{out}", "--seed", "-1"], "--seed"),
    (["track", "{video}", "--out", "{out}", "--seed", "abc"], "--seed"),
    (["track", "{video}", "--out", "{out}", "--seed", str(2**64)], "--seed"),
    (["track", "{video}", "--out", "{out}", "--set", "delta_f=nan"], "delta_f"),
    (["track", "{video}", "--out", "{out}", "--set", "delta_f=-1"], "delta_f"),
    (["track", "{video}", "--out", "{out}", "--set", "delta_f=inf"], "delta_f"),
    (["track", "{video}", "--out", "{out}", "--set", "delta_f=1e400"], "delta_f"),
    (["track", "{video}", "--out", "{out}", "--set", "birth_particles=99999999999"], "birth_particles"),
    (["track", "{video}", "--out", "{out}", "--set", "birth_particles=-3"], "birth_particles"),
    (["track", "{video}", "--out", "{out}", "--set", "birth_particles=2.5"], "birth_particles"),
    (["track", "{video}", "--out", "{out}", "--set", "max_particles=10000000"], "max_particles"),
    (["track", "{video}", "--out", "{out}", "--set", "resampling=bogus"], "resampling"),
    (["track", "{video}", "--out", "{out}", "--set", "nosuch=1"], "nosuch"),
    (["track", "{video}", "--out", "{out}", "--set", "delta_f"], "name=value"),
    (["track", "{video}", "--out", "{out}", "--render", "{out_dir}/r.txt"], "--render"),
    (["track", "{video}", "--out", "{out}", "--bogus"], "--bogus"),
    (["track", "{video}", "--out", "{out}", "--method", "glmb"], "--detector hog"),
    (["track", "--detections", "{det}", "--method", "glmb", "--out", "{out}", "--image-size", "0x10"],
     "--image-size"),
    (["track", "--detections", "{det}", "--method", "glmb", "--out", "{out}", "--image-size",
      "2000000x10"], "--image-size"),
    (["track", "--detections", "{det}", "--method", "glmb", "--out", "{out}", "--image-size", "axb"],
     "--image-size"),
    (["track", "--detections", "{det}", "--method", "glmb", "--out", "{out}", "--set",
      "hypothesis_budget=1000000"], "hypothesis_budget"),
    (["track", "--detections", "{det}", "--method", "glmb", "--out", "{out}", "--set",
      "hypothesis_budget=0"], "hypothesis_budget"),
    (["track", "--detections", "{det}", "--method", "glmb", "--out", "{out}", "--set",
      "min_confidence=nan"], "min_confidence"),
    (["track", "--detections", "{det}", "--method", "glmb", "--out", "{out}", "--set",
      "detection_probability=1.5"], "detection_probability"),
    (["track", "--detections", "{det}", "--method", "glmb", "--out", "{out}", "--set",
      "last_frame=5"], "last_frame"),
    (["track", "--detections", "{det}", "--method", "mb", "--out", "{out}"], "--detections"),
    (["track", "--detections", "{det}", "--method", "glmb", "--out", "{det}"], "--out"),
    (["track", "{video}", "--out", "{video}"], "--out"),
    (["track", "{video}", "--out", "{out}", "--render", "{video}"], "--render"),
    (["track", "{video}", "--out", "{out}", "--render", "{out}"], "--render"),
    (["bgs"], "VIDEO"),
    (["bgs", "{video}"], "--out"),
    (["bgs", "{video}", "--out", "{video}"], "--out"),
    (["bgs", "{in_dir}", "--out", "{in_dir}"], "--out"),
    (["bgs", "{video}", "--out", "{out_dir}/y.avi", "--set", "n_samples=0"], "n_samples"),
    (["bgs", "{video}", "--out", "{out_dir}/y.avi", "--set", "bandwidth=0.1,nan,0.1"], "bandwidth"),
    (["bgs", "{video}", "--out", "{out_dir}/y.avi", "--set", "threads=-1"], "threads"),
    (["info"], "VIDEO"),
    (["info", "{video}", "{video}"], "info"),
    (["params", "--method", "x"], "method must be one of"),
    (["params", "--set", "delta_f=abc"], "delta_f"),
    (["params", "--seed", "-5"], "--seed"),
    (["vehicles"], "--camera"),
    (["vehicles", "--observations", "{obs}", "--camera", "{cam}"], "--out"),
    (["vehicles", "--camera", "{cam}", "--out", "{out}"], "--observations"),
    (["vehicles", "--observations", "{obs}", "--camera", "{cam}", "--out", "{obs}"], "--out"),
    (["vehicles", "--observations", "{obs}", "--camera", "{cam}", "--out", "{cam}"], "--out"),
    (["vehicles", "--observations", "{obs}", "--camera", "{cam}", "--out", "{out}", "--tracks", "{out_dir}/t.txt"],
     "--tracks"),
    (["vehicles", "--observations", "{obs}", "--camera", "{cam}", "--out", "{out}", "--set", "n_particles=0"],
     "n_particles"),
    (["vehicles", "--observations", "{obs}", "--camera", "{cam}", "--out", "{out}", "--set", "sampler=gibbs"],
     "sampler"),
    (["vehicles", "--observations", "{obs}", "--camera", "{cam}", "--out", "{out}", "--set", "sigma_w=nan"],
     "sigma_w"),
    (["vehicles", "--observations", "{obs}", "--camera", "{cam}", "--out", "{out}", "--seed", "-1"], "--seed"),
    (["vehicles", "--observations", "{obs}", "--camera", "{cam}", "--out", "{out}", "--bogus", "1"], "--bogus"),
    (["vehicles", "{video}", "--observations", "{obs}", "--camera", "{cam}", "--out", "{out}"], "either"),
    (["vehicles", "{video}", "--camera", "{cam}", "--out", "{out}", "--render", "{out_dir}/r.txt"], "--render"),
    (["vehicles", "{video}", "--camera", "{cam}", "--out", "{out}", "--tracks", "{video}"], "--tracks"),
    (["vehicles", "{video}", "--camera", "{cam}", "--out", "{out}", "--set", "min_area=-1"], "min_area"),
    (["vehicles", "{video}", "--camera", "{cam}", "--out", "{out}", "--set", "blob_closing=4"], "blob_closing"),
    (["bogus"], "bogus"),
    ([], "no command"),
    (["follow", "{video}", "--out", "{out}"], "--init"),
    (["follow", "{video}", "--init", "1,1,4,4"], "--out"),
    (["follow", "--init", "1,1,4,4", "--out", "{out}"], "VIDEO"),
    (["follow", "{video}", "--init", "1,1,4", "--out", "{out}"], "--init"),
    (["follow", "{video}", "--init", "1,1,4,4", "--out", "{out}", "--method", "x"], "method must be one of"),
    (["follow", "{video}", "--init", "1,1,4,4", "--out", "{out}", "--set", "sigma=nan"], "sigma"),
    (["follow", "{video}", "--init", "1,1,4,4", "--out", "{out}", "--set", "nosuch=1"], "nosuch"),
    (["follow", "{video}", "--init", "1,1,4,4", "--out", "{out}", "--particles", "0"], "n_particles"),
    (["follow", "{video}", "--init", "1,1,4,4", "--out", "{out}", "--first", "0"], "--first"),
    (["follow", "{video}", "--init", "1,1,4,4", "--out", "{out}", "--first", "3", "--last", "2"],
     "--last"),
    (["follow", "{video}", "--init", "1,1,4,4", "--out", "{video}"], "--out"),
    (["follow", "{video}", "--init", "1,1,4,4", "--out", "{out}", "--render", "{video}"], "--render"),
    (["follow", "{video}", "--init", "1,1,4,4", "--out", "{out}", "--seed", "-1"], "--seed"),
]


@pytest.mark.parametrize("args,word", USAGE_CASES, ids=[" ".join(a) or "none" for a, _ in USAGE_CASES])
def test_cli_usage_errors(tmp_path, args, word):
    video = make(tmp_path, ("v.avi", VIDEO))
    det = good_det(tmp_path)
    before = {p: p.read_bytes() for p in (video, det, tmp_path / "in" / "obs.csv", tmp_path / "in" / "cam.json")
              if p.exists()}
    names = {"video": video, "det": det, "out": tmp_path / "out" / "t.txt",
             "obs": make(tmp_path, ("obs.csv", GOOD_OBS)), "cam": make(tmp_path, ("cam.json", CAMERA_JSON)),
             "out_dir": tmp_path / "out", "in_dir": tmp_path / "in"}
    result, left = cli(tmp_path, *[a.format(**names) for a in args])
    assert result.returncode == 2, (args, result.returncode, result.stderr)
    assert result.stderr.startswith("vtrack: error: "), result.stderr
    assert word in result.stderr, (word, result.stderr)
    assert left == [], left
    assert {p: p.read_bytes() for p in before} == before


# ---------------------------------------------------------------------------------------------
# Python: file readers (OSError for a missing/unreadable file, ValueError for bad content; the
# message names the file)

READERS = {
    "read_detections": (vtrack.io.read_detections, DETS),
    "read_mot": (vtrack.io.read_mot, DETS),
    "track_detections": (vtrack.track_detections, DETS),
    "load_config": (vtrack.load_config, CONFIGS),
    "probe_video": (vtrack.io.probe_video, VIDEOS),
    "track_video": (lambda p: vtrack.track_video(p, method="mb"), VIDEOS),
    "track_video_sir": (lambda p: vtrack.track_video(p, method="sir"), VIDEOS),
    "read_camera_file": (vtrack.vehicles.read_camera_file, FILES),
    "read_vehicle_models_file": (vtrack.vehicles.read_vehicle_models_file, FILES),
    "read_camera_file_contents": (vtrack.vehicles.read_camera_file, CAMERA_CONTENTS),
    "estimate_vehicles": (lambda p: vtrack.vehicles.estimate_vehicles(p, _CAMERA), OBSERVATIONS),
    "measure_vehicles": (lambda p: vtrack.vehicles.measure_vehicles(p, _CAMERA), VIDEOS),
}
READER_CASES = [(r, k) for r, (_, kinds) in READERS.items() for k in kinds]
# Contents a reader accepts as valid (empty det/MOT files are no rows; a config may be empty; a
# MOT reader takes any numbers; load_config reads a file without applying it).
ACCEPTED = {
    ("read_detections", "empty"), ("read_mot", "empty"), ("track_detections", "empty"),
    ("load_config", "empty"), ("read_mot", "negative_size"), ("read_mot", "frame_huge"),
    ("read_mot", "coordinate_huge"), ("read_mot", "too_few_fields"),
    ("load_config", "unknown_section"), ("load_config", "unknown_name"), ("load_config", "wrong_kind"),
    ("load_config", "int_overflow"), ("load_config", "nan"), ("load_config", "negative"),
    ("probe_video", "truncated"), ("track_video", "truncated"), ("track_video_sir", "truncated"),
    ("estimate_vehicles", "empty"), ("measure_vehicles", "truncated"),
}


@pytest.mark.parametrize("reader,kind", READER_CASES, ids=[f"{r}-{k}" for r, k in READER_CASES])
def test_python_readers(tmp_path, reader, kind):
    function, kinds = READERS[reader]
    path = make(tmp_path, kinds[kind])
    if (reader, kind) in ACCEPTED:
        try:
            function(path)
        except (OSError, ValueError) as e:  # a truncated video may fail at the cut: named
            assert (reader, kind) in {("probe_video", "truncated"), ("track_video", "truncated"),
                                      ("measure_vehicles", "truncated"), ("track_video_sir", "truncated"),
                                      ("read_mot", "too_few_fields")}, e
            assert "frame" in str(e) or path.name in str(e), e
        return
    with pytest.raises((OSError, ValueError)) as error:
        function(path)
    message = str(error.value)
    assert path.name in message or "frame" in message, message
    if kind in ("missing", "folder"):
        assert isinstance(error.value, OSError), repr(error.value)
    assert not isinstance(error.value, UnicodeError)
    assert sorted(p.name for p in path.parent.iterdir()) == sorted(
        [kinds[kind][0]] if kinds[kind][1] is not None else [])


# ---------------------------------------------------------------------------------------------
# Python: parameters of every parameterised class, NaN/inf/negative/huge/wrong kind

_RANGE_BEARING = vtrack.models.RangeBearingObservation()
_PRIOR_4D = vtrack.smc.Gaussian([10.0, 0.0, 10.0, 0.0], np.eye(4))
CLASSES = {
    "KdeBackground": lambda **kw: vtrack.KdeBackground(**kw),
    "MultiBernoulliTracker": lambda **kw: vtrack.MultiBernoulliTracker((64, 48), **kw),
    "ReclusteringSirTracker": lambda **kw: vtrack.ReclusteringSirTracker((64, 48), **kw),
    "BoxTracker": lambda **kw: vtrack.BoxTracker((64, 48), **kw),
    "GlmbTracker": lambda **kw: vtrack.GlmbTracker(MOTION, OBSERVATION, [], **kw),
    "HogPeopleDetector": lambda **kw: vtrack.HogPeopleDetector(**kw),
    "DepthLikelihood": lambda **kw: vtrack.models.DepthLikelihood(64, 48, 50.0, **kw),
    "ColorParticleTracker": lambda **kw: vtrack.ColorParticleTracker(**kw),
    "PartParticleTracker": lambda **kw: vtrack.PartParticleTracker(**kw),
    "VehicleDimensionEstimator": lambda **kw: vtrack.vehicles.VehicleDimensionEstimator(_CAMERA, **kw),
    "ParticleFilter": lambda **kw: vtrack.smc.ParticleFilter(
        vtrack.models.RandomWalk([1.0, 0.1, 1.0, 0.1]), _RANGE_BEARING, prior=_PRIOR_4D, **kw),
    "MCMCParticleFilter": lambda **kw: vtrack.smc.MCMCParticleFilter(
        vtrack.models.RandomWalk([1.0, 0.1, 1.0, 0.1]), _RANGE_BEARING, prior=_PRIOR_4D, **kw),
}
DEFAULTS = {
    "KdeBackground": vtrack.KdeBackground.default_params(),
    "MultiBernoulliTracker": vtrack.MultiBernoulliTracker.default_params(),
    "ReclusteringSirTracker": vtrack.ReclusteringSirTracker.default_params(),
    "BoxTracker": vtrack.BoxTracker.default_params(),
    "GlmbTracker": vtrack.GlmbTracker.default_params(),
    "HogPeopleDetector": vtrack.HogPeopleDetector.default_params(),
    "DepthLikelihood": vtrack.models.DepthLikelihood.default_params(),
    "ColorParticleTracker": vtrack.ColorParticleTracker.default_params(),
    "PartParticleTracker": vtrack.PartParticleTracker.default_params(),
    "VehicleDimensionEstimator": vtrack.vehicles.VehicleDimensionEstimator.default_params(),
    "ParticleFilter": vtrack.smc.ParticleFilter.default_params(),
    "MCMCParticleFilter": vtrack.smc.MCMCParticleFilter.default_params(),
}
# Always refused: NaN (no parameter means anything by it), a string, None, and (for an integer
# parameter) an int beyond its type. Refused or accepted (some parameters are documented to take
# them): inf, -inf, -1, 0, 1e300, and 2**70 for a real parameter. Refused means TypeError or
# ValueError naming the parameter.
ALWAYS_BAD = {"nan": math.nan, "str": "x", "none": None, "int_2_70": 2**70}
MAYBE_BAD = {"inf": math.inf, "-inf": -math.inf, "-1": -1, "0": 0, "1e300": 1e300}
PARAM_CASES = [(c, name, v) for c, d in DEFAULTS.items() for name, default in d.items()
               if isinstance(default, (int, float)) and not isinstance(default, bool)
               for v in list(ALWAYS_BAD) + list(MAYBE_BAD)]


@pytest.mark.parametrize("cls,name,value", PARAM_CASES,
                         ids=[f"{c}-{n}-{v}" for c, n, v in PARAM_CASES])
def test_python_parameters(cls, name, value):
    default = DEFAULTS[cls][name]
    given = {**ALWAYS_BAD, **MAYBE_BAD}[value]
    if isinstance(default, int) and isinstance(given, float) and math.isfinite(given) and \
            given == int(given) and abs(given) < 1e18:
        given = int(given)
    try:
        CLASSES[cls](**{name: given})
    except (TypeError, ValueError) as e:
        assert name in str(e), (name, str(e))
        return
    except MemoryError as e:  # e.g. a valid but huge image-independent allocation, named
        assert "cannot allocate" in str(e), e
        return
    assert value in MAYBE_BAD or (value == "int_2_70" and isinstance(default, float)), \
        f"{cls}({name}={given!r}) was accepted"


# ---------------------------------------------------------------------------------------------
# Python: arrays of the wrong dtype, shape or values for every array-taking entry point

BAD_ARRAYS = {
    "object": np.array([object()] * 4, dtype=object),
    "str": np.array(["a", "b"]),
    "complex": np.zeros((4, 4), np.complex128),
    "0d": np.float64(1.0),
    "3d": np.zeros((2, 2, 2)),
    "nan": np.full((4, 4), np.nan),
    "inf": np.full((4, 4), np.inf),
    "list_of_str": ["a", "b"],
    "none": None,
}
_box = vtrack.BoxTracker((64, 48))
_mb = vtrack.MultiBernoulliTracker((64, 48))
_sir = vtrack.ReclusteringSirTracker((64, 48))
_glmb = vtrack.GlmbTracker(MOTION, OBSERVATION, [])
_kde = vtrack.KdeBackground()
_hog = vtrack.HogPeopleDetector()
_ii = vtrack.image.IntegralImage(np.ones((8, 8), np.float32))
_depth = vtrack.models.DepthLikelihood(64, 48, 50.0)
_frame = np.random.default_rng(0).integers(1, 255, (48, 64, 3), dtype=np.uint8)
_color = vtrack.ColorParticleTracker()
_color.init(_frame, (10, 10, 20, 20))
_parts = vtrack.PartParticleTracker()
_parts.init(_frame, (10, 10, 20, 20))
_vehicles = vtrack.vehicles.VehicleDimensionEstimator(_CAMERA)
ARRAY_TAKERS = {
    "BoxTracker.step": _box.step,
    "MultiBernoulliTracker.step": _mb.step,
    "ReclusteringSirTracker.step": _sir.step,
    "ellipse_log_likelihood": lambda a: vtrack.trackers.ellipse_log_likelihood(
        (10.0, 10.0, 3.0, 5.0), a, 0.1, (2.0, 3.0)),
    "GlmbTracker.step": _glmb.step,
    "KdeBackground.apply": _kde.apply,
    "HogPeopleDetector.detect": _hog.detect,
    "IntegralImage": vtrack.image.IntegralImage,
    "IntegralImage.sums": _ii.sums,
    "bgr_to_rgi": vtrack.image.bgr_to_rgi,
    "foreground_mask": lambda a: vtrack.image.foreground_mask(a, threshold=0.5),
    "close_square": lambda a: vtrack.image.close_square(a, 3),
    "hsv_histogram": lambda a: vtrack.image.hsv_histogram(a, np.array([0.0, 0.0, 4.0, 4.0])),
    "bhattacharyya_coefficient": lambda a: vtrack.image.bhattacharyya_coefficient(a, a),
    "log_sum_exp": vtrack.smc.log_sum_exp,
    "normalize_log_weights": vtrack.smc.normalize_log_weights,
    "effective_sample_size": vtrack.smc.effective_sample_size,
    "resample": lambda a: vtrack.smc.resample(a, 0),
    "Gaussian": lambda a: vtrack.smc.Gaussian(a, a),
    "LinearGaussianMotion": lambda a: vtrack.LinearGaussianMotion(F=a, Q=a),
    "LinearGaussianObservation": lambda a: vtrack.LinearGaussianObservation(H=a, R=a),
    "DepthLikelihood.log_ratio": lambda a: _depth.log_ratio(a, np.zeros((1, 3))),
    "linear_assignment": vtrack.assign.linear_assignment,
    "murty": lambda a: vtrack.assign.murty(a, 3),
    "gibbs_assignments": lambda a: vtrack.assign.gibbs_assignments(a, 3, 0),
    "ospa": lambda a: vtrack.metrics.ospa(a, a, 5.0),
    "gospa": lambda a: vtrack.metrics.gospa(a, a, 5.0),
    "ospa2": lambda a: vtrack.metrics.ospa2(a, a, 5.0),
    "track_detections": lambda a: vtrack.track_detections(a),
    "write_mot": lambda a: vtrack.io.write_mot(os.devnull, a),
    "ColorParticleTracker.init": lambda a: vtrack.ColorParticleTracker().init(a, (0, 0, 4, 4)),
    "ColorParticleTracker.init-box": lambda a: vtrack.ColorParticleTracker().init(_frame, a),
    "ColorParticleTracker.update": _color.update,
    "PartParticleTracker.init": lambda a: vtrack.PartParticleTracker().init(a, (0, 0, 4, 4)),
    "PartParticleTracker.init-box": lambda a: vtrack.PartParticleTracker().init(_frame, a),
    "PartParticleTracker.update": _parts.update,
    "PartParticleTracker-parts": lambda a: vtrack.PartParticleTracker(parts=a),
    "VehicleDimensionEstimator.update": lambda a: _vehicles.update(1, a),
    "ParticleFilter.step": lambda a: CLASSES["ParticleFilter"](n_particles=50).step(a),
    "MCMCParticleFilter.step": lambda a: CLASSES["MCMCParticleFilter"](n_particles=20).step(a),
}
# Inputs some functions accept by definition: NaN rows are "absent" in ospa2 tracks and NaN
# depth is "no reading"; inf weights/costs have meanings in the log domain and in assignment.
ACCEPTS = {("ospa2", "nan"), ("ospa2", "3d"), ("log_sum_exp", "inf"), ("normalize_log_weights", "inf"),
           ("linear_assignment", "inf"), ("murty", "inf"), ("gibbs_assignments", "inf"),
           ("ospa", "0d"), ("gospa", "0d"), ("log_sum_exp", "0d"), ("bhattacharyya_coefficient", "0d")}
ARRAY_CASES = [(f, a) for f in ARRAY_TAKERS for a in BAD_ARRAYS]


@pytest.mark.parametrize("function,array", ARRAY_CASES, ids=[f"{f}-{a}" for f, a in ARRAY_CASES])
def test_python_bad_arrays(function, array):
    try:
        ARRAY_TAKERS[function](BAD_ARRAYS[array])
    except (TypeError, ValueError) as e:
        assert str(e) and "Unable to cast" not in str(e) and "incompatible function" not in str(e), e
        return
    except OSError as e:
        assert function == "write_mot", e
        return
    assert (function, array) in ACCEPTS, f"{function}({array}) was accepted"
