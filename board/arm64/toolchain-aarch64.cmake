# CMake toolchain file: cross-build Candela for arm64 (Raspberry Pi 4/5 with a
# 64-bit Raspberry Pi OS / Debian 12) on an amd64 Debian 12 machine with
# Debian multiarch. board/arm64/cross-build.sh uses it; install what it needs
# with `board/install-deps.sh --arm64` (crossbuild-essential-arm64,
# qemu-user-static and the :arm64 -dev packages).
#   cmake -S . -B build-arm64 -DCMAKE_TOOLCHAIN_FILE=board/arm64/toolchain-aarch64.cmake \
#     -DCANDELA_NOISE_TOOL=/path/to/host/candela-noise -DCANDELA_BUILD_TOOLS=OFF
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)

set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)

# Without this pkg-config finds the amd64 .pc files and the link fails with
# "file in wrong format". Debian's wrapper (package pkgconf:arm64) searches
# /usr/lib/aarch64-linux-gnu/pkgconfig and /usr/share/pkgconfig.
set(PKG_CONFIG_EXECUTABLE /usr/bin/aarch64-linux-gnu-pkg-config CACHE FILEPATH
    "pkg-config for arm64 (Debian: pkgconf:arm64)")

# Run the arm64 programs (tests, gtest discovery) with qemu-user; no
# binfmt_misc needed. Debian: qemu-user-static.
set(CMAKE_CROSSCOMPILING_EMULATOR /usr/bin/qemu-aarch64-static CACHE FILEPATH
    "runs arm64 programs on this machine (Debian: qemu-user-static)")

# find_library/find_package look in /usr/lib/aarch64-linux-gnu first
# (CMAKE_LIBRARY_ARCHITECTURE above); header-only packages (CLI11,
# nlohmann-json) are the same for every architecture.

# The .deb (cmake/Packaging.cmake, board/arm64/package.sh) is for arm64, not
# for the machine that builds it.
set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE arm64)
