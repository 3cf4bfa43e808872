#!/bin/sh
# The Perlin-fire benchmark matrix: 1280x720 headless output, each noise kind
# at render scale 1.0, 0.5 and 0.25, with 1 and 3 fire volumes, plus the
# test-pattern baseline. Prints one table row per run: p50/p95 frame ms, fps,
# and CPU ms per frame (all llvmpipe threads: steadier than wall time on a
# machine shared with other work).
# usage: tests/elements/perlinfire/bench-perlinfire.sh [build-dir] [frames]
set -eu
here=$(cd "$(dirname "$0")/../../.." && pwd)
build=${1:-$here/build}
frames=${2:-120}
candela=$build/firmware/candela
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

field() { sed -n "s/.*\"$1\":\([0-9.]*\).*/\1/p"; }

row() {  # label, then candela's arguments
  label=$1
  shift
  out=$("$candela" --bench --display headless --size 1280x720 "$@" 2>/dev/null | tail -n 1)
  printf '%-34s %9s %9s %7s %9s\n' "$label" "$(echo "$out" | field frame_ms_p50)" \
    "$(echo "$out" | field frame_ms_p95)" "$(echo "$out" | field fps)" \
    "$(echo "$out" | field cpu_ms_per_frame)"
}

printf '%-34s %9s %9s %7s %9s\n' "run" "p50 ms" "p95 ms" "fps" "cpu ms"
row "test-pattern (baseline)" --test-pattern --frames 600
for volumes in 1 3; do
  for noise in simplex3d flow3d simplex4d perlin4d; do
    for scale in 1.0 0.5 0.25; do
      scene=$tmp/bench-$volumes-$noise-$scale.toml
      sed -e "s/^noise = .*/noise = \"$noise\"/" -e "s/^render_scale = .*/render_scale = $scale/" \
        "$here/firmware/scenes/bench-perlinfire-$volumes.toml" >"$scene"
      row "$volumes vol $noise scale $scale" --scene "$scene" --frames "$frames"
    done
  done
done
