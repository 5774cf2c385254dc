// mrsv.mesh_grid: adaptive meshes of a grid stream (spec 8 Delaunay insertion,
// spec 9 quadtree), as 'mrsv mesh' makes them, returned as arrays.
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include <pybind11/stl.h>

#include "common.h"
#include "region.h"
#include "mrsv/grid_mesh.h"
#include "mrsv/quadtree_mesh.h"
#include "mrsv/terrain_insertion.h"
#include "mrsv/volume_insertion.h"

namespace mrsv::python {
namespace {

// The exact bound of spec 8.3 from a Python number, through its shortest decimal.
ErrorBound errorBoundOf(double value) {
  ErrorBound bound;
  char text[64];
  std::snprintf(text, sizeof text, "%.9f", value);
  if (!std::isfinite(value) || !parseErrorBound(text, &bound))
    throw py::value_error("max_error= must be a number from 0 to 2147483648 with at most 9 decimals");
  return bound;
}

py::tuple meshGrid(const py::object& source_object, const std::string& method,
                   const std::optional<double>& max_error, const std::optional<uint64_t>& triangles,
                   const std::optional<uint64_t>& tets, int levels, const py::object& byte_limit,
                   bool border_rule, const std::string& distance, double z_scale, bool remove_vertices,
                   const py::object& region_object, bool border_cleanup) {
  if (method != "insertion" && method != "quadtree") throw py::value_error("method= must be 'insertion' or 'quadtree'");
  if (triangles && tets) throw py::value_error("give triangles= or tets=, not both");
  if ((triangles && *triangles == 0) || (tets && *tets == 0))
    throw py::value_error("triangles= and tets= must be positive");
  if (!max_error && !triangles && !tets) throw py::value_error("give max_error=, triangles= or tets=");
  if (levels < 0 || levels > 16) throw py::value_error("levels= must be a whole number from 0 to 16");
  if (distance != "mesh" && distance != "trilinear") throw py::value_error("distance= must be 'mesh' or 'trilinear'");
  if (remove_vertices && method == "insertion" && !max_error)
    throw py::value_error("remove_vertices=True with method='insertion' needs max_error= (spec 8.8)");
  // spec 8.1 R8.1-3: a region is meshed once from its samples, as 'mrsv mesh --region'.
  const bool by_region = !region_object.is_none();
  RegionArgument region;
  if (by_region) {
    region = parseGridRegion(region_object);
    if (levels != 0)
      throw py::value_error("region= meshes the region's samples once: not with levels= (spec 8.1)");
  }
  InsertionLimits limits;
  if (max_error) limits.max_error = errorBoundOf(*max_error);
  limits.max_cells = triangles ? *triangles : tets ? *tets : 0;
  limits.border_rule = border_rule;

  DecodeOptions options;
  options.void_values = true;  // no-data samples take their synthesised value (spec 8.1)
  Source source;
  DecodedGrid grid;
  Error e;
  if (by_region) {
    // The field is the region decode's (spec 11.5), a grid of the box's sizes.
    grid = std::move(decodeRegion(source_object, byte_limit, region, options).grid);
    grid.header.size_x = grid.output_size[0];
    grid.header.size_y = grid.output_size[1];
    grid.header.size_z = grid.output_size[2];
  } else {
    source = loadSource(source_object);
    options.container.allow_partial_tail = applyByteLimit(byte_limit, &source);
    {
      py::gil_scoped_release release;
      e = decodeGrid(source.data, source.size, options, &grid);
    }
    if (!e.ok()) raiseStreamError(e);
  }
  if (!grid.has_samples) throw py::value_error("the stream holds no samples yet (no band in the bytes read)");
  const int dims = grid.header.num_dims;
  if (dims == 1) throw py::value_error("mesh_grid meshes 2-D and 3-D grids");
  if (dims == 3 && method == "quadtree") throw py::value_error("the quadtree meshes 2-D grids; use method='insertion'");
  if (dims == 2 && tets) throw py::value_error("a 2-D grid gives triangles: use triangles=");
  if (dims == 3 && triangles) throw py::value_error("a 3-D grid gives tets: use tets=");
  if (dims == 3 && remove_vertices) throw py::value_error("remove_vertices=True is for 2-D grids");
  if (distance == "trilinear" && (dims == 2 || !max_error))
    throw py::value_error("distance='trilinear' is for 3-D grids with max_error=");
  // The finest stage the bytes and levels= allow (spec 8.7); not refined stage by stage.
  // A region: one stage on the samples already decoded.
  std::vector<ReconstructionStage> stages =
      by_region ? std::vector<ReconstructionStage>{{source.size, 0}}
                : reconstructionStages(grid, source.size, static_cast<unsigned>(levels));
  if (stages.empty() && grid.header.coding == GridCoding::kTiled)
    throw py::value_error("levels= is not defined for tiled grids in this version (spec 8.7 stages are the levels "
                          "of one wavelet pyramid); mesh the whole grid, or decode with levels= first");
  if (stages.empty()) throw py::value_error("levels= leaves no complete level in the bytes read");
  const ReconstructionStage stage = stages.back();

  GridMesh mesh;
  std::string error;
  bool ok = true;
  {
    py::gil_scoped_release release;
    DecodedGrid prefix;
    const DecodedGrid* decoded = &grid;
    if (stage.bytes != source.size) {
      e = decodeGrid(source.data, stage.bytes, options, &prefix);
      decoded = &prefix;
    }
    SampleField field;
    ok = e.ok() && sampleFieldFromGrid(*decoded, &field, &error);
    if (ok && method == "quadtree") {
      QuadtreeOptions qt;
      qt.threshold = limits.max_error;
      qt.max_triangles = limits.max_cells;
      qt.tile_borders = limits.max_error.set() && border_rule && field.size[0] >= 4 && field.size[1] >= 4;
      qt.remove_vertices = remove_vertices;
      ok = quadtreeMesh(field, nullptr, qt, &mesh, &error);
    } else if (ok && dims == 2) {
      TerrainInserter inserter(grid.header.size_x, grid.header.size_y);
      ok = inserter.refine(field, stage.shift, limits, &error);
      if (ok) inserter.mesh(&mesh);
      if (ok && remove_vertices) ok = removeInnerVertices(field, limits.max_error, &mesh, nullptr, &error);
      else if (ok && border_cleanup && borderCleanupApplies(limits, false))  // one stage: not progressive
        ok = cleanBorderZone(field, limits.max_error, &mesh, nullptr, &error);
    } else if (ok) {
      VolumeInserter inserter(grid.header.size_x, grid.header.size_y, grid.header.size_z);
      inserter.setDistance(distance == "trilinear" ? VolumeDistance::kTrilinear : VolumeDistance::kMesh);
      ok = inserter.refine(field, stage.shift, limits, &error);
      if (ok) inserter.mesh(&mesh);
    }
  }
  if (!e.ok()) raiseStreamError(e);
  if (!ok) throw py::value_error(error);
  GridMeshGeometry geometry;
  geometry.z_scale = z_scale;
  if (!gridMeshGeometryFromMetadata(grid.metadata, dims, &geometry, &error)) throw py::value_error(error);
  if (by_region)  // positions in the whole grid's frame, so that adjacent boxes meet
    for (int a = 0; a < 3; ++a) geometry.origin[a] += double(region.box.lo[a]) * geometry.spacing[a];
  if (dims == 2) {
    TriangleMesh t = gridMeshToTriangles(mesh, geometry);
    return py::make_tuple(rowsToArray<double>(t.positions), rowsToArray<int32_t>(t.triangles),
                          vectorToArray<double>(t.scalars));
  }
  TetMesh t = gridMeshToTets(mesh, geometry);
  return py::make_tuple(rowsToArray<double>(t.positions), rowsToArray<int32_t>(t.tets),
                        vectorToArray<double>(t.fields.at(0).values));
}

}  // namespace

void registerReconstruct(py::module_& m) {
  m.def("mesh_grid", &meshGrid, py::arg("source"), py::kw_only(), py::arg("method") = "insertion",
        py::arg("max_error") = py::none(), py::arg("triangles") = py::none(), py::arg("tets") = py::none(),
        py::arg("levels") = 0, py::arg("bytes") = py::none(), py::arg("border_rule") = true,
        py::arg("distance") = "mesh", py::arg("z_scale") = 1.0, py::arg("remove_vertices") = false,
        py::arg("region") = py::none(), py::arg("border_cleanup") = true,
        R"doc(An adaptive mesh of a grid stream of integer samples (as 'mrsv mesh').

method: 'insertion' (Delaunay insertion, spec 8; 2-D and 3-D) or 'quadtree'
(spec 9; 2-D). Stop at max_error (every sample within it), or at triangles=
(2-D) / tets= (3-D) cells. levels and bytes choose the stage as in decode;
border_rule (spec 8.6), distance ('mesh'|'trilinear', 3-D), z_scale and
remove_vertices (2-D: the vertex-removal pass of spec 9.7 and 8.8) as the
CLI's; border_cleanup=False as --no-border-cleanup (spec 8.8: by default,
with border_rule and max_error, the inner vertices next to the sides are
tried once for removal). A tiled stream (encode(tile=...)) is meshed whole, without levels.
region: mesh only a box (as 'mrsv mesh --region', spec 8.1):
((x0, y0[, z0]), (x1, y1[, z1])), half-open, x, y, z order as in decode.
From a path a tiled stream reads only the tiles the box touches. The
vertices are in the whole grid's frame, so that two boxes sharing a side
have the same vertices on it (with border_rule, or the quadtree with
max_error) and meet without cracks. Not with levels.
Returns (vertices (N, 3) float64 in the meta chunk's spacing and origin
(2-D: z = sample * z_scale), cells (M, 3) or (M, 4) int32, values (N,)
float64 samples at the vertices).)doc");
}

}  // namespace mrsv::python
