#!/usr/bin/python3
"""Input tests against real kernel drivers on the virtual board (gpio-sim,
vivid, vimc through libcamera), run inside the VM by
board/virtual/run-in-vm.sh; the camera_absent, camera_libcamera_absent and
record_no_camera cases also run on the host.

    vboard_inputs.py CASE BUILD_DIR

Every wait polls observable state (the control socket's `state`, a process's
exit, a manifest) against a deadline; nothing sleeps to synchronise."""
import atexit
import glob
import json
import os
import re
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import time
import zlib

# check(), wait_for() and FAILED: tests/support/checks.py
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "support"))
from checks import FAILED, check, run_case, wait_for  # noqa: E402
from programs import program  # noqa: E402

CASE, BUILD = sys.argv[1], os.path.abspath(sys.argv[2])
CANDELA = program(os.path.join(BUILD, "firmware", "candela"))
RECORD = program(os.path.join(BUILD, "tools", "record", "candela-record"))
TOOL = program(os.path.join(BUILD, "tools", "candela-tool", "candela-tool"))
WORK = tempfile.mkdtemp(prefix="candela-vb-")
atexit.register(shutil.rmtree, WORK, True)  # nothing left in /tmp, pass or fail


class Candela:
    def __init__(self, scene_toml, extra=(), nice=0):
        self.scene = os.path.join(WORK, "scene.toml")
        with open(self.scene, "w") as f:
            f.write(scene_toml)
        self.sock_path = os.path.join(WORK, "ctl")
        self.log_path = os.path.join(WORK, "candela.log")
        self.log = open(self.log_path, "w")
        self.proc = subprocess.Popen(
            ["nice", "-n", str(nice), *CANDELA, "--display", "headless", "--realtime", "--size", "32x24", "--scene", self.scene,
             "--control", self.sock_path, *extra], stdout=self.log, stderr=subprocess.STDOUT)
        self.sock = None
        wait_for("the control socket", self._connect, timeout=60)

    def _connect(self):
        if self.proc.poll() is not None:
            raise AssertionError("candela exited early:\n" + open(self.log_path).read())
        if not os.path.exists(self.sock_path):
            return False
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        try:
            s.connect(self.sock_path)
        except OSError:
            s.close()
            return False
        s.settimeout(20)
        self.sock, self.buf = s, b""
        return True

    def ask(self, line):
        self.sock.sendall(line.encode() + b"\n")
        while b"\n" not in self.buf:
            chunk = self.sock.recv(65536)
            if not chunk:
                raise AssertionError("control socket closed")
            self.buf += chunk
        reply, self.buf = self.buf.split(b"\n", 1)
        return reply.decode()

    def state(self):
        return json.loads(self.ask("state"))

    def input(self, name):
        return next(i for i in self.state()["inputs"] if i["name"] == name)

    def log_text(self):
        self.log.flush()
        return open(self.log_path).read()

    def stop(self):
        self.proc.terminate()
        rc = self.proc.wait(timeout=30)
        check(rc == 0, "candela exits cleanly on SIGTERM (status %s)" % rc)


# --- gpio-sim ------------------------------------------------------------------
def sim_line(n):
    paths = glob.glob("/sys/devices/platform/gpio-sim.*/gpiochip*/sim_gpio%d/pull" % n)
    if not paths:
        raise AssertionError("no gpio-sim line %d (is this the virtual board?)" % n)
    return paths[0]


def pull(n, up):
    with open(sim_line(n), "w") as f:
        f.write("pull-up" if up else "pull-down")


def gpio_scene(inputs, wind="gust_seconds = 4.0\ngust_speed = 2.0\n"):
    # Plane S at the origin: wind reaches the sampled point with no travel
    # delay or attenuation, so `state` shows what the sensor asked for.
    return "[wind]\nplane_distance = 0.0\n" + wind + "".join("[[input]]\n" + i + "\n" for i in inputs)


def case_gpio_button_gust():
    pull(3, False)
    c = Candela(gpio_scene(['kind = "button"\nname = "b"\nchip = "vboard-gpio"\n'
                            'line_name = "sim3"\nside = "left"\ndebounce_ms = 10\n']))
    wait_for("the button line to be requested", lambda: c.input("b")["status"] == "ok")
    check(c.state()["wind"]["x"] == 0, "calm before the press")
    t0 = time.monotonic()
    pull(3, True)
    st = wait_for("the gust", lambda: (lambda s: s if s["wind"]["x"] > 0.05 else None)(c.state()),
                  timeout=10)
    seen = time.monotonic() - t0
    b = next(i for i in st["inputs"] if i["name"] == "b")
    check(b["events"] == 1 and b["activations"] == 1, "one press, one gust event (%s)" % b)
    check(st["wind"]["z"] == 0, "the gust from the left blows along +x only")
    print("latency: edge -> wind field %.3f ms (frame loop measured); edge -> visible in state %.0f ms"
          % (st["latency_ms"]["last"], seen * 1000), flush=True)
    check(st["latency_ms"]["last"] is not None and st["latency_ms"]["last"] < 1000,
          "edge-to-wind latency under 1 s even under emulation")
    pull(3, False)
    c.stop()


def case_gpio_debounce_burst():
    pull(4, False)
    c = Candela(gpio_scene(['kind = "button"\nname = "b"\nchip = "vboard-gpio"\n'
                            'line = 4\nside = "right"\ndebounce_ms = 400\n']))
    wait_for("the button line", lambda: c.input("b")["status"] == "ok")
    t0 = time.monotonic()
    for _ in range(4):  # 8 edges, ending low again
        pull(4, True)
        pull(4, False)
    burst = time.monotonic() - t0
    check(burst < 0.3, "the burst (%.0f ms) is shorter than the 400 ms debounce" % (burst * 1000))
    # A real press afterwards is the synchronisation point: once it counts, the
    # burst before it has long been decided.
    pull(4, True)
    b = wait_for("the real press to reach the wind field",
                 lambda: (lambda i: i if i["activations"] >= 1 and i["events"] >= 1 else None)(c.input("b")),
                 timeout=15)
    check(b["activations"] == 1 and b["events"] == 1,
          "the burst was swallowed; only the real press counted (%s)" % b)
    st = wait_for("the gust", lambda: (lambda s: s if s["wind"]["x"] < 0 else None)(c.state()), timeout=10)
    check(st["wind"]["x"] < 0, "the gust from the right blows toward -x")
    pull(4, False)
    c.stop()


def case_gpio_anemometer_rate():
    pull(5, False)
    rate, cal = 5.0, 0.5
    c = Candela(gpio_scene(['kind = "anemometer"\nname = "a"\nchip = "vboard-gpio"\n'
                            'line_name = "sim5"\ncalibration = %g\nwindow_s = 2.0\n'
                            'debounce_ms = 2\nside = "left"\n' % cal], wind="speed = 0.0\n"),
               nice=15)
    wait_for("the anemometer line", lambda: c.input("a")["status"] == "ok")
    # candela's headless loop renders flat out on the VM's one CPU: let the
    # pulse generator come first so the train keeps its rate.
    period = 1.0 / rate
    start = time.monotonic() + 0.1
    ups, errors = [], []
    for k in range(int(5 * rate)):
        at = start + k * period  # absolute deadlines: no drift in the mean rate
        while time.monotonic() < at:
            time.sleep(min(0.005, max(0.0, at - time.monotonic())))
        ups.append(time.monotonic())
        pull(5, True)
        while time.monotonic() < at + 0.04:
            time.sleep(0.005)
        pull(5, False)
        if k * period > 2.5 and k % 4 == 0:  # the 2 s window is full of pulses
            # Read once candela has seen every pulse so far: the emulated CPU
            # (candela niced, a busy host) may run its GPIO thread late, and
            # a speed read before the last pulse counts one pulse fewer.
            wait_for("pulse %d seen" % len(ups), lambda: c.input("a")["activations"] >= len(ups),
                     timeout=5)
            a = c.input("a")  # its speed, from that pulse's interval on
            window = [t for t in ups if t > ups[-1] - 2.0]
            made = (len(window) - 1) / (window[-1] - window[0])
            got = a["speed"]
            errors.append(abs(got - made * cal) / (made * cal))
            # The wind field follows the anemometer (a frame later).
            wait_for("the wind to follow the anemometer's %.3f m/s" % got,
                     lambda: abs(c.state()["wind"]["x"] - got) <= 0.05 * got, timeout=5)
            print("anemometer: train %.3f Hz (nominal %g) -> %.3f m/s, want %.3f" %
                  (made, rate, got, made * cal), flush=True)
            check(abs(made - rate) / rate < 0.1, "the generator kept the rate (%.3f Hz)" % made)
    check(max(errors) < 0.05, "anemometer speed within 5%% (worst %.1f%%)" % (max(errors) * 100))
    # The wind stops: the speed falls to nothing.
    wait_for("the wind to drop", lambda: c.state()["wind"]["x"] == 0, timeout=10)
    check(True, "calm again after the pulses stop")
    c.stop()


def case_gpio_chip_removed():
    pull(6, False)
    c = Candela(gpio_scene(['kind = "presence"\nname = "p"\nchip = "vboard-gpio"\n'
                            'line_name = "sim6"\nside = "front"\nstrength = 0.4\n'
                            'debounce_ms = 0\n']))
    wait_for("the presence line", lambda: c.input("p")["status"] == "ok")
    pull(6, True)
    wait_for("the draught", lambda: c.state()["wind"]["z"] < -0.3, timeout=10)
    live = "/sys/kernel/config/gpio-sim/vboard/live"
    with open(live, "w") as f:
        f.write("0")
    p = wait_for("the loss to be noticed",
                 lambda: (lambda i: i if i["status"].startswith("lost") else None)(c.input("p")),
                 timeout=10)
    check("lost" in p["status"], "state reports the line lost: %s" % p["status"])
    # The input thread marks the loss first; the frame loop applies the calm
    # on its next frame.
    st = wait_for("the draught to stop", lambda: (lambda s: s if s["wind"]["z"] == 0 else None)(c.state()),
                  timeout=10)
    check(st["wind"]["z"] == 0, "the draught stops with the sensor gone (calm)")
    f0 = c.state()["frame"]
    wait_for("frames to keep coming", lambda: c.state()["frame"] > f0 + 5, timeout=20)
    check(c.proc.poll() is None, "the display keeps running")
    log = c.log_text()
    check(log.count("lost:") == 1, "the loss is logged once:\n" + log)
    # The chip comes back: the sensor is found again.
    with open(live, "w") as f:
        f.write("1")
    wait_for("the line to come back", lambda: c.input("p")["status"] == "ok", timeout=15)
    check(True, "the sensor is used again once its chip returns")
    c.stop()


# --- camera ------------------------------------------------------------------------
def vivid_set(dev, **ctrls):
    subprocess.run(["v4l2-ctl", "-d", dev, "-c", ",".join("%s=%s" % kv for kv in ctrls.items())],
                   check=True)


def vivid_menu(dev, ctrl, label):
    out = subprocess.run(["v4l2-ctl", "-d", dev, "-L"], capture_output=True, text=True).stdout
    block = out.split(ctrl, 1)[1]
    m = re.search(r"^\s*(\d+): %s\s*$" % re.escape(label), block, re.M)
    if not m:
        raise AssertionError("vivid has no %s menu item %r" % (ctrl, label))
    return int(m.group(1))


def case_camera_vivid_motion():
    dev = "/dev/video0"
    cross = vivid_menu(dev, "test_pattern", "Ten Pixels Wide Cross")
    vivid_set(dev, test_pattern=cross, osd_text_mode=2,
              horizontal_movement=vivid_menu(dev, "horizontal_movement", "Move Right Fast"))
    c = Candela("[wind]\nplane_distance = 0.0\ngust_seconds = 6.0\n[[input]]\nkind = \"camera\"\nname = \"cam\"\n"
                "device = \"%s\"\nmirror = false\nsensitivity = 8\ncooldown_ms = 0\n" % dev)
    wait_for("camera frames", lambda: c.input("cam").get("frames", 0) > 3, timeout=60)
    st = wait_for("a gust to the right",
                  lambda: (lambda s: s if s["wind"]["x"] > 0.05 else None)(c.state()), timeout=60)
    cam = next(i for i in st["inputs"] if i["name"] == "cam")
    check(cam["gusts"] >= 1, "moving pattern -> gust to the right (%s)" % cam)
    # Still pattern: frames keep coming, no new gusts.
    vivid_set(dev, horizontal_movement=vivid_menu(dev, "horizontal_movement", "No Movement"))
    f0 = c.input("cam")["frames"]
    wait_for("frames of the still pattern", lambda: c.input("cam")["frames"] > f0 + 4, timeout=60)
    g0, f1 = c.input("cam")["gusts"], c.input("cam")["frames"]
    wait_for("more still frames", lambda: c.input("cam")["frames"] > f1 + 20, timeout=120)
    check(c.input("cam")["gusts"] == g0, "still frames -> no gust")
    vivid_set(dev, horizontal_movement=vivid_menu(dev, "horizontal_movement", "Move Left Fast"))
    wait_for("a gust to the left",
             lambda: (lambda s: s if s["wind"]["x"] < -0.05 else None)(c.state()), timeout=60)
    check(True, "moving left -> gust to the left")
    print("camera thread: %s" % c.input("cam"), flush=True)
    c.stop()


def case_camera_absent():
    c = Candela("[[input]]\nkind = \"camera\"\nname = \"cam\"\ndevice = \"/dev/video63\"\n")
    cam = wait_for("the camera status", lambda: (lambda i: i if "cannot open" in i["status"] else None)(c.input("cam")))
    check("No such file" in cam["status"], "state says why: %s" % cam["status"])
    f0 = c.state()["frame"]
    wait_for("frames to keep coming", lambda: c.state()["frame"] > f0 + 5)
    check(c.log_text().count("/dev/video63") == 1, "logged once")
    c.stop()


def case_camera_libcamera_absent():
    c = Candela("[[input]]\nkind = \"camera\"\nname = \"cam\"\nbackend = \"libcamera\"\n"
                "device = \"candela-test/absent-camera\"\n")
    cam = wait_for("the camera status",
                   lambda: (lambda i: i if "libcamera" in i["status"] else None)(c.input("cam")))
    check("no camera \"candela-test/absent-camera\"" in cam["status"] or "not built" in cam["status"],
          "state says why: %s" % cam["status"])
    f0 = c.state()["frame"]
    wait_for("frames to keep coming", lambda: c.state()["frame"] > f0 + 5)
    check(c.log_text().count("candela-test/absent-camera") == 1, "logged once:\n" + c.log_text())
    c.stop()


# --- libcamera on vimc ----------------------------------------------------------------
def start_udev():
    """libcamera finds vimc's media graph only through udev; udevd and udevadm
    refuse to work in the VM's chroot unless told to (see board/virtual/README.md)."""
    if not os.path.exists("/lib/systemd/systemd-udevd"):
        raise AssertionError("no /lib/systemd/systemd-udevd: install udev (board/install-deps.sh)")
    env = dict(os.environ, SYSTEMD_IGNORE_CHROOT="1")
    subprocess.run(["/lib/systemd/systemd-udevd", "--daemon"], env=env, check=True)
    subprocess.run(["udevadm", "trigger"], env=env, check=True)
    subprocess.run(["udevadm", "settle", "--timeout=60"], env=env, check=True)


def vimc_camera_id():
    start_udev()
    p = subprocess.run(["cam", "-l"], capture_output=True, text=True, timeout=60)
    m = re.search(r"^\d+: .*\((.*Sensor B)\)\s*$", p.stdout, re.M)
    if not m:
        raise AssertionError("cam -l lists no vimc Sensor B:\n" + p.stdout + p.stderr)
    return m.group(1)


# An unprivileged user in the video group, as on a kiosk.
AS_USER = ["setpriv", "--reuid=65534", "--regid=65534", "--groups=video", "--inh-caps=-all"]


def case_record_libcamera_vimc():
    cam_id = vimc_camera_id()
    os.chmod(WORK, 0o755)  # mkdtemp made it private to root
    dest = os.path.join(WORK, "shared")
    os.makedirs(dest)
    os.chmod(dest, 0o777)
    out = os.path.join(dest, "clip")
    n = 12
    p = subprocess.run(AS_USER + [*RECORD, "--backend", "libcamera", "--device", cam_id, "--out", out,
                                  "--size", "320x240", "--fps", "10", "--frames", str(n)],
                       capture_output=True, text=True, timeout=180, env=dict(os.environ, HOME="/tmp"))
    print("candela-record: status %d: %s" % (p.returncode, p.stderr.strip()), flush=True)
    check(p.returncode == 0, "recording through libcamera as an unprivileged user succeeds")
    m = check_recording(out, True)
    check(m["backend"] == "libcamera" and m["device"] == cam_id,
          "manifest names the backend and camera (%s, %s)" % (m["backend"], m["device"]))
    check(m["pixel_format"] in ("RGB3", "BGR3"), "vimc's BGR888/RGB888 recorded as %s" % m["pixel_format"])
    seqs = [f["sequence"] for f in m["frames"]]
    check(len(seqs) == n and seqs == list(range(seqs[0], seqs[0] + n)),
          "%d frames with consecutive sequence numbers (%s)" % (n, seqs))
    ts = [f["timestamp_ns"] for f in m["frames"]]
    check(all(b > a for a, b in zip(ts, ts[1:])), "timestamps increase")
    check(m["dropped"]["count"] == 0, "nothing dropped")
    check(set(m["locked"]) >= {"AeEnable", "AnalogueGain", "AwbEnable"},
          "what was locked is listed: %s" % m["locked"])
    # vimc's colour bars are not flat: the frames hold a picture, not zeros.
    first = os.path.join(out, m["frames"][0]["file"])
    check(os.path.getsize(first) > 200, "the first frame holds an image (%d bytes)" % os.path.getsize(first))
    check_dataset(out, m)


# After the camera goes, the recorder must be done within this many seconds
# (2 s for libcamera's silent timeout, then the preview's and writers' shutdown
# under TCG). It took minutes when libcamera's thread spun on the dead nodes.
UNPLUG_EXIT_BOUND_S = float(os.environ.get("CANDELA_UNPLUG_EXIT_BOUND_S", "25"))


def case_record_libcamera_unplugged():
    cam_id = vimc_camera_id()
    out = os.path.join(WORK, "clip")
    # With the live preview on vkms, as a user filming on the board would.
    # libcamera 0.0.3 is not told of the unbind (no disconnected signal): its
    # thread kept polling the unbound camera's dead nodes, spinning the VM's one
    # vCPU, and starved the preview thread (nice +10) that record() joins
    # before it writes the final manifest, so the recorder exited minutes late.
    # libcamera_capture.cpp now finds the removed nodes and silences them.
    env = {k: v for k, v in os.environ.items() if k != "DISPLAY"}
    proc = subprocess.Popen([*RECORD, "--backend", "libcamera", "--device", cam_id, "--out", out,
                             "--size", "320x240", "-n", "100000", "--preview", "drm"],
                            stderr=subprocess.PIPE, text=True, env=env)
    wait_for_manifest_frames(out, 5)
    # Unbinding the driver removes the media graph, as for a yanked camera.
    with open("/sys/bus/platform/drivers/vimc/unbind", "w") as f:
        f.write("vimc.0")
    t0 = time.monotonic()
    try:
        _, err = proc.communicate(timeout=180)
    except subprocess.TimeoutExpired:
        proc.kill()
        _, err = proc.communicate()
    took = time.monotonic() - t0
    print("candela-record: status %d after %.1f s: %s" % (proc.returncode, took, err.strip()), flush=True)
    check(took < UNPLUG_EXIT_BOUND_S,
          "the recorder is done %.1f s after the camera went (bound %.0f s)" % (took, UNPLUG_EXIT_BOUND_S))
    check(proc.returncode == 5, "exit status 5 (camera lost): %d" % proc.returncode)
    check("device nodes were removed" in err, "clear message: the camera's nodes were removed")
    check("preview: showing the recording on drm" in err, "the preview was on the DRM screen")
    m = check_recording(out, False)
    check(m["frame_count"] >= 5, "frames so far kept (%d)" % m["frame_count"])
    check(m["preview"]["backend"] == "drm" and m["preview"]["shown"] > 0,
          "the manifest records the preview: %s" % m["preview"])


def case_camera_libcamera_vimc():
    vimc_camera_id()
    c = Candela("[wind]\nplane_distance = 0.0\ngust_seconds = 6.0\n[[input]]\nkind = \"camera\"\n"
                "name = \"cam\"\nbackend = \"libcamera\"\ndevice = \"auto\"\nmirror = false\n"
                "sensitivity = 8\ncooldown_ms = 0\n")
    cam = wait_for("camera frames", lambda: (lambda i: i if i.get("frames", 0) > 3 else None)(c.input("cam")),
                   timeout=90)
    check(cam["status"] == "ok", "the camera input is ok: %s" % cam)
    check("Sensor B" in cam.get("device", ""), "it opened vimc's Sensor B: %s" % cam.get("device"))
    f1 = cam["frames"]
    cam = wait_for("more still frames",
                   lambda: (lambda i: i if i["frames"] > f1 + 20 else None)(c.input("cam")), timeout=120)
    check(cam["gusts"] == 0, "still colour bars -> no gust (%s)" % cam)
    check(c.state()["wind"]["x"] == 0, "and no wind")
    check("via libcamera" in c.log_text(), "the log says it went through libcamera")
    # The thread's own figures come every 2 s of capture.
    cam = wait_for("the camera thread's figures",
                   lambda: (lambda i: i if i["fps"] > 0 else None)(c.input("cam")), timeout=60)
    check(cam["gusts"] == 0, "still no gust")
    if cam["fps"] > 0:
        print("camera thread (libcamera, vimc, under TCG: not a performance figure): %.1f fps, "
              "%.2f%% of a core, %.2f ms CPU per frame" %
              (cam["fps"], cam["cpu_percent"], cam["cpu_percent"] * 10 / cam["fps"]), flush=True)
    c.stop()


def cpu_seconds(pid):
    """User + system CPU time of a whole process (all its threads), in seconds."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def case_camera_libcamera_unplugged():
    """The kiosk's camera, through libcamera, unbound mid-run: the input says
    so, the display keeps running, and nothing is left spinning on the dead
    camera (libcamera 0.0.3 is not told and polled its removed nodes in a loop
    that took the whole vCPU, for as long as the kiosk ran). The retries say
    the camera is gone (not "busy"), and when it is bound again the kiosk
    reads it again."""
    vimc_camera_id()
    c = Candela("[[input]]\nkind = \"camera\"\nname = \"cam\"\nbackend = \"libcamera\"\n"
                "device = \"auto\"\n", extra=("--fps", "5"))
    wait_for("camera frames", lambda: c.input("cam").get("frames", 0) > 3, timeout=90)
    with open("/sys/bus/platform/drivers/vimc/unbind", "w") as f:
        f.write("vimc.0")
    cam = wait_for("the loss to be noticed",
                   lambda: (lambda i: i if i["status"] != "ok" else None)(c.input("cam")), timeout=30)
    check("device nodes were removed" in cam["status"], "state says the camera's nodes went: %s" % cam["status"])
    # CPU of the whole kiosk over 3 s: a 5 fps 32x24 render takes a little;
    # a thread spinning on the dead nodes took all of the one vCPU.
    t0, cpu0 = time.monotonic(), cpu_seconds(c.proc.pid)
    wait_for("3 s of running", lambda: time.monotonic() - t0 >= 3.0, timeout=10)
    share = (cpu_seconds(c.proc.pid) - cpu0) / (time.monotonic() - t0)
    check(share < 0.5, "nothing spins on the dead camera: the kiosk used %.0f%% of a CPU" % (100 * share))
    f0 = c.state()["frame"]
    wait_for("frames to keep coming", lambda: c.state()["frame"] > f0 + 5, timeout=30)
    check(c.proc.poll() is None, "the display keeps running")
    check("device nodes were removed" in c.log_text(), "the log says what happened")
    # Its retries (every 2 s) say what is really the matter: the camera is
    # not there (libcamera, not told, listed it still, held by this process:
    # the retries said "busy (in use by another program)").
    cam = wait_for("a retry's status",
                   lambda: (lambda i: i if "no camera found" in i["status"] else None)(c.input("cam")),
                   timeout=30)
    check("libcamera lists none" in cam["status"], "the retries say the camera is gone: %s" % cam["status"])
    check("busy" not in c.log_text(), "no retry calls it busy:\n" + c.log_text())
    # The camera comes back (vimc bound again): the kiosk opens it again
    # (libcamera 0.0.3 used to abort the process: a camera registered twice).
    frames_lost = cam["frames"]
    with open("/sys/bus/platform/drivers/vimc/bind", "w") as f:
        f.write("vimc.0")
    cam = wait_for("the camera to be opened again and deliver frames",
                   lambda: (lambda i: i if i["status"] == "ok" and i["frames"] > frames_lost + 1 else None)(
                       c.input("cam")), timeout=60)
    check(c.proc.poll() is None, "the kiosk survives the camera coming back and reads it again: %s" % cam)
    check("taking it off libcamera's list" in c.log_text(), "the log says what was done")
    c.stop()


# --- candela-record ----------------------------------------------------------------
def png_size(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n" or data[-8:-4] != b"IEND":
        return None
    w, h, depth, ctype = struct.unpack(">IIBB", data[16:26])
    return w, h, ctype


def wait_for_manifest_frames(out, n):
    """Until a running recording's manifest (rewritten every second) lists n frames."""
    def listed():
        try:
            return json.load(open(os.path.join(out, "manifest.json")))["frame_count"] >= n
        except (OSError, ValueError):  # not written yet, or caught mid-rename
            return False
    wait_for("%d frames in the manifest" % n, listed, timeout=60)


def check_dataset(out, m):
    """The recording is a dataset as it stands: candela-tool ingest reads it
    unchanged, every frame, at the rate the camera's timestamps show (some
    cameras, vimc among them, ignore the rate asked for and report none: a
    dataset at the wrong rate would play at the wrong speed)."""
    check(re.search(r"\b[0-9.]+ fps\b", open(os.path.join(out, "info.txt")).read()) is not None,
          "info.txt gives the rate the way ingest reads it")
    seqs = [f["sequence"] for f in m["frames"]]
    ts = [f["timestamp_ns"] for f in m["frames"]]
    rate = (seqs[-1] - seqs[0]) / ((ts[-1] - ts[0]) * 1e-9)
    check(abs(m["measured_fps"] - rate) < 0.01 * rate,
          "manifest measured_fps %.2f matches the timestamps (%.2f)" % (m["measured_fps"], rate))
    ds = os.path.join(WORK, "clip_dataset")
    p = subprocess.run([*TOOL, "ingest", out, "--out", ds, "--width", "32", "--height", "48"],
                       capture_output=True, text=True, timeout=120)
    check(p.returncode == 0, "candela-tool ingest accepts the recording: " + p.stderr.strip()[-300:])
    if p.returncode == 0:
        d = json.load(open(os.path.join(ds, "manifest.json")))
        got = d["clips"][0]["fps"]
        check(d["frames"] == len(seqs) and abs(got - rate) < 0.05 * rate,
              "the dataset holds the %d recorded frames at the camera's real rate %.2f (%s)"
              % (len(seqs), rate, d["clips"][0]))


def check_recording(out, expect_complete):
    m = json.load(open(os.path.join(out, "manifest.json")))
    files = sorted(os.path.basename(p) for p in glob.glob(os.path.join(out, "frames", "*.png")))
    listed = sorted(os.path.basename(f["file"]) for f in m["frames"])
    check(files == listed, "manifest lists exactly the frame files (%d)" % len(files))
    check(m["frame_count"] == len(files), "frame_count matches")
    check(not glob.glob(os.path.join(out, "**", "*.tmp"), recursive=True), "no temporary files left")
    bad = [f for f in files if png_size(os.path.join(out, "frames", f)) != (m["width"], m["height"], 0)]
    check(not bad, "every frame is a whole %dx%d gray PNG (bad: %s)" % (m["width"], m["height"], bad[:3]))
    check(m["complete"] == expect_complete, "complete = %s (%s)" % (m["complete"], m["end_reason"]))
    return m


def record(out, *args, timeout=120, env=None):
    # The live preview is tested by the record_preview_* cases; elsewhere it stays off.
    preview = () if "--preview" in args else ("--preview", "off")
    p = subprocess.run([*RECORD, "--device", "/dev/video0", "--out", out, *preview, *args],
                       capture_output=True, text=True, timeout=timeout, env=env)
    print("candela-record: status %d: %s" % (p.returncode, p.stderr.strip()), flush=True)
    return p


def case_record_vivid():
    out = os.path.join(WORK, "clip")
    n = 20
    p = record(out, "--size", "320x180", "--fps", "10", "--frames", str(n))
    check(p.returncode == 0, "recording succeeds")
    m = check_recording(out, True)
    seqs = [f["sequence"] for f in m["frames"]]
    check(len(seqs) == n and seqs == list(range(seqs[0], seqs[0] + n)),
          "%d frames with consecutive sequence numbers" % n)
    ts = [f["timestamp_ns"] for f in m["frames"]]
    check(all(b > a for a, b in zip(ts, ts[1:])), "timestamps increase")
    check(m["dropped"]["count"] == 0, "nothing dropped")
    check(m["locked"].get("gain_automatic") == "off", "auto gain locked off: %s" % m["locked"])
    check_dataset(out, m)
    # Sustained rate at 640x480 (a figure for the report; TCG is slow, so not asserted).
    out2 = os.path.join(WORK, "vga")
    p = record(out2, "--size", "640x480", "--fps", "30", "--seconds", "6")
    m2 = json.load(open(os.path.join(out2, "manifest.json")))
    print("vivid 640x480: %d frames, %d dropped, negotiated %s fps" %
          (m2["frame_count"], m2["dropped"]["count"], m2["fps"]), flush=True)


def case_record_no_camera():
    out = os.path.join(WORK, "none")
    p = subprocess.run([*RECORD, "--device", "/dev/video61", "--out", out, "-n", "5"],
                       capture_output=True, text=True, timeout=30)
    check(p.returncode == 4, "exit status 4 (no camera): %d" % p.returncode)
    check("/dev/video61" in p.stderr and "No such file" in p.stderr, "clear message: " + p.stderr.strip())
    check(not os.path.exists(out), "no empty folder left behind")
    # An asked-for preview that cannot open changes nothing of that: same status and message,
    # and nothing is opened before a camera delivers.
    env = {k: v for k, v in os.environ.items() if k != "DISPLAY"}
    p2 = subprocess.run([*RECORD, "--device", "/dev/video61", "--out", out, "-n", "5", "--preview", "window"],
                        capture_output=True, text=True, timeout=30, env=env)
    check(p2.returncode == 4 and p2.stderr.strip().splitlines()[-1] == p.stderr.strip().splitlines()[-1],
          "--preview window without X: the same no-camera ending: " + p2.stderr.strip())
    check("preview" not in p2.stderr, "no preview is opened without a camera")


def case_record_readonly():
    mnt = os.path.join(WORK, "ro")
    os.makedirs(mnt)
    subprocess.run(["mount", "-t", "tmpfs", "-o", "ro,size=1m", "tmpfs", mnt], check=True)
    p = record(os.path.join(mnt, "clip"), "--size", "320x180", "-n", "5")
    check(p.returncode == 3, "exit status 3 (output not writable): %d" % p.returncode)
    check("Read-only file system" in p.stderr, "clear message: " + p.stderr.strip())


def case_record_disk_full():
    mnt = os.path.join(WORK, "small")
    os.makedirs(mnt)
    subprocess.run(["mount", "-t", "tmpfs", "-o", "size=400k", "tmpfs", mnt], check=True)
    vivid_set("/dev/video0", test_pattern=vivid_menu("/dev/video0", "test_pattern", "Noise"))
    out = os.path.join(mnt, "clip")
    p = record(out, "--size", "320x180", "--fps", "10", "-n", "1000")
    check(p.returncode == 3, "exit status 3 (disk full): %d" % p.returncode)
    check("disk full" in p.stderr and "No space left" in p.stderr, "clear message: " + p.stderr.strip())
    m = check_recording(out, False)
    check(m["frame_count"] > 0, "the frames written before the disk filled are kept (%d)" % m["frame_count"])


def case_record_camera_unplugged():
    out = os.path.join(WORK, "clip")
    proc = subprocess.Popen([*RECORD, "--device", "/dev/video0", "--out", out, "--size", "320x180",
                             "--fps", "10", "-n", "100000", "--preview", "off"],
                            stderr=subprocess.PIPE, text=True)
    wait_for_manifest_frames(out, 5)
    vivid_set("/dev/video0", disconnect=1)  # vivid's simulated USB unplug
    _, err = proc.communicate(timeout=60)
    print("candela-record: status %d: %s" % (proc.returncode, err.strip()), flush=True)
    check(proc.returncode == 5, "exit status 5 (camera lost): %d" % proc.returncode)
    check("went away" in err, "clear message")
    m = check_recording(out, False)
    check(m["frame_count"] >= 5, "frames so far kept (%d)" % m["frame_count"])


# --- candela-record's live preview ------------------------------------------------------
def read_png_rgb(path):
    """A PNG (gray or RGB) as a numpy array (H, W, 3), decoded by ffmpeg (Debian: ffmpeg)."""
    import numpy as np
    w, h, _ = png_size(path)
    raw = subprocess.run(["ffmpeg", "-v", "error", "-i", path, "-f", "rawvideo", "-pix_fmt", "rgb24", "-"],
                         capture_output=True, check=True, timeout=60).stdout
    return np.frombuffer(raw, np.uint8).reshape(h, w, 3).astype(np.int32)


def expected_preview(frame, dw, dh):
    """The frame letterboxed and bilinearly scaled to dw x dh the way the preview draws it
    (tools/record/preview.cpp letterbox()), and a mask of the picture minus the red dot."""
    import numpy as np
    fh, fw = frame.shape[:2]
    if dw * fh <= dh * fw:
        rw, rh = dw, max(1, (dw * fh + fw // 2) // fw)
    else:
        rw, rh = max(1, (dh * fw + fh // 2) // fh), dh
    x0, y0 = (dw - rw) // 2, (dh - rh) // 2
    u = np.clip((np.arange(rw) + 0.5) * fw / rw - 0.5, 0, fw - 1)
    v = np.clip((np.arange(rh) + 0.5) * fh / rh - 0.5, 0, fh - 1)
    xa, ya = u.astype(int), v.astype(int)
    xb, yb = np.minimum(xa + 1, fw - 1), np.minimum(ya + 1, fh - 1)
    fx, fy = (u - xa)[None, :, None], (v - ya)[:, None, None]
    f = frame.astype(float)
    top = f[ya][:, xa] * (1 - fx) + f[ya][:, xb] * fx
    bot = f[yb][:, xa] * (1 - fx) + f[yb][:, xb] * fx
    want = np.zeros((dh, dw, 3))
    want[y0:y0 + rh, x0:x0 + rw] = top * (1 - fy) + bot * fy
    mask = np.zeros((dh, dw), bool)
    mask[y0:y0 + rh, x0:x0 + rw] = True
    dot = max(4, min(dw, dh) // 32)
    mask[dot // 2:dot // 2 + dot, dot // 2:dot // 2 + dot] = False
    return want, mask


def check_preview_shows(out, dump_dir):
    import numpy as np
    m = json.load(open(os.path.join(out, "manifest.json")))
    pv = m["preview"]
    check(pv["opened"] and pv["shown"] > 0, "the preview showed frames: %s" % pv)
    shown = read_png_rgb(os.path.join(dump_dir, "preview.png"))
    frame = read_png_rgb(os.path.join(out, "frames", "%08u.png" % pv["last_sequence"]))
    want, mask = expected_preview(frame, shown.shape[1], shown.shape[0])
    diff = np.abs(shown - want)[mask]
    check(frame.std() > 20, "the camera's frame has something to see (std %.1f)" % frame.std())
    check(diff.mean() < 2.0 and np.percentile(diff, 99) < 24,
          "the preview image is recorded frame %d, letterboxed to %dx%d (mean |diff| %.2f, p99 %.1f)" %
          (pv["last_sequence"], shown.shape[1], shown.shape[0], diff.mean(), np.percentile(diff, 99)))
    check((shown[~mask] [:, :].max(axis=1) > 0).sum() <= max(4, min(shown.shape[:2]) // 32) ** 2,
          "only the red recording dot lies outside the picture")
    return m


def case_record_preview_headless():
    out, dump = os.path.join(WORK, "clip"), os.path.join(WORK, "dump")
    n = 20
    p = record(out, "--size", "320x180", "--fps", "10", "-n", str(n), "--preview", "headless",
               "--preview-size", "200x150", "--preview-dump", dump)
    check(p.returncode == 0, "recording with a headless preview succeeds")
    m = check_recording(out, True)
    # The preview draws on the emulated CPU (TCG): on a loaded host a frame
    # is now and then dropped (1 run in 6 CI rehearsals). What must hold is
    # that the clip is whole and any gap is named in the manifest, as
    # record_preview_drm checks it.
    d = m["dropped"]
    check(m["frame_count"] == n and d["count"] <= 2 and len(d["sequences"]) == d["count"],
          "all %d frames recorded, at most 2 dropped and named (%d dropped: %s)" % (n, d["count"], d["sequences"]))
    check_preview_shows(out, dump)
    check(re.search(r"preview on headless showed \d+ of %d frames" % n, p.stderr) is not None,
          "the summary says what the preview showed")


def case_record_preview_drm():
    n = 10
    env = {k: v for k, v in os.environ.items() if k != "DISPLAY"}
    # Asked for: the vkms screen.
    out, dump = os.path.join(WORK, "drm"), os.path.join(WORK, "drm_dump")
    p = record(out, "--size", "320x180", "--fps", "10", "-n", str(n), "--preview", "drm",
               "--preview-dump", dump, env=env)
    check(p.returncode == 0, "recording with a DRM preview succeeds")
    check("connector Virtual-1" in p.stderr and "preview: showing the recording on drm" in p.stderr,
          "the preview opened on vkms' connector Virtual-1")
    m = check_recording(out, True)
    check(m["frame_count"] == n, "all %d frames recorded (%d dropped)" % (n, m["dropped"]["count"]))
    check(m["preview"]["backend"] == "drm" and m["preview"]["width"] == 1024,
          "manifest: preview on drm at the screen's 1024x768 mode: %s" % m["preview"])
    check_preview_shows(out, dump)
    # auto without $DISPLAY picks the same screen and says why.
    out2 = os.path.join(WORK, "auto")
    p = record(out2, "--size", "320x180", "--fps", "10", "-n", str(n), "--preview", "auto", env=env)
    check(p.returncode == 0 and "auto: no $DISPLAY" in p.stderr and
          json.load(open(os.path.join(out2, "manifest.json")))["preview"]["shown"] > 0,
          "auto without $DISPLAY shows the recording on the DRM screen")
    # The kiosk holds the screen: the preview steps aside, the recording is whole.
    log_path = os.path.join(WORK, "kiosk.log")
    with open(log_path, "w") as log:
        kiosk = subprocess.Popen([*CANDELA, "--display", "drm", "--test-pattern"], stdout=log,
                                 stderr=subprocess.STDOUT)
    try:
        wait_for("the kiosk's modeset", lambda: "modeset" in open(log_path).read(), timeout=60)
        out3 = os.path.join(WORK, "busy")
        p = record(out3, "--size", "320x180", "--fps", "10", "-n", str(n), "--preview", "drm", env=env)
    finally:
        kiosk.terminate()
        kiosk.wait(timeout=30)
    check(p.returncode == 0, "recording succeeds while the kiosk holds the screen")
    line = [l for l in p.stderr.splitlines() if "preview: cannot open drm" in l]
    check(len(line) == 1 and "DRM master" in line[0] and line[0].endswith("recording without a preview"),
          "one clear line says the preview could not open: %s" % line)
    m3 = check_recording(out3, True)
    check(m3["frame_count"] == n and not m3["preview"]["opened"],
          "all %d frames recorded, the manifest says no preview ran" % n)


run_case(CASE, globals())
