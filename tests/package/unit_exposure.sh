#!/usr/bin/env bash
# The kiosk unit's exposure, as systemd scores it (issue 15: at most 3.0):
# `systemd-analyze security --offline=yes` reads the file itself, no systemd
# needs to run. --threshold is in tenths. Also: the settings the kiosk cannot
# work without are still there (a score can be bought by locking it out).
set -euo pipefail
unit=${1:?usage: unit_exposure.sh UNIT}
out=$(systemd-analyze security --offline=yes --threshold=30 "$unit" 2>&1) || {
  echo "$out" | tail -25
  echo "unit_exposure: $unit: exposure above 3.0 (or systemd-analyze failed)" >&2
  exit 1
}
line=$(grep -o 'Overall exposure level for [^:]*: [0-9.]*' <<<"$out") ||
  { echo "unit_exposure: no overall exposure line in systemd-analyze's output" >&2; exit 1; }
echo "$line"
for need in 'DeviceAllow=char-drm rw' 'DeviceAllow=char-gpiochip rw' 'DeviceAllow=char-video4linux rw' \
  'DeviceAllow=char-input rw' 'RuntimeDirectory=candela' 'User=candela' 'Type=notify' \
  'ExecStart=/usr/bin/candela --config /etc/candela/candela.toml $CANDELA_ARGS'; do
  grep -qxF "$need" "$unit" || { echo "unit_exposure: $unit lacks '$need'" >&2; exit 1; }
done
# llvmpipe and GPU drivers JIT shaders into W+X memory.
if grep -q '^MemoryDenyWriteExecute=yes' "$unit"; then
  echo "unit_exposure: MemoryDenyWriteExecute=yes breaks Mesa's shader JIT" >&2; exit 1
fi
