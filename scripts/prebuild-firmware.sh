#!/usr/bin/env bash
# Builds, ahead of `cargo test`, the firmware images and host tools that
# host-sim/tests/integration/firmware_qemu.rs builds — the same commands into the same target
# directories — so that CI can run these mostly single-threaded builds (fat LTO, one
# codegen unit) while other steps leave a core idle. The test's own `cargo build` calls
# then find them up to date; if this script fails, the test builds again and reports the
# error itself. Output goes to firmware-stub/target/prebuild.log.
set -euo pipefail
cd "$(dirname "$0")/../firmware-stub"
unset RUSTFLAGS CARGO_ENCODED_RUSTFLAGS CARGO_BUILD_TARGET
export CARGO_TARGET_DIR="$PWD/target"
host=$(rustc -vV | sed -n 's/^host: //p')
# (target, features) as the test's `firmware(target, features)` calls.
for spec in "thumbv7em-none-eabihf:" "thumbv7m-none-eabi:" \
            "thumbv7m-none-eabi:i16-stream" "thumbv7em-none-eabihf:life"; do
  t=${spec%%:*}
  f=${spec#*:}
  if [ -z "$f" ]; then dir="$PWD/target"; else dir="$PWD/target/${f//,/-}"; fi
  args=(build --release -p wearsim-fw --target "$t" --target-dir "$dir")
  if [ -n "$f" ]; then args+=(--features "$f"); fi
  cargo "${args[@]}"
done
cargo build --profile host -p wearsim-fwtool --target "$host"
cargo test --no-run --profile host -p wearsim-frame -p wearsim-vsensor --target "$host"
