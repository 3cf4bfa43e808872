#!/usr/bin/env python3
"""The arm64 frame comparison's own check, on real frames: the Perlin
fireplace rendered by this build (candela-state-hash) after steps 1 and 300.
Its rule for the fireplace (each pixel against the other frame's 3x3
neighbourhood) must let an edge move by a pixel -- what llvmpipe's texel
rounding does between x86 and arm64 -- and must still catch another moment of the fire (flames moved and
reshaped) and a fire gone dark, which the scenes' frames would show if a
build's animation or shader went wrong.

  compare_builds_test.py PROG OUT_DIR
"""
import argparse
import os
import subprocess
import sys

import numpy as np
from PIL import Image

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compare_builds  # noqa: E402


def main():
    prog, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    subprocess.run([prog, "--steps", "300", "--every", "300", "--size", "160x90",
                    "--frames-at", "1,300", "--out", out, "perlin-fireplace"],
                   check=True, stdout=subprocess.DEVNULL)
    load = lambda step: np.asarray(Image.open(os.path.join(out, f"perlin-fireplace-{step}.png")),
                                   dtype=np.int16)
    first, later = load(1), load(300)
    args = argparse.Namespace(tolerance=2, share=0.15, max=32)
    lit = first[..., :3].max(axis=-1) > 64
    assert lit.mean() > 0.1, f"the fireplace lights {lit.mean():.1%} of the frame, expected a fire"

    moved = np.roll(first, 1, axis=1)  # every edge one pixel to the right
    cases = [("every edge moved a pixel", moved, True),
             ("the fire 300 steps later", later, False),
             ("the fire dark", np.where(lit[..., None], first // 3, first), False)]
    failures = []
    for what, other, alike in cases:
        plain = compare_builds.compare_frames(first, other, args)
        ok, stats, rule = compare_builds.compare_frames(first, other, args, loose=True)
        print(f"{what}: {stats}: {'alike' if ok else 'different'} (plain rule: "
              f"{'alike' if plain[0] else 'different'})")
        if ok != alike:
            failures.append(f"{what}: expected {'alike' if alike else 'different'} ({rule})")
        if what.startswith("an edge") and plain[0]:
            failures.append(f"{what}: the plain rule should not pass it, or the case tests nothing")
    for f in failures:
        print("compare_builds_test: " + f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
