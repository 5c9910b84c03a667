"""Runs vtrack's atheris fuzz harnesses (fuzz/fuzz_*.py), as many at a time as there are cores,
for a bounded time each, against the committed seed corpus, and reports what they covered and
found.

    .venv/bin/python fuzz/run.py --seconds 12           # make test: under a minute in all
    .venv/bin/python fuzz/run.py --seconds 300 --random  # make fuzz

New inputs go to a scratch corpus (build/fuzz/<harness>/), never into fuzz/corpus; a crash, a hang
(-timeout) or an exception outside the contract (fuzz/_common.py) stops that harness, leaves the
input in build/fuzz/ and fails the run with the command that reproduces it. A finding becomes a
regression test: copy the input into fuzz/corpus/<harness>/ (tests/test_fuzz_corpus.py and the
sanitizer replay run it) and add a test that names the bug.
"""

from __future__ import annotations

import argparse
import concurrent.futures
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
HARNESSES = ("detections", "config", "video", "api")


def run(harness: str, seconds: int, seed: int, work: str) -> dict:
    scratch = os.path.join(work, harness)
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(os.path.join(scratch, "corpus"))
    log_path = os.path.join(scratch, "log.txt")
    command = [sys.executable, os.path.join(HERE, f"fuzz_{harness}.py"),
               f"-max_total_time={seconds}", "-timeout=20", "-rss_limit_mb=4096",
               f"-seed={seed}", f"-artifact_prefix={scratch}/", "-print_final_stats=1",
               os.path.join(scratch, "corpus"), os.path.join(HERE, "corpus", harness)]
    start = time.monotonic()
    with open(log_path, "w") as log:
        code = subprocess.call(command, stdout=log, stderr=subprocess.STDOUT, cwd=ROOT)
    elapsed = time.monotonic() - start
    text = open(log_path, errors="replace").read()
    runs = re.findall(r"Done (\d+) runs", text) or re.findall(r"stat::number_of_executed_units:\s*(\d+)", text)
    artifacts = [os.path.join(scratch, f) for f in os.listdir(scratch)
                 if f.startswith(("crash-", "timeout-", "oom-", "leak-"))]
    return {"harness": harness, "code": code, "seconds": elapsed, "runs": int(runs[-1]) if runs else 0,
            "seeds": len(os.listdir(os.path.join(HERE, "corpus", harness))),
            "new": len(os.listdir(os.path.join(scratch, "corpus"))), "artifacts": artifacts,
            "log": log_path, "command": command}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=int, default=12, help="fuzzing time per harness")
    parser.add_argument("--random", action="store_true",
                        help="a random libFuzzer seed (default: fixed, so make test is repeatable)")
    parser.add_argument("--harness", action="append", choices=HARNESSES,
                        help="run only these (repeatable)")
    parser.add_argument("--work", default=os.path.join(ROOT, "build", "fuzz"),
                        help="scratch folder for new inputs, logs and findings")
    args = parser.parse_args()
    seed = int.from_bytes(os.urandom(4), "little") if args.random else 16
    # Each harness is its own process, bounded by wall time (-max_total_time): one per core.
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        results = list(pool.map(lambda h: run(h, args.seconds, seed, args.work),
                                args.harness or HARNESSES))
    print(f"fuzzing (libFuzzer seed {seed}):")
    print("| harness | seconds | inputs run | seed files | new inputs | result |")
    print("|---|---|---|---|---|---|")
    failed = False
    for r in results:
        ok = r["code"] == 0 and not r["artifacts"]
        failed |= not ok
        print(f"| {r['harness']} | {r['seconds']:.0f} | {r['runs']} | {r['seeds']} | {r['new']} | "
              f"{'ok' if ok else 'FINDING'} |")
    for r in results:
        if r["code"] == 0 and not r["artifacts"]:
            continue
        print(f"\n{r['harness']}: exit {r['code']}; log {r['log']}; inputs {r['artifacts']}")
        print("".join(open(r["log"], errors="replace").readlines()[-40:]))
        if r["artifacts"]:
            print("reproduce: " + " ".join(r["command"][:2] + [r["artifacts"][0]]))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
