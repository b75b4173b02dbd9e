"""Hostile input from Python, as a demanding outside user tries it: every bad value is a
ConfigError naming the field (never a crash, a silent default or another exception type)."""

import subprocess
import sys

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

