"""Sweeps from Python: the Parquet index, byte-identical shards on a 2-worker Dask cluster,
and a sweep killed with SIGKILL and resumed with nothing lost or doubled."""

import json
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import wearsim

HERE = Path(__file__).resolve().parent
SPEC = (HERE.parent / "examples" / "small-sweep.toml").read_text()


def tree(d: Path):
    return {str(p.relative_to(d)): p.read_bytes() for p in sorted(d.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("ref") / "set"
    r = wearsim.sweep(SPEC, out, threads=1)
    assert r["complete"] and r["records_generated"] == 24
    return out


def test_index_has_every_label_and_parameter(reference):
    pa = pytest.importorskip("pyarrow.parquet")
    t = pa.read_table(reference / "index.parquet").to_pydict()
    assert t["record"] == list(range(24))
    assert set(t["fault"]) == {"healthy", "outer", "inner", "ball"}
    assert all(s == "healthy" for f, s in zip(t["fault"], t["stage"]) if f == "healthy")
    assert all(0.01 <= v <= 0.2 for v in t["sensor.noise"])
    assert set(t["sensor.hum_hz"]) <= {50.0, 60.0}
    assert 0 < sum(t["effect.sensor"]) < 24
    assert all(t["effect.slip"])
    # The config column reproduces a record exactly.
    i = 13
    x, _ = wearsim.simulate(t["config"][i])
    sig = np.load(reference / "shards" / f"shard-{t['shard'][i]:05d}.npy")
    assert sig.dtype == np.float32 and sig.shape == (6, 1200)
    assert np.array_equal(sig[t["row"][i]], x.astype(np.float32))
    index, signals = wearsim.load_dataset(reference)
    assert len(index) == 24 and signals(3).shape == (6, 1200)
    # The data set names the library that made it, as the package reports it.
    manifest = json.loads((reference / "manifest.json").read_text())
    assert re.fullmatch(r"\d+\.\d+\.\d+.*", wearsim.__version__)
    assert manifest["wearsim_version"] == wearsim.__version__


def test_dask_two_workers_byte_identical(reference, tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cl:
        with distributed.Client(cl) as client:
            r = wearsim.sweep(SPEC, tmp_path / "set", cluster=client)
    assert r["complete"]
    # The local report's keys (the Dask one had `shards` only, no written/skipped/time).
    assert r["records_generated"] == 24 and r["shards_written"] == 4 and r["shards_skipped"] == 0
    assert r["simulated_s"] == pytest.approx(24 * 0.1) and r["wall_s"] > 0 and r["workers"] == 2
    assert tree(tmp_path / "set") == tree(reference)


def test_sigkill_then_resume_loses_and_doubles_nothing(tmp_path):
    spec = SPEC.replace("records = 24", "records = 40").replace("records_per_shard = 6", "records_per_shard = 2")
    ref = tmp_path / "ref"
    wearsim.sweep(spec, ref, threads=2)
    out = tmp_path / "set"
    code = f"import wearsim, sys; wearsim.sweep(sys.stdin.read(), {str(out)!r}, threads=1)"
    p = subprocess.Popen([sys.executable, "-c", code], stdin=subprocess.PIPE)
    p.stdin.write(spec.encode())
    p.stdin.close()
    shards = out / "shards"
    while p.poll() is None and len(list(shards.glob("*.done.json"))) < 3:
        time.sleep(0.005)
    assert p.poll() is None, "the sweep finished before it could be killed"
    os.kill(p.pid, signal.SIGKILL)
    p.wait()
    done = len(list(shards.glob("*.done.json")))
    assert 3 <= done < 20
    assert not (out / "manifest.json").exists()
    r = wearsim.sweep(spec, out, threads=2)
    assert r["complete"]
    assert r["records_generated"] == 40 - 2 * done
    # The killed shard's temporary file is gone and the set equals the reference.
    assert tree(out) == tree(ref)


def test_bad_spec_raises_config_error(tmp_path):
    with pytest.raises(wearsim.ConfigError, match="grid.fault"):
        wearsim.sweep(SPEC.replace('"ball"]', '"cage"]'), tmp_path / "a")
    with pytest.raises(wearsim.ConfigError, match="fraction"):
        wearsim.sweep(SPEC.replace("[0.0, 0.02]", "[0.0, 0.9]"), tmp_path / "a")
    assert not (tmp_path / "a").exists()


def test_a_directory_of_another_sweep_is_named_as_the_out_argument(tmp_path):
    # The native message says `--out DIR`, as the command line does; the call has `out`.
    (tmp_path / "d").mkdir()
    wearsim.sweep(SPEC.replace("records = 24", "records = 6"), tmp_path / "d", threads=1)
    with pytest.raises(wearsim.ConfigError) as e:
        wearsim.sweep(SPEC.replace("seed = 11", "seed = 12"), tmp_path / "d", threads=1)
    msg = str(e.value)
    assert "holds another sweep" in msg and "out = " in msg and "--" not in msg, msg
