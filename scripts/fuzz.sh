#!/usr/bin/env bash
# Runs every libFuzzer target of host-sim/fuzz for SECONDS each (default 30), after
# generating the seed corpus. Installs cargo-fuzz if it is missing. Uses the nightly
# toolchain when installed; otherwise stable with RUSTC_BOOTSTRAP=1 (cargo-fuzz's flags
# need nightly features; the sanitizer is then switched off, coverage still works).
# Exit status: non-zero if any target found a crash (the reproducer is in
# host-sim/fuzz/artifacts/<target>/).
# `fuzz.sh --build-only` builds the targets and stops (CI builds first, then starts other
# work in the background while the single-process fuzzers run).
set -euo pipefail
BUILD_ONLY=0
if [ "${1:-}" = "--build-only" ]; then
    BUILD_ONLY=1
    shift
fi
SECONDS_PER_TARGET="${1:-30}"
cd "$(dirname "$0")/../host-sim/fuzz"

if ! cargo fuzz --version >/dev/null 2>&1; then
    cargo install cargo-fuzz --locked
fi
if rustup toolchain list | grep -q '^nightly'; then
    TOOLCHAIN=(+nightly)
    SAN=()
else
    export RUSTC_BOOTSTRAP=1
    TOOLCHAIN=()
    SAN=(--sanitizer none)
fi

python3 make_corpus.py
TARGETS=(mat wav npy csv ims_snapshot ims_features feature_table sidecar frame)
cargo "${TOOLCHAIN[@]}" fuzz build "${SAN[@]}" -O --debug-assertions
if [ "$BUILD_ONLY" = 1 ]; then
    exit 0
fi
# The file-reader targets write each input to a scratch directory under the temporary
# directory, and libFuzzer exits without running destructors: give them one of their own,
# removed when this script ends (each run left a `wearsim-fuzz-PID` per target in /tmp).
SCRATCH="$(mktemp -d)"
trap 'rm -rf "$SCRATCH"' EXIT
export TMPDIR="$SCRATCH"
status=0
for t in "${TARGETS[@]}"; do
    mkdir -p "corpus/$t"
    echo "== $t: ${SECONDS_PER_TARGET} s"
    if ! cargo "${TOOLCHAIN[@]}" fuzz run "${SAN[@]}" -O --debug-assertions "$t" "corpus/$t" -- \
        -max_total_time="$SECONDS_PER_TARGET" -rss_limit_mb=1024 -malloc_limit_mb=1024 \
        -timeout=10 -print_final_stats=1 2>&1 | tee "fuzz-$t.log" | grep -E 'stat::number_of_executed_units|SUMMARY|ERROR|#[0-9]+ +DONE'; then
        :
    fi
    if grep -q -E '^==[0-9]+== ERROR|SUMMARY: libFuzzer|deadly signal|panicked' "fuzz-$t.log"; then
        echo "!! $t found a failure; see fuzz-$t.log and artifacts/$t/"
        status=1
    fi
done
exit $status
