#!/usr/bin/env bash
# Benchmark of issue 6: one full `wearsim gap` run on one CWRU file on one core
# (`--jobs 1`), reporting wall-clock and CPU time and the simulations it needed.
# Usage: scripts/bench-gap.sh [FILE]   (default: the 0.007 in inner-race record at 0 hp)
set -euo pipefail
cd "$(dirname "$0")/.."
data="${WEARSIM_DATA:-../shared/data}"
file="${1:-$data/cwru/12k_Drive_End_IR007_0_105.mat}"
[ -f "$file" ] || { echo "bench-gap: $file not found (set WEARSIM_DATA)" >&2; exit 2; }
cargo build --release -q -p wearsim-host
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
start=$(date +%s.%N)
/usr/bin/env time -f "%U %S" -o "$out/time" ./target/release/wearsim gap --real "$file" --jobs 1 --out "$out/gap" --json > "$out/gap.json"
end=$(date +%s.%N)
read -r user sys < "$out/time"
python3 - "$out/gap.json" "$start" "$end" "$user" "$sys" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
wall = float(sys.argv[3]) - float(sys.argv[2])
cpu = float(sys.argv[4]) + float(sys.argv[5])
print(json.dumps({"file": r["records"][0]["meta"]["file"], "jobs": 1, "wall_s": round(wall, 2),
                  "cpu_s": round(cpu, 2), "simulations": r["simulations"],
                  "total_before": r["totals"]["before"], "total_after": r["totals"]["after"],
                  "under_a_minute": wall < 60.0}, indent=2))
PY
