#!/usr/bin/env python3
"""Inside the virtual board (tests/app/vboard_screen_power.sh runs it).

candela on vkms with a control socket: `screen off`, then `screen on`, with
the connector's DPMS read with modetest at each stage (on an atomic driver it
reports whether the CRTC is active; modetest, not an atomic client, cannot
see ACTIVE itself), on the atomic path and on the legacy one. Prints what it saw; the host side
checks it. One Python process for everything: under TCG each start costs.
  vboard_screen_power_guest.py CANDELA
"""
import json, os, re, socket, subprocess, sys, time

CANDELA = sys.argv[1]
SOCK = "/tmp/kiosk.sock"


def ask(line):
    s = socket.socket(socket.AF_UNIX)
    s.settimeout(120)
    s.connect(SOCK)
    s.sendall((line + "\n").encode())
    reply = s.makefile().readline().strip()
    s.close()
    return reply


def frame():
    return json.loads(ask("state"))["frame"]


def dpms():
    """The connector's DPMS value: 0 On, 3 Off ("?" if modetest did not say)."""
    out = subprocess.run(["modetest", "-M", "vkms", "-c"], capture_output=True, text=True).stdout
    m = re.search(r"^\s*\d+ DPMS:\n(?:\s+(?!value:).*\n)*?\s+value:\s*(\d+)", out, re.M)
    if not m:
        print("modetest said:\n" + out[:3000])
    return m.group(1) if m else "?"


def until(pred, seconds=120):
    """Bounded polling for a condition the VM reaches in its own time."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        try:
            if pred():
                return True
        except OSError:
            pass
        time.sleep(0.1)
    return False


def run(kind, legacy):
    print("=== " + kind, flush=True)
    if os.path.exists(SOCK):
        os.unlink(SOCK)
    env = dict(os.environ, HOME="/tmp", XDG_CACHE_HOME="/tmp", CANDELA_DRM_LEGACY=legacy)
    log = open("/tmp/candela-%s.log" % kind, "w")
    p = subprocess.Popen([CANDELA, "--display", "drm", "--test-pattern", "--size", "640x480",
                          "--control", SOCK], stdout=log, stderr=subprocess.STDOUT, env=env)
    if not until(lambda: os.path.exists(SOCK) and frame() >= 3, 240):
        print("no frames")
    print("on-before: dpms=" + dpms())
    print("reply-off: " + ask("screen off"))
    if not until(lambda: dpms() == "3"):
        print("DPMS never went Off")
    print("off: dpms=" + dpms())
    f1 = frame()
    time.sleep(1)  # a measuring window: the frame counter must not move in it
    f2 = frame()
    print("off-frames: %d %d" % (f1, f2))
    print("reply-on: " + ask("screen on"))
    if not until(lambda: frame() >= f2 + 3):
        print("frames did not resume")
    print("on-after: dpms=%s frame=%d" % (dpms(), frame()))
    p.terminate()
    print("candela-exit=%d" % p.wait(timeout=120))
    log.close()
    for line in open("/tmp/candela-%s.log" % kind):
        if re.search(r"drm: (screen|atomic|legacy|presented|restored)|cec: ", line):
            print(line.rstrip())
    sys.stdout.flush()


run("atomic", "0")
run("legacy", "1")
