"""Paths to the real data the tests read: the bundled crops (demo/data) and
../shared/data (MRSV_SHARED_DATA when ctest runs them); the CLI of the build
(MRSV_BUILD_DIR) for the tests that compare with it."""
import os
import pathlib

import numpy as np
import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("MRSV_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
SHARED_DATA = pathlib.Path(os.environ.get("MRSV_SHARED_DATA", SOURCE_DIR.parent / "shared" / "data"))
CROPS = SOURCE_DIR / "demo" / "data"
BUILD_DIR = pathlib.Path(os.environ.get("MRSV_BUILD_DIR", SOURCE_DIR / "build"))


def raw(name, dtype, shape):
    """A bundled crop as a numpy array in C order (z, y, x)."""
    return np.fromfile(CROPS / name, dtype=dtype).reshape(shape)


@pytest.fixture(scope="session")
def st_helens():
    return raw("mt_st_helens_128x128_int16le.raw", "<i2", (128, 128))


@pytest.fixture(scope="session")
def fuji():
    """128 x 128 SRTM-3 around Mt. Fuji's summit with 50 voids (-32768)."""
    return raw("mt_fuji_summit_128x128_int16le.raw", "<i2", (128, 128))


@pytest.fixture(scope="session")
def ct_head():
    """64 x 64 x 32 of the Stanford CT head, numpy shape (z, y, x)."""
    return raw("ct_head_64x64x32_uint8.raw", "u1", (32, 64, 64))


@pytest.fixture(scope="session")
def ct_headsq():
    return raw("ct_headsq_16x16x8_uint16le.raw", "<u2", (8, 16, 16))


def shared(relative):
    path = SHARED_DATA / relative
    if not path.exists():
        pytest.fail(f"{path} is missing: ../shared/data must be beside the project")
    return path


def cli():
    """The 'mrsv' command of the build the module comes from."""
    path = BUILD_DIR / "mrsv"
    if not path.exists():
        pytest.fail(f"{path} is missing: build the 'mrsv' target (MRSV_BUILD_DIR names the build)")
    return path
