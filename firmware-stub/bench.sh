#!/usr/bin/env bash
# Budget of the wearsim firmware, measured deterministically in QEMU.
#
#   firmware-stub/bench.sh [--json]
#
# Builds the M4F (thumbv7em-none-eabihf, mps2-an386) and M3 (thumbv7m-none-eabi, mps2-an385)
# firmwares and fwtool, runs both under `-icount shift=0,sleep=off` (one guest instruction per
# nanosecond of virtual time, so the 25 MHz TIMER1 advances once per 40 instructions), and
# reads the instructions per output sample of the firmware's timed loop (1000 samples of the
# reference scenario through model, wire conversion, framing and CRC) from the end frame of
# the stream. RAM (data + bss) and flash (text + rodata + data image) are those of the M4F ELF.
# Needs: qemu-system-arm, rustup targets thumbv7em-none-eabihf and thumbv7m-none-eabi.
set -euo pipefail
cd "$(dirname "$0")"
json=0
[[ "${1:-}" == "--json" ]] && json=1
unset RUSTFLAGS CARGO_ENCODED_RUSTFLAGS
export CARGO_TARGET_DIR="$PWD/target"
host=$(rustc -vV | sed -n 's/^host: //p')
log=$(mktemp -d)
trap 'rm -rf "$log"' EXIT
cargo build -q --release -p wearsim-fw --target thumbv7em-none-eabihf --target thumbv7m-none-eabi >&2
cargo build -q --profile host -p wearsim-fwtool --target "$host" >&2
fwtool="$CARGO_TARGET_DIR/$host/host/fwtool"
run() { # machine elf serial-out
  timeout 600 qemu-system-arm -M "$1" -display none -monitor none -icount shift=0,sleep=off \
    -kernel "$2" -semihosting-config enable=on,target=native -serial "file:$3" >"$3.defmt"
}
m4=target/thumbv7em-none-eabihf/release/wearsim-fw
m3=target/thumbv7m-none-eabi/release/wearsim-fw
run mps2-an386 "$m4" "$log/m4.bin"
run mps2-an385 "$m3" "$log/m3.bin"
ips() { "$fwtool" budget "$1" | sed -n 's/.*"instructions_per_sample":\([0-9.e+-]*\).*/\1/p'; }
i4=$(ips "$log/m4.bin")
i3=$(ips "$log/m3.bin")
size=$("$fwtool" size "$m4" --json)
ram=$(sed -n 's/.*"ram_bytes":\([0-9]*\).*/\1/p' <<<"$size")
flash=$(sed -n 's/.*"flash_bytes":\([0-9]*\).*/\1/p' <<<"$size")
if [[ $json == 1 ]]; then
  printf '{"instructions_per_sample_m4f":%.1f,"instructions_per_sample_m3":%.1f,"ram_bytes":%d,"flash_bytes":%d}\n' \
    "$i4" "$i3" "$ram" "$flash"
else
  printf 'instructions/sample: M4F %.0f (target <= 4000), M3 %.0f\n' "$i4" "$i3"
  printf 'M4F static RAM %d bytes (limit 32768), flash %d bytes (limit 131072)\n' "$ram" "$flash"
fi
