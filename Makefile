# The README's two commands. Each sets itself up on a fresh Debian machine and is idempotent:
# stamps record what is installed, and the CMake build directory is reused, so a second run
# installs nothing and rebuilds only what changed.
#   make test   system packages, .venv, build + install vtrack, then ctest and pytest
#   make demo   the same set-up, fetch the sample video (PETS2009 S2.L1), run the main job
#   make bench  the benchmarks in benchmarks/ (needs the sample video too)
#   make fuzz   the atheris fuzz harnesses of fuzz/, FUZZ_SECONDS (300) each
#   make sanitize  the C++ library, its GoogleTest suites and the fuzz corpus replay built with
#               AddressSanitizer + UndefinedBehaviorSanitizer (own build tree, build/sanitize)

PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
BUILD := build
DATA ?= $(HOME)/.cache/vtrack
VIDEO := $(DATA)/vtest.avi
VIDEO_SHA256 := 45cddc9490be69345cbdab64ca583be65987e864ca408038e648db99e10516cf
DEMO_OUT ?= demo-output
# PETS09-S2L1 ground truth (MOT15), shipped in data/ (data/pets09-s2l1/SOURCE.md).
PETS_GT ?= data/pets09-s2l1/gt.txt
APT_PACKAGES := build-essential libeigen3-dev libopencv-dev libgtest-dev libyaml-cpp-dev
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
SOURCES := CMakeLists.txt pyproject.toml $(shell find cpp bindings python -type f -not -name '*.pyc' 2>/dev/null)

FUZZ_SECONDS ?= 300

.PHONY: test demo bench build clean fuzz sanitize

test: $(VENV)/.vtrack-installed $(VIDEO)
	$(VENV)/bin/ctest --test-dir $(BUILD)/wheel --output-on-failure -j2
	$(PY) -m pytest -q -n auto
	$(PY) fuzz/run.py --seconds 12

fuzz: $(VENV)/.vtrack-installed
	$(PY) fuzz/run.py --seconds $(FUZZ_SECONDS) --random

# Leak checking stays on; OpenCV's and yaml-cpp's one-time allocations are not reported as leaks
# by LeakSanitizer (they stay reachable). Python is not instrumented: the bindings are covered by
# pytest and the fuzzers in the normal build.
SANITIZE_ENV := ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
sanitize: $(VENV)/.dev-deps
	$(VENV)/bin/cmake -S . -B $(BUILD)/sanitize -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-g1 \
	  -DVTRACK_SANITIZE=ON -DVTRACK_BUILD_TESTS=ON -DVTRACK_BUILD_PYTHON=OFF
	$(VENV)/bin/cmake --build $(BUILD)/sanitize -j2 --target vtrack_tests vtrack_replay_corpus
	$(SANITIZE_ENV) $(VENV)/bin/ctest --test-dir $(BUILD)/sanitize --output-on-failure -j2

demo: $(VENV)/.vtrack-installed $(VIDEO)
	mkdir -p $(DEMO_OUT)
	$(VENV)/bin/vtrack info $(VIDEO)
	$(VENV)/bin/vtrack track $(VIDEO) --method mb --out $(DEMO_OUT)/tracks.txt \
	  --render $(DEMO_OUT)/tracks.mp4
	$(PY) -m vtrack.contact_sheet --video $(VIDEO) --tracks $(DEMO_OUT)/tracks.txt \
	  --gt $(PETS_GT) --out $(DEMO_OUT)/contact_sheet.png
	@echo "PETS09-S2L1 tracking metrics (TrackEval; GT conf-0 rows ignored):"
	$(PY) -m vtrack.evaluate --gt $(PETS_GT) --tracks $(DEMO_OUT)/tracks.txt

bench: $(VENV)/.vtrack-installed $(VENV)/.bench-deps $(VIDEO)
	$(PY) benchmarks/resampling.py
	$(PY) benchmarks/particle_filter.py
	$(PY) benchmarks/murty.py
	$(PY) benchmarks/glmb_standard.py
	$(PY) benchmarks/rgbd_switching.py --figure $(DEMO_OUT)/rgbd_switching.png
	$(PY) benchmarks/bgs.py
	$(PY) benchmarks/bgs_quality.py --out $(DEMO_OUT)/bgs_contact_sheet.png
	$(PY) benchmarks/multi_bernoulli.py
	$(PY) benchmarks/pets09.py
	$(PY) benchmarks/detections.py
	$(PY) benchmarks/detections_sim.py
	$(PY) benchmarks/track_video.py
	$(PY) benchmarks/vehicle_geometry.py
	$(PY) benchmarks/vehicles.py --video-vehicles 20
	$(PY) benchmarks/color_histogram.py
	$(PY) benchmarks/follow.py
	$(PY) benchmarks/person_size.py

build: $(VENV)/.vtrack-installed

# Debian packages: installed only when one is missing.
$(BUILD)/.system-deps:
	dpkg -s $(APT_PACKAGES) >/dev/null 2>&1 || { $(SUDO) apt-get update && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y --no-install-recommends $(APT_PACKAGES); }
	mkdir -p $(BUILD) && touch $@

$(VENV)/.dev-deps: requirements/dev.txt requirements/eval.txt | $(BUILD)/.system-deps
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -r requirements/dev.txt
	$(PY) -m pip install --quiet --no-deps -r requirements/eval.txt
	touch $@

$(VENV)/.bench-deps: requirements/bench.txt requirements/bench-nodeps.txt $(VENV)/.dev-deps
	$(PY) -m pip install --quiet -r requirements/bench.txt || echo "some benchmark peers failed to install; their rows will be skipped"
	$(PY) -m pip install --quiet --no-deps -r requirements/bench-nodeps.txt || echo "a --no-deps benchmark peer failed to install (sort-track, norfair, trackers, particles); its rows will be skipped"
	$(PY) -m pip install --quiet --no-deps --upgrade --target $(VENV)/opencv-contrib \
	  "opencv-contrib-python-headless==$$($(PY) -c 'from importlib.metadata import version; print(version("opencv-python-headless"))')" \
	  || echo "opencv-contrib failed to install; benchmarks/follow.py will skip CSRT and KCF"
	touch $@

# Build with the persistent build directory (incremental), C++ tests included, then install the
# wheel (module + `vtrack` executable) into .venv.
$(VENV)/.vtrack-installed: $(VENV)/.dev-deps $(SOURCES)
	$(PY) -m pip install --no-build-isolation --no-deps --quiet \
	  -Cbuild-dir=$(BUILD)/wheel -Ccmake.define.VTRACK_BUILD_TESTS=ON .
	touch $@

# The real sample video, PETS2009 S2.L1 View 001, from Debian's opencv-doc package; cached outside
# the repository and checked against its known hash.
$(VIDEO):
	mkdir -p $(DATA)/deb
	cd $(DATA)/deb && { apt-get download opencv-doc || { $(SUDO) apt-get update && apt-get download opencv-doc; }; }
	dpkg-deb --fsys-tarfile $(DATA)/deb/opencv-doc_*.deb \
	  | tar -x -O ./usr/share/doc/opencv-doc/examples/data/vtest.avi > $(VIDEO).part
	echo "$(VIDEO_SHA256)  $(VIDEO).part" | sha256sum -c --quiet
	mv $(VIDEO).part $(VIDEO)
	rm -rf $(DATA)/deb

clean:
	rm -rf $(BUILD) $(VENV) $(DEMO_OUT)
