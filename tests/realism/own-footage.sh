#!/usr/bin/env bash
# own-footage.sh CLIP KIND [MEASURE OPTIONS...]
# "Your own footage, faithfully": makes a model of the shared real clip CLIP
# (a folder of ../shared/data/flames) as a user who wants it as filmed would
# (`candela-tool ingest --as-filmed`: the whole frame at its own size, nothing
# cut; `build --components 512`: an EigenFire per frame), plays it in the
# runtime's eigenflame element (graph driver, frames held as video shows them,
# no edge fade), headless 256x256 with the image at 1:1 (its larger side 256
# px, centred, on black), $FRAMES frames at 60 fps, and prints
# `candela-tool measure --against KIND --source CLIP`: each feature inside the
# real range of KIND or within 10% of the clip's own value, each spectrum's
# distance to the clip within the real clips' spread. The model is made in a
# temporary folder and never kept (the footage's licence is unclear).
# Exit status: measure's (0 inside, 1 outside, 2 bad input); 77 if the shared
# clips are not here. OWN_FOOTAGE_KEYS adds eigenflame keys (to try settings);
# OWN_FOOTAGE_KEEP=1 keeps the folder (model, scene, frames) to look at;
# OWN_FOOTAGE_SEED (default 5) seeds the walk.
set -u
if [ $# -lt 2 ]; then
  sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
. "$(dirname "$0")/common.sh"
need_shared
clip=$1 kind=$2
shift 2
[ -d "$flames/$clip" ] || { echo "no clip $flames/$clip" >&2; exit 2; }
out=$(mktemp -d "${TMPDIR:-/tmp}/candela-own.XXXXXX")
[ -n "${OWN_FOOTAGE_KEEP:-}" ] && echo "keeping $out" >&2 || trap 'rm -rf "$out"' EXIT
if ! "$tool" ingest "$flames/$clip" --out "$out/dataset" --as-filmed >"$out/ingest.log" 2>&1 ||
  ! "$tool" build "$out/dataset" --out "$out/model.cmodel" --components 512 --holdout 0 \
    >"$out/build.log" 2>&1; then
  echo "making the model of $clip failed:" >&2
  tail -n 5 "$out/ingest.log" "$out/build.log" >&2
  exit 2
fi
size=$("$tool" inspect "$out/model.cmodel" | sed -n 's/.* components of \([0-9]*x[0-9]*\),.*/\1/p')
w=${size%x*} h=${size#*x}
# The camera sees 2 * 0.16 * tan(20 deg) = 0.11647 m across 256 px: the
# image's larger side spans it, centred on the camera's target (y = 0.05).
read -r height base < <(awk -v w="$w" -v h="$h" 'BEGIN {
  v = 0.11647 * (w > h ? h / w : 1); printf "%.6f %.6f\n", v, 0.05 - v / 2 }')
cat >"$out/scene.toml" <<SCENE
# The model of $clip, framed as the clip is: the whole image on black, 1:1.
seed = ${OWN_FOOTAGE_SEED:-5}
[background]
color = "#000000"
[camera]
position = [0.0, 0.05, 0.16]
target = [0.0, 0.05, 0.0]
fov = 40
[[element]]
kind = "eigenflame"
model = "model.cmodel"
position = [0.0, $base, 0.0]
height = $height
driver = "graph"
crossfade = 0
edge_fade = 0
${OWN_FOOTAGE_KEYS:-}
SCENE
render "$out/scene.toml" "${OWN_FOOTAGE_SEED:-5}" "$out/frames"
echo "$clip: ingest --as-filmed ($size), build an EigenFire per frame, played 256x256 at 1:1, $frames frames at 60 fps:"
"$tool" measure "$out/frames" --fps 60 --against "$kind" --flames "$flames" --source "$clip" "$@"
