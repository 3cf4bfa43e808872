#!/usr/bin/python3
"""The soak (issue 15): each built-in scene through HOURS of animation time.

Headless at a tiny size with --fps 1, so every frame advances 60 fixed
animation steps and 24 h (5.2 M steps) is 86,400 small frames: minutes, not a
day. While it runs, the resident set size is sampled from /proc; afterwards
the frames (.y4m, luma) are read back hour by hour. Per scene one line:

  scene  steps  wall s  RSS first/last/max MB (after warm-up)  luma hour 1 / last hour  moving %  verdict

A scene passes when, after warm-up (5 % of the run, at least 5 s):
- RSS stays within --rss-mb of its first value, plus the frame statistics'
  buffer (16 bytes a frame, filled along the run: 1.3 MB for 24 h at --fps 1)
  and 3 MB for the GL driver's pools, and within --rss-mb plus one 1 MB pool
  step over the run's second half (a leak keeps growing);
- the count of open files does not grow;
- the frame time does not grow: measured from the output's growth in each
  eighth of the run, no eighth slower than 3x the fastest one before it
  (checked when each eighth lasts 5 s or more; build machines are shared and
  loaded; --frame-time-ratio);
- every hour of frames keeps changing (no stuck state: a NaN in the animation
  freezes or blanks the picture) and the last hour's mean brightness stays
  within a factor of two of the first hour's (no drift to black or white);
- with --repeats (graph-walk scenes), no stretch of 3 s or more repeats an
  earlier one over the whole run. At --fps 1 this finds a walk that settles
  into a loop (a cycle shows at some lag that is a whole number of seconds);
  a single repeat at an arbitrary lag needs the 15 fps check of
  tests/realism/no-repeats.sh (10 minutes).

A benchmark script; a 1-hour version of the eigen fireplace runs in CI
(ctest soak_eigen_fireplace_short, tests/bench/CMakeLists.txt). The long run:

  tests/bench/soak.py [--build build] [--hours 24] [--size 32x18] [--repeats] [--seed N] [SCENE.toml ...]

Without scenes: every firmware/scenes/*.toml but the bench-* and
eigen-bench-* ones (the same elements at other counts). Exit status 1 if a
scene fails. Needs Debian's /usr/bin/python3 (numpy; scipy for --repeats).
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


def sampler(pid, out, samples, stop):
    """Every 0.2 s until stop is set or the process ends: (time, VmRSS kB,
    open fds, bytes of output written so far)."""
    path = f"/proc/{pid}/status"
    while not stop.is_set():
        try:
            with open(path) as f:
                rss = next(int(line.split()[1]) for line in f if line.startswith("VmRSS:"))
            fds = len(os.listdir(f"/proc/{pid}/fd"))
            written = os.path.getsize(out) if os.path.exists(out) else 0
        except (OSError, StopIteration):
            return
        samples.append((time.monotonic(), rss, fds, written))
        stop.wait(0.2)


def longest_repeat_frames(luma, frac=0.2, k=3):
    """The graph walk's no-repeat check over a whole soak: the longest run of
    consecutive frames that match, frame for frame, a run at some earlier lag
    (mean |difference| of every 4th pixel under frac x the median step between
    consecutive frames, as candela-tool measure repeats and realism.py). The
    measure's all-lags scan is quadratic; here k frames in a row are one point
    and a k-d tree finds the near pairs, so a day of frames takes seconds.
    Runs shorter than k are not looked for (returns 0 then)."""
    from scipy.spatial import cKDTree
    n = luma.shape[0]
    small = luma[:, ::4, ::4].reshape(n, -1).astype(np.float32) / 255.0
    p = small.shape[1]
    tol = frac * float(np.median(np.abs(np.diff(small, axis=0)).mean(axis=1)))
    if n < k + 2 or tol <= 0:
        return 0
    windows = np.concatenate([small[i : n - k + 1 + i] for i in range(k)], axis=1)
    # Every frame of a match under tol puts the window's L1 distance under k p tol.
    pairs = cKDTree(windows).query_pairs(r=k * p * tol, p=1, output_type="ndarray")
    if len(pairs) == 0:
        return 0
    s, t = pairs.min(axis=1), pairs.max(axis=1)
    keep = (t - s) >= 2
    s, t = s[keep], t[keep]
    ok = np.ones(len(s), dtype=bool)
    for i in range(k):
        for a in range(0, len(s), 1 << 16):  # bounded memory however many pairs
            b = a + (1 << 16)
            ok[a:b] &= np.abs(small[s[a:b] + i] - small[t[a:b] + i]).mean(axis=1) < tol
    s, t = s[ok], t[ok]
    if len(s) == 0:
        return 0
    # Matching windows at one lag with consecutive starts are one run.
    order = np.lexsort((s, t - s))
    s, lag = s[order], (t - s)[order]
    new_run = np.ones(len(s), dtype=bool)
    new_run[1:] = (lag[1:] != lag[:-1]) | (s[1:] != s[:-1] + 1)
    starts = np.flatnonzero(new_run)
    lengths = np.diff(np.append(starts, len(s)))
    return int(lengths.max()) + k - 1


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


# Mesa's llvmpipe (and the heap under it, never trimmed: app/heap_tuning)
# grows its pools in 1 MB steps at times set by its threads' scheduling, up to
# a high-water mark, then stays flat. On a loaded machine, a run in three
# stepped up by 1-2 MB after warm-up where the same run alone did not; CI once
# saw three steps between frames 340 and 680 of 900 (a machine drawing 100 a
# second); a 6 h run with 16 llvmpipe threads grew 0.3 MB, the frame
# statistics' fill. A leak grows with every frame, without a ceiling.
DRIVER_STEPS_MB = 3.0
DRIVER_STEP_MB = 1.0


def rss_problems(warm, fill, rss_mb, end):
    """RSS after warm-up, [(time, MB)], judged: within rss_mb of its first
    value plus the frame statistics' fill (spread along the run, ending at
    `end`) and the driver's steps; and, because a leak keeps growing, within
    rss_mb and one driver step over the second half of the run."""
    t0, first = warm[0]
    beyond = [r - first - fill * (t - t0) / max(end - t0, 1e-9) for t, r in warm]
    moved = max(abs(b) for b in beyond)
    half = beyond[len(beyond) // 2:]
    late = max(half) - half[0]
    if moved > rss_mb + DRIVER_STEPS_MB:
        return [f"RSS moved {moved:.1f} MB beyond the frame statistics' {fill:.1f} MB "
                f"(allowed: {rss_mb:.1f} + {DRIVER_STEPS_MB:.0f} for the GL driver's pools)"]
    if late > rss_mb + DRIVER_STEP_MB:
        return [f"RSS still grew {late:.1f} MB in the second half of the run (a leak; allowed: "
                f"{rss_mb:.1f} + one {DRIVER_STEP_MB:.0f} MB step of the GL driver's pools)"]
    return []


def soak(candela, scene, hours, size, rss_mb, tmp, repeats=False, seed=None, frame_ratio=3.0):
    frames = int(hours * 3600)  # --fps 1: one frame per animation second
    out = os.path.join(tmp, os.path.basename(scene) + ".y4m")
    cmd = [candela, "--display", "headless", "--scene", scene, "--size", size, "--fps", "1",
           "--frames", str(frames), "--out", out, "--log-level", "warn",
           "--mute"]  # 24 h of sound would be 8 GB of .wav; the sound has its own tests
    if seed is not None:
        cmd += ["--seed", str(seed)]
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    samples, stop = [], threading.Event()
    watcher = threading.Thread(target=sampler, args=(proc.pid, out, samples, stop))
    watcher.start()
    _, err = proc.communicate()
    stop.set()
    watcher.join()
    wall = time.monotonic() - start
    name = os.path.basename(scene)
    if proc.returncode != 0:
        print(f"{name}: candela exited {proc.returncode}: {err.decode()[-400:]}")
        return False
    problems = []
    # RSS after warm-up: the first 5 % builds caches, textures, GL state.
    # Only while frames were still coming: the samples after the last frame
    # are of the exit (GL torn down, RSS falling), not of the run.
    final = max((x[3] for x in samples), default=0)
    samples = [x for x in samples if x[3] < final] or samples
    # The eigen flames' frame cache fills as the walk first visits each model
    # frame (1 MB steps, the last at frame ~175 of the eigen fireplace): the
    # warm-up is also the first 400 frames (about 7 min of animation at --fps
    # 1), however fast the machine draws them.
    w, h = (int(v) for v in size.split("x"))
    warm_bytes = min(400, frames // 2) * (6 + w * h * 3)  # a .y4m 4:4:4 frame and its FRAME line
    warm_samples = [x for x in samples
                    if x[0] - start >= max(0.05 * wall, 5.0) and x[3] >= warm_bytes]
    if len(warm_samples) < 2:
        warm_samples = samples or [(start, 0, 0, 0)]
    warm = [(t, kb / 1024) for t, kb, _, _ in warm_samples]
    rss = [r for _, r in warm]
    first, last, peak = rss[0], rss[-1], max(rss)
    # candela's frame statistics fill a buffer reserved up front, 16 bytes a
    # frame up to --frames (at most 2^16 frames without --frames): pages it
    # touches as it goes, bounded, not a leak. Expected growth: along the run.
    fill = 16 * min(frames, 1 << 20) / 2**20
    problems += rss_problems(warm, fill, rss_mb, start + wall)
    # Open files: the same count from warm-up to the end (a leak of one fd per
    # reconnect or reload would show as a climb).
    fds = [x[2] for x in warm_samples]
    if fds and max(fds) > fds[0]:
        problems.append(f"open fds grew {fds[0]} -> {max(fds)}")
    # Frame time: ms a frame in each eighth of the run after warm-up (from
    # the output's growth), when each eighth is long enough to measure (5 s).
    # Steady: the slowest eighth within 3x the fastest (build machines are
    # shared and loaded; work that grows per frame climbs far more than that).
    w, h = (int(v) for v in size.split("x"))
    frame_bytes = 6 + 3 * w * h
    eighths = []
    if len(warm_samples) >= 9 and warm_samples[-1][0] - warm_samples[0][0] >= 40:
        for q in range(8):
            a = warm_samples[len(warm_samples) * q // 8]
            b = warm_samples[min(len(warm_samples) - 1, len(warm_samples) * (q + 1) // 8)]
            nf = (b[3] - a[3]) / frame_bytes
            if nf > 0:
                eighths.append(1000 * (b[0] - a[0]) / nf)
    # Growth is what a soak looks for: an eighth slower than ratio x the
    # fastest one before it (a machine whose load drops only speeds it up).
    fastest = float("inf")
    for v in eighths:
        if v > frame_ratio * fastest:
            problems.append("frame time grew: " + " ".join(f"{x:.1f}" for x in eighths) + " ms")
            break
        fastest = min(fastest, v)
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
    repeat_s = None
    if repeats:
        # --fps 1: one frame is one animation second.
        repeat_s = longest_repeat_frames(luma) / 1.0
        if repeat_s > 2.0:
            problems.append(f"a stretch of {repeat_s:.0f} s repeats an earlier one")
    verdict = "ok" if not problems else "FAIL: " + "; ".join(problems)
    track = " ".join(f"{rss[min(len(rss) - 1, len(rss) * q // 8)]:.1f}" for q in range(9))
    verdict += f"  (RSS by eighths of the run: {track}; fds {fds[0] if fds else 0}"
    if eighths:
        verdict += "; ms a frame by eighths: " + " ".join(f"{v:.1f}" for v in eighths)
    if repeat_s is not None:
        verdict += f"; longest repeat {repeat_s:.0f} s" if repeat_s else "; no repeat of 3 s or more"
    verdict += ")"
    print(f"{name:28s} {frames * 60:>9d} {wall:7.1f} {first:7.1f} {last:7.1f} {peak:7.1f} "
          f"{first_hour:6.1f} {last_hour:6.1f} {min(moving):6.1f}  {verdict}", flush=True)
    return not problems


def self_test():
    """The repeat check on made-up frames: none in noise; a copied stretch
    (with a little noise on top) found at its length; a walk stuck in a loop."""
    rng = np.random.default_rng(1)
    frames = rng.integers(0, 256, size=(5000, 18, 32), dtype=np.uint8)
    ok = True

    def expect(what, got, want):
        nonlocal ok
        print(("ok   " if got == want else "FAIL ") + f"{what}: {got} (expected {want})")
        ok &= got == want
    expect("noise: no repeat", longest_repeat_frames(frames), 0)
    copied = frames.copy()
    noise = rng.integers(-2, 3, size=(10, 18, 32))
    copied[4000:4010] = np.clip(copied[1234:1244].astype(int) + noise, 0, 255).astype(np.uint8)
    expect("a 10-frame stretch copied 2766 frames later", longest_repeat_frames(copied), 10)
    loop = frames.copy()
    loop[3000:] = np.resize(frames[2900:3000], (2000, 18, 32))  # period 100 from frame 2900
    expect("stuck in a 100-frame loop", longest_repeat_frames(loop) >= 1900, True)
    # The RSS judgement on made-up tracks (a sample a second for 100 s, 1 MB allowed).
    t = range(100)
    expect("flat RSS", rss_problems([(x, 140.0) for x in t], 0.0, 1.0, 100), [])
    expect("the driver's two 1 MB steps early on",
           rss_problems([(x, 140.0 + (x > 10) + (x > 20)) for x in t], 0.0, 1.0, 100), [])
    expect("the frame statistics' 1.5 MB filled along the run",
           rss_problems([(x, 140.0 + 1.5 * x / 100) for x in t], 1.5, 1.0, 100), [])
    expect("three 1 MB steps mid-run, as once on CI (then flat)",
           rss_problems([(x, 140.0 + (x > 35) + (x > 50) + (x > 60)) for x in t], 0.0, 1.0, 100), [])
    expect("a leak of 5 MB along the run", len(rss_problems([(x, 140.0 + 0.05 * x) for x in t],
                                                            0.0, 1.0, 100)), 1)
    expect("a leak of 2.5 MB in the second half", len(rss_problems(
        [(x, 140.0 + 0.05 * max(0, x - 50)) for x in t], 0.0, 1.0, 100)), 1)
    expect("a 5 MB jump", len(rss_problems([(x, 140.0 + 5 * (x > 30)) for x in t], 0.0, 1.0, 100)), 1)
    return 0 if ok else 1


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scenes", nargs="*")
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--hours", type=float, default=24.0, help="animation time per scene")
    ap.add_argument("--size", default="32x18")
    ap.add_argument("--rss-mb", type=float, default=1.0, help="allowed RSS change after warm-up")
    ap.add_argument("--repeats", action="store_true",
                    help="also the no-repeat check over the whole run (graph-walk scenes)")
    ap.add_argument("--seed", type=int, help="candela --seed")
    ap.add_argument("--frame-time-ratio", type=float, default=3.0,
                    help="allowed growth of ms a frame: an eighth of the run over the fastest before it")
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
            ok &= soak(candela, s, a.hours, a.size, a.rss_mb, tmp, a.repeats, a.seed, a.frame_time_ratio)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
