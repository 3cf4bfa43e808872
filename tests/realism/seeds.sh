#!/usr/bin/env bash
# seeds.sh SCENE KIND [FIRST [LAST]]
# Judges SCENE (a file, or an eval scene or its letter, as judge.sh takes) on
# every seed from FIRST to LAST (default 1 to 20; FIRST alone: that seed):
# renders each headless at 256x256, $FRAMES frames, and measures it against
# the real clips of KIND (candle or fire) on the seven features and the four
# spectra. Prints a line a seed naming what fell outside, then how many seeds
# had all seven features inside and how many had all eleven (issue 35: the
# built-in flames over seeds 1-20), and what fell outside most often.
# Exit status: 0 when every seed had all seven features inside, 1 otherwise,
# 2 on bad input, 77 when the shared scenes or clips are not here.
set -u
if [ $# -lt 2 ]; then
  sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
here=$(dirname "$0")
scene=$1 kind=$2
first=${3:-1} last=${4:-${3:-20}}
for v in "$first" "$last"; do
  case $v in '' | *[!0-9]*) echo "seeds.sh: FIRST, LAST: expected whole numbers, got '$v'" >&2; exit 2 ;; esac
done
[ "$first" -le "$last" ] || { echo "seeds.sh: FIRST ($first) is after LAST ($last)" >&2; exit 2; }
case $kind in candle | fire) ;; *) echo "seeds.sh: KIND: expected candle or fire, got '$kind'" >&2; exit 2 ;; esac
n=0 features_ok=0 all_ok=0
declare -A misses=()
for ((s = first; s <= last; ++s)); do
  out=$("$here/judge.sh" "$scene" "$s" "$kind" --json 2>&1)
  rc=$?
  case $rc in 0 | 1) ;; 77) echo "$out" | tail -3 >&2; exit 77 ;;
  *) echo "seeds.sh: judging seed $s failed (exit $rc):" >&2; echo "$out" | tail -5 >&2; exit 2 ;;
  esac
  # measure's verdict (its JSON, the last line): the features outside, then the spectra.
  verdict=$(echo "$out" | tail -1 | /usr/bin/python3 -c '
import json, sys
d = json.load(sys.stdin)
print(" ".join(k for k, v in d["features"].items() if not v["inside"]))
print(" ".join(k for k, v in d["spectra"].items() if not v["inside"]))') ||
    { echo "seeds.sh: seed $s: no verdict from measure:" >&2; echo "$out" | tail -3 >&2; exit 2; }
  feat_out=$(echo "$verdict" | sed -n 1p)
  outside=$(echo "$verdict" | tr '\n' ' ' | sed 's/^ *//; s/ *$//')
  n=$((n + 1))
  [ -z "$feat_out" ] && features_ok=$((features_ok + 1))
  [ -z "$outside" ] && all_ok=$((all_ok + 1))
  for f in $outside; do misses[$f]=$((${misses[$f]:-0} + 1)); done
  echo "seed $s: ${outside:-all inside}"
done
echo "$(basename "$scene"): the seven features inside on $features_ok of $n seeds; all eleven (with the four spectra) on $all_ok of $n"
if [ ${#misses[@]} -gt 0 ]; then
  echo -n "outside most often:"
  for f in "${!misses[@]}"; do echo "${misses[$f]} $f"; done | sort -rn | awk '{printf " %s (%d)", $2, $1} END {print ""}'
fi
[ "$features_ok" -eq "$n" ]
