#!/usr/bin/env python3
"""candela-tool story --size (issue 34): frames rendered at a chosen size show
the model's flame scaled to fit, its aspect kept, centred on black.

check_fit.py NATIVE_DIR SIZED_DIR WIDTH HEIGHT
NATIVE_DIR: the same story's PNG frames at the model's own size. For frames
spread over the story: the sized frame is WIDTHxHEIGHT; the flame's middle
(its light's centroid) sits where it sits in the native frame, once the
native frame is scaled and centred; shrunk back to the native size, the
fitted part matches the native frame (mean difference under 4 of 255, the
glow being blurred at the new size); the bars beside it stay dark.
"""
import os, sys

import numpy as np
from PIL import Image


def load(path):
    return np.asarray(Image.open(path).convert("RGB"), dtype=np.float64)


def centroid(img):
    light = img.sum(axis=2)
    ys, xs = np.indices(light.shape)
    return (xs * light).sum() / light.sum(), (ys * light).sum() / light.sum()


native_dir, sized_dir, W, H = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
names = sorted(n for n in os.listdir(native_dir) if n.endswith(".png"))
if not names or sorted(n for n in os.listdir(sized_dir) if n.endswith(".png")) != names:
    sys.exit("FAIL: %s and %s do not hold the same frames" % (native_dir, sized_dir))
failures = 0
for name in names[:: max(1, len(names) // 8)]:
    a = load(os.path.join(native_dir, name))
    b = load(os.path.join(sized_dir, name))
    h, w = a.shape[:2]
    if b.shape[:2] != (H, W):
        print("FAIL %s: %dx%d, expected %dx%d" % (name, b.shape[1], b.shape[0], W, H))
        failures += 1
        continue
    scale = min(W / w, H / h)
    fw, fh = round(w * scale), round(h * scale)
    x0, y0 = (W - fw) // 2, (H - fh) // 2
    fitted = b[y0:y0 + fh, x0:x0 + fw]
    back = np.asarray(Image.fromarray(fitted.astype(np.uint8)).resize((w, h), Image.BILINEAR),
                      dtype=np.float64)
    diff = np.abs(back - a).mean()
    cxa, cya = centroid(a)
    cxb, cyb = centroid(b)
    off = max(abs(x0 + cxa * scale - cxb), abs(y0 + cya * scale - cyb))
    bars = np.concatenate([b[:, :max(0, x0 - fw // 4)], b[:, x0 + fw + fw // 4:]], axis=1)
    bar_light = bars.max() if bars.size else 0
    ok = diff < 4 and off < 0.02 * H and bar_light < 24
    print("%s %s: mean difference %.2f of 255, centroid off by %.1f px, bars at most %d"
          % ("ok  " if ok else "FAIL", name, diff, off, bar_light))
    failures += not ok
sys.exit(1 if failures else 0)
