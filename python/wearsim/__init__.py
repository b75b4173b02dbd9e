"""wearsim from Python: rolling-bearing vibration over the wear life.

Every function calls the same Rust library as the ``wearsim`` command (same code path,
same samples bit for bit for the same configuration and seed); the GIL is released while
it computes. Bad input raises :class:`ConfigError` (a ``ValueError``) naming the field and
its allowed range; a failed run raises ``RuntimeError``. See docs/python.md.
"""

from __future__ import annotations

import json
import numbers
import os
import re
import tempfile
from pathlib import Path
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np

from . import _wearsim
from ._wearsim import ConfigError

#: Version of the wearsim library inside this package (the one a sweep's index stamps as
#: ``wearsim_version``).
__version__: str = _wearsim.__version__

#: Most worker threads one call takes (``sweep(threads=...)``, ``life(threads=...)``): the
#: command line's ``--threads``/``--jobs`` bound; past the cores more threads add only memory.
MAX_WORKERS: int = _wearsim.MAX_WORKERS

__all__ = [
    "__version__",
    "MAX_WORKERS",
    "ConfigError",
    "simulate",
    "life",
    "analyze",
    "gap",
    "effects",
    "presets",
    "bearings",
    "sweep",
    "load_dataset",
    "read_record",
]


def simulate(
    preset_or_config: Union[str, Dict[str, Any]] = "thesis-61810", **overrides: Any
) -> Tuple[np.ndarray, Dict[str, Any]]:
    """Simulate one scenario.

    ``preset_or_config`` is a preset name (``presets()``), TOML text of a scenario file,
    or a dict with the same keys. ``overrides`` are scenario-file keys merged on top
    (e.g. ``duration=1.0, fs=12000, seed=3, speed={"rpm": 1750},
    effect=[{"name": ..., "params": {...}}]``).

    Returns ``(accel, meta)``: the acceleration in m/s² (float64, ``meta["fs"]`` Hz) and
    the metadata, whose ``"config"`` is the resolved model configuration and
    ``"scenario"`` the scenario file that produced it (``simulate(meta["scenario"])``
    reproduces the run). ``channels="all"`` is refused: only the acceleration is returned.
    Ctrl-C stops the run and raises ``KeyboardInterrupt``.
    """
    x, meta = _wearsim.simulate(preset_or_config, overrides)
    return x, json.loads(meta)


def effects() -> List[Dict[str, Any]]:
    """The candidate-effect registry: names, parameters, units, defaults and bounds."""
    return json.loads(_wearsim.effects())


def presets() -> List[Dict[str, Any]]:
    """The presets with their geometry and derived fault frequencies (Hz and orders)."""
    return json.loads(_wearsim.presets())


def bearings() -> List[Dict[str, Any]]:
    """The catalogue bearings: geometries of public data sets that are no model preset
    (``mfpt-nice``, ``paderborn-6203``, ``xjtu-ldk-uer204``), each with its elements, ball
    and pitch diameter (mm), contact angle (degrees), kinematic orders (FTF, BPFO, BPFI, BSF
    per shaft revolution) and the source of its numbers. Their names are accepted wherever a
    bearing is (``analyze(bearing=...)``, ``gap``, ``features``)."""
    return json.loads(_wearsim.bearings())


_GEOMETRY_KEYS = ("elements", "ball", "pitch", "angle")


def analyze(
    signal: Any,
    fs: float,
    bearing: Union[str, Dict[str, float], None] = None,
    rpm: Optional[float] = None,
    trust_rpm: bool = False,
) -> Dict[str, Any]:
    """Analyse a signal like ``wearsim analyze --json``: statistics, kurtogram band,
    envelope-spectrum fault family, zones. ``bearing`` is a preset or catalogue name
    (see ``presets()`` and ``bearings()``) or any bearing's geometry as a dict like ``--bearing-geometry``:
    ``{"elements": 9, "ball": 7.94, "pitch": 39.04, "angle": 0}`` (diameters in mm,
    contact angle in degrees; ``angle`` may be left out for 0). ``rpm`` is the shaft
    speed; a speed 1-5 % from the signal's own 1x line (with its own 2x or 3x), with no
    line at the stated 1x, is replaced by the speed of the line's 1x-5x series (reported
    under ``speed_refined``) unless ``trust_rpm`` is true
    (``--trust-rpm``: a tachometer's speed)."""
    geometry = None
    if isinstance(bearing, dict):
        geometry = _geometry(bearing)
        bearing = None
    elif bearing is not None and not isinstance(bearing, str):
        raise ConfigError(
            f"bearing: expected a preset name (see presets()) or a geometry dict with keys "
            f"{', '.join(_GEOMETRY_KEYS)}, got {type(bearing).__name__}"
        )
    x = _one_channel(signal)
    rpm_v = None if rpm is None else _number("rpm", rpm)
    if not isinstance(trust_rpm, bool):
        raise ConfigError(f"trust_rpm: expected True or False, got {type(trust_rpm).__name__}")
    fs_v = _number("fs", fs)
    try:
        out = _wearsim.analyze(x, fs_v, bearing, rpm_v, geometry, trust_rpm)
    except ConfigError as e:
        raise ConfigError(_pythonic(str(e), _ANALYZE_NAMES)) from None
    return json.loads(out)


def _geometry(g: Dict[str, Any]) -> str:
    """A geometry dict as ``--bearing-geometry`` text; unknown keys and non-numbers are
    ConfigErrors naming them (the ranges are checked natively, naming the field)."""
    unknown = [k for k in g if k not in _GEOMETRY_KEYS]
    if unknown:
        raise ConfigError(f"bearing: unknown geometry key {unknown[0]!r}; expected {', '.join(_GEOMETRY_KEYS)}")
    parts = []
    for k in _GEOMETRY_KEYS:
        if k in g:
            parts.append(f"{k}={_number(f'bearing.{k}', g[k])!r}")
    return ",".join(parts)


def _one_channel(signal: Any) -> np.ndarray:
    """``signal`` as a contiguous 1-D float64 array: real numbers, 1-D or a single row or
    column (several channels are refused rather than run together into one)."""
    try:
        a = np.asarray(signal)
    except (TypeError, ValueError) as e:
        raise ConfigError(f"signal: not an array of numbers ({e})") from None
    if a.dtype.kind not in "biuf":
        raise ConfigError(f"signal: expected real numbers, got an array of dtype {a.dtype}")
    if a.ndim != 1 and not (a.ndim == 2 and 1 in a.shape):
        raise ConfigError(f"signal: expected one channel (a 1-D array), got shape {a.shape}; pass one, e.g. signal[:, 0]")
    return np.ascontiguousarray(a, dtype=np.float64).ravel()


def _number(field: str, v: Any) -> float:
    """``v`` as a float if it is a real number (not a string or a bool), else ConfigError."""
    if isinstance(v, (bool, np.bool_)) or not isinstance(v, numbers.Real):
        raise ConfigError(f"{field}: expected a number, got {type(v).__name__}")
    return float(v)


def read_record(path: Union[str, os.PathLike], channel: Optional[str] = None) -> Tuple[np.ndarray, Dict[str, Any]]:
    """Read a measurement file (CWRU ``.mat`` — channel ``"DE"`` by default —, CSV, WAV,
    NPY, IMS snapshot) like ``wearsim analyze``: ``(samples, meta)`` with ``meta["fs"]``,
    ``meta["rpm"]``, ``meta["unit"]`` and the file's labels in ``meta["meta"]``."""
    if not isinstance(path, (str, os.PathLike)):
        raise ConfigError(f"path: expected a str or os.PathLike path, got {type(path).__name__}")
    if channel is not None and not isinstance(channel, str):
        raise ConfigError(f"channel: expected a channel name (str) such as \"DE\", got {type(channel).__name__}")
    try:
        x, meta = _wearsim.read_record(os.fsdecode(os.fspath(path)), channel)
    except ConfigError as e:
        raise ConfigError(_pythonic(str(e))) from None
    return x, json.loads(meta)


_FLAG = re.compile(r"(?<![\w/.-])--([a-z][a-z0-9-]*)")
_FLAG_VALUE = re.compile(r"(?<![\w/.-])--([a-z][a-z0-9-]*) (-?[0-9.][^\s:,;]*)")
_QUOTED_FLAG = re.compile(r"'--([a-z][a-z0-9-]*)(?: <[^>]*>)?'")


def _keyword(flag: str) -> str:
    """A command-line option's name (``stop-after``) as its keyword argument (``stop_after``)."""
    return flag.replace("-", "_")


def _pythonic(message: str, names: Optional[Dict[str, str]] = None) -> str:
    """A native message in the Python API's words: options named as the keyword arguments
    that set them (``--stop-after 0`` → ``stop_after=0``, ``names`` first, e.g. ``--real``
    → ``records``), ``wearsim effects`` as ``wearsim.effects()``, and the argument parser's
    usage lines and ``--help`` hint left out, as the call has neither."""
    lines = [
        ln.strip()
        for ln in message.splitlines()
        if ln.strip() and not ln.startswith(("Usage:", "For more information"))
    ]
    text = "; ".join(lines)
    text = re.sub(r"^error: ", "", text)
    text = re.sub(r"unexpected argument '--([a-z0-9-]+)' found",
                  lambda m: f"unexpected keyword argument '{_keyword(m.group(1))}'", text)
    text = text.replace("tip: a similar argument exists:", "a similar keyword argument exists:")
    for old, new in (names or {}).items():
        text = text.replace(old, new)
    text = re.sub(r"`wearsim (effects|presets|bearings)`", r"`wearsim.\1()`", text)
    text = _QUOTED_FLAG.sub(lambda m: f"'{_keyword(m.group(1))}'", text)
    text = _FLAG_VALUE.sub(lambda m: f"{_keyword(m.group(1))}={m.group(2)}", text)
    return _FLAG.sub(lambda m: _keyword(m.group(1)), text)


# How `analyze`'s native messages name its arguments (`geometry` is the `bearing` dict).
_ANALYZE_NAMES = {
    "--bearing-geometry elements=N,ball=MM,pitch=MM,angle=DEG":
        'bearing={"elements": N, "ball": MM, "pitch": MM, "angle": DEG}',
    "--bearing-geometry": "bearing (a geometry dict)",
    "--bearing NAME": "bearing=NAME",
}
# How the commands behind `life` and `gap` name their options (`--real` is `records`).
_CLI_NAMES = {
    "--real": "records",
    "--bearing-geometry elements=N,ball=MM,pitch=MM,angle=DEG":
        'bearing_geometry="elements=N,ball=MM,pitch=MM,angle=DEG"',
    "--bearing NAME": "bearing=NAME",
}


def _flag_value(key: str, v: Any) -> str:
    """One option's value as the command line takes it: an effect given as a dict
    (``{"name": "sensor", "noise": 0.1}``, as in :func:`simulate`'s ``effect`` list) in the
    ``NAME:KEY=VALUE,...`` form of ``--effect``; anything else as ``str``."""
    if key == "effect" and isinstance(v, dict):
        if not isinstance(v.get("name"), str):
            raise ConfigError(f"effect = {v!r}: an effect given as a dict needs its \"name\"")
        params = ",".join(f"{k}={p}" for k, p in v.items() if k != "name")
        return f"{v['name']}:{params}" if params else v["name"]
    return str(v)


def _argv(command: str, kwargs: Dict[str, Any]) -> List[str]:
    # `--flag=value`, so that a value beginning with "-" (an output directory "-runs", a
    # negative number) is not read as another option.
    argv = [command]
    for k, v in kwargs.items():
        flag = "--" + k.replace("_", "-")
        if v is None or v is False:
            continue
        if v is True:
            argv.append(flag)
        elif isinstance(v, (list, tuple)):
            argv += [f"{flag}={_flag_value(k, item)}" for item in v]
        else:
            argv.append(f"{flag}={_flag_value(k, v)}")
    return argv


def _out_dir(out: Any) -> str:
    """``out`` as a directory path (str), or ConfigError: ``str(7)`` would name a folder
    "7" in the working directory, which the whole command would fill before a TypeError."""
    if not isinstance(out, (str, os.PathLike)):
        raise ConfigError(f"out = {out!r}: give the output directory as a str or os.PathLike path")
    p = os.fspath(out)
    if isinstance(p, bytes):
        p = os.fsdecode(p)
    if p == "":
        raise ConfigError("out = '': give the output directory's path")
    return p


def _stats(out: str) -> Dict[str, Tuple[int, int, int]]:
    """Identity of every file in ``out`` (inode, mtime in ns, size); empty if none."""
    try:
        with os.scandir(out) as it:
            return {e.name: _stat_key(e.stat()) for e in it if e.is_file()}
    except (FileNotFoundError, NotADirectoryError):
        return {}


def _stat_key(st: os.stat_result) -> Tuple[int, int, int]:
    return (st.st_ino, st.st_mtime_ns, st.st_size)


def _run_cli(command: str, args: List[str], kwargs: Dict[str, Any], out: Any) -> Dict[str, Any]:
    tmp = None
    if out is None:
        tmp = tempfile.TemporaryDirectory(prefix=f"wearsim-{command}-")
        out = os.path.join(tmp.name, "out")
    out = _out_dir(out)
    kwargs = dict(kwargs)
    config_file = None
    try:
        conf = kwargs.get("config")
        if isinstance(conf, dict) or (isinstance(conf, str) and "=" in conf and not os.path.exists(conf)):
            # A scenario as a dict or TOML text, as `simulate` takes it: checked and written
            # as a file for the command's --config (a dict was passed as its repr, "not found").
            text = _wearsim.scenario_toml(conf)
            config_file = tempfile.NamedTemporaryFile("w", suffix=".toml", prefix="wearsim-config-", delete=False)
            with config_file:
                config_file.write(text)
            kwargs["config"] = config_file.name
        argv = _argv(command, kwargs) + list(args) + [f"--out={out}"]
        # Only what this run wrote is returned: files from an earlier run (another seed's
        # features), or the user's own (notes.csv, an unrelated config.json), are not. The
        # commands write every file anew (a new file, or renamed over the old one).
        before = _stats(out)
        code, message = _wearsim.cli(argv)
        if code == 2:
            raise ConfigError(_pythonic(message, _CLI_NAMES))
        if code != 0:
            raise RuntimeError(_pythonic(message, _CLI_NAMES))
        # A temporary `out` is gone when this returns: its path is not returned.
        result: Dict[str, Any] = {"out": None if tmp is not None else out, "files": {}}
        for p in sorted(Path(out).glob("*")):
            if not p.is_file() or before.get(p.name) == _stat_key(p.stat()):
                continue
            if p.suffix == ".json":
                result["files"][p.name] = json.loads(p.read_text())
            elif p.suffix == ".csv":
                result["files"][p.name] = p.read_text()
        return result
    finally:
        if tmp is not None:
            tmp.cleanup()
        if config_file is not None:
            os.unlink(config_file.name)


def life(out: Union[str, os.PathLike, None] = None, **kwargs: Any) -> Dict[str, Any]:
    """Run a whole wear life like ``wearsim life`` (keyword arguments are its options,
    ``preset="cwru-6205-de"``, ``config="life.toml"``, ...). Wraps the command at file
    level: it writes into ``out`` (a temporary directory when ``None``) and returns
    ``{"out": ..., "files": {name: parsed JSON or CSV text}}`` with the JSON and CSV files
    this run wrote (not older files in ``out``), and ``"complete"``: whether the run wrote
    its completion marker (``life-summary.json``, or ``lives.json`` with ``lives=``). A
    dense run stopped by ``stop_after`` is not complete; give ``out`` to resume it (a
    temporary ``out`` is removed on return, and ``"out"`` is then ``None``)."""
    r = _run_cli("life", [], kwargs, out)
    r["complete"] = "life-summary.json" in r["files"] or "lives.json" in r["files"]
    return r


def gap(records: Union[str, List[str]], out: Union[str, os.PathLike, None] = None, **kwargs: Any) -> Dict[str, Any]:
    """Diagnose the sim-to-real gap of measured records like ``wearsim gap`` (keyword
    arguments are its options). File level, like :func:`life`."""
    if isinstance(records, (str, os.PathLike)):
        files = [records]
    elif isinstance(records, (list, tuple)) and all(isinstance(f, (str, os.PathLike)) for f in records):
        files = list(records)
    else:
        raise ConfigError(f"records: expected a path or a list of paths, got {type(records).__name__}")
    if not files:
        raise ConfigError("records: at least one record is needed")
    real = [f"--real={os.fspath(f)}" for f in files]
    return _run_cli("gap", real, kwargs, out)


from ._sweep import load_dataset, sweep  # noqa: E402
