"""What the outside review (probe D) found: a crash on self-referencing input, Ctrl-C that
panicked or was held until a long call ended, duplicate effects kept silently, values
accepted and ignored, output folders misused. Crashes and interrupts run in a subprocess
so that a failure fails the test instead of pytest."""

import json
import os
import pickle
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import wearsim


def _python(code: str, *args: str, timeout: float = 300) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code), *args], capture_output=True, text=True, timeout=timeout
    )


def test_self_referencing_or_deeply_nested_input_is_a_config_error():
    # Each once overflowed the native stack: the interpreter died with SIGSEGV.
    p = _python(
        """
        import wearsim
        def msg(f):
            try:
                f()
            except wearsim.ConfigError as e:
                return str(e)
            return "accepted"
        d = {}
        d["speed"] = d
        print(msg(lambda: wearsim.simulate(d)))
        l = []
        l.append(l)
        print(msg(lambda: wearsim.simulate("cwru-6205-de", effect=l)))
        x = 1
        for _ in range(20000):
            x = [x]
        print(msg(lambda: wearsim.simulate("cwru-6205-de", duration=x)))
        """
    )
    assert p.returncode == 0, p.stderr
    cyc, lst, deep = p.stdout.splitlines()
    assert cyc.startswith("speed.speed.speed.") and "32" in cyc, cyc
    assert lst.startswith("effect[0][0][0]") and "32" in lst, lst
    assert deep.startswith("duration[0][0]") and "32" in deep, deep


def test_the_depth_bound_is_32_levels():
    # The bound refuses nesting, not values: within it, the field's own check speaks.
    def wrapped(n):
        x = 0.05
        for _ in range(n):
            x = [x]
        return x

    with pytest.raises(wearsim.ConfigError) as within:
        wearsim.simulate("cwru-6205-de", duration=wrapped(31))
    assert "nested more than" not in str(within.value)
    with pytest.raises(wearsim.ConfigError, match="nested more than 32"):
        wearsim.simulate("cwru-6205-de", duration=wrapped(32))


# The watcher thread needs the GIL to send the signal; with a switch interval of 1000 s
# the main thread keeps it until the call releases it, so the signal arrives during the
# call, whatever the machine's load (no sleeps).
_DURING_THE_CALL = """
import os, signal, sys, threading
import wearsim
signal.signal(signal.SIGINT, signal.default_int_handler)
sys.setswitchinterval(1000.0)
gate = threading.Lock()
gate.acquire()
def fire():
    gate.acquire()
    {wait}
    os.kill(os.getpid(), signal.SIGINT)
threading.Thread(target=fire, daemon=True).start()
gate.release()
try:
    {call}
    print("returned")
except KeyboardInterrupt:
    print("KeyboardInterrupt")
"""


def test_ctrl_c_in_the_first_simulate_is_a_prompt_keyboard_interrupt():
    # Was a PanicException ("Failed to access NumPy array API capsule: KeyboardInterrupt",
    # not an Exception) once the whole 300 s had been simulated.
    code = _DURING_THE_CALL.format(wait="", call='wearsim.simulate("cwru-6205-de", duration=300.0)')
    p = _python(code)
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == "KeyboardInterrupt", p.stdout + p.stderr
    assert "PanicException" not in p.stderr


SWEEP = """seed = 3
records = 2000
records_per_shard = 2
duration = 0.2
fs = 12000.0
[grid]
preset = ["cwru-6205-de"]
rpm = [1797.0]
fault = ["inner", "outer"]
stage = ["mild-defect"]
"""


def test_ctrl_c_stops_a_sweep_at_a_shard_boundary_and_it_resumes(tmp_path):
    # Was held until all 1000 shards were written (then raised, losing the report).
    out = tmp_path / "set"
    wait = (
        "import time, pathlib\n"
        "    while not (pathlib.Path(sys.argv[2]) / 'shards' / 'shard-00000.done.json').exists():\n"
        "        time.sleep(0.001)"
    )
    code = _DURING_THE_CALL.format(wait=wait, call="wearsim.sweep(sys.argv[1], sys.argv[2], threads=1)")
    p = _python(code, SWEEP, str(out))
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == "KeyboardInterrupt", p.stdout + p.stderr
    done = sorted((out / "shards").glob("*.done.json"))
    assert 1 <= len(done) < 1000
    assert not (out / "manifest.json").exists() and not (out / "index.parquet").exists()
    assert not [f for f in (out / "shards").iterdir() if ".tmp-" in f.name]
    r = wearsim.sweep(SWEEP, out, threads=2)
    assert r["complete"] and r["shards_skipped"] == len(done)
    index, signals = wearsim.load_dataset(out)
    assert len(index) == 2000 and signals(999).shape == (2, 2400)


def test_ctrl_c_stops_a_life_statistics_run_without_its_report(tmp_path):
    # Was held until every life had run (minutes), then wrote lives.json and raised.
    out = tmp_path / "lives"
    code = _DURING_THE_CALL.format(
        wait="", call="wearsim.life(out=sys.argv[1], preset='cwru-6205-de', lives=400, threads=1)"
    )
    p = _python(code, str(out))
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == "KeyboardInterrupt", p.stdout + p.stderr
    assert not (out / "lives.json").exists() and not (out / "lives.csv").exists()


def test_ctrl_c_stops_a_gap_run_without_its_report(tmp_path):
    # Was held until the whole diagnosis had run, then wrote gap.json and raised.
    sys.path.insert(0, str(Path(__file__).parent))
    from test_api import _cwru_dir

    rec = _cwru_dir() / "12k_Drive_End_OR007@6_0_130.mat"
    out = tmp_path / "gap"
    code = _DURING_THE_CALL.format(wait="", call="wearsim.gap(sys.argv[1], out=sys.argv[2], jobs=2)")
    p = _python(code, str(rec), str(out))
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == "KeyboardInterrupt", p.stdout + p.stderr
    assert not (out / "gap.json").exists()


def test_a_repeated_effect_is_refused_naming_it():
    # The first entry was silently dropped; the command line exits 2 with this message.
    two = [{"name": "sensor", "params": {"noise": 1}}, {"name": "sensor", "params": {"noise": 50}}]
    with pytest.raises(wearsim.ConfigError, match=r'`effect\[1\].name` = "sensor" repeats `effect\[0\]`'):
        wearsim.simulate("cwru-6205-de", duration=0.05, effect=two)
    text = 'preset = "cwru-6205-de"\nduration = 0.05\n' + "".join(
        f'[[effect]]\nname = "sensor"\nparams = {{ noise = {n} }}\n' for n in (1, 50)
    )
    with pytest.raises(wearsim.ConfigError, match="repeats"):
        wearsim.simulate(text)
    with pytest.raises(wearsim.ConfigError, match="repeats"):
        wearsim.simulate({"preset": "cwru-6205-de", "effect": two}, duration=0.05)


def test_channels_all_is_refused_rather_than_ignored():
    with pytest.raises(wearsim.ConfigError, match="channels"):
        wearsim.simulate("cwru-6205-de", duration=0.05, channels="all")
    x, _ = wearsim.simulate("cwru-6205-de", duration=0.05, channels="acceleration")
    assert x.ndim == 1


@pytest.mark.parametrize("call", ["life", "gap"])
def test_a_non_path_out_is_refused_before_running(call, tmp_path, monkeypatch):
    # The whole command once ran into ./7, then raised TypeError.
    monkeypatch.chdir(tmp_path)
    with pytest.raises(wearsim.ConfigError, match="out = 7"):
        if call == "life":
            wearsim.life(out=7, preset="thesis-61810")
        else:
            wearsim.gap(str(tmp_path / "none.npy"), out=7)
    assert list(tmp_path.iterdir()) == []


def test_life_returns_only_the_files_it_wrote(tmp_path):
    # Every *.json/*.csv in `out` was returned as this run's: a stale features table of an
    # earlier run, the user's notes.csv, and a malformed config.json raised JSONDecodeError
    # after the run had finished.
    out = tmp_path / "life"
    out.mkdir()
    (out / "notes.csv").write_text("mine\n")
    (out / "config.json").write_text("{not json")
    (out / "life-features.csv").write_text("stale\n")
    r = wearsim.life(out=str(out), preset="thesis-61810", dense=True, stop_after=1)
    assert r["out"] == str(out)
    assert r["files"], r
    assert not {"notes.csv", "config.json", "life-features.csv"} & set(r["files"])
    assert (out / "notes.csv").read_text() == "mine\n"
    # Stopped after 1 s of the life: not complete (the docs' example returned a deleted
    # temporary folder and no sign of that); a temporary out's path is not returned.
    assert r["complete"] is False
    t = wearsim.life(preset="thesis-61810", dense=True, stop_after=1)
    assert t["out"] is None and t["complete"] is False


def test_config_error_pickles_with_its_message():
    # Its module was `_wearsim`, which no import finds: multiprocessing lost the error.
    e = pickle.loads(pickle.dumps(wearsim.ConfigError("duration = 0 is out of range")))
    assert type(e) is wearsim.ConfigError and str(e) == "duration = 0 is out of range"
    assert wearsim.ConfigError.__module__ == "wearsim"
    try:
        wearsim.simulate("cwru-6205-de", duration=0.0)
    except wearsim.ConfigError as raised:
        again = pickle.loads(pickle.dumps(raised))
        assert "duration" in str(again)


def test_seeds_take_the_whole_u64_range():
    # 2**63 and above were refused ("out of the 64-bit integer range"); the CLI takes them.
    for seed in (2**63, 2**64 - 1):
        x, meta = wearsim.simulate("cwru-6205-de", duration=0.05, seed=seed)
        assert meta["seed"] == seed and meta["scenario"]["seed"] == seed
        y, _ = wearsim.simulate(meta["scenario"])
        assert (x == y).all()
    # The overrides' seed wins over the source's, big or not.
    _, meta = wearsim.simulate({"preset": "cwru-6205-de", "seed": 2**64 - 1}, duration=0.05, seed=5)
    assert meta["seed"] == 5
    _, meta = wearsim.simulate({"preset": "cwru-6205-de", "seed": 5}, duration=0.05, seed=2**63)
    assert meta["seed"] == 2**63
    with pytest.raises(wearsim.ConfigError, match="seed"):
        wearsim.simulate("cwru-6205-de", duration=0.05, seed=2**64)


def test_wrong_argument_types_are_config_errors(tmp_path):
    # Were TypeError ("channel=1"), a stat error of a file named "None", OverflowError, and a
    # TypeError from Client(5) after `out` had been initialised.
    with pytest.raises(wearsim.ConfigError, match="channel"):
        wearsim.read_record(str(tmp_path / "x.npy"), channel=1)
    with pytest.raises(wearsim.ConfigError, match="path"):
        wearsim.read_record(None)
    with pytest.raises(wearsim.ConfigError, match="threads"):
        wearsim.sweep(SWEEP, tmp_path / "a", threads=2**64)
    pytest.importorskip("dask.distributed")
    with pytest.raises(wearsim.ConfigError, match="cluster"):
        wearsim.sweep(SWEEP, tmp_path / "b", cluster=5)
    assert not (tmp_path / "b").exists()
