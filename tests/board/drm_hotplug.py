#!/usr/bin/python3
"""A monitor connected later, unplugged and plugged in again, on the virtual
board's vkms display (run inside it by board/virtual/run-in-vm.sh, as root):

  1. Candela starts with vkms's connector forced off: it logs once that it
     waits for a screen, keeps running, and tells systemd so (READY=1 with
     STATUS=...: waiting for a screen, then WATCHDOG=1 pings: the loop is
     healthy) on a NOTIFY_SOCKET this test listens on; the control socket's
     `state` says "display": {"status": "waiting", ...}.
  2. The connector on: candela sets the mode and flips framebuffers; `state`
     says drawing at 640x480.
  3. Off: the CRTC shows nothing (no framebuffer); candela keeps running,
     `state` says waiting again.
  4. On again: the mode is chosen again and frames are flipped again.

The connector is forced through /sys/class/drm/card0-Virtual-1/status. On
Debian 12's kernel that sends no uevent (vkms does not poll its connector,
so the DRM core's hot-plug event never fires): each switch is followed by
`echo change > /sys/class/drm/card0/uevent`, the card's "change" uevent that
a driver's hot-plug sends (with HOTPLUG=1) on real hardware.

    drm_hotplug.py CANDELA    (CANDELA_DRM_LEGACY=1 in the environment: the legacy path)

What is on screen is read from the kernel (the CRTC's framebuffer id). Every
wait polls against a deadline."""
import atexit
import json
import os
import shutil
import signal
import socket
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "support"))
from checks import check, run_case, wait_for  # noqa: E402
from drm_query import CandelaOnDrm, crtc_state, first_crtc  # noqa: E402

CANDELA = sys.argv[1]
CARD = "/dev/dri/card0"
STATUS = "/sys/class/drm/card0-Virtual-1/status"
UEVENT = "/sys/class/drm/card0/uevent"
WORK = tempfile.mkdtemp(prefix="candela-drm-hotplug-")
atexit.register(shutil.rmtree, WORK, True)  # nothing left in /tmp, pass or fail

def ask(path, line):
    """One control-socket command, its one-line reply."""
    s = socket.socket(socket.AF_UNIX)
    s.settimeout(30)
    try:
        s.connect(path)
        s.sendall((line + "\n").encode())
        return s.makefile().readline().strip()
    finally:
        s.close()


def connector(state):
    with open(STATUS, "w") as f:
        f.write(state)
    with open(UEVENT, "w") as f:  # the hot-plug uevent (see above)
        f.write("change")


def case_hotplug():
    connector("off")
    reader = os.open(CARD, os.O_RDWR | os.O_CLOEXEC)
    crtc = first_crtc(reader)
    console = crtc_state(reader, crtc)  # what the console left on the CRTC
    os.close(reader)
    sock_path = os.path.join(WORK, "notify")
    notify = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
    notify.bind(sock_path)
    os.chmod(WORK, 0o755)
    os.chmod(sock_path, 0o777)
    messages = []

    def received(pred):
        while True:
            try:
                messages.append(notify.recv(4096, socket.MSG_DONTWAIT).decode())
            except BlockingIOError:
                break
        return [m for m in messages if pred(m)]

    control_dir = os.path.join(WORK, "control")  # candela runs as nobody
    os.mkdir(control_dir)
    os.chmod(control_dir, 0o777)
    control = os.path.join(control_dir, "candela.sock")
    log_path = os.path.join(WORK, "candela.log")
    candela = CandelaOnDrm(CANDELA, log_path,
                           dict(NOTIFY_SOCKET=sock_path, WATCHDOG_USEC="400000"),
                           args=("--test-pattern", "--size", "640x480", "--control", control))
    proc, log_text, alive = candela.proc, candela.log_text, candela.alive

    def display_state():
        """The `state` reply's "display" object (None before the socket is up)."""
        alive()
        try:
            return json.loads(ask(control, "state"))["display"]
        except (FileNotFoundError, ConnectionRefusedError):  # not listening yet
            return None

    def fbs_seen(want, timeout):
        seen = set()

        def enough():
            alive()
            fb = crtc_state(reader, crtc)[0]
            if fb and fb != console[0]:  # candela's, not the console's
                seen.add(fb)
            return len(seen) >= want
        wait_for("%d different framebuffers on screen (flips)" % want, enough, timeout=timeout)
        return seen

    reader = None
    try:
        # 1. No screen: waiting, alive, ready, pinging.
        wait_for("candela to say it waits for a screen",
                 lambda: alive() and "waiting for one" in log_text(), timeout=60)
        status = wait_for("READY=1 with the waiting status",
                          lambda: received(lambda m: "READY=1" in m and "waiting for a screen" in m),
                          timeout=30)
        check(True, "systemd is told: %r" % status[0])
        pings = wait_for("two watchdog pings while waiting",
                         lambda: alive() and received(lambda m: m == "WATCHDOG=1")[1:], timeout=10)
        check(len(pings) >= 1, "WATCHDOG=1 pings go on while waiting (the loop is healthy)")
        check(alive(), "candela keeps running without a screen")
        shown = wait_for("`state` to say it waits for a screen",
                         lambda: display_state() == dict(status="waiting", width=None, height=None),
                         timeout=30, interval=0.1)
        check(shown, "`state` while no monitor is connected: %s" % display_state())
        check(log_text().count("waiting for one") == 1, "the wait is logged once")
        reader = os.open(CARD, os.O_RDWR | os.O_CLOEXEC)  # candela is master: not this
        check(crtc_state(reader, crtc) == console,
              "no mode set while no monitor is connected (CRTC as the console left it: %s)" %
              (console,))

        # 2. A monitor is connected.
        connector("on")
        wait_for("candela to take the screen",
                 lambda: alive() and "a screen on Virtual-1" in log_text(), timeout=30)
        first = fbs_seen(2, timeout=60)
        fb, w, h = crtc_state(reader, crtc)
        check((w, h) == (640, 480), "mode 640x480 set on the connected screen (%dx%d)" % (w, h))
        check(len(first) >= 2, "frames presented after the hot-plug: %s" % sorted(first))
        drawing = dict(status="drawing", width=640, height=480)
        wait_for("`state` to say it draws at 640x480", lambda: display_state() == drawing,
                 timeout=10, interval=0.1)
        check(display_state() == drawing, "`state` once the monitor is there: %s" % drawing)

        # 3. Unplugged: drawing pauses, the CRTC shows nothing.
        connector("off")
        wait_for("candela to notice the screen went away",
                 lambda: alive() and "went away" in log_text(), timeout=30)
        wait_for("the CRTC without a framebuffer", lambda: crtc_state(reader, crtc)[0] == 0, timeout=10)
        check(alive(), "candela keeps running after the unplug")
        waiting = dict(status="waiting", width=640, height=480)
        wait_for("`state` to say it waits again", lambda: display_state() == waiting,
                 timeout=10, interval=0.1)
        check(display_state() == waiting,
              "`state` after the unplug: %s (the size drawn last)" % waiting)

        # 4. Plugged in again: the mode is set again, frames again.
        connector("on")
        wait_for("candela to take the screen again",
                 lambda: alive() and log_text().count("a screen on Virtual-1") == 2, timeout=30)
        again = fbs_seen(2, timeout=60)
        check(len(again) >= 2, "frames presented after the second hot-plug: %s" % sorted(again))
        text = log_text()
        check(text.count(" modeset 640x480") == 2,  # atomic, or legacy (CANDELA_DRM_LEGACY=1)
              "the mode was chosen and set again: %s" %
              [l for l in text.splitlines() if "modeset" in l])

        proc.send_signal(signal.SIGTERM)
        proc.wait(timeout=60)
        check(proc.returncode == 0, "candela exits 0 on SIGTERM (%d)" % proc.returncode)
    finally:
        if reader is not None:
            os.close(reader)
        if proc.poll() is None:
            proc.kill()
            proc.wait()
        print(log_text())


run_case("hotplug", globals())
