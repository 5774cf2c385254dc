#!/usr/bin/python3
"""The MRSV HDF5 filter against the HDF5 filters of Debian, measured in one run
on the same real data (issue 24): a terrain and a CT volume written as chunked
datasets through h5py with each filter, then read back.

Per filter: compression ratio (the data's own bytes over the stored chunk
bytes), write and read speed in MB/s of the data's own bytes (best of --reps),
max absolute error and PSNR of what is read back, and the ratio against gzip.
bits/smp is stored bits per sample. Both data sets are whole chunks (no padding).

Peers: gzip (level 4, h5py's default) with and without shuffle, lzf (both
built into h5py), and when their Debian plugins are installed lz4 and bzip2
(hdf5-filter-plugin) and zfp (hdf5-filter-plugin-zfp-serial). ZFP codes only
32/64-bit samples: it gets the data as float32 (every int16/uint8 value is
exact in float32), reversible for lossless, fixed accuracy for an error bound
(its tolerance is the bound asked for), fixed rate for a rate; its ratio is
still against the data's own bytes, so it is what a user storing the data with
ZFP gets.

  /usr/bin/python3 tools/bench/hdf5_bench.py            # about 3 minutes on 2 cores
  /usr/bin/python3 tools/bench/hdf5_bench.py --reps 1 --plugin build/hdf5plugins

HDF5_PLUGIN_PATH is set by the script (the MRSV plugin's directory, then
Debian's plugin directory); it must happen before h5py loads, so the script
re-executes itself once with it set.
"""
import argparse
import os
import pathlib
import struct
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
DEBIAN_PLUGINS = "/usr/lib/x86_64-linux-gnu/hdf5/serial/plugins"

MRSV_ID, LZ4_ID, BZIP2_ID, ZFP_ID = 421, 32004, 307, 32013


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--data", default=str(ROOT.parent / "shared" / "data"), help="../shared/data")
    p.add_argument("--plugin", default=str(ROOT / "build" / "hdf5plugins"),
                   help="directory of libmrsv_h5filter.so (default build/hdf5plugins)")
    p.add_argument("--reps", type=int, default=3, help="timed repetitions, best kept (default 3)")
    return p.parse_args()


ARGS = parse_args()
if os.environ.get("HDF5_BENCH_REEXEC") != "1":
    os.environ["HDF5_PLUGIN_PATH"] = os.pathsep.join([os.path.abspath(ARGS.plugin), DEBIAN_PLUGINS])
    os.environ["HDF5_BENCH_REEXEC"] = "1"
    os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)

import h5py  # noqa: E402  (after HDF5_PLUGIN_PATH is set)
import numpy as np  # noqa: E402


def load(data_dir, name, dtype, shape):
    raw = subprocess.run(["zstd", "-dc", str(pathlib.Path(data_dir) / name)], capture_output=True,
                         check=True).stdout
    return np.frombuffer(raw, dtype=dtype).reshape(shape)


def f64_words(value):
    return struct.unpack("<II", struct.pack("<d", value))


def mrsv(mode, value=0.0):
    return dict(compression=MRSV_ID, compression_opts=(mode,) + f64_words(value))


def zfp(mode, value=0.0):
    lo, hi = f64_words(value)
    return dict(compression=ZFP_ID, compression_opts=(mode, 0, lo, hi, 0, 0))


def filter_available(filter_id):
    return h5py.h5z.filter_avail(filter_id)


def run(path, data, chunks, kwargs, as_float, reps):
    """Writes and reads `data` with one filter; returns (stored bytes, write s, read s, back)."""
    stored = data.astype(np.float32) if as_float else data
    best_w = best_r = float("inf")
    for _ in range(reps):
        if path.exists():
            path.unlink()
        t = time.perf_counter()
        with h5py.File(path, "w") as f:
            f.create_dataset("d", data=stored, chunks=chunks, **kwargs)
        best_w = min(best_w, time.perf_counter() - t)
        t = time.perf_counter()
        with h5py.File(path, "r") as f:
            back = f["d"][...]
        best_r = min(best_r, time.perf_counter() - t)
    with h5py.File(path, "r") as f:
        d = f["d"].id
        size = sum(d.get_chunk_info(i).size for i in range(d.get_num_chunks()))
    return size, best_w, best_r, back


def psnr(a, b):
    a = a.astype(np.float64)
    mse = np.mean((a - b.astype(np.float64)) ** 2)
    return float("inf") if mse == 0 else 10 * np.log10((a.max() - a.min()) ** 2 / mse)


def bench(name, data, chunks, tmp, reps):
    have_zfp, have_lz4, have_bz2 = (filter_available(i) for i in (ZFP_ID, LZ4_ID, BZIP2_ID))
    rows = [("none", {}, False), ("gzip", dict(compression="gzip"), False),
            ("shuffle+gzip", dict(compression="gzip", shuffle=True), False), ("lzf", dict(compression="lzf"), False)]
    if have_lz4:
        rows.append(("lz4", dict(compression=LZ4_ID), False))
    if have_bz2:
        rows.append(("bzip2", dict(compression=BZIP2_ID, compression_opts=(9,)), False))
    if have_zfp:
        rows.append(("zfp reversible (f32)", zfp(5), True))
    rows.append(("MRSV lossless", mrsv(0), False))
    for bound in (1, 4):
        if have_zfp:
            rows.append((f"zfp accuracy {bound} (f32)", zfp(3, bound), True))
        rows.append((f"MRSV max error {bound}", mrsv(3, bound), False))
    for rate in (1, 2):
        if have_zfp:
            rows.append((f"zfp rate {rate} (f32)", zfp(1, rate), True))
        rows.append((f"MRSV rate {rate}", mrsv(1, rate), False))
    rows.append(("MRSV PSNR 50", mrsv(2, 50), False))

    mb = data.nbytes / 1e6
    print(f"\n{name}: {' x '.join(map(str, data.shape[::-1]))} {data.dtype}, {data.nbytes} bytes, "
          f"chunks {' x '.join(map(str, chunks[::-1]))} (x fastest)")
    if not have_zfp:
        print("  (zfp not run: install hdf5-filter-plugin-zfp-serial)")
    print(f"  {'filter':<24}{'ratio':>7}{'vs gzip':>9}{'bits/smp':>9}{'write MB/s':>12}{'read MB/s':>11}"
          f"{'max err':>9}{'PSNR dB':>9}")
    gzip_size = None
    for label, kwargs, as_float in rows:
        size, w, r, back = run(tmp / "bench.h5", data, chunks, kwargs, as_float, reps)
        if label == "gzip":
            gzip_size = size
        err = float(np.abs(back.astype(np.float64) - data).max())
        vs = f"{gzip_size / size:.2f}x" if gzip_size else ""
        print(f"  {label:<24}{data.nbytes / size:>7.2f}{vs:>9}{8 * size / data.size:>9.3f}{mb / w:>12.1f}"
              f"{mb / r:>11.1f}{err:>9.3g}{psnr(data, back):>9.2f}", flush=True)


def main():
    print(f"h5py {h5py.version.version}, HDF5 {h5py.version.hdf5_version}; best of {ARGS.reps}; "
          "ratio = the data's bytes / stored chunk bytes; MB/s of the data's bytes")
    # 1024 x 512 of Big Tujunga: whole chunks, so that no filter codes padding
    # (HDF5 pads edge chunks with the fill value, a cliff beside the terrain
    # for every coder but MRSV, which can take the fill value as no-data: D75).
    terrain = load(ARGS.data, "terrain/big_tujunga_1197x643_int16le.raw.zst", "<i2", (643, 1197))[:512, :1024]
    ct = load(ARGS.data, "volume/ct_head_stanford_cthead_256x256x99_uint8.raw.zst", "u1", (99, 256, 256))
    with tempfile.TemporaryDirectory(prefix="mrsv_hdf5_bench_") as tmp:
        bench("Big Tujunga terrain (SRTM-1, int16)", terrain, (256, 256), pathlib.Path(tmp), ARGS.reps)
        bench("Stanford CT head (uint8)", ct, (33, 128, 128), pathlib.Path(tmp), ARGS.reps)


if __name__ == "__main__":
    main()
