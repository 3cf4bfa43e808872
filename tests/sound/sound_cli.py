#!/usr/bin/env python3
"""candela's sound as a user meets it: tests/sound/sound_cli.py CASE BUILD_DIR.

  wav_beside   a .y4m render of a fireplace writes x.wav beside it: 48 kHz mono,
               one step (800 samples) per frame, audible; the same seed twice gives
               the same bytes; --mute writes none
  mp4_sound    an .mp4 render carries an AAC stream as long as the video, and no
               .wav is left beside it
  signal_mp4   SIGINT to the process group mid-render: exit 0, the mp4 is whole and
               still carries its sound
  volume_socket  `volume 0.1` on the control socket early in a render: `state` reports
               it, the last second of the .wav is 0.1/0.6 as loud as the same render
               without it (same seed, same samples before the change), and the change
               glides (no sample-to-sample jump larger than the fire's own)
  scheduled_volume  a [schedule] with night_volume = 0.3 (the kiosk config, --clock-start):
               a render at 23:00 is 0.3 as loud as the same render at 12:00 (same
               seed: the same samples scaled), and neither is silent
"""
import array, json, math, os, shutil, signal, socket, subprocess, sys, tempfile, time, wave

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "support"))
from programs import program  # noqa: E402

CASE, BUILD = sys.argv[1], sys.argv[2]
CANDELA = program(os.path.join(BUILD, "firmware", "candela"))
SRC = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(SRC, "firmware", "scenes", "perlin-fireplace.toml")
WORK = tempfile.mkdtemp(prefix="candela-sound-")
failures = []


def check(ok, what, detail=""):
    print(("ok   " if ok else "FAIL ") + what + ("" if ok else " " + detail))
    if not ok:
        failures.append(what)


def render(out, frames, *extra):
    cmd = [*CANDELA, "--display", "headless", "--scene", SCENE, "--size", "64x48", "--frames",
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
    p = subprocess.Popen([*CANDELA, "--display", "headless", "--scene", SCENE, "--size", "64x48",
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


def read_wav(path):
    with wave.open(path) as w:
        return array.array("h", w.readframes(w.getnframes()))


def rms(x):
    return math.sqrt(sum(v * v for v in x) / max(1, len(x))) / 32768


def case_volume_socket():
    frames = 300  # 5 s of sound, one 800-sample step per frame (lockstep: deterministic)
    a = os.path.join(WORK, "a.y4m")
    r = render(a, frames)
    check(r.returncode == 0, "reference render exits 0", r.stderr)
    ctl = os.path.join(WORK, "ctl")
    b = os.path.join(WORK, "b.y4m")
    cmd = [*CANDELA, "--display", "headless", "--scene", SCENE, "--size", "64x48", "--frames",
           str(frames), "--out", b, "--log-level", "warn", "--control", ctl]
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    c = None
    while c is None and time.monotonic() < deadline and p.poll() is None:
        try:
            c = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            c.settimeout(5)
            c.connect(ctl)
        except OSError:
            c = None
            time.sleep(0.002)  # polling for the socket to appear, bounded by the deadline
    check(c is not None, "the control socket answers")
    state = {}
    if c is not None:
        f = c.makefile("rw")
        def ask(line):
            f.write(line + "\n")
            f.flush()
            return f.readline().strip()
        first = json.loads(ask("state"))
        check(abs(first["volume"] - 0.6) < 1e-3, "state reports the scene's volume 0.6 at first",
              str(first.get("volume")))
        check(ask("volume 1.5").startswith("error: volume: expected one level in [0, 1]"),
              "volume 1.5 is refused, naming the range")
        check(ask("volume 0.1") == "ok", "volume 0.1 answers ok")
        check(ask("volume") == "0.100", "volume alone answers 0.100")
        state = json.loads(ask("state"))
        c.close()
    check(abs(state.get("volume", -1) - 0.1) < 1e-3, "state reports volume 0.1", str(state))
    rc = p.wait(timeout=300)
    check(rc == 0, "the controlled render exits 0", p.stderr.read()[-800:])
    ref, ctl_wav = read_wav(os.path.join(WORK, "a.wav")), read_wav(os.path.join(WORK, "b.wav"))
    check(len(ref) == len(ctl_wav) == frames * 800, "both renders hold %d samples" % (frames * 800))
    # Where the volume changed: the first sample that differs.
    change = next((i for i in range(min(len(ref), len(ctl_wav))) if ref[i] != ctl_wav[i]), None)
    check(change is not None and change < (frames - 120) * 800,
          "the volume changed at least 2 s before the end (at sample %s)" % change)
    last = slice(len(ref) - 48000, len(ref))
    ratio = rms(ctl_wav[last]) / max(1e-9, rms(ref[last]))
    check(abs(ratio - 0.1 / 0.6) < 0.02,
          "the last second is 0.1/0.6 = 0.167 as loud as without the command (%.3f)" % ratio)
    if change is not None:
        def max_jump(x, lo, hi):
            return max(abs(x[i + 1] - x[i]) for i in range(lo, hi - 1))
        glide = max_jump(ctl_wav, change, min(len(ctl_wav), change + 4800))
        before = max_jump(ref, change, min(len(ref), change + 4800))
        check(glide <= before + 2, "the change glides: no jump beyond the fire's own "
              "(%d vs %d in the reference)" % (glide, before))


def case_scheduled_volume():
    # On all day but 05:00-06:00 (never off during the render: an off screen
    # draws no frames), no fades, quieter from 22:00.
    config = os.path.join(WORK, "candela.toml")
    with open(config, "w") as f:
        f.write('[schedule]\ndaily = "06:00-05:00"\nfade_in = 0\nfade_out = 0\n'
                'night = "22:00-02:00"\nnight_level = 0.4\nnight_volume = 0.3\n')
    level = {}
    for at in ("12:00", "23:00"):
        out = os.path.join(WORK, "at%s.y4m" % at.replace(":", ""))
        r = render(out, 90, "--seed", "3", "--config", config, "--clock-start", "2026-12-07T" + at)
        check(r.returncode == 0, "render at %s exits 0" % at, r.stderr)
        level[at] = rms(read_wav(out[:-len(".y4m")] + ".wav"))
    check(level["12:00"] > 0.01, "the day's fire is heard (RMS %.4f)" % level["12:00"])
    ratio = level["23:00"] / max(level["12:00"], 1e-9)
    check(abs(ratio - 0.3) < 0.02, "at night the sound is 0.3 as loud (%.3f)" % ratio)


try:
    {"scheduled_volume": case_scheduled_volume, "wav_beside": case_wav_beside, "mp4_sound": case_mp4_sound, "signal_mp4": case_signal_mp4,
     "volume_socket": case_volume_socket}[CASE]()
finally:
    shutil.rmtree(WORK, ignore_errors=True)
sys.exit(1 if failures else 0)
