#!/usr/bin/env bash
# Runs `candela --display drm --test-pattern` on the virtual board's vkms
# display as an unprivileged user in the video (and render) group, and checks
# from its log that it picked card0/Virtual-1 and a mode, modeset (atomic or
# legacy as asked), flipped every frame, exited 0 and put the CRTC back the
# way it found it (the console's 1024x768 framebuffer, seen with modetest).
#   drm_test_pattern.sh CANDELA atomic|legacy FRAMES
set -euo pipefail
candela=$1 kind=$2 frames=$3
vboard=${CANDELA_VBOARD:-$(dirname "$0")/../../board/virtual/run-in-vm.sh}
legacy=0
[ "$kind" = legacy ] && legacy=1

# Under TCG llvmpipe draws a few frames a second: 640x480 keeps the test short.
log=$("$vboard" --timeout 500 "
  crtcs() { modetest -M vkms -p 2>&1 | grep -E '^[0-9]+\s+[0-9]+\s+\([0-9]+,[0-9]+\)\s+\(' | sed 's/^/crtc: /'; }
  echo before; crtcs
  groups=video; getent group render >/dev/null && groups=video,render
  env HOME=/tmp XDG_CACHE_HOME=/tmp CANDELA_DRM_LEGACY=$legacy \
    setpriv --reuid=65534 --regid=65534 --groups=\$groups --inh-caps=-all \
    $candela --display drm --test-pattern --frames $frames --size 640x480 --bench 2>&1
  echo \"candela-exit=\$?\"
  echo after; crtcs
  # A device that is not there is named in the error.
  env CANDELA_DRM_LEGACY=$legacy $candela --display drm --drm-device /dev/dri/card7 --frames 1 2>&1
  echo \"missing-exit=\$?\"
" 2>&1) || {
  echo "$log"
  echo "FAIL: the virtual board run failed (exit $?)"
  exit 1
}

fail() {
  echo "$log"
  echo "FAIL: $*"
  exit 1
}
expect() { grep -Eq -- "$1" <<<"$log" || fail "$2 (no line matching: $1)"; }

expect '^candela-exit=0$' "candela did not exit 0"
expect 'drm: /dev/dri/card0 \(vkms\), connector Virtual-1, mode 640x480@60,' \
  "candela did not choose card0, connector Virtual-1, mode 640x480@60"
if [ $legacy -eq 1 ]; then
  expect 'drm: CANDELA_DRM_LEGACY set: using legacy modesetting' "legacy path not taken"
  expect 'drm: legacy modeset 640x480@60 on Virtual-1 done' "no legacy modeset"
else
  expect 'drm: .*, atomic$' "atomic modesetting not chosen"
  expect 'drm: atomic modeset 640x480@60 on Virtual-1 done' "no atomic modeset"
  if grep -q 'falling back to legacy' <<<"$log"; then fail "atomic fell back to legacy"; fi
fi
expect "drm: presented $frames frames \\(1 modeset \\+ $((frames - 1)) page flips completed\\)" \
  "not every frame was flipped"
expect "\"display\":\"drm\",\"width\":640,\"height\":480,\"frames\":$frames," "bench line wrong"
expect '"missed_vblanks":[0-9]+,' "missed vblanks not counted"
expect 'drm: restored CRTC [0-9]+ to its previous state \(1024x768@60 \(preferred\), framebuffer [0-9]+\)' \
  "the console's CRTC state was not restored"
before=$(sed -n '/^before$/,/^after$/s/^crtc: //p' <<<"$log")
after=$(sed -n '/^after$/,$s/^crtc: //p' <<<"$log")
[ -n "$before" ] || fail "modetest showed no CRTC before the run"
[ "$before" = "$after" ] || fail "CRTC differs after the run: before '$before', after '$after'"
expect '^missing-exit=1$' "a missing --drm-device did not fail"
expect '/dev/dri/card7: No such file or directory' "the error does not name the missing device"
echo "$log" | grep -E 'drm:|"bench"|^crtc: '
echo "PASS: $kind, $frames frames flipped on vkms, CRTC restored"
