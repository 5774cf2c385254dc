#!/usr/bin/env python3
"""rasterio on .mrsv files through the GDAL driver plugin (issue 25).

rasterio (Debian python3-rasterio) uses the system GDAL, so gdal_MRSV.so in
GDAL_DRIVER_PATH is all it needs: it reads a .mrsv's samples, CRS,
transform, no-data value and overviews (the wavelet levels) as it reads the
GeoTIFF they came from, and writes .mrsv with rasterio.open(..., 'w',
driver='MRSV') (a CreateCopy-only driver: rasterio buffers the raster in
memory and copies it on close) and rasterio.shutil.copy, whose output is the
bytes mrsv encode writes with the same options.

Usage: gdal_rasterio_test.py PATH/TO/mrsv SHARED_DATA_DIR PLUGIN_DIR
Exits 77 (skipped) when rasterio is not installed or the build has no plugin.
"""
import os
import subprocess
import sys
import tempfile

MRSV, DATA = sys.argv[1], sys.argv[2]
PLUGINS = sys.argv[3] if len(sys.argv) > 3 else ""
if not PLUGINS:
    print("skipped: this build has no GDAL driver plugin (MRSV_GDAL off)")
    sys.exit(77)
# Before rasterio registers GDAL's drivers.
os.environ["GDAL_DRIVER_PATH"] = PLUGINS
try:
    import numpy as np
    import rasterio
    import rasterio.shutil
except ImportError as e:
    print(f"skipped: {e} (install python3-rasterio: tools/setup.sh)")
    sys.exit(77)

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


def run(*cmd):
    r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True)
    check(r.returncode == 0, f"exit {r.returncode}: {' '.join(map(str, cmd))}: {r.stderr.strip()[:300]}")
    return r


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


with tempfile.TemporaryDirectory() as work:
    whole = os.path.join(work, "whole.tif")  # UTM 11N, no-data 32767
    run("zstd", "-q", "-d", "-f", os.path.join(DATA, "terrain", "big_tujunga_srtm1_30m_utm11.tif.zst"), "-o", whole)
    tif = os.path.join(work, "tujunga.tif")  # a 400 x 300 crop: fast to encode
    run("gdal_translate", "-q", "-srcwin", "700", "300", "400", "300", whole, tif)
    stream = os.path.join(work, "tujunga.mrsv")
    run(MRSV, "encode", "--quiet", "--progressive", tif, stream)
    low = os.path.join(work, "tujunga_l2.tif")
    run(MRSV, "decode", "--quiet", "--levels", "2", stream, low)

    with rasterio.open(tif) as a, rasterio.open(stream) as b:
        check(b.driver == "MRSV", f"driver {b.driver}")
        check((b.width, b.height, b.count, b.dtypes) == (a.width, a.height, a.count, a.dtypes),
              f"shape {b.width}x{b.height}x{b.count} {b.dtypes}")
        check(b.crs == a.crs and b.crs.to_epsg() == 32611, f"crs {b.crs}")
        check(b.transform.almost_equals(a.transform, precision=1e-9), f"transform {b.transform}")
        check(b.nodata == a.nodata == 32767, f"nodata {b.nodata}")
        check(np.array_equal(a.read(1), b.read(1)), "samples differ from the GeoTIFF's")
        window = rasterio.windows.Window(100, 50, 64, 32)
        check(np.array_equal(a.read(1, window=window), b.read(1, window=window)), "window samples differ")
        factors = b.overviews(1)
        check(factors[:3] == [2, 4, 8], f"overview factors {factors}")
    # Overview level 1 (decimation 4) is the stream decoded two levels up.
    with rasterio.open(stream, overview_level=1) as o, rasterio.open(low) as l2:
        check((o.width, o.height) == (l2.width, l2.height), f"overview size {o.width}x{o.height}")
        check(np.array_equal(o.read(1), l2.read(1)), "overview samples differ from mrsv decode --levels 2")

    # Writing: rasterio.shutil.copy gives mrsv encode's bytes.
    copied = os.path.join(work, "copied.mrsv")
    with rasterio.open(tif) as a:
        rasterio.shutil.copy(a, copied, driver="MRSV", max_error=3)
    run(MRSV, "encode", "--quiet", "--max-error", "3", tif, os.path.join(work, "cli.mrsv"))
    check(read_bytes(copied) == read_bytes(os.path.join(work, "cli.mrsv")),
          "rasterio.shutil.copy(..., driver='MRSV', max_error=3) differs from mrsv encode --max-error 3")

    # rasterio.open(..., 'w', driver='MRSV'): an array and its georeferencing.
    written = os.path.join(work, "written.mrsv")
    with rasterio.open(tif) as a:
        samples, profile = a.read(1), a.profile
    profile.update(driver="MRSV", max_error=2)
    for key in ("blockxsize", "blockysize", "tiled", "compress", "interleave"):
        profile.pop(key, None)
    with rasterio.open(written, "w", **profile) as w:
        w.write(samples, 1)
    with rasterio.open(written) as b:
        check(b.driver == "MRSV", f"written: driver {b.driver}")
        back = b.read(1)
        valid = samples != 32767
        check(np.array_equal(back != 32767, valid), "written: no-data samples moved")
        worst = int(np.max(np.abs(back[valid].astype(np.int32) - samples[valid])))
        check(worst <= 2, f"written with max_error=2: worst error {worst}")
        check(b.crs == profile["crs"] and b.transform.almost_equals(profile["transform"], precision=1e-9),
              f"written: crs {b.crs} transform {b.transform}")
        check(b.nodata == 32767, f"written: nodata {b.nodata}")

print(f"gdal_rasterio_test: {len(failures)} failures")
sys.exit(1 if failures else 0)
