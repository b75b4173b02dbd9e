#!/usr/bin/env python3
"""`analyze`'s speed refinement on the CWRU records, two binaries compared (docs/cwru-detector.md).

Every 12 kHz record in the data folder (drive end on `DE`, fan end on `FE` with the
`cwru-6203-fe` geometry) is analysed by both binaries at 0.97, 0.98, 1, 1.02 and 1.03 x its
stored speed and at 1 800 rpm. Prints how many calls differ, and for every run whose refined
speed differs between the binaries, both errors against a whole-record reference: the Hann
periodogram of the whole record zero-padded x8, the shaft frequency that maximises the sum of
log power at 1x-10x within +-0.6 % of both estimates (numpy; not the detector's code, but the
same record). Nothing here chooses anything.

Usage: scripts/refine-speed-cwru.py NEW_WEARSIM OLD_WEARSIM [DATA_DIR] [--json]
DATA_DIR defaults to $WEARSIM_DATA/cwru or ../shared/data/cwru. Needs the Python package
(`wearsim.read_record`) and numpy.
"""
import glob
import json
import os
import statistics
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import wearsim

args = [a for a in sys.argv[1:] if a != "--json"]
if len(args) < 2:
    sys.exit(__doc__)
new, old = args[0], args[1]
root = os.environ.get("WEARSIM_DATA", os.path.join(os.path.dirname(__file__), "../../shared/data"))
data = args[2] if len(args) > 2 else os.path.join(root, "cwru")
files = sorted(glob.glob(os.path.join(data, "12k_*.mat")))
if not files:
    sys.exit(f"no 12k_*.mat records in {data}")


def fan(path):
    return "Fan_End" in os.path.basename(path)


def analyze(binary, path, rpm):
    cmd = [binary, "analyze", path, "--json"]
    if fan(path):
        cmd += ["--channel", "FE", "--bearing", "cwru-6203-fe"]
    if rpm is not None:
        cmd += ["--rpm", f"{rpm:.1f}"]
    a = json.loads(subprocess.run(cmd, capture_output=True, text=True, check=True).stdout)
    return a["diagnosis"].get("family"), a["rpm"], (a.get("speed_refined") or {}).get("harmonics")


def runs(path):
    stored = wearsim.read_record(path, channel="FE" if fan(path) else "DE")[1]["rpm"]
    rpms = [None] + [m * stored for m in (0.97, 0.98, 1.02, 1.03)] + [1800.0]
    return [(path, r, analyze(new, path, r), analyze(old, path, r)) for r in rpms]


def reference(path, a, b):
    x, meta = wearsim.read_record(path, channel="FE" if fan(path) else "DE")
    x = np.asarray(x, float) - np.mean(x)
    n = len(x)
    power = np.abs(np.fft.rfft(x * np.hanning(n), 8 * n)) ** 2
    df = meta["fs"] / (8 * n)
    grid = np.arange(min(a, b) / 60 * 0.994, max(a, b) / 60 * 1.006, 0.0005)
    score = [sum(np.log(power[int(round(k * f / df))]) for k in range(1, 11)) for f in grid]
    return 60 * grid[int(np.argmax(score))]


with ThreadPoolExecutor(os.cpu_count() or 1) as ex:
    all_runs = [r for rs in ex.map(runs, files) for r in rs]
calls_changed = [(os.path.basename(p), r) for p, r, n, o in all_runs if n[0] != o[0]]
moved = [(p, r, n, o) for p, r, n, o in all_runs if abs(n[1] - o[1]) > 0.05]
refs = {}
err_new, err_old, rows = [], [], []
for p, r, n, o in moved:
    key = (p, round(n[1], 1), round(o[1], 1))
    if key not in refs:
        refs[key] = reference(p, n[1], o[1])
    ref = refs[key]
    err_new.append(abs(100 * (n[1] / ref - 1)))
    err_old.append(abs(100 * (o[1] / ref - 1)))
    rows.append({"file": os.path.basename(p), "stated_rpm": r, "new_rpm": n[1], "old_rpm": o[1],
                 "new_harmonics": n[2], "old_harmonics": o[2], "reference_rpm": ref})
summary = {
    "runs": len(all_runs),
    "calls_changed": calls_changed,
    "refined_speed_moved": len(moved),
    "records_moved": len({r["file"] for r in rows}),
    "error_pct_median": [statistics.median(err_old), statistics.median(err_new)] if moved else None,
    "error_pct_max": [max(err_old), max(err_new)] if moved else None,
    "rows": rows,
}
if "--json" in sys.argv:
    print(json.dumps(summary, indent=1))
else:
    print(f"{summary['runs']} runs; calls changed: {len(calls_changed)} {calls_changed}")
    print(f"refined speed moved in {len(moved)} runs ({summary['records_moved']} records)")
    if moved:
        print(f"error vs whole-record reference, old -> new: median {summary['error_pct_median'][0]:.3f} "
              f"-> {summary['error_pct_median'][1]:.3f} %, largest {summary['error_pct_max'][0]:.3f} "
              f"-> {summary['error_pct_max'][1]:.3f} %")
        for r in rows:
            print(f"  {r['file']:36s} stated {r['stated_rpm'] or 'stored'}: {r['old_rpm']:.1f} ({r['old_harmonics']}) "
                  f"-> {r['new_rpm']:.1f} ({r['new_harmonics']}), reference {r['reference_rpm']:.1f}")
