"""Bad arguments raise TypeError or ValueError with a message naming the fix."""
import numpy as np
import pytest

import mrsv


def test_sample_types(tmp_path, st_helens):
    with pytest.raises(TypeError, match="int64 is not a sample type.*int32"):
        mrsv.encode(st_helens.astype(np.int64), tmp_path / "x.mrsv")
    with pytest.raises(TypeError, match="int8"):
        mrsv.encode(np.zeros(4, np.int8), tmp_path / "x.mrsv")


def test_dimensions(tmp_path):
    with pytest.raises(ValueError, match="1 to 3 dimensions"):
        mrsv.encode(np.zeros((2, 2, 2, 2), np.uint8), tmp_path / "x.mrsv")
    with pytest.raises(ValueError, match="1 to 3 dimensions"):
        mrsv.encode(np.uint8(3), tmp_path / "x.mrsv")


def test_rate_options(tmp_path, st_helens):
    path = tmp_path / "x.mrsv"
    with pytest.raises(ValueError, match="at most one"):
        mrsv.encode(st_helens, path, psnr=40, max_error=3)
    with pytest.raises(ValueError, match="max_error= must be a number from 0"):
        mrsv.encode(st_helens, path, max_error=-1)
    with pytest.raises(ValueError, match="levels="):
        mrsv.encode(st_helens, path, levels=17)
    with pytest.raises(ValueError, match="roi="):
        mrsv.encode(st_helens, path, roi=("box", (0, 0), (10, 10)))
    with pytest.raises(ValueError, match="order= is for"):
        mrsv.encode(st_helens, path, wavelet="cdf97", order=2)
    with pytest.raises(TypeError):
        mrsv.encode(st_helens, path, quality=3)  # no such keyword
    assert not path.exists()  # nothing written by a refused call


def test_float_samples_need_a_rate_or_quality(tmp_path, st_helens):
    with pytest.raises(ValueError, match="integer samples"):
        mrsv.encode(st_helens.astype(np.float32), tmp_path / "x.mrsv")


def test_stored_lossless(tmp_path, st_helens):
    mrsv.encode(st_helens, tmp_path / "s.mrsv", coding="stored", lossless=True)
    with pytest.raises(ValueError, match="stored"):
        mrsv.encode(st_helens, tmp_path / "s.mrsv", coding="stored", psnr=40)


def test_region_of_interest(tmp_path, st_helens):
    path = tmp_path / "roi.mrsv"
    mrsv.encode(st_helens, path, bits_per_sample=0.3, roi=("ellipsoid", (64, 64), (16, 16)))
    samples, _ = mrsv.decode(path)
    error = np.abs(samples.astype(int) - st_helens)
    assert error[56:72, 56:72].mean() < error.mean()


def test_nodata(tmp_path, st_helens):
    with pytest.raises(ValueError, match="out of range for int16"):
        mrsv.encode(st_helens, tmp_path / "x.mrsv", nodata=40000)
    with pytest.raises(ValueError, match="whole number"):
        mrsv.encode(st_helens, tmp_path / "x.mrsv", nodata=1.5)


def test_metadata(tmp_path, st_helens):
    with pytest.raises(TypeError, match="dict of str"):
        mrsv.encode(st_helens, tmp_path / "x.mrsv", metadata={"a": 1})
    with pytest.raises(ValueError, match="spacing= must give 2 numbers"):
        mrsv.encode(st_helens, tmp_path / "x.mrsv", spacing=(1, 1, 1))


def test_decode_arguments(tmp_path, st_helens):
    path = tmp_path / "x.mrsv"
    mrsv.encode(st_helens, path)
    with pytest.raises(ValueError, match="levels="):
        mrsv.decode(path, levels=-1)
    with pytest.raises(ValueError, match="negative"):
        mrsv.decode(path, bytes=-5)
    with pytest.raises(TypeError):
        mrsv.decode(12345)
    with pytest.raises(FileNotFoundError):
        mrsv.decode(tmp_path / "absent.mrsv")
    with pytest.raises(ValueError, match="before its sample data"):
        mrsv.decode(path, bytes=12)
