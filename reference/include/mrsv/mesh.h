// Triangle meshes as the library, the tools and the tests exchange them.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace mrsv {

// An indexed triangle mesh. Triangles list their corners counter-clockwise as
// seen from outside (the right-hand rule gives the outward normal); indices
// are 0-based into `positions`. `scalars` is empty or holds one value per
// vertex (the optional per-vertex attribute of the PM stream, spec 6).
struct TriangleMesh {
  std::vector<std::array<double, 3>> positions;
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<double> scalars;
};

}  // namespace mrsv
