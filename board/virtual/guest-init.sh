#!/bin/busybox sh
# /init of the virtual board's initramfs (busybox). Loads the drivers, builds
# the root (host / over 9p, read-only, under a RAM overlay), sets up the
# virtual hardware, runs the command from the host and reports its status
# through the writable 9p share, then powers off.
/bin/busybox --install -s /bin
export PATH=/bin
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev

log() { echo "vboard-init: $*" >/dev/console; }

# The accelerator probe only needs to reach this point.
if grep -q 'vboard.probe=1' /proc/cmdline; then
  echo "vboard: probe ok" >/dev/console
  reboot -f
fi

while read -r m; do
  insmod "$m" >/dev/null 2>&1 || log "insmod $m failed"
done </modules.load

fail() {
  log "$*"
  echo "vboard-init: $*" >>/vbshare/output.log 2>/dev/null
  echo 125 >/vbshare/rc 2>/dev/null
  reboot -f
}

mount -t 9p -o trans=virtio,version=9p2000.L,cache=none,msize=262144 vbshare /vbshare ||
  fail "cannot mount the results share"
mount -t 9p -o trans=virtio,version=9p2000.L,ro,cache=loose,msize=262144 hostroot /host ||
  fail "cannot mount the host root (9p)"
mount -t tmpfs -o mode=0755 tmpfs /rw
mkdir -p /rw/upper /rw/work
mount -t overlay overlay -o lowerdir=/host,upperdir=/rw/upper,workdir=/rw/work /newroot ||
  fail "cannot mount the overlay root"

r=/newroot
mount -t proc proc $r/proc
mount -t sysfs sys $r/sys
mount -t devtmpfs dev $r/dev
mkdir -p $r/dev/pts $r/dev/shm
mount -t devpts devpts $r/dev/pts
mount -t tmpfs -o mode=1777 tmpfs $r/dev/shm
# /tmp is left as the host's (writes land in the RAM overlay): a checkout or
# build under /tmp, as CI may use, must stay visible inside.
mount -t tmpfs -o mode=0755 tmpfs $r/run
mount -t configfs configfs $r/sys/kernel/config || fail "cannot mount configfs"
out=$(cat /vbshare/out_dir)
mkdir -p "$r$out"
mount -t 9p -o trans=virtio,version=9p2000.L,cache=none,msize=262144 vbout "$r$out" ||
  fail "cannot mount the output folder $out"

# gpio-sim: one chip, "vboard-gpio", 16 lines named sim0..sim15.
g=$r/sys/kernel/config/gpio-sim/vboard
if mkdir $g && mkdir $g/bank0; then
  echo 16 >$g/bank0/num_lines
  echo vboard-gpio >$g/bank0/label
  i=0
  while [ $i -lt 16 ]; do
    mkdir $g/bank0/line$i && echo "sim$i" >$g/bank0/line$i/name
    i=$((i + 1))
  done
  echo 1 >$g/live || log "gpio-sim: could not bring the chip up"
else
  log "gpio-sim: configfs has no gpio-sim"
fi

# What udev would do on a real system: device nodes for the video/render groups.
chroot $r /bin/sh -c '
  for f in /dev/dri/card* /dev/video* /dev/media* /dev/v4l-subdev*; do
    [ -e "$f" ] && chgrp video "$f" && chmod 0660 "$f"
  done
  for f in /dev/dri/renderD*; do [ -e "$f" ] && chgrp render "$f" && chmod 0660 "$f"; done
  true' >/dev/null 2>&1

cp /vbshare/command.sh $r/tmp/vboard-command.sh
if [ -f /vbshare/live ]; then
  { env -i chroot $r /bin/sh /tmp/vboard-command.sh </dev/null; echo $? >/vbshare/rc.tmp; } 2>&1 |
    tee /vbshare/output.log >/dev/console
  sleep 0.3  # let the serial port drain
else
  env -i chroot $r /bin/sh /tmp/vboard-command.sh </dev/null >/vbshare/output.log 2>&1
  echo $? >/vbshare/rc.tmp
fi
mv /vbshare/rc.tmp /vbshare/rc
sync
umount "$r$out" /vbshare 2>/dev/null
reboot -f
