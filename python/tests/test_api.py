"""wearsim's Python API: same samples as the Rust library, resolved metadata, errors as
ConfigError naming the field, analysis of a simulated defect."""

import json
import os
from pathlib import Path

import numpy as np
import pytest

import wearsim


def test_simulate_preset_shape_meta_and_determinism():
    x, meta = wearsim.simulate("cwru-6205-de", duration=0.2)
    assert isinstance(x, np.ndarray) and x.dtype == np.float64
    assert meta["fs"] == pytest.approx(meta["config"]["output_rate"])
    assert x.shape == (round(0.2 * meta["fs"]),)
    assert np.all(np.isfinite(x)) and x.std() > 0
    assert meta["preset"] == "cwru-6205-de"
    assert meta["scenario"]["duration"] == 0.2
    y, _ = wearsim.simulate("cwru-6205-de", duration=0.2)
    assert np.array_equal(x, y)
    z, _ = wearsim.simulate("cwru-6205-de", duration=0.2, seed=meta["seed"] + 1)
    assert not np.array_equal(x, z)


def test_dict_toml_and_overrides_agree():
    toml = 'preset = "cwru-6205-de"\nduration = 0.1\nfs = 12000.0\n[speed]\nrpm = 1750.0\n'
    a, ma = wearsim.simulate(toml)
    b, mb = wearsim.simulate({"preset": "cwru-6205-de", "duration": 0.1, "fs": 12000.0, "speed": {"rpm": 1750.0}})
    c, _ = wearsim.simulate("cwru-6205-de", duration=0.1, fs=12000.0, speed={"rpm": 1750.0})
    assert np.array_equal(a, b) and np.array_equal(a, c)
    assert ma["config"] == mb["config"]
    assert ma["fs"] == 12000.0


def test_effect_changes_the_signal():
    a, _ = wearsim.simulate("cwru-6205-de", duration=0.1)
    b, meta = wearsim.simulate("cwru-6205-de", duration=0.1, effect=[{"name": "sensor", "params": {"noise": 5.0}}])
    assert meta["scenario"]["effect"][0]["name"] == "sensor"
    # 5 m/s^2 of white noise adds about 5 m/s^2 RMS.
    assert np.std(b - a) == pytest.approx(5.0, rel=0.1)


@pytest.mark.parametrize(
    "kwargs, words",
    [
        ({"duration": -1.0}, ["duration"]),
        ({"fs": 5.0}, ["fs"]),
        ({"durration": 1.0}, ["durration"]),
        ({"effect": [{"name": "sensor", "params": {"noise": 1e6}}]}, ["noise", "100"]),
    ],
)
def test_bad_input_raises_config_error_naming_the_field(kwargs, words):
    with pytest.raises(wearsim.ConfigError) as e:
        wearsim.simulate("cwru-6205-de", **kwargs)
    assert isinstance(e.value, ValueError)
    for w in words:
        assert w in str(e.value)


def test_unknown_preset_lists_the_presets():
    with pytest.raises(wearsim.ConfigError, match="cwru-6205-de"):
        wearsim.simulate("no-such-bearing")


def test_effects_and_presets_catalogues():
    fx = wearsim.effects()
    names = [e["name"] for e in fx]
    assert "sensor" in names and "slip" in names
    for e in fx:
        for p in e["params"]:
            assert p["min"] <= p["default"] <= p["max"]
    pr = {p["name"]: p for p in wearsim.presets()}
    # SKF 6205 at 1797 rpm: BPFO 107.4 Hz, BPFI 162.2 Hz (CWRU's published figures).
    assert pr["cwru-6205-de"]["hz"]["bpfo"] == pytest.approx(107.4, rel=0.01)
    assert pr["cwru-6205-de"]["hz"]["bpfi"] == pytest.approx(162.2, rel=0.01)
    # The catalogue bearings were named only in error messages (probe D). XJTU-SY's LDK
    # UER204, 8 balls of 7.92 mm on 34.55 mm: BPFO = 4 (1 - 7.92/34.55) = 3.083 orders,
    # BPFI = 4 (1 + 7.92/34.55) = 4.917 (Wang et al. 2020 give 107.9 and 172.1 Hz at 35 Hz).
    bb = {b["name"]: b for b in wearsim.bearings()}
    assert set(bb) == {"mfpt-nice", "paderborn-6203", "xjtu-ldk-uer204"}
    x = bb["xjtu-ldk-uer204"]
    assert x["orders"]["bpfo"] == pytest.approx(4 * (1 - 7.92 / 34.55), rel=1e-9)
    assert x["orders"]["bpfi"] == pytest.approx(4 * (1 + 7.92 / 34.55), rel=1e-9)
    assert 35 * x["orders"]["bpfo"] == pytest.approx(107.9, rel=0.002)
    assert 35 * x["orders"]["bpfi"] == pytest.approx(172.1, rel=0.002)
    assert all(b["source"] for b in bb.values())
    sig, meta = wearsim.simulate("cwru-6205-de", duration=1.0)
    wearsim.analyze(sig, meta["fs"], bearing="xjtu-ldk-uer204", rpm=2100)


def test_analyze_names_the_outer_race_defect():
    x, meta = wearsim.simulate("cwru-6205-de", duration=1.0)
    a = wearsim.analyze(x, meta["fs"], bearing="cwru-6205-de", rpm=1797)
    text = json.dumps(a).lower()
    assert "outer" in text or "bpfo" in text
    with pytest.raises(wearsim.ConfigError):
        wearsim.analyze(np.zeros(4), 12000.0, bearing="cwru-6205-de", rpm=1797)


def _cwru_dir():
    env = os.environ.get("WEARSIM_DATA")
    here = Path(__file__).resolve()
    for p in [Path(env) if env else None, here.parents[3] / "shared" / "data"]:
        if p is not None and (p / "cwru").is_dir():
            return p / "cwru"
    if os.environ.get("CI") == "true":
        pytest.fail("CWRU data not found (CI=true): set WEARSIM_DATA to the folder holding cwru/")
    pytest.skip("CWRU data not found (set WEARSIM_DATA to the folder holding cwru/)")


def test_analyze_measures_a_speed_a_few_percent_off_unless_told_to_trust_it():
    x, meta = wearsim.read_record(str(_cwru_dir() / "12k_Drive_End_IR007_0_105.mat"), "DE")
    a = wearsim.analyze(x, meta["fs"], bearing="cwru-6205-de", rpm=1851.0)
    assert a["speed_refined"] is not None and a["rpm_source"] == "shaft line"
    assert abs(a["rpm"] / 1797.0 - 1.0) < 0.005
    assert a["diagnosis"]["family"] == "InnerRace"
    kept = wearsim.analyze(x, meta["fs"], bearing="cwru-6205-de", rpm=1851.0, trust_rpm=True)
    assert kept["speed_refined"] is None and kept["rpm"] == 1851.0


def test_gap_of_a_measured_record(tmp_path):
    # `wearsim.gap(path)` once passed the path where the command wants `--real PATH`, so
    # every call with a real record failed with a usage error.
    rec = _cwru_dir() / "12k_Drive_End_OR007@6_0_130.mat"
    r = wearsim.gap(str(rec), out=str(tmp_path / "gap"), jobs=2)
    g = r["files"]["gap.json"]
    assert g["records"][0]["meta"]["file"].endswith(rec.name)
    assert g["totals"]["after"] < g["totals"]["before"]
    assert "transfer-path" in [x["effect"] for x in g["ranking"]]
