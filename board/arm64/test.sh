#!/usr/bin/env bash
# Runs an arm64 cross build's tests (board/arm64/cross-build.sh) on this
# amd64 machine under qemu-user: every test labelled unit or render (and the
# candle, eigenflame and model areas' tests, labelled by area) whose program
# ctest starts through the emulator (CMAKE_CROSSCOMPILING_EMULATOR: the
# GoogleTest programs), then
# arm64_state_equality (tests/arm64: every built-in scene's animation state
# bit-identical to the host build's over 10,000 steps, frames within 2 LSB;
# configured when the cross build was given -DCANDELA_HOST_BUILD_DIR).
# Tests that start an arm64 program themselves -- `candela ...` command
# lines given as $<TARGET_FILE:candela>, scripts (python, sh), or from inside
# a test (`not_here` below: the control-socket cases that posix_spawn
# `candela`) -- would need binfmt_misc and are left out; they run in the
# amd64 builds.
# Some render tests take minutes under emulation (the Perlin fire's ray march
# on llvmpipe, eigen-flame reconstructions checked against the CPU, hundreds
# of frames in frame_loop_alloc); they are left out
# unless --all is given (`slow` below). Their arm64 pixels are covered by the
# state check's frames of the fire scenes, and their code by the amd64 runs.
#   board/arm64/test.sh [--all] BUILD_DIR
set -euo pipefail
slow='^(perlinfire_render\.|eigenflame_render\.|frame_loop_alloc\.FrameLoop\.NoHeapAllocationPerFrame$)'
if [ "${1:-}" = --all ]; then slow='^$'; shift; fi
build=${1:?usage: board/arm64/test.sh [--all] BUILD_DIR}
jobs=$(nproc)
not_here='^input_control\.ControlSocket\.CandelaProgram'
# The kiosk's live-control cases start `candela` themselves too.
not_here+='|^kiosk_live\.'
# Assumes native speed: perlin-fireplace's quality = "auto" steps down under
# emulation (frames far over its 33 ms budget), and llvmpipe compiles the new
# shader variant -- LLVM's operator new -- inside the counted frames (3620
# allocations). Left out under qemu; it runs in every amd64 build.
not_here+='|^sound_scene\.SceneSound\.FrameLoopFeedsOneStepOfSoundPerStep$'
emulator=$(sed -n 's/^CMAKE_CROSSCOMPILING_EMULATOR:[A-Z]*=//p' "$build/CMakeCache.txt")
[ -n "$emulator" ] || { echo "arm64 test: $build is not a cross build with an emulator" >&2; exit 1; }

# The tests of those labels that ctest runs through the emulator.
ctest --test-dir "$build" --show-only=json-v1 >"$build/arm64-tests.json"
picked=$(/usr/bin/python3 - "$build/arm64-tests.json" "$emulator" "$not_here" "$slow" <<'PY'
import json, re, sys
tests = json.load(open(sys.argv[1]))["tests"]
picked, skipped, slow = [], 0, 0
for number, t in enumerate(tests, 1):  # ctest's test numbers (for -I)
    labels = set()
    for p in t.get("properties", []):
        if p["name"] == "LABELS":
            labels.update(p["value"])
    if not labels & {"unit", "render", "candle", "eigenflame", "model"}:
        continue
    if t.get("command", [""])[0] != sys.argv[2] or re.search(sys.argv[3], t["name"]):
        skipped += 1
    elif sys.argv[4] != "^$" and re.search(sys.argv[4], t["name"]):
        slow += 1
    else:
        picked.append(str(number))
print(f"arm64 test: {len(picked)} tests under the emulator; {skipped} start an "
      f"arm64 program themselves or need native speed, and {slow} slow ones (--all), are left out", file=sys.stderr)
print(",".join(picked))
PY
)
[ -n "$picked" ] || { echo "arm64 test: no unit or render test found in $build" >&2; exit 1; }
ctest --test-dir "$build" --output-on-failure -j "$jobs" -I "0,0,0,$picked"
if ctest --test-dir "$build" -N -L arm64 | grep -q 'Total Tests: [1-9]'; then
  ctest --test-dir "$build" --output-on-failure -L arm64
else
  echo "arm64 test: no arm64_state_equality (configure $build with -DCANDELA_HOST_BUILD_DIR=an amd64 build)" >&2
  exit 1
fi
