#!/usr/bin/env bash
# contact-sheet.sh [OUT.png]: one picture for people. Renders each built-in
# flame with the eval scenes (../shared/eval/scenes: one flame, close, on black;
# the eigen-flames with tests/realism/scenes/, which frame the whole model image;
# 256x256, $FRAMES frames at 60 fps, the seeds of ../shared/eval/README.md) and
# puts, one row per scene, four of its frames (1, 4, 7 and 10 s in) beside the
# first frames of the real clips of its kind (candles for the candle scenes,
# real-speed fires, in colour, for the eigen and Perlin fires). Needs ImageMagick
# (montage). Default OUT: build/realism/contact-sheet.png. RENDERS=DIR keeps the
# rendered frames there (DIR/a_candle_calm/ ...), e.g. to measure them afterwards.
set -u
. "$(dirname "$0")/common.sh"
need_shared
command -v montage >/dev/null || { echo "needs ImageMagick's montage (apt-get install imagemagick)" >&2; exit 2; }
out_png=${1:-$build/realism/contact-sheet.png}
mkdir -p "$(dirname "$out_png")"
if [ -n "${RENDERS:-}" ]; then
  work=$RENDERS
  mkdir -p "$work"
else
  work=$(mktemp -d "${TMPDIR:-/tmp}/candela-sheet.XXXXXX")
  trap 'rm -rf "$work"' EXIT
fi

candles="candle_schodl_singan candle_red_ngasocute candle_breeze_tfg_flameshaken candle_triplet_oscillating_cpldcpu"
fires="campfire_night_arvideo fireplace_logs_grpatter fireplace_logs_meditation"
# scene seed kind
rows="a_candle_calm 1 candle
b_candle_breeze 1 candle
$here/scenes/eigen_candle.toml 5 candle
$here/scenes/eigen_fire.toml 5 fire
e_perlinfire 3 fire"

tiles=()
while read -r name seed kind; do
  scene=$(scene_file "$name") || exit 2
  name=$(basename "$name" .toml)
  echo "rendering $name (seed $seed, $frames frames)" >&2
  render "$scene" "$seed" "$work/$name"
  shots=$(ls "$work/$name" | grep -i '\.png$' | sort)
  count=$(echo "$shots" | wc -l)
  for sec in 1 4 7 10; do
    i=$((sec * 60))
    [ "$i" -gt "$count" ] && i=$count
    f=$(echo "$shots" | sed -n "${i}p")
    tiles+=(-label "$name ${sec}s" "$work/$name/$f")
  done
  clips=$candles
  [ "$kind" = fire ] && clips=$fires
  n=0
  for c in $clips; do
    [ $n -ge 3 ] && break
    f="$flames/$c/frames_rgb/00001.png"
    [ -f "$f" ] || f="$flames/$c/frames/00001.png"
    [ -f "$f" ] || continue
    tiles+=(-label "real: $c" "$f")
    n=$((n + 1))
  done
  while [ $n -lt 3 ]; do tiles+=(-label "" "xc:black"); n=$((n + 1)); done
done <<<"$rows"

montage -background '#202020' -fill white -pointsize 11 "${tiles[@]}" \
  -tile 7x -geometry 192x192+4+4 "$out_png"
echo "$out_png: rows = candle calm, candle breeze, eigen candle, eigen fire (built-in models), Perlin fire;" \
  "columns: 4 rendered frames (1, 4, 7, 10 s), then first frames of real clips of the kind"
