#!/usr/bin/env bash
# The virtual board's GPIO and camera drivers work as later tests need them:
# gpio-sim's chip "vboard-gpio" has 16 named lines whose inputs follow the
# simulated pull (as a button would), vivid captures frames of the size it reports, and vimc
# shows up as a media device.
set -euo pipefail
vboard=${CANDELA_VBOARD:-$(dirname "$0")/../../board/virtual/run-in-vm.sh}

log=$("$vboard" --timeout 300 '
  gpiodetect
  gpioinfo vboard-gpio | grep -c "\"sim[0-9]*\"" | sed "s/^/named-lines=/"
  sim=/sys/devices/platform/gpio-sim.0/gpiochip0/sim_gpio5
  echo pull-up >$sim/pull;   echo "line5-up=$(gpioget vboard-gpio 5)"
  echo pull-down >$sim/pull; echo "line5-down=$(gpioget vboard-gpio 5)"
  v4l2-ctl -d /dev/video0 --info | grep "Driver name"
  size=$(v4l2-ctl -d /dev/video0 --get-fmt-video | sed -n "s/.*Size Image *: //p")
  v4l2-ctl -d /dev/video0 --stream-mmap --stream-count=3 --stream-to=$VBOARD_OUT/frames.raw
  echo "sizeimage=$size captured=$(stat -c %s $VBOARD_OUT/frames.raw)"
  for m in /dev/media*; do media-ctl -d $m -p | sed -n "s/^driver  *//p"; done
' 2>&1) || {
  echo "$log"
  echo "FAIL: the virtual board run failed"
  exit 1
}
fail() {
  echo "$log"
  echo "FAIL: $*"
  exit 1
}
expect() { grep -Eq -- "$1" <<<"$log" || fail "$2 (no line matching: $1)"; }

expect '^gpiochip[0-9]+ \[vboard-gpio\] \(16 lines\)$' "gpio-sim chip vboard-gpio with 16 lines missing"
expect '^named-lines=16$' "gpio-sim lines are not named sim0..sim15"
expect '^line5-up=1$' "a pulled-up simulated input does not read 1"
expect '^line5-down=0$' "a pulled-down simulated input does not read 0"
expect 'Driver name *: vivid' "/dev/video0 is not vivid"
sizes=$(sed -n 's/^sizeimage=\([0-9]*\) captured=\([0-9]*\)$/\1 \2/p' <<<"$log")
read -r size captured <<<"$sizes" || fail "no capture result"
[ "${size:-0}" -gt 0 ] && [ "$captured" -eq $((3 * size)) ] ||
  fail "vivid captured $captured bytes, expected 3 frames of $size"
expect '^vimc$' "no vimc media device"
echo "PASS: gpio-sim (16 named lines, pulls), vivid ($size bytes/frame), vimc"
