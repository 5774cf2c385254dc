#!/usr/bin/env python3
"""mrsv and the real GDAL tools (issue 25, decision D73).

The GeoTIFF originals of ../shared/data/terrain go through `mrsv encode` and
`mrsv decode OUT.tif`; the real gdalinfo -json, gdal_translate and
gdallocationinfo then compare the round trip with the original: samples
(exactly when lossless), geotransform, EPSG code, no-data value, data type.
Bad rasters must give one-line errors naming the file and leave no output.

With the directory of the driver plugin gdal_MRSV.so, the same tools also
open .mrsv files through it (GDAL_DRIVER_PATH): samples, georeferencing and
overviews (the wavelet levels, as mrsv decode --levels K gives them); and
gdal_translate -of MRSV writes them: the bytes mrsv encode writes with the
same options, refused options named with their rule.

Usage: gdal_cli_test.py PATH/TO/mrsv SHARED_DATA_DIR ON|OFF [PLUGIN_DIR]
(ON|OFF is the build's MRSV_GDAL; OFF exits 77, which ctest reports as
skipped).
"""
import array
import json
import math
import os
import re
import subprocess
import sys
import tempfile

MRSV, DATA, GDAL = sys.argv[1], sys.argv[2], sys.argv[3].upper()
PLUGINS = sys.argv[4] if len(sys.argv) > 4 else None
if GDAL not in ("ON", "1", "TRUE", "YES"):
    print("skipped: this build has MRSV_GDAL off")
    sys.exit(77)

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


def run(*cmd, expect=0, env=None):
    r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, env=env)
    if r.returncode != expect:
        failures.append(f"exit {r.returncode} (want {expect}): {' '.join(map(str, cmd))}: {r.stderr.strip()[:300]}")
        print("FAIL:", failures[-1])
    return r


def info(path, *config, env=None):
    return json.loads(run("gdalinfo", "-json", *config, path, env=env).stdout or "{}")


def epsg(gdal_json):
    m = re.search(r'ID\["EPSG",(\d+)\]\]\s*$', gdal_json.get("coordinateSystem", {}).get("wkt", ""))
    return int(m.group(1)) if m else None


def samples(path, work, typecode):
    """The band's samples as gdal_translate writes them (ENVI: raw, row 0 first)."""
    out = os.path.join(work, os.path.basename(path) + ".bin")
    run("gdal_translate", "-q", "-of", "ENVI", path, out)
    a = array.array(typecode)
    with open(out, "rb") as f:
        a.frombytes(f.read())
    return a


def meta(mrsv_file):
    return json.loads(run(MRSV, "info", "--json", mrsv_file).stdout or "{}").get("metadata", {})


def close(a, b):
    return all(math.isclose(x, y, rel_tol=1e-12, abs_tol=1e-9) for x, y in zip(a, b)) and len(a) == len(b)


def one_line_error(r, path, words):
    line = r.stderr.strip()
    check("\n" not in line and os.path.basename(path) in line and words in line,
          f"one-line error naming {os.path.basename(path)} and '{words}': {r.stderr!r}")


def unzstd(name, work):
    out = os.path.join(work, name)
    run("zstd", "-q", "-d", "-f", os.path.join(DATA, "terrain", name + ".zst"), "-o", out)
    return out


def same_as_mrsv_decode(stream, out, overview, work, env, label):
    """Through the plugin, a 200 x 150 window (samples and geotransform), the
    whole raster and overview index `overview` of an int16 `stream` equal what
    mrsv decode gives (--region, whole, --levels overview + 1)."""
    run("gdal_translate", "-q", "-srcwin", "300", "170", "200", "150", stream, out + "_win.tif", env=env)
    run(MRSV, "decode", "--quiet", "--region", "300,170,500,320", stream, out + "_region.tif")
    check(samples(out + "_win.tif", work, "h") == samples(out + "_region.tif", work, "h"),
          f"plugin, {label}: a window differs from mrsv decode --region")
    check(close(info(out + "_win.tif")["geoTransform"], info(out + "_region.tif")["geoTransform"]),
          f"plugin, {label}: a window's geotransform differs from mrsv decode --region")
    run("gdal_translate", "-q", stream, out + "_whole.tif", env=env)
    run(MRSV, "decode", "--quiet", stream, out + "_whole_m.tif")
    check(samples(out + "_whole.tif", work, "h") == samples(out + "_whole_m.tif", work, "h"),
          f"plugin, {label}: the whole raster differs from mrsv decode")
    run("gdal_translate", "-q", "-ovr", str(overview), stream, out + "_ovr.tif", env=env)
    run(MRSV, "decode", "--quiet", "--levels", str(overview + 1), stream, out + "_levels.tif")
    check(samples(out + "_ovr.tif", work, "h") == samples(out + "_levels.tif", work, "h"),
          f"plugin, {label}: overview {overview + 1} differs from mrsv decode --levels {overview + 1}")


def round_trip(work, tif, raw_name, encode_options):
    """Encode and decode `tif`, compare everything gdalinfo and the samples say."""
    base = os.path.join(work, os.path.splitext(os.path.basename(tif))[0])
    run(MRSV, "encode", "--quiet", *encode_options, tif, base + ".mrsv")
    run(MRSV, "decode", "--quiet", base + ".mrsv", base + "_rt.tif")
    a, b = info(tif), info(base + "_rt.tif")
    name = os.path.basename(tif)
    check(a["size"] == b["size"], f"{name}: size {b['size']} != {a['size']}")
    check(close(a["geoTransform"], b["geoTransform"]), f"{name}: geotransform {b['geoTransform']} != {a['geoTransform']}")
    check(epsg(a) is not None and epsg(a) == epsg(b), f"{name}: EPSG {epsg(b)} != {epsg(a)}")
    check(a["bands"][0]["type"] == b["bands"][0]["type"], f"{name}: type {b['bands'][0]['type']}")
    check(a["bands"][0].get("noDataValue") == b["bands"][0].get("noDataValue"), f"{name}: nodata differs")
    # The meta chunk says what D73 says: origin at the centre of pixel (0, 0).
    gt, m = a["geoTransform"], meta(base + ".mrsv")
    origin = [float(v) for v in m.get("origin", "nan,nan").split(",")]
    spacing = [float(v) for v in m.get("spacing", "nan,nan").split(",")]
    check(close(origin, [gt[0] + gt[1] / 2, gt[3] + gt[5] / 2]), f"{name}: meta origin {origin}")
    check(close(spacing, [gt[1], gt[5]]), f"{name}: meta spacing {spacing}")
    check(m.get("crs") == f"EPSG:{epsg(a)}", f"{name}: meta crs {m.get('crs')}")
    # Samples: exactly those of the original, and of the .raw made from it (row 0 north).
    check(samples(tif, work, "h") == samples(base + "_rt.tif", work, "h"), f"{name}: samples differ")
    raw = unzstd(raw_name, work)
    run(MRSV, "decode", "--quiet", base + ".mrsv", base + "_rt.raw")
    with open(raw, "rb") as f1, open(base + "_rt.raw", "rb") as f2:
        check(f1.read() == f2.read(), f"{name}: samples differ from {raw_name}")
    # gdallocationinfo at the map positions of a few sample centres.
    for px, py in ((0, 0), (17, 301), (a["size"][0] - 1, a["size"][1] - 1), (400, 200)):
        x, y = gt[0] + (px + 0.5) * gt[1], gt[3] + (py + 0.5) * gt[5]
        va = run("gdallocationinfo", "-valonly", "-geoloc", tif, x, y).stdout.strip()
        vb = run("gdallocationinfo", "-valonly", "-geoloc", base + "_rt.tif", x, y).stdout.strip()
        check(va != "" and va == vb, f"{name}: gdallocationinfo at pixel {px},{py}: {vb!r} != {va!r}")
    return base


with tempfile.TemporaryDirectory() as work:
    # Projected (UTM 11N), no-data 32767; geographic (EPSG:4326) with voids.
    tujunga = unzstd("big_tujunga_srtm1_30m_utm11.tif", work)
    rainier = unzstd("srtm3_N46W122_mt_rainier_90m.tif", work)
    round_trip(work, tujunga, "big_tujunga_1197x643_int16le.raw", [])
    rb = round_trip(work, rainier, "srtm3_N46W122_mt_rainier_1201x1201_int16le.raw", ["--progressive"])

    # Reduced resolution: 2 levels up, the pixel is 4 times larger and pixel
    # (0, 0) still has its centre on sample (0, 0).
    run(MRSV, "decode", "--quiet", "--levels", "2", rb + ".mrsv", rb + "_l2.tif")
    full, low = info(rainier), info(rb + "_l2.tif")
    g, h = full["geoTransform"], low["geoTransform"]
    check(low["size"] == [301, 301], f"--levels 2 size {low['size']}")
    check(close([h[1], h[5]], [4 * g[1], 4 * g[5]]), f"--levels 2 pixel size {h}")
    check(close([h[0] + h[1] / 2, h[3] + h[5] / 2], [g[0] + g[1] / 2, g[3] + g[5] / 2]), f"--levels 2 origin {h}")
    check(epsg(low) == 4326, "--levels 2 EPSG")

    # Lossy within a bound: every valid sample within 3, voids stay voids.
    run(MRSV, "encode", "--quiet", "--max-error", "3", rainier, rb + "_e3.mrsv")
    run(MRSV, "decode", "--quiet", rb + "_e3.mrsv", rb + "_e3.tif")
    orig, lossy = samples(rainier, work, "h"), samples(rb + "_e3.tif", work, "h")
    worst = max(abs(x - y) for x, y in zip(orig, lossy) if x != -32768)
    check(worst <= 3 and all((x == -32768) == (y == -32768) for x, y in zip(orig, lossy)),
          f"--max-error 3: worst {worst} or voids moved")

    # GDAL is opened only when a file needs it (D82): the tool itself does not
    # link it, and without the module a GeoTIFF is refused with one line and
    # no output while everything else still works.
    dyn = subprocess.run(["readelf", "-d", MRSV], capture_output=True, text=True).stdout
    check("libgdal" not in dyn, "mrsv links libgdal at start-up")
    nomod = dict(os.environ, MRSV_GDAL_MODULE=os.path.join(work, "absent.so"))
    r = run(MRSV, "encode", "--quiet", rainier, rb + "_nomod.mrsv", expect=3, env=nomod)
    check("GDAL module" in r.stderr and "MRSV_GDAL_MODULE" in r.stderr and len(r.stderr.strip().splitlines()) == 1
          and not os.path.exists(rb + "_nomod.mrsv"), f"no module: {r.stderr.strip()[:200]}")
    run(MRSV, "decode", "--quiet", rb + "_e3.mrsv", rb + "_nomod.raw", env=nomod)
    check(os.path.getsize(rb + "_nomod.raw") == 1201 * 1201 * 2, "no module: a raw decode failed")

    # PixelIsPoint: GDAL's geotransform is still the pixel corner; the meta
    # origin is the tie point itself (what GDAL reports when told not to shift).
    point = os.path.join(work, "point.tif")
    run("gdal_translate", "-q", "-mo", "AREA_OR_POINT=Point", tujunga, point)
    run(MRSV, "encode", "--quiet", point, point + ".mrsv")
    m = meta(point + ".mrsv")
    tie = info(point, "--config", "GTIFF_POINT_GEO_IGNORE", "TRUE")["geoTransform"]
    check(close([float(v) for v in m.get("origin", "nan,nan").split(",")], [tie[0], tie[3]]),
          f"PixelIsPoint origin {m.get('origin')} != tie point {tie[0]},{tie[3]}")
    check(m.get("area_or_point") == "point", "PixelIsPoint not kept in the meta chunk")
    run(MRSV, "decode", "--quiet", point + ".mrsv", point + "_rt.tif")
    p = info(point + "_rt.tif")
    check(p.get("metadata", {}).get("", {}).get("AREA_OR_POINT") == "Point", "decoded GeoTIFF is not PixelIsPoint")
    check(close(p["geoTransform"], info(point)["geoTransform"]), "PixelIsPoint geotransform changed")

    # Any raster GDAL reads, found by content: a VRT window of the GeoTIFF.
    vrt = os.path.join(work, "window.vrt")
    run("gdal_translate", "-q", "-of", "VRT", "-srcwin", "100", "50", "256", "128", tujunga, vrt)
    run(MRSV, "encode", "--quiet", vrt, vrt + ".mrsv")
    run(MRSV, "decode", "--quiet", vrt + ".mrsv", vrt + "_rt.tif")
    check(samples(vrt, work, "h") == samples(vrt + "_rt.tif", work, "h"), "VRT window samples differ")
    check(close(info(vrt)["geoTransform"], info(vrt + "_rt.tif")["geoTransform"]), "VRT window geotransform")

    # Multi-band: refused without --band, band 2 read with it.
    multi = os.path.join(work, "multi.tif")
    run("gdal_translate", "-q", "-b", "1", "-b", "1", "-b", "1", tujunga, multi)
    one_line_error(run(MRSV, "encode", "--quiet", multi, multi + ".mrsv", expect=1), multi, "--band N")
    check(not os.path.exists(multi + ".mrsv"), "refused multi-band input left an output")
    run(MRSV, "encode", "--quiet", "--band", "2", multi, multi + ".mrsv")
    run(MRSV, "decode", "--quiet", multi + ".mrsv", multi + "_rt.tif")
    check(samples(multi + "_rt.tif", work, "h") == samples(tujunga, work, "h"), "--band 2 samples differ")
    one_line_error(run(MRSV, "encode", "--quiet", "--band", "4", multi, multi + "4.mrsv", expect=1), multi, "bands 1 to 3")

    # Unsupported sample types, rotation, damage, 3-D output; the output that
    # was there before a failure stays as it was.
    for ot in ("UInt32", "CInt16"):
        bad = os.path.join(work, ot + ".tif")
        run("gdal_translate", "-q", "-ot", ot, tujunga, bad)
        one_line_error(run(MRSV, "encode", "--quiet", bad, bad + ".mrsv", expect=1), bad, ot)
    rotated = os.path.join(work, "rotated.vrt")
    with open(vrt) as f:
        text = re.sub(r"<GeoTransform>[^<]*</GeoTransform>",
                      "<GeoTransform>376313.7, 30, 4, 3807917.8, 4, -30</GeoTransform>", f.read())
    with open(rotated, "w") as f:
        f.write(text)
    keep = os.path.join(work, "keep.mrsv")
    with open(keep, "wb") as f:
        f.write(b"old")
    one_line_error(run(MRSV, "encode", "--quiet", rotated, keep, expect=1), rotated, "rotated")
    with open(keep, "rb") as f:
        check(f.read() == b"old", "a failed encode changed the existing output")
    truncated = os.path.join(work, "truncated.tif")
    with open(tujunga, "rb") as f, open(truncated, "wb") as g:
        g.write(f.read()[:3000])
    one_line_error(run(MRSV, "encode", "--quiet", truncated, truncated + ".mrsv", expect=1), truncated, "truncated.tif")
    check(not os.path.exists(truncated + ".mrsv"), "a damaged raster left an output")
    volume = os.path.join(work, "volume.raw")
    with open(volume, "wb") as f:
        f.write(bytes(range(256)) * 64)
    run(MRSV, "encode", "--quiet", "--dims", "32,32,16", "--type", "uint8", volume, volume + ".mrsv")
    one_line_error(run(MRSV, "decode", "--quiet", volume + ".mrsv", volume + ".tif", expect=2), volume + ".tif", "3-D")
    check(not os.path.exists(volume + ".tif"), "a refused GeoTIFF output was written")

    # The driver plugin: gdalinfo and gdal_translate read .mrsv themselves.
    if PLUGINS:
        env = dict(os.environ, GDAL_DRIVER_PATH=PLUGINS)
        stream = rb + ".mrsv"  # Rainier, lossless, progressive: 7 levels
        d, full = info(stream, env=env), info(rainier)
        check(d.get("driverShortName") == "MRSV", f"driver {d.get('driverShortName')}")
        check(d.get("size") == full["size"] and close(d.get("geoTransform", []), full["geoTransform"]),
              "plugin: size or geotransform differs")
        check(epsg(d) == 4326, "plugin: EPSG")
        band = (d.get("bands") or [{}])[0]
        check(band.get("type") == "Int16" and band.get("noDataValue") == -32768, f"plugin band {band}")
        sizes = [o["size"] for o in band.get("overviews", [])]
        check(sizes[:3] == [[601, 601], [301, 301], [151, 151]] and len(sizes) == 7, f"plugin overviews {sizes}")
        out = os.path.join(work, "plugin.tif")
        run("gdal_translate", "-q", stream, out, env=env)
        check(samples(out, work, "h") == samples(rainier, work, "h"), "plugin: gdal_translate samples differ")
        check(close(info(out)["geoTransform"], full["geoTransform"]), "plugin: gdal_translate geotransform")
        # Overview 2 (index 1) is the stream decoded 2 levels up. (Its pixel
        # size is GDAL's: the full extent over its size, not 4 pixels; D73.)
        run("gdal_translate", "-q", "-ovr", "1", stream, out + "_ovr1.tif", env=env)
        check(samples(out + "_ovr1.tif", work, "h") == samples(rb + "_l2.tif", work, "h"), "plugin: overview samples")
        # A tiled grid (spec 11): one block per tile, each read by region
        # decoding; windows, the whole raster and the overviews (the 2^K
        # lattice of 11.6) equal what mrsv decode gives.
        tiled = rb + "_t128.mrsv"
        run(MRSV, "encode", "--quiet", "--tile", "128", "--max-error", "2", rainier, tiled)
        t = info(tiled, env=env)
        tband = (t.get("bands") or [{}])[0]
        check(tband.get("block") == [128, 128], f"plugin, tiled: block {tband.get('block')}")
        check(close(t.get("geoTransform", []), full["geoTransform"]), "plugin, tiled: geotransform")
        tsizes = [o["size"] for o in tband.get("overviews", [])]
        check(tsizes == [[601, 601], [301, 301], [151, 151], [76, 76]],  # down to one block
              f"plugin, tiled: overviews {tsizes}")
        same_as_mrsv_decode(tiled, out + "_t", 2, work, env, "tiled")
        with open(tiled, "rb") as f, open(tiled + ".bad.mrsv", "wb") as g:
            b = bytearray(f.read())
            b[-200] ^= 0xFF  # inside the last tile's chunks
            g.write(b)
        r = run("gdal_translate", "-q", tiled + ".bad.mrsv", out + "_bad.tif", expect=1, env=env)
        check("bad.mrsv: window 0,0 1201x1201" in r.stderr and "E113" in r.stderr,
              f"plugin, tiled: a damaged tile: {r.stderr.strip()[:200]}")

        # A grid in precincts (spec 5.7.6): one block per precinct at full
        # resolution, each read by region decoding; windows and the whole
        # raster equal mrsv decode, the overviews its --levels.
        prec = rb + "_p128.mrsv"
        run(MRSV, "encode", "--quiet", "--precinct", "128", "--step", "8", rainier, prec)
        run("gdal_translate", "-q", "-of", "MRSV", "-co", "PRECINCT=128", "-co", "STEP=8", rainier,
            prec + ".gdal.mrsv", env=env)
        check("precincts 128" in run(MRSV, "info", prec + ".gdal.mrsv").stdout,
              "plugin, precincts: CreateCopy with PRECINCT=128")
        r = run("gdal_translate", "-q", "-of", "MRSV", "-co", "PRECINCT=100", rainier, prec + ".bad.mrsv",
                expect=1, env=env)
        check("PRECINCT=100" in r.stderr and "power of two" in r.stderr,
              f"plugin, precincts: PRECINCT=100: {r.stderr.strip()[:200]}")
        p = info(prec, env=env)
        check(p["bands"][0].get("block") == [128, 128], f"plugin, precincts: block {p['bands'][0].get('block')}")
        same_as_mrsv_decode(prec, out + "_p", 0, work, env, "precincts")

        # Opening reads the header part only: a stream damaged in its last
        # chunk opens, its overviews read (their prefix is intact), and only
        # a read of the full resolution fails, naming the file and the rule.
        with open(stream, "rb") as f, open(stream + ".tail.mrsv", "wb") as g:
            b = bytearray(f.read())
            b[-20] ^= 0xFF
            g.write(b)
        tail = info(stream + ".tail.mrsv", env=env)
        check(tail.get("size") == [1201, 1201], f"plugin: a stream damaged at its end does not open: {tail.get('size')}")
        run("gdal_translate", "-q", "-ovr", "1", stream + ".tail.mrsv", out + "_tail_ovr.tif", env=env)
        check(samples(out + "_tail_ovr.tif", work, "h") == samples(rb + "_l2.tif", work, "h"),
              "plugin: an overview of a stream damaged at its end")
        r = run("gdal_translate", "-q", stream + ".tail.mrsv", out + "_tail.tif", expect=1, env=env)
        check("tail.mrsv" in r.stderr and "E113" in r.stderr, f"plugin: damaged end: {r.stderr.strip()[:200]}")

        # Not rasters: a 3-D grid, a damaged stream.
        r = run("gdalinfo", volume + ".mrsv", expect=1, env=env)
        check("3-D" in r.stderr, f"plugin: 3-D grid: {r.stderr.strip()[:200]}")
        damaged = os.path.join(work, "damaged.mrsv")
        with open(stream, "rb") as f, open(damaged, "wb") as g:
            b = bytearray(f.read())
            b[60] ^= 0xFF
            g.write(b)
        r = run("gdalinfo", damaged, expect=1, env=env)
        check("damaged.mrsv" in r.stderr and "E1" in r.stderr, f"plugin: damaged stream: {r.stderr.strip()[:200]}")

        # Writing through the plugin (CreateCopy): gdal_translate -of MRSV
        # gives the bytes mrsv encode gives with the same options, and the
        # round trips give the original's samples and georeferencing.
        listed = run("gdalinfo", "--format", "MRSV", env=env).stdout
        for option in ("LOSSLESS", "MAX_ERROR", "RATE", "PSNR", "WAVELET", "LEVELS", "PROGRESSIVE"):
            check(f'name="{option}"' in listed, f"gdalinfo --format MRSV does not list {option}")
        via = os.path.join(work, "via_gdal.mrsv")
        r = run("gdal_translate", "-of", "MRSV", tujunga, via, env=env)
        check("100 - done" in r.stdout, f"gdal_translate -of MRSV shows no progress: {r.stdout!r}")
        with open(via, "rb") as f1, open(os.path.join(work, "big_tujunga_srtm1_30m_utm11.mrsv"), "rb") as f2:
            check(f1.read() == f2.read(), "gdal_translate -of MRSV (lossless) differs from mrsv encode")
        run(MRSV, "decode", "--quiet", via, via + ".tif")
        run("gdal_translate", "-q", via, via + "_gdal.tif", env=env)
        a = info(tujunga)
        for out in (via + ".tif", via + "_gdal.tif"):
            b = info(out)
            check(samples(out, work, "h") == samples(tujunga, work, "h"), f"{out}: samples differ")
            check(close(b["geoTransform"], a["geoTransform"]) and epsg(b) == epsg(a) and
                  b["bands"][0].get("noDataValue") == a["bands"][0].get("noDataValue"),
                  f"{out}: georeferencing differs")
        # Creation options: mrsv encode's bytes with its options (on the
        # 256 x 128 window, to be fast), and within MAX_ERROR of the samples.
        for co, cli in ((["MAX_ERROR=3"], ["--max-error", "3"]),
                        (["WAVELET=BSPLINE", "ORDER=3", "LEVELS=3", "RATE=2"],
                         ["--order", "3", "--levels", "3", "--bits-per-sample", "2"]),
                        (["PSNR=60", "PROGRESSIVE=YES", "ENTROPY=BASELINE"],
                         ["--psnr", "60", "--progressive", "--entropy", "baseline"]),
                        (["CODING=STORED"], ["--coding", "stored"])):
            name = os.path.join(work, "co_" + "_".join(co).replace("=", "") + ".mrsv")
            run("gdal_translate", "-q", "-of", "MRSV", *[x for c in co for x in ("-co", c)], vrt, name, env=env)
            run(MRSV, "encode", "--quiet", *cli, vrt, name + ".cli.mrsv")
            with open(name, "rb") as f1, open(name + ".cli.mrsv", "rb") as f2:
                check(f1.read() == f2.read(), f"-co {' -co '.join(co)} differs from mrsv encode {' '.join(cli)}")
        e3 = os.path.join(work, "co_MAX_ERROR3.mrsv")
        run("gdal_translate", "-q", e3, e3 + ".tif", env=env)
        orig, lossy = samples(vrt, work, "h"), samples(e3 + ".tif", work, "h")
        worst = max(abs(x - y) for x, y in zip(orig, lossy) if x != 32767)
        check(worst <= 3 and all((x == 32767) == (y == 32767) for x, y in zip(orig, lossy)),
              f"-co MAX_ERROR=3: worst {worst} or no-data moved")
        # PixelIsPoint stays PixelIsPoint, with mrsv encode's meta chunk
        # (stored samples: the georeferencing does not depend on the coding).
        run("gdal_translate", "-q", "-of", "MRSV", "-co", "CODING=STORED", point, point + ".gdal.mrsv", env=env)
        # (The wavelet coder adds its error_* entries.)
        georef = {k: v for k, v in meta(point + ".mrsv").items() if not k.startswith("error_")}
        check(meta(point + ".gdal.mrsv") == georef and georef.get("area_or_point") == "point",
              f"PixelIsPoint: meta {meta(point + '.gdal.mrsv')} != mrsv encode's {georef}")
        # Bad options and rasters: a one-line GDAL error naming the option and
        # the rule; nothing written.
        for co, words in ((["MAX_ERROR=-1"], "MAX_ERROR=-1: must be a number from 0"),
                          (["RATE=2", "PSNR=40"], "creation options RATE, PSNR: give at most one of"),
                          (["ORDER=3", "WAVELET=CDF97"], "ORDER=3: is for WAVELET=BSPLINE"),
                          (["BOUND_ROUTE=PREDICTIVE", "PROGRESSIVE=YES"], "not progressive"),
                          (["CODING=STORED", "RATE=1"], "CODING=STORED takes no")):
            bad = os.path.join(work, "bad.mrsv")
            r = run("gdal_translate", "-q", "-of", "MRSV", *[x for c in co for x in ("-co", c)], vrt, bad,
                    expect=1, env=env)
            check(words in r.stderr and "bad.mrsv" in r.stderr, f"-co {co}: {r.stderr.strip()[:200]}")
            check(not os.path.exists(bad), f"-co {co}: an output was written")
        r = run("gdal_translate", "-q", "-of", "MRSV", "-ot", "UInt32", vrt, vrt + ".u32.mrsv", expect=1, env=env)
        check("u32.mrsv: the source raster: sample type UInt32" in r.stderr and not os.path.exists(vrt + ".u32.mrsv"),
              f"UInt32 source: {r.stderr.strip()[:200]}")
        r = run("gdal_translate", "-q", "-of", "MRSV", multi, multi + ".gdal.mrsv", expect=1, env=env)
        check("gdal_translate -b N" in r.stderr and not os.path.exists(multi + ".gdal.mrsv"),
              f"multi-band source: {r.stderr.strip()[:200]}")
        run("gdal_translate", "-q", "-of", "MRSV", "-co", "CODING=STORED", "-b", "2", multi, multi + ".gdal.mrsv", env=env)
        run(MRSV, "decode", "--quiet", multi + ".gdal.mrsv", multi + "_gdal_rt.tif")
        check(samples(multi + "_gdal_rt.tif", work, "h") == samples(tujunga, work, "h"), "-b 2: samples differ")
        check(not [n for n in os.listdir(work) if "mrsv-tmp" in n or n.endswith(".mrsv.aux.xml")],
              f"temporary or .aux.xml files left: {os.listdir(work)}")

print(f"gdal_cli_test: {len(failures)} failures")
sys.exit(1 if failures else 0)
