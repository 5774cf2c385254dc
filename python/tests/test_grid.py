"""mrsv.encode / mrsv.decode on real terrain and CT crops."""
import numpy as np
import pytest

import mrsv


def roundtrip(array, tmp_path, **options):
    path = tmp_path / "grid.mrsv"
    report = mrsv.encode(array, path, **options)
    samples, info = mrsv.decode(path)
    assert report["bytes"] == path.stat().st_size == info["bytes"] == info["bytes_used"]
    assert samples.shape == array.shape and samples.dtype == array.dtype.newbyteorder("<")
    return samples, info, report


@pytest.mark.parametrize("crop", ["st_helens", "ct_head", "ct_headsq"])
def test_lossless_by_default(crop, request, tmp_path):
    array = request.getfixturevalue(crop)
    samples, info, report = roundtrip(array, tmp_path)
    assert np.array_equal(samples, array)
    assert report["max_abs_error"] == 0 and info["error_bound"] == 0
    assert info["complete"] and info["coding"] == "wavelet"


def test_voids_kept_with_nodata(fuji, tmp_path):
    assert (fuji == -32768).sum() == 50
    samples, info, _ = roundtrip(fuji, tmp_path, nodata=-32768)
    assert np.array_equal(samples, fuji)
    assert info["nodata"] == -32768


@pytest.mark.parametrize("crop", ["st_helens", "ct_head"])
@pytest.mark.parametrize("bound", [1, 4, 10])
def test_max_error_on_every_sample(crop, bound, request, tmp_path):
    array = request.getfixturevalue(crop)
    samples, info, report = roundtrip(array, tmp_path, max_error=bound)
    error = np.abs(samples.astype(np.int64) - array.astype(np.int64)).max()
    assert error <= bound
    assert report["max_abs_error"] == error and info["error_bound"] == bound


def test_bits_per_sample_and_psnr_targets(st_helens, tmp_path):
    _, _, report = roundtrip(st_helens, tmp_path, bits_per_sample=0.5)
    assert report["bits_per_sample"] <= 0.5
    samples, _, report = roundtrip(st_helens, tmp_path, psnr=50)
    assert report["psnr"] >= 50


def test_float_samples(st_helens, tmp_path):
    heights = st_helens.astype(np.float32) / 3
    samples, info, report = roundtrip(heights, tmp_path, psnr=70)
    peak = heights.max() - heights.min()
    rmse = np.sqrt(np.mean((samples.astype(np.float64) - heights) ** 2))
    assert 20 * np.log10(peak / rmse) >= 70 - 1e-9
    assert info["sample_type"] == "float32"


def test_stored_coding_of_a_1d_float64_profile(st_helens, tmp_path):
    profile = st_helens[64].astype(np.float64) + 0.25
    samples, info, _ = roundtrip(profile, tmp_path, coding="stored")
    assert np.array_equal(samples, profile) and info["coding"] == "stored"


def test_non_contiguous_and_big_endian_input(ct_headsq, tmp_path):
    view = ct_headsq[:, ::2, :]  # a strided view
    samples, _, _ = roundtrip(view, tmp_path)
    assert np.array_equal(samples, view)
    big = ct_headsq.astype(">u2")
    samples, _, _ = roundtrip(big, tmp_path)
    assert np.array_equal(samples, ct_headsq) and samples.dtype == np.dtype("<u2")


def test_reduced_resolution_levels(st_helens, ct_head, tmp_path):
    path = tmp_path / "p.mrsv"
    mrsv.encode(st_helens, path, progressive=True, max_error=2)
    full, info = mrsv.decode(path)
    assert info["decomposition_levels"][0] >= 2
    for k in (1, 2):
        samples, info = mrsv.decode(path, levels=k)
        assert samples.shape == (128 >> k, 128 >> k) and info["levels"] == k
        # A coarser view of the same terrain: its range stays within the input's.
        assert st_helens.min() - 50 <= samples.min() and samples.max() <= st_helens.max() + 50
    mrsv.encode(ct_head, path, progressive=True, psnr=40)
    samples, _ = mrsv.decode(path, levels=1)
    assert samples.shape == (16, 32, 32)


def test_byte_prefixes(st_helens, tmp_path):
    path = tmp_path / "p.mrsv"
    mrsv.encode(st_helens, path, progressive=True, max_error=1)
    size = path.stat().st_size
    full, info = mrsv.decode(path)
    previous_bands = 0
    errors = []
    for fraction in (0.2, 0.4, 0.7, 1.0):
        samples, info = mrsv.decode(path, bytes=int(size * fraction))
        assert samples.shape == st_helens.shape
        assert info["bytes_used"] <= info["bytes"] <= size
        assert info["bands_decoded"] >= previous_bands
        previous_bands = info["bands_decoded"]
        errors.append(np.abs(samples.astype(int) - st_helens).max())
    assert info["complete"] and np.array_equal(samples, full)
    assert errors[-1] <= 1 and errors[0] > errors[-1]
    partial, info = mrsv.decode(path, bytes=size // 2)
    assert not info["complete"]
    assert info["bands_decoded"] < info["bands_total"] or not info["residual_decoded"]
    # The same prefix from the stream's bytes; without bytes= a stream cut in
    # a chunk is a broken rule, not a prefix (as 'mrsv decode' without --bytes).
    same, _ = mrsv.decode(path.read_bytes(), bytes=size // 2)
    assert np.array_equal(same, partial)
    with pytest.raises(mrsv.Error) as caught:
        mrsv.decode(path.read_bytes()[: size // 2])
    assert caught.value.name == "chunk_past_end"


def test_metadata_round_trip(ct_head, tmp_path):
    path = tmp_path / "m.mrsv"
    entries = {"description": "Stanford CT head crop", "value_units": "CT number", "spatial_units": "mm"}
    mrsv.encode(ct_head, path, spacing=(1, 1, 2), origin=(96, 96, 80.5), metadata=entries)
    _, info = mrsv.decode(path)
    assert info["spacing"] == (1.0, 1.0, 2.0) and info["origin"] == (96.0, 96.0, 80.5)
    for key, value in entries.items():
        assert info["metadata"][key] == value
    assert info["metadata"]["spacing"] == "1,1,2"
    # At reduced resolution spacing and origin describe the array returned (an
    # output step spans 2^K samples on each axis with K levels), as the GeoTIFF
    # of `mrsv decode --levels K` does; metadata keeps the stream's entries.
    coarse, info = mrsv.decode(path, levels=1)
    k = [min(1, n) for n in info["decomposition_levels"]]
    assert info["spacing"] == tuple(s * 2 ** a for s, a in zip((1.0, 1.0, 2.0), k))
    assert info["origin"] == (96.0, 96.0, 80.5)
    assert coarse.shape == tuple((n + 2 ** a - 1) // 2 ** a for n, a in zip(ct_head.shape, reversed(k)))
    assert info["metadata"]["spacing"] == "1,1,2"


def test_concurrent_decodes_release_the_gil(ct_head, tmp_path):
    import concurrent.futures

    path = tmp_path / "c.mrsv"
    mrsv.encode(ct_head, path)
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        results = list(pool.map(lambda _: mrsv.decode(path)[0], range(4)))
    assert all(np.array_equal(r, ct_head) for r in results)
