"""The fuzz corpus (fuzz/corpus/<harness>/: the seeds and every input a fuzzer found) replayed
through its atheris harness, once per file, as a regression test: each input must keep meeting
the harness's contract (return, or raise TypeError/ValueError/OSError naming the problem). The
inputs a fuzzer found are named after their bug (e.g. api/ospa2_zero_steps.bin) and also have a
test of their own in tests/test_hardening.py."""

import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("atheris")

FUZZ = Path(__file__).resolve().parents[1] / "fuzz"
HARNESSES = ("detections", "config", "video", "api")


@pytest.mark.parametrize("harness", HARNESSES)
def test_corpus_replays_cleanly(harness, tmp_path):
    files = sorted((FUZZ / "corpus" / harness).iterdir())
    assert len(files) >= 8, f"the {harness} seed corpus is missing"
    # libFuzzer given files (not folders) runs each of them once and exits non-zero on a finding.
    result = subprocess.run([sys.executable, str(FUZZ / f"fuzz_{harness}.py"),
                             f"-artifact_prefix={tmp_path}/", *map(str, files)],
                            capture_output=True, text=True, timeout=600, cwd=tmp_path)
    assert result.returncode == 0, result.stderr[-3000:]
    assert f"Running {len(files)} inputs 1 time(s) each" in result.stderr
    assert not list(tmp_path.iterdir()), "a finding was written"
