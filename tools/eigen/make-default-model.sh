#!/bin/sh
# Builds the runtime's built-in eigen-flame model, firmware/models/default.cmodel,
# from data the project makes itself: three 2-D fluid simulations of a candle
# flame (calm, a steady breeze to the right, one to the left), ingested and
# built with candela-tool. No recorded footage is used. Seeds are fixed, so
# the same tools give the same model.
#
#   tools/eigen/make-default-model.sh [CANDELA_TOOL] [OUT]
#   (defaults: build/tools/candela-tool/candela-tool, firmware/models/default.cmodel)
set -eu
here=$(cd "$(dirname "$0")/../.." && pwd)
tool=${1:-$here/build/tools/candela-tool/candela-tool}
out=${2:-$here/firmware/models/default.cmodel}
[ -x "$tool" ] || { echo "make-default-model: no candela-tool at $tool (build it first)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Clips: 30 fps, 96x160-cell candle preset. Wind in cells/s (+ = to the right).
"$tool" simulate -q --preset candle --no-fields --seed 11 --frames 300 --wind none --name calm --out "$work/calm"
"$tool" simulate -q --preset candle --no-fields --seed 12 --frames 150 --wind 0:10 --name breeze-right --out "$work/breeze-right"
"$tool" simulate -q --preset candle --no-fields --seed 13 --frames 150 --wind 0:-10 --name breeze-left --out "$work/breeze-left"

"$tool" ingest "$work/calm" "$work/breeze-right" "$work/breeze-left" --out "$work/dataset" \
  --width 64 --height 96 \
  --label calm:0-300:calm --label breeze-right:0-150:wind-right --label breeze-left:0-150:wind-left

# 64 EigenFires (scenes choose how many to use), 8-bit images: about 0.6 MB.
"$tool" build "$work/dataset" --out "$out" --components 64 --bits 8 --holdout 0 --report "$work/report" --hue 28 --saturation 0.9
ls -l "$out"
