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
