#!/usr/bin/env bash
# Builds Debian 13 (trixie)'s libgpiod 2.x C library from Debian's source
# archive into a private prefix, so Candela's libgpiod-2 code
# (firmware/input/gpio_line_v2.cpp) can be built and tested on a Debian 12 host
# that only has libgpiod 1.6. Nothing is installed system-wide.
#
#   board/libgpiod2/build.sh [CACHE_DIR]     (default: build-gpiod2)
#
# Result: CACHE_DIR/libgpiod-prefix/{include/gpiod.h,lib/libgpiod.so.3,
# lib/pkgconfig/libgpiod.pc}; its path is the last line printed on stdout.
# Configure Candela with -DCMAKE_PREFIX_PATH=that path (or PKG_CONFIG_PATH=
# path/lib/pkgconfig); the binaries find libgpiod.so.3 there by RUNPATH.
#
# The version is whatever trixie carries today (never hard-coded). The source
# comes through apt itself: `apt-get source --print-uris` with a private
# apt state (CACHE_DIR/apt) whose only source is trixie's deb-src on the same
# Debian archive this machine's apt already uses (read from `apt-cache
# policy`; no archive host is named here). apt verifies everything as it does
# for any install: the InRelease signatures against debian-archive-keyring
# (bookworm's keyring already holds the trixie keys) and the Sources index
# against the signed Release; apt's own downloader (apt-helper) fetches the
# upstream tarball and checks it against the sha256 in that index.
# Debian's own patches (debian.tar.xz) only touch the documentation today, so
# the upstream .orig tarball is built as it is.
#
# Idempotent: the library is rebuilt only when trixie's tarball changed.
# Without network it fails (exit 1, saying so), unless a verified build is
# already there, which it then reuses with a warning. Needs: apt, gpgv,
# debian-archive-keyring, xz-utils, build-essential (board/install-deps.sh).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
cache=$(mkdir -p "${1:-$repo/build-gpiod2}" && cd "${1:-$repo/build-gpiod2}" && pwd)
suite=trixie
package=libgpiod
keyring=${CANDELA_DEBIAN_KEYRING:-/usr/share/keyrings/debian-archive-keyring.gpg}
prefix=$cache/libgpiod-prefix
dl=$cache/libgpiod-download
stamp=$prefix/.candela-built-from

say() { echo "libgpiod2: $*" >&2; }
die() {
  echo "libgpiod2: error: $*" >&2
  exit 1
}
for tool in apt-get apt-cache gpgv xz sha256sum make cc; do
  command -v "$tool" >/dev/null || die "'$tool' is missing: run board/install-deps.sh"
done
[ -r "$keyring" ] || die "$keyring is missing: apt-get install debian-archive-keyring"

mkdir -p "$dl"
exec 9>"$cache/.libgpiod2.lock"
flock 9 # concurrent runs wait for one another

reuse_or_die() {
  if [ -f "$stamp" ]; then
    say "WARNING: $1; reusing the verified build in $prefix ($(cat "$stamp"))"
    echo "$prefix"
    exit 0
  fi
  die "$1"
}

# --- 1. which Debian archive this machine uses ------------------------------------
# The URI of the release's main component, as apt reports it (origin Debian, not
# the security archive).
archive=$(apt-cache policy 2>/dev/null | awk '
  / [0-9]+ [a-z]+:\/\// {uri = $2}
  /release .*o=Debian,/ && /,c=main,/ && !/l=Debian-Security/ && uri != "" {print uri; exit}')
[ -n "$archive" ] || die "apt knows no Debian archive (apt-cache policy lists none): run apt-get update"

# --- 2. a private apt state with trixie's sources only ----------------------------
state=$cache/apt
mkdir -p "$state/lists/partial" "$state/archives/partial" "$state/etc"
printf 'Types: deb-src\nURIs: %s\nSuites: %s\nComponents: main\nSigned-By: %s\n' \
  "$archive" "$suite" "$keyring" >"$state/etc/trixie.sources"
apt_private=(-o "Dir::Etc::SourceList=/dev/null" -o "Dir::Etc::SourceParts=$state/etc"
  -o "Dir::State::Lists=$state/lists" -o "Dir::Cache=$state" -o "Dir::State::Status=/dev/null"
  -o "APT::Sandbox::User=root" -o "Debug::NoLocking=1" -qq)
apt-get "${apt_private[@]}" update >"$state/update.log" 2>&1 ||
  reuse_or_die "apt-get update of $suite's sources failed (no network?):
$(cat "$state/update.log")"

# --- 3. the package: version and upstream tarball, verified by apt -----------------
entry=$(apt-cache "${apt_private[@]}" showsrc "$package" 2>/dev/null | awk 'BEGIN {RS = ""} NR == 1')
[ -n "$entry" ] || die "$suite has no source package '$package'"
version=$(sed -n 's/^Version: //p' <<<"$entry")
read -r tar_sha tar_size tar_name < <(awk '/^Checksums-Sha256:/{s=1; next} /^[^ ]/{s=0}
  s && $3 ~ /\.orig\.tar\.(xz|gz|bz2)$/ {print $1, $2, $3}' <<<"$entry") || true
[ -n "${tar_sha:-}" ] || die "$suite's entry for $package has no .orig tarball with a sha256:
$entry"
say "$suite has $package $version ($tar_name)"

# --- 4. build, unless this exact tarball was built already ----------------------
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$tar_sha $tar_name" ]; then
  say "already built: $prefix"
  echo "$prefix"
  exit 0
fi
if ! echo "$tar_sha  $dl/$tar_name" | sha256sum -c --status 2>/dev/null; then
  # Only the upstream tarball is needed: apt names its URI (on the archive above)
  # and its own downloader fetches it, checking the sha256 from the signed index.
  uri=$(apt-get "${apt_private[@]}" source --print-uris "$package=$version" 2>"$state/source.log" |
    awk -v n="$tar_name" '$2 == n {gsub(/\047/, "", $1); print $1}')
  [ -n "$uri" ] || reuse_or_die "apt names no URI for $tar_name:
$(cat "$state/source.log")"
  /usr/lib/apt/apt-helper -o "APT::Sandbox::User=root" download-file "$uri" "$dl/$tar_name" \
    "SHA256:$tar_sha" >"$state/download.log" 2>&1 || reuse_or_die "cannot download $tar_name:
$(cat "$state/download.log")"
  echo "$tar_sha  $dl/$tar_name" | sha256sum -c --status ||
    die "$tar_name does not match the sha256 in $suite's signed Sources"
fi
[ "$(stat -c %s "$dl/$tar_name")" = "$tar_size" ] || die "$tar_name has the wrong size"

src=$cache/libgpiod-src
rm -rf "$src" "$prefix"
mkdir -p "$src"
tar -xf "$dl/$tar_name" -C "$src" --strip-components=1
say "building $package $version into $prefix (the C library only)"
(
  cd "$src"
  # Only libgpiod.so: no tools, tests, examples or bindings, so nothing beyond
  # a C compiler and make is needed. The tarball ships a generated configure.
  ./configure -q --prefix="$prefix" --disable-static --disable-dependency-tracking \
    --disable-tools --disable-tests --disable-examples --disable-bindings-cxx \
    --disable-bindings-python --disable-bindings-rust --disable-bindings-glib \
    --disable-dbus --disable-systemd >/dev/null
  make -s -j "$(nproc)" >/dev/null
  make -s install >/dev/null
) || die "building $package $version failed (log above)"
rm -f "$prefix"/lib/*.la
[ -f "$prefix/lib/pkgconfig/libgpiod.pc" ] || die "the build left no libgpiod.pc in $prefix"
rm -rf "$src"
echo "$tar_sha $tar_name" >"$stamp" # last: its presence means a complete, verified build
say "done: $package $version in $prefix"
echo "$prefix"
