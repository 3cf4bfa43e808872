#!/usr/bin/python3
"""The soak (issue 15): each built-in scene through HOURS of animation time.

Headless at a tiny size with --fps 1, so every frame advances 60 fixed
animation steps and 24 h (5.2 M steps) is 86,400 small frames: minutes, not a
day. While it runs, the resident set size is sampled from /proc; afterwards
the frames (.y4m, luma) are read back hour by hour. Per scene one line:

  scene  steps  wall s  RSS first/last/max MB (after warm-up)  luma hour 1 / last hour  moving %  verdict

A scene passes when RSS stays within --rss-mb of its value after warm-up
(5 % of the run, at least 5 s) plus the frame statistics' buffer (16 bytes a
frame, filled along the run: 1.3 MB for 24 h at --fps 1), every hour of frames keeps changing (no stuck state: a
NaN in the animation freezes or blanks the picture) and the last hour's mean
brightness stays within a factor of two of the first hour's (no drift to
black or to white). A benchmark script, not a ctest:

  tests/bench/soak.py [--build build] [--hours 24] [--size 32x18] [SCENE.toml ...]

Without scenes: every firmware/scenes/*.toml but the bench-* and
eigen-bench-* ones (the same elements at other counts). Exit status 1 if a
scene fails. Needs Debian's /usr/bin/python3 (numpy).
"""
import argparse
import glob
import os
import subprocess
import sys
import tempfile
import threading
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def rss_sampler(pid, samples, stop):
    """VmRSS (kB) of pid every 0.2 s until stop is set or the process ends."""
    path = f"/proc/{pid}/status"
    while not stop.is_set():
        try:
            with open(path) as f:
                for line in f:
                    if line.startswith("VmRSS:"):
                        samples.append((time.monotonic(), int(line.split()[1])))
                        break
        except OSError:
            return
        stop.wait(0.2)


def read_luma(path):
    """Frames x H x W uint8 luma of a C444 .y4m file (as candela writes it)."""
    with open(path, "rb") as f:
        header = f.readline().split()
        w = int(next(t for t in header if t.startswith(b"W"))[1:])
        h = int(next(t for t in header if t.startswith(b"H"))[1:])
        data = np.frombuffer(f.read(), dtype=np.uint8)
    frame = 6 + 3 * w * h  # "FRAME\n" + Y, U, V planes
    n = data.size // frame
    return data[: n * frame].reshape(n, frame)[:, 6 : 6 + w * h].reshape(n, h, w)


def soak(candela, scene, hours, size, rss_mb, tmp):
    frames = int(hours * 3600)  # --fps 1: one frame per animation second
    out = os.path.join(tmp, os.path.basename(scene) + ".y4m")
    cmd = [candela, "--display", "headless", "--scene", scene, "--size", size, "--fps", "1",
           "--frames", str(frames), "--out", out, "--log-level", "warn",
           "--mute"]  # 24 h of sound would be 8 GB of .wav; the sound has its own tests
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    samples, stop = [], threading.Event()
    sampler = threading.Thread(target=rss_sampler, args=(proc.pid, samples, stop))
    sampler.start()
    _, err = proc.communicate()
    stop.set()
    sampler.join()
    wall = time.monotonic() - start
    name = os.path.basename(scene)
    if proc.returncode != 0:
        print(f"{name}: candela exited {proc.returncode}: {err.decode()[-400:]}")
        return False
    problems = []
    # RSS after warm-up: the first 5 % builds caches, textures, GL state.
    warm = [(t, kb / 1024) for t, kb in samples if t - start >= max(0.05 * wall, 5.0)]
    if len(warm) < 2:
        warm = [(t, kb / 1024) for t, kb in samples] or [(start, 0.0)]
    rss = [r for _, r in warm]
    first, last, peak = rss[0], rss[-1], max(rss)
    # candela's frame statistics fill a buffer reserved up front, 16 bytes a
    # frame up to --frames (at most 2^16 frames without --frames): pages it
    # touches as it goes, bounded, not a leak. Expected growth: along the run.
    fill = 16 * min(frames, 1 << 20) / 2**20
    t0, t1 = warm[0][0], start + wall
    moved = max(abs(r - first - fill * (t - t0) / max(t1 - start, 1e-9)) for t, r in warm)
    if moved > rss_mb:
        problems.append(f"RSS moved {moved:.1f} MB beyond the frame statistics' {fill:.1f} MB")
    luma = read_luma(out)
    os.remove(out)
    if luma.shape[0] != frames:
        problems.append(f"{luma.shape[0]} frames written, expected {frames}")
    per_hour = 3600
    hours_seen = max(1, luma.shape[0] // per_hour)
    mean = luma.reshape(luma.shape[0], -1).mean(axis=1)
    diff = np.abs(np.diff(luma.astype(np.int16), axis=0)).reshape(luma.shape[0] - 1, -1).max(axis=1)
    moving = []
    for hr in range(hours_seen):
        d = diff[hr * per_hour : (hr + 1) * per_hour - 1]
        moving.append(100.0 * np.count_nonzero(d) / max(1, d.size))
    first_hour, last_hour = mean[:per_hour].mean(), mean[-per_hour:].mean()
    if min(moving) < 50:
        problems.append(f"hour {int(np.argmin(moving)) + 1}: only {min(moving):.0f} % of frames change")
    if first_hour > 1 and not (0.5 * first_hour <= last_hour <= 2 * first_hour):
        problems.append(f"mean luma {first_hour:.1f} -> {last_hour:.1f}")
    verdict = "ok" if not problems else "FAIL: " + "; ".join(problems)
    track = " ".join(f"{rss[min(len(rss) - 1, len(rss) * q // 8)]:.1f}" for q in range(9))
    verdict += f"  (RSS by eighths of the run: {track})"
    print(f"{name:28s} {frames * 60:>9d} {wall:7.1f} {first:7.1f} {last:7.1f} {peak:7.1f} "
          f"{first_hour:6.1f} {last_hour:6.1f} {min(moving):6.1f}  {verdict}", flush=True)
    return not problems


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scenes", nargs="*")
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--hours", type=float, default=24.0, help="animation time per scene")
    ap.add_argument("--size", default="32x18")
    ap.add_argument("--rss-mb", type=float, default=1.0, help="allowed RSS change after warm-up")
    a = ap.parse_args()
    candela = os.path.join(a.build, "firmware", "candela")
    scenes = a.scenes or sorted(
        s for s in glob.glob(os.path.join(ROOT, "firmware", "scenes", "*.toml"))
        if not os.path.basename(s).startswith(("bench-", "eigen-bench-")))
    print(f"{'scene':28s} {'steps':>9s} {'wall s':>7s} {'RSS MB first':>7s} {'last':>7s} "
          f"{'max':>7s} {'luma 1h':>6s} {'last h':>6s} {'moving %':>6s}  verdict")
    ok = True
    with tempfile.TemporaryDirectory() as tmp:
        for s in scenes:
            ok &= soak(candela, s, a.hours, a.size, a.rss_mb, tmp)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
