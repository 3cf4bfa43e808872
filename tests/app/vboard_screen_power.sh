#!/usr/bin/env bash
# `screen off|on` on the virtual board's vkms display (issue 16): the
# atomic path makes the CRTC inactive (the connector's DPMS then reads Off)
# and the frame counter stops; `screen on` sets the mode again (DPMS On) and
# frames resume. The legacy path switches the connector's DPMS property.
# HDMI-CEC: libcec finds vivid's emulated adapter (or says once that there
# is none) and DPMS works beside it. candela exits 0 and restores the console's CRTC either way.
#   vboard_screen_power.sh CANDELA
set -euo pipefail
candela=$1
here=$(cd "$(dirname "$0")" && pwd)
vboard=${CANDELA_VBOARD:-$here/../../board/virtual/run-in-vm.sh}

log=$("$vboard" --timeout 550 "/usr/bin/python3 $here/vboard_screen_power_guest.py $candela" 2>&1) || {
  echo "$log"
  echo "FAIL: the virtual board run failed"
  exit 1
}
failed=0
section() { sed -n "/^=== $1\$/,/^=== /p" <<<"$log"; }
check() {  # check SECTION REGEX WHAT
  if ! section "$1" | grep -Eq -- "$2"; then
    echo "FAIL ($1): $3 (no line matching: $2)"
    failed=1
  fi
}
for kind in atomic legacy; do
  check $kind '^on-before: dpms=0$' "not on at first"
  check $kind '^reply-off: ok$' "screen off not answered ok"
  check $kind '^reply-on: ok$' "screen on not answered ok"
  check $kind '^on-after: dpms=0 ' "not on again after screen on"
  check $kind '^off: dpms=3$' "the screen did not go off (DPMS Off)"
  check $kind 'drm: screen off' "candela did not log the screen off"
  check $kind 'drm: screen on' "candela did not log the screen on"
  check $kind '^candela-exit=0$' "candela did not exit 0"
  check $kind 'drm: restored CRTC' "the console's CRTC was not restored"
  # vivid's emulated CEC adapters (/dev/cec*) are found through libcec (no
  # TV answers on their bus: a warning per switch); without them, the
  # absence is said once. Either way, once, and DPMS did its part above.
  n=$(section $kind | grep -cE 'cec: (switching the TV through|no CEC adapter|libcec|built without)' || true)
  if [ "$n" != 1 ]; then
    echo "FAIL ($kind): what became of HDMI-CEC was said $n times, not once"
    failed=1
  fi
  read -r f1 f2 < <(section $kind | sed -n 's/^off-frames: //p')
  if [ -z "${f1:-}" ] || [ $((f2 - f1)) -gt 1 ]; then
    echo "FAIL ($kind): frames went on with the screen off (${f1:-?} -> ${f2:-?})"
    failed=1
  fi
done
check atomic 'drm: screen off \(CRTC ACTIVE\)' "the atomic path did not switch the CRTC"
check legacy 'drm: screen off \(connector DPMS\)' "the legacy path did not switch DPMS"
echo "$log" | grep -E '^===|^on-|^off|^reply|drm: screen|cec: |^candela-exit'
if [ $failed -ne 0 ]; then
  echo "--- full log"
  echo "$log"
  exit 1
fi
echo "PASS: screen off/on on vkms (atomic: CRTC inactive/active; legacy: DPMS Off/On), frames stopped while off"
