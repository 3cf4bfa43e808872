#!/usr/bin/python3
"""Faults on the virtual board's vkms display that a kiosk must survive, in one
VM boot (run inside it by board/virtual/run-in-vm.sh, as root):

  1. Another program takes DRM master while candela shows the test pattern
     (what logind does on a VT switch: it drops master on candela's own file
     through a duplicate of its fd, then the other program opens the card and
     becomes master). Candela must keep running, log it, stop flipping, and
     once master is free again take it back, set the mode and flip again.
  2. SIGSTOP, then SIGCONT: flipping resumes.

Both with atomic modesetting and on the legacy path (CANDELA_DRM_LEGACY=1).

    drm_faults.py CANDELA

Candela runs as an unprivileged user in the video/render groups, as the
kiosk's unit does (taking master back needs no capability: the kernel lets a
process that was master become it again). What is on screen is read from the
kernel (the CRTC's framebuffer id through DRM_IOCTL_MODE_GETCRTC on a file
opened while candela is master, so this reader never becomes master itself).
Every wait polls against a deadline."""
import atexit
import ctypes
import fcntl
import os
import shutil
import signal
import sys
import tempfile
import time

# check(), wait_for() and FAILED: tests/support/checks.py
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "support"))
from checks import FAILED, check, wait_for  # noqa: E402
from drm_query import CandelaOnDrm, crtc_state, first_crtc  # noqa: E402

CANDELA = sys.argv[1]
CARD = "/dev/dri/card0"
WORK = tempfile.mkdtemp(prefix="candela-drm-faults-")
atexit.register(shutil.rmtree, WORK, True)  # nothing left in /tmp, pass or fail

DRM_IOCTL_SET_MASTER = 0x641E
DRM_IOCTL_DROP_MASTER = 0x641F
SYS_PIDFD_GETFD = 438  # x86_64


def crtc_fb(fd, crtc):
    return crtc_state(fd, crtc)[0]


def fbs_seen(fd, crtc, want, timeout):
    """The distinct framebuffers scanned out until `want` of them were seen."""
    seen = set()

    def enough():
        seen.add(crtc_fb(fd, crtc))
        return len(seen) >= want
    wait_for("%d different framebuffers on screen (flips)" % want, enough, timeout=timeout)
    return seen


def fbs_during(fd, crtc, seconds):
    """The framebuffers on screen over a fixed observation window."""
    seen = set()
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        seen.add(crtc_fb(fd, crtc))
        time.sleep(0.02)  # sampling interval of the window
    return seen


def card_fd_of(pid):
    for name in os.listdir("/proc/%d/fd" % pid):
        try:
            if os.readlink("/proc/%d/fd/%s" % (pid, name)) == CARD:
                return int(name)
        except OSError:
            pass
    raise AssertionError("candela holds no fd of " + CARD)


def take_master_from(pid):
    """Drops master on candela's own file (through a duplicate of its fd, as
    logind does), then opens the card: the first opener of a card without a
    master becomes master. Returns the new master's fd."""
    libc = ctypes.CDLL(None, use_errno=True)
    pidfd = os.pidfd_open(pid)
    dup = libc.syscall(SYS_PIDFD_GETFD, pidfd, card_fd_of(pid), 0)
    os.close(pidfd)
    if dup < 0:
        raise AssertionError("pidfd_getfd: " + os.strerror(ctypes.get_errno()))
    fcntl.ioctl(dup, DRM_IOCTL_DROP_MASTER)
    os.close(dup)
    thief = os.open(CARD, os.O_RDWR | os.O_CLOEXEC)
    fcntl.ioctl(thief, DRM_IOCTL_SET_MASTER)  # already master (0), or raises
    return thief


def run(legacy):
    print("=== %s" % ("legacy modesetting" if legacy else "atomic modesetting"), flush=True)
    log_path = os.path.join(WORK, "candela-%s.log" % ("legacy" if legacy else "atomic"))
    candela = CandelaOnDrm(CANDELA, log_path, dict(CANDELA_DRM_LEGACY="1" if legacy else "0"))
    proc, log_text, alive = candela.proc, candela.log_text, candela.alive

    fds = {}
    try:
        wait_for("candela's modeset", lambda: alive() and "modeset" in log_text(), timeout=120)
        reader = fds["reader"] = os.open(CARD, os.O_RDWR | os.O_CLOEXEC)  # candela is master: not this
        crtc = first_crtc(reader)
        before = fbs_seen(reader, crtc, 2, timeout=60)
        check(len(before) >= 2, "candela flips framebuffers %s on CRTC %d" % (sorted(before), crtc))

        # 1. Another program takes DRM master.
        fds["thief"] = take_master_from(proc.pid)
        wait_for("candela to log the loss", lambda: alive() and "lost the display" in log_text(), timeout=30)
        frozen = fbs_during(reader, crtc, 1.0)
        check(len(frozen) == 1, "without master candela shows nothing new: %s" % sorted(frozen))
        check(alive(), "candela keeps running without master")
        line = [l for l in log_text().splitlines() if "lost the display" in l]
        check(len(line) == 1 and "another program holds DRM master" in line[0],
              "one log line says what happened: %s" % line)
        t_free = time.monotonic()
        os.close(fds.pop("thief"))  # master is free again
        wait_for("candela to take the display back",
                 lambda: alive() and "DRM master is back" in log_text(), timeout=30)
        after = fbs_seen(reader, crtc, 2, timeout=60)
        took = time.monotonic() - t_free
        check(len(after) >= 2,
              "flipping again %.1f s after master was freed: %s" % (took, sorted(after)))
        check(took < 10, "back on screen within 10 s of master being free (%.1f s)" % took)

        # 2. SIGSTOP / SIGCONT (once: the display path is the same for both).
        if not legacy:
            os.kill(proc.pid, signal.SIGSTOP)
            stopped = fbs_during(reader, crtc, 1.0)
            check(len(stopped) == 1, "stopped: one framebuffer stays on screen")
            os.kill(proc.pid, signal.SIGCONT)
            again = fbs_seen(reader, crtc, 2, timeout=30)
            check(alive() and len(again) >= 2, "after SIGCONT candela flips again: %s" % sorted(again))
        os.close(fds.pop("reader"))

        proc.send_signal(signal.SIGTERM)
        proc.wait(timeout=60)
        text = log_text()
        check(proc.returncode == 0, "candela exits 0 on SIGTERM (%d)" % proc.returncode)
        check("2 modesets" in text and "1 times without DRM master" in text,
              "its summary counts the second modeset and the pause: %s" %
              [l for l in text.splitlines() if "presented" in l])
    finally:
        for fd in fds.values():  # a failed run must not leave master taken for the next
            os.close(fd)
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    if FAILED:
        print(log_text())


for legacy in (False, True):
    try:
        run(legacy)
    except AssertionError as e:
        FAILED.append(str(e))
        print("FAIL " + str(e), flush=True)
print("drm_faults: %s" % ("FAILED" if FAILED else "passed"), flush=True)
sys.exit(1 if FAILED else 0)
