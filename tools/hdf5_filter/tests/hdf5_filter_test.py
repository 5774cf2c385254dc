"""The MRSV HDF5 filter through h5py (issue 24): every mode on a real terrain
and a CT crop, exactness and bounds on every sample, the filter in h5dump,
reading without the plugin, refused types and corrupt chunks.

Run by ctest with HDF5_PLUGIN_PATH set to the built plugin's directory:
    /usr/bin/python3 -m pytest -q tools/hdf5_filter/tests/hdf5_filter_test.py
"""
import os
import pathlib
import struct
import subprocess
import sys

import h5py
import numpy as np
import pytest

FILTER_ID = 421  # MRSV_H5Z_FILTER_ID
LOSSLESS, RATE, PSNR, MAX_ERROR = 0, 1, 2, 3
SOURCE_DIR = pathlib.Path(os.environ.get("MRSV_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[3]))
CROPS = SOURCE_DIR / "demo" / "data"  # crops of ../shared/data (demo/data/SOURCES.md)


def opts(mode, value=0.0):
    """cd_values as the user gives them: mode and the parameter's float64 bits."""
    lo, hi = struct.unpack("<II", struct.pack("<d", value))
    return (mode, lo, hi)


def st_helens():
    return np.fromfile(CROPS / "mt_st_helens_128x128_int16le.raw", "<i2").reshape(128, 128)


def fuji():  # 50 SRTM voids (-32768)
    return np.fromfile(CROPS / "mt_fuji_summit_128x128_int16le.raw", "<i2").reshape(128, 128)


def ct_head():  # (z, y, x)
    return np.fromfile(CROPS / "ct_head_64x64x32_uint8.raw", "u1").reshape(32, 64, 64)


def write(path, data, chunks, mode, value=0.0, **kwargs):
    with h5py.File(path, "w") as f:
        f.create_dataset("d", data=data, chunks=chunks, compression=FILTER_ID,
                         compression_opts=opts(mode, value), **kwargs)


def read(path):
    """The dataset, after checking that the filter coded every chunk: h5py sets
    the filter optional, and HDF5 stores a chunk it fails on as is."""
    with h5py.File(path, "r") as f:
        d = f["d"].id
        assert all(d.get_chunk_info(i).filter_mask == 0 for i in range(d.get_num_chunks()))
        return f["d"][...]


def chunk_sizes(path):
    with h5py.File(path, "r") as f:
        d = f["d"].id
        assert all(d.get_chunk_info(i).filter_mask == 0 for i in range(d.get_num_chunks()))
        return [d.get_chunk_info(i).size for i in range(d.get_num_chunks())]


def chunk_blocks(data, chunks):
    """The samples of every chunk (edge chunks cut to the dataset)."""
    ranges = [range(0, n, c) for n, c in zip(data.shape, chunks)]
    for corner in np.array(np.meshgrid(*ranges, indexing="ij")).reshape(len(chunks), -1).T:
        yield data[tuple(slice(s, s + c) for s, c in zip(corner, chunks))]


def psnr(a, b):
    a = a.astype(np.float64)
    mse = np.mean((a - b.astype(np.float64)) ** 2)
    return np.inf if mse == 0 else 10 * np.log10((a.max() - a.min()) ** 2 / mse)


CASES = [("terrain", st_helens, (64, 64)), ("ct", ct_head, (16, 32, 32))]


@pytest.mark.parametrize("name,load,chunks", CASES)
def test_lossless_is_exact_and_smaller(tmp_path, name, load, chunks):
    data = load()
    path = tmp_path / f"{name}.h5"
    write(path, data, chunks, LOSSLESS)
    back = read(path)
    assert back.dtype == data.dtype and np.array_equal(back, data)
    assert sum(chunk_sizes(path)) < 0.7 * data.nbytes


@pytest.mark.parametrize("name,load,chunks", CASES)
@pytest.mark.parametrize("bound", [1, 4])
def test_max_error_holds_on_every_sample(tmp_path, name, load, chunks, bound):
    data = load()
    path = tmp_path / f"{name}.h5"
    write(path, data, chunks, MAX_ERROR, bound)
    error = np.abs(read(path).astype(np.int64) - data)
    assert error.max() <= bound
    assert sum(chunk_sizes(path)) < 0.5 * data.nbytes


@pytest.mark.parametrize("name,load,chunks", CASES)
def test_rate_is_kept_by_every_chunk(tmp_path, name, load, chunks):
    data = load()
    path = tmp_path / f"{name}.h5"
    rate = 1.5
    write(path, data, chunks, RATE, rate)
    samples = int(np.prod(chunks))
    assert all(size * 8 <= rate * samples for size in chunk_sizes(path))
    assert psnr(data, read(path)) > 30


@pytest.mark.parametrize("name,load,chunks", CASES)
def test_psnr_is_reached_by_every_chunk_and_the_dataset(tmp_path, name, load, chunks):
    data = load()
    path = tmp_path / f"{name}.h5"
    target = 45.0
    write(path, data, chunks, PSNR, target)
    back = read(path)
    for a, b in zip(chunk_blocks(data, chunks), chunk_blocks(back, chunks)):
        assert psnr(a, b) >= target
    assert psnr(data, back) >= target
    assert sum(chunk_sizes(path)) < 0.5 * data.nbytes


def test_edge_chunks_and_fill_value_as_no_data(tmp_path):
    # 100 x 90 in 64 x 64 chunks: HDF5 pads the edge chunks (with the fill
    # value); the Fuji voids are the fill value and come back exactly.
    data = fuji()[:100, :90]
    voids = data == -32768
    assert voids.sum() > 0
    path = tmp_path / "fuji.h5"
    write(path, data, (64, 64), MAX_ERROR, 2, fillvalue=-32768)
    with h5py.File(path, "r") as f:
        cd = f["d"].id.get_create_plist().get_filter_by_id(FILTER_ID)[1]
    assert cd[5] == 1 and cd[6] == 0x8000 and cd[7] == 0  # no-data flag, int16 -32768
    back = read(path)
    assert np.array_equal(back[voids], data[voids])
    assert np.abs(back[~voids].astype(np.int64) - data[~voids]).max() <= 2
    write(path, data, (64, 64), LOSSLESS)  # no fill value: voids are samples like any other
    assert np.array_equal(read(path), data)


def test_chunk_shapes_squeeze_leading_ones(tmp_path):
    data = ct_head().reshape(1, 32, 64, 64)
    path = tmp_path / "rank4.h5"
    write(path, data, (1, 8, 32, 32), LOSSLESS)  # a 3-D grid per chunk
    assert np.array_equal(read(path), data)
    write(path, data, (1, 1, 64, 64), MAX_ERROR, 3)  # slices: 2-D grids
    assert np.abs(read(path).astype(np.int64) - data).max() <= 3
    line = st_helens()[5]
    write(path, line, (64,), LOSSLESS)  # rank 1
    assert np.array_equal(read(path), line)
    with pytest.raises(Exception, match="at most 3"):
        write(path, np.zeros((2, 2, 8, 8), "u1"), (2, 2, 8, 8), LOSSLESS)


def test_sample_types(tmp_path):
    path = tmp_path / "types.h5"
    terrain = st_helens()
    for dtype in ["u1", "<u2", "<i4"]:
        data = (terrain - terrain.min()).astype(dtype) if dtype != "u1" else (terrain // 8).astype("u1")
        write(path, data, (64, 64), MAX_ERROR, 1)
        back = read(path)
        assert back.dtype == data.dtype and np.abs(back.astype(np.int64) - data).max() <= 1
    for dtype in ["<f4", "<f8"]:
        data = terrain.astype(dtype) * 0.25
        write(path, data, (64, 64), LOSSLESS)  # floats are stored, exactly
        assert np.array_equal(read(path), data)
        write(path, data, (64, 64), PSNR, 50)
        assert psnr(data, read(path)) >= 50
        assert sum(chunk_sizes(path)) < 0.3 * data.nbytes


@pytest.mark.parametrize("dtype,name", [("i1", "int8"), ("<u4", "uint32"), ("<i8", "int64"),
                                        ("<f2", "float16"), (">i2", "int16 big-endian")])
def test_unsupported_types_are_refused_by_name(tmp_path, dtype, name):
    with pytest.raises(Exception, match=f"element type {name} is not supported"):
        write(tmp_path / "bad.h5", np.zeros((8, 8), dtype), (8, 8), LOSSLESS)


@pytest.mark.parametrize("cd,message", [
    (opts(MAX_ERROR, 1), "needs integer samples"),
    (opts(7, 1), "mode 7 is not"),
    (opts(RATE, 0), "rate must be"),
    (opts(PSNR, 1000), "PSNR must be"),
    ((1, 2), "give no cd_values"),
])
def test_bad_parameters_are_refused(tmp_path, cd, message):
    with pytest.raises(Exception, match=message):
        with h5py.File(tmp_path / "bad.h5", "w") as f:
            f.create_dataset("d", data=np.zeros((8, 8), "<f4"), chunks=(8, 8), compression=FILTER_ID,
                             compression_opts=cd)


def test_h5dump_shows_the_filter(tmp_path):
    path = tmp_path / "dump.h5"
    write(path, st_helens(), (64, 64), PSNR, 50)
    out = subprocess.run(["h5dump", "-p", "-H", str(path)], capture_output=True, text=True, check=True).stdout
    assert f"FILTER_ID {FILTER_ID}" in out and "mrsv" in out
    with h5py.File(path, "r") as f:
        assert str(FILTER_ID) in f["d"]._filters


def test_reading_without_the_plugin_says_filter_not_available(tmp_path):
    path = tmp_path / "noplugin.h5"
    write(path, st_helens(), (64, 64), LOSSLESS)
    empty = tmp_path / "no_plugins"
    empty.mkdir()
    script = ("import h5py, sys\n"
              "try:\n"
              f"    h5py.File({str(path)!r}, 'r')['d'][...]\n"
              "except OSError as e:\n"
              "    print(e); sys.exit(0)\n"
              "sys.exit('read without the plugin')\n")
    env = dict(os.environ, HDF5_PLUGIN_PATH=str(empty))
    run = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "filter" in run.stdout.lower() and ("not available" in run.stdout or "not registered" in run.stdout)


def test_corrupt_chunks_raise_errors(tmp_path):
    data = st_helens()
    path = tmp_path / "good.h5"
    write(path, data, (64, 64), LOSSLESS)
    with h5py.File(path, "r") as f:
        info = f["d"].id.get_chunk_info(0)
    good = path.read_bytes()
    stream = good[info.byte_offset:info.byte_offset + info.size]
    assert stream[:4] != b"\0\0\0\0"
    rng = np.random.default_rng(24)
    bad_path = tmp_path / "bad.h5"
    # Bytes flipped on disk, at the header and in the coded bands.
    for at in [1, 20, 40, info.size // 2, info.size - 3]:
        bad = bytearray(good)
        bad[info.byte_offset + at] ^= 0x5A
        bad_path.write_bytes(bytes(bad))
        with h5py.File(bad_path, "r") as f:
            assert np.array_equal(f["d"][64:, :], data[64:, :])  # other chunks still read
            with pytest.raises(OSError):
                f["d"][:64, :64]
    # Chunks written past the filter: noise, a prefix (a valid progressive
    # prefix is not a whole chunk), a stream of another chunk's shape, nothing.
    other = tmp_path / "other.h5"
    write(other, data[:32, :64], (32, 64), LOSSLESS)
    with h5py.File(other, "r") as f:
        info32 = f["d"].id.get_chunk_info(0)
    other_stream = other.read_bytes()[info32.byte_offset:info32.byte_offset + info32.size]
    payloads = [rng.integers(0, 256, 3000, dtype=np.uint8).tobytes(), stream[:len(stream) // 2],
                stream[:len(stream) - 12], other_stream, stream[:8], b"\x00"]
    for payload in payloads:
        with h5py.File(bad_path, "w") as f:
            d = f.create_dataset("d", shape=data.shape, dtype=data.dtype, chunks=(64, 64),
                                 compression=FILTER_ID, compression_opts=opts(LOSSLESS))
            d.id.write_direct_chunk((0, 0), payload)
        with h5py.File(bad_path, "r") as f:
            with pytest.raises(OSError):
                f["d"][:64, :64]


def test_copied_creation_properties_keep_the_mode(tmp_path):
    data = st_helens()
    path = tmp_path / "like.h5"
    with h5py.File(path, "w") as f:
        src = f.create_dataset("a", data=data, chunks=(64, 64), compression=FILTER_ID,
                               compression_opts=opts(MAX_ERROR, 2))
        # The stored cd_values (not the user's form) go through set_local again.
        dcpl = src.id.get_create_plist()
        h5py.h5d.create(f.id, b"b", src.id.get_type(), h5py.h5s.create_simple(data.shape), dcpl=dcpl)
        f["b"][...] = data
        cd_a = src.id.get_create_plist().get_filter_by_id(FILTER_ID)[1]
        cd_b = f["b"].id.get_create_plist().get_filter_by_id(FILTER_ID)[1]
        assert cd_a == cd_b
        assert np.abs(f["b"][...].astype(np.int64) - data).max() <= 2


def test_a_chunk_the_filter_cannot_code(tmp_path):
    # A rate below the coarsest approximation of noise: as an optional filter
    # (h5py's choice) HDF5 stores the chunk as is and flags it; as a mandatory
    # one the write fails with the encoder's reason. Without a chunk cache the
    # filter runs in H5Dwrite: a filter failing in the flush at close makes
    # HDF5 crash later in H5D_close (HDF5 issue 6601, not the plugin's).
    noise = np.random.default_rng(24).integers(0, 256, (64, 64)).astype("u1")
    path = tmp_path / "noise.h5"
    write(path, noise, (64, 64), RATE, 0.01)
    with h5py.File(path, "r") as f:
        assert f["d"].id.get_chunk_info(0).filter_mask == 1
        assert np.array_equal(f["d"][...], noise)
    with pytest.raises(Exception, match="the rate is too low"):
        with h5py.File(path, "w") as f:
            dcpl = h5py.h5p.create(h5py.h5p.DATASET_CREATE)
            dcpl.set_chunk(noise.shape)
            dcpl.set_filter(FILTER_ID, h5py.h5z.FLAG_MANDATORY, opts(RATE, 0.01))
            dapl = h5py.h5p.create(h5py.h5p.DATASET_ACCESS)
            dapl.set_chunk_cache(0, 0, 1.0)
            d = h5py.h5d.create(f.id, b"d", h5py.h5t.STD_U8LE, h5py.h5s.create_simple(noise.shape), dcpl=dcpl,
                                dapl=dapl)
            d.write(h5py.h5s.ALL, h5py.h5s.ALL, noise)


def test_nan_samples_with_a_nan_fill_value(tmp_path):
    terrain = st_helens().astype("<f4")
    terrain[::7, ::5] = np.nan
    path = tmp_path / "nan.h5"
    write(path, terrain, (64, 64), PSNR, 60, fillvalue=np.nan)
    back = read(path)
    voids = np.isnan(terrain)
    assert np.array_equal(np.isnan(back), voids)
    assert psnr(terrain[~voids], back[~voids]) >= 60
