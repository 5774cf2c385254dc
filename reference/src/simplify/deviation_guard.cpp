#include "simplify/deviation_guard.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "simplify/triangle_distance.h"

namespace mrsv::simplify {

namespace {

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
