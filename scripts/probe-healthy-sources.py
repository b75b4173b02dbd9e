#!/usr/bin/env python3
"""Healthy-machine envelope sources that are not a bearing fault (docs/cwru-detector.md,
"Lines locked to the mains"). Pure Python (no numpy), no data files; single-column CSV.

  probe-healthy-sources.py SEED [DIR]   the development probe: five 10 s, 12 kHz records
      (loose1x_1797, rub2x_1750, am120_2000, imp120_2000, gear25_1797; the rpm in the
      name). Analyse with `wearsim analyze FILE --fs 12000 --rpm RPM --bearing cwru-6205-de`.
  probe-healthy-sources.py judged [DIR] the judged set (made after the rule's constants were
      fixed): seeds 101-105, a 50.02 Hz grid's 100.04 Hz impulses exciting a 5 kHz mode
      (imp100_sS) and a 100.04 Hz modulation of broadband noise (am100_sS), 25.6 kHz, 5 s.
      Analyse with `--fs 25600` and `--bearing cwru-6203-fe --rpm 1504` or
      `--bearing cwru-6205-de --rpm 1674`.

DIR defaults to /tmp/probe.
"""
import math
import os
import random
import sys


def write(name, x):
    with open(name, "w") as f:
        f.write("accel\n")
        f.writelines("%.6g\n" % v for v in x)


def resonance_train(times, fs, n, f0, zeta, jitter):
    """Impulse responses of one mode (f0 Hz, damping zeta) at `times` (s), jittered."""
    x = [0.0] * n
    wd = 2 * math.pi * f0
    a = zeta * wd
    length = int(fs * 8 / a)
    for t in times:
        t += random.gauss(0, jitter)
        i0 = int(t * fs)
        for k in range(length):
            i = i0 + k
            if i >= n:
                break
            tt = i / fs - t
            if tt >= 0:
                x[i] += math.exp(-a * tt) * math.sin(wd * tt)
    return x


def noisy(x, sd):
    return [v + random.gauss(0, sd) for v in x]


def development(seed, out):
    random.seed(seed)
    fs, dur = 12000.0, 10.0
    n = int(fs * dur)
    train = lambda rate: resonance_train(
        [k / rate for k in range(int(dur * rate))], fs, n, 3000.0, 0.05, 0.0002)
    f1 = 1797 / 60
    write(out + "/loose1x_1797.csv", noisy(train(f1), 0.3))
    write(out + "/rub2x_1750.csv", noisy(train(2 * 1750 / 60), 0.3))
    write(out + "/am120_2000.csv",
          [random.gauss(0, 1) * (1 + 0.8 * math.sin(2 * math.pi * 120 * i / fs)) for i in range(n)])
    random.seed(seed * 1000 + 4)
    x = resonance_train([k / 120.0 for k in range(int(dur * 120))], fs, n, 3000.0, 0.05, 0.00005)
    write(out + "/imp120_2000.csv", noisy(x, 0.3))
    fm = 25 * f1
    write(out + "/gear25_1797.csv",
          [(1 + 0.5 * math.cos(2 * math.pi * f1 * i / fs)) * math.sin(2 * math.pi * fm * i / fs)
           + random.gauss(0, 0.3) for i in range(n)])


def judged(out):
    fs, dur, grid = 25600.0, 5.0, 50.02
    n = int(fs * dur)
    for seed in range(1, 6):
        random.seed(100 + seed)
        t = [k / (2 * grid) for k in range(int(dur * 2 * grid))]
        x = resonance_train(t, fs, n, 5000.0, 0.04, 0.00003)
        write(out + "/imp100_s%d.csv" % seed, noisy(x, 0.3))
        write(out + "/am100_s%d.csv" % seed,
              [random.gauss(0, 1) * (1 + 0.8 * math.sin(2 * math.pi * 2 * grid * i / fs))
               for i in range(n)])


if __name__ == "__main__":
    what = sys.argv[1] if len(sys.argv) > 1 else "1"
    out = sys.argv[2] if len(sys.argv) > 2 else "/tmp/probe"
    os.makedirs(out, exist_ok=True)
    if what == "judged":
        judged(out)
    else:
        development(int(what), out)
