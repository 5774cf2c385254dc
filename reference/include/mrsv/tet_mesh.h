// Tetrahedral meshes as the library, the tools and the tests exchange them.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace mrsv {

// One per-vertex scalar field of a tet mesh (density, CT value, ...).
struct ScalarField {
  std::string name;
  std::vector<double> values;  // one per vertex
};

// An indexed tetrahedral mesh. A tet (a, b, c, d) is positively oriented when
// d lies on the side of the plane (a, b, c) that the right-hand rule over
// a -> b -> c points to: det[b - a, c - a, d - a] > 0. Indices are 0-based
// into `positions`. `fields` holds zero or more per-vertex scalar fields.
struct TetMesh {
  std::vector<std::array<double, 3>> positions;
  std::vector<std::array<uint32_t, 4>> tets;
  std::vector<ScalarField> fields;
};

}  // namespace mrsv
