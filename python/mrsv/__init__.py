"""MRSV: multiresolution grids, progressive meshes and progressive tet meshes.

The reference C++ library bound with pybind11 (the _mrsv extension, built by
the project's CMake). Arrays follow numpy C order: a grid of shape (z, y, x)
has x varying fastest, the format's own sample order; values that list axes
(spacing, origin, regions of interest, tile sizes, region corners) keep the
format's x, y, z order.

    samples, info = mrsv.decode("dem.mrsv", levels=1)
    mrsv.encode(samples, "copy.mrsv", max_error=2, spacing=(30, 30))
    mrsv.check("copy.mrsv")
    mrsv.encode(samples, "tiled.mrsv", tile=256); mrsv.decode("tiled.mrsv", region=((0, 0), (512, 512)))
    h5file.create_dataset("dem", data=dem, chunks=(256, 256), **mrsv.hdf5_filter("max_error", 1))
    pm = mrsv.ProgressiveMesh("bunny.mrsv"); pm.level = 100; pm.vertices, pm.faces
    d = mrsv.StreamDecoder(); d.feed(piece); ...; d.finish(); d.samples()

Broken streams raise mrsv.Error (code, name, offset, field, rule); bad
arguments raise TypeError or ValueError; unreadable files raise OSError.
"""

from ._mrsv import (
    Error,
    ProgressiveMesh,
    ProgressiveTetMesh,
    StreamDecoder,
    check,
    decode,
    encode,
    encode_mesh,
    encode_tets,
    mesh_grid,
    read_mesh,
    read_tets,
    tetrahedralize,
)
from .hdf5 import HDF5_FILTER_ID, hdf5_filter

__all__ = [
    "Error",
    "HDF5_FILTER_ID",
    "ProgressiveMesh",
    "ProgressiveTetMesh",
    "StreamDecoder",
    "check",
    "decode",
    "encode",
    "encode_mesh",
    "encode_tets",
    "hdf5_filter",
    "mesh_grid",
    "read_mesh",
    "read_tets",
    "tetrahedralize",
]
