// Terrain to mesh: a 2-D grid of heights as a triangulated surface, the input
// the PM encoder and `mrsv compare` use to treat a terrain as a mesh.
//
// Sample (i, j) (i the column, x fastest; j the row) becomes the vertex
// (i * spacing_x, j * spacing_y, value * z_scale). Each cell whose four
// corners all hold data becomes two triangles, split along the diagonal whose
// ends differ less in value; on a tie the diagonal from (i, j) to (i+1, j+1).
// Triangles face up: their normals have a positive z component whatever the
// signs of the spacings (for a north-up raster, whose row 0 is the northern
// edge, a negative spacing_y gives a map with y pointing north). A cell
// touching a no-data sample (the header's nodata value, or a NaN/Inf float
// sample) is left out, and so is every vertex no triangle uses. Vertices are
// numbered in sample order (row by row), triangles in cell order.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/grid.h"
#include "mrsv/mesh.h"

namespace mrsv {

struct TerrainMeshOptions {
  double spacing_x = 1.0;  // finite, not zero
  double spacing_y = 1.0;  // finite, not zero
  double z_scale = 1.0;    // finite
};

// `samples` as readGridInput() gives them: little-endian, x fastest, any
// sample type. The grid must be 2-D (size_z 1). On failure returns false with
// one line in `error`.
bool terrainToMesh(const GridHeader& header, const std::vector<uint8_t>& samples,
                   const TerrainMeshOptions& options, TriangleMesh* mesh, std::string* error);

}  // namespace mrsv
