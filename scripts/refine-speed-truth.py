#!/usr/bin/env python3
"""Ground truth for `analyze`'s speed refinement (docs/cwru-detector.md, stop 57).

Simulates CWRU-6205 outer-race records at known speeds (uniform 1 700-1 800 rpm, shaft
harmonics and sensor hum/noise drawn per record, 10 s at 12 kHz), analyses each with a
stated speed 0.97, 0.98, 1.02 and 1.03 x the true one, and reports how many runs were
refined, how many kept the outer-race call, and the refined speed's error against the
truth. Usage: scripts/refine-speed-truth.py WEARSIM [OTHER_WEARSIM]   (the second binary,
e.g. an older build, is run on the same records for comparison). Add --json for JSON.
"""
import json
import random
import statistics
import subprocess
import sys
import tempfile

args = [a for a in sys.argv[1:] if a != "--json"]
if not args:
    sys.exit(__doc__)
binaries = args[:2]
sim = binaries[0]
random.seed(57)
cases = [(i, round(random.uniform(1700, 1800), 1), random.choice([5, 20, 50]),
          random.choice([0, 10, 30])) for i in range(24)]
errors = {b: [] for b in binaries}
refined = {b: 0 for b in binaries}
outer = {b: 0 for b in binaries}
runs = 0
with tempfile.TemporaryDirectory() as tmp:
    for i, rpm, f2, f3 in cases:
        d = f"{tmp}/{i}"
        subprocess.run([sim, "simulate", "--preset", "cwru-6205-de", "--rpm", str(rpm),
                        "--duration", "10", "--seed", str(100 + i), "--effect",
                        f"shaft-harmonics:f2={f2},f3={f3}", "--effect", "sensor",
                        "--out", d, "--json"], capture_output=True, check=True)
        for m in (0.97, 0.98, 1.02, 1.03):
            runs += 1
            for b in binaries:
                o = subprocess.run([b, "analyze", f"{d}/simulate.wav", "--rpm",
                                    str(round(rpm * m, 1)), "--json"],
                                   capture_output=True, text=True, check=True)
                a = json.loads(o.stdout)
                outer[b] += a["diagnosis"]["family"] == "OuterRace"
                if a["rpm_source"] == "shaft line":
                    refined[b] += 1
                    errors[b].append(100.0 * abs(a["rpm"] / rpm - 1.0))
report = {"runs": runs, "binaries": {}}
for b in binaries:
    e = sorted(errors[b])
    report["binaries"][b] = {
        "refined": refined[b], "outer_race": outer[b],
        "error_pct_median": statistics.median(e) if e else None,
        "error_pct_p90": e[int(0.9 * len(e))] if e else None,
        "error_pct_max": max(e) if e else None,
    }
if "--json" in sys.argv:
    print(json.dumps(report, indent=2))
else:
    for b, r in report["binaries"].items():
        print(f"{b}: {r['refined']}/{runs} refined, {r['outer_race']}/{runs} outer race; "
              f"error median {r['error_pct_median']:.4f} %, 90th percentile "
              f"{r['error_pct_p90']:.4f} %, largest {r['error_pct_max']:.4f} %")
