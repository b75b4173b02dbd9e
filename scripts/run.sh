#!/usr/bin/env bash
# Sets up and runs the main job: builds wearsim (release) and simulates the built-in
# reference scenario (thesis-61810: SKF 61810 at 160 rad/s with a medium outer-race
# defect), writing wearsim-out/simulate.{csv,wav,json} and printing the summary.
# Extra arguments go to `wearsim simulate` (e.g. --duration 5 --topography real-dent).
set -euo pipefail
cd "$(dirname "$0")/.."
command -v cargo >/dev/null || { echo "cargo not found: install Rust with rustup first" >&2; exit 1; }
cargo build --release -p wearsim-host --bin wearsim
exec ./target/release/wearsim simulate "$@"
