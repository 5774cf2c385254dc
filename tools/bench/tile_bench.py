#!/usr/bin/env python3
"""Issue 24's measured goals for tiled grids, peers measured in the same run.

  1. A terrain mosaic of at least 12,000 x 12,000 samples, built from the three SRTM
     tiles of ../shared/data by tiling with mirroring (each copy reflected so that
     neighbours meet along equal edges; a stand-in until larger real data is
     available): encoded with 256 x 256 tiles, on 1 and 2 threads (same bytes,
     speed-up), peak memory against the raw size; decoded whole and as a 512 x 512
     region (speed ratio, bytes read), against OpenJPEG's tiled JPEG 2000 at the
     same rate decoded with opj_decompress -d on the same window. The same grid in
     precincts of 256^2 (spec 5.7.6): out-of-core encode (peak memory, 1 and 2
     threads), whole decode, the region, OpenJPEG. mrsv-mpi on 1 and 2 ranks, tiles
     and precincts (speed-up, same bytes as mrsv encode).
  2. Rate-distortion at 1 bit per sample, tiled (256^2, and 64^3 bricks for a CT
     volume) and in precincts of the same size (spec 5.7.6) against neither, per grid.

  python3 tools/bench/tile_bench.py [--mrsv build/mrsv] [--side 12010] [--quick]

--quick uses a 2402 x 2402 mosaic and skips nothing else (a smoke run).
"""
import argparse
import math
import os
import re
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
DATA = os.path.join(ROOT, "..", "shared", "data")
SRTM = ["srtm3_N27E086_mt_everest_1201x1201_int16le", "srtm3_N35E138_mt_fuji_1201x1201_int16le",
        "srtm3_N46W122_mt_rainier_1201x1201_int16le"]


def load(name, tmp):
    path = os.path.join(tmp, name + ".raw")
    if not os.path.exists(path):
        subprocess.run(["zstd", "-dqf", os.path.join(DATA, "terrain" if "x1201" in name or "tujunga" in name
                                                       else "volume", name + ".raw.zst"), "-o", path], check=True)
    return path


def mosaic(tmp, side):
    """side x side int16: SRTM tiles (voids filled by their row's neighbour) laid out
    with mirroring; numpy does the work."""
    import numpy as np
    tiles = []
    for name in SRTM:
        a = np.fromfile(load(name, tmp), dtype="<i2").reshape(1201, 1201).copy()
        voids = a == -32768
        if voids.any():
            a[voids] = int(np.median(a[~voids]))
        tiles.append(a)
    n = math.ceil(side / 1201)
    rows = []
    for j in range(n):
        row = []
        for i in range(n):
            t = tiles[(i + 2 * j) % len(tiles)]
            if i % 2:
                t = t[:, ::-1]
            if j % 2:
                t = t[::-1, :]
            row.append(t)
        rows.append(np.hstack(row))
    m = np.vstack(rows)[:side, :side]
    path = os.path.join(tmp, f"mosaic_{side}.raw")
    m.astype("<i2").tofile(path)
    return path


def run(cmd, **kw):
    """(seconds, peak RSS in MB, stderr) of a command."""
    t = time.perf_counter()
    p = subprocess.run(["/usr/bin/time", "-f", "maxrss %M"] + cmd, capture_output=True, text=True, **kw)
    dt = time.perf_counter() - t
    if p.returncode != 0:
        sys.exit(f"tile_bench: {' '.join(cmd)} failed: {p.stderr.strip()[-400:]}")
    rss = int(re.search(r"maxrss (\d+)", p.stderr).group(1)) / 1024
    return dt, rss, p.stderr


def best(cmd, repeat=3):
    return min(run(cmd)[0] for _ in range(repeat))


def psnr_of(stderr):
    m = re.search(r"PSNR ([0-9.inf]+) dB", stderr)
    return float(m.group(1)) if m else float("nan")


def mpi_speedup(mpi, tmp, label, options, raw, reference):
    """mrsv-mpi encode and decode on 1 and 2 ranks: the wall time of mpirun
    and the ranks' own time (mrsv-mpi's status line: from the moment every
    rank has started, without mpirun's and MPI_Init's start-up)."""
    def ranks_time(stderr):
        m = re.search(r"ranks, ([0-9.]+) s", stderr)
        return float(m.group(1)) if m else float("nan")
    mpirun = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np"]
    times, inner = {}, {}
    for np_ in (1, 2):
        times[np_], _, err = run([*mpirun, str(np_), mpi, "encode", *options, raw,
                                  os.path.join(tmp, f"mpi{np_}.mrsv")])
        inner[np_] = ranks_time(err)
    same = open(os.path.join(tmp, "mpi2.mrsv"), "rb").read() == open(reference, "rb").read()
    print(f"mrsv-mpi encode, {label}: {times[1]:.1f} s on 1 rank, {times[2]:.1f} s on 2 (speed-up "
          f"{times[1] / times[2]:.2f}x; the ranks' own time {inner[1]:.1f} s and {inner[2]:.1f} s, "
          f"{inner[1] / inner[2]:.2f}x); same stream as mrsv encode: {same}")
    dec, dec_inner = {}, {}
    for np_ in (1, 2):
        runs = [run([*mpirun, str(np_), mpi, "decode", os.path.join(tmp, "mpi2.mrsv"),
                     os.path.join(tmp, "mpi.raw")]) for _ in range(2)]
        dec[np_] = min(r[0] for r in runs)
        dec_inner[np_] = min(ranks_time(r[2]) for r in runs)
    print(f"mrsv-mpi decode, {label}: {dec[1]:.2f} s on 1 rank, {dec[2]:.2f} s on 2 (speed-up "
          f"{dec[1] / dec[2]:.2f}x; the ranks' own time {dec_inner[1]:.2f} s and {dec_inner[2]:.2f} s, "
          f"{dec_inner[1] / dec_inner[2]:.2f}x)")
    for np_ in (1, 2):
        os.remove(os.path.join(tmp, f"mpi{np_}.mrsv"))
    os.remove(os.path.join(tmp, "mpi.raw"))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--mrsv", default=os.path.join(ROOT, "build", "mrsv"))
    ap.add_argument("--side", type=int, default=12010)
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    mrsv = os.path.abspath(args.mrsv)
    side = 2402 if args.quick else args.side
    with tempfile.TemporaryDirectory(prefix="mrsv-tile-bench-") as tmp:
        print(f"== mosaic {side} x {side} int16 ({side * side * 2 / 2**20:.0f} MiB raw), 256 x 256 tiles")
        raw = mosaic(tmp, side)
        raw_mb = os.path.getsize(raw) / 2**20
        dims = ["--dims", f"{side},{side}", "--type", "int16"]
        out = {}
        for threads in (1, 2):
            out[threads] = os.path.join(tmp, f"m{threads}.mrsv")
            dt, rss, _ = run([mrsv, "encode", "--quiet", *dims, "--tile", "256", "--max-error", "2", "--bound-route", "residual",
                              "--threads", str(threads), raw, out[threads]])
            print(f"encode --max-error 2 (residual route), {threads} thread(s): {dt:.1f} s, peak {rss:.0f} MB "
                  f"({100 * rss / raw_mb:.0f} % of raw)")
            if threads == 1:
                t1 = dt
            else:
                print(f"  speed-up 1 -> 2 threads: {t1 / dt:.2f}x; streams identical: "
                      f"{open(out[1], 'rb').read() == open(out[2], 'rb').read()}")
        stream = out[2]
        size = os.path.getsize(stream)
        bps = 8 * size / (side * side)
        print(f"stream {size / 2**20:.1f} MiB, {bps:.3f} bits/sample")
        whole1 = best([mrsv, "decode", "--quiet", "--threads", "1", stream, os.path.join(tmp, "w.raw")], 2)
        whole2 = best([mrsv, "decode", "--quiet", "--threads", "2", stream, os.path.join(tmp, "w.raw")], 2)
        print(f"decode whole: {whole1:.2f} s on 1 thread, {whole2:.2f} s on 2 (speed-up {whole1 / whole2:.2f}x)")
        x0, y0 = side // 2 - 200, side // 3 + 77
        box = f"{x0},{y0},{x0 + 512},{y0 + 512}"
        region = best([mrsv, "decode", "--quiet", "--threads", "1", "--region", box, stream, os.path.join(tmp, "r.raw")])
        _, _, err = run([mrsv, "decode", "--threads", "1", "--region", box, stream, os.path.join(tmp, "r.raw")])
        read = re.search(r"(\d+) of (\d+) bytes read", err)
        print(f"decode 512 x 512 region {box}: {1000 * region:.0f} ms, {whole1 / region:.0f}x faster than the "
              f"whole (1 thread); {int(read.group(1)) / 2**10:.0f} KiB of {int(read.group(2)) / 2**20:.1f} MiB read")
        # OpenJPEG: a tiled JPEG 2000 at the same rate, the same window.
        j2k = os.path.join(tmp, "m.j2k")
        ratio = 16 / bps
        dt, _, _ = run(["opj_compress", "-i", raw, "-o", j2k, "-F", f"{side},{side},1,16,s@1x1", "-t", "256,256",
                        "-r", f"{ratio:.3f}"])
        opj = best(["opj_decompress", "-i", j2k, "-o", os.path.join(tmp, "r.raw"), "-d",
                    f"{x0},{y0},{x0 + 512},{y0 + 512}"], 3)
        print(f"OpenJPEG (tiled 256, {8 * os.path.getsize(j2k) / side / side:.3f} bits/sample, encode {dt:.0f} s): "
              f"opj_decompress -d on the same window {1000 * opj:.0f} ms; MRSV region / OpenJPEG speed "
              f"{opj / region:.2f}x")

        # Precincts (spec 5.7.6): the same grid and options in one transform,
        # every band in blocks of 256^2 samples; the region decoded from the
        # blocks it reaches, against the whole and against OpenJPEG at the
        # precinct stream's own rate.
        # Encoded out of core (decision D91), on 1 and 2 threads.
        pstream = os.path.join(tmp, "p.mrsv")
        pout = {}
        for threads in (1, 2):
            pout[threads] = os.path.join(tmp, f"p{threads}.mrsv")
            dt, rss, _ = run([mrsv, "encode", "--quiet", *dims, "--precinct", "256", "--max-error", "2",
                              "--out-of-core", "--threads", str(threads), raw, pout[threads]])
            print(f"precincts 256: encode --out-of-core --max-error 2, {threads} thread(s): {dt:.1f} s, "
                  f"peak {rss:.0f} MB ({100 * rss / raw_mb:.0f} % of raw)")
            if threads == 1:
                pt1 = dt
            else:
                print(f"  speed-up 1 -> 2 threads: {pt1 / dt:.2f}x; streams identical: "
                      f"{open(pout[1], 'rb').read() == open(pout[2], 'rb').read()}")
        os.replace(pout[2], pstream)
        os.remove(pout[1])
        pbps = 8 * os.path.getsize(pstream) / (side * side)
        print(f"precinct stream {os.path.getsize(pstream) / 2**20:.1f} MiB, {pbps:.3f} bits/sample")
        pwhole = best([mrsv, "decode", "--quiet", "--threads", "1", pstream, os.path.join(tmp, "w.raw")], 1)
        pregion = best([mrsv, "decode", "--quiet", "--threads", "1", "--region", box, pstream,
                        os.path.join(tmp, "r.raw")], 5)
        _, prss, err = run([mrsv, "decode", "--threads", "1", "--region", box, pstream, os.path.join(tmp, "r.raw")])
        read = re.search(r"(\d+) of (\d+) bytes read", err)
        run(["opj_compress", "-i", raw, "-o", j2k, "-F", f"{side},{side},1,16,s@1x1", "-t", "256,256",
             "-r", f"{16 / pbps:.3f}"])
        popj = best(["opj_decompress", "-i", j2k, "-o", os.path.join(tmp, "o.raw"), "-d",
                     f"{x0},{y0},{x0 + 512},{y0 + 512}"], 3)
        print(f"precincts: whole decode {pwhole:.2f} s; 512 x 512 region {1000 * pregion:.0f} ms "
              f"({pwhole / pregion:.0f}x faster), peak {prss:.0f} MB, {int(read.group(1)) / 2**10:.0f} KiB of "
              f"{int(read.group(2)) / 2**20:.1f} MiB read; OpenJPEG at {8 * os.path.getsize(j2k) / side / side:.3f} "
              f"bits/sample: {1000 * popj:.0f} ms, MRSV region / OpenJPEG speed {popj / pregion:.2f}x")
        os.remove(pstream)

        # Out of core: the grid read a row of tiles at a time (peak memory
        # against the raw size), and MPI ranks (speed-up, same bytes).
        ooc = os.path.join(tmp, "ooc.mrsv")
        dt, rss, _ = run([mrsv, "encode", "--quiet", *dims, "--tile", "256", "--max-error", "2", "--bound-route", "residual", "--threads", "2",
                          "--out-of-core", raw, ooc])
        print(f"encode --out-of-core, 2 threads: {dt:.1f} s, peak {rss:.0f} MB ({100 * rss / raw_mb:.0f} % of raw); "
              f"same stream: {open(ooc, 'rb').read() == open(stream, 'rb').read()}")
        os.remove(ooc)
        mpi = os.path.join(os.path.dirname(mrsv), "mrsv-mpi")
        if os.path.exists(mpi):
            mpi_speedup(mpi, tmp, "tiles 256", [*dims, "--tile", "256", "--max-error", "2", "--bound-route",
                                                "residual"], raw, stream)
            # Precincts by a team of ranks (decision D92), against the
            # single-process out-of-core stream.
            pref = os.path.join(tmp, "pref.mrsv")
            run([mrsv, "encode", "--quiet", *dims, "--precinct", "256", "--max-error", "2", "--out-of-core", raw, pref])
            mpi_speedup(mpi, tmp, "precincts 256", [*dims, "--precinct", "256", "--max-error", "2"], raw, pref)
            os.remove(pref)
        if not args.quick:
            print("== a 1024^3 CT volume (the bonsai scan mirrored 4 x 4 x 4), 64^3 bricks, out of core")
            import numpy as np
            b = np.fromfile(load("ct_bonsai_256x256x256_uint8", tmp), dtype=np.uint8).reshape(256, 256, 256)
            row = np.concatenate([b, b[:, :, ::-1]] * 2, axis=2)
            slab = np.concatenate([row, row[:, ::-1, :]] * 2, axis=1)
            vol = os.path.join(tmp, "bonsai1024.raw")
            with open(vol, "wb") as f:
                for k in range(4):
                    (slab if k % 2 == 0 else slab[::-1]).tofile(f)
            del b, row, slab
            vo = os.path.join(tmp, "bonsai1024.mrsv")
            dt, rss, _ = run([mrsv, "encode", "--quiet", "--dims", "1024,1024,1024", "--type", "uint8", "--tile", "64",
                              "--step", "2", "--threads", "2", "--out-of-core", vol, vo])
            print(f"encode --out-of-core --step 2: {dt:.0f} s, peak {rss:.0f} MB ({100 * rss / 1024:.1f} % of the "
                  f"1024 MiB raw), {8 * os.path.getsize(vo) / 2**30:.3f} bits/sample")
            r3, _, err = run([mrsv, "decode", "--region", "300,400,500,428,528,628", vo, os.path.join(tmp, "v.raw")])
            read3 = re.search(r"(\d+) of (\d+) bytes read", err)
            print(f"decode a 128^3 region: {1000 * r3:.0f} ms, {int(read3.group(1)) / 2**20:.1f} of "
                  f"{int(read3.group(2)) / 2**20:.1f} MiB read")
            # The same volume in precincts of 64^3, out of core (D91): pieces
            # of a few rows of planes, about 5 minutes.
            dt, rss, _ = run([mrsv, "encode", "--quiet", "--dims", "1024,1024,1024", "--type", "uint8",
                              "--precinct", "64", "--step", "2", "--threads", "2", "--out-of-core", vol, vo])
            print(f"precincts 64^3: encode --out-of-core --step 2: {dt:.0f} s, peak {rss:.0f} MB "
                  f"({100 * rss / 1024:.1f} % of the 1024 MiB raw), {8 * os.path.getsize(vo) / 2**30:.3f} bits/sample")
            os.remove(vol)
        print("== rate-distortion at 1 bit per sample: tiles and precincts against neither")
        grids = [(n, ["--dims", "1201,1201", "--type", "int16", "--nodata", "-32768"], "256") for n in SRTM]
        grids.append(("big_tujunga_1197x643_int16le", ["--dims", "1197,643", "--type", "int16"], "256"))
        if not args.quick:
            grids.append(("ct_head_stanford_cthead_256x256x99_uint8", ["--dims", "256,256,99", "--type", "uint8"],
                          "64"))
        worst, worst_precinct = 0, 0
        for name, opts, tile in grids:
            path = load(name, tmp)
            o = os.path.join(tmp, "rd.mrsv")
            _, _, untiled = run([mrsv, "encode", *opts, "--bits-per-sample", "1", path, o])
            _, _, tiled = run([mrsv, "encode", *opts, "--bits-per-sample", "1", "--tile", tile, path, o])
            _, _, precinct = run([mrsv, "encode", *opts, "--bits-per-sample", "1", "--precinct", tile, path, o])
            d = psnr_of(untiled) - psnr_of(tiled)
            dp = psnr_of(untiled) - psnr_of(precinct)
            worst, worst_precinct = max(worst, d), max(worst_precinct, dp)
            print(f"{name}: untiled {psnr_of(untiled):.2f} dB, tiled {tile} {psnr_of(tiled):.2f} dB "
                  f"(loss {d:.2f} dB), precincts {tile} {psnr_of(precinct):.2f} dB (loss {dp:.2f} dB)")
        print(f"largest loss: tiles {worst:.2f} dB, precincts {worst_precinct:.2f} dB (goal: at most 0.3)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
