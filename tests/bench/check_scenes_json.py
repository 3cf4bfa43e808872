#!/usr/bin/env python3
"""check_scenes_json.py < scenes.py --json: every built-in scene and the empty
floor reported, with frame times in order (p50 <= p95 <= p99), a CPU time a
frame, RSS, a start-up time inside the run's own, and ratios that are each
scene's CPU time over the floor's."""
import json
import os
import sys

sys.path.insert(0, __file__.rsplit("/", 1)[0])
from scenes import SCENES  # noqa: E402

TICK_MS = 1000.0 / os.sysconf("SC_CLK_TCK")
report = json.load(sys.stdin)
rows = {r["scene"]: r for r in report["scenes"]}
problems = []
if sorted(rows) != sorted(["empty"] + SCENES):
    problems.append("expected the empty scene and %s, got %s" % (SCENES, sorted(rows)))
floor = rows.get("empty", {}).get("cpu_ms_per_frame") or 0
for name, r in rows.items():
    if not 0 <= r["frame_ms_p50"] <= r["frame_ms_p95"] <= r["frame_ms_p99"]:
        problems.append("%s: frame times out of order: %s" % (name, r))
    if not (r["cpu_ms_per_frame"] > 0 and r["peak_rss_mb"] > 0):
        problems.append("%s: no CPU time or RSS: %s" % (name, r))
    # Start-up: from the process's start (the kernel's record) to its first
    # frame; inside the run as timed from outside it, so a wrong clock shows.
    # The kernel records the start in whole clock ticks (10 ms at USER_HZ
    # 100), so the start-up can read up to one tick long: a run of 8 tiny
    # frames (52 ms) once read 54.5.
    if not (r.get("first_frame_ms") is not None and
            0 < r["first_frame_ms"] <= r["wall_ms"] + TICK_MS):
        problems.append("%s: first frame at %s ms, expected within the run's %.0f ms" %
                        (name, r.get("first_frame_ms"), r["wall_ms"]))
    if floor > 0 and abs(r["ratio_to_empty"] - r["cpu_ms_per_frame"] / floor) > 1e-6:
        problems.append("%s: ratio %g is not CPU %g over the empty scene's %g" %
                        (name, r["ratio_to_empty"], r["cpu_ms_per_frame"], floor))
for p in problems:
    print("check_scenes_json: " + p)
print("%d scenes checked, %d problems" % (len(rows), len(problems)))
sys.exit(1 if problems else 0)
