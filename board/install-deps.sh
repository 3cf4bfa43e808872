#!/usr/bin/env bash
# Installs every package Candela needs to build, run and test on Debian 12
# (bookworm) or Raspberry Pi OS bookworm. Safe to run again.
#   board/install-deps.sh            build + run + test dependencies
#   board/install-deps.sh --runtime  only what the kiosk needs to run
# On amd64 the full set includes the arm64 cross build (Debian multiarch:
# board/arm64/cross-build.sh and its tests under qemu-user); alone:
#   board/install-deps.sh --arm64
set -euo pipefail

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

runtime=(
  libegl1 libgles2 libgbm1 libdrm2 libpng16-16 libfftw3-single3
  libegl-mesa0 libgl1-mesa-dri libgpiod2 libx11-6
  libasound2  # sound (ALSA)
  libmosquitto1  # MQTT ([mqtt] in the kiosk config)
  libcec6  # HDMI-CEC screen power (dlopened: without it, DPMS only)
  libudev1  # monitor hot-plug (udev uevents)
  libcamera-ipa  # pulls in the libcamera library of the release (0.0.3 on bookworm)
)
build=(
  build-essential cmake ninja-build pkg-config clang-format
  libegl-dev libgles-dev libdrm-dev libgbm-dev libx11-dev
  libtomlplusplus-dev libcli11-dev libpng-dev libfftw3-dev
  libeigen3-dev libgpiod-dev gpiod
  libasound2-dev
  libmosquitto-dev
  libudev-dev  # the DRM display follows monitor hot-plug (display/drm_display.cpp)
  libcec-dev  # its headers only (display/cec_switch.cpp dlopens libcec6)
  libavformat-dev libavcodec-dev libswscale-dev libavutil-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  nlohmann-json3-dev zlib1g-dev
  libcamera-dev
  libimgui-dev  # the studio window (candela-tool studio): Dear ImGui + its OpenGL ES 3 backend source
  # Debian packages (board/package.sh, ctest -L package): cpack + dpkg-shlibdeps, lintian
  dpkg-dev lintian
)
tests=(
  # MQTT tests (tests/input/mqtt_cli.py): a real broker on loopback, and a client;
  # openssl makes the TLS case's certificates
  mosquitto python3-paho-mqtt openssl
  ffmpeg python3 python3-numpy python3-scipy python3-pil imagemagick xvfb xauth
  python3-sklearn  # ../shared/eval/c2st.py (tests/realism/c2st.sh): the classifier two-sample test
  # virtual board (board/virtual): QEMU + Debian kernel + out-of-tree drivers
  qemu-system-x86 busybox-static cpio kmod gzip xz-utils bc flex bison libelf-dev
  v4l-utils libdrm-tests
  # ALSA on the virtual board (board_sound_aloop): arecord on snd-aloop
  alsa-utils
  # libgpiod 2 check (board/libgpiod2/build.sh): Debian 13's source through apt
  gpgv debian-archive-keyring
  # libcamera on the board's vimc: `cam`, and udevd (libcamera enumerates through udev)
  libcamera-tools udev
  # libFuzzer targets (tests/fuzz/run-fuzz.sh): clang and its fuzzer runtime
  clang libclang-rt-14-dev
  # systemd-analyze security (ctest -L systemd), systemd-sysusers --dry-run (-L package);
  # libseccomp for the unit's syscall filter applied by hand (-L systemd)
  systemd python3-seccomp
)

# The arm64 cross build (board/arm64/): the cross compiler, qemu-user to run
# the arm64 tests, and the :arm64 libraries the runtime and its tests link
# (Mesa's llvmpipe for the headless render tests). Everything the runtime
# uses installs for arm64 on Debian 12; candela-tool (Eigen, libav) is not
# cross-built.
arm64=(
  crossbuild-essential-arm64 qemu-user-static
  pkgconf:arm64 libegl-dev:arm64 libgles-dev:arm64 libegl-mesa0:arm64 libgl1-mesa-dri:arm64
  libdrm-dev:arm64 libgbm-dev:arm64 libpng-dev:arm64 libx11-dev:arm64 zlib1g-dev:arm64
  libtomlplusplus-dev:arm64 libgpiod-dev:arm64 libasound2-dev:arm64 libmosquitto-dev:arm64
  libcamera-dev:arm64 libudev-dev:arm64
  libfftw3-dev:arm64  # tests/elements/eigenflame's reference FFT
  libgtest-dev:arm64 libgmock-dev:arm64
)
# Adds arm64 to dpkg's architectures (once) so the :arm64 packages can be had.
enable_arm64() {
  if ! dpkg --print-foreign-architectures | grep -qx arm64; then
    echo "install-deps: adding the arm64 architecture (dpkg --add-architecture arm64)" >&2
    $SUDO dpkg --add-architecture arm64
  fi
}

want=("${runtime[@]}")
case "${1:-}" in
  --runtime) ;;
  --arm64) want=("${arm64[@]}") ;;
  *) want+=("${build[@]}" "${tests[@]}") ;;
esac
if [ "${1:-}" != "--runtime" ] && [ "$(dpkg --print-architecture)" = amd64 ]; then
  [ "${1:-}" = "--arm64" ] || want+=("${arm64[@]}")
  enable_arm64
elif [ "${1:-}" = "--arm64" ]; then
  echo "install-deps: --arm64 is for cross-building on amd64 (this is $(dpkg --print-architecture))" >&2
  exit 2
fi

missing=()
for p in "${want[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}" >&2
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "install-deps: all packages present" >&2
fi
