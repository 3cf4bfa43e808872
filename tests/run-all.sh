#!/usr/bin/env bash
# Builds and runs every test three times: a normal build (build/) and
# README's package command from a fresh folder (build-package/), a clang
# Release build against libgpiod 2 (build-gpiod2/) and an AddressSanitizer +
# UndefinedBehaviorSanitizer build (build-asan/); then an arm64 cross build
# (build-arm64/, its tests under qemu-user) and the fuzz targets. The
# virtual-board tests (label "board", slow under emulation), the slow pure
# numerics (label "numeric") and the realism checks against real footage
# (label "realism") run in the normal build only.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
# Each stage's minutes, printed as it ends: CI must stay within its budget on
# the slowest 2-core machine it gets (the same work took 2-3x as long on some).
started=$(date +%s)
minutes() { echo $(( ($(date +%s) - started) / 60 )); }
stage() { echo "run-all: $1 done at $(minutes) min"; }

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCANDELA_WERROR=ON
cmake --build build -j "$jobs"
ctest --test-dir build --output-on-failure -j "$jobs" -LE board
# The virtual-board tests time real kernel events under emulation: run them
# on their own, one at a time, so the other tests' load cannot skew them.
ctest --test-dir build --output-on-failure -L board
stage "normal build, its tests and the virtual board"

# README's package command exactly as README gives it, from a fresh build
# folder (tests/package/readme_package.sh; issue 34: the package test above
# packages build/, which hid that board/package.sh's own build left a
# program out). A whole Release build without tests (7 min on a 2-core
# machine whose stages above took 30 min; the whole run then took over 60,
# and CI's own run with it took 61 min): run where the stages so far took at
# most CANDELA_CI_PACKAGE_BY minutes (default 20), so CI keeps its budget on
# a slower machine.
if [ $(minutes) -le "${CANDELA_CI_PACKAGE_BY:-20}" ]; then
  tests/package/readme_package.sh
  rm -rf build-package
  stage "README's package command from a fresh build folder"
else
  echo "run-all: README's package command not run: the stages above took $(minutes) min"
fi

# libgpiod 2.x (Debian 13) next to the 1.6 above, built by the other compiler
# in the other optimised build type: build trixie's libgpiod from Debian's
# signed source archive into build-gpiod2/ (board/libgpiod2/build.sh; it
# fails, and so does this, when the archive cannot be reached), build all of
# candela with clang in Release against it -- gpio_line_v2.cpp instead of
# gpio_line_v1.cpp -- and run the unit and render tests there, then the gpio tests of the
# virtual board. One build proves three things: libgpiod 2, clang with
# -Werror, and Release (-O3, no asserts) giving the same answers. The VM comes
# from build/vboard: it is not built again.
gpiod2_prefix=$(board/libgpiod2/build.sh build-gpiod2) ||
  { echo "run-all: error: could not build Debian 13's libgpiod (see above)" >&2; exit 1; }
# Without candela-tool (the offline tools: Eigen, libav; 4 of every 10 CPU
# minutes of a build): the normal build above builds and tests them, the
# fuzz targets read their manifests under ASan, and CI fits its budget.
cmake -S . -B build-gpiod2 -G Ninja -DCMAKE_BUILD_TYPE=Release -DCANDELA_WERROR=ON -DCANDELA_BUILD_BENCH=OFF \
  -DCANDELA_BUILD_TOOLS=OFF \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_PREFIX_PATH="$gpiod2_prefix"
grep -qx 'CANDELA_GPIO_API:INTERNAL=2' build-gpiod2/CMakeCache.txt ||
  { echo "run-all: error: build-gpiod2 did not pick libgpiod 2 (gpio_line_v2.cpp)" >&2; exit 1; }
cmake --build build-gpiod2 -j "$jobs"
# Not "package": this libgpiod is in no Debian 12 package, so dpkg-shlibdeps
# cannot name the .deb's Depends (the normal build packages); not "numeric"
# and not "realism" (the footage comparisons: 12 of the normal build's 37
# CPU minutes of tests, the same numerics): they ran above.
ctest --test-dir build-gpiod2 --output-on-failure -j "$jobs" -LE 'board|package|numeric|realism'
CANDELA_VBOARD_CACHE=${CANDELA_VBOARD_CACHE:-$PWD/build/vboard} ctest --test-dir build-gpiod2 --output-on-failure -L board -R gpio
stage "clang Release build against libgpiod 2 and its tests"

# intercept_tls_get_addr=0: LeakSanitizer does not walk the dynamic TLS of
# dlopen'd libraries (Mesa's driver). With it on, its tracer read a stale
# slot of glibc's DTV at a GL test's exit ("DTLS 20 at 0x1052-...", "Tracer
# caught signal 11") and aborted after the test had passed; whether it does
# shifts with the heap's layout. Our code's TLS is static, and Mesa's own
# allocations are suppressed (tests/lsan.supp).
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:intercept_tls_get_addr=0
export LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# The runtime and the recorder (what runs on the board), without candela-tool
# as in build-gpiod2/.
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCANDELA_WERROR=ON -DCANDELA_SANITIZE=ON -DCANDELA_BUILD_BENCH=OFF \
  -DCANDELA_BUILD_TOOLS=OFF
cmake --build build-asan -j "$jobs"
# Label "numeric": pure numerics whose code a smaller test runs here (5 min
# under ASan for 2 s normally); "realism": the footage comparisons, whose
# code (every element's drawing) the render tests run here; both run in the
# normal build above.
# Where the stages above took more than CANDELA_CI_ASAN_FULL_BY minutes
# (default 40; about 30 on a fast 2-core machine, 48 on CI's), the slowest
# tests under ASan are left out: the writers' full-disk sweep and the Perlin
# fireplace's 1920x1080 fill (2.5 of the 8 minutes of this stage's tests; the
# normal build ran them, and the 1280x720 fill runs the same code here).
asan_skip=()
if [ $(minutes) -gt "${CANDELA_CI_ASAN_FULL_BY:-40}" ]; then
  asan_skip=(-E 'cli_hostile_full_disk|FillsThePictureAsOneFire/1920x1080')
  echo "run-all: ASan: the full-disk sweep and the 1080p fill left out: the stages above took $(minutes) min"
fi
ctest --test-dir build-asan --output-on-failure -j "$jobs" -LE 'board|numeric|realism' "${asan_skip[@]}"
stage "ASan + UBSan build and its tests"

# arm64 (board/arm64/): the runtime cross-built with GCC -Werror in
# MinSizeRel (the one build type not built above) against Debian's :arm64
# libraries, its unit and headless render tests under qemu-user, every
# built-in scene's animation state bit-identical to build/'s over 10,000
# steps (frames within 2 LSB), and the arm64 .deb.
# Under qemu-user the renders are the slowest part of CI: where the stages
# above took longer than CANDELA_CI_ARM64_FULL_BY minutes (default 35; they
# take about 25 on a fast 2-core machine, 50 on a slow one), only the unit
# tests and the state equality run here; later than CANDELA_CI_ARM64_QUICK_BY
# (default 45), only the programs are built (not the tests) and only the
# state equality runs (its frames still compare arm64's pixels). So CI stays
# inside its budget; the renders' and unit tests' code ran natively above.
if [ $(minutes) -le "${CANDELA_CI_ARM64_FULL_BY:-35}" ]; then
  board/arm64/cross-build.sh --host-build build build-arm64
  board/arm64/test.sh build-arm64
elif [ $(minutes) -le "${CANDELA_CI_ARM64_QUICK_BY:-45}" ]; then
  echo "run-all: arm64: unit tests and the state equality only (--quick): the stages above took $(minutes) min"
  board/arm64/cross-build.sh --host-build build build-arm64
  board/arm64/test.sh --quick build-arm64
else
  echo "run-all: arm64: the programs and the state equality only: the stages above took $(minutes) min"
  board/arm64/cross-build.sh --host-build build --programs build-arm64
  board/arm64/test.sh --state-only build-arm64
fi
board/arm64/package.sh build-arm64
stage "arm64 cross build, its tests under qemu-user and its package"

# libFuzzer (clang, build-fuzz/): the model reader with the players built from
# it, the scene reader, noise tables, the control-socket commands and the
# dataset manifest, 10 s each from tests/fuzz/corpus/; any crash, leak,
# timeout or > 2 GB RSS fails the run.
# 5 s each where the stages above took more than CANDELA_CI_FUZZ_FULL_BY
# minutes (default 50), so a slow machine keeps CI's budget.
fuzz_s=10
[ $(minutes) -le "${CANDELA_CI_FUZZ_FULL_BY:-50}" ] || fuzz_s=5
tests/fuzz/run-fuzz.sh $fuzz_s
stage "fuzzing"
