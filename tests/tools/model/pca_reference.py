"""Independent PCA for the tests: numpy's SVD of the centred frames.
usage: pca_reference.py FRAMES.u8 FRAMES HEIGHT WIDTH K OUT.txt
writes: line 1: the K largest variances (sigma^2 / n); then the K principal
directions, one per line (unit vectors over the pixels)."""
import sys
import numpy as np

path, frames, height, width, k, out = sys.argv[1:7]
frames, height, width, k = int(frames), int(height), int(width), int(k)
x = np.fromfile(path, dtype=np.uint8).astype(np.float64).reshape(frames, height * width)
xc = x - x.mean(axis=0)
_, s, vt = np.linalg.svd(xc, full_matrices=False)
with open(out, "w") as f:
    f.write(" ".join(repr(v) for v in (s[:k] ** 2 / frames)) + "\n")
    for row in vt[:k]:
        f.write(" ".join(repr(v) for v in row) + "\n")
