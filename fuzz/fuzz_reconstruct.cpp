// Fuzz target: the mesh reconstructors (spec 8, 9) on whatever grid a stream
// decodes to: Delaunay insertion in stages and the quadtree, on grids of at
// most 64 x 64 samples (larger ones are skipped, so every input stays fast).
// Checks what must hold for any samples: the triangles tile the grid's
// rectangle (counter-clockwise, areas summing to it), also after the border
// cleanup (8.8) and the quadtree's removal pass (9.7).
#include <cstdint>
#include <cstdlib>

#include "fuzz_params.h"
#include "mrsv/grid_mesh.h"
#include "mrsv/quadtree_mesh.h"
#include "mrsv/terrain_insertion.h"

namespace {

void checkTiling(const mrsv::GridMesh& m) {
  int64_t area = 0;
  for (const auto& c : m.cells) {
    const auto &a = m.points[c[0]], &b = m.points[c[1]], &d = m.points[c[2]];
    const int64_t twice = (int64_t(b[0]) - a[0]) * (int64_t(d[1]) - a[1]) - (int64_t(b[1]) - a[1]) * (int64_t(d[0]) - a[0]);
    if (twice <= 0) std::abort();
    area += twice;
  }
  if (area != 2 * (int64_t(m.size[0]) - 1) * (int64_t(m.size[1]) - 1)) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mrsv::DecodeOptions options;
  options.container = mrsv::fuzz::containerOptionsFromTail(data, size);
  options.max_output_bytes = 1u << 20;
  options.void_values = true;
  mrsv::DecodedGrid grid;
  if (!mrsv::decodeGrid(data, size, options, &grid).ok()) return 0;
  mrsv::SampleField field;
  std::string error;
  if (!mrsv::sampleFieldFromGrid(grid, &field, &error) || field.size[2] != 1) return 0;
  if (field.size[0] < 2 || field.size[1] < 2 || field.size[0] > 64 || field.size[1] > 64) return 0;
  const uint8_t tail = size ? data[size - 1] : 0;

  mrsv::InsertionLimits limits;
  limits.max_error.num = tail >> 4;  // 0 to 15 sample units
  limits.max_cells = (tail & 4) ? 200 : 0;
  limits.border_rule = (tail & 8) != 0;
  mrsv::TerrainInserter inserter(field.size[0], field.size[1]);
  for (const mrsv::ReconstructionStage& stage : mrsv::reconstructionStages(grid, size)) {
    if (!inserter.refine(field, stage.shift, limits, &error)) std::abort();
  }
  mrsv::GridMesh mesh;
  inserter.mesh(&mesh);
  checkTiling(mesh);
  if (mrsv::borderCleanupApplies(limits, false)) {  // spec 8.8's border cleanup (on the stages' mesh)
    const size_t points = mesh.points.size(), cells = mesh.cells.size();
    uint64_t removed = 0;
    if (!mrsv::cleanBorderZone(field, limits.max_error, &mesh, &removed, &error)) std::abort();
    if (mesh.points.size() + removed != points || mesh.cells.size() + 2 * removed != cells) std::abort();
    checkTiling(mesh);
  }

  mrsv::QuadtreeOptions qt;
  qt.threshold = limits.max_error;
  qt.tile_borders = limits.border_rule && field.size[0] >= 4 && field.size[1] >= 4;
  for (bool remove : {false, true}) {  // the tree's mesh, then after the removal pass (spec 9.7)
    qt.remove_vertices = remove;
    if (mrsv::quadtreeMesh(field, nullptr, qt, &mesh, &error)) checkTiling(mesh);
  }
  return 0;
}
