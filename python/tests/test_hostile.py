"""Hostile input from Python, as a demanding outside user tries it: every bad value is a
ConfigError naming the field (never a crash, a silent default or another exception type)."""

import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest

import wearsim

ONE_CELL = """seed = 1
records = 16
records_per_shard = 16
duration = 0.25
fs = 12000.0
[grid]
preset = ["cwru-6205-de"]
rpm = [1797.0]
fault = ["outer"]
stage = ["mild-defect"]
"""


def test_sweep_of_a_full_lane_group_does_not_overflow_the_worker_stack(tmp_path):
    # 16 records of one cell form one 16-lane group, built on a sweep worker thread: with
    # std's 2 MiB thread stack an opt-level 1 extension died of SIGSEGV here. In a
    # subprocess, so that a crash fails this test instead of killing pytest.
    code = "import sys, wearsim; print(wearsim.sweep(sys.argv[1], sys.argv[2], threads=1)['complete'])"
    p = subprocess.run([sys.executable, "-c", code, ONE_CELL, str(tmp_path / "set")], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == "True"


@pytest.mark.parametrize(
    "source, overrides, field",
    [
        ('preset = "cwru-6205-de"\nduration = nan\n', {}, "duration"),
        ('preset = "cwru-6205-de"\nduration = 0.1\nfs = inf\n', {}, "fs"),
        ({"preset": "cwru-6205-de", "duration": float("nan")}, {}, "duration"),
        ("cwru-6205-de", {"duration": float("inf")}, "duration"),
        ("cwru-6205-de", {"duration": 0.1, "speed": {"rpm": float("nan")}}, "speed.rpm"),
        ("cwru-6205-de", {"duration": 0.1, "effect": [{"name": "sensor", "params": {"noise": float("nan")}}]}, "noise"),
        ("cwru-6205-de", {"duration": 0.1, "effect": [{"name": "sensor", "params": {"noise": -float("inf")}}]}, "noise"),
    ],
)
def test_simulate_refuses_non_finite_values_naming_the_field(source, overrides, field):
    # TOML's nan once became "absent" (the default duration) on its way through JSON, and
    # a Python NaN was a JSON syntax error naming no field.
    with pytest.raises(wearsim.ConfigError, match=field):
        wearsim.simulate(source, **overrides)


def test_simulate_takes_numpy_scalars_and_names_a_bad_type():
    x, meta = wearsim.simulate("cwru-6205-de", duration=np.float32(0.05), seed=np.int64(3))
    assert meta["seed"] == 3 and x.shape == (round(0.05 * meta["fs"]),)
    with pytest.raises(wearsim.ConfigError, match="duration"):
        wearsim.simulate("cwru-6205-de", duration={1, 2})
    with pytest.raises(wearsim.ConfigError, match="seed"):
        wearsim.simulate("cwru-6205-de", duration=0.05, seed=2**70)


@pytest.fixture(scope="module")
def signal():
    x, meta = wearsim.simulate("cwru-6205-de", duration=0.5)
    return x, meta["fs"]


@pytest.mark.parametrize(
    "make, field",
    [
        # Two channels were once concatenated into one signal of twice the length.
        (lambda x: np.vstack([x, x]), "signal"),
        (lambda x: np.stack([x, x], axis=1), "signal"),
        (lambda x: x.astype(complex), "signal"),
        (lambda x: None, "signal"),
        (lambda x: ["a", "b"], "signal"),
        (lambda x: 3.0, "signal"),
    ],
)
def test_analyze_refuses_a_signal_that_is_not_one_real_channel(signal, make, field):
    x, fs = signal
    with pytest.raises(wearsim.ConfigError, match=field):
        wearsim.analyze(make(x), fs, bearing="cwru-6205-de", rpm=1797)


def test_analyze_accepts_any_real_one_channel_layout(signal):
    x, fs = signal
    ref = wearsim.analyze(x, fs, bearing="cwru-6205-de", rpm=1797)
    for y in [x.reshape(-1, 1), x.reshape(1, -1), np.repeat(x, 2)[::2], list(x)]:
        assert wearsim.analyze(y, fs, bearing="cwru-6205-de", rpm=1797) == ref
    assert ref["file"] == "signal"


@pytest.mark.parametrize(
    "kwargs, field",
    [
        ({"fs": None}, "fs"),
        ({"fs": "12000"}, "fs"),
        ({"rpm": "fast"}, "rpm"),
        ({"bearing": 5}, "bearing"),
        ({"bearing": {"elements": 9}}, "bearing"),
        ({"trust_rpm": "yes"}, "trust_rpm"),
        # Was named `signal: absurd sample rate`, the temporary file's error.
        ({"fs": 0.0}, "fs = 0"),
        ({"fs": float("inf")}, "fs = inf"),
    ],
)
def test_analyze_names_an_argument_of_the_wrong_type(signal, kwargs, field):
    x, fs = signal
    args = {"fs": fs, "bearing": "cwru-6205-de", "rpm": 1797.0, **kwargs}
    with pytest.raises(wearsim.ConfigError, match=field):
        wearsim.analyze(x, **args)


def test_analyze_errors_name_the_signal_not_a_temporary_file(signal):
    x, fs = signal
    y = x.copy()
    y[100] = np.nan
    with pytest.raises(wearsim.ConfigError) as e:
        wearsim.analyze(y, fs, bearing="cwru-6205-de", rpm=1797)
    assert "index 100" in str(e.value) and "signal" in str(e.value)
    assert "/tmp" not in str(e.value) and ".npy" not in str(e.value)


@pytest.mark.parametrize(
    "kwargs, field",
    [
        ({"part": (-1, 2)}, "part"),
        ({"part": (0,)}, "part"),
        ({"part": "0/2"}, "part"),
        ({"part": (2, 2)}, "part"),
        ({"threads": -1}, "threads"),
        ({"threads": 1.5}, "threads"),
    ],
)
def test_sweep_names_a_bad_part_or_thread_count(tmp_path, kwargs, field):
    # These were OverflowError, TypeError or a plain ValueError naming nothing.
    with pytest.raises(wearsim.ConfigError, match=field):
        wearsim.sweep(ONE_CELL, tmp_path / "set", **kwargs)
    assert not (tmp_path / "set").exists()


@pytest.mark.parametrize("out", [None, 5, ""])
def test_sweep_refuses_an_output_that_is_no_path(tmp_path, monkeypatch, out):
    # `str(out)` made directories named "None" and "5" in the working folder.
    monkeypatch.chdir(tmp_path)
    with pytest.raises(wearsim.ConfigError, match="out"):
        wearsim.sweep(ONE_CELL, out)
    assert list(tmp_path.iterdir()) == []


def test_sweep_names_a_spec_file_that_does_not_exist(tmp_path):
    # A missing path was parsed as TOML text ("invalid key").
    missing = tmp_path / "nope" / "spec.toml"
    for spec in [missing, str(missing)]:
        with pytest.raises(wearsim.ConfigError, match="no such file"):
            wearsim.sweep(spec, tmp_path / "set")
    with pytest.raises(wearsim.ConfigError, match="spec"):
        wearsim.sweep(None, tmp_path / "set")


def test_sweep_refuses_a_shard_too_large_for_memory_before_writing(tmp_path):
    # 100 000 records of 30 s at 1 MHz in one shard: 3e12 samples held in memory, once
    # accepted (each record alone is under the per-record limit).
    spec = ONE_CELL.replace("records = 16", "records = 100000").replace("records_per_shard = 16", "records_per_shard = 100000")
    spec = spec.replace("duration = 0.25", "duration = 30.0").replace("fs = 12000.0", "fs = 1000000.0")
    with pytest.raises(wearsim.ConfigError, match="records_per_shard.*limit"):
        wearsim.sweep(spec, tmp_path / "set")
    assert not (tmp_path / "set").exists()


@pytest.mark.parametrize("angle", [100.0, 90.0, -5.0, float("nan")])
def test_contact_angle_is_refused_in_the_degrees_it_was_given(angle):
    # Was `bearing.contact_angle = 1.745... allowed 0 ..= 0.8`: radians, and a key the
    # scenario file does not have.
    with pytest.raises(wearsim.ConfigError, match=r"bearing\.contact_angle_deg = .* allowed 0 \.\.= 45\.8"):
        wearsim.simulate("cwru-6205-de", duration=0.05, bearing={"contact_angle_deg": angle})


def test_analyze_takes_any_bearing_as_a_geometry_dict():
    # The preset's own geometry given as a dict (mm, degrees) gives the preset's
    # kinematics and the same call; a geometry that cannot exist or a key that is not one
    # of the four is a ConfigError naming it.
    p = next(r for r in wearsim.presets() if r["name"] == "cwru-6205-de")
    g = {
        "elements": p["elements"],
        "ball": p["element_diameter_m"] * 1e3,
        "pitch": p["pitch_diameter_m"] * 1e3,
        "angle": p["contact_angle_deg"],
    }
    x, meta = wearsim.simulate("cwru-6205-de", duration=1.0)
    by_name = wearsim.analyze(x, meta["fs"], bearing="cwru-6205-de", rpm=1797)
    by_geometry = wearsim.analyze(x, meta["fs"], bearing=g, rpm=1797)
    bpfo = by_name["kinematics"]["bpfo"]
    assert abs(by_geometry["kinematics"]["bpfo"] - bpfo) < 1e-9 * bpfo
    assert by_geometry["diagnosis"]["family"] == by_name["diagnosis"]["family"]
    with pytest.raises(wearsim.ConfigError, match="pitch"):
        wearsim.analyze(x, meta["fs"], bearing=dict(g, pitch=g["ball"] * 0.5), rpm=1797)
    with pytest.raises(wearsim.ConfigError, match="angle"):
        wearsim.analyze(x, meta["fs"], bearing=dict(g, angle=95.0), rpm=1797)
    with pytest.raises(wearsim.ConfigError, match="'balls'"):
        wearsim.analyze(x, meta["fs"], bearing={"balls": 9}, rpm=1797)
    with pytest.raises(wearsim.ConfigError, match="bearing.ball"):
        wearsim.analyze(x, meta["fs"], bearing=dict(g, ball="7.9"), rpm=1797)
    # A missing key and an impossible value are about `bearing`, not the signal (the
    # native check's message named the temporary file, shown as "signal: ...").
    with pytest.raises(wearsim.ConfigError, match="^bearing: .*pitch"):
        wearsim.analyze(x, meta["fs"], bearing={"elements": 9, "ball": 7.94}, rpm=1797)
    with pytest.raises(wearsim.ConfigError, match="^bearing: .*elements"):
        wearsim.analyze(x, meta["fs"], bearing=dict(g, elements=40), rpm=1797)


def test_gap_records_and_dataset_shards_of_the_wrong_kind_are_config_errors(tmp_path):
    for bad in (5, None, [], [3]):
        with pytest.raises(wearsim.ConfigError, match="records"):
            wearsim.gap(bad)
    spec = ONE_CELL.replace("records = 16", "records = 3").replace("records_per_shard = 16", "records_per_shard = 2")
    assert wearsim.sweep(spec, str(tmp_path / "set"), threads=1)["complete"]
    index, signals = wearsim.load_dataset(tmp_path / "set")
    assert signals(1).shape[0] == 1 and len(index) == 3
    for bad in (-1, 2, 99):
        with pytest.raises(wearsim.ConfigError, match=r"shards 0..=1"):
            signals(bad)
    for bad in ("0", 1.0, True):
        with pytest.raises(wearsim.ConfigError, match="shard"):
            signals(bad)


def test_sweep_spec_path_with_an_equals_sign_is_read_as_a_path(tmp_path):
    # A Hydra-style run directory (`lr=0.1`) put `=` in the path: the one-line string was
    # taken for TOML text and refused as a parse error of the path itself.
    run = tmp_path / "run lr=0.1"
    run.mkdir()
    spec = run / "spec.toml"
    spec.write_text(ONE_CELL.replace("records = 16", "records = 2").replace("duration = 0.25", "duration = 0.01"))
    report = wearsim.sweep(str(spec), str(tmp_path / "set"), threads=1)
    assert report["complete"] is True
    # A one-line string with `=` that names no file is still TOML text (and refused as such).
    with pytest.raises(wearsim.ConfigError, match="missing field `records`"):
        wearsim.sweep("seed = 1", str(tmp_path / "other"), threads=1)


def test_sweep_threads_zero_is_refused_like_the_command_line(tmp_path):
    # `wearsim sweep --threads 0` exits 2; threads=0 ran on one thread without a word.
    # threads=2**64-1 was taken: one stack per thread, past the cores only memory.
    for n in (0, wearsim.MAX_WORKERS + 1, 2**64 - 1, 2**70):
        with pytest.raises(wearsim.ConfigError, match=f"threads = {n} is out of range: allowed 1 ..= 256"):
            wearsim.sweep(ONE_CELL, str(tmp_path / "set"), threads=n)
    assert not (tmp_path / "set").exists()


def test_a_tiny_or_huge_value_is_named_in_exponent_form():
    # `{}` of 1e-300 is a 300-digit decimal; the message shows it as it was written.
    with pytest.raises(wearsim.ConfigError, match="duration") as e:
        wearsim.simulate("cwru-6205-de", duration=1e-300)
    assert "1e-300" in str(e.value) and len(str(e.value)) < 200, str(e.value)


def test_analyze_takes_a_small_bearing():
    # 7 balls of 1.588 mm on a 6.5 mm pitch (a miniature 623) was refused with "fs:
    # internal step too large", the scaled structure's simulation limit: an analysis needs
    # only the kinematics (BPFO = N/2 (1 - d/P) f).
    x, meta = wearsim.simulate("cwru-6205-de", duration=1.0)
    g = {"elements": 7, "ball": 1.588, "pitch": 6.5, "angle": 0.0}
    r = wearsim.analyze(x, meta["fs"], bearing=g, rpm=1797)
    want = 3.5 * (1 - 1.588 / 6.5) * 1797 / 60
    assert abs(r["kinematics"]["bpfo"] - want) < 1e-9 * want


def test_numpy_values_in_a_configuration_are_their_numbers():
    # A numpy array in a dict (a speed table, from np.linspace) was refused as "[0.5] is out
    # of the 64-bit integer range"; numpy scalars are their Python numbers.
    table = np.array([[0.0, 25.0], [0.5, 30.0]])
    x, meta = wearsim.simulate("cwru-6205-de", duration=0.05, speed={"table": table})
    y, _ = wearsim.simulate("cwru-6205-de", duration=0.05, speed={"table": table.tolist()})
    assert np.array_equal(x, y)
    z, _ = wearsim.simulate("cwru-6205-de", duration=np.float64(0.05), seed=np.int64(3))
    assert z.shape == x.shape


@pytest.mark.parametrize(
    "call, expected",
    [
        # clap's words for the command line become the call's: keyword arguments, no usage
        # line, no `--help` hint.
        (lambda: wearsim.life(seeds=0), ["unexpected keyword argument 'seeds'", "'seed'"]),
        (lambda: wearsim.life(lives=5, load=-1), ["unexpected keyword argument 'load'", "'loads'"]),
        (lambda: wearsim.life(stop_after=0), ["stop_after applies to dense runs only"]),
        (lambda: wearsim.life(lives=1), ["lives: 1 is out of range"]),
        (lambda: wearsim.gap("missing.mat", jobs="abc"), ["invalid value 'abc' for 'jobs'"]),
        (lambda: wearsim.analyze(np.random.default_rng(1).normal(size=24000), 12000.0,
                                 bearing="cwru-6205-de", rpm=-5), ["rpm=-5 is out of range"]),
        (lambda: wearsim.analyze(np.random.default_rng(1).normal(size=24000), 12000.0,
                                 bearing="nope", rpm=1797),
         ["unknown bearing `nope`", "bearing=NAME", 'bearing={"elements": N']),
    ],
)
def test_messages_name_the_keyword_arguments_not_command_line_options(call, expected):
    with pytest.raises(wearsim.ConfigError) as e:
        call()
    msg = str(e.value)
    for part in expected:
        assert part in msg, msg
    assert "--" not in msg and "Usage" not in msg and "\n" not in msg, msg


def test_life_takes_a_dash_directory_a_dict_config_and_effect_dicts(tmp_path, monkeypatch):
    # Each was passed through to the command line as is: "-runs" read as options, the
    # dict's repr "not found" as a file, an effect dict as "unknown effect `{'name'`".
    monkeypatch.chdir(tmp_path)
    configs = lambda: set(Path(tempfile.gettempdir()).glob("wearsim-config-*"))  # noqa: E731
    before = configs()
    r = wearsim.life(out="-runs", seed=2)
    assert r["complete"] and (tmp_path / "-runs" / "life-summary.json").is_file()
    r = wearsim.life(out=tmp_path / "c", config={"preset": "thesis-61810", "seed": 2},
                     effect=[{"name": "sensor", "noise": 0.05}])
    assert r["complete"], r.keys()
    with pytest.raises(wearsim.ConfigError, match="speeed"):
        wearsim.life(out=tmp_path / "e", config={"preset": "thesis-61810", "speeed": 3})
    with pytest.raises(wearsim.ConfigError, match="name"):
        wearsim.life(out=tmp_path / "f", config={"preset": "thesis-61810"}, effect=[{"noise": 0.05}])
    assert configs() == before, "a temporary --config file was left behind"
