"""mrsv.hdf5_filter: the h5py arguments of the MRSV HDF5 filter (spec Annex C)."""
import os
import pathlib

import numpy as np
import pytest

import mrsv


def test_arguments():
    assert mrsv.hdf5_filter() == {"compression": 421, "compression_opts": (0,)}
    assert mrsv.hdf5_filter("max_error", 1) == {"compression": 421, "compression_opts": (3, 0, 1072693248)}
    assert mrsv.hdf5_filter("rate", 2.5)["compression_opts"][0] == 1
    assert mrsv.hdf5_filter("psnr", 50)["compression_opts"][0] == 2
    with pytest.raises(ValueError, match="not one of lossless, rate, psnr, max_error"):
        mrsv.hdf5_filter("zfp")
    with pytest.raises(ValueError, match="needs a value"):
        mrsv.hdf5_filter("psnr")
    with pytest.raises(ValueError, match="lossless takes no value"):
        mrsv.hdf5_filter("lossless", 3)


def test_round_trip_through_h5py(tmp_path, st_helens):
    h5py = pytest.importorskip("h5py")
    plugins = pathlib.Path(os.environ.get("MRSV_BUILD_DIR", "build")) / "hdf5plugins"
    if not (plugins / "libmrsv_h5filter.so").exists():
        pytest.skip("the HDF5 filter plugin is not built (MRSV_HDF5)")
    h5py.h5pl.prepend(str(plugins).encode())
    path = tmp_path / "dem.h5"
    with h5py.File(path, "w") as f:
        f.create_dataset("dem", data=st_helens, chunks=(64, 64), **mrsv.hdf5_filter("max_error", 2))
    with h5py.File(path, "r") as f:
        back = f["dem"][...]
    assert np.abs(back.astype(np.int64) - st_helens).max() <= 2
