#include "simplify/deviation_guard.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mrsv::simplify {

namespace {

inline double segmentDistance2(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = sub(b, a);
  const Vec3 ap = sub(p, a);
  const double l = dot(ab, ab);
  double t = l > 0.0 ? dot(ap, ab) / l : 0.0;
  t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
  const Vec3 d = {ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]};
  return dot(d, d);
}

// A triangle with what the distance test needs precomputed.
struct Triangle {
  Vec3 a, ab, ac;
  double d00, d01, d11, det;
};

inline Triangle makeTriangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  Triangle t;
  t.a = a;
  t.ab = sub(b, a);
  t.ac = sub(c, a);
  t.d00 = dot(t.ab, t.ab);
  t.d01 = dot(t.ab, t.ac);
  t.d11 = dot(t.ac, t.ac);
  t.det = t.d00 * t.d11 - t.d01 * t.d01;
  return t;
}

inline double area(const Triangle& t) { return 0.5 * std::sqrt(std::fmax(0.0, t.det)); }

// Squared distance from p to triangle t: to the plane when p projects inside,
// else to the nearest of the three edges (where the closest point then lies).
inline double distance2(const Vec3& p, const Triangle& t) {
  const Vec3 ap = sub(p, t.a);
  if (t.det > 0.0) {
    const double d20 = dot(ap, t.ab);
    const double d21 = dot(ap, t.ac);
    const double v = (t.d11 * d20 - t.d01 * d21) / t.det;
    const double w = (t.d00 * d21 - t.d01 * d20) / t.det;
    if (v >= 0.0 && w >= 0.0 && v + w <= 1.0) {
      const Vec3 d = {ap[0] - v * t.ab[0] - w * t.ac[0], ap[1] - v * t.ab[1] - w * t.ac[1],
                      ap[2] - v * t.ab[2] - w * t.ac[2]};
      return dot(d, d);
    }
  }
  const Vec3 b = {t.a[0] + t.ab[0], t.a[1] + t.ab[1], t.a[2] + t.ab[2]};
  const Vec3 c = {t.a[0] + t.ac[0], t.a[1] + t.ac[1], t.a[2] + t.ac[2]};
  return std::min({segmentDistance2(p, t.a, b), segmentDistance2(p, b, c), segmentDistance2(p, c, t.a)});
}

// The squared distance from p to the nearest triangle of the fan, stopping as
// soon as it is at most `enough` (the caller needs no less).
inline double fanDistance2(const Vec3& p, const std::vector<Triangle>& fan, double enough) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < fan.size() && best > enough; ++i) {
    const double d2 = distance2(p, fan[i]);
    if (d2 < best) best = d2;
  }
  return best;
}

// Appends the triangles around v that do not touch `other` (kNone: all of
// them), with x in v's place.
void appendFan(const EdgeTopology& topo, const std::vector<Vec3>& positions, uint32_t v, uint32_t other,
               const Vec3& x, std::vector<Triangle>* fan) {
  topo.forEachOutgoing(v, [&](uint32_t h) {
    const uint32_t p = topo.target(h);
    const uint32_t q = topo.vertexOf(EdgeTopology::prev(h));
    if (p != other && q != other) fan->push_back(makeTriangle(x, positions[p], positions[q]));
  });
}

// The scratch fan of cost() and merge(), which run once per collapse or
// candidate and would otherwise allocate each time.
thread_local std::vector<Triangle> scratch_fan;

}  // namespace

void DeviationGuard::init(const TriangleMesh& mesh, double weight) {
  weight_ = weight;
  const size_t nv = mesh.positions.size();
  input_.resize(nv);
  for (size_t v = 0; v < nv; ++v) input_[v] = {mesh.positions[v], 0.0};
  for (const auto& t : mesh.triangles) {
    for (int i = 0; i < 3; ++i) {
      InputVertex& a = input_[t[i]];
      InputVertex& b = input_[t[(i + 1) % 3]];
      const Vec3 e = sub(b.position, a.position);
      const double l = length(e);
      a.reach = std::max(a.reach, l);
      b.reach = std::max(b.reach, l);
    }
  }
  members_.assign(nv, Members{});
  for (uint32_t v = 0; v < nv; ++v) {
    members_[v].count = 1;
    members_[v].vertex[0] = v;
  }
}

double DeviationGuard::cost(const EdgeTopology& topo, const std::vector<Vec3>& positions, uint32_t removed,
                            uint32_t kept, const Vec3& x) const {
  // The fan the collapse makes: the triangles around either end but not on
  // the edge, with x for the end.
  // The members' input positions are scattered: they are asked into the
  // cache before the fan is built, which takes about as long as a miss.
  for (const uint32_t v : {kept, removed})
    for (uint32_t i = 0; i < members_[v].count; ++i) __builtin_prefetch(&input_[members_[v].vertex[i]]);
  std::vector<Triangle>& fan = scratch_fan;
  fan.clear();
  appendFan(topo, positions, kept, removed, x, &fan);
  appendFan(topo, positions, removed, kept, x, &fan);
  double fan_area = 0.0;
  for (const Triangle& t : fan) fan_area += area(t);
  // d_out: a member nearer the fan than the farthest so far cannot change it.
  // d_in, from below: the input triangles around member m are at least
  // |x - m| - reach(m) away (reach: m's longest input edge). A bound, not the
  // distance, because reading those triangles took about as long again as
  // the rest of the simplifier (turbine: +0.4 s); and what it is for, an
  // optimum that overshoots a thin tip, lands many input edge lengths away,
  // where the bound is nearly exact.
  double out2 = 0.0;
  double in = std::numeric_limits<double>::infinity();
  for (const uint32_t v : {kept, removed}) {
    for (uint32_t i = 0; i < members_[v].count; ++i) {
      const InputVertex& m = input_[members_[v].vertex[i]];
      const double d2 = fanDistance2(m.position, fan, out2);
      if (d2 > out2 && d2 != std::numeric_limits<double>::infinity()) out2 = d2;
      const double gap = length(sub(x, m.position)) - m.reach;
      if (gap < in) in = gap;
    }
  }
  const double in2 = in > 0.0 ? in * in : 0.0;
  return weight_ * fan_area * std::fmax(out2, in2);
}

void DeviationGuard::merge(const EdgeTopology& topo, const std::vector<Vec3>& positions, uint32_t removed,
                           uint32_t kept) {
  Members& into = members_[kept];
  const Members& from = members_[removed];
  if (into.count + from.count <= kMaxMembers) {
    for (uint32_t i = 0; i < from.count; ++i) into.vertex[into.count++] = from.vertex[i];
    return;
  }
  // Keep the members farthest from the new fan: they are the ones a later
  // collapse is most likely to leave too far away.
  std::vector<Triangle>& fan = scratch_fan;
  fan.clear();
  appendFan(topo, positions, kept, kNone, positions[kept], &fan);
  std::array<std::pair<double, uint32_t>, 2 * kMaxMembers> all;
  uint32_t n = 0;
  for (const Members* m : std::array<const Members*, 2>{&into, &from}) {
    for (uint32_t i = 0; i < m->count; ++i) {
      const uint32_t v = m->vertex[i];
      all[n++] = {fanDistance2(input_[v].position, fan, 0.0), v};
    }
  }
  // Farthest first; ties by vertex number, so the result never depends on
  // the sort's internals.
  std::partial_sort(all.begin(), all.begin() + kMaxMembers, all.begin() + n,
                    [](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && a.second < b.second); });
  into.count = kMaxMembers;
  for (uint32_t i = 0; i < kMaxMembers; ++i) into.vertex[i] = all[i].second;
}

}  // namespace mrsv::simplify
