#!/usr/bin/env bash
# No visible loop: renders a built-in scene for MINUTES of animation time
# (default 10; $REPEAT_MINUTES) headless at 64x36 and 15 fps -- the whole
# picture, small, since a repeat shows at any size -- and fails when
# `candela-tool measure repeats` finds a stretch longer than 2 s that matches
# an earlier one (frames whose mean difference is under a fifth of the median
# step between consecutive frames, as ../shared/eval/realism.py repeats).
#   tests/realism/no-repeats.sh SCENE.toml [SEED]
# Exit: 0 no repeat over 2 s, 1 a longer repeat, 2 the render or measure failed.
set -euo pipefail
. "$(dirname "$0")/common.sh"
scene=${1:?usage: no-repeats.sh SCENE.toml [SEED]}
seed=${2:-1}
minutes=${REPEAT_MINUTES:-10}
fps=15
limit_s=2
frames=$((minutes * 60 * fps))
need_tools
work=$(mktemp -d "${TMPDIR:-/tmp}/candela-repeats.XXXXXX")
trap 'rm -rf "$work"' EXIT
if ! "$candela" --display headless --size 64x36 --fps "$fps" --frames "$frames" --seed "$seed" --mute \
    --scene "$scene" --out "$work/frames/" >"$work/render.log" 2>&1; then
  echo "rendering $scene failed:" >&2
  tail -5 "$work/render.log" >&2
  exit 2
fi
out=$("$tool" measure repeats "$work/frames" --fps "$fps" --max-frames "$frames") || {
  echo "measure repeats failed: $out" >&2; exit 2; }
# "DIR: longest repeated stretch S s"
s=$(sed -n 's/.*longest repeated stretch \([0-9.]*\) s.*/\1/p' <<<"$out")
[ -n "$s" ] || { echo "unexpected output from measure repeats: $out" >&2; exit 2; }
echo "$(basename "$scene") seed $seed: longest repeated stretch $s s in $minutes min (limit $limit_s s)"
awk -v s="$s" -v l="$limit_s" 'BEGIN { exit !(s <= l) }' || exit 1
