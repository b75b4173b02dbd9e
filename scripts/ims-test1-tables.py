#!/usr/bin/env python3
"""IMS test 1 bearings 3 (inner race) and 4 (roller), channel x, as documented
wearsim feature tables on running time: an interval longer than twice the median
counts as one median interval (the rig stood still), as `wearsim ims-validate` reads
test 1. Usage: ims_test1_tables.py DATA_DIR OUT_DIR"""
import csv, datetime, json, os, statistics, sys

data, out = sys.argv[1], sys.argv[2]
src = os.path.join(data, "ims/features_chocho66/test1_timefeatures.csv")
rows = list(csv.reader(open(src)))
head, body = rows[0], rows[1:]
col = {n: i for i, n in enumerate(head)}
t = [datetime.datetime.strptime(r[0], "%Y-%m-%d %H:%M:%S").timestamp() for r in body]
d = [b - a for a, b in zip(t, t[1:])]
med = statistics.median(d)
run = [0.0]
for x in d:
    run.append(run[-1] + (med if x > 2.0 * med else x))
os.makedirs(out, exist_ok=True)
for b, mode in [(3, "inner-race"), (4, "rolling-element")]:
    name = os.path.join(out, f"test1_b{b}x.csv")
    with open(name, "w") as f:
        f.write("snapshot,time_s,rms,kurtosis,crest_factor,skewness,peak\n")
        n = 0
        for i, r in enumerate(body):
            g = lambda k: float(r[col[f"B{b}_x_{k}"]])
            f.write(f"{i},{run[i]!r},{g('rms')!r},{g('kurtosis') + 3.0!r},{g('crest')!r},{g('skew')!r},{g('max')!r}\n")
            n += 1
    side = {
        "format": "wearsim-feature-table", "format_version": 1,
        "source": "IMS test 1 (NASA Ames; features_chocho66/test1_timefeatures.csv), running time",
        "bearing": {"preset": "ims-za2115", "id": f"test 1 bearing {b}"},
        "channel": f"B{b}_x", "unit": "g", "rpm": 2000.0, "radial_load_n": 26689.3296,
        "sample_rate_hz": 20000.0, "snapshot_samples": 20480,
        "snapshot_interval_s": med, "failure_mode": mode, "n_snapshots": n,
        "notes": [f"running time: intervals over {2*med:.0f} s counted as {med:.0f} s (rig stopped)"],
    }
    json.dump(side, open(name[:-4] + ".json", "w"), indent=1)
    print(name, n, "snapshots", run[-1] / 3600, "running h")
