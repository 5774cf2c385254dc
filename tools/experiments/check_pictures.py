#!/usr/bin/python3
"""Checks what section7.sh wrote: report.md and results.json present, every PNG there,
of a sane size, not blank, and the four methods' pictures of a level told apart.

  check_pictures.py OUT_DIR                      check an existing run
  check_pictures.py --run --mrsv M --data D OUT  run 'section7.sh --quick' into OUT first

Exit 0 when every check passes; otherwise one line per failed check and exit 1.
"""
import argparse
import itertools
import json
import os
import subprocess
import sys

import numpy as np

import matplotlib
matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402

METHODS = ["quadtree", "insertion", "pm_paper", "pm_quadric"]
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
    return ok


def load(path):
    """The PNG as an H x W x 3 float array in [0, 1], or None."""
    if not check(os.path.isfile(path), "%s: missing" % path):
        return None
    check(os.path.getsize(path) >= 8000, "%s: only %d bytes" % (path, os.path.getsize(path)))
    img = mpimg.imread(path)
    if img.dtype != np.float32:
        img = img / 255.0
    if img.ndim == 2:
        img = np.stack([img] * 3, -1)
    return img[..., :3]


def sane(path, img, min_w, min_h, min_ink=0.10):
    h, w = img.shape[:2]
    check(w >= min_w and h >= min_h, "%s: %d x %d pixels, under %d x %d" % (path, w, h, min_w, min_h))
    grey = img.mean(axis=2)
    not_white = float((grey < 0.97).mean())
    check(not_white > min_ink, "%s: blank (%.1f %% of the pixels not white)" % (path, 100 * not_white))
    check(float(grey.std()) > min_ink / 2, "%s: flat (grey level std %.3f)" % (path, grey.std()))
    # colour: the error scale must show (a grey-only picture lost its colour map)
    sat = img.max(axis=2) - img.min(axis=2)
    return float((sat > 0.15).mean())


def plot_area(img):
    """The central part of a picture (the map, without title and colour bar)."""
    h, w = img.shape[:2]
    return img[int(0.2 * h):int(0.8 * h), int(0.1 * w):int(0.7 * w)]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--run", action="store_true")
    ap.add_argument("--mrsv")
    ap.add_argument("--data")
    a = ap.parse_args()
    here = os.path.dirname(os.path.abspath(__file__))
    if a.run:
        env = dict(os.environ)
        if a.mrsv:
            env["MRSV"] = a.mrsv
        if a.data:
            env["MRSV_SHARED_DATA"] = a.data
        p = subprocess.run(["bash", os.path.join(here, "section7.sh"), "--quick", a.out], env=env)
        if p.returncode != 0:
            print("check_pictures: section7.sh --quick failed (exit %d)" % p.returncode)
            return 1

    out = a.out
    check(os.path.isfile(os.path.join(out, "report.md")), "report.md missing")
    try:
        with open(os.path.join(out, "results.json")) as f:
            results = json.load(f)
    except (OSError, ValueError) as e:
        print("check_pictures: results.json: %s" % e)
        return 1
    terrain = results[results["terrain_main"]]
    nlev = len(terrain["levels"])
    check(nlev >= 2, "7.1 has %d levels" % nlev)
    for li, lvl in enumerate(terrain["levels"]):
        n = [lvl["methods"][k]["triangles"] for k in METHODS]
        check(max(n) - min(n) <= 2, "7.1 level %d: triangle counts differ: %s" % (li + 1, n))
        for k in METHODS:
            m = lvl["methods"][k]
            check(0 <= m["rms"] <= m["hausdorff"], "7.1 level %d %s: RMS %s, Hausdorff %s" %
                  (li + 1, k, m["rms"], m["hausdorff"]))

    with open(os.path.join(out, "report.md")) as f:
        text = f.read()
    for li in range(nlev):
        imgs = {}
        for k in METHODS:
            fn = "fig5_%s_L%d.png" % (k, li + 1)
            img = load(os.path.join(out, fn))
            check(fn in text or "fig5_<method>_L<level>.png" in text, "report.md does not name %s" % fn)
            if img is None:
                continue
            colour = sane(fn, img, 500, 500)
            check(colour > 0.05, "%s: no error colours (%.1f %% coloured pixels)" % (fn, 100 * colour))
            imgs[k] = plot_area(img)
        for x, y in itertools.combinations(sorted(imgs), 2):
            h = min(imgs[x].shape[0], imgs[y].shape[0])
            w = min(imgs[x].shape[1], imgs[y].shape[1])
            diff = float(np.abs(imgs[x][:h, :w] - imgs[y][:h, :w]).mean())
            check(diff > 0.02, "level %d: %s and %s look alike (mean difference %.4f)" % (li + 1, x, y, diff))
    img = load(os.path.join(out, "fig5_montage.png"))
    if img is not None:
        sane("fig5_montage.png", img, 200 * nlev, 800)
    img = load(os.path.join(out, "fig5_readme.png"))
    if img is not None:
        sane("fig5_readme.png", img, 700, 200)
    if "terrain_companion" in results:
        img = load(os.path.join(out, "fig5_montage_%s.png" % results["terrain_companion"]))
        if img is not None:
            sane("fig5_montage_%s.png" % results["terrain_companion"], img, 200 * nlev, 800)
    plots = {}
    for fn in ("fig3a_psnr.png", "fig3b_times.png"):
        img = load(os.path.join(out, fn))
        if img is not None:
            sane(fn, img, 500, 350, min_ink=0.03)
            plots[fn] = img
    if len(plots) == 2:
        p, q = plots.values()
        h, w = min(p.shape[0], q.shape[0]), min(p.shape[1], q.shape[1])
        check(float(np.abs(p[:h, :w] - q[:h, :w]).mean()) > 0.005, "fig3a and fig3b look alike")
    vol = results["volume"]
    for lvl in vol["levels"]:
        for k, m in lvl["methods"].items():
            check(m["valid"] and m["outside"] == 0 and 10 < m["psnr_db"] < 200,
                  "7.2 %d tets %s: valid %s, outside %s, PSNR %s" % (lvl["target"], k, m["valid"], m["outside"],
                                                                    m["psnr_db"]))
    for f in failures:
        print("check_pictures: " + f)
    if not failures:
        pngs = [f for f in os.listdir(out) if f.endswith(".png")]
        print("check_pictures: %d PNGs, report.md and results.json pass" % len(pngs))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
