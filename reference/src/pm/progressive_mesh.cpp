// spec: 6.6 levels of a progressive mesh, 6.8 canonical output.
#include <cstdio>

#include "pm/pm_state.h"

namespace mrsv {

void ProgressiveMesh::Impl::applySplit(const CornerTable::Ring& vs_ring) {
  SplitRecord& r = splits[level];
  if (header.placement == kPlacementFree)
    for (int k = 0; k < 3; ++k) positions[r.vs][k] += r.vs_move[k];
  table.split(r.vs, vs_ring, r.a, r.b, r.shape);
  positions.push_back(r.vt_position);
  if (header.scalar_bits) scalars.push_back(r.vt_scalar);
  ++level;
}

void ProgressiveMesh::Impl::coarsenOne() {
  const SplitRecord& r = splits[level - 1];
  table.collapseLast(r.vs, r.shape);
  positions.pop_back();
  if (header.scalar_bits) scalars.pop_back();
  if (header.placement == kPlacementFree)
    for (int k = 0; k < 3; ++k) positions[r.vs][k] -= r.vs_move[k];
  --level;
}

ProgressiveMesh::ProgressiveMesh() : impl_(new Impl) {}
ProgressiveMesh::~ProgressiveMesh() = default;
ProgressiveMesh::ProgressiveMesh(ProgressiveMesh&&) noexcept = default;
ProgressiveMesh& ProgressiveMesh::operator=(ProgressiveMesh&&) noexcept = default;

const PmHeader& ProgressiveMesh::header() const { return impl_->header; }
uint32_t ProgressiveMesh::splitsDecoded() const { return static_cast<uint32_t>(impl_->splits.size()); }
uint32_t ProgressiveMesh::level() const { return impl_->level; }
uint32_t ProgressiveMesh::vertexCount() const { return impl_->table.vertexCount(); }
uint32_t ProgressiveMesh::triangleCount() const { return impl_->table.triangleCount(); }

uint32_t ProgressiveMesh::vertexCountAt(uint32_t level) const {
  return impl_->header.base_vertex_count + level;
}

uint32_t ProgressiveMesh::triangleCountAt(uint32_t level) const {
  // Each split adds one face per present G1/G2 (recorded when it was applied).
  uint32_t t = impl_->table.triangleCount();
  const auto& s = impl_->splits;
  for (uint32_t i = impl_->level; i > level; --i) t -= s[i - 1].shape.has_g1 + s[i - 1].shape.has_g2;
  for (uint32_t i = impl_->level; i < level && i < s.size(); ++i)
    t += s[i].shape.has_g1 + s[i].shape.has_g2;
  return t;
}

uint32_t ProgressiveMesh::finestLevelWithin(uint64_t max_triangles) const {
  uint64_t t = triangleCountAt(0);
  uint32_t level = 0;
  for (const SplitRecord& r : impl_->splits) {
    t += r.shape.has_g1 + r.shape.has_g2;
    if (t > max_triangles) break;
    ++level;
  }
  return level;
}

void ProgressiveMesh::setLevel(uint32_t target) {
  if (target > impl_->splits.size()) target = static_cast<uint32_t>(impl_->splits.size());
  // Moving up, the splits to come are known: start loading the first face of
  // the ring of a split kLookahead ahead, so that its ring walk begins from
  // cache (on a large mesh every face of a walk is a cache miss, one after
  // the other).
  constexpr uint32_t kLookahead = 8;
  while (impl_->level < target) {
    if (impl_->level + kLookahead < target) impl_->table.prefetchRing(impl_->splits[impl_->level + kLookahead].vs);
    impl_->refineOne();
  }
  while (impl_->level > target) impl_->coarsenOne();
}

TriangleMesh ProgressiveMesh::mesh() const {
  const PmHeader& h = impl_->header;
  TriangleMesh m;
  m.positions.resize(impl_->positions.size());
  for (size_t v = 0; v < m.positions.size(); ++v)
    for (int k = 0; k < 3; ++k)
      m.positions[v][k] = h.origin[k] + impl_->positions[v][k] * h.position_step;
  m.triangles = impl_->table.triangles();
  if (h.scalar_bits) {
    m.scalars.resize(impl_->scalars.size());
    for (size_t v = 0; v < m.scalars.size(); ++v)
      m.scalars[v] = h.scalar_origin + impl_->scalars[v] * h.scalar_step;
  }
  return m;
}

const std::vector<std::array<int32_t, 3>>& ProgressiveMesh::quantizedPositions() const {
  return impl_->positions;
}
std::vector<std::array<uint32_t, 3>> ProgressiveMesh::triangles() const {
  return impl_->table.triangles();
}
const std::vector<int32_t>& ProgressiveMesh::quantizedScalars() const { return impl_->scalars; }

std::vector<uint8_t> canonicalMeshOutput(const ProgressiveMesh& pm) {
  const PmHeader& h = pm.header();
  char line[128];
  int n = std::snprintf(line, sizeof line, "mrsv-canonical-mesh 1 %u %u %u %u\n", pm.vertexCount(),
                        pm.triangleCount(), unsigned{h.position_bits}, unsigned{h.scalar_bits});
  std::vector<uint8_t> out(line, line + n);
  auto put32 = [&](uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
  };
  const auto& q = pm.quantizedPositions();
  const auto& s = pm.quantizedScalars();
  for (size_t v = 0; v < q.size(); ++v) {
    for (int k = 0; k < 3; ++k) put32(static_cast<uint32_t>(q[v][k]));
    if (h.scalar_bits) put32(static_cast<uint32_t>(s[v]));
  }
  for (const auto& t : pm.triangles())
    for (uint32_t v : t) put32(v);
  return out;
}

}  // namespace mrsv
