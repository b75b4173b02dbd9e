#!/usr/bin/env bash
# Installs what wearsim's builds and tests need on a fresh machine (idempotent):
# Rust components and cross targets, and the Debian packages for QEMU and plot fonts.
set -euo pipefail

log() { printf '[setup] %s\n' "$*" >&2; }

command -v cargo >/dev/null || { log "cargo not found: install Rust with rustup first"; exit 1; }

if command -v rustup >/dev/null; then
  installed=$(rustup component list --installed 2>/dev/null || true)
  for c in rustfmt clippy; do
    grep -q "^$c" <<<"$installed" || { log "rustup component add $c"; rustup component add "$c"; }
  done
  targets=$(rustup target list --installed 2>/dev/null || true)
  for t in thumbv6m-none-eabi thumbv7m-none-eabi thumbv7em-none-eabihf; do
    grep -qx "$t" <<<"$targets" || { log "rustup target add $t"; rustup target add "$t"; }
  done
else
  log "rustup not found: the thumb targets must already be installed"
fi

# Debian packages: QEMU for the firmware tests, DejaVu fonts for plot text.
need=()
command -v qemu-system-arm >/dev/null || need+=(qemu-system-arm)
[ -f /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf ] || need+=(fonts-dejavu-core)
if [ ${#need[@]} -gt 0 ]; then
  if command -v apt-get >/dev/null; then
    SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
    log "apt-get install ${need[*]}"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need[@]}" >/dev/null
  else
    log "apt-get not available; please install: ${need[*]}"
  fi
fi

# The Python package (python/, docs/python.md): its build and test dependencies, then the
# extension itself (maturin, cargo profile `pyext`, sharing ./target). WEARSIM_SKIP_PYTHON=1
# skips it.
if [ "${WEARSIM_SKIP_PYTHON:-0}" != 1 ] && command -v python3 >/dev/null; then
  log "pip install the wearsim Python package and its test dependencies"
  python3 -m pip install -q --disable-pip-version-check "maturin>=1.5,<2" numpy pyarrow pandas pytest "dask[distributed]"
  python3 -m pip install -q --disable-pip-version-check --no-build-isolation "$(dirname "$0")/../python"
fi
