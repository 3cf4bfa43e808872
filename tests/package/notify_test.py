#!/usr/bin/python3
"""candela's systemd notifications (firmware/app/sd_notify.h), as systemd sees them.

notify_test.py CANDELA SCRATCH

Listens on its own NOTIFY_SOCKET (AF_UNIX datagrams, as systemd does) while
candela runs to completion:
  - headless, 45 frames at 30 fps, WATCHDOG_USEC=2 (a period shorter than any frame):
    READY=1 first, naming frame 1 as presented; one WATCHDOG=1 after every
    presented frame (45); STATUS= with the scene and its fps; STOPPING=1 last
  - the same with WATCHDOG_PID of another process: no pings (sd_watchdog_enabled)
  - a display that cannot open (drm on /dev/null): no READY, no ping
  - an abstract socket (@name) works as a path does
"""
import os
import select
import socket
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "support"))
from programs import program  # noqa: E402

candela, scratch = [os.path.abspath(a) for a in sys.argv[1:3]]
candela = program(candela)  # the command: an emulator first in a cross build
os.makedirs(scratch, exist_ok=True)
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what)


def run(args, env_extra, abstract=False):
    path = os.path.join(scratch, "notify.sock")
    if os.path.exists(path):
        os.unlink(path)
    s = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
    s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 1 << 20)
    if abstract:
        name = "candela-notify-test-%d" % os.getpid()
        s.bind("\0" + name)
        addr = "@" + name
    else:
        s.bind(path)
        addr = path
    env = dict(os.environ, NOTIFY_SOCKET=addr, **env_extra)
    # Read while it runs, as systemd does: a datagram socket queues only
    # net.unix.max_dgram_qlen (10) messages, and candela drops what does not fit
    # rather than wait. select() wakes on a datagram; its timeout only lets
    # the loop notice that candela has exited.
    p = subprocess.Popen(candela + args, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    msgs = []
    while True:
        if select.select([s], [], [], 0.2)[0]:
            msgs.append(s.recv(4096).decode())
        elif p.poll() is not None:
            break
    s.setblocking(False)
    while True:
        try:
            msgs.append(s.recv(4096).decode())
        except BlockingIOError:
            break
    s.close()
    out, err = p.communicate()
    return subprocess.CompletedProcess(p.args, p.returncode, out, err), msgs


# Paced at 30 fps (--realtime): 33 ms between frames leaves the reader time.
headless = ["--display", "headless", "--test-pattern", "--size", "64x64", "--frames", "45", "--realtime", "--fps", "30"]
r, msgs = run(headless, {"WATCHDOG_USEC": "2"})
print("headless:", msgs[:3], "...", msgs[-2:], "(%d datagrams)" % len(msgs))
check(r.returncode == 0, "candela exited %d: %s" % (r.returncode, r.stderr[-300:]))
check(msgs and msgs[0].startswith("READY=1\n") and "frame 1 presented" in msgs[0],
      "the first datagram is not READY=1 after frame 1: %r" % msgs[:1])
check(sum(m.startswith("READY=1") for m in msgs) == 1, "READY=1 sent more than once")
pings = [i for i, m in enumerate(msgs) if m == "WATCHDOG=1"]
check(len(pings) == 45, "expected one WATCHDOG=1 per presented frame (45), got %d" % len(pings))
# 1.5 s at 30 fps: at least one STATUS= with the frame rate, in (0, 31].
rates = [m for m in msgs if m.startswith("STATUS=") and m.endswith(" fps")]
check(rates, "no STATUS= with the frame rate: %r" % msgs)
for m in rates:
    fps = float(m.split(": ")[-1][:-4])
    check(m.startswith("STATUS=<built-in test-pattern>: ") and 0 < fps <= 31, "bad STATUS=: %r" % m)
check(pings and pings[0] > 0, "a WATCHDOG=1 came before READY=1")
check(msgs and msgs[-1] == "STOPPING=1", "the last datagram is not STOPPING=1: %r" % msgs[-1:])
check(all(m.startswith(("READY=1", "WATCHDOG=1", "STATUS=", "STOPPING=1")) for m in msgs),
      "unexpected datagrams: %r" % [m for m in msgs if not m.startswith(("READY", "WATCHDOG", "STATUS", "STOPPING"))])

r, msgs = run(headless, {"WATCHDOG_USEC": "2", "WATCHDOG_PID": "1"})
check(r.returncode == 0 and msgs and msgs[0].startswith("READY=1"), "READY=1 missing with WATCHDOG_PID=1")
check("WATCHDOG=1" not in msgs, "pinged a watchdog meant for another process (WATCHDOG_PID=1)")

r, msgs = run(["--display", "drm", "--drm-device", "/dev/null", "--frames", "1"], {"WATCHDOG_USEC": "2"})
check(r.returncode != 0 and not any(m.startswith(("READY=1", "WATCHDOG=1")) for m in msgs),
      "a display that never presented reported READY or a ping: rc %d %r" % (r.returncode, msgs))

r, msgs = run(headless, {}, abstract=True)
check(r.returncode == 0 and msgs and msgs[0].startswith("READY=1") and "WATCHDOG=1" not in msgs,
      "abstract NOTIFY_SOCKET without WATCHDOG_USEC: %r" % msgs[:3])

if failures:
    sys.exit("%d check(s) failed" % len(failures))
print("notify: OK")
