#!/bin/sh
# Makes the project's own flame data from scratch (no real footage involved):
#   1. simulates a candle-like and a fireplace-like flame (candela-tool simulate),
#   2. renders a procedural flame photograph for each (candela-tool flame-photo),
#   3. puts the photo's detail on each simulation (candela-tool texturize),
#   4. if this candela-tool has `ingest` and `build` (the model builder),
#      ingests the texturised clips and builds the default eigen-flame models.
# Usage: tools/fluid/make-default-data.sh [OUT_DIR]   (default: ./default-data)
# CANDELA_TOOL may name the candela-tool binary (default: build/tools/candela-tool/
# candela-tool if it exists, else candela-tool on PATH). Deterministic: fixed seeds.
set -eu

OUT=${1:-default-data}
if [ -n "${CANDELA_TOOL:-}" ]; then
  TOOL=$CANDELA_TOOL
elif [ -x build/tools/candela-tool/candela-tool ]; then
  TOOL=build/tools/candela-tool/candela-tool
else
  TOOL=candela-tool
fi
FRAMES=${FRAMES:-300}   # 10 s at 30 fps per clip

start=$(date +%s)
mkdir -p "$OUT"
echo "make-default-data: $FRAMES frames per clip into $OUT (tool: $TOOL)" >&2

"$TOOL" simulate --preset candle --seed 1 --warmup 5 --frames "$FRAMES" --out "$OUT/candle_sim" --name candle_sim
"$TOOL" simulate --preset fireplace --seed 2 --warmup 5 --frames "$FRAMES" --out "$OUT/fireplace_sim" \
  --name fireplace_sim
"$TOOL" flame-photo --seed 1 --size 96x160 --out "$OUT/candle_photo.png"
"$TOOL" flame-photo --seed 2 --size 128x128 --out "$OUT/fireplace_photo.png"
"$TOOL" texturize --photo "$OUT/candle_photo.png" --sim "$OUT/candle_sim" \
  --out "$OUT/candle" --name candle --seed 1
"$TOOL" texturize --photo "$OUT/fireplace_photo.png" --sim "$OUT/fireplace_sim" \
  --out "$OUT/fireplace" --name fireplace --seed 2

# The model builder lives on another branch; use it only where it exists.
if "$TOOL" ingest --help >/dev/null 2>&1 && "$TOOL" build --help >/dev/null 2>&1; then
  mkdir -p "$OUT/models"
  for clip in candle fireplace; do
    "$TOOL" ingest "$OUT/$clip/frames" --out "$OUT/${clip}_dataset"
    "$TOOL" build "$OUT/${clip}_dataset" --out "$OUT/models/$clip.model"
  done
else
  echo "make-default-data: this candela-tool has no 'ingest'/'build' yet: clips made, models skipped" >&2
fi
echo "make-default-data: done in $(( $(date +%s) - start )) s" >&2
