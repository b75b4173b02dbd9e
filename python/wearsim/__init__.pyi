from os import PathLike
from typing import Any, Callable, Dict, List, Optional, Tuple, Union

import numpy as np

__version__: str
"""Version of the wearsim library inside this package (a sweep's ``wearsim_version``)."""

MAX_WORKERS: int
"""Most worker threads one call takes (``sweep(threads=...)``, ``life(threads=...)``)."""

class ConfigError(ValueError):
    """Bad input: the message names the field and its allowed range."""

def simulate(
    preset_or_config: Union[str, Dict[str, Any]] = ..., **overrides: Any
) -> Tuple[np.ndarray, Dict[str, Any]]: ...
def effects() -> List[Dict[str, Any]]: ...
def presets() -> List[Dict[str, Any]]: ...
def bearings() -> List[Dict[str, Any]]: ...
def analyze(
    signal: Any,
    fs: float,
    bearing: Union[str, Dict[str, float], None] = ...,
    rpm: Optional[float] = ...,
    trust_rpm: bool = ...,
) -> Dict[str, Any]: ...
def life(out: Union[str, PathLike, None] = ..., **kwargs: Any) -> Dict[str, Any]: ...
def gap(
    records: Union[str, List[str]], out: Union[str, PathLike, None] = ..., **kwargs: Any
) -> Dict[str, Any]: ...
def sweep(
    spec: Union[str, PathLike],
    out: Union[str, PathLike],
    cluster: Any = ...,
    threads: Optional[int] = ...,
    part: Optional[Tuple[int, int]] = ...,
) -> Dict[str, Any]: ...
def load_dataset(
    path: Union[str, PathLike], mmap: bool = ...
) -> Tuple[Any, Callable[[int], np.ndarray]]: ...
def read_record(
    path: Union[str, PathLike], channel: Optional[str] = ...
) -> Tuple[np.ndarray, Dict[str, Any]]: ...
