"""One surface for every component: keyword parameters with defaults, `default_params()`,
`.params`, the same errors for unknown or wrongly typed keywords, config files that round-trip,
and `vtrack.load_config` reading what the CLI reads."""

import json

import numpy as np
import pytest

import vtrack

MOTION = vtrack.LinearGaussianMotion.constant_velocity()
OBSERVATION = vtrack.LinearGaussianObservation.position()

# Each public component, built with keyword parameters (and the data arguments it needs).
COMPONENTS = {
    "KdeBackground": lambda **kw: vtrack.KdeBackground(**kw),
    "MultiBernoulliTracker": lambda **kw: vtrack.MultiBernoulliTracker((64, 48), **kw),
    "BoxTracker": lambda **kw: vtrack.BoxTracker((64, 48), **kw),
    "GlmbTracker": lambda **kw: vtrack.GlmbTracker(MOTION, OBSERVATION, [], **kw),
    "HogPeopleDetector": lambda **kw: vtrack.HogPeopleDetector(**kw),
    "DepthLikelihood": lambda **kw: vtrack.models.DepthLikelihood(64, 48, 50.0, **kw),
}
CLASSES = {"DepthLikelihood": vtrack.models.DepthLikelihood}


def cls_of(name):
    return CLASSES.get(name) or getattr(vtrack, name)


def wrong_type(value):
    """A value of another Python type than the parameter takes."""
    if isinstance(value, bool):
        return 1
    if isinstance(value, int):
        return 1.5
    if isinstance(value, float):
        return "1.0"
    if isinstance(value, str):
        return 3
    return "abc"  # a tuple of numbers


@pytest.mark.parametrize("name", COMPONENTS)
def test_defaults_params_and_errors(name):
    make, cls = COMPONENTS[name], cls_of(name)
    defaults = cls.default_params()
    assert make().params == defaults
    assert make(**defaults).params == defaults  # every name is a keyword
    first = next(iter(defaults))
    typo = first[:-1] + ("x" if first[-1] != "x" else "y")
    with pytest.raises(TypeError, match=f"unknown .*parameter '{typo}' \\(did you mean '{first}'\\?\\)"):
        make(**{typo: defaults[first]})
    for key, value in defaults.items():
        with pytest.raises(TypeError, match=key):
            make(**{key: wrong_type(value)})


def test_seeds_are_unsigned_64_bit_everywhere():
    for name in ("MultiBernoulliTracker", "BoxTracker", "GlmbTracker"):
        make = COMPONENTS[name]
        assert make(seed=2**64 - 1).params["seed"] == 2**64 - 1
        assert make(seed=np.uint64(7)).params["seed"] == 7
        for bad in (-1, 2**64):
            with pytest.raises(ValueError, match="seed must be an int in"):
                make(seed=bad)
        with pytest.raises(TypeError, match="seed must be an int"):
            make(seed=1.0)


@pytest.mark.parametrize("size, error", [
    ((64.0, 48), TypeError), ((64, 48, 3), TypeError), ("64x48", TypeError), (64, TypeError),
    ((0, 48), ValueError), ((64, -1), ValueError), ((2**40, 48), ValueError)])
def test_image_size_is_a_pair_of_positive_ints_everywhere(size, error):
    for cls in (vtrack.MultiBernoulliTracker, vtrack.BoxTracker):
        with pytest.raises(error, match="image_size"):
            cls(size)


# The config sections of each method and the component whose parameters each holds.
SECTIONS = {
    "mb": {"background": vtrack.KdeBackground, "tracker": vtrack.MultiBernoulliTracker},
    "glmb": {"detector": vtrack.HogPeopleDetector, "tracker": vtrack.BoxTracker},
}


def candidates(value):
    """Other values of the same type, nearest first."""
    if isinstance(value, bool):
        return [not value]
    if isinstance(value, int):
        return [value + 1, value + 2, value - 1]
    if isinstance(value, float):
        return [value * 0.875, value * 1.0625, 0.25] if np.isfinite(value) and value else [0.25]
    if isinstance(value, tuple):
        return [tuple(v * 0.875 for v in value)]
    return []


def changed_params(cls):
    """Every parameter of cls changed to another value cls accepts (alone), where one exists."""
    make = (lambda **kw: cls((64, 48), **kw)) if "Tracker" in cls.__name__ else cls
    out = {}
    for key, value in cls.default_params().items():
        for candidate in candidates(value):
            try:
                make(**{key: candidate})
            except ValueError:
                continue
            out[key] = candidate
            break
    return out


@pytest.mark.parametrize("method", SECTIONS)
def test_config_files_round_trip_and_the_cli_reads_the_same(method, tmp_path, vtrack_cli):
    detector = ["--detector", "hog"] if method == "glmb" else []
    sections = {}
    for section, cls in SECTIONS[method].items():
        values = changed_params(cls)
        values.pop("seed", None)  # the top-level seed sets it
        sections[section] = values
    sections["seed"] = 2**63 + 5
    for suffix, text in ((".json", json.dumps(sections)),
                         (".yml", "\n".join(f"{k}: {json.dumps(v)}" for k, v in sections.items()))):
        path = tmp_path / f"config{suffix}"
        path.write_text(text)
        loaded = vtrack.load_config(path)
        assert loaded["seed"] == 2**63 + 5
        for section, values in sections.items():
            if section == "seed":
                continue
            for key, value in values.items():
                assert loaded[section][key] == pytest.approx(value), (section, key)
        cli = vtrack_cli("params", "--method", method, *detector, "--config", path)
        assert cli.returncode == 0, cli.stderr
        effective = json.loads(cli.stdout)
        assert effective["tracker"]["seed"] == 2**63 + 5
        for section, cls in SECTIONS[method].items():
            # The component built from the loaded section has exactly the CLI's values.
            params = dict(loaded[section], **({"seed": loaded["seed"]} if section == "tracker" else {}))
            built = cls((64, 48), **params) if "Tracker" in cls.__name__ else cls(**params)
            for key, value in built.params.items():
                assert effective[section][key] == pytest.approx(value), (section, key)


def setting_text(value):
    """A parameter value as `--set name=value` writes it."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (tuple, list)):
        return ",".join(repr(float(v)) for v in value)
    return repr(value) if isinstance(value, float) else str(value)


@pytest.mark.parametrize("method", SECTIONS)
def test_pipeline_params_resolve_as_vtrack_params(method, tmp_path, vtrack_cli):
    """pipeline_params gives what `vtrack params` prints for the same config, seed and --set
    (every parameter changed, so no value can pass by being a default), with the CLI's
    precedence: config < keywords (--seed) < settings (--set)."""
    detector = ["--detector", "hog"] if method == "glmb" else []
    config = tmp_path / "config.json"
    config.write_text(json.dumps({"seed": 5}))
    changed = {}
    for cls in SECTIONS[method].values():
        changed.update(changed_params(cls))
    changed.pop("seed", None)
    settings = [f"{k}={setting_text(v)}" for k, v in changed.items()]
    cli = vtrack_cli("params", "--method", method, *detector, "--config", config, "--seed", 6,
                     *[a for s in settings for a in ("--set", s)])
    assert cli.returncode == 0, cli.stderr
    expected = json.loads(cli.stdout)
    found = vtrack.pipelines.pipeline_params(method, detector=detector[-1] if detector else None,
                                             config=config, settings=settings, seed=6)
    assert set(found) == set(expected)
    for section, values in expected.items():
        assert set(found[section]) == set(values), section
        for key, value in values.items():
            got = found[section][key]
            assert (list(got) if isinstance(got, tuple) else got) == value, (section, key)
    assert found["tracker"]["seed"] == 6
    assert vtrack.pipelines.pipeline_params(method, detector=detector[-1] if detector else None,
                                            config=config, settings=["seed=7"],
                                            seed=6)["tracker"]["seed"] == 7
    with pytest.raises(ValueError, match="name=value"):
        vtrack.pipelines.pipeline_params("mb", settings=["=1"])
    with pytest.raises(TypeError, match="did you mean 'delta_f'"):
        vtrack.pipelines.pipeline_params("mb", settings=["delta_ff=1"])
    with pytest.raises(TypeError, match="settings"):
        vtrack.pipelines.pipeline_params("mb", settings="delta_f=1")


def test_load_config_errors_name_the_problem(tmp_path):
    with pytest.raises(OSError, match="no such config file"):
        vtrack.load_config(tmp_path / "none.yml")
    bad = tmp_path / "bad.yml"
    bad.write_text("tracker: {delta_f: [1\n")
    with pytest.raises(OSError, match="line 2, column 1"):
        vtrack.load_config(bad)
    bad.write_text("tracker: {delta_f: 1, delta_f: 2}\n")
    with pytest.raises(ValueError, match="appears twice"):
        vtrack.load_config(bad)
    with pytest.raises(TypeError, match="did you mean 'delta_f'"):
        vtrack.track_video(bad, config={"tracker": {"delta_ff": 1.0}})


def test_vtrack_params_for_the_vehicles_pipeline(tmp_path, vtrack_cli):
    """`vtrack params --method vehicles` prints the sections `vtrack vehicles` reads (background,
    blobs, estimator) with the same precedence (config < --seed < --set), and its output read
    back as --config gives the same parameters."""
    config = tmp_path / "config.json"
    config.write_text(json.dumps({"seed": 5, "blobs": {"min_area": 90, "lost_memory": 7}}))
    cli = vtrack_cli("params", "--method", "vehicles", "--config", config, "--seed", 6,
                     "--set", "min_area=40", "--set", "sampler=ray")
    assert cli.returncode == 0, cli.stderr
    found = json.loads(cli.stdout)
    assert list(found) == ["background", "blobs", "estimator"]
    assert set(found["estimator"]) == set(vtrack.vehicles.VehicleDimensionEstimator.default_params())
    assert set(found["background"]) == set(vtrack.KdeBackground.default_params())
    assert found["blobs"]["min_area"] == 40 and found["blobs"]["lost_memory"] == 7
    assert found["estimator"]["seed"] == 6 and found["estimator"]["sampler"] == "ray"
    again = tmp_path / "effective.json"
    again.write_text(cli.stdout)
    cli2 = vtrack_cli("params", "--method", "vehicles", "--config", again)
    assert cli2.returncode == 0, cli2.stderr
    assert json.loads(cli2.stdout) == found
    bad = vtrack_cli("params", "--method", "vehicles", "--set", "min_aera=3")
    assert bad.returncode == 2 and "min_area" in bad.stderr  # the closest known name
