#!/bin/sh
# Builds the runtime's built-in eigen-flame models from data the project makes
# itself (no recorded footage is used):
#   firmware/models/default.cmodel  a candle (also "builtin:candle"), learnt
#       from the runtime's own "candles" element (the noise-morphed still,
#       which measures inside the real candles' range): 20 s calm, 20 s with
#       breezes to the right, 20 s to the left (tools/eigen/candle-dataset/),
#       rendered headless at 60 fps, then ingested and built;
#   firmware/models/fire.cmodel     a log fire ("builtin:fire"): eight
#       independent 2-D simulations (`tongues` preset: MacCormack advection,
#       vorticity confinement, turbulent fuel burning to heat) side by side
#       and in depth on one canvas (after Horvath and Geiger), rendered as a
#       camera sees black-body radiance (exposure, soft clip, the shutter's
#       motion blur) over logs and coals, then ingested and built.
# Seeds are fixed, the solver and the renders deterministic and the PCA sums
# in a fixed order, so the same tools give the same models.
#
#   tools/eigen/make-default-model.sh [CANDELA_TOOL] [OUT_DIR] [WHICH]
#   (defaults: build/tools/candela-tool/candela-tool, firmware/models, "candle fire")
#   CANDELA=PATH is the runtime that renders the candle clips
#   (default: build/firmware/candela). KEEP=DIR keeps the clips and datasets there.
#   SIZE=small: the same recipes at a size for iterating on them (a quarter of
#   the candle clips, 120 fire frames, fewer components: both models in 1.5
#   CPU minutes, under 3 minutes beside a test run on a 2-core machine); its
#   models are for measuring, never for firmware/models. Full size: both in
#   7.6 minutes (the candle 4.7, the fire 2.9).
set -eu
size=${SIZE:-full}
case $size in
full) candle_frames=1200 candle_components=80 fire_frames=300 fire_components=300 ;;
small) candle_frames=300 candle_components=40 fire_frames=120 fire_components=120 ;;
*) echo "make-default-model: SIZE: expected full or small, got \"$size\"" >&2; exit 2 ;;
esac
here=$(cd "$(dirname "$0")/../.." && pwd)
tool=${1:-$here/build/tools/candela-tool/candela-tool}
case $tool in /*) ;; */*) tool=$(pwd)/$tool ;; esac
out=${2:-$here/firmware/models}
which=${3:-candle fire}
[ -x "$tool" ] || { echo "make-default-model: no candela-tool at $tool (build it first)" >&2; exit 1; }
candela=${CANDELA:-$here/build/firmware/candela}
case $candela in /*) ;; */*) candela=$(pwd)/$candela ;; esac
case " $which " in *" candle "*)
  [ -x "$candela" ] || { echo "make-default-model: no candela at $candela (build it first)" >&2; exit 1; } ;;
esac
if [ -n "${KEEP:-}" ]; then
  work=$KEEP
  mkdir -p "$work"
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$out"
out=$(cd "$out" && pwd)
# Work inside the folder with relative names: the model records where its
# data came from, so the same run gives byte-identical files wherever it runs.
cd "$work"
start=$(date +%s)

for kind in $which; do
  case $kind in
  candle)
    # 60 fps clips of the candles element; each its own seed.
    seed=7
    for clip in calm right left; do
      seed=$((seed + 1))
      mkdir -p "$clip"
      "$candela" --display headless --size 256x256 --frames $candle_frames --seed $seed \
        --scene "$here/tools/eigen/candle-dataset/$clip.toml" --out "$clip/" >/dev/null
    done
    "$tool" ingest calm right left --force --out candle-dataset --width 96 --height 144 --fps 60 \
      --label calm:0-$candle_frames:calm --label right:0-$candle_frames:wind-right \
      --label left:0-$candle_frames:wind-left
    # 80 EigenFires (scenes choose how many to use), 8-bit images, no glow of its own.
    "$tool" build candle-dataset --out "$out/default.cmodel" --components $candle_components --bits 8 \
      --holdout 0 --report candle-report --hue 28 --saturation 0.9
    ls -l "$out/default.cmodel"
    ;;
  fire)
    # Eight slices of a few tongues each, over a fuel bed; 10 s at 30 fps.
    # The visible flame is the hot gas, not only where fuel burns (soot 5:
    # with soot 90 only the burning fuel glowed, and the vortices drew it
    # into thin ribbons, issue 35), through a camera's exposure (4) with a
    # soft clip, so tongues are broad bodies with a clipped core and crisp
    # edges. What turned the curling ribbons into tongues (issue 35): the gas
    # rises slowly (buoyancy 0.75) and cools fast (6000 K/s), so a tongue
    # ends in a point instead of trailing a long wisp; its fuel burns
    # quickly (burn-rate 8), so flame stays near the wood; vortices
    # confined harder (7) break its edges into licks. Eight slices 0.4
    # widths apart make one dense, many-tongued fire (with five, the fire
    # broke into fewer pieces than a real one, and its sway spectrum was a
    # single plume's); each slice's light flickers on its own (0.3, 1/f: the
    # small pockets the 2-D grid cannot resolve, and the fire's breathing);
    # each slice's clock runs at its own rate (0.7-1.3: tongues of many
    # sizes puff at many frequencies, so the brightness spectrum has no
    # single peak); each slice's light fades out at its grid's sides and
    # (where inside the canvas) top, so no tongue ends on a straight line;
    # the shutter is open for the last of the three substeps only (averaging
    # all three showed fast tongues as three stacked copies); a faint glow
    # joins tongues that nearly touch (a stronger one blurred their edges
    # into a smooth, too-steep spatial spectrum) and the haze gives them
    # video's dim envelope. Seed 22: with 21 the same recipe's sway spectrum
    # fell outside a real fire's, with 23 its pieces and breathing (c2st and
    # flame_features over the cooling, slices, flicker, glow and seed: the
    # closing note of stop 50, issue 35). Scenes play
    # it at speed 1.45-1.75 with detail_scale 1.2 (see eigen-fireplace.toml).
    "$tool" simulate -q --preset tongues --slices 8 --slice-spacing 0.4 --fuel-bed --no-fields \
      --seed 22 --frames $fire_frames --wind 0:0 --substeps 3 --warmup 2 --render radiance \
      --exposure 4 --knee 0.65 --soot 5 --buoyancy 0.75 --cooling 6000 --vorticity 7 --burn-rate 8 \
      --slice-flicker 0.3 --slice-rates 0.3 --slice-edge-fade 0.08 --shutter 0.34 \
      --glow 0.08 --glow-radius 4 --haze 0.1 --haze-radius 10 --name fire-calm --out fire-calm
    # One clip, no labels, no background level taken off (the simulation's
    # black is black; the haze is the picture). An EigenFire per frame (300
    # at 128x160; the runtime plays up to 512): eight independent fires are
    # hard to compress, and what fewer components left out showed as a
    # mottled orange grain in the haze between the tongues. No glow of its
    # own: the simulation's camera has one, and more softened the edges.
    "$tool" ingest fire-calm --force --out fire-dataset --width 128 --height 160 --threshold 0
    "$tool" build fire-dataset --out "$out/fire.cmodel" --components $fire_components \
      --bits 8 --holdout 0 --report fire-report --hue 26 --saturation 0.95 \
      --glow-strength 0
    ls -l "$out/fire.cmodel"
    ;;
  *) echo "make-default-model: unknown model \"$kind\" (candle or fire)" >&2; exit 2 ;;
  esac
done
echo "make-default-model: done in $(( $(date +%s) - start )) s" >&2
