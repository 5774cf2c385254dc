// Small tet meshes for the PT tests, made in the test so that the tests of
// the stream do not depend on the file readers.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "pt/pt_encode.h"

namespace mrsv::test {

// n x n x n vertices on the integer grid times `spacing`, 6 tets per cube
// around its main diagonal (the same diagonal everywhere, so faces conform),
// every tet positive; one field: a smooth function of the position.
inline QuantizedTets gridTets(int n, int spacing = 64, int position_bits = 12) {
  QuantizedTets q;
  q.header.position_bits = static_cast<uint8_t>(position_bits);
  PtField field;
  field.bits = 16;
  field.name = "f";
  q.header.fields.push_back(field);
  auto id = [n](int x, int y, int z) { return static_cast<uint32_t>((z * n + y) * n + x); };
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        q.positions.push_back({x * spacing, y * spacing, z * spacing});
        q.scalars.push_back(1000 + 37 * x + 11 * y * y + 5 * z + 3 * x * z);
      }
  static const int kPerms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int z = 0; z + 1 < n; ++z)
    for (int y = 0; y + 1 < n; ++y)
      for (int x = 0; x + 1 < n; ++x)
        for (const auto& perm : kPerms) {
          int c[3] = {x, y, z};
          Tet t;
          t[0] = id(c[0], c[1], c[2]);
          ++c[perm[0]];
          t[1] = id(c[0], c[1], c[2]);
          ++c[perm[1]];
          t[2] = id(c[0], c[1], c[2]);
          t[3] = id(x + 1, y + 1, z + 1);
          if (orient3d(q.positions[t[0]], q.positions[t[1]], q.positions[t[2]], q.positions[t[3]]) < 0)
            std::swap(t[1], t[2]);
          q.tets.push_back(t);
        }
  return q;
}

}  // namespace mrsv::test
