#!/usr/bin/env python3
"""Where does MRSV lose rate-distortion against JPEG 2000 on terrains? (issue 4)

A controlled comparison of transforms alone: every transform gets the same
quantiser (the reference encoder's: step delta / g_b per band, dead zone 0.3 on
detail bands, rounding on the coarsest block) and the same rate measure (the
first-order entropy of the quantised integers of each band, the coarsest block
as differences along x). Only the transform differs:

  bspline k=1..4   MRSV's semi-orthogonal B-spline wavelets (spec 4), the axis
                   plans the encoder chooses (spec 4.10), matrices built from the
                   filter tables by tools/wavelets/make_filters.py;
  discrete k=2     the same linear B-spline spaces with the wavelets orthogonal to
                   the coarse space for the *sample* inner product (taps -1/2, 1,
                   -1/2) instead of the L2 inner product of functions;
  cdf 5/3, 9/7     the JPEG 2000 lifting wavelets, whole-sample symmetric
                   extension, 5 levels (OpenJPEG's default).

It prints PSNR (peak = max - min) at 0.5, 1, 2 and 4 bits/sample, interpolated
in log rate, and the non-orthogonality ("Hadamard") loss of each 1-D synthesis
matrix: log2(prod ||s_i|| / |det S|) / N bits per sample per axis, the rate a
quantiser pays because the cells of the lattice S * diag(steps) * Z^N are
skewed. Nothing here is normative; it explains a measurement.

  /usr/bin/python3 tools/bench/transform_gain.py [--dataset mt_st_helens|big_tujunga]
"""
import argparse
import math
import os
import subprocess
import sys

try:
    import numpy as np
except ImportError:  # pyenv or venv python without numpy: use Debian's
    if os.path.exists("/usr/bin/python3") and sys.executable != "/usr/bin/python3":
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    raise

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools", "wavelets"))
import make_filters  # noqa: E402  (exact filter tables, spec 4.2)

DATASETS = {
    "mt_st_helens": (317, 460, "mt_st_helens_317x460_int16le.raw.zst"),
    "big_tujunga": (1197, 643, "big_tujunga_1197x643_int16le.raw.zst"),
}
N_MIN = {1: 1, 2: 4, 3: 7, 4: 11}  # spec 4.2
DEAD_ZONE = 0.3                      # spec 5.9 item 5
RATES = (0.5, 1, 2, 4)
COARSEST = 99                        # band label of the coarsest scaling block


def choose_levels(n, k):
    """spec 4.10: the most levels (<= 16) whose padding is at most N/32."""
    d = k - 1
    for levels in range(16, 0, -1):
        if n < k:
            continue
        n0 = -(-(n - d) // 2 ** levels)
        if n0 < N_MIN[k]:
            continue
        if (n0 * 2 ** levels + d - n) * 32 <= n:
            return levels
    return 0


def dense(cols, rows):
    m = np.zeros((rows, len(cols)))
    for j, (first, taps) in enumerate(cols):
        m[first:first + len(taps), j] = [float(t) for t in taps]
    return m


def bspline_synthesis(n, k, order_tables):
    """1-D synthesis matrix (padded size) and band labels of MRSV's transform."""
    d = k - 1
    levels = choose_levels(n, k)
    n0 = -(-(n - d) // 2 ** levels)
    size = n0 * 2 ** levels + d
    s = np.eye(size)
    labels = np.zeros(size, int)
    fine = size
    for j in range(1, levels + 1):
        nj = n0 * 2 ** (levels - j)  # coarse intervals of this step
        coarse = nj + d
        level = np.hstack([dense(order_tables.p_columns(nj), fine),
                           dense(order_tables.q_columns(nj), fine)])
        e = np.eye(size)
        e[:fine, :fine] = level
        s = s @ e
        labels[coarse:fine] = j
        fine = coarse
    labels[:fine] = COARSEST
    return s, labels


def discrete_linear_synthesis(n, levels=5):
    """Linear B-spline spaces, wavelets orthogonal for the sample inner product."""
    n0 = -(-(n - 1) // 2 ** levels)
    size = n0 * 2 ** levels + 1
    s = np.eye(size)
    labels = np.zeros(size, int)
    fine = size
    for j in range(1, levels + 1):
        nj = n0 * 2 ** (levels - j)
        level = np.zeros((fine, fine))
        for c in range(nj + 1):  # hat functions
            for r, v in ((2 * c - 1, .5), (2 * c, 1.), (2 * c + 1, .5)):
                if 0 <= r < fine:
                    level[r, c] = v
        for w in range(nj):      # -1/2, 1, -1/2 centred on odd rows
            level[2 * w:2 * w + 3, nj + 1 + w] = (-.5, 1., -.5)
        e = np.eye(size)
        e[:fine, :fine] = level
        s = s @ e
        labels[nj + 1:fine] = j
        fine = nj + 1
    labels[:fine] = COARSEST
    return s, labels


def lifting_synthesis(n, steps, levels=5):
    """Inverse of a lifting wavelet (symmetric extension), Mallat layout."""
    def forward(x):
        x = x.copy()
        m = len(x)

        def ext(i):
            return -i if i < 0 else 2 * (m - 1) - i if i >= m else i
        for coefficient, parity in steps:
            y = x.copy()
            for i in range(parity, m, 2):
                y[i] = x[i] + coefficient * (x[ext(i - 1)] + x[ext(i + 1)])
            x = y
        return np.concatenate([x[0::2], x[1::2]])
    t = np.eye(n)
    labels = np.zeros(n, int)
    m = n
    for j in range(1, levels + 1):
        t[:m] = np.array([forward(col) for col in t[:m].T]).T
        half = (m + 1) // 2
        labels[half:m] = j
        m = half
    labels[:m] = COARSEST
    return np.linalg.inv(t), labels


CDF53 = [(-0.5, 1), (0.25, 0)]
CDF97 = [(-1.586134342, 1), (-0.05298011854, 0), (0.8829110762, 1), (0.4435068522, 0)]


def hadamard_loss(s):
    _, logdet = np.linalg.slogdet(s)
    return (np.log(np.linalg.norm(s, axis=0)).sum() - logdet) / math.log(2) / s.shape[0]


def rate_distortion(x, sy, ly, sx, lx, deltas):
    my, mx = sy.shape[0], sx.shape[0]
    padded = np.pad(x, ((0, my - x.shape[0]), (0, mx - x.shape[1])), mode="edge")
    c = np.linalg.solve(sy, padded) @ np.linalg.inv(sx).T
    gain = np.outer(np.linalg.norm(sy, axis=0), np.linalg.norm(sx, axis=0))
    coarsest = np.outer(ly == COARSEST, lx == COARSEST)
    rounding = np.where(coarsest, 0.5, DEAD_ZONE)
    peak = x.max() - x.min()
    curve = []
    for delta in deltas:
        step = delta / gain
        q = np.sign(c) * np.floor(np.abs(c) / step + rounding)
        decoded = sy @ (q * step) @ sx.T
        mse = np.mean((decoded[:x.shape[0], :x.shape[1]] - x) ** 2)
        bits = 0.0
        for by in np.unique(ly):
            for bx in np.unique(lx):
                band = q[np.ix_(ly == by, lx == bx)]
                if by == COARSEST and bx == COARSEST and band.shape[1] > 1:
                    band = np.diff(band, axis=1)
                _, counts = np.unique(band.ravel(), return_counts=True)
                bits -= (counts * np.log2(counts / counts.sum())).sum()
        curve.append((bits / x.size, 10 * math.log10(peak ** 2 / mse)))
    return curve


def psnr_at(curve, rate):
    rates = np.log2([r for r, _ in curve])
    order = np.argsort(rates)
    return float(np.interp(math.log2(rate), rates[order], np.array([p for _, p in curve])[order]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--dataset", default="mt_st_helens", choices=sorted(DATASETS))
    ap.add_argument("--data", default=os.path.join(ROOT, "..", "shared", "data"))
    args = ap.parse_args()
    width, height, name = DATASETS[args.dataset]
    raw = subprocess.run(["zstd", "-dc", os.path.join(args.data, "terrain", name)],
                         check=True, capture_output=True).stdout
    x = np.frombuffer(raw, "<i2").reshape(height, width).astype(float)
    deltas = [0.5, 1, 2, 4, 8, 16, 32, 64]
    transforms = {}
    for k in (1, 2, 3, 4):
        tables = make_filters.Order(k)
        transforms[f"bspline k={k}"] = (bspline_synthesis(height, k, tables),
                                        bspline_synthesis(width, k, tables))
    transforms["discrete k=2"] = (discrete_linear_synthesis(height), discrete_linear_synthesis(width))
    transforms["cdf 5/3"] = (lifting_synthesis(height, CDF53), lifting_synthesis(width, CDF53))
    transforms["cdf 9/7"] = (lifting_synthesis(height, CDF97), lifting_synthesis(width, CDF97))
    print(f"{args.dataset} {width}x{height}: PSNR dB at first-order-entropy rates "
          f"(same quantiser for all); Hadamard loss in bits/sample/axis")
    print(f"{'transform':14s} " + " ".join(f"{'R=' + str(r):>8s}" for r in RATES) +
          "   vs k=2 @1   loss y   loss x")
    rows = {}
    for label, ((sy, ly), (sx, lx)) in transforms.items():
        curve = rate_distortion(x, sy, ly, sx, lx, deltas)
        rows[label] = ([psnr_at(curve, r) for r in RATES], hadamard_loss(sy), hadamard_loss(sx))
        sys.stderr.write(f"  {label} done\n")
    base = rows["bspline k=2"][0][1]
    for label, (psnrs, loss_y, loss_x) in rows.items():
        print(f"{label:14s} " + " ".join(f"{p:8.2f}" for p in psnrs) +
              f"   {psnrs[1] - base:+7.2f}   {loss_y:6.3f}   {loss_x:6.3f}")


if __name__ == "__main__":
    main()
