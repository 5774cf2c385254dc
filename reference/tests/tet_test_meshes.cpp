// Tet meshes and the field sampler of tet_test_meshes.h.
#include "tet_test_meshes.h"

#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "tetsimplify/exact_predicates.h"

namespace mrsv::test {

namespace {

bool readFile(const std::string& path, std::vector<uint8_t>* data) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  data->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return true;
}

// Orients every tet positively; false if one is flat.
bool orient(QuantizedTetMesh* mesh, std::string* error) {
  for (auto& t : mesh->tets) {
    const auto& p = mesh->positions;
    const auto o = tetsimplify::orient3d(p[t[0]], p[t[1]], p[t[2]], p[t[3]]);
    if (o == 0) {
      *error = "flat tet after quantisation";
      return false;
    }
    if (o < 0) std::swap(t[2], t[3]);
  }
  return true;
}

}  // namespace

bool readMeditTets(const std::string& path, QuantizedTetMesh* mesh, std::string* error) {
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open";
    return false;
  }
  std::vector<std::array<double, 3>> points;
  mesh->tets.clear();
  mesh->fields.clear();
  std::string word;
  while (in >> word) {
    if (word == "Vertices") {
      size_t n;
      in >> n;
      points.resize(n);
      for (auto& p : points) {
        int ref;
        in >> p[0] >> p[1] >> p[2] >> ref;
      }
    } else if (word == "Tetrahedra") {
      size_t n;
      in >> n;
      mesh->tets.resize(n);
      for (auto& t : mesh->tets) {
        int ref;
        in >> t[0] >> t[1] >> t[2] >> t[3] >> ref;
        for (auto& v : t) --v;
      }
    } else if (word == "End") {
      break;
    }
  }
  if (points.empty() || mesh->tets.empty()) {
    *error = path + ": no vertices or tetrahedra";
    return false;
  }
  std::array<double, 3> lo = points[0], hi = points[0];
  for (const auto& p : points) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  const double side = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const double scale = double((1 << 29) - 1) / side;
  mesh->positions.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    for (int k = 0; k < 3; ++k) mesh->positions[i][k] = int32_t(std::lround((points[i][k] - lo[k]) * scale));
  }
  return orient(mesh, error);
}

bool ctHeadCrop(int n, int x0, int y0, int z0, QuantizedTetMesh* mesh, std::string* error, int z_scale) {
  const std::string path = std::string(MRSV_SHARED_DATA) + "/volume/ct_head_stanford_cthead_256x256x99_uint8.raw.zst";
  std::vector<uint8_t> packed;
  if (!readFile(path, &packed)) {
    *error = path + ": cannot read";
    return false;
  }
  const int sx = 256, sy = 256, sz = 99;
  std::vector<uint8_t> volume(size_t(sx) * sy * sz);
  const size_t got = ZSTD_decompress(volume.data(), volume.size(), packed.data(), packed.size());
  if (ZSTD_isError(got) || got != volume.size() || x0 + n > sx || y0 + n > sy || z0 + n > sz) {
    *error = path + ": not the expected volume";
    return false;
  }
  mesh->positions.clear();
  mesh->tets.clear();
  mesh->fields.assign(1, {});
  auto id = [n](int x, int y, int z) { return uint32_t((z * n + y) * n + x); };
  for (int z = 0; z < n; ++z) {
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        mesh->positions.push_back({x * 1024, y * 1024, z * 1024 * z_scale});
        mesh->fields[0].push_back(volume[(size_t(z + z0) * sy + (y + y0)) * sx + (x + x0)]);
      }
    }
  }
  // Six tets around the diagonal from corner 000 to 111, one per order in
  // which a path between them steps along the axes.
  static const int kOrders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int z = 0; z + 1 < n; ++z) {
    for (int y = 0; y + 1 < n; ++y) {
      for (int x = 0; x + 1 < n; ++x) {
        for (const auto& order : kOrders) {
          int c[3] = {x, y, z};
          std::array<uint32_t, 4> t;
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[order[s]];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          mesh->tets.push_back(t);
        }
      }
    }
  }
  return orient(mesh, error);
}

bool paperCtCrop(QuantizedTetMesh* mesh, std::string* error) {
  // A fragment across the skull and brain, mid-height.
  return ctHeadCrop(32, 96, 112, 40, mesh, error);
}

bool loxPost(QuantizedTetMesh* mesh, std::string* error) {
  const std::string base = std::string(MRSV_SHARED_DATA) + "/tet/lox_post_plot3d_38x76x38_f32be";
  std::vector<uint8_t> xyz, q;
  if (!readFile(base + "_iblank.xyz", &xyz) || !readFile(base + ".q", &q)) {
    *error = base + ": cannot read";
    return false;
  }
  auto be32 = [](const uint8_t* p) { return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]; };
  auto bef = [&](const uint8_t* p) {
    const uint32_t u = be32(p);
    float f;
    std::memcpy(&f, &u, 4);
    return f;
  };
  // Plain (unformatted-free) layout: dims, then x, y, z (float) and IBLANK (int).
  const int ni = 38, nj = 76, nk = 38;
  const size_t np = size_t(ni) * nj * nk;
  size_t off = 0;
  // Skip a header of 3 ints (dims), with or without Fortran record markers.
  if (be32(xyz.data()) == uint32_t(ni)) {
    off = 12;
  } else if (be32(xyz.data()) == 12u) {
    off = 20;
  } else {
    *error = base + ".xyz: unexpected header";
    return false;
  }
  if (xyz.size() < off + np * 16) {
    *error = base + ".xyz: too short";
    return false;
  }
  std::vector<std::array<double, 3>> points(np);
  std::vector<int32_t> iblank(np);
  for (int k = 0; k < 3; ++k) {
    for (size_t i = 0; i < np; ++i) points[i][k] = bef(&xyz[off + (k * np + i) * 4]);
  }
  for (size_t i = 0; i < np; ++i) iblank[i] = int32_t(be32(&xyz[off + (3 * np + i) * 4]));
  // Q file: dims, then mach, alpha, re, time, then 5 fields (density,
  // x, y, z momentum, energy). This file's density is 1 everywhere (an
  // incompressible solution), so the scalar is the x momentum.
  size_t qoff = be32(q.data()) == uint32_t(ni) ? 12 + 16 : 20 + 24;
  if (q.size() < qoff + 2 * np * 4) {
    *error = base + ".q: too short";
    return false;
  }
  std::vector<double> density(np);
  for (size_t i = 0; i < np; ++i) density[i] = bef(&q[qoff + (np + i) * 4]);

  std::array<double, 3> lo = points[0], hi = points[0];
  for (const auto& p : points) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  const double side = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const double scale = double((1 << 29) - 1) / side;
  auto id = [&](int i, int j, int k) { return uint32_t((size_t(k) * nj + j) * ni + i); };
  // Five tets per hex: the corner tets at four alternate corners and the
  // middle one; the other four corners in cells of odd parity.
  mesh->tets.clear();
  std::vector<uint8_t> used(np, 0);
  for (int k = 0; k + 1 < nk; ++k) {
    for (int j = 0; j + 1 < nj; ++j) {
      for (int i = 0; i + 1 < ni; ++i) {
        uint32_t c[8];
        bool blanked = false;
        for (int b = 0; b < 8; ++b) {
          c[b] = id(i + (b & 1), j + (b >> 1 & 1), k + (b >> 2));
          if (iblank[c[b]] == 0) blanked = true;
        }
        if (blanked) continue;
        static const int kEven[5][4] = {{0, 1, 2, 4}, {3, 1, 2, 7}, {5, 1, 4, 7}, {6, 2, 4, 7}, {1, 2, 4, 7}};
        static const int kOdd[5][4] = {{1, 0, 3, 5}, {2, 0, 3, 6}, {4, 0, 5, 6}, {7, 3, 5, 6}, {0, 3, 5, 6}};
        const auto& table = (i + j + k) % 2 == 0 ? kEven : kOdd;
        for (const auto& t : table) {
          mesh->tets.push_back({c[t[0]], c[t[1]], c[t[2]], c[t[3]]});
          for (int a = 0; a < 4; ++a) used[c[t[a]]] = 1;
        }
      }
    }
  }
  // The grid wraps around the post: its first and last i planes hold the
  // same points (1,444 pairs), left apart as in the file (welded, vertex 0's
  // link is an annulus), so the boundary touches itself along the seam and
  // the self-intersection test refuses the collapses that would move it
  // there (outside flat fans).
  // Only the vertices the tets use.
  std::vector<uint32_t> map(np, ~0u);
  mesh->positions.clear();
  mesh->fields.assign(1, {});
  for (size_t i = 0; i < np; ++i) {
    if (!used[i]) continue;
    map[i] = uint32_t(mesh->positions.size());
    std::array<int32_t, 3> p;
    for (int k = 0; k < 3; ++k) p[k] = int32_t(std::lround((points[i][k] - lo[k]) * scale));
    mesh->positions.push_back(p);
    mesh->fields[0].push_back(density[i]);
  }
  for (auto& t : mesh->tets) {
    for (auto& v : t) v = map[v];
  }
  return orient(mesh, error);
}

FieldSampler::FieldSampler(const QuantizedTetMesh& mesh) : mesh_(mesh) {
  std::array<double, 3> hi{};
  lo_ = {1e300, 1e300, 1e300};
  hi = {-1e300, -1e300, -1e300};
  for (const auto& p : mesh.positions) {
    for (int k = 0; k < 3; ++k) {
      lo_[k] = std::min(lo_[k], double(p[k]));
      hi[k] = std::max(hi[k], double(p[k]));
    }
  }
  const double cells = std::max<double>(1.0, double(mesh.tets.size()) / 2.0);
  const double volume = std::max(1.0, (hi[0] - lo_[0]) * (hi[1] - lo_[1]) * (hi[2] - lo_[2]));
  const double side = std::cbrt(volume / cells);
  for (int k = 0; k < 3; ++k) {
    dims_[k] = std::max(1, int(std::ceil((hi[k] - lo_[k]) / side)));
    cell_[k] = std::max(1.0, (hi[k] - lo_[k]) / dims_[k]) * (1.0 + 1e-12);
  }
  const size_t n = size_t(dims_[0]) * dims_[1] * dims_[2];
  std::vector<uint32_t> count(n + 1, 0);
  auto range = [&](const std::array<uint32_t, 4>& t, int* a, int* b) {
    for (int k = 0; k < 3; ++k) {
      double l = 1e300, h = -1e300;
      for (uint32_t v : t) {
        l = std::min(l, double(mesh.positions[v][k]));
        h = std::max(h, double(mesh.positions[v][k]));
      }
      a[k] = std::clamp(int((l - lo_[k]) / cell_[k]), 0, dims_[k] - 1);
      b[k] = std::clamp(int((h - lo_[k]) / cell_[k]), 0, dims_[k] - 1);
    }
  };
  for (int pass = 0; pass < 2; ++pass) {
    for (uint32_t t = 0; t < mesh.tets.size(); ++t) {
      int a[3], b[3];
      range(mesh.tets[t], a, b);
      for (int z = a[2]; z <= b[2]; ++z) {
        for (int y = a[1]; y <= b[1]; ++y) {
          for (int x = a[0]; x <= b[0]; ++x) {
            const size_t c = (size_t(z) * dims_[1] + y) * dims_[0] + x;
            if (pass == 0) {
              ++count[c + 1];
            } else {
              items_[start_[c] + count[c]++] = t;
            }
          }
        }
      }
    }
    if (pass == 0) {
      for (size_t c = 0; c < n; ++c) count[c + 1] += count[c];
      start_ = count;
      items_.resize(count[n]);
      std::fill(count.begin(), count.end(), 0);
    }
  }
}

bool FieldSampler::sample(const std::array<double, 3>& p, double* value) const {
  int c[3];
  for (int k = 0; k < 3; ++k) {
    const double f = (p[k] - lo_[k]) / cell_[k];
    if (f < 0.0 || f >= dims_[k]) return false;
    c[k] = int(f);
  }
  const size_t cell = (size_t(c[2]) * dims_[1] + c[1]) * dims_[0] + c[0];
  for (uint32_t i = start_[cell]; i < start_[cell + 1]; ++i) {
    const auto& t = mesh_.tets[items_[i]];
    std::array<double, 3> q[4];
    for (int j = 0; j < 4; ++j) {
      for (int k = 0; k < 3; ++k) q[j][k] = mesh_.positions[t[j]][k];
    }
    auto det = [](const std::array<double, 3>& a, const std::array<double, 3>& b, const std::array<double, 3>& c,
                  const std::array<double, 3>& d) {
      const double bx = b[0] - a[0], by = b[1] - a[1], bz = b[2] - a[2];
      const double cx = c[0] - a[0], cy = c[1] - a[1], cz = c[2] - a[2];
      const double dx = d[0] - a[0], dy = d[1] - a[1], dz = d[2] - a[2];
      return bx * (cy * dz - cz * dy) + by * (cz * dx - cx * dz) + bz * (cx * dy - cy * dx);
    };
    const double total = det(q[0], q[1], q[2], q[3]);
    const double w0 = det(p, q[1], q[2], q[3]) / total, w1 = det(q[0], p, q[2], q[3]) / total,
                 w2 = det(q[0], q[1], p, q[3]) / total, w3 = det(q[0], q[1], q[2], p) / total;
    const double eps = -1e-12;
    if (w0 < eps || w1 < eps || w2 < eps || w3 < eps) continue;
    const auto& f = mesh_.fields[0];
    *value = w0 * f[t[0]] + w1 * f[t[1]] + w2 * f[t[2]] + w3 * f[t[3]];
    return true;
  }
  return false;
}

PsnrResult scalarPsnr(const QuantizedTetMesh& original, const QuantizedTetMesh& simplified, uint64_t samples,
                      uint32_t seed) {
  FieldSampler a(original), b(simplified);
  std::array<double, 3> lo = {1e300, 1e300, 1e300}, hi = {-1e300, -1e300, -1e300};
  for (const auto& p : original.positions) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], double(p[k]));
      hi[k] = std::max(hi[k], double(p[k]));
    }
  }
  const auto [mn, mx] = std::minmax_element(original.fields[0].begin(), original.fields[0].end());
  const double range = *mx - *mn;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  PsnrResult result;
  double sum = 0.0;
  uint64_t taken = 0;
  while (taken < samples) {
    std::array<double, 3> p;
    for (int k = 0; k < 3; ++k) p[k] = lo[k] + u(rng) * (hi[k] - lo[k]);
    double va, vb;
    if (!a.sample(p, &va)) continue;
    ++taken;
    if (!b.sample(p, &vb)) {
      ++result.outside;
      vb = 0.0;
    }
    sum += (va - vb) * (va - vb);
  }
  const double mse = sum / double(samples);
  result.psnr = mse > 0.0 ? 10.0 * std::log10(range * range / mse) : 999.0;
  return result;
}

}  // namespace mrsv::test
