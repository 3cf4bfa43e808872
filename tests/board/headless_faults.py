#!/usr/bin/python3
"""Faults a kiosk must survive that need no virtual hardware (headless, on the
host; the DRM ones are drm_faults.py on the virtual board):

  sigstop         SIGSTOP, then SIGCONT after 2 s: candela resumes at its own
                  pace, without replaying the stopped time in a burst of
                  frames or one huge animation step, and its wind stays sane.
  model_replaced  the model file of a running eigen flame replaced by rename,
                  truncated and rewritten in place, then deleted: the running
                  flame is exactly what it would have been (a loaded model
                  never reads its file again) and candela finishes normally.

    headless_faults.py CASE BUILD_DIR

Every wait polls observable state (the control socket's `state`, the output
file's size, a process's exit) against a deadline; the only fixed waits are
the lengths of the faults themselves."""
import atexit
import json
import math
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

# check(), wait_for() and FAILED: tests/support/checks.py
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "support"))
from checks import FAILED, check, run_case, wait_for  # noqa: E402
from programs import program  # noqa: E402

CASE, BUILD = sys.argv[1], os.path.abspath(sys.argv[2])
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CANDELA = program(os.path.join(BUILD, "firmware", "candela"))
WORK = tempfile.mkdtemp(prefix="candela-faults-")
atexit.register(shutil.rmtree, WORK, True)  # nothing left in /tmp, pass or fail


# --- SIGSTOP / SIGCONT -------------------------------------------------------------
STEPS_PER_SECOND = 60  # the animation clock's default rate
FPS = 30
STOPPED_S = 2.0
CATCH_UP_CAP = 8  # StepClock::advance_wall: at most this many steps in one frame


def case_sigstop():
    sock_path = os.path.join(WORK, "ctl")
    log_path = os.path.join(WORK, "candela.log")
    with open(log_path, "w") as log:
        proc = subprocess.Popen([*CANDELA, "--display", "headless", "--realtime", "--fps", str(FPS),
                                 "--size", "32x24", "--scene", os.path.join(ROOT, "firmware", "scenes", "default.toml"),
                                 "--control", sock_path], stdout=log, stderr=subprocess.STDOUT)
    try:
        def connect():
            if proc.poll() is not None:
                raise AssertionError("candela exited:\n" + open(log_path).read())
            s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            try:
                s.connect(sock_path)
                return s
            except OSError:
                s.close()
                return None
        s = wait_for("the control socket", connect, timeout=60)
        s.settimeout(20)
        f = s.makefile("rw")

        def state():
            f.write("state\n")
            f.flush()
            return json.loads(f.readline()), time.monotonic()

        wait_for("some frames", lambda: state()[0]["frame"] > 10, timeout=60)
        f.write("gust left 2\n")  # wind that moves through the stop
        f.flush()
        f.readline()
        wait_for("the gust", lambda: state()[0]["wind"]["x"] != 0, timeout=30)
        a, t_a = state()
        os.kill(proc.pid, signal.SIGSTOP)
        t_stop = time.monotonic()
        time.sleep(STOPPED_S)  # the fault: stopped this long
        os.kill(proc.pid, signal.SIGCONT)
        stopped = time.monotonic() - t_stop
        b, t_b = state()
        wait_for("a second of frames after SIGCONT", lambda: time.monotonic() - t_b >= 1.0)
        c, t_c = state()
        running = (t_c - t_a) - stopped
        steps = c["step"] - a["step"]
        allowed = STEPS_PER_SECOND * running + CATCH_UP_CAP + 20
        check(steps <= allowed,
              "the stopped %.1f s are not replayed: %d steps for %.2f s of running (at most %.0f; "
              "replaying would add %d)" % (stopped, steps, running, allowed, STEPS_PER_SECOND * stopped))
        check(c["step"] > b["step"] and c["frame"] > b["frame"], "animation and frames resume")
        frames = c["frame"] - b["frame"]
        check(frames <= FPS * (t_c - t_b) * 1.25 + 3,
              "no burst of catch-up frames: %d frames in %.2f s at %d fps" % (frames, t_c - t_b, FPS))
        w = c["wind"]
        check(all(math.isfinite(w[k]) and abs(w[k]) <= 2.5 for k in ("x", "z")),
              "the gust's wind stays finite and within its 2 m/s: before %s, after %s" % (a["wind"], w))
        s.close()
        proc.send_signal(signal.SIGTERM)
        check(proc.wait(timeout=30) == 0, "candela exits 0 on SIGTERM")
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()


# --- the model file replaced while running ---------------------------------------------------
FRAMES = 240
W = H = 48
FRAME_BYTES = len("FRAME\n") + 3 * W * H  # y4m C444


def frames_in(path):
    try:
        size = os.path.getsize(path)
    except OSError:
        return 0
    with open(path, "rb") as f:
        header = len(f.readline())
    return max(0, (size - header) // FRAME_BYTES)


def render(scene, out, faults=()):
    """Renders FRAMES frames; each fault (frame, function) runs while candela is
    stopped once at least that many frames were written."""
    proc = subprocess.Popen([*CANDELA, "--display", "headless", "--size", "%dx%d" % (W, H), "--frames", str(FRAMES),
                             "--scene", scene, "--out", out], stderr=subprocess.PIPE, text=True)
    at = []
    try:
        for frame, fault in faults:
            def reached():
                if proc.poll() is not None:
                    raise AssertionError("candela ended before frame %d: %s" % (frame, proc.stderr.read()))
                return frames_in(out) >= frame
            wait_for("frame %d" % frame, reached, timeout=120, interval=0.001)
            os.kill(proc.pid, signal.SIGSTOP)
            at.append(frames_in(out))
            fault()
            os.kill(proc.pid, signal.SIGCONT)
        _, err = proc.communicate(timeout=300)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    return proc.returncode, err, at


def case_model_replaced():
    model = os.path.join(WORK, "candle.cmodel")
    shutil.copy(os.path.join(ROOT, "firmware", "models", "default.cmodel"), model)
    text = open(os.path.join(ROOT, "firmware", "scenes", "eigen-candle.toml")).read()
    check('model = "builtin:candle"' in text, "the eigen candle scene names its model")
    scene = os.path.join(WORK, "scene.toml")
    with open(scene, "w") as f:
        f.write(text.replace('model = "builtin:candle"', 'model = "%s"' % model))
    ref = os.path.join(WORK, "ref.y4m")
    rc, err, _ = render(scene, ref)
    check(rc == 0, "the undisturbed render succeeds: " + err.strip()[-300:])

    garbage = b"not a model\n" * 100

    def replace_by_rename():  # what an update tool does
        tmp = model + ".new"
        with open(tmp, "wb") as f:
            f.write(garbage)
        os.rename(tmp, model)

    def truncate_and_rewrite():  # what `cp` over it does
        with open(model, "r+b") as f:
            f.truncate(0)
            f.write(garbage[:500])

    def delete():
        os.unlink(model)

    # Put the real model back first, so the rename replaces a good file.
    def restore_then_rename():
        shutil.copy(os.path.join(ROOT, "firmware", "models", "default.cmodel"), model)
        replace_by_rename()

    out = os.path.join(WORK, "run.y4m")
    rc, err, at = render(scene, out, [(20, replace_by_rename), (60, truncate_and_rewrite),
                                      (100, delete), (140, restore_then_rename)])
    check(rc == 0, "candela finishes normally (status %d): %s" % (rc, err.strip()[-300:]))
    check(len(at) == 4 and at == sorted(at) and at[-1] < FRAMES,
          "the faults came mid-run, at frames %s of %d" % (at, FRAMES))
    same = open(ref, "rb").read() == open(out, "rb").read()
    check(same, "every frame is the same as the undisturbed render's (%d frames)" % frames_in(out))
    bad = [l for l in err.splitlines() if "warn" in l or "error" in l]
    check(not bad, "no warning or error logged: %s" % bad)


run_case(CASE, globals())
