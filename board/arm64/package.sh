#!/usr/bin/env bash
# Makes the kiosk's Debian package for arm64 from an arm64 cross build
# (board/arm64/cross-build.sh): candela_VERSION_arm64.deb, the same contents
# as board/package.sh's candela package (candela, candela-record, scenes,
# models, the systemd unit, user, udev rule, conffile), Depends from
# dpkg-shlibdeps over the :arm64 libraries installed by multiarch
# (board/install-deps.sh --arm64), lintian clean of errors. candela-tool is
# not cross-built, so there is no candela-tool package for arm64 here.
#   board/arm64/package.sh BUILD_DIR [--out DIR]   (default ./out/deb-arm64)
# Then, on the board: sudo apt install ./candela_*_arm64.deb
set -euo pipefail
build=$(realpath -m "${1:?usage: board/arm64/package.sh BUILD_DIR [--out DIR]}")
out=$(realpath -m out/deb-arm64)
if [ "${2:-}" = --out ]; then out=$(realpath -m "${3:?--out needs a folder}"); fi
grep -q 'set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE "arm64")' "$build/CPackConfig.cmake" 2>/dev/null ||
  { echo "package: $build is not an arm64 cross build (board/arm64/cross-build.sh)" >&2; exit 1; }
for t in firmware/candela tools/record/candela-record; do
  [ -x "$build/$t" ] || { echo "package: $build/$t not built (cmake --build $build)" >&2; exit 1; }
done

rm -rf "$out" && mkdir -p "$out"
# dpkg-shlibdeps looks for the libraries of the package's architecture.
DEB_HOST_ARCH=arm64 cpack --config "$build/CPackConfig.cmake" -B "$out" -D CPACK_COMPONENTS_ALL=candela
rm -rf "$out/_CPack_Packages"
deb=$(ls "$out"/candela_*_arm64.deb)
[ "$(dpkg-deb -f "$deb" Architecture)" = arm64 ] || { echo "package: $deb is not arm64" >&2; exit 1; }
dpkg-deb -f "$deb" Depends | grep -q 'libgpiod2' ||
  { echo "package: $deb has no Depends from dpkg-shlibdeps: $(dpkg-deb -f "$deb" Depends)" >&2; exit 1; }
lintian --fail-on error "$deb" 2>/dev/null || { echo "package: lintian found errors (above)" >&2; exit 1; }
ls -l "$deb"
echo "package: Depends: $(dpkg-deb -f "$deb" Depends)"
