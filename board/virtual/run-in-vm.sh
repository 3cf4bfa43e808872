#!/usr/bin/env bash
# The virtual board: runs one command inside a small QEMU VM that boots
# Debian's own kernel with virtual hardware drivers loaded -- vkms (KMS
# display, /dev/dri/card0), gpio-sim (a simulated GPIO chip), vivid and vimc
# (virtual cameras). The host's root filesystem is the VM's root (9p,
# read-only, with a RAM overlay so the guest can write), so host binaries run
# unchanged. Prints the command's output and exits with its exit status.
#
#   board/virtual/run-in-vm.sh [options] COMMAND...
#     --prepare      only fetch and build what the VM needs (done on first use anyway)
#     --timeout S    give up after S seconds (default 600); exit status 124
#     --out DIR      a host folder the guest sees writable at the same path
#                    (default: a fresh folder; its path is in $VBOARD_OUT inside)
#     --live         stream the command's output while it runs (slower: serial)
#
# The command runs through `sh -c` in the current directory, as root, with
# VBOARD_OUT set. Built once and cached under ${CANDELA_VBOARD_CACHE:-build/vboard}
# (per kernel version): kernel, out-of-tree modules, initramfs. See README.md.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
cache=${CANDELA_VBOARD_CACHE:-$repo/build/vboard}
timeout_s=600
out_dir=""
live=0
prepare_only=0

die() {
  echo "vboard: error: $*" >&2
  exit 125
}
say() { echo "vboard: $*" >&2; }

while [ $# -gt 0 ]; do
  case "$1" in
    --prepare) prepare_only=1 ;;
    --timeout)
      timeout_s=${2:?--timeout needs seconds}
      shift
      ;;
    --out)
      out_dir=${2:?--out needs a folder}
      shift
      ;;
    --live) live=1 ;;
    --help | -h)
      sed -n '2,19p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
      exit 0
      ;;
    --)
      shift
      break
      ;;
    -*) die "unknown option $1 (see --help)" ;;
    *) break ;;
  esac
  shift
done
if [ $prepare_only -eq 0 ] && [ $# -eq 0 ]; then die "no command given (see --help)"; fi

for tool in qemu-system-x86_64 cpio gzip xz depmod modprobe apt-get apt-cache dpkg-deb make gcc flock timeout; do
  command -v "$tool" >/dev/null || die "'$tool' is missing: run board/install-deps.sh"
done
# The initramfs needs busybox-static's /bin/busybox (the dynamic busybox package has none there).
[ -x /bin/busybox ] || die "/bin/busybox is missing: apt-get install busybox-static"

# --- which kernel -------------------------------------------------------------
# The version linux-image-amd64 points at today; never hard-coded.
kv=${CANDELA_VBOARD_KV:-}
if [ -z "$kv" ]; then
  kv=$(apt-cache depends linux-image-amd64 2>/dev/null |
    sed -n 's/^ *Depends: linux-image-\([0-9][^ ]*-amd64\)$/\1/p' | head -n1)
fi
if [ -z "$kv" ]; then
  # Offline: reuse a board built earlier, if there is one.
  kv=$(ls -1 "$cache" 2>/dev/null | grep -E '^[0-9].*-amd64$' | while read -r d; do
    [ -f "$cache/$d/ready" ] && echo "$d"
  done | sort -V | tail -n1 || true)
  [ -n "$kv" ] || die "cannot tell which kernel to use: 'apt-cache depends linux-image-amd64' \
names no linux-image-*-amd64 (run apt-get update) and nothing is cached in $cache"
  say "apt knows no linux-image-amd64; reusing cached kernel $kv"
fi
work=$cache/$kv
mkdir -p "$work"

# --- build (once per kernel version) -------------------------------------------
# Modules the guest loads, in this order; their dependencies come along.
guest_modules=(virtio_pci 9pnet_virtio 9p overlay configfs irq_sim gpio-sim vivid vimc vkms)

fetch_debs() {
  local dl=$work/debs
  mkdir -p "$dl"
  local ver
  ver=$(apt-cache policy "linux-image-$kv" 2>/dev/null | sed -n 's/^ *Candidate: //p' | head -n1)
  [ -n "$ver" ] && [ "$ver" != "(none)" ] || die "apt knows no package linux-image-$kv (run apt-get update)"
  local abi=${kv%-amd64}
  local kbuild=linux-kbuild-${kv%%.*}.$(echo "$kv" | cut -d. -f2)
  local source=linux-source-$(echo "$kv" | cut -d. -f1-2 | sed 's/-.*//')
  local pkgs=("linux-image-$kv=$ver" "linux-headers-$kv=$ver" "linux-headers-$abi-common=$ver"
    "$kbuild=$ver" "$source=$ver")
  say "downloading ${pkgs[*]}"
  local sandbox=()
  if [ "$(id -u)" -eq 0 ]; then sandbox=(-o APT::Sandbox::User=root); fi
  if ! (cd "$dl" && apt-get download -q "${sandbox[@]}" "${pkgs[@]}" >&2); then
    # Stale package lists name versions the mirror no longer has.
    if [ "$(id -u)" -eq 0 ]; then
      say "download failed: refreshing the package lists and retrying"
      apt-get update -qq >&2 || true
      (cd "$dl" && apt-get download -q "${sandbox[@]}" "${pkgs[@]}" >&2) ||
        die "apt-get download failed for ${pkgs[*]} (is apt reachable?)"
    else
      die "apt-get download failed for ${pkgs[*]} (is apt reachable? run 'sudo apt-get update')"
    fi
  fi
}

extract_kernel() {
  local root=$work/root
  rm -rf "$root" && mkdir -p "$root"
  say "extracting kernel, headers and kbuild into $root"
  for deb in "$work"/debs/linux-{image,headers,kbuild}-*.deb; do
    dpkg-deb -x "$deb" "$root"
  done
  [ -f "$root/boot/vmlinuz-$kv" ] || die "no /boot/vmlinuz-$kv in linux-image-$kv"
  [ -f "$root/usr/src/linux-headers-$kv/Makefile" ] || die "no headers for $kv"
  # The headers' Makefile includes the -common one by its installed path.
  sed -i "s|^include /usr/src/|include $root/usr/src/|" "$root/usr/src/linux-headers-$kv/Makefile"
  # Only the files the out-of-tree modules need, out of a 140 MB tarball.
  local src=$work/src
  rm -rf "$src" && mkdir -p "$src"
  say "extracting driver sources from linux-source"
  local tarball
  tarball=$(dpkg-deb -c "$work"/debs/linux-source-*.deb | awk '{print $6}' | grep 'linux-source-.*\.tar\.xz$')
  local top
  top=$(basename "$tarball" .tar.xz)
  dpkg-deb --fsys-tarfile "$work"/debs/linux-source-*.deb | tar -xO "$tarball" |
    tar -xJ -C "$src" --strip-components=1 \
      "$top/drivers/gpio/gpio-sim.c" "$top/drivers/gpio/gpiolib.h" "$top/kernel/irq/irq_sim.c" \
      "$top/drivers/gpu/drm/vkms" "$top/drivers/media/test-drivers/vimc" "$top/scripts/extract-vmlinux"
}

build_modules() {
  local src=$work/src m=$work/modsrc
  rm -rf "$m" && mkdir -p "$m"/{irq_sim,gpio-sim,vkms,vimc}
  cp "$src/kernel/irq/irq_sim.c" "$m/irq_sim/"
  # irq_sim is built in or absent in Debian's kernel; as a module it needs a
  # licence (for the GPL-only exports) and must not use the unexported irq_to_desc().
  sed -i 's/handle_simple_irq(irq_to_desc(\([a-z_]*\)));/generic_handle_irq(\1);/' "$m/irq_sim/irq_sim.c"
  grep -q 'generic_handle_irq(' "$m/irq_sim/irq_sim.c" ||
    die "irq_sim.c: could not replace handle_simple_irq(irq_to_desc(...)) -- source changed?"
  printf '\n#include <linux/module.h>\nMODULE_LICENSE("GPL");\n' >>"$m/irq_sim/irq_sim.c"
  echo 'obj-m += irq_sim.o' >"$m/irq_sim/Kbuild"
  cp "$src/drivers/gpio/gpio-sim.c" "$src/drivers/gpio/gpiolib.h" "$m/gpio-sim/"
  echo 'obj-m += gpio-sim.o' >"$m/gpio-sim/Kbuild"
  cp "$src"/drivers/gpu/drm/vkms/*.[ch] "$m/vkms/"
  sed 's/obj-$(CONFIG_DRM_VKMS)/obj-m/' "$src/drivers/gpu/drm/vkms/Makefile" >"$m/vkms/Kbuild"
  cp "$src"/drivers/media/test-drivers/vimc/*.[ch] "$m/vimc/"
  sed 's/obj-$(CONFIG_VIDEO_VIMC)/obj-m/' "$src/drivers/media/test-drivers/vimc/Makefile" >"$m/vimc/Kbuild"
  echo 'obj-m += irq_sim/ gpio-sim/ vkms/ vimc/' >"$m/Kbuild"
  say "building irq_sim, gpio-sim, vkms, vimc out of tree"
  make -s -C "$work/root/usr/src/linux-headers-$kv" M="$m" -j2 modules >"$work/modules-build.log" 2>&1 || {
    tail -n 30 "$work/modules-build.log" >&2
    die "building the out-of-tree modules failed (log: $work/modules-build.log)"
  }
  # A module tree the way the guest sees it: Debian's modules + ours in extra/.
  local lib=$work/root/lib/modules/$kv
  mkdir -p "$lib/extra"
  find "$m" -name '*.ko' -exec cp {} "$lib/extra/" \;
  depmod -b "$work/root" "$kv"
}

build_vmlinux() {
  # The uncompressed kernel boots through QEMU's PVH entry, about 3 s faster under TCG.
  say "extracting vmlinux"
  if sh "$work/src/scripts/extract-vmlinux" "$work/root/boot/vmlinuz-$kv" >"$work/vmlinux.tmp" 2>/dev/null &&
    [ -s "$work/vmlinux.tmp" ]; then
    mv "$work/vmlinux.tmp" "$work/vmlinux"
  else
    say "extract-vmlinux failed; booting the compressed kernel"
    rm -f "$work/vmlinux.tmp"
    cp "$work/root/boot/vmlinuz-$kv" "$work/vmlinux"
  fi
}

build_initramfs() {
  local ir=$work/initramfs
  rm -rf "$ir" && mkdir -p "$ir"/{bin,dev,proc,sys,host,rw,newroot,vbshare,lib/modules}
  cp /bin/busybox "$ir/bin/busybox"
  # The module closure, in load order, without repeats.
  : >"$ir/modules.load"
  local line path
  for mod in "${guest_modules[@]}"; do
    modprobe -d "$work/root" -S "$kv" --show-depends "$mod" >"$work/deps.tmp" 2>&1 ||
      die "module $mod not found for $kv: $(cat "$work/deps.tmp")"
    while read -r kind path _; do
      [ "$kind" = insmod ] || continue
      local name=${path##*/}
      name=${name%.xz}
      name=${name%.zst}
      grep -qx "/lib/modules/$name" "$ir/modules.load" && continue
      case "$path" in
        *.ko.xz) xz -dc "$path" >"$ir/lib/modules/$name" ;;
        *.ko.zst) zstd -qdc "$path" >"$ir/lib/modules/$name" ;;
        *) cp "$path" "$ir/lib/modules/$name" ;;
      esac
      echo "/lib/modules/$name" >>"$ir/modules.load"
    done <"$work/deps.tmp"
  done
  rm -f "$work/deps.tmp"
  cp "$here/guest-init.sh" "$ir/init"
  chmod +x "$ir/init"
  (cd "$ir" && find . | cpio -o -H newc --quiet | gzip -1) >"$work/initramfs.cpio.gz"
}

prepare() {
  exec 9>"$work/.lock"
  flock 9
  local stamp=$work/ready
  # Rebuild the initramfs when the guest init changes; everything else once.
  if [ -f "$stamp" ] && [ "$stamp" -nt "$here/guest-init.sh" ] && [ "$stamp" -nt "${BASH_SOURCE[0]}" ]; then
    exec 9>&-
    return
  fi
  local t0=$SECONDS
  [ -f "$work/debs.done" ] || [ -f "$work/extract.done" ] || {
    fetch_debs
    touch "$work/debs.done"
  }
  [ -f "$work/extract.done" ] || {
    extract_kernel
    touch "$work/extract.done"
    rm -rf "$work/debs" "$work/debs.done" # 220 MB, all extracted
  }
  build_modules
  build_vmlinux
  build_initramfs
  touch "$stamp"
  say "board for $kv ready in $((SECONDS - t0)) s ($work)"
  exec 9>&-
}

prepare
[ $prepare_only -eq 1 ] && exit 0

# --- accelerator ----------------------------------------------------------------
# KVM only where it truly boots a stock kernel: nested paravirtual KVM on some
# cloud machines aborts or hangs. The probe runs once per host kernel.
accel=${CANDELA_VBOARD_ACCEL:-auto}
qemu_base=(qemu-system-x86_64 -nodefaults -no-user-config -nographic -no-reboot
  -m "${CANDELA_VBOARD_MEM:-512}" -kernel "$work/vmlinux" -initrd "$work/initramfs.cpio.gz")
if [ "$accel" = auto ]; then
  accel=tcg
  if [ -r /dev/kvm ] && [ -w /dev/kvm ]; then
    probe=$cache/kvm-probe.$(uname -r)
    if [ ! -f "$probe" ]; then
      say "probing whether KVM boots a stock kernel here (once)"
      if timeout 30 "${qemu_base[@]}" -accel kvm -cpu host -serial stdio \
        -append "console=ttyS0 quiet panic=-1 vboard.probe=1" </dev/null 2>/dev/null |
        grep -q 'vboard: probe ok'; then
        echo kvm >"$probe"
      else
        echo tcg >"$probe"
      fi
    fi
    accel=$(cat "$probe")
  fi
fi
case "$accel" in
  kvm) accel_args=(-accel kvm -cpu host -smp 2) ;;
  # Not AVX2 under TCG: Debian 12's QEMU (7.2) emulates vpgatherdd wrongly (it
  # faulted at the base address - 2^31 with every index small), and llvmpipe's
  # texture fetches gather: candela on the DRM display died with SIGSEGV in
  # its shaders' code within a minute at 1280x720 (tests/bench/vboard_realtime.sh).
  tcg) accel_args=(-accel "tcg,tb-size=${CANDELA_VBOARD_TB_MB:-256}" -cpu "${CANDELA_VBOARD_CPU_MODEL:-max,-avx2}" -smp "${CANDELA_VBOARD_CPUS:-1}") ;;
  *) die "CANDELA_VBOARD_ACCEL: expected auto, kvm or tcg, got '$accel'" ;;
esac

# --- run --------------------------------------------------------------------------
mkdir -p "$cache/runs"
run=$(mktemp -d "$cache/runs/run.XXXXXX")
cleanup() { rm -rf "$run"; }
trap cleanup EXIT
if [ -z "$out_dir" ]; then
  out_dir=$run/out
fi
mkdir -p "$out_dir"
out_dir=$(cd "$out_dir" && pwd)
share=$run/share
mkdir -p "$share"
# What the guest runs: the command, where, and where results go.
{
  printf 'cd %q 2>/dev/null || cd /\n' "$PWD"
  printf 'export VBOARD_OUT=%q\n' "$out_dir"
  printf 'export PATH=%q\n' "/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin"
  printf 'export HOME=/root LANG=C.UTF-8 TERM=dumb\n'
  printf '%s\n' "$*"
} >"$share/command.sh"
printf '%s\n' "$out_dir" >"$share/out_dir"
[ $live -eq 1 ] && touch "$share/live"

say "booting $kv ($accel)"
t0=$EPOCHREALTIME
set +e
timeout --foreground -k 5 "$timeout_s" "${qemu_base[@]}" "${accel_args[@]}" \
  -fsdev local,id=hostroot,path=/,security_model=none,readonly=on,multidevs=remap \
  -device virtio-9p-pci,fsdev=hostroot,mount_tag=hostroot \
  -fsdev local,id=vbshare,path="$share",security_model=none,multidevs=remap \
  -device virtio-9p-pci,fsdev=vbshare,mount_tag=vbshare \
  -fsdev local,id=vbout,path="$out_dir",security_model=none,multidevs=remap \
  -device virtio-9p-pci,fsdev=vbout,mount_tag=vbout \
  -serial stdio \
  -append "console=ttyS0 quiet loglevel=3 panic=-1 oops=panic" </dev/null 2>&1 |
  if [ $live -eq 1 ]; then tee "$run/console.log" >&2; else cat >"$run/console.log"; fi
qemu_rc=${PIPESTATUS[0]}
set -e
elapsed=$(awk -v a="$t0" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f", b - a }')

if [ $live -eq 0 ] && [ -f "$share/output.log" ]; then cat "$share/output.log"; fi
if [ ! -f "$share/rc" ]; then
  echo "vboard: the VM ended without the command's exit status (qemu exit $qemu_rc)." >&2
  echo "vboard: last lines of the console:" >&2
  tail -n 40 "$run/console.log" | sed 's/^/  | /' >&2
  if [ $qemu_rc -eq 124 ] || [ $qemu_rc -eq 137 ]; then
    echo "vboard: timed out after $timeout_s s" >&2
    exit 124
  fi
  exit 125
fi
rc=$(cat "$share/rc")
say "command exited $rc; VM ran $elapsed s"
exit "$rc"
