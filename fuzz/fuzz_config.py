"""Fuzz the config-file reader (vtrack.load_config, the reader behind `vtrack track --config`) and
the parameter tables it feeds: whatever a file holds, each section is applied to the components
that read it (BoxTracker, MultiBernoulliTracker, KdeBackground, HogPeopleDetector) as keyword
arguments, which must take it or raise TypeError/ValueError naming the parameter.

Inputs are raw bytes mutated from fuzz/corpus/config/ and, for inputs whose first byte is 0xF0 or
above, YAML assembled from the fuzz data (sections, names the components have, values of every
kind, deep nesting, anchors, tags, several documents).

    .venv/bin/python fuzz/fuzz_config.py -max_total_time=60 fuzz/corpus/config
"""

from __future__ import annotations

import sys

import atheris

# Coverage feedback from vtrack's Python code only: the compiled module is not instrumented, and
# instrumenting NumPy and OpenCV's Python parts took ~20 s per harness start for nothing.
with atheris.instrument_imports(include=["vtrack"]):
    import vtrack

from _common import check, scratch_file

SECTIONS = [b"seed", b"tracker", b"background", b"detector", b"extra", b""]
NAMES = [n.encode() for n in sorted(set(vtrack.BoxTracker.default_params())
                                    | set(vtrack.MultiBernoulliTracker.default_params())
                                    | set(vtrack.KdeBackground.default_params())
                                    | set(vtrack.HogPeopleDetector.default_params()))]
VALUES = [b"0", b"1", b"-1", b"0.5", b"1e400", b"-1e400", b".nan", b".inf", b"nan", b"inf",
          b"true", b"True", b"no", b"null", b"~", b"'0.1'", b'"x"', b"murty", b"gibbs",
          b"99999999999", b"18446744073709551615", b"18446744073709551616", b"-9223372036854775809",
          b"[0.03, 0.03, 0.06]", b"[1, 2]", b"[]", b"{}", b"{a: 1}", b"!!str 1", b"&a 1", b"*a",
          b"[[1]]", b"0x1F", b"1_000", b"\xff", b"2147483648", b"1e-320", b"- 1"]


def structured(fdp: atheris.FuzzedDataProvider) -> bytes:
    out = []
    for _ in range(fdp.ConsumeIntInRange(0, 4)):
        section = SECTIONS[fdp.ConsumeIntInRange(0, len(SECTIONS) - 1)]
        if section == b"seed":
            out.append(b"seed: " + VALUES[fdp.ConsumeIntInRange(0, len(VALUES) - 1)])
            continue
        entries = []
        for _ in range(fdp.ConsumeIntInRange(0, 6)):
            name = NAMES[fdp.ConsumeIntInRange(0, len(NAMES) - 1)]
            value = VALUES[fdp.ConsumeIntInRange(0, len(VALUES) - 1)]
            entries.append(name + b": " + value)
        if fdp.ConsumeBool():
            out.append(section + b": {" + b", ".join(entries) + b"}")
        else:
            out.append(section + b":\n" + b"".join(b"  " + e + b"\n" for e in entries))
    depth = fdp.ConsumeIntInRange(0, 40) if fdp.ConsumeIntInRange(0, 7) == 0 else 0
    if depth:
        out.append(b"extra: " + b"[" * depth + b"1" + b"]" * depth)
    text = b"\n".join(out) + b"\n"
    if fdp.ConsumeIntInRange(0, 15) == 0:
        text += b"---\n" + text
    return text


def apply_sections(config: dict) -> None:
    for section, cls in (("tracker", vtrack.BoxTracker), ("tracker", vtrack.MultiBernoulliTracker)):
        params = dict(config.get(section, {}))
        for name in [n for n in params if n not in cls.default_params()]:
            del params[name]
        if "seed" in config and "seed" in cls.default_params():
            params["seed"] = config["seed"]
        check(lambda: cls((32, 32), **params))
    for section, cls in (("background", vtrack.KdeBackground), ("detector", vtrack.HogPeopleDetector)):
        params = {k: v for k, v in config.get(section, {}).items() if k in cls.default_params()}
        check(lambda: cls(**params))


def one_input(data: bytes) -> None:
    # A first byte >= 0xF0 asks for an assembled file; anything else is the file itself (so the
    # seed files are plain files, mutated by libFuzzer).
    text = structured(atheris.FuzzedDataProvider(data[1:])) if data[:1] >= b"\xf0" else data
    suffix = ".json" if text[:1] in (b"{", b"[") else ".yml"
    with scratch_file(text, suffix) as path:
        config = None

        def load():
            nonlocal config
            config = vtrack.load_config(path)

        check(load)
        if config is not None:
            apply_sections(config)


def main() -> None:
    atheris.Setup(sys.argv, one_input)
    atheris.Fuzz()


if __name__ == "__main__":
    main()
