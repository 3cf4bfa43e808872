#!/usr/bin/env bash
# The real-time run (issue 15): a scene on the virtual board's DRM display
# (vkms) at 1280x720 on the wall clock for MINUTES (default 60), as the kiosk
# runs it, with the resident set size sampled once a minute. A benchmark
# script, not a ctest: the VM is emulated (TCG), so frames are few a second
# and the figures that matter are memory and survival, not frame rate.
# Prints one line a minute and a verdict:
#   minute  rss_mb  frame (the kiosk's state: frames drawn so far)
#   rss first/last/max after the first minute; PASS when the last is within
#   --rss-mb (default 1) of the first and candela was still running.
#   tests/bench/vboard_realtime.sh [--build build] [--minutes 60] [--rss-mb 1] [--scene FILE]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=build minutes=60 rss_mb=1 scene=firmware/scenes/default.toml
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$2; shift 2 ;;
    --minutes) minutes=$2; shift 2 ;;
    --rss-mb) rss_mb=$2; shift 2 ;;
    --scene) scene=$2; shift 2 ;;
    *) echo "usage: $0 [--build DIR] [--minutes N] [--rss-mb MB] [--scene FILE]" >&2; exit 2 ;;
  esac
done
candela=$PWD/$build/firmware/candela
[ -x "$candela" ] || { echo "vboard_realtime: no $candela (build first)" >&2; exit 2; }
scene=$(realpath "$scene")
vboard=board/virtual/run-in-vm.sh
out=$(mktemp -d "${TMPDIR:-/tmp}/candela-realtime.XXXXXX")
trap 'rm -rf "$out"' EXIT

# Inside the VM: candela on the DRM display, its state asked over the
# control socket and its RSS read from /proc once a minute.
"$vboard" --timeout $((minutes * 60 + 300)) --out "$out" "
  sock=/tmp/candela.sock
  # A crash leaves its core in the output folder, and its stacks in the log.
  ulimit -c unlimited; echo \$VBOARD_OUT/core > /proc/sys/kernel/core_pattern
  env HOME=/tmp XDG_CACHE_HOME=/tmp $candela --display drm --size 1280x720 --mute \
    --scene $scene --control \$sock >/tmp/candela.log 2>&1 &
  pid=\$!
  for m in \$(seq 1 $minutes); do
    sleep 60
    if ! kill -0 \$pid 2>/dev/null; then echo \"minute \$m: candela exited\"; break; fi
    rss=\$(awk '/^VmRSS/ {print \$2}' /proc/\$pid/status)
    frames=\$(/usr/bin/python3 -c \"import json, socket; s = socket.socket(socket.AF_UNIX); s.settimeout(5); s.connect('\$sock'); s.sendall(b'state\\\\n'); print(json.loads(s.makefile().readline()).get('frame', '?'))\" 2>/dev/null)
    echo \"sample \$m \$rss \${frames:-?}\"
  done
  alive=0; kill -0 \$pid 2>/dev/null && alive=1
  kill -TERM \$pid 2>/dev/null; wait \$pid; echo \"exit \$? alive \$alive\"
  tail -5 /tmp/candela.log
  for c in \$VBOARD_OUT/core*; do
    [ -f \"\$c\" ] && gdb -q -batch -ex 'thread apply all bt 12' $candela \"\$c\" 2>&1 | grep -v '^\\[New LWP' | tail -80
  done
  true
" | tee "$out/log.txt"

/usr/bin/python3 - "$out/log.txt" "$rss_mb" <<'PY'
import sys
rows, alive = [], False
for line in open(sys.argv[1]):
    f = line.split()
    if f[:1] == ["sample"]:
        rows.append((int(f[1]), int(f[2]) / 1024.0, f[3]))
    if f[:1] == ["exit"]:
        alive = f[3] == "1"
for m, rss, frames in rows:
    print(f"minute {m:3d}  rss {rss:7.1f} MB  frames {frames}")
if len(rows) < 2:
    print("FAIL: fewer than two samples"); sys.exit(1)
after = [r[1] for r in rows[1:]]
first, last, peak = after[0], after[-1], max(after)
ok = alive and abs(last - first) <= float(sys.argv[2])
print(f"rss after the first minute: first {first:.1f} MB, last {last:.1f} MB, max {peak:.1f} MB; "
      f"{'still running' if alive else 'NOT running'} after {rows[-1][0]} min: {'PASS' if ok else 'FAIL'}")
sys.exit(0 if ok else 1)
PY
