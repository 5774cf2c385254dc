// Dense, deterministic sampling of a triangulated surface (Metro's scheme:
// vertices, points along edges, area-proportional stratified face points).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "metrics/splitmix64.h"
#include "metrics/surface_distance.h"

namespace mrsv {
namespace {

Point3 sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double length(const Point3& a) { return std::sqrt(dot(a, a)); }

// Faces and edges (by owning face and corner) of the non-degenerate triangles.
struct SurfaceTopology {
  std::vector<uint32_t> faces;          // indices into mesh.triangles
  std::vector<double> face_area;        // per entry of `faces`
  std::vector<uint8_t> owned_edges;     // per entry of `faces`: bit e set when the
                                        // face is the first to use edge (corner e, e+1)
  std::vector<uint8_t> vertex_used;     // per mesh vertex
  double area = 0.0;
  double edge_length = 0.0;
  uint64_t vertex_count = 0;
};

SurfaceTopology buildTopology(const TriangleMesh& mesh) {
  SurfaceTopology t;
  t.vertex_used.assign(mesh.positions.size(), 0);
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& tri = mesh.triangles[f];
    const Point3& a = mesh.positions[tri[0]];
    const Point3& b = mesh.positions[tri[1]];
    const Point3& c = mesh.positions[tri[2]];
    if (isDegenerateTriangle(a, b, c)) continue;
    t.faces.push_back(static_cast<uint32_t>(f));
    double area = 0.5 * length(cross(sub(b, a), sub(c, a)));
    t.face_area.push_back(area);
    t.area += area;
    for (uint32_t v : tri) {
      if (!t.vertex_used[v]) ++t.vertex_count;
      t.vertex_used[v] = 1;
    }
  }
  // An edge belongs to the first face (in face order) that uses it: sort the
  // (edge key, face position, corner) triples and keep the first of each key.
  struct EdgeUse {
    uint64_t key;
    uint32_t face_pos;
    uint32_t corner;
  };
  std::vector<EdgeUse> uses;
  uses.reserve(t.faces.size() * 3);
  for (size_t i = 0; i < t.faces.size(); ++i) {
    const auto& tri = mesh.triangles[t.faces[i]];
    for (uint32_t e = 0; e < 3; ++e) {
      uint64_t u = tri[e], v = tri[(e + 1) % 3];
      if (u > v) std::swap(u, v);
      uses.push_back({(u << 32) | v, static_cast<uint32_t>(i), e});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return x.key != y.key ? x.key < y.key : x.face_pos < y.face_pos;
  });
  t.owned_edges.assign(t.faces.size(), 0);
  for (size_t i = 0; i < uses.size(); ++i) {
    if (i > 0 && uses[i].key == uses[i - 1].key) continue;
    t.owned_edges[uses[i].face_pos] |= static_cast<uint8_t>(1u << uses[i].corner);
    const Point3& p = mesh.positions[uses[i].key >> 32];
    const Point3& q = mesh.positions[uses[i].key & 0xffffffffu];
    t.edge_length += length(sub(p, q));
  }
  return t;
}

// Error diffusion: the count of the next element is the change in the rounded
// running total, so counts differ from their expected values by less than one
// and add up to the rounded grand total.
class CountDiffuser {
 public:
  uint64_t next(double expected) {
    total_ += expected;
    auto rounded = static_cast<uint64_t>(std::llround(total_));
    uint64_t count = rounded > emitted_ ? rounded - emitted_ : 0;
    emitted_ += count;
    return count;
  }

 private:
  double total_ = 0.0;
  uint64_t emitted_ = 0;
};

// k stratified points in triangle (a, b, c). The triangle is cut into m^2
// similar sub-triangles (grid points a + (i/m)(b-a) + (j/m)(c-a)); row j holds
// the upward triangles (i,j) and the downward ones between them, 2(m-j)-1 in
// all. Strata are numbered row by row and k of them taken at even strides.
void sampleFace(const Point3& a, const Point3& b, const Point3& c, uint64_t k, SplitMix64* rng,
                SurfaceSamples* out) {
  const auto m = static_cast<uint64_t>(std::ceil(std::sqrt(static_cast<double>(k))));
  const uint64_t strata = m * m;
  const Point3 ab = sub(b, a), ac = sub(c, a);
  const double inv_m = 1.0 / static_cast<double>(m);
  uint64_t row = 0, row_start = 0, row_size = 2 * m - 1;
  for (uint64_t s = 0; s < k; ++s) {
    // Middle of the s-th of k equal runs of strata.
    uint64_t stratum = (2 * s + 1) * strata / (2 * k);
    while (stratum >= row_start + row_size) {
      row_start += row_size;
      ++row;
      row_size -= 2;
    }
    uint64_t pos = stratum - row_start;
    auto i = static_cast<double>(pos / 2), j = static_cast<double>(row);
    double u = rng->unit(), v = rng->unit();
    if (u + v > 1.0) {
      u = 1.0 - u;
      v = 1.0 - v;
    }
    // Barycentric grid coordinates (along ab, along ac) of the sample.
    double x, y;
    if (pos % 2 == 0) {  // upward: corners (i,j), (i+1,j), (i,j+1)
      x = i + u;
      y = j + v;
    } else {  // downward: corners (i+1,j+1), (i,j+1), (i+1,j)
      x = i + 1.0 - u;
      y = j + 1.0 - v;
    }
    x *= inv_m;
    y *= inv_m;
    out->points.push_back({a[0] + x * ab[0] + y * ac[0], a[1] + x * ab[1] + y * ac[1],
                           a[2] + x * ab[2] + y * ac[2]});
    out->is_face_sample.push_back(true);
  }
  out->face_samples += k;
}

}  // namespace

bool isDegenerateTriangle(const Point3& a, const Point3& b, const Point3& c) {
  Point3 ab = sub(b, a), bc = sub(c, b), ca = sub(a, c);
  double longest2 = std::max({dot(ab, ab), dot(bc, bc), dot(ca, ca)});
  Point3 n = cross(ab, sub(c, a));
  // |n| <= 1e-12 * longest^2, compared squared; !(x > y) also catches NaN.
  return !(dot(n, n) > 1e-24 * longest2 * longest2);
}

bool checkSurfaceMesh(const TriangleMesh& mesh, std::string* error) {
  const size_t n = mesh.positions.size();
  if (n > std::numeric_limits<uint32_t>::max()) {
    *error = "more than 2^32 - 1 vertices";
    return false;
  }
  bool any_face = false;
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (uint32_t v : mesh.triangles[f]) {
      if (v >= n) {
        *error = "triangle " + std::to_string(f) + " uses vertex " + std::to_string(v) + " of " +
                 std::to_string(n);
        return false;
      }
      for (double x : mesh.positions[v])
        if (!std::isfinite(x)) {
          *error = "vertex " + std::to_string(v) + " has a coordinate that is not finite";
          return false;
        }
    }
    const auto& t = mesh.triangles[f];
    if (!any_face && !isDegenerateTriangle(mesh.positions[t[0]], mesh.positions[t[1]],
                                           mesh.positions[t[2]]))
      any_face = true;
  }
  if (!any_face) {
    *error = mesh.triangles.empty() ? "no triangles" : "every triangle has zero area";
    return false;
  }
  return true;
}

double surfaceBoxDiagonal(const TriangleMesh& mesh) {
  Point3 lo{}, hi{};
  bool first = true;
  for (const auto& tri : mesh.triangles) {
    const Point3& a = mesh.positions[tri[0]];
    const Point3& b = mesh.positions[tri[1]];
    const Point3& c = mesh.positions[tri[2]];
    if (isDegenerateTriangle(a, b, c)) continue;
    for (const Point3* p : {&a, &b, &c}) {
      for (int d = 0; d < 3; ++d) {
        lo[d] = first ? (*p)[d] : std::min(lo[d], (*p)[d]);
        hi[d] = first ? (*p)[d] : std::max(hi[d], (*p)[d]);
      }
      first = false;
    }
  }
  return length(sub(hi, lo));
}

void sampleSurface(const TriangleMesh& mesh, const SurfaceSamplingOptions& options,
                   SurfaceSamples* samples) {
  *samples = SurfaceSamples{};
  const SurfaceTopology topo = buildTopology(mesh);
  samples->area = topo.area;

  const uint64_t n = options.sample_count;
  const uint64_t budget = std::max(n > topo.vertex_count ? n - topo.vertex_count : 0, n / 2);
  // Spacing h along edges and density 1/h^2 on faces, with
  // area / h^2 + edge_length / h = budget; s = 1/h is the positive root of
  // area s^2 + edge_length s - budget = 0, in the form without cancellation.
  const double b = static_cast<double>(budget);
  const double s = b > 0.0 ? 2.0 * b /
                                 (topo.edge_length +
                                  std::sqrt(topo.edge_length * topo.edge_length + 4.0 * topo.area * b))
                           : 0.0;
  const uint64_t reserve = topo.vertex_count + budget + 1;
  samples->points.reserve(reserve);
  samples->is_face_sample.reserve(reserve);

  std::vector<uint8_t> vertex_done(mesh.positions.size(), 0);
  CountDiffuser diffuser;
  for (size_t i = 0; i < topo.faces.size(); ++i) {
    const uint32_t f = topo.faces[i];
    const auto& tri = mesh.triangles[f];
    for (uint32_t v : tri) {
      if (vertex_done[v]) continue;
      vertex_done[v] = 1;
      samples->points.push_back(mesh.positions[v]);
      samples->is_face_sample.push_back(false);
      ++samples->vertex_samples;
    }
    for (uint32_t e = 0; e < 3; ++e) {
      if (!(topo.owned_edges[i] & (1u << e))) continue;
      const Point3& p = mesh.positions[tri[e]];
      const Point3& q = mesh.positions[tri[(e + 1) % 3]];
      const Point3 pq = sub(q, p);
      const uint64_t k = diffuser.next(length(pq) * s);
      if (k == 0) continue;
      SplitMix64 rng = splitMixStream(options.seed, 1 + e, f);
      for (uint64_t j = 0; j < k; ++j) {
        double t = (static_cast<double>(j) + rng.unit()) / static_cast<double>(k);
        samples->points.push_back({p[0] + t * pq[0], p[1] + t * pq[1], p[2] + t * pq[2]});
        samples->is_face_sample.push_back(false);
      }
      samples->edge_samples += k;
    }
    const uint64_t k = diffuser.next(topo.face_area[i] * s * s);
    if (k == 0) continue;
    SplitMix64 rng = splitMixStream(options.seed, 0, f);
    sampleFace(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]], k, &rng,
               samples);
  }
}

}  // namespace mrsv
