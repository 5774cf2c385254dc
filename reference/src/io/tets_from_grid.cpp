// A uniform grid of samples as a conforming tet mesh: 6 tets per cube.
//
// Every cube is cut along its diagonal from corner (0,0,0) to corner (1,1,1)
// into the six tets that walk from one to the other along the three axes in
// each order (the Kuhn / Freudenthal triangulation). Each cube face is then
// cut along its diagonal through the face's lowest corner, the same from both
// cubes sharing it, so the tets meet face to face.
#include <cmath>
#include <cstring>

#include "mrsv/raw_grid.h"
#include "mrsv/tet_formats.h"
#include "io/tet_build.h"

namespace mrsv {
namespace {

// The six tets as corner numbers (bit 0: +x, bit 1: +y, bit 2: +z), each
// ordered positively for a cube with positive spacings.
struct CubeTemplate {
  std::array<std::array<int, 4>, 6> tets;
  CubeTemplate() {
    static const int kOrders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                      {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int t = 0; t < 6; ++t) {
      int a = 1 << kOrders[t][0], b = a | (1 << kOrders[t][1]);
      tets[t] = {0, a, b, 7};
    }
    tet_build::orientTemplate(tets.data(), 6);
  }
};

}  // namespace

bool tetrahedralizeGrid(const GridHeader& header, const std::vector<uint8_t>& samples,
                        const double spacing[3], const GridCrop& crop, TetMesh* mesh,
                        TetBuildReport* report, std::string* error) {
  *mesh = TetMesh{};
  *report = TetBuildReport{};
  if (header.num_dims != 3) {
    *error = "a " + std::to_string(header.num_dims) + "-D grid has no cubes to cut into tets (3-D only)";
    return false;
  }
  const uint32_t full[3] = {header.size_x, header.size_y, header.size_z};
  const size_t sample_size = sampleSize(header.sample_type);
  if (samples.size() != header.sampleCount() * sample_size) {
    *error = std::to_string(samples.size()) + " bytes of samples for a " + std::to_string(full[0]) + "x" +
             std::to_string(full[1]) + "x" + std::to_string(full[2]) + " grid of " +
             sampleTypeName(header.sample_type);
    return false;
  }
  uint32_t size[3];
  static const char kAxis[3] = {'x', 'y', 'z'};
  for (int a = 0; a < 3; ++a) {
    if (!(std::isfinite(spacing[a]) && spacing[a] != 0.0)) {
      *error = std::string("spacing along ") + kAxis[a] + " is zero or not finite";
      return false;
    }
    if (crop.origin[a] >= full[a]) {
      *error = std::string("crop origin ") + kAxis[a] + " = " + std::to_string(crop.origin[a]) +
               " is outside the grid (" + std::to_string(full[a]) + " samples)";
      return false;
    }
    size[a] = crop.size[a] ? crop.size[a] : full[a] - crop.origin[a];
    if (size[a] > full[a] - crop.origin[a]) {
      *error = std::string("crop along ") + kAxis[a] + " (" + std::to_string(crop.origin[a]) + " + " +
               std::to_string(size[a]) + ") runs past the grid's " + std::to_string(full[a]) + " samples";
      return false;
    }
    if (size[a] < 2) {
      *error = std::string("the grid (or crop) has ") + std::to_string(size[a]) + " sample along " +
               kAxis[a] + "; cubes need 2";
      return false;
    }
  }
  const uint64_t vertices = uint64_t{size[0]} * size[1] * size[2];
  if (vertices > UINT32_MAX) {
    *error = "the crop has more than 2^32-1 samples; crop it smaller";
    return false;
  }
  static const CubeTemplate kCube;
  tet_build::Builder builder(vertices, 1);
  builder.fields[0].name = "value";
  std::vector<bool> nodata;
  if (header.hasNodata()) nodata.assign(vertices, false);
  for (uint32_t z = 0; z < size[2]; ++z)
    for (uint32_t y = 0; y < size[1]; ++y)
      for (uint32_t x = 0; x < size[0]; ++x) {
        const uint64_t v = x + uint64_t{size[0]} * (y + uint64_t{size[1]} * z);
        const uint64_t s = (crop.origin[0] + x) +
                           uint64_t{full[0]} * ((crop.origin[1] + y) + uint64_t{full[1]} * (crop.origin[2] + z));
        const uint8_t* p = samples.data() + s * sample_size;
        builder.positions[v] = {(crop.origin[0] + x) * spacing[0], (crop.origin[1] + y) * spacing[1],
                                (crop.origin[2] + z) * spacing[2]};
        builder.fields[0].values[v] = sampleValue(p, header.sample_type);
        if (header.hasNodata()) {
          uint64_t bits = 0;
          for (size_t i = 0; i < sample_size; ++i) bits |= uint64_t{p[i]} << (8 * i);
          nodata[v] = bits == header.nodata_bits;
        }
      }
  builder.reserveTets(6 * uint64_t{size[0] - 1} * (size[1] - 1) * (size[2] - 1));
  for (uint32_t z = 0; z + 1 < size[2]; ++z)
    for (uint32_t y = 0; y + 1 < size[1]; ++y)
      for (uint32_t x = 0; x + 1 < size[0]; ++x) {
        uint32_t corner[8];
        bool blank = false;
        for (int c = 0; c < 8; ++c) {
          corner[c] = static_cast<uint32_t>((x + (c & 1)) +
                                            uint64_t{size[0]} * ((y + ((c >> 1) & 1)) + uint64_t{size[1]} * (z + (c >> 2))));
          if (!nodata.empty() && nodata[corner[c]]) blank = true;
        }
        ++report->cells;
        if (blank) {
          ++report->cells_left_out;
          continue;
        }
        for (const auto& t : kCube.tets)
          if (!builder.addTet({corner[t[0]], corner[t[1]], corner[t[2]], corner[t[3]]})) {
            *error = "cube at sample (" + std::to_string(crop.origin[0] + x) + ", " +
                     std::to_string(crop.origin[1] + y) + ", " + std::to_string(crop.origin[2] + z) +
                     ") gives a degenerate tet";
            return false;
          }
      }
  report->flipped = builder.flipped;
  builder.finish(mesh);
  return true;
}

}  // namespace mrsv
