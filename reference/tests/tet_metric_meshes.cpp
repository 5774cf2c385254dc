// Grid tet meshes and a minimal MEDIT reader (see tet_metric_meshes.h).
#include "tet_metric_meshes.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <utility>
#include <vector>

namespace mrsv::test {

TetMesh gridTetMesh(int nx, int ny, int nz, const std::array<double, 3>& origin,
                    const std::array<double, 3>& spacing,
                    const std::function<double(int, int, int)>& value, const std::string& field) {
  TetMesh m;
  auto at = [&](int i, int j, int k) { return static_cast<uint32_t>((k * ny + j) * nx + i); };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        m.positions.push_back(
            {origin[0] + i * spacing[0], origin[1] + j * spacing[1], origin[2] + k * spacing[2]});
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
  const std::map<std::string, int> skip = {
      {"Edges", 3},   {"Triangles", 4}, {"Quadrilaterals", 5},   {"Hexahedra", 9},
      {"Corners", 1}, {"Ridges", 1},    {"RequiredVertices", 1}, {"RequiredEdges", 1}};
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

namespace {

// Big-endian 32-bit words of a whole file.
bool readWords(const std::string& path, std::vector<uint32_t>* words) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  words->resize(bytes.size() / 4);
  for (size_t i = 0; i < words->size(); ++i)
    (*words)[i] = (uint32_t{bytes[4 * i]} << 24) | (uint32_t{bytes[4 * i + 1]} << 16) |
                  (uint32_t{bytes[4 * i + 2]} << 8) | bytes[4 * i + 3];
  return true;
}

float asFloat(uint32_t w) {
  float f;
  std::memcpy(&f, &w, 4);
  return f;
}

}  // namespace

bool readPlot3dTetMesh(const std::string& xyz_path, const std::string& q_path, TetMesh* mesh,
                       std::string* error) {
  *mesh = TetMesh{};
  std::vector<uint32_t> xyz, q;
  if (!readWords(xyz_path, &xyz) || !readWords(q_path, &q)) {
    *error = "cannot read " + xyz_path + " or " + q_path;
    return false;
  }
  if (xyz.size() < 3 || q.size() < 7) {
    *error = "PLOT3D files too short";
    return false;
  }
  const int ni = static_cast<int>(xyz[0]), nj = static_cast<int>(xyz[1]),
            nk = static_cast<int>(xyz[2]);
  const size_t n = static_cast<size_t>(ni) * nj * nk;
  if (ni < 2 || nj < 2 || nk < 2 || xyz.size() != 3 + 3 * n || q[0] != xyz[0] || q[1] != xyz[1] ||
      q[2] != xyz[2] || q.size() < 3 + 4 + 5 * n) {
    *error = "not a single-grid PLOT3D pair without IBLANK";
    return false;
  }
  mesh->positions.resize(n);
  for (size_t v = 0; v < n; ++v)
    for (int d = 0; d < 3; ++d) mesh->positions[v][d] = asFloat(xyz[3 + d * n + v]);
  ScalarField density{"density", std::vector<double>(n)};
  for (size_t v = 0; v < n; ++v) density.values[v] = asFloat(q[7 + v]);
  mesh->fields.push_back(std::move(density));
  // Corner c of a hex is (i + (c & 1), j + (c >> 1 & 1), k + (c >> 2)). The
  // even cut keeps corners 1, 2, 4, 7 for the middle tet and cuts off 0, 3,
  // 5, 6 with their three neighbours each; the odd cut the other way round.
  const int cuts[2][5][4] = {
      {{0, 1, 2, 4}, {3, 2, 1, 7}, {5, 1, 4, 7}, {6, 4, 2, 7}, {1, 2, 4, 7}},
      {{1, 0, 3, 5}, {2, 3, 0, 6}, {4, 5, 6, 0}, {7, 6, 5, 3}, {0, 3, 5, 6}}};
  // Grid points at the same place (the blunt fin's grid collapses one line:
  // 39 points of k = 0 are there twice) become one vertex, and the tets of
  // the collapsed cells that lose a corner that way are left out.
  std::vector<uint32_t> same(n);
  {
    std::vector<uint32_t> order(n);
    for (size_t v = 0; v < n; ++v) order[v] = static_cast<uint32_t>(v);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
      return mesh->positions[a] != mesh->positions[b] ? mesh->positions[a] < mesh->positions[b]
                                                      : a < b;
    });
    for (size_t r = 0; r < n; ++r)
      same[order[r]] = r > 0 && mesh->positions[order[r]] == mesh->positions[order[r - 1]]
                           ? same[order[r - 1]]
                           : order[r];
  }
  auto at = [&](int i, int j, int k) { return same[(static_cast<size_t>(k) * nj + j) * ni + i]; };
  for (int k = 0; k + 1 < nk; ++k)
    for (int j = 0; j + 1 < nj; ++j)
      for (int i = 0; i + 1 < ni; ++i)
        for (const auto& cut : cuts[(i + j + k) & 1]) {
          std::array<uint32_t, 4> t;
          for (int c = 0; c < 4; ++c)
            t[c] = at(i + (cut[c] & 1), j + (cut[c] >> 1 & 1), k + (cut[c] >> 2));
          if (t[0] == t[1] || t[0] == t[2] || t[0] == t[3] || t[1] == t[2] || t[1] == t[3] ||
              t[2] == t[3])
            continue;
          const auto &a = mesh->positions[t[0]], &b = mesh->positions[t[1]],
                     &c = mesh->positions[t[2]], &d = mesh->positions[t[3]];
          const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
          const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
          const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
          const double det = u[0] * (v[1] * w[2] - v[2] * w[1]) -
                             u[1] * (v[0] * w[2] - v[2] * w[0]) +
                             u[2] * (v[0] * w[1] - v[1] * w[0]);
          if (det < 0) std::swap(t[2], t[3]);
          mesh->tets.push_back(t);
        }
  return true;
}

}  // namespace mrsv::test
