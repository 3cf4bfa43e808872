#!/usr/bin/env bash
# Runs `candela --display drm --test-pattern` on the virtual board's vkms
# display as an unprivileged user in the video (and render) group -- first
# with atomic modesetting for FRAMES frames, then forced onto the legacy
# path for a few -- and checks from its log that each run picked card0,
# connector Virtual-1 and the asked mode, modeset, flipped every frame, exited
# 0 and put the CRTC back the way it found it (the console's 1024x768
# framebuffer, also compared with modetest before and after). One VM boot for
# both, to keep the test short.
#   drm_test_pattern.sh CANDELA FRAMES
set -euo pipefail
candela=$1 frames=$2
legacy_frames=10
vboard=${CANDELA_VBOARD:-$(dirname "$0")/../../board/virtual/run-in-vm.sh}

# Under TCG llvmpipe draws a few frames a second: 640x480 keeps it short.
log=$("$vboard" --timeout 500 "
  crtcs() { modetest -M vkms -p 2>&1 | grep -E '^[0-9]+\s+[0-9]+\s+\([0-9]+,[0-9]+\)\s+\(' | sed \"s/^/crtc-\$1: /\"; }
  groups=video; getent group render >/dev/null && groups=video,render
  show() {  # show KIND LEGACY FRAMES
    echo \"=== \$1\"
    crtcs before
    env HOME=/tmp XDG_CACHE_HOME=/tmp CANDELA_DRM_LEGACY=\$2 \
      setpriv --reuid=65534 --regid=65534 --groups=\$groups --inh-caps=-all \
      $candela --display drm --test-pattern --frames \$3 --size 640x480 --bench 2>&1
    echo \"candela-exit=\$?\"
    crtcs after
  }
  show atomic 0 $frames
  show legacy 1 $legacy_frames
  echo '=== missing'
  $candela --display drm --drm-device /dev/dri/card7 --frames 1 2>&1
  echo \"candela-exit=\$?\"
" 2>&1) || {
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
check_run() {  # check_run KIND FRAMES
  local kind=$1 n=$2
  check "$kind" '^candela-exit=0$' "candela did not exit 0"
  check "$kind" 'drm: /dev/dri/card0 \(vkms\), connector Virtual-1, mode 640x480@60, .*'"$kind"'$' \
    "not card0 / connector Virtual-1 / mode 640x480@60 / $kind"
  check "$kind" "drm: $kind modeset 640x480@60 on Virtual-1 done" "no $kind modeset"
  check "$kind" "drm: presented $n frames \\(1 modeset \\+ $((n - 1)) page flips completed\\)" \
    "not every frame was flipped"
  check "$kind" "\"display\":\"drm\",\"width\":640,\"height\":480,\"frames\":$n," "bench line wrong"
  check "$kind" '"missed_vblanks":[0-9]+,' "missed vblanks not counted"
  check "$kind" 'drm: restored CRTC [0-9]+ to its previous state \(1024x768@60 \(preferred\), framebuffer [0-9]+\)' \
    "the console's CRTC state was not restored"
  local before after
  before=$(section "$kind" | sed -n 's/^crtc-before: //p')
  after=$(section "$kind" | sed -n 's/^crtc-after: //p')
  if [ -z "$before" ] || [ "$before" != "$after" ]; then
    echo "FAIL ($kind): CRTC before '$before', after '$after'"
    failed=1
  fi
}
check_run atomic "$frames"
if section atomic | grep -q 'falling back to legacy'; then
  echo "FAIL (atomic): atomic fell back to legacy"
  failed=1
fi
check legacy 'drm: CANDELA_DRM_LEGACY set: using legacy modesetting' "legacy path not taken"
check_run legacy "$legacy_frames"
check missing '^candela-exit=1$' "a missing --drm-device did not fail"
check missing '/dev/dri/card7: No such file or directory' "the error does not name the missing device"

echo "$log" | grep -E '^===|drm:|"bench"|^crtc-'
if [ $failed -ne 0 ]; then
  echo "--- full log"
  echo "$log"
  exit 1
fi
echo "PASS: atomic ($frames frames) and legacy ($legacy_frames frames) on vkms, CRTC restored"
