#!/usr/bin/env python3
"""candela's sound as a user meets it: tests/sound/sound_cli.py CASE BUILD_DIR.

  wav_beside   a .y4m render of a fireplace writes x.wav beside it: 48 kHz mono,
               one step (800 samples) per frame, audible; the same seed twice gives
               the same bytes; --mute writes none
  mp4_sound    an .mp4 render carries an AAC stream as long as the video, and no
               .wav is left beside it
  signal_mp4   SIGINT to the process group mid-render: exit 0, the mp4 is whole and
               still carries its sound
"""
import array, math, os, shutil, signal, subprocess, sys, tempfile, time, wave

CASE, BUILD = sys.argv[1], sys.argv[2]
CANDELA = os.path.join(BUILD, "firmware", "candela")
SRC = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(SRC, "firmware", "scenes", "perlin-fireplace.toml")
WORK = tempfile.mkdtemp(prefix="candela-sound-")
failures = []


def check(ok, what, detail=""):
    print(("ok   " if ok else "FAIL ") + what + ("" if ok else " " + detail))
    if not ok:
        failures.append(what)


def render(out, frames, *extra):
    cmd = [CANDELA, "--display", "headless", "--scene", SCENE, "--size", "64x48", "--frames",
           str(frames), "--out", out, "--log-level", "warn", *extra]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=300)


def streams(path):
    p = subprocess.run(["ffprobe", "-v", "error", "-show_entries", "stream=codec_type,codec_name,duration",
                        "-of", "csv=p=0", path], capture_output=True, text=True)
    rows = [r.split(",") for r in p.stdout.split()]
    return {r[1]: (r[0], float(r[2])) for r in rows if len(r) == 3 and r[2] != "N/A"}


def case_wav_beside():
    out = os.path.join(WORK, "a.y4m")
    r = render(out, 120)
    check(r.returncode == 0, "render exits 0", r.stderr)
    wav = os.path.join(WORK, "a.wav")
    with wave.open(wav) as w:
        check(w.getframerate() == 48000 and w.getnchannels() == 1 and w.getsampwidth() == 2,
              "48 kHz mono 16-bit")
        n = w.getnframes()
        samples = array.array("h", w.readframes(n))
    check(n == 120 * 800, "one step of sound per frame (%d samples, expected %d)" % (n, 120 * 800))
    level = math.sqrt(sum(s * s for s in samples) / max(1, n)) / 32768
    check(0.01 < level < 0.5, "the fire is heard (RMS %.3f)" % level)
    first = open(wav, "rb").read()
    render(out, 120)
    check(open(wav, "rb").read() == first, "the same seed gives the same sound, byte for byte")
    os.remove(wav)
    r = render(out, 30, "--mute")
    check(r.returncode == 0 and not os.path.exists(wav), "--mute writes no .wav")


def case_mp4_sound():
    out = os.path.join(WORK, "b.mp4")
    r = render(out, 120)
    check(r.returncode == 0, "render exits 0", r.stderr)
    s = streams(out)
    check("audio" in s and s["audio"][0] == "aac", "the mp4 carries AAC sound", str(s))
    if "audio" in s and "video" in s:
        check(abs(s["audio"][1] - s["video"][1]) < 0.1,
              "sound as long as the video (%.2f s vs %.2f s)" % (s["audio"][1], s["video"][1]))
    check(not os.path.exists(os.path.join(WORK, "b.wav")), "no .wav left beside the mp4")
    check(not os.path.exists(os.path.join(WORK, "b.muxing.mp4")), "no temporary file left")


def case_signal_mp4():
    out = os.path.join(WORK, "c.mp4")
    log = open(os.path.join(WORK, "log"), "w")
    p = subprocess.Popen([CANDELA, "--display", "headless", "--scene", SCENE, "--size", "64x48",
                          "--out", out, "--log-level", "info"], stdout=log, stderr=subprocess.STDOUT,
                         start_new_session=True)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and not (os.path.exists(out) and os.path.getsize(out) > 20000):
        time.sleep(0.05)
    os.killpg(p.pid, signal.SIGINT)  # Ctrl-C reaches the whole group
    rc = p.wait(timeout=120)
    check(rc == 0, "exit 0 after SIGINT (got %d)" % rc, open(os.path.join(WORK, "log")).read()[-800:])
    s = streams(out)
    check("video" in s and "audio" in s, "the mp4 is whole and carries its sound", str(s))


try:
    {"wav_beside": case_wav_beside, "mp4_sound": case_mp4_sound, "signal_mp4": case_signal_mp4}[CASE]()
finally:
    shutil.rmtree(WORK, ignore_errors=True)
sys.exit(1 if failures else 0)
