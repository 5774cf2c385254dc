"""MRSV: multiresolution grids, progressive meshes and progressive tet meshes.

The reference C++ library bound with pybind11 (the _mrsv extension, built by
the project's CMake). Arrays follow numpy C order: a grid of shape (z, y, x)
has x varying fastest, the format's own sample order; values that list axes
(spacing, origin, regions of interest) keep the format's x, y, z order.

    samples, info = mrsv.decode("dem.mrsv", levels=1)
    mrsv.encode(samples, "copy.mrsv", max_error=2, spacing=(30, 30))
    mrsv.check("copy.mrsv")
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

__all__ = [
    "Error",
    "ProgressiveMesh",
    "ProgressiveTetMesh",
    "StreamDecoder",
    "check",
    "decode",
    "encode",
    "encode_mesh",
    "encode_tets",
    "mesh_grid",
    "read_mesh",
    "read_tets",
    "tetrahedralize",
]
