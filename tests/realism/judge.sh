#!/usr/bin/env bash
# judge.sh SCENE SEED KIND [MEASURE OPTIONS...]
# Renders SCENE (a file, or an eval scene: a_candle_calm, b_candle_breeze,
# c_eigen_graph, d_eigen_arp, e_perlinfire, or its letter) headless, 256x256,
# $FRAMES frames (600 = 10 s at 60 fps), and prints
# `candela-tool measure FRAMES --fps 60 --against KIND` (KIND: candle, fire or a
# REFS file); extra options go to measure (e.g. --features spat_slope --json).
# Exit status: measure's (0 inside, 1 outside, 2 bad input); 77 if the shared
# scenes or clips are not here. CANDELA_BUILD_DIR (default build/) says where
# candela and candela-tool are.
set -u
if [ $# -lt 3 ]; then
  sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
. "$(dirname "$0")/common.sh"
need_shared
scene=$(scene_file "$1") || exit 2
seed=$2 kind=$3
shift 3
out=$(mktemp -d "${TMPDIR:-/tmp}/candela-judge.XXXXXX")
trap 'rm -rf "$out"' EXIT
render "$scene" "$seed" "$out/frames"
echo "$(basename "$scene") seed $seed, $frames frames at 60 fps:"
"$tool" measure "$out/frames" --fps 60 --against "$kind" --flames "$flames" "$@"
