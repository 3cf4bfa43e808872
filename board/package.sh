#!/usr/bin/env bash
# Makes Candela's Debian packages for this machine's architecture:
#   candela_VERSION_ARCH.deb       the kiosk (runtime, candela-record, scenes,
#                                  models, systemd unit, user, udev rule, conffile)
#   candela-tool_VERSION_ARCH.deb  the offline tools (Eigen, FFTW, libav)
#   board/package.sh [--build-dir DIR] [--out DIR]
#     --build-dir DIR  an existing build tree to package as it is (not rebuilt;
#                      e.g. build); default: configure and build a Release tree
#                      in build-package/ without tests
#     --out DIR        where the .debs go (default: out/deb)
# Then, on the board: sudo apt install ./candela_*.deb  (starts at the next boot)
set -euo pipefail
cd "$(dirname "$0")/.."

build="" out=out/deb
while [ $# -gt 0 ]; do
  case "$1" in
    --build-dir) build=${2:?--build-dir needs a folder}; shift ;;
    --out) out=${2:?--out needs a folder}; shift ;;
    -h | --help) sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "package: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done

board/install-deps.sh
if [ -z "$build" ]; then
  build=build-package
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCANDELA_BUILD_TESTS=OFF -DCANDELA_BUILD_BENCH=OFF
  # Everything the install rules name (candela-studio too, where libimgui-dev
  # is installed): a narrower target list left CPack without the studio.
  cmake --build "$build" -j "$(nproc)"
fi
[ -f "$build/CPackConfig.cmake" ] || { echo "package: $build is not a configured build tree" >&2; exit 1; }
grep -q '^CANDELA_SANITIZE:BOOL=ON' "$build/CMakeCache.txt" &&
  { echo "package: $build is a sanitizer build; package a normal one" >&2; exit 1; }
programs=(firmware/candela tools/record/candela-record tools/candela-tool/candela-tool)
grep -q '^CANDELA_STUDIO:INTERNAL=ON' "$build/CMakeCache.txt" 2>/dev/null && programs+=(tools/candela-tool/candela-studio)
for t in "${programs[@]}"; do
  [ -x "$build/$t" ] || { echo "package: $build/$t not built (cmake --build $build)" >&2; exit 1; }
done

mkdir -p "$out"
cpack --config "$build/CPackConfig.cmake" -B "$out"
rm -rf "$out/_CPack_Packages"
lintian --fail-on error "$out"/*.deb 2>/dev/null || { echo "package: lintian found errors (above)" >&2; exit 1; }
ls -l "$out"/*.deb
