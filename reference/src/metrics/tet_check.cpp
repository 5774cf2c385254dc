// The input check every tet measurement starts from.
#include <cmath>
#include <limits>
#include <string>

#include "mrsv/tet_metrics.h"

namespace mrsv {

bool checkTetMesh(const TetMesh& mesh, std::string* error) {
  const size_t n = mesh.positions.size();
  if (n > std::numeric_limits<uint32_t>::max()) {
    *error = "more than 2^32 - 1 vertices";
    return false;
  }
  for (size_t v = 0; v < n; ++v)
    for (double x : mesh.positions[v])
      if (!std::isfinite(x)) {
        *error = "vertex " + std::to_string(v) + " has a coordinate that is not finite";
        return false;
      }
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& tet = mesh.tets[t];
    for (int i = 0; i < 4; ++i) {
      if (tet[i] >= n) {
        *error = "tet " + std::to_string(t) + " uses vertex " + std::to_string(tet[i]) + " of " +
                 std::to_string(n);
        return false;
      }
      for (int j = 0; j < i; ++j)
        if (tet[i] == tet[j]) {
          *error = "tet " + std::to_string(t) + " uses vertex " + std::to_string(tet[i]) + " twice";
          return false;
        }
    }
  }
  for (const ScalarField& f : mesh.fields) {
    if (f.values.size() != n) {
      *error = "field '" + f.name + "' has " + std::to_string(f.values.size()) + " values for " +
               std::to_string(n) + " vertices";
      return false;
    }
    for (size_t v = 0; v < n; ++v)
      if (!std::isfinite(f.values[v])) {
        *error = "field '" + f.name + "' is not finite at vertex " + std::to_string(v);
        return false;
      }
  }
  return true;
}

}  // namespace mrsv
