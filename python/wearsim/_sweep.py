"""Labelled data sets: ``wearsim.sweep`` runs a sweep spec (docs/datasets.md) locally on
threads, or on a Dask cluster with one task per shard. Every way gives the same bytes:
each shard is a pure function of the spec and its number."""

from __future__ import annotations

import json
import numbers
import os
import time
from pathlib import Path
from typing import Any, Dict, Optional, Tuple, Union

import numpy as np

from . import _out_dir, _wearsim  # _out_dir: defined before __init__ imports this module
from ._wearsim import ConfigError


def _is_file(s: str) -> bool:
    try:
        return Path(s).is_file()
    except (OSError, ValueError):  # a name too long, a NUL byte: not a path
        return False


def _spec_text(spec: Union[str, os.PathLike]) -> str:
    """The TOML text of ``spec``: a path (``PathLike``, or a one-line string that names a
    file or has no ``=``) is read; anything else is the text itself. A path may hold ``=``
    (Hydra-style run directories, ``runs/lr=0.1/spec.toml``)."""
    if not isinstance(spec, (str, os.PathLike)):
        raise ConfigError(f"spec: expected a TOML file path or TOML text, got {type(spec).__name__}")
    s = os.fspath(spec)
    if isinstance(spec, os.PathLike) or ("\n" not in s and (_is_file(s) or "=" not in s)):
        if not Path(s).is_file():
            raise ConfigError(f"spec: {s}: no such file (pass a TOML file path or TOML text)")
        return Path(s).read_text()
    return s


def _count(field: str, v: Any) -> int:
    """``v`` as an int if it is an integer >= 0 (not a bool), else ConfigError."""
    if isinstance(v, bool) or not isinstance(v, numbers.Integral) or v < 0:
        raise ConfigError(f"{field} = {v!r}: expected an integer >= 0")
    return int(v)


def _part(part: Any) -> Optional[Tuple[int, int]]:
    """``part=(I, N)`` as two integers >= 0 (the native side checks I < N)."""
    if part is None:
        return None
    if not isinstance(part, tuple) or len(part) != 2:
        raise ConfigError(f"part = {part!r}: expected a tuple (I, N) with 0 <= I < N")
    return _count("part[0]", part[0]), _count("part[1]", part[1])  # 0 <= I < N: checked natively


def _native(fn: Any, *args: Any) -> Any:
    """``fn(*args)`` of the native module, its errors naming ``out`` as this API does (the
    native messages say ``--out DIR`` as the command line does)."""
    try:
        return fn(*args)
    except ConfigError as e:
        raise ConfigError(str(e).replace("--out ", "out = ")) from None


def _shard_task(spec_text: str, out: str, shard: int) -> int:
    # Runs on a Dask worker: imports the package there.
    from wearsim import _wearsim as native

    return native.sweep_shard(spec_text, out, shard)


def sweep(
    spec: Union[str, os.PathLike],
    out: Union[str, os.PathLike],
    cluster: Any = None,
    threads: Optional[int] = None,
    part: Optional[Tuple[int, int]] = None,
) -> Dict[str, Any]:
    """Generate the labelled data set of ``spec`` (a TOML file path or TOML text) into
    ``out``; resumable (complete shards are skipped).

    ``cluster``: ``None`` runs on local threads (``threads``, default every core);
    otherwise a ``dask.distributed`` ``Client`` or anything ``Client(...)`` accepts
    (a ``LocalCluster``, a scheduler address): one task per pending shard. ``part=(I,
    N)`` generates only shards with index mod N == I (like ``--shard I/N``).
    Returns a report dict (``complete`` is True once every shard and the index exist).
    Ctrl-C stops a local sweep once each thread has written the shards it is on (complete,
    kept; no index or manifest) and raises ``KeyboardInterrupt``: the same call resumes.
    """
    text = _spec_text(spec)
    out = _out_dir(out)
    part = _part(part)
    if cluster is None:
        most = _wearsim.MAX_WORKERS  # `wearsim sweep --threads`'s rule (lanes::workers)
        if threads is None:
            n = min(os.cpu_count() or 1, most)
        else:
            n = _count("threads", threads)
            if not 1 <= n <= most:  # 0 ran on one thread; 10**6 started a million threads
                raise ConfigError(f"threads = {n} is out of range: allowed 1 ..= {most}")
        return json.loads(_native(_wearsim.sweep_run, text, out, n, part))
    from dask.distributed import Client

    plan = json.loads(_wearsim.sweep_plan(text, part))
    # The client first: a bad `cluster` once left an initialised `out` (sweep.json,
    # shards/) behind it. A client made here is closed here.
    if isinstance(cluster, Client):
        client, own = cluster, False
    else:
        try:
            client, own = Client(cluster), True
        except (TypeError, ValueError) as e:
            raise ConfigError(
                f"cluster = {cluster!r}: expected a dask.distributed Client, a cluster or a scheduler address ({e})"
            ) from None
    try:
        t0 = time.perf_counter()
        _native(_wearsim.sweep_prepare, text, out)
        shards = [s for s in range(plan["shards"]) if part is None or s % part[1] == part[0]]
        futures = client.map(_shard_task, [text] * len(shards), [out] * len(shards), shards, pure=False)
        per_shard = client.gather(futures)
        complete, nbytes = _native(_wearsim.sweep_finalize, text, out)
        generated = sum(per_shard)
        written = sum(1 for n in per_shard if n > 0)
        # The local report's keys (`shards` kept for earlier callers), `workers` for `threads`.
        return {
            "records_generated": generated,
            "shards_written": written,
            "shards_skipped": len(shards) - written,
            "shards": len(shards),
            "complete": complete,
            "simulated_s": generated * plan["duration"],
            "wall_s": time.perf_counter() - t0,
            "workers": len(client.scheduler_info().get("workers", {})),
            "bytes": nbytes,
        }
    finally:
        if own:
            client.close()


def load_dataset(path: Union[str, os.PathLike], mmap: bool = True):
    """Load a complete data set: ``(index, signals)`` with ``index`` a pandas DataFrame
    (pyarrow) and ``signals`` a function ``signals(shard) -> ndarray [records, samples]``
    (float32, memory-mapped). Raises ``RuntimeError`` for an incomplete set."""
    import pyarrow.parquet as pq

    p = Path(path)
    manifest = p / "manifest.json"
    if not manifest.is_file() or not json.loads(manifest.read_text()).get("complete"):
        raise RuntimeError(f"{p}: not a complete wearsim data set (no manifest.json)")
    shards = int(json.loads(manifest.read_text()).get("shards", 0))
    table = pq.read_table(p / "index.parquet")
    index = table.to_pandas() if _has_pandas() else table

    def signals(shard: int) -> np.ndarray:
        if isinstance(shard, (bool, np.bool_)) or not isinstance(shard, (int, np.integer)):
            raise ConfigError(f"shard: expected an integer 0..={shards - 1}, got {type(shard).__name__}")
        if not 0 <= shard < shards:
            raise ConfigError(f"shard = {shard} is out of range: this data set has shards 0..={shards - 1}")
        return np.load(p / "shards" / f"shard-{int(shard):05d}.npy", mmap_mode="r" if mmap else None)

    return index, signals


def _has_pandas() -> bool:
    try:
        import pandas  # noqa: F401

        return True
    except ImportError:
        return False
