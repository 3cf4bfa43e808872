#!/usr/bin/env bash
# c2st.sh SCENE KIND [SEED SEED SEED] [-- c2st.py options]
# Renders SCENE (a file, or an eval scene: a_candle_calm, b_candle_breeze,
# e_perlinfire, or its letter) headless at 256x256, $FRAMES frames (600 = 10 s
# at 60 fps), once per seed (default 1 2 3), and asks ../shared/eval/c2st.py
# whether a classifier tells them from the real clips of KIND (candle or fire:
# ../shared/eval/refs-KIND.txt). Prints its verdict in a few lines (d', the
# most any real clip reaches when it plays the render, beyond_real, and what
# differs most); C2ST_JSON=FILE keeps the whole report.
# Exit status: 0 when the renders are not beyond the real clips, 1 when they
# are, 2 on bad input, 77 when the shared scenes or clips are not here (or
# python3-sklearn, which c2st.py needs, is missing).
set -u
if [ $# -lt 2 ]; then
  sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
. "$(dirname "$0")/common.sh"
need_shared
scene=$(scene_file "$1") || exit 2
kind=$2
shift 2
case $kind in candle | fire) ;; *) echo "c2st.sh: KIND: expected candle or fire, got '$kind'" >&2; exit 2 ;; esac
seeds=()
while [ $# -gt 0 ] && [ "$1" != -- ]; do
  case $1 in '' | *[!0-9]*) echo "c2st.sh: SEED: expected a whole number, got '$1'" >&2; exit 2 ;; esac
  seeds+=("$1")
  shift
done
[ "${1:-}" = -- ] && shift
[ ${#seeds[@]} -gt 0 ] || seeds=(1 2 3)
/usr/bin/python3 -c 'import sklearn' 2>/dev/null ||
  { echo "skipped: c2st.py needs python3-sklearn (apt-get install python3-sklearn)" >&2; exit 77; }
out=$(mktemp -d "${TMPDIR:-/tmp}/candela-c2st.XXXXXX")
trap 'rm -rf "$out"' EXIT
dirs=()
for s in "${seeds[@]}"; do
  render "$scene" "$s" "$out/seed$s"
  dirs+=("$out/seed$s")
done
report=${C2ST_JSON:-$out/report.json}
(cd "$eval_dir" && /usr/bin/python3 c2st.py "$kind" "${dirs[@]}" --real "refs-$kind.txt" "$@") >"$report" ||
  { echo "c2st.sh: c2st.py failed" >&2; exit 2; }
/usr/bin/python3 - "$report" "$(basename "$scene")" "${seeds[*]}" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
print("%s, seeds %s: d' %.2f, a real clip at most %.2f: %s (all features: %.2f, %.2f)" % (
    sys.argv[2], sys.argv[3], d["dprime"], d["null"]["one_clip_dprime_max"],
    "beyond the real clips" if d["beyond_real"] else "inside the real clips' range",
    d["all_features"]["dprime"], d["all_features"]["null"]["one_clip_dprime_max"]))
for f in d["top_features"][:6]:
    print("  %-16s render %s (%.3f; real %s)" % (f["feature"], f["render_is"], f["render_median"],
          ", ".join("%.3f" % v for v in f["real_clip_medians"])))
sys.exit(1 if d["beyond_real"] else 0)
PY
