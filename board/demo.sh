#!/usr/bin/env bash
# Sets up, builds and shows Candela. On a screen (a desktop session or a
# kiosk's DRM display) it runs live until you press Esc/q or Ctrl-C; on a
# machine without a screen it renders a 10-second video and PNG frames into
# out/ for you to look at. Extra arguments go to candela (e.g. --scene FILE).
set -euo pipefail
cd "$(dirname "$0")/.."
board/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build --target candela
bin=build/firmware/candela

if [ -n "${DISPLAY:-}" ]; then
  exec "$bin" --display window "$@"
fi
if "$bin" --display drm --frames 1 "$@" >/dev/null 2>&1; then
  exec "$bin" --display drm "$@"
fi
mkdir -p out
echo "demo: no screen here; rendering out/candela-demo.mp4 and out/frames/*.png" >&2
"$bin" --display headless --size 1280x720 --frames 60 --out out/frames "$@"
if command -v ffmpeg >/dev/null; then
  "$bin" --display headless --size 1280x720 --frames 600 --out out/candela-demo.mp4 "$@"
else
  "$bin" --display headless --size 1280x720 --frames 600 --out out/candela-demo.y4m "$@"
fi
ls -l out
