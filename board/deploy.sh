#!/usr/bin/env bash
# Installs Candela as a kiosk on this board (Raspberry Pi OS / Debian 12)
# without a package (board/package.sh makes the .deb, the usual way): binary,
# scenes and models under /usr/local, /etc/candela/candela.toml, a system user
# in the video/render/input/gpio/audio groups, the GPIO udev rule, and the systemd
# unit that starts candela at boot and restarts it if it stops.
# Run from a built checkout, as root (or with sudo):
#   board/deploy.sh [--build-dir build] [--no-start] [--disable-desktop]
#     --build-dir DIR     where `candela` was built (default: build)
#     --no-start          install and enable, but do not start now
#     --disable-desktop   boot to the console (multi-user.target): a desktop
#                         holds the display and candela cannot show
set -euo pipefail
cd "$(dirname "$0")/.."

args=("$@")
build=build
start=1
disable_desktop=0
while [ $# -gt 0 ]; do
  case "$1" in
    --build-dir) build=${2:?--build-dir needs a folder}; shift ;;
    --no-start) start=0 ;;
    --disable-desktop) disable_desktop=1 ;;
    -h | --help) sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "deploy: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
if [ "$(id -u)" -ne 0 ]; then exec sudo "$0" "${args[@]}"; fi

bin=$build/firmware/candela
[ -x "$bin" ] || { echo "deploy: $bin not found: build first (see README.md)" >&2; exit 1; }
board/install-deps.sh --runtime

# The kiosk needs the display's groups: without them it could never open
# /dev/dri (a udev or image problem to fix first, not to paper over).
for g in video render; do
  getent group "$g" >/dev/null ||
    { echo "deploy: error: no '$g' group on this system: /dev/dri/* would be root-only (is udev installed?)" >&2; exit 1; }
done

install -D -m 0755 "$bin" /usr/local/bin/candela
# The same layout as the .deb (board/package.sh), under /usr/local.
install -d /usr/local/share/candela/scenes /usr/local/share/candela/models
install -m 0644 firmware/scenes/*.toml /usr/local/share/candela/scenes/
install -m 0644 firmware/models/*.cmodel /usr/local/share/candela/models/
sed 's|^ExecStart=/usr/bin/candela |ExecStart=/usr/local/bin/candela |' board/systemd/candela.service \
  >/etc/systemd/system/candela.service
chmod 0644 /etc/systemd/system/candela.service
install -D -m 0644 board/package/60-candela-gpio.rules /etc/udev/rules.d/60-candela-gpio.rules
if [ -d /run/udev ]; then udevadm control --reload-rules && udevadm trigger --subsystem-match=gpio || true; fi
if [ ! -f /etc/candela/candela.toml ]; then
  install -d /etc/candela
  sed 's|"/usr/share/candela/|"/usr/local/share/candela/|' board/package/candela.toml >/etc/candela/candela.toml
fi
if [ ! -f /etc/default/candela ]; then
  cat >/etc/default/candela <<'CONF'
# Extra arguments for the kiosk, e.g.
#   CANDELA_ARGS="--size 1920x1080 --refresh 60"
# (the scene and display: /etc/candela/candela.toml)
CANDELA_ARGS=""
CONF
fi

# A system user with access to the display (video: /dev/dri/card*, render:
# /dev/dri/renderD*), input devices, GPIO and cameras; no login, no root.
# GPIO: Raspberry Pi OS has a gpio group, plain Debian does not (the udev rule
# above gives it /dev/gpiochip*), as the package's sysusers.d file does.
getent group gpio >/dev/null || groupadd --system gpio
groups=()
for g in video render input gpio audio; do getent group "$g" >/dev/null && groups+=("$g"); done
group_list=$(IFS=,; echo "${groups[*]}")
if ! id candela >/dev/null 2>&1; then
  useradd --system --user-group --home-dir /nonexistent --no-create-home --shell /usr/sbin/nologin \
    ${group_list:+--groups "$group_list"} candela
else
  [ -n "$group_list" ] && usermod -a -G "$group_list" candela
fi
echo "deploy: user candela in groups: $(id -nG candela)"

if systemctl is-enabled --quiet display-manager.service 2>/dev/null; then
  if [ $disable_desktop -eq 1 ]; then
    systemctl set-default multi-user.target
    echo "deploy: the desktop will no longer start at boot (multi-user.target)"
  else
    echo "deploy: warning: a desktop (display-manager.service) starts at boot and holds the" \
      "display; candela will keep retrying until it is gone. Rerun with --disable-desktop." >&2
  fi
fi

systemctl daemon-reload
systemctl enable candela.service
if [ $start -eq 1 ]; then
  # Type=notify: this waits for candela's first frame on the screen.
  if systemctl restart candela.service; then
    echo "deploy: started; follow it with: journalctl -u candela -f"
  else
    echo "deploy: warning: candela did not show a frame (no screen? a desktop holding it?);" \
      "it stays enabled and retries; see: journalctl -u candela" >&2
  fi
else
  echo "deploy: enabled; it starts at the next boot"
fi
