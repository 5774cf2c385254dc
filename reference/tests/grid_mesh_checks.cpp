#include "grid_mesh_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <utility>

#include "shared_data.h"

namespace mrsv::test {

SampleField terrainCrop(const std::string& file, uint32_t x0, uint32_t y0, uint32_t w, uint32_t h) {
  SampleField f;
  SharedGrid g;
  if (!loadSharedGrid(std::string(MRSV_SHARED_DATA) + "/terrain/" + file, &g)) return f;
  EXPECT_EQ(g.header.sample_type, SampleType::kInt16);
  if (x0 + w > g.header.size_x || y0 + h > g.header.size_y) {
    ADD_FAILURE() << file << ": crop outside the grid";
    return f;
  }
  f.size[0] = w, f.size[1] = h, f.size[2] = 1;
  f.values.resize(uint64_t{w} * h);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const size_t k = (size_t{y0 + y} * g.header.size_x + x0 + x) * 2;
      f.values[size_t{y} * w + x] = int16_t(uint16_t(g.samples[k] | (g.samples[k + 1] << 8)));
    }
  return f;
}

namespace {
int64_t cross(const std::array<uint32_t, 3>& a, const std::array<uint32_t, 3>& b,
              const std::array<uint32_t, 3>& c) {
  return (int64_t(b[0]) - a[0]) * (int64_t(c[1]) - a[1]) - (int64_t(b[1]) - a[1]) * (int64_t(c[0]) - a[0]);
}
}  // namespace

std::string triangulationProblem(const GridMesh& m) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  int64_t area = 0;
  for (size_t t = 0; t < m.cells.size(); ++t) {
    const auto& c = m.cells[t];
    const int64_t a = cross(m.points[c[0]], m.points[c[1]], m.points[c[2]]);
    if (a <= 0) return "triangle " + std::to_string(t) + " is not counter-clockwise";
    area += a;
    for (int i = 0; i < 3; ++i)
      if (++directed[{c[i], c[(i + 1) % 3]}] > 1) return "edge used twice the same way in triangle " + std::to_string(t);
  }
  if (area != 2 * (int64_t(m.size[0]) - 1) * (int64_t(m.size[1]) - 1)) return "areas do not sum to the grid's";
  const uint32_t mx = m.size[0] - 1, my = m.size[1] - 1;
  for (const auto& [e, n] : directed) {
    if (directed.count({e.second, e.first})) continue;
    const auto& p = m.points[e.first];
    const auto& q = m.points[e.second];
    const bool border = (p[1] == 0 && q[1] == 0) || (p[1] == my && q[1] == my) || (p[0] == 0 && q[0] == 0) ||
                        (p[0] == mx && q[0] == mx);
    if (!border) return "edge " + std::to_string(e.first) + "-" + std::to_string(e.second) + " has one triangle and is inside";
  }
  return "";
}

bool withinBoundEverywhere(const SampleField& f, const GridMesh& m, const ErrorBound& bound, double* worst) {
  bool ok = true;
  *worst = 0;
  for (const auto& c : m.cells) {
    const auto &a = m.points[c[0]], &b = m.points[c[1]], &d = m.points[c[2]];
    const int64_t den = cross(a, b, d);
    const uint32_t x0 = std::min({a[0], b[0], d[0]}), x1 = std::max({a[0], b[0], d[0]});
    const uint32_t y0 = std::min({a[1], b[1], d[1]}), y1 = std::max({a[1], b[1], d[1]});
    for (uint32_t y = y0; y <= y1; ++y)
      for (uint32_t x = x0; x <= x1; ++x) {
        const std::array<uint32_t, 3> p = {x, y, 0};
        const int64_t wa = cross(p, b, d), wb = cross(a, p, d), wc = cross(a, b, p);
        if (wa < 0 || wb < 0 || wc < 0) continue;
        __int128 e = __int128{f.at(x, y)} * den -
                     (__int128{wa} * m.values[c[0]] + __int128{wb} * m.values[c[1]] + __int128{wc} * m.values[c[2]]);
        if (e < 0) e = -e;
        *worst = std::max(*worst, double(e) / double(den));
        if (e * bound.den > __int128{bound.num} * den) ok = false;
      }
  }
  return ok;
}

std::vector<std::array<uint32_t, 3>> borderPoints(const GridMesh& mesh) {
  std::vector<std::array<uint32_t, 3>> out;
  for (const auto& p : mesh.points)
    if (p[0] == 0 || p[1] == 0 || p[0] + 1 == mesh.size[0] || p[1] + 1 == mesh.size[1]) out.push_back(p);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace mrsv::test
