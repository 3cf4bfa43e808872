#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz/CMakeLists.txt) with clang in
# build-fuzz/ and runs each for a fixed budget from its seed corpus
# (tests/fuzz/corpus/<kind>/), failing on any crash, leak, sanitizer report,
# timeout (10 s per input, 1 s per story) or more than 2 GB RSS. Prints executions per second
# and coverage (edges) per target. A crash leaves its input in build-fuzz/:
# add it to the corpus once fixed, as a regression input. Then candela-tool's
# options against hostile values (tests/fuzz/tool_options.py).
#   tests/fuzz/run-fuzz.sh [SECONDS_PER_TARGET]   (default 20; Debian: clang libclang-rt-14-dev)
set -euo pipefail
cd "$(dirname "$0")/../.."
budget=${1:-20}
# The runtime's noise tables come from the normal build's candela-tool (not
# needed by the fuzz targets, but the project's configure names one).
tool=${CANDELA_NOISE_TOOL:-$PWD/build/tools/candela-tool/candela-tool}
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
  -DCMAKE_CXX_COMPILER=clang++ -DCANDELA_WERROR=ON -DCANDELA_BUILD_BENCH=OFF -DCANDELA_NOISE_TOOL="$tool" >/dev/null
# target:corpus folder[:seconds an input may take] (10 s where not said). A
# story that plans longer than 1 s counts as a hang (issue 34: the planner's
# work limit is about 0.8 s on the board).
targets="model_reader:model scene_reader:scene noise_table:noise control_command:control
  dataset_manifest:manifest story_reader:story:1 config_file:config mqtt_command:mqtt"
cmake --build build-fuzz --target $(for t in $targets; do printf '%s_fuzz ' "${t%%:*}"; done)
status=0
for entry in $targets; do
  target=${entry%%:*} rest=${entry#*:}
  seeds=${rest%%:*} timeout=10
  [ "$rest" != "$seeds" ] && timeout=${rest#*:}
  work=build-fuzz/fuzz-$target
  rm -rf "$work" && mkdir -p "$work/corpus"
  log=$work/log.txt
  # A target's words (tests/fuzz/TARGET.dict), where it has them.
  dict=()
  if [ -f "tests/fuzz/$target.dict" ]; then dict=(-dict="$PWD/tests/fuzz/$target.dict"); fi
  # New inputs go to $work/corpus; the committed seeds are read only.
  if ! (cd "$work" && ASAN_OPTIONS=detect_leaks=1 ../tests/fuzz/${target}_fuzz -max_total_time="$budget" \
        -rss_limit_mb=2048 -timeout="$timeout" -print_final_stats=1 "${dict[@]}" corpus \
        "$OLDPWD/tests/fuzz/corpus/$seeds") >"$log" 2>&1; then
    echo "run-fuzz: $target FAILED; see $log" >&2
    tail -40 "$log" >&2
    status=1
  fi
  execs=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  echo "run-fuzz: $target: ${runs:-?} inputs in ${budget} s, ${execs:-?} exec/s, ${cov:-?} edges"
done
# candela-tool's option parsing (issue 34): every subcommand's options given
# hostile values, then random mixes for the budget (the normal build's tool).
if [ -x build/tools/candela-tool/candela-tool ]; then
  /usr/bin/python3 tests/fuzz/tool_options.py build "$budget" || status=1
else
  echo "run-fuzz: tool_options: no build/tools/candela-tool/candela-tool (build the normal tree first)" >&2
  status=1
fi
exit $status
