#!/usr/bin/env bash
# Candela's sound through a real ALSA driver on the virtual board: snd-aloop
# (loaded in the guest from the board's module cache) is the sound card.
# `candela --display headless --realtime` plays a fire scene into the
# loopback's playback side (hw:Loopback,0,0) while arecord records its capture
# side (hw:Loopback,1,0); then the same with --mute. On the host: the
# recording is sound, not silence (RMS floor), it is the fire's (its level
# moves over time, and most of its energy is below 1 kHz: the roar, not white
# noise), and the muted run recorded pure digital silence. One boot.
#   alsa_loopback.sh CANDELA PYTHON3
set -euo pipefail
candela=$1 python=$2
vboard=${CANDELA_VBOARD:-$(dirname "$0")/../../board/virtual/run-in-vm.sh}
# The guest loads snd-aloop's closure from the kernel the board unpacked.
cache=${CANDELA_VBOARD_CACHE:-$(cd "$(dirname "$vboard")/../.." && pwd)/build/vboard}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

cat >"$out/fire.toml" <<'TOML'
seed = 21
[sound]
volume = 1.0
device = "hw:Loopback,0,0"
[[element]]
kind = "hearth"
name = "logs and embers"
width = 1.15
depth = 0.4
TOML

# Under TCG softpipe starts far sooner than llvmpipe (no LLVM to JIT the shaders);
# at 64x48, 20 real-time frames are about 3 s of sound.
log=$("$vboard" --out "$out" --timeout 120 "
  modprobe -d '$cache/'\$(uname -r)/root snd-aloop || exit 3
  grep -H . /proc/asound/cards
  record() {  # record NAME CANDELA-ARGS...: arecord runs before candela starts, ends after it
    name=\$1; shift
    arecord -q -D hw:Loopback,1,0 -f S16_LE -r 48000 -c 2 $out/\$name.wav & rec=\$!
    i=0  # bounded wait until the capture runs
    until grep -qs 'state: RUNNING' /proc/asound/Loopback/pcm1c/sub0/status; do
      i=\$((i + 1)); [ \$i -gt 1000 ] && { echo 'arecord did not start'; break; }; sleep 0.01
    done
    echo \"=== \$name\"
    GALLIUM_DRIVER=softpipe $candela --display headless --realtime --size 64x48 --scene $out/fire.toml \"\$@\" 2>&1
    echo \"candela-exit=\$?\"
    kill -INT \$rec; wait \$rec || true  # arecord ends 1 on SIGINT, its .wav complete
  }
  record sound --frames 20
  record mute --mute --frames 1
" 2>&1) || {
  echo "$log"
  echo "FAIL: the virtual board run failed"
  exit 1
}
echo "$log"
section() { sed -n "/^=== $1\$/,/^=== /p" <<<"$log"; }
fail() {
  echo "FAIL: $*"
  exit 1
}
grep -q 'Loopback' <<<"$log" || fail "snd-aloop gave no Loopback card"
section sound | grep -q '^candela-exit=0$' || fail "candela (sound) did not exit 0"
section mute | grep -q '^candela-exit=0$' || fail "candela (--mute) did not exit 0"
section sound | grep -q 'sound: ALSA "hw:Loopback,0,0", 2 channel(s), 48 kHz' ||
  fail "candela did not open hw:Loopback,0,0"
section mute | grep -q 'sound: ALSA' && fail "candela --mute opened an ALSA device"

"$python" - "$out/sound.wav" "$out/mute.wav" <<'PY'
import sys, wave
import numpy as np

def load(path):
    with wave.open(path) as w:
        assert w.getframerate() == 48000 and w.getnchannels() == 2, path
        return np.frombuffer(w.readframes(w.getnframes()), dtype="<i2").reshape(-1, 2)

snd, mute = load(sys.argv[1]), load(sys.argv[2])
ok = True
def check(cond, what):
    global ok
    print(("ok: " if cond else "FAIL: ") + what)
    ok &= bool(cond)

x = snd[:, 0].astype(float) / 32768
# Candela plays mono on every channel.
check(np.array_equal(snd[:, 0], snd[:, 1]), "both channels carry the same (mono) sound")
heard = np.nonzero(np.abs(x) > 1e-3)[0]
check(len(heard) > 0, "the loopback recorded sound")
if len(heard):
    s = x[heard[0]:heard[-1] + 1]
    secs = len(s) / 48000
    rms = float(np.sqrt(np.mean(s ** 2)))
    check(secs >= 1.0, f"{secs:.1f} s of sound (>= 1 s)")
    check(rms > 0.01, f"RMS {rms:.4f} above the floor 0.01 (volume 1)")
    win = 4800  # 100 ms
    n = len(s) // win
    if n >= 5:
        lv = np.sqrt(np.mean(s[: n * win].reshape(n, win) ** 2, axis=1))
        cv = float(lv.std() / lv.mean())
        # Steady noise of this length: well under 1 %.
        check(cv > 0.05, f"level over time varies ({cv:.3f} of its mean, > 0.05): a fire, not a hum")
    spec = np.abs(np.fft.rfft(s)) ** 2
    f = np.fft.rfftfreq(len(s), 1 / 48000)
    low = float(spec[f < 1000].sum() / spec.sum())
    # White noise: about 4 % below 1 kHz.
    check(low > 0.5, f"{100 * low:.0f} % of the energy below 1 kHz (> 50 %): the roar")
mute_s = len(mute) / 48000
check(mute_s >= 0.5, f"the muted run recorded {mute_s:.1f} s")
check(not np.any(mute), "--mute: every sample recorded is 0")
sys.exit(0 if ok else 1)
PY
echo "PASS: candela's fire sound came out of snd-aloop; --mute is silent"
