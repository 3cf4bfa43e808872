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
# The version is whatever trixie carries today (read from its Sources index,
# never hard-coded). Everything downloaded is verified before use:
#   InRelease  -- OpenPGP signatures, gpgv against debian-archive-keyring
#                 (bookworm's keyring already holds the trixie keys): one
#                 good signature and no bad one, as apt requires;
#   Sources.xz -- sha256 and size from the verified Release text;
#   .orig.tar  -- sha256 and size from the verified Sources entry.
# Debian's own patches (debian.tar.xz) only touch the documentation today, so
# the upstream .orig tarball is built as it is.
#
# Idempotent: the index is fetched again only when its checksum changed, and
# the library is rebuilt only when the tarball did. Without network it fails
# (exit 1, saying so), unless a verified build is already there, which it then
# reuses with a warning. Needs: curl gpgv debian-archive-keyring xz-utils
# build-essential (board/install-deps.sh).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
cache=$(mkdir -p "${1:-$repo/build-gpiod2}" && cd "${1:-$repo/build-gpiod2}" && pwd)
mirror=${CANDELA_DEBIAN_MIRROR:-http://deb.debian.org/debian}
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
for tool in curl gpgv xz sha256sum make cc; do
  command -v "$tool" >/dev/null || die "'$tool' is missing: run board/install-deps.sh"
done
[ -r "$keyring" ] || die "$keyring is missing: apt-get install debian-archive-keyring"

mkdir -p "$dl"
exec 9>"$cache/.libgpiod2.lock"
flock 9 # concurrent runs wait for one another

fetch() { # URL FILE
  curl -sSf --retry 3 --connect-timeout 15 -o "$2.part" "$1" && mv "$2.part" "$2"
}
reuse_or_die() {
  if [ -f "$stamp" ]; then
    say "WARNING: $1; reusing the verified build in $prefix ($(cat "$stamp"))"
    echo "$prefix"
    exit 0
  fi
  die "$1"
}

# --- 1. the signed Release text -------------------------------------------------
fetch "$mirror/dists/$suite/InRelease" "$dl/InRelease" ||
  reuse_or_die "cannot download $mirror/dists/$suite/InRelease (no network?)"
# As apt does: at least one good signature by a key in the keyring and no bad
# one. (InRelease carries several; gpgv exits non-zero when any key is unknown,
# e.g. a newer release key than this keyring has, so its status lines decide.)
rm -f "$dl/Release.verified"
gpgv --status-fd 3 --keyring "$keyring" --output "$dl/Release.verified" "$dl/InRelease" \
  3>"$dl/gpgv.status" 2>"$dl/gpgv.log" || true
if ! grep -q '^\[GNUPG:\] VALIDSIG ' "$dl/gpgv.status" ||
  grep -qE '^\[GNUPG:\] (BADSIG|EXPKEYSIG|REVKEYSIG) ' "$dl/gpgv.status" ||
  [ ! -s "$dl/Release.verified" ]; then
  rm -f "$dl/Release.verified"
  die "the signature of $suite's InRelease does not verify against $keyring:
$(cat "$dl/gpgv.log")"
fi
# Only the verified text is read from here on, never InRelease itself.

# --- 2. the source index ----------------------------------------------------------
# The SHA256 section of Release: " <sha256> <size> main/source/Sources.xz".
read -r idx_sha idx_size < <(awk '/^SHA256:/{s=1; next} /^[^ ]/{s=0}
  s && $3 == "main/source/Sources.xz" {print $1, $2}' "$dl/Release.verified") || true
[ -n "${idx_sha:-}" ] || die "$suite's Release lists no sha256 for main/source/Sources.xz"
if ! echo "$idx_sha  $dl/Sources.xz" | sha256sum -c --status 2>/dev/null; then
  fetch "$mirror/dists/$suite/main/source/Sources.xz" "$dl/Sources.xz" ||
    reuse_or_die "cannot download $suite's main/source/Sources.xz"
  echo "$idx_sha  $dl/Sources.xz" | sha256sum -c --status ||
    die "main/source/Sources.xz does not match the sha256 in $suite's signed Release"
fi
[ "$(stat -c %s "$dl/Sources.xz")" = "$idx_size" ] || die "main/source/Sources.xz has the wrong size"

# --- 3. the package's entry: version, folder, upstream tarball ------------------
# (awk reads to the end: stopping early would kill xz with SIGPIPE under pipefail)
entry=$(xz -dc "$dl/Sources.xz" | awk -v p="$package" 'BEGIN {RS = ""}
  !found && $0 ~ "^Package: " p "\n" {print; found = 1}')
[ -n "$entry" ] || die "$suite has no source package '$package'"
version=$(sed -n 's/^Version: //p' <<<"$entry")
directory=$(sed -n 's/^Directory: //p' <<<"$entry")
# The Checksums-Sha256 line of the upstream tarball: " <sha256> <size> <name>.orig.tar.<ext>".
read -r tar_sha tar_size tar_name < <(awk '/^Checksums-Sha256:/{s=1; next} /^[^ ]/{s=0}
  s && $3 ~ /\.orig\.tar\.(xz|gz|bz2)$/ {print $1, $2, $3}' <<<"$entry") || true
{ [ -n "${tar_sha:-}" ] && [ -n "$directory" ]; } ||
  die "$suite's entry for $package has no .orig tarball with a sha256:
$entry"
say "$suite has $package $version ($tar_name)"

# --- 4. build, unless this exact tarball was built already ----------------------
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$tar_sha $tar_name" ]; then
  say "already built: $prefix"
  echo "$prefix"
  exit 0
fi
if ! echo "$tar_sha  $dl/$tar_name" | sha256sum -c --status 2>/dev/null; then
  fetch "$mirror/$directory/$tar_name" "$dl/$tar_name" || reuse_or_die "cannot download $tar_name"
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
