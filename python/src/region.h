// Boxes of grids for mrsv.decode and mrsv.mesh_grid (spec 11.5, 8.1 R8.1-3):
// region= read in x, y, z order as the CLI's --region, and a region decode
// from a path (through the file, so that a tiled stream reads only the tiles
// the box touches) or from bytes.
#pragma once

#include <cstdint>

#include "common.h"
#include "mrsv/grid.h"
#include "mrsv/tiled_grid.h"

namespace mrsv::python {

struct RegionArgument {
  GridRegion box;
  int dims = 0;  // the number of axes region= gave
};

// region=((x0, y0[, z0]), (x1, y1[, z1])), half-open; raises TypeError or
// ValueError naming the rule.
RegionArgument parseGridRegion(const py::object& region);
// The box back as region= gives it.
py::tuple regionTuple(const RegionArgument& region);

// Raises ValueError when the stream's first bytes are a PM or PT stream's.
void refuseMeshStreams(const uint8_t* data, size_t size);

struct RegionDecode {
  DecodedGrid grid;
  uint64_t bytes_read = 0;   // what the decoder read from the source
  uint64_t bytes_total = 0;  // the source's size (after bytes=)
};

// decodeGridRegion() of `source` (a path, read through the file unless
// bytes= cuts it, or bytes-like). Raises ValueError for a box outside the
// grid or of other dimensions than the grid's, for levels the tiling does not
// allow and for mesh streams; mrsv.Error for a broken rule; OSError when the
// file cannot be opened. The result may lack samples (a prefix).
RegionDecode decodeRegion(const py::object& source, const py::object& byte_limit, const RegionArgument& region,
                          DecodeOptions options);

// DecodeOptions::threads from threads= (None: one per core, as the CLI).
int threadCount(const py::object& threads);

}  // namespace mrsv::python
