#!/usr/bin/env bash
# Cross-builds Candela's runtime for arm64 (Raspberry Pi 4/5, 64-bit OS) on an
# amd64 Debian 12 machine, with Debian multiarch (board/install-deps.sh --arm64
# installs the cross compiler, qemu-user-static and the :arm64 libraries):
# `candela`, `candela-record`, and the unit and headless render tests, which
# ctest runs under qemu-user (CMAKE_CROSSCOMPILING_EMULATOR). No candela-tool
# (Eigen, FFTW, libav): the built-in noise tables come from a HOST
# candela-noise, so they are the amd64 build's byte for byte.
#   board/arm64/cross-build.sh [--host-build DIR] [--type TYPE] [--programs] BUILD_DIR
#     --host-build DIR  an amd64 build of this source (e.g. build/) whose
#                       candela-noise makes the noise tables and whose
#                       candela-state-hash arm64_state_equality compares with;
#                       default: BUILD_DIR-host, configured and built here
#                       (those two programs only)
#     --type TYPE       CMake build type (default MinSizeRel: the smallest
#                       binaries for a board, and the build type no other
#                       CI build uses)
#     --programs        only what the board runs and the state check needs
#                       (candela, candela-record, candela-state-hash), not the
#                       test programs: what tests/run-all.sh builds when CI
#                       is late (then board/arm64/test.sh --state-only)
# (ccache: export CMAKE_C_COMPILER_LAUNCHER=ccache CMAKE_CXX_COMPILER_LAUNCHER=ccache)
#   then: board/arm64/test.sh BUILD_DIR   (the tests under qemu-user)
#   and:  board/arm64/package.sh BUILD_DIR  (candela_VERSION_arm64.deb)
set -euo pipefail

host="" type=MinSizeRel build="" targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --host-build) host=${2:?--host-build needs a folder}; shift ;;
    --type) type=${2:?--type needs a build type}; shift ;;
    --programs) targets=(--target candela candela-record candela-state-hash) ;;
    -h | --help) sed -n '2,24p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "cross-build: unknown option $1 (see --help)" >&2; exit 2 ;;
    *) build=$1 ;;
  esac
  shift
done
[ -n "$build" ] || { echo "cross-build: usage: $0 [--host-build DIR] [--type TYPE] [--programs] BUILD_DIR" >&2; exit 2; }
build=$(realpath -m "$build")
[ -z "$host" ] || host=$(realpath -m "$host")
cd "$(dirname "$0")/../.."
for tool in aarch64-linux-gnu-g++ aarch64-linux-gnu-pkg-config qemu-aarch64-static; do
  command -v "$tool" >/dev/null ||
    { echo "cross-build: $tool not found: run board/install-deps.sh --arm64" >&2; exit 1; }
done
jobs=$(nproc)

if [ -z "$host" ]; then
  # The noise tables are made while building, by a host candela-noise (FFTW
  # only); the state comparison needs the host's candela-state-hash.
  host=$build-host
  cmake -S . -B "$host" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCANDELA_WERROR=ON \
    -DCANDELA_BUILD_BENCH=OFF -DCANDELA_BUILD_TOOLS=OFF >/dev/null
  cmake --build "$host" -j "$jobs" --target candela-noise candela-state-hash
fi
host=$(realpath "$host")
for p in tools/noise/candela-noise tests/arm64/candela-state-hash; do
  [ -x "$host/$p" ] || { echo "cross-build: $host/$p not built (cmake --build $host --target ${p##*/})" >&2; exit 1; }
done

cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE="$type" -DCANDELA_WERROR=ON \
  -DCMAKE_TOOLCHAIN_FILE="$PWD/board/arm64/toolchain-aarch64.cmake" \
  -DCANDELA_NOISE_TOOL="$host/tools/noise/candela-noise" -DCANDELA_HOST_BUILD_DIR="$host" \
  -DCANDELA_BUILD_TOOLS=OFF -DCANDELA_BUILD_BENCH=OFF
cmake --build "$build" -j "$jobs" "${targets[@]}"
readelf -h "$build/firmware/candela" | grep -q "Machine: *AArch64" ||
  { echo "cross-build: $build/firmware/candela is not an arm64 program" >&2; exit 1; }
echo "cross-build: arm64 $type build in $build (test: board/arm64/test.sh $build)"
