#!/usr/bin/python3
"""The shared yardsticks' own numbers, for candela-tool measure's agreement tests.

usage: eval_reference.py EVAL_DIR LIMIT OUT.json CLIP DIR FPS [CLIP DIR FPS ...] [--pair A B ...]

Runs ../shared/eval/flame_features.py (features) and realism.py (stats, repeats, compare)
unchanged, except that each clip's frames are read once (the first LIMIT, as
flame_features.load reads them) and handed to both scripts. Writes one JSON object:
{"clips": {CLIP: {"features": ..., "stats": ..., "repeats": ...}}, "pairs": {"A B": compare}}.
"""
import json
import math
import sys

import numpy as np


def clean(x):
    """NaN -> None, so the JSON is standard."""
    if isinstance(x, dict):
        return {k: clean(v) for k, v in x.items()}
    if isinstance(x, float) and math.isnan(x):
        return None
    return x


def main(a):
    eval_dir, limit, out = a[0], int(a[1]), a[2]
    sys.dont_write_bytecode = True  # leave the shared folder as it is
    sys.path.insert(0, eval_dir)
    import flame_features as ff
    import realism as rl

    rest = a[3:]
    pairs = []
    if '--pair' in rest:
        i = rest.index('--pair')
        p = rest[i + 1:]
        pairs = [(p[j], p[j + 1]) for j in range(0, len(p), 2)]
        rest = rest[:i]
    clips = [(rest[j], rest[j + 1], float(rest[j + 2])) for j in range(0, len(rest), 3)]

    ims, raw = {}, {}
    for name, d, fps in clips:
        ims[d] = ff.load(d, limit)
        raw[d] = np.stack([np.asarray(im, np.float32) / 255.0 for im in ims[d]])
    # The scripts load by folder; hand them the frames already read.
    ff.load = lambda d, limit=900: ims[d]
    rl.load = lambda d, limit=None: raw[d]

    res = {'clips': {}, 'pairs': {}}
    dirs = {name: (d, fps) for name, d, fps in clips}
    for name, d, fps in clips:
        res['clips'][name] = {'features': ff.features(d, fps), 'stats': rl.stats(d, fps),
                              'repeats': rl.repeats(d, fps)}
    for x, y in pairs:
        (da, fa), (db, fb) = dirs[x], dirs[y]
        res['pairs'][x + ' ' + y] = rl.compare(da, fa, db, fb)
    with open(out, 'w') as f:
        json.dump(clean(res), f)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
