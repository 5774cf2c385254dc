#!/usr/bin/python3
"""MRSV against its peers, measured in one run on the real data of ../shared/data (issue 4).

Parts (see tools/bench/README.md for the exact definitions and commands):
  1. rate-distortion at 0.5, 1, 2, 4 bits/sample: MRSV, ZFP fixed-rate, ZFP fixed-accuracy,
     OpenJPEG 9/7 (16-bit terrains), JPEG XL (terrains)
  2. lossless: MRSV, OpenJPEG 5/3 (terrains), xz -9, zstd -19, JPEG XL -d 0 -e 9 (terrains)
  3. error bound: MRSV --max-error d for d in 0, 1, 4, 16
  4. decoding speed: MRSV vs zfp (256^3 volume) and opj_decompress (2-D terrain)

Tables go to stdout and to RESULTS/summary.txt, CSVs and rd_curves.png to RESULTS
(default tools/bench/results/). Temporary files live in a temp dir that is removed.

  /usr/bin/python3 tools/bench/rd_bench.py                 # everything (10-15 min on 2 cores)
  /usr/bin/python3 tools/bench/rd_bench.py --quick         # mt_st_helens + ct_tooth (+ speed)
  /usr/bin/python3 tools/bench/rd_bench.py --datasets rainier,bonsai --no-speed
"""
import os
import sys

try:
    import numpy as np
except ImportError:  # a pyenv/venv python3 without numpy: use Debian's, which setup_peers.sh fills
    if os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3") and os.path.exists(
            "/usr/bin/python3") and not os.environ.get("RD_BENCH_REEXEC"):
        os.environ["RD_BENCH_REEXEC"] = "1"
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    sys.exit("rd_bench: numpy is missing: run tools/bench/setup_peers.sh (as root)")

import argparse
import csv
import hashlib
import math
import re
import shutil
import signal
import subprocess
import tempfile
import threading
import time
import traceback
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
RATES = [0.5, 1.0, 2.0, 4.0]
MAX_ERRORS = [0, 1, 4, 16]
NODATA = -32768
CODECS_RD = ["mrsv", "zfp-rate", "zfp-acc", "opj-9/7", "jxl", "jxl-scaled"]
QUICK = ["mt_st_helens", "ct_tooth"]
TYPE_INFO = {  # file suffix -> (mrsv --type, numpy dtype, bits)
    "int16le": ("int16", "<i2", 16),
    "uint16le": ("uint16", "<u2", 16),
    "uint8": ("uint8", "u1", 8),
}
MRSV_EXTRA = []  # --order K when given on the command line
TOOLS = ["zstd", "zfp", "opj_compress", "opj_decompress", "cjxl", "djxl", "xz"]


class ToolError(RuntimeError):
    pass


def log(msg):
    print(f"[{time.strftime('%H:%M:%S')}] {msg}", file=sys.stderr, flush=True)


_children = set()
_children_lock = threading.Lock()
_stop = threading.Event()


def stop_all(*_):
    """SIGTERM/SIGINT: no new process, kill the running ones, then leave (the temp dir is removed)."""
    _stop.set()
    with _children_lock:
        for p in list(_children):
            p.kill()
    raise SystemExit(130)


def run(cmd, stdout=subprocess.PIPE):
    cmd = [str(c) for c in cmd]
    if _stop.is_set():
        raise ToolError("stopped")
    p = subprocess.Popen(cmd, stdout=stdout, stderr=subprocess.PIPE)
    with _children_lock:
        _children.add(p)
    try:
        out, err = p.communicate()
    finally:
        with _children_lock:
            _children.discard(p)
    p.stdout, p.stderr = out, err
    if p.returncode != 0:
        lines = err.decode(errors="replace").strip().splitlines()[-3:]
        raise ToolError(f"{' '.join(cmd)}: exit {p.returncode}: {' | '.join(lines)}")
    return p


def timed(cmd):
    """Wall clock and CPU (user+sys) seconds of one process, from fork to reaping."""
    cmd = [str(c) for c in cmd]
    with tempfile.TemporaryFile() as errf:
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=errf)
        _, status, ru = os.wait4(p.pid, 0)
        wall = time.perf_counter() - t0
        p.returncode = os.waitstatus_to_exitcode(status)
        errf.seek(0)
        err = errf.read().decode(errors="replace")
    if p.returncode != 0:
        raise ToolError(f"{' '.join(cmd)}: exit {p.returncode}: {err.strip()[-300:]}")
    return wall, ru.ru_utime + ru.ru_stime


# ----------------------------------------------------------------------------- data sets

@dataclass
class Dataset:
    name: str
    src: Path
    kind: str            # terrain | volume
    dims: tuple          # (x, y) or (x, y, z), x fastest
    mtype: str           # mrsv --type
    npdt: str
    bits: int
    n: int = 0
    dir: Path = None
    raw: Path = None     # the original samples
    filled_raw: Path = None  # voids filled (int16 LE), for the 2-D peers
    f32: Path = None     # filled, as float32 for zfp -f (fixed accuracy)
    i32: Path = None     # filled, promoted to int32 for zfp -t i32 (fixed rate), see zfp_promotion
    orig: np.ndarray = None
    valid: np.ndarray = None  # bool mask or None when every sample is valid
    nvoid: int = 0
    vmin: int = 0
    vmax: int = 0
    filled: np.ndarray = None

    @property
    def peak(self):
        return float(self.vmax - self.vmin)

    def mrsv_args(self):
        a = ["--dims", ",".join(map(str, self.dims)), "--type", self.mtype]
        if self.kind == "terrain" and self.mtype == "int16":
            a += ["--nodata", str(NODATA)]
        return a + MRSV_EXTRA


NAME_RE = re.compile(r"^(?P<stem>.+?)_(?P<dims>\d+x\d+(?:x\d+)?)_(?P<type>int16le|uint16le|uint8)\.raw\.zst$")


def discover(data_dir):
    out = []
    for kind in ("terrain", "volume"):
        d = data_dir / kind
        if not d.is_dir():
            continue
        for f in sorted(d.iterdir()):
            m = NAME_RE.match(f.name)
            if not m:
                continue
            stem = re.sub(r"^srtm3_[NS]\d+[EW]\d+_", "", m["stem"])
            dims = tuple(int(v) for v in m["dims"].split("x"))
            mtype, npdt, bits = TYPE_INFO[m["type"]]
            out.append(Dataset(stem, f, kind, dims, mtype, npdt, bits, n=math.prod(dims)))
    return out


def fill_voids_rows(a2, valid2):
    """Each void takes the value of the nearest valid sample in its row (ties: the western
    one). A row with no valid sample takes the nearest row that has one."""
    out = a2.copy()
    h, _ = a2.shape
    empty = []
    for r in range(h):
        v = valid2[r]
        if v.all():
            continue
        idx = np.flatnonzero(v)
        if idx.size == 0:
            empty.append(r)
            continue
        miss = np.flatnonzero(~v)
        pos = np.searchsorted(idx, miss)
        left = idx[np.clip(pos - 1, 0, idx.size - 1)]
        right = idx[np.clip(pos, 0, idx.size - 1)]
        take = np.where(np.abs(miss - left) <= np.abs(right - miss), left, right)
        out[r, miss] = a2[r, take]
    if empty:
        full = np.array([r for r in range(h) if r not in set(empty)])
        for r in empty:
            out[r] = out[full[np.argmin(np.abs(full - r))]]
    return out


def prepare(ds, root):
    ds.dir = root / ds.name
    ds.dir.mkdir(parents=True, exist_ok=True)
    ds.raw = ds.dir / "orig.raw"
    with open(ds.raw, "wb") as f:
        run(["zstd", "-q", "-dc", ds.src], stdout=f)
    ds.orig = np.fromfile(ds.raw, dtype=ds.npdt)
    if ds.orig.size != ds.n:
        raise ToolError(f"{ds.src}: {ds.orig.size} samples, expected {ds.n}")
    if ds.kind == "terrain" and ds.mtype == "int16":
        valid = ds.orig != NODATA
        ds.nvoid = int(ds.n - valid.sum())
        ds.valid = None if ds.nvoid == 0 else valid
    vals = ds.orig if ds.valid is None else ds.orig[ds.valid]
    ds.vmin, ds.vmax = int(vals.min()), int(vals.max())
    if ds.valid is not None:
        w, h = ds.dims
        ds.filled = fill_voids_rows(ds.orig.reshape(h, w), ds.valid.reshape(h, w)).ravel()
    else:
        ds.filled = ds.orig
    if ds.kind == "terrain":
        ds.filled_raw = ds.dir / "filled.rawl"
        ds.filled.astype("<i2").tofile(ds.filled_raw)
    ds.f32 = ds.dir / "filled.f32"
    ds.filled.astype("<f4").tofile(ds.f32)  # exact: |values| < 2^24
    off, sh = zfp_promotion(ds)
    ds.i32 = ds.dir / "filled.i32"
    ((ds.filled.astype(np.int64) - off) << sh).astype("<i4").tofile(ds.i32)


def zfp_promotion(ds):
    """(offset, shift) of zfp's own promotion of 8/16-bit integers to int32 (zfp_promote_*:
    int16 << 15, uint16 (x - 0x8000) << 15, uint8 (x - 0x80) << 23). The zfp CLI reads only
    int32/int64/float/double, so the bench applies it and zfp_demote() undoes it."""
    return {"int16": (0, 15), "uint16": (0x8000, 15), "uint8": (0x80, 23)}[ds.mtype]


def zfp_demote(ds, path):
    off, sh = zfp_promotion(ds)
    b = np.fromfile(path, dtype="<i4").astype(np.int64)
    lo, hi = type_range(ds)
    return np.clip(((b + (1 << (sh - 1))) >> sh) + off, lo, hi)


def type_range(ds):
    info = np.iinfo(np.dtype(ds.npdt))
    return info.min, info.max


def metrics(ds, dec):
    """PSNR over the valid samples; peak = max - min of the valid original samples.
    Float decodes are rounded to the nearest integer and clamped to the type's range."""
    dec = np.asarray(dec)
    if dec.size != ds.n:
        raise ToolError(f"decoded {dec.size} samples, expected {ds.n}")
    if dec.dtype.kind == "f":
        lo, hi = type_range(ds)
        dec = np.clip(np.rint(dec), lo, hi)
    dec = dec.astype(np.int64)
    a = ds.orig.astype(np.int64)
    if ds.valid is not None:
        a, dec = a[ds.valid], dec[ds.valid]
    e = dec - a
    del dec, a
    mse = float(np.mean(e.astype(np.float64) ** 2))
    maxe = int(np.abs(e).max()) if e.size else 0
    psnr = math.inf if mse == 0 else 10 * math.log10(ds.peak ** 2 / mse)
    psnr16 = None
    if ds.bits == 16:
        psnr16 = math.inf if mse == 0 else 10 * math.log10(65535.0 ** 2 / mse)
    return dict(psnr=psnr, psnr65535=psnr16, max_error=maxe, mse=mse)


def bps(path, ds):
    return os.path.getsize(path) * 8.0 / ds.n


# ----------------------------------------------------------------------------- codecs

MRSV_LINE = re.compile(r"(\d+) bytes, ([\d.]+) bits/sample, PSNR (\S+) dB, max error (\d+)")


def mrsv_encode(args, ds, opts, out):
    p = run([args.mrsv, "encode"] + ds.mrsv_args() + opts + [ds.raw, out])
    m = MRSV_LINE.search(p.stderr.decode(errors="replace"))
    return {"reported_psnr": float(m[3])} if m else {}


def mrsv_decode(args, ds, src, out):
    run([args.mrsv, "decode", "--quiet", src, out])
    return np.fromfile(out, dtype=ds.npdt)


def task_mrsv_rd(args, ds, rate, wd):
    enc, dec = wd / "rd.mrsv", wd / "rd.raw"
    rep = mrsv_encode(args, ds, ["--bits-per-sample", f"{rate:g}"], enc)
    r = dict(bps=bps(enc, ds), param=f"--bits-per-sample {rate:g}", **metrics(ds, mrsv_decode(args, ds, enc, dec)))
    if rep.get("reported_psnr") is not None and math.isfinite(r["psnr"]) and abs(rep["reported_psnr"] - r["psnr"]) > 0.01:
        r["note"] = f"mrsv reported PSNR {rep['reported_psnr']:.3f}"
    return [dict(target=rate, codec="mrsv", **r)]


def zfp_dims(ds):
    return [f"-{len(ds.dims)}"] + list(ds.dims)


def task_zfp_rate(args, ds, wd):
    rows = []
    for rate in RATES:
        z, o = wd / "r.zfp", wd / "r.i32"
        run(["zfp", "-q", "-t", "i32"] + zfp_dims(ds) + ["-r", f"{rate:g}", "-i", ds.i32, "-z", z, "-o", o])
        rows.append(dict(target=rate, codec="zfp-rate", bps=bps(z, ds), param=f"-t i32 -r {rate:g}",
                         **metrics(ds, zfp_demote(ds, o))))
    return rows


def task_zfp_acc(args, ds, wd):
    # Fixed accuracy exists in zfp for floating point only (-t i32 -a is lossless), so float32.
    # zfp -a t codes bit planes down to 2^floor(log2 t) only, so the rate is a step function
    # of t with steps at powers of two: scanning t = 2^k finds every reachable rate.
    scan = {}
    z = wd / "a.zfp"
    for k in range(24, -12, -1):  # 2^24: far above any |sample|, where the rate bottoms out
        tol = 2.0 ** k
        run(["zfp", "-q", "-f"] + zfp_dims(ds) + ["-a", repr(tol), "-i", ds.f32, "-z", z])
        scan[tol] = bps(z, ds)
        if scan[tol] > max(RATES):
            break
    rows = []
    for rate in RATES:
        ok = [t for t, r in scan.items() if r <= rate]
        tol = max(ok, key=lambda t: (scan[t], -t)) if ok else min(scan, key=lambda t: scan[t])
        o = wd / "a.f32"
        run(["zfp", "-q", "-f"] + zfp_dims(ds) + ["-a", repr(tol), "-i", ds.f32, "-z", z, "-o", o])
        r = dict(target=rate, codec="zfp-acc", bps=bps(z, ds), param=f"-f -a {tol:g}",
                 **metrics(ds, np.fromfile(o, dtype="<f4")))
        if not ok:
            r["note"] = "no tolerance reaches the rate"
        rows.append(r)
    return rows


def opj_F(ds):
    return f"{ds.dims[0]},{ds.dims[1]},1,16,s"


def task_opj_rd(args, ds, wd):
    rows = []
    for rate in RATES:
        j, o = wd / "c.j2k", wd / "d.rawl"
        ratio = 16.0 / rate
        run(["opj_compress", "-i", ds.filled_raw, "-o", j, "-F", opj_F(ds), "-I", "-r", f"{ratio:g}"])
        run(["opj_decompress", "-i", j, "-o", o])
        rows.append(dict(target=rate, codec="opj-9/7", bps=bps(j, ds), param=f"-I -r {ratio:g}",
                         **metrics(ds, np.fromfile(o, dtype="<i2"))))
    return rows


def write_pgm16(path, ds, u):
    w, h = ds.dims
    with open(path, "wb") as f:
        f.write(b"P5\n%d %d\n65535\n" % (w, h))
        f.write(u.astype(">u2").tobytes())


def read_pgm16(path, ds):
    data = Path(path).read_bytes()
    # header: P5 <ws> w <ws> h <ws> maxval <one ws>
    toks, i = [], 0
    while len(toks) < 4:
        while data[i:i + 1].isspace():
            i += 1
        if data[i:i + 1] == b"#":
            i = data.index(b"\n", i)
            continue
        j = i
        while not data[j:j + 1].isspace():
            j += 1
        toks.append(data[i:j])
        i = j
    i += 1
    w, h, maxval = int(toks[1]), int(toks[2]), int(toks[3])
    if (w, h) != tuple(ds.dims) or maxval != 65535:
        raise ToolError(f"{path}: PGM {w}x{h} maxval {maxval}, expected {ds.dims} maxval 65535")
    return np.frombuffer(data, dtype=">u2", count=w * h, offset=i).astype(np.int64)


def task_jxl_rd(args, ds, wd, scaled):
    """cjxl -d D on a 16-bit PGM (maxval 65535) of the filled terrain shifted by -min.
    jxl-scaled also multiplies by k = floor(65535 / (max - min)) (exactly invertible),
    so that the signal spans the 16-bit range that the perceptual distance refers to."""
    codec = "jxl-scaled" if scaled else "jxl"
    k = max(1, 65535 // max(1, ds.vmax - ds.vmin)) if scaled else 1
    pgm = wd / "in.pgm"
    write_pgm16(pgm, ds, (ds.filled.astype(np.int64) - ds.vmin) * k)
    cache = {}

    def rate_at(d):
        if d not in cache:
            out = wd / f"d{d:.6g}.jxl"
            run(["cjxl", pgm, out, "-d", f"{d:.6g}", "--num_threads=0"])
            cache[d] = (bps(out, ds), out)
        return cache[d][0]

    D_MIN, D_MAX = 0.01, 25.0  # the range of cjxl 0.7's distance
    rows = []
    for rate in RATES:
        note = ""
        if rate_at(D_MIN) <= rate:
            note = f"best quality (-d {D_MIN:g}) is below the target rate"
        elif rate_at(D_MAX) > rate:
            note = f"lowest quality (-d {D_MAX:g}) exceeds the target rate"
        else:
            lo, hi = D_MIN, D_MAX  # rate(lo) > target >= rate(hi)
            for _ in range(9):
                mid = math.sqrt(lo * hi)
                if rate_at(mid) > rate:
                    lo = mid
                else:
                    hi = mid
        ok = [d for d, (r, _) in cache.items() if r <= rate]
        d = max(ok, key=lambda d: cache[d][0]) if ok else D_MAX
        dec = wd / "dec.pgm"
        run(["djxl", cache[d][1], dec, "--num_threads=1"])
        u = read_pgm16(dec, ds)
        vals = np.rint(u / k) + ds.vmin if k > 1 else u + ds.vmin
        r = dict(target=rate, codec=codec, bps=cache[d][0], param=f"-d {d:.4g}" + (f" (x{k})" if k > 1 else ""),
                 **metrics(ds, vals.astype(np.float64)))
        if note:
            r["note"] = note
        rows.append(r)
    for _, p in cache.values():
        p.unlink(missing_ok=True)
    return rows


def verify_same(ds, src, dtype=None):
    """True when the decoded samples (an array, or a raw file of dtype) equal the original file."""
    b = np.fromfile(src, dtype=dtype or ds.npdt) if isinstance(src, Path) else src
    return b.size == ds.n and bool(np.array_equal(b.astype(np.int64), ds.orig.astype(np.int64)))


def task_lossless(args, ds, wd, codec):
    if codec == "mrsv":
        enc = wd / "l.mrsv"
        mrsv_encode(args, ds, ["--lossless"], enc)
        ok = verify_same(ds, mrsv_decode(args, ds, enc, wd / "l.raw"))
        return dict(codec=codec, bytes=os.path.getsize(enc), ok=ok, param="--lossless")
    if codec in ("xz", "zstd"):
        c = wd / f"l.{codec}"
        cmd = ["xz", "-9", "-T1", "-c", ds.raw] if codec == "xz" else ["zstd", "-19", "-q", "-c", ds.raw]
        with open(c, "wb") as f:
            run(cmd, stdout=f)
        back = wd / "l.back"
        with open(back, "wb") as f:
            run([codec, "-dc", c] if codec == "xz" else ["zstd", "-q", "-dc", c], stdout=f)
        return dict(codec=codec, bytes=os.path.getsize(c), ok=verify_same(ds, back),
                    param=" ".join(cmd[1:-2]) if codec == "xz" else "-19")
    if codec == "opj-5/3":
        src = wd / "in.rawl"  # the file itself, voids included (lossless means that file back)
        shutil.copyfile(ds.raw, src)
        j, o = wd / "l.j2k", wd / "l.rawl"
        run(["opj_compress", "-i", src, "-o", j, "-F", opj_F(ds)])
        run(["opj_decompress", "-i", j, "-o", o])
        return dict(codec=codec, bytes=os.path.getsize(j), ok=verify_same(ds, o, "<i2"), param="(default: 5/3, lossless)")
    if codec == "jxl":
        lo = int(ds.orig.min())  # shift the whole file (voids included) to unsigned
        pgm, j, dec = wd / "l.pgm", wd / "l.jxl", wd / "l.dec.pgm"
        write_pgm16(pgm, ds, ds.orig.astype(np.int64) - lo)
        run(["cjxl", pgm, j, "-d", "0", "-e", "9", "--num_threads=0"])
        run(["djxl", j, dec, "--num_threads=1"])
        ok = verify_same(ds, read_pgm16(dec, ds) + lo)
        return dict(codec=codec, bytes=os.path.getsize(j), ok=ok, param=f"-d 0 -e 9 (shift {-lo:+d})")
    raise ValueError(codec)


def task_maxerr(args, ds, wd, d):
    enc = wd / "e.mrsv"
    mrsv_encode(args, ds, ["--max-error", str(d)], enc)
    dec = mrsv_decode(args, ds, enc, wd / "e.raw")
    a, b = ds.orig.astype(np.int64), dec.astype(np.int64)
    v = ds.valid
    err = np.abs(b - a) if v is None else np.abs(b[v] - a[v])
    outside = int((err > d).sum())
    voids_exact = None if v is None else bool((dec[~v] == NODATA).all())
    m = metrics(ds, dec)
    return dict(d=d, bps=bps(enc, ds), outside=outside, max_abs_error=int(err.max()), voids=ds.nvoid,
                voids_exact=voids_exact, psnr=m["psnr"])


# ----------------------------------------------------------------------------- speed

def speed(args, datasets_all, root, results):
    def pick(name):
        for ds in datasets_all:
            if name in ds.name:
                return ds
        raise ToolError(f"no data set matches {name!r}")

    reps = args.speed_reps
    vol = pick(args.speed_volume)
    ter = pick(args.speed_terrain)
    for ds in (vol, ter):
        if ds.raw is None:
            prepare(ds, root)
    sd = root / "_speed"
    sd.mkdir(exist_ok=True)
    rows = []

    def best(cmd, ds, what, tool):
        runs = [timed(cmd) for _ in range(reps)]
        wall, cpu = min(runs)
        rows.append(dict(what=what, tool=tool, dataset=ds.name, samples=ds.n, wall_s=wall, cpu_s=cpu,
                         msps=ds.n / wall / 1e6, msps_cpu=ds.n / cpu / 1e6 if cpu > 0 else math.nan,
                         cmd=" ".join(map(str, cmd))))
        log(f"speed: {what}: best of {reps}: {wall:.3f} s wall, {ds.n / wall / 1e6:.2f} M samples/s")

    # 3-D: MRSV at 1 bit/sample, zfp fixed-rate 1 bit/sample, same volume
    m3 = sd / "v.mrsv"
    mrsv_encode(args, vol, ["--progressive", "--bits-per-sample", "1"], m3)
    best([args.mrsv, "decode", "--quiet", m3, sd / "v.raw"], vol, "3-D decode", "mrsv")
    # The same rate with the encoder's defaults: it may keep fewer levels and code the
    # coarse block with weighted prediction (D28, D23), which decodes more slowly.
    m3d = sd / "vd.mrsv"
    mrsv_encode(args, vol, ["--bits-per-sample", "1"], m3d)
    best([args.mrsv, "decode", "--quiet", m3d, sd / "vd.raw"], vol, "3-D decode", "mrsv-default")
    z3 = sd / "v.zfp"  # as in part 1: int32, fixed rate
    run(["zfp", "-q", "-t", "i32"] + zfp_dims(vol) + ["-r", "1", "-i", vol.i32, "-z", z3])
    best(["zfp", "-q", "-t", "i32"] + zfp_dims(vol) + ["-r", "1", "-z", z3, "-o", sd / "v.i32"], vol, "3-D decode",
         "zfp")
    z3f = sd / "vf.zfp"  # float32, fixed rate
    run(["zfp", "-q", "-f"] + zfp_dims(vol) + ["-r", "1", "-i", vol.f32, "-z", z3f])
    best(["zfp", "-q", "-f"] + zfp_dims(vol) + ["-r", "1", "-z", z3f, "-o", sd / "v.f32"], vol, "3-D decode",
         "zfp-f32")
    # 2-D: opj_decompress at 1 bit/sample (-r 16), MRSV on the same terrain at 1 bit/sample
    j2 = sd / "t.j2k"
    run(["opj_compress", "-i", ter.filled_raw, "-o", j2, "-F", opj_F(ter), "-I", "-r", "16"])
    best(["opj_decompress", "-quiet", "-threads", "1", "-i", j2, "-o", sd / "t.rawl"], ter, "2-D decode", "opj_decompress")
    m2 = sd / "t.mrsv"
    mrsv_encode(args, ter, ["--progressive", "--bits-per-sample", "1"], m2)
    best([args.mrsv, "decode", "--quiet", m2, sd / "t.raw"], ter, "2-D decode", "mrsv")
    for r in rows:
        r["bps"] = bps({"mrsv": m3 if r["what"].startswith("3") else m2, "mrsv-default": m3d, "zfp": z3,
                        "zfp-f32": z3f, "opj_decompress": j2}[r["tool"]], vol if r["what"].startswith("3") else ter)
    results["speed"] = rows


# ----------------------------------------------------------------------------- tables

def fnum(v, nd=2, w=None):
    if v is None or (isinstance(v, float) and math.isnan(v)):
        s = "-"
    elif isinstance(v, float) and math.isinf(v):
        s = "inf"
    elif isinstance(v, float):
        s = f"{v:.{nd}f}"
    else:
        s = str(v)
    return s


def table(headers, rows, title=None):
    cols = list(zip(*([headers] + rows))) if rows else [[h] for h in headers]
    widths = [max(len(str(c)) for c in col) for col in cols]
    out = []
    if title:
        out.append(title)
    out.append("  ".join(str(h).ljust(w) for h, w in zip(headers, widths)).rstrip())
    out.append("  ".join("-" * w for w in widths))
    for r in rows:
        out.append("  ".join(str(c).rjust(w) if i > 0 else str(c).ljust(w) for i, (c, w) in enumerate(zip(r, widths))).rstrip())
    return "\n".join(out)


EXTRAP = 0.03  # a peer's curve is extended by at most 3 % of rate beyond its end points


def interp_peer(points, x):
    """PSNR of a peer's curve at rate x: linear in (log2 rate, PSNR) between measured points
    (lossless points left out); None when x is more than EXTRAP outside the measured rates."""
    pts = sorted({(p["bps"], p["psnr"]) for p in points if math.isfinite(p["psnr"])})
    if not pts or x < pts[0][0] * (1 - EXTRAP) or x > pts[-1][0] * (1 + EXTRAP):
        return None
    if len(pts) == 1:
        return pts[0][1]
    segs = list(zip(pts, pts[1:]))
    seg = segs[0] if x < pts[0][0] else segs[-1] if x > pts[-1][0] else next(
        s for s in segs if s[0][0] <= x <= s[1][0])
    (x0, y0), (x1, y1) = seg
    if x1 == x0:
        return max(y0, y1)
    t = (math.log2(x) - math.log2(x0)) / (math.log2(x1) - math.log2(x0))
    return y0 + t * (y1 - y0)


def write_csv(path, rows, keys):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: ("inf" if isinstance(r.get(k), float) and math.isinf(r[k]) else r.get(k, "")) for k in keys})


def report(args, datasets, results, out_dir, info):
    txt = []
    rd = results["rd"]
    names = [ds.name for ds in datasets]
    codecs = [c for c in CODECS_RD if any(r["codec"] == c for r in rd)]

    dcsv, ll, eb, li = [], results["lossless"], results["maxerr"], {}
    if datasets:
        def cell(r, key="psnr"):
            if r is None:
                return "-"
            return f"{fnum(r[key])} @{r['bps']:.3f}" + ("*" if r.get("note") else "")

        idx = {(r["dataset"], r["target"], r["codec"]): r for r in rd}
        rows = []
        for n in names:
            for R in RATES:
                rows.append([n, f"{R:g}"] + [cell(idx.get((n, R, c))) for c in codecs])
        txt.append(table(["dataset", "R"] + codecs, rows,
                         "RATE-DISTORTION: PSNR dB (peak = max - min of the valid samples) @ bits/sample reached\n"
                         "  * = see note in rd.csv (target not reachable; the pair reached is shown)"))
        rows16 = []
        for ds in datasets:
            if ds.bits != 16:
                continue
            for R in RATES:
                rows16.append([ds.name, f"{R:g}"] + [cell(idx.get((ds.name, R, c)), "psnr65535") for c in codecs])
        if rows16:
            txt.append(table(["dataset", "R"] + codecs, rows16,
                             "RATE-DISTORTION, 16-bit data sets: PSNR dB with peak 65535 @ bits/sample"))
        # MRSV minus peer, at MRSV's rate
        peers = [c for c in codecs if c != "mrsv"]
        drows, dcsv = [], []
        for n in names:
            for R in RATES:
                m = idx.get((n, R, "mrsv"))
                if not m:
                    continue
                line = [n, f"{R:g}", f"{m['bps']:.3f}", fnum(m["psnr"])]
                for c in peers:
                    pts = [r for r in rd if r["dataset"] == n and r["codec"] == c]
                    p = interp_peer(pts, m["bps"]) if pts else None
                    dv = None if p is None or not math.isfinite(m["psnr"]) else m["psnr"] - p
                    line.append("-" if dv is None else f"{dv:+.2f}")
                    dcsv.append(dict(dataset=n, target=R, mrsv_bps=m["bps"], mrsv_psnr=m["psnr"], peer=c,
                                     peer_psnr_at_mrsv_bps=p, delta_db=dv))
                drows.append(line)
        txt.append(table(["dataset", "R", "mrsv bps", "mrsv PSNR"] + [f"vs {c}" for c in peers], drows,
                         "MRSV minus peer, dB, at MRSV's rate (peer curve interpolated in log2(rate); '-' = more than 3 %\n"
                         "  outside the peer's measured rates). Negative = MRSV loses."))
        # lossless
        ll = results["lossless"]
        lcod = [c for c in ["mrsv", "opj-5/3", "jxl", "xz", "zstd"] if any(r["codec"] == c for r in ll)]
        li = {(r["dataset"], r["codec"]): r for r in ll}
        lrows = []
        for ds in datasets:
            m = li.get((ds.name, "mrsv"))
            line = [ds.name]
            for c in lcod:
                r = li.get((ds.name, c))
                line.append("-" if r is None else f"{r['bytes'] * 8 / ds.n:.4f}" + ("" if r["ok"] else "!"))
            for c in lcod[1:]:
                r = li.get((ds.name, c))
                line.append("-" if r is None or m is None else f"{m['bytes'] / r['bytes']:.3f}")
            lrows.append(line)
        txt.append(table(["dataset"] + [f"{c} bps" for c in lcod] + [f"mrsv/{c}" for c in lcod[1:]], lrows,
                         "LOSSLESS: bits/sample of the whole grid, and size ratio MRSV/peer (<1: MRSV smaller).\n"
                         "  Every decode was compared with the original file ('!' = it differed)."))
        # error bound
        eb = results["maxerr"]
        erows = []
        for ds in datasets:
            for r in sorted((r for r in eb if r["dataset"] == ds.name), key=lambda r: r["d"]):
                own = best = None
                if math.isfinite(r["psnr"]):
                    own = interp_peer([x for x in rd if x["dataset"] == ds.name and x["codec"] == "mrsv"], r["bps"])
                    for c in peers:
                        v = interp_peer([x for x in rd if x["dataset"] == ds.name and x["codec"] == c], r["bps"])
                        if v is not None and (best is None or v > best[1]):
                            best = (c, v)
                r["mrsv_bps_route_psnr"] = own
                r["best_peer"], r["best_peer_psnr"] = best if best else (None, None)
                erows.append([ds.name, r["d"], f"{r['bps']:.4f}", r["outside"], r["max_abs_error"], fnum(r["psnr"]),
                              "-" if r["voids_exact"] is None else f"{'yes' if r['voids_exact'] else 'NO'} ({r['voids']})",
                              "-" if own is None else f"{own:.2f}",
                              "-" if best is None else f"{best[1]:.2f} {best[0]}"])
        txt.append(table(["dataset", "d", "bps", "outside d", "max |err|", "PSNR", "voids exact (count)",
                          "mrsv --bits-per-sample", "best peer"], erows,
                         "ERROR BOUND: mrsv encode --max-error d; decoded samples with |error| > d (must be 0).\n"
                         "  Last two columns: PSNR at the same rate of MRSV's --bits-per-sample curve and of the best peer\n"
                         "  among those measured around that rate (interpolated as in the table above; '-' = none)."))
    # speed
    sp = results.get("speed")
    if sp:
        srows = []
        for r in sp:
            srows.append([r["what"], r["tool"], r["dataset"], r["samples"], f"{r['bps']:.3f}", f"{r['wall_s']:.3f}",
                          f"{r['cpu_s'] / r['wall_s']:.2f}", f"{r['msps']:.2f}", f"{r['msps_cpu']:.2f}"])
        txt.append(table(["what", "tool", "dataset", "samples", "bps", "best wall s", "cpu/wall", "M samples/s",
                          "M samples/cpu-s"], srows,
                         f"DECODING SPEED: best of {args.speed_reps}, wall clock of the whole process (file in, file out);\n"
                         f"  machine load average (1/5/15 min) before {results.get('load_before')}, "
                         f"after {results.get('load_after')} ({os.cpu_count()} CPUs)"))
        g = {(r["what"], r["tool"]): r for r in sp}
        ratios = []
        for a, b in [(("3-D decode", "mrsv"), ("3-D decode", "zfp")),
                     (("3-D decode", "mrsv"), ("3-D decode", "zfp-f32")),
                     (("3-D decode", "mrsv"), ("2-D decode", "opj_decompress")),
                     (("2-D decode", "mrsv"), ("2-D decode", "opj_decompress"))]:
            if a in g and b in g:
                ratios.append([f"mrsv {a[0]} / {b[1]} {b[0]}", f"{g[a]['msps'] / g[b]['msps']:.3f}"])
        for tool, label in [("mrsv", "mrsv 3-D (--progressive)"), ("mrsv-default", "mrsv 3-D (default options)")]:
            if ("3-D decode", tool) in g:
                m = g[("3-D decode", tool)]
                ratios.append([f"{label} M samples/s per core vs goal 50",
                               f"{m['msps_cpu']:.2f} ({m['msps_cpu'] / 50:.1%} of goal)"])
        txt.append(table(["ratio (samples/s)", "value"], ratios, "SPEED RATIOS (same run)"))
        results["speed_ratios"] = ratios
    if results["skipped"]:
        txt.append("NOT RUN / FAILED:\n" + "\n".join("  " + s for s in results["skipped"]))
    body = "\n\n".join(txt)
    head = "\n".join(info)
    (out_dir / ("summary.txt" if datasets else "summary_speed.txt")).write_text(head + "\n\n" + body + "\n")
    print(head + "\n\n" + body)
    if sp:
        write_csv(out_dir / "speed.csv", sp, ["what", "tool", "dataset", "samples", "bps", "wall_s", "cpu_s", "msps",
                                              "msps_cpu", "cmd"])
    if not datasets:
        return

    write_csv(out_dir / "rd.csv", rd, ["dataset", "kind", "type", "samples", "voids", "target", "codec", "bps",
                                       "psnr", "psnr65535", "max_error", "mse", "param", "note"])
    write_csv(out_dir / "rd_delta.csv", dcsv, ["dataset", "target", "mrsv_bps", "mrsv_psnr", "peer",
                                               "peer_psnr_at_mrsv_bps", "delta_db"])
    for r in ll:
        r["bps"] = r["bytes"] * 8 / r["samples"]
        m = li.get((r["dataset"], "mrsv"))
        r["mrsv_over_peer"] = m["bytes"] / r["bytes"] if m else None
    write_csv(out_dir / "lossless.csv", ll, ["dataset", "samples", "codec", "bytes", "bps", "mrsv_over_peer", "ok", "param"])
    write_csv(out_dir / "error_bound.csv", eb, ["dataset", "d", "bps", "outside", "max_abs_error", "psnr", "voids",
                                                "voids_exact", "mrsv_bps_route_psnr", "best_peer", "best_peer_psnr"])
    plot(datasets, rd, codecs, eb, out_dir / "rd_curves.png")


def plot(datasets, rd, codecs, eb, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        log("matplotlib missing: no plot (run tools/bench/setup_peers.sh)")
        return
    n = len(datasets)
    ncol = min(4, n)
    nrow = math.ceil(n / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.6 * ncol, 3.9 * nrow), squeeze=False)
    style = {"mrsv": ("k", "o", "-"), "zfp-rate": ("tab:blue", "s", "--"), "zfp-acc": ("tab:cyan", "D", "--"),
             "opj-9/7": ("tab:red", "^", "-."), "jxl": ("tab:green", "v", ":"), "jxl-scaled": ("tab:olive", "P", ":")}
    style["mrsv --max-error"] = ("dimgray", "o", (0, (1, 1)))
    for ax, ds in zip(axes.flat, datasets):
        ys, xs, ym, lossless = [], [], [], []
        series = [(c, [r for r in rd if r["dataset"] == ds.name and r["codec"] == c]) for c in codecs]
        series.append(("mrsv --max-error", [r for r in eb if r["dataset"] == ds.name]))
        for c, rs in series:
            pts = sorted({(r["bps"], r["psnr"]) for r in rs if math.isfinite(r["psnr"])})
            col, mk, ls = style.get(c, ("gray", "x", "-"))
            lossless += [(r["bps"], col, mk) for r in rs if math.isinf(r["psnr"])]
            if not pts:
                continue
            ax.plot([p[0] for p in pts], [p[1] for p in pts], color=col, marker=mk, ls=ls, lw=1.4, ms=5, label=c,
                    mfc="none" if c == "mrsv --max-error" else col)
            ys += [p[1] for p in pts]
            xs += [p[0] for p in pts]
            if c == "mrsv":
                ym += [p[1] for p in pts]
        if lossless:
            tr = ax.get_xaxis_transform()
            for x, col, mk in sorted(set(lossless)):
                ax.plot([x], [0.96], marker=mk, color=col, mfc="none", ms=7, transform=tr, clip_on=False)
            ax.text(0.02, 0.90, "hollow at top: lossless", transform=ax.transAxes, fontsize=7, color="gray")
            xs += [x for x, _, _ in lossless]
        ax.set_xscale("log", base=2)
        ax.set_xticks([0.125, 0.25, 0.5, 1, 2, 4, 8])
        ax.set_xticklabels(["1/8", "1/4", "1/2", "1", "2", "4", "8"])
        ax.set_xlim(min([0.35] + [x * 0.85 for x in xs]), 6)
        if ys:
            floor = (min(ym) if ym else min(ys)) - 25
            lo = max(min(ys), floor)
            ax.set_ylim(lo - 2, max(ys) + (8 if lossless else 3))
            if min(ys) < lo:
                ax.text(0.02, 0.02, "some points below the axis (rd.csv)", transform=ax.transAxes, fontsize=7,
                        color="gray")
        dims = "x".join(map(str, ds.dims))
        ax.set_title(f"{ds.name}\n{dims} {ds.mtype}" + (f", {ds.nvoid} voids" if ds.nvoid else ""), fontsize=10)
        ax.set_xlabel("bits/sample")
        ax.set_ylabel("PSNR dB (peak max-min)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, loc="lower right")
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    fig.suptitle("MRSV vs peers: PSNR over valid samples vs bits/sample (all samples)\n"
                 "mrsv = --bits-per-sample 0.5/1/2/4; mrsv --max-error = d 16/4/1 (0 = lossless)", fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


# ----------------------------------------------------------------------------- main

def loadavg():
    try:
        return " ".join(open("/proc/loadavg").read().split()[:3])
    except OSError:
        return "?"


def versions(args):
    out = []
    try:
        p = subprocess.run(["dpkg-query", "-W", "-f", "${Package} ${Version}\\n", "zfp", "libopenjp2-tools",
                            "libjxl-tools", "xz-utils", "zstd", "python3-numpy", "python3-matplotlib"],
                           capture_output=True, text=True)
        out += [l for l in p.stdout.splitlines() if l.strip()]
    except OSError:
        pass
    try:
        cpu = [l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")]
        out.append(f"cpu: {cpu[0]} x{len(cpu)}" if cpu else "")
    except OSError:
        pass
    out.append(f"mrsv encode options: {' '.join(MRSV_EXTRA) or 'none beyond those listed in README.md'}; wavelet order used: "
               f"{args.order or args.mrsv_default_order}")
    out.append(f"mrsv: {args.mrsv_orig} built {args.mrsv_mtime}, sha256 {args.mrsv_sha256[:16]}, copied at the start; "
               f"work tree then: git {args.git_state}")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="See tools/bench/README.md.")
    ap.add_argument("--data", type=Path, default=REPO.parent / "shared" / "data", help="data dir (../shared/data)")
    ap.add_argument("--mrsv", type=Path, default=REPO / "build" / "mrsv", help="the mrsv tool (build/mrsv)")
    ap.add_argument("--out", type=Path, default=REPO / "tools" / "bench" / "results", help="results dir")
    ap.add_argument("--datasets", help="comma-separated substrings of data set names (e.g. rainier,bonsai)")
    ap.add_argument("--quick", action="store_true", help=f"only {' and '.join(QUICK)} (the speed part still runs)")
    ap.add_argument("--no-speed", action="store_true", help="skip the decoding-speed part")
    ap.add_argument("--speed-only", action="store_true", help="only the decoding-speed part (part 4)")
    ap.add_argument("--lossless-only", action="store_true", help="only the lossless part (part 2)")
    ap.add_argument("--speed-volume", default="ct_bonsai", help="256^3 volume for the speed part (ct_bonsai)")
    ap.add_argument("--speed-terrain", default="mt_rainier", help="2-D terrain for the speed part (mt_rainier)")
    ap.add_argument("--speed-reps", type=int, default=3)
    ap.add_argument("--order", type=int, choices=[1, 2, 3, 4],
                    help="pass --order K to every mrsv encode (default: the encoder's own default)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2,
                    help="parallel jobs for parts 1-3 (speed always runs alone)")
    ap.add_argument("--tmp", type=Path, default=None, help="parent of the temp dir (system default)")
    args = ap.parse_args()
    args.mrsv = args.mrsv.resolve()
    if args.order:
        MRSV_EXTRA.extend(["--order", str(args.order)])

    if not args.mrsv.exists():
        sys.exit(f"rd_bench: {args.mrsv} not found: build with ninja -C build")
    missing = [t for t in TOOLS if shutil.which(t) is None]
    if "zstd" in missing:
        sys.exit("rd_bench: zstd is needed to read the data: run tools/bench/setup_peers.sh")
    all_ds = discover(args.data)
    if not all_ds:
        sys.exit(f"rd_bench: no terrain/volume .raw.zst files in {args.data}")
    sel = all_ds
    if args.quick:
        sel = [ds for ds in all_ds if ds.name in QUICK]
    if args.datasets:
        keys = [k.strip() for k in args.datasets.split(",") if k.strip()]
        sel = [ds for ds in sel if any(k in ds.name for k in keys)]
        if not sel:
            sys.exit(f"rd_bench: --datasets {args.datasets} matches none of: {', '.join(d.name for d in all_ds)}")
    args.out.mkdir(parents=True, exist_ok=True)

    results = dict(rd=[], lossless=[], maxerr=[], skipped=[])
    lock = threading.Lock()
    for t in missing:
        results["skipped"].append(f"{t}: not installed (tools/bench/setup_peers.sh): its parts are skipped")

    def have(*tools):
        return all(t not in missing for t in tools)

    t_start = time.time()
    signal.signal(signal.SIGTERM, stop_all)
    signal.signal(signal.SIGINT, stop_all)
    with tempfile.TemporaryDirectory(prefix="mrsv_rd_bench_", dir=args.tmp) as tmp:
        root = Path(tmp)
        # One binary for the whole run, even if build/ is rebuilt meanwhile.
        snap = root / "mrsv"
        shutil.copy2(args.mrsv, snap)
        args.mrsv_sha256 = hashlib.sha256(snap.read_bytes()).hexdigest()
        args.mrsv_mtime = time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(args.mrsv.stat().st_mtime))
        args.mrsv_orig, args.mrsv = args.mrsv, snap
        rev = subprocess.run(["git", "-C", str(REPO), "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
        dirty = subprocess.run(["git", "-C", str(REPO), "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True)
        args.git_state = rev.stdout.strip() + (" + uncommitted changes" if dirty.stdout.strip() else "")
        hp = subprocess.run([str(snap), "encode", "--help"], capture_output=True, text=True)
        m = re.search(r"--order K.*\(default (\d+)\)", hp.stdout + hp.stderr)
        args.mrsv_default_order = f"{m[1]} (the encoder default)" if m else "the encoder default"
        log(f"temp dir {root}; data sets: {', '.join(d.name for d in sel)}")
        for ds in ([] if args.speed_only else sel):
            prepare(ds, root)

        tasks = []  # (cost estimate, label, fn)
        for ds in sel:
            def add(cost, label, fn, ds=ds):
                tasks.append((cost * ds.n, ds, label, fn))
            if args.speed_only:
                continue
            rd = not args.lossless_only
            for R in RATES if rd else []:
                add(0.6, f"mrsv rd {R:g}", lambda wd, ds=ds, R=R: ("rd", task_mrsv_rd(args, ds, R, wd)))
            if rd and have("zfp"):
                add(0.15, "zfp-rate", lambda wd, ds=ds: ("rd", task_zfp_rate(args, ds, wd)))
                add(0.5, "zfp-acc", lambda wd, ds=ds: ("rd", task_zfp_acc(args, ds, wd)))
            if ds.kind == "terrain" and ds.bits == 16:
                if have("opj_compress", "opj_decompress"):
                    if rd:
                        add(0.4, "opj rd", lambda wd, ds=ds: ("rd", task_opj_rd(args, ds, wd)))
                    add(0.2, "opj lossless", lambda wd, ds=ds: ("lossless", [task_lossless(args, ds, wd, "opj-5/3")]))
                if have("cjxl", "djxl"):
                    if rd:
                        add(12, "jxl rd", lambda wd, ds=ds: ("rd", task_jxl_rd(args, ds, wd, False)))
                        add(12, "jxl-scaled rd", lambda wd, ds=ds: ("rd", task_jxl_rd(args, ds, wd, True)))
                    add(17, "jxl lossless", lambda wd, ds=ds: ("lossless", [task_lossless(args, ds, wd, "jxl")]))
            add(1.5, "mrsv lossless", lambda wd, ds=ds: ("lossless", [task_lossless(args, ds, wd, "mrsv")]))
            if have("xz"):
                add(0.8, "xz", lambda wd, ds=ds: ("lossless", [task_lossless(args, ds, wd, "xz")]))
            add(0.4, "zstd", lambda wd, ds=ds: ("lossless", [task_lossless(args, ds, wd, "zstd")]))
            for d in MAX_ERRORS if rd else []:
                add(1.2, f"mrsv max-error {d}", lambda wd, ds=ds, d=d: ("maxerr", [task_maxerr(args, ds, wd, d)]))
        tasks.sort(key=lambda t: -t[0])
        log(f"parts 1-3: {len(tasks)} tasks on {args.jobs} jobs")

        def go(i, ds, label, fn):
            wd = root / ds.name / f"t{i}"
            wd.mkdir()
            t0 = time.time()
            try:
                kind, rows = fn(wd)
                for r in rows:
                    r.update(dataset=ds.name, kind=ds.kind, type=ds.mtype, samples=ds.n, voids=ds.nvoid)
                with lock:
                    results[kind].extend(rows)
                log(f"done {ds.name}: {label} ({time.time() - t0:.1f} s)")
            except Exception as e:  # noqa: BLE001 - report and go on with the other parts
                with lock:
                    results["skipped"].append(f"{ds.name}: {label}: {e}")
                log(f"FAILED {ds.name}: {label}: {e}\n{traceback.format_exc()}")
            finally:
                shutil.rmtree(wd, ignore_errors=True)

        with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as ex:
            futs = [ex.submit(go, i, ds, label, fn) for i, (_, ds, label, fn) in enumerate(tasks)]
            for f in as_completed(futs):
                f.result()
        t_parts = time.time() - t_start

        if not args.no_speed:
            if have("zfp", "opj_compress", "opj_decompress"):
                log("part 4: decoding speed (no other job of this bench runs meanwhile)")
                try:
                    results["load_before"] = loadavg()
                    speed(args, all_ds, root, results)
                    results["load_after"] = loadavg()
                except Exception as e:  # noqa: BLE001
                    results["skipped"].append(f"speed: {e}")
                    log(f"FAILED speed: {e}")
            else:
                results["skipped"].append("speed: needs zfp and opj_decompress")

    if args.speed_only:
        sel = []
    order = {ds.name: i for i, ds in enumerate(sel)}
    results["rd"].sort(key=lambda r: (order[r["dataset"]], r["target"], CODECS_RD.index(r["codec"])))
    info = ["MRSV rate-distortion / lossless / error-bound / speed benchmark (tools/bench/rd_bench.py)",
            f"date: {time.strftime('%Y-%m-%d %H:%M:%S')}; data: {args.data}; "
            f"wall time: parts 1-3 {t_parts:.0f} s, total {time.time() - t_start:.0f} s ({args.jobs} jobs)"]
    info += versions(args)
    info.append("data sets: " + "; ".join(
        f"{d.name} {'x'.join(map(str, d.dims))} {d.mtype} range {d.vmin}..{d.vmax}" + (f" voids {d.nvoid}" if d.nvoid else "")
        for d in sel))
    report(args, sel, results, args.out, info)
    log(f"results in {args.out}")


if __name__ == "__main__":
    main()
