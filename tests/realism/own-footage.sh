#!/usr/bin/env bash
# own-footage.sh CLIP KIND WIDTHxHEIGHT [MEASURE OPTIONS...]
# "Your own footage, faithfully": ingests the shared real clip CLIP (a folder
# of ../shared/data/flames), builds a model of it with `candela-tool build`
# as a user would (128 EigenFires), plays it in the runtime's eigenflame
# element (graph driver, the model's own colour and glow), headless 256x256,
# $FRAMES frames at 60 fps, framed like the clips (the whole model image, on
# black), and prints `candela-tool measure --against KIND`. The model is made
# in a temporary folder and never kept (the footage's licence is unclear).
# Exit status: measure's (0 inside, 1 outside, 2 bad input); 77 if the shared
# clips are not here. OWN_FOOTAGE_KEYS adds eigenflame keys (to try settings).
set -u
if [ $# -lt 3 ]; then
  sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
. "$(dirname "$0")/common.sh"
need_shared
clip=$1 kind=$2 size=$3
shift 3
[ -d "$flames/$clip" ] || { echo "no clip $flames/$clip" >&2; exit 2; }
out=$(mktemp -d "${TMPDIR:-/tmp}/candela-own.XXXXXX")
trap 'rm -rf "$out"' EXIT
if ! "$tool" ingest "$flames/$clip" --out "$out/dataset" --width "${size%x*}" --height "${size#*x}" \
    >"$out/ingest.log" 2>&1 ||
  ! "$tool" build "$out/dataset" --out "$out/model.cmodel" --components "${OWN_FOOTAGE_COMPONENTS:-128}" --holdout 0 \
    >"$out/build.log" 2>&1; then
  echo "making the model of $clip failed:" >&2
  tail -n 5 "$out/ingest.log" "$out/build.log" >&2
  exit 2
fi
cat >"$out/scene.toml" <<SCENE
# The model of $clip, framed as the clip is: the whole image on black.
seed = 5
[background]
color = "#000000"
[camera]
position = [0.0, 0.05, 0.16]
target = [0.0, 0.05, 0.0]
fov = 40
[[element]]
kind = "eigenflame"
model = "model.cmodel"
position = [0.0, 0.0, 0.0]
height = 0.1
driver = "graph"
${OWN_FOOTAGE_KEYS:-}
SCENE
render "$out/scene.toml" 5 "$out/frames"
echo "$clip: ingest $size, build 128 components, played 256x256, $frames frames at 60 fps:"
"$tool" measure "$out/frames" --fps 60 --against "$kind" --flames "$flames" "$@"
