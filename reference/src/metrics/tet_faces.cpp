// Sorted face uses of a tet mesh (see tet_faces.h).
#include "metrics/tet_faces.h"

#include <algorithm>
#include <utility>

namespace mrsv {

std::vector<TetFaceUse> sortedTetFaces(const TetMesh& mesh) {
  std::vector<TetFaceUse> uses;
  uses.reserve(mesh.tets.size() * 4);
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    for (int f = 0; f < 4; ++f) {
      std::array<uint32_t, 3> k = outwardFace(mesh.tets[t], f);
      // Sorting three values with swaps; each swap flips the parity.
      bool odd = false;
      if (k[1] < k[0]) std::swap(k[0], k[1]), odd = !odd;
      if (k[2] < k[1]) std::swap(k[1], k[2]), odd = !odd;
      if (k[1] < k[0]) std::swap(k[0], k[1]), odd = !odd;
      uses.push_back({k, static_cast<uint32_t>(t), static_cast<uint8_t>(f), odd});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const TetFaceUse& x, const TetFaceUse& y) {
    if (x.key != y.key) return x.key < y.key;
    return x.tet != y.tet ? x.tet < y.tet : x.face < y.face;
  });
  return uses;
}

}  // namespace mrsv
