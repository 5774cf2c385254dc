// The faces of a tet mesh as the boundary extraction and the manifold check
// both need them: every (tet, face) use, sorted so that the uses of one face
// are adjacent.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mrsv/tet_mesh.h"

namespace mrsv {

// Corners of face f of a tet (the face opposite corner f), in the order that
// makes the face's right-hand normal point out of a positively oriented tet.
constexpr uint8_t kOutwardFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

struct TetFaceUse {
  std::array<uint32_t, 3> key;  // the face's vertices, ascending
  uint32_t tet;
  uint8_t face;  // 0..3, the corner opposite the face
  bool odd;      // the outward order is an odd permutation of `key`
};

// The outward triangle (vertex indices) of face `face` of `tet`.
inline std::array<uint32_t, 3> outwardFace(const std::array<uint32_t, 4>& tet, int face) {
  return {tet[kOutwardFace[face][0]], tet[kOutwardFace[face][1]], tet[kOutwardFace[face][2]]};
}

// All 4 T face uses, sorted by key, then tet, then face. Two uses of one key
// orient the face oppositely (as two tets sharing it must) when their `odd`
// differ.
std::vector<TetFaceUse> sortedTetFaces(const TetMesh& mesh);

}  // namespace mrsv
