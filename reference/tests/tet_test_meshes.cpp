// Grid tet meshes and a minimal MEDIT reader (see tet_test_meshes.h).
#include "tet_test_meshes.h"

#include <fstream>
#include <map>
#include <utility>

namespace mrsv::test {

TetMesh gridTetMesh(int nx, int ny, int nz, const std::array<double, 3>& origin,
                    const std::array<double, 3>& spacing,
                    const std::function<double(int, int, int)>& value, const std::string& field) {
  TetMesh m;
  auto at = [&](int i, int j, int k) { return static_cast<uint32_t>((k * ny + j) * nx + i); };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        m.positions.push_back({origin[0] + i * spacing[0], origin[1] + j * spacing[1],
                               origin[2] + k * spacing[2]});
  if (value) {
    m.fields.push_back({field, {}});
    m.fields[0].values.reserve(m.positions.size());
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) m.fields[0].values.push_back(value(i, j, k));
  }
  // The six axis orders; a path adds one axis step at a time. Odd orders
  // give negatively oriented paths (with positive spacings), so their
  // middle corners are swapped.
  const int orders[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  bool flip = (spacing[0] < 0) != (spacing[1] < 0);
  flip = flip != (spacing[2] < 0);
  for (int k = 0; k + 1 < nz; ++k)
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i)
        for (int o = 0; o < 6; ++o) {
          int c[3] = {i, j, k};
          std::array<uint32_t, 4> t;
          t[0] = at(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[orders[o][s]];
            t[s + 1] = at(c[0], c[1], c[2]);
          }
          if ((o >= 3) != flip) std::swap(t[1], t[2]);
          m.tets.push_back(t);
        }
  return m;
}

bool readMeditTetMesh(const std::string& path, TetMesh* mesh, std::string* error) {
  *mesh = TetMesh{};
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open";
    return false;
  }
  // Numbers per entry of the sections skipped.
  const std::map<std::string, int> skip = {{"Edges", 3},      {"Triangles", 4}, {"Quadrilaterals", 5},
                                           {"Hexahedra", 9},  {"Corners", 1},   {"Ridges", 1},
                                           {"RequiredVertices", 1}, {"RequiredEdges", 1}};
  std::string word;
  while (in >> word) {
    if (word == "MeshVersionFormatted" || word == "Dimension") {
      int x;
      in >> x;
    } else if (word == "Vertices") {
      size_t n;
      in >> n;
      mesh->positions.resize(n);
      for (auto& p : mesh->positions) {
        int ref;
        in >> p[0] >> p[1] >> p[2] >> ref;
      }
    } else if (word == "Tetrahedra") {
      size_t n;
      in >> n;
      mesh->tets.resize(n);
      for (auto& t : mesh->tets) {
        int64_t v[4], ref;
        in >> v[0] >> v[1] >> v[2] >> v[3] >> ref;
        for (int i = 0; i < 4; ++i) {
          if (v[i] < 1 || static_cast<size_t>(v[i]) > mesh->positions.size()) {
            *error = path + ": tet vertex out of range";
            return false;
          }
          t[i] = static_cast<uint32_t>(v[i] - 1);
        }
      }
    } else if (word == "End") {
      break;
    } else if (skip.count(word)) {
      size_t n;
      in >> n;
      for (size_t i = 0; i < n * static_cast<size_t>(skip.at(word)); ++i) {
        double x;
        in >> x;
      }
    } else {
      *error = path + ": unknown section " + word;
      return false;
    }
    if (!in) {
      *error = path + ": truncated near " + word;
      return false;
    }
  }
  if (mesh->tets.empty()) {
    *error = path + ": no Tetrahedra";
    return false;
  }
  return true;
}

}  // namespace mrsv::test
