#!/usr/bin/env bash
# Sets up and runs every check of the project: formatting, lints, all tests (host,
# integration, data-backed, QEMU), the no_std builds of the core for Cortex-M0 and M4F,
# and the fast-math error measurement. With CI=true, missing measured data fails the
# data-backed tests instead of skipping them.
set -euo pipefail
cd "$(dirname "$0")/.."
# The Python extension at opt-level 1 here: its tests run a few hundred short simulations,
# and a fully optimised build of every dependency was several minutes of CI (a user's
# `pip install ./python` keeps the optimised `pyext` profile).
start=$(date +%s)
# Each step prints the minutes since the start, so a slow step shows in CI's log.
step() { printf '\n== [%d min] %s\n' "$(( ($(date +%s) - start) / 60 ))" "$*"; }

step "set-up: Rust targets, QEMU, fonts, the Python package"
CARGO_PROFILE_PYEXT_OPT_LEVEL=1 bash scripts/setup.sh

step "cargo fmt --check"
cargo fmt --all -- --check

step "cargo clippy (deny warnings)"
cargo clippy --workspace --all-targets -- -D warnings

step "no import cycle between host-sim modules"
python3 scripts/check-import-cycles.py

step "core: no_std builds for thumbv6m-none-eabi and thumbv7em-none-eabihf, both precisions"
for target in thumbv6m-none-eabi thumbv7em-none-eabihf; do
  cargo build -p wearsim-core --target "$target"
  cargo build -p wearsim-core-f32 --target "$target"
done
cargo build -p wearsim-core-f32 --target thumbv7em-none-eabihf --features fast-math,defmt
cargo clippy -p wearsim-core-f32 --target thumbv7em-none-eabihf -- -D warnings

step "every feature at once (features are additive)"
cargo check --workspace --all-features
# and the readers alone, as the fuzz targets build them (host-sim without its `app` feature)
cargo clippy -p wearsim-host --no-default-features --all-targets -- -D warnings

step "docs build without warnings"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --all-features

step "core: fast-math approximation error; serde round trips in both precisions"
cargo test -p wearsim-core-f32 --features fast-math --test fast_math
cargo test -p wearsim-core --features serde --test serde_config
cargo test -p wearsim-core-f32 --features serde --test serde_config
# The core as a microcontroller builds it (no `oversample-16`: ratios up to 8, 256-sample
# lines): low rates refused by name, checkpoints of the other capacity still resume. The
# workspace run below has the feature on (host-sim enables it).
cargo test -p wearsim-core --test low_rate --test checkpoint_resume --test lanes --test dynamics

if [ -f firmware-stub/Cargo.toml ]; then
  step "firmware-stub: fmt and clippy"
  (cd firmware-stub && cargo fmt --all -- --check && cargo clippy --all-targets -- -D warnings)

  # An image whose panic handler calls a symbol defined nowhere links only if no panic is
  # reachable in the core (both precisions, its whole public API on opaque inputs), on the
  # two targets the core is built for: the M4F and the M0 (no divide instruction, no FPU;
  # the M3 is covered by the firmware's own proof below).
  step "core: no reachable panic (link-time proof, firmware-stub/nopanic)"
  for target in thumbv7em-none-eabihf thumbv6m-none-eabi; do
    (cd firmware-stub && cargo build --release -p wearsim-nopanic --target "$target")
  done
  (cd firmware-stub && cargo clippy --release -p wearsim-nopanic --target thumbv7em-none-eabihf -- -D warnings)

  # The firmware's own code as well (its defmt logger, its interrupt queues, the frame
  # encoder, the virtual sensor): feature `panic-proof` gives the whole image the same
  # undefined-symbol panic handler; built with no feature and with every one, so both sides
  # of each `cfg` are linked.
  step "firmware: no reachable panic in the whole image (wearsim-fw, feature panic-proof)"
  for target in thumbv7em-none-eabihf thumbv7m-none-eabi; do
    for features in "panic-proof" "panic-proof life i16-stream fast-math"; do
      (cd firmware-stub && cargo build --release -p wearsim-fw --target "$target" --features "$features")
    done
  done
  # The host clippy above sees only the stub of the firmware binary; lint the image itself.
  (cd firmware-stub && cargo clippy --release -p wearsim-fw --target thumbv7em-none-eabihf \
    --features "panic-proof life i16-stream fast-math" -- -D warnings)
fi

step "fuzz every reader and the frame decoder (libFuzzer, ${WEARSIM_FUZZ_SECONDS:-15} s each)"
bash scripts/fuzz.sh --build-only
# The firmware images of the QEMU tests (fat LTO, mostly one core) build in the background
# while the fuzzers and the Python tests, one process each, leave a core free;
# firmware_qemu.rs then finds them built (or waits for the build's lock).
mkdir -p firmware-stub/target
bash scripts/prebuild-firmware.sh > firmware-stub/target/prebuild.log 2>&1 &
prebuild=$!
bash scripts/fuzz.sh "${WEARSIM_FUZZ_SECONDS:-15}"

step "Python package: pytest (Dask 2-worker sweep, SIGKILL resume) and the worked example's tiny version"
python3 -m pytest -q python/tests
example_out="$(mktemp -d)"
python3 python/examples/cwru_transfer.py --tiny --out "$example_out/set"
rm -rf "$example_out"

step "all tests"
cargo test --workspace
if ! wait "$prebuild"; then
  # Not a failure by itself: the QEMU tests built the firmware again and passed.
  echo "note: the background firmware build failed; its log:"
  tail -20 firmware-stub/target/prebuild.log
fi
step "done"
