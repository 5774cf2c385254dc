// spec: 7.3 the mesh a PT decoder holds, moving between levels; 7.8 canonical output.
#include <algorithm>
#include <cstring>

#include "pt/pt_state.h"

namespace mrsv {

std::string ProgressiveTetMesh::Impl::startFromBase() {
  // Room for the whole stream as THDR announces it (checked against the
  // memory limit before TBAS, 7.2): growing the arrays split by split
  // copied each of them about twice (callgrind: about 350 instructions per
  // split on the CT crop). Reserved, not filled: a prefix uses what it needs.
  const uint32_t splits = header.splitCount();
  mesh.tets.reserve(header.tet_count);
  mesh.positions.reserve(header.vertex_count);
  mesh.scalars.reserve(size_t{header.vertex_count} * header.fields.size());
  this->splits.reserve(splits);
  tet_count_after.reserve(splits);
  moved.reserve(size_t{splits} * 12);
  cuts.reserve(size_t{splits} * 6);
  mesh.buildIncidence();
  // The tet lists take about 8 entries per tet with their room to grow
  // (CT crop): reserved so, the pool is not moved on the way, which cost a
  // sixth more page faults (perf stat, pt_decode_bench).
  mesh.incident.reserveTotal(header.vertex_count, size_t{header.tet_count} * 8);
  std::string problem = mesh.checkManifold();
  tet_count_after.clear();
  level = 0;
  return problem;
}

template <class LinkT>
std::string ProgressiveTetMesh::Impl::applyNewSplit(const LinkT& link_of_vs, uint32_t vs, bool closed) {
  const uint32_t vt = mesh.vertexCount() - 1;
  if (std::string problem = splitRegion(link_of_vs, walk_local, closed, &scratch, &region); !problem.empty())
    return problem;
  // In slot order, as the tet lists keep them (incidence_lists.h).
  std::sort(region.begin(), region.end());
  walk_global.clear();
  for (uint32_t local : walk_local) walk_global.push_back(link_of_vs.vertices[local]);
  mesh.incident.addVertex();
  std::string problem = applySplit(&mesh, vs, vt, walk_global.data(), static_cast<uint32_t>(walk_global.size()),
                                   closed, region.data(), static_cast<uint32_t>(region.size()));
  if (!problem.empty()) {
    mesh.incident.removeLastVertex();
    return problem;
  }
  recordSplit(vs, closed);
  return "";
}

std::string ProgressiveTetMesh::Impl::applyDecodedSplit(uint32_t vs, bool closed) {
  const uint32_t vt = mesh.vertexCount() - 1;
  mesh.incident.addVertex();
  std::string problem = applyStarSplit(&mesh, &star_link, vt, walk_local, closed, &scratch, &region, &walk_global);
  if (!problem.empty()) {
    mesh.incident.removeLastVertex();
    return problem;
  }
  recordSplit(vs, closed);
  return "";
}

void ProgressiveTetMesh::Impl::recordSplit(uint32_t vs, bool closed) {
  PtSplitRecord r;
  r.vs = vs;
  r.moved_begin = static_cast<uint32_t>(moved.size());
  r.moved_count = static_cast<uint32_t>(region.size());
  r.cut_begin = static_cast<uint32_t>(cuts.size());
  r.cut_length = static_cast<uint32_t>(walk_global.size());
  r.closed = closed;
  moved.insert(moved.end(), region.begin(), region.end());
  cuts.insert(cuts.end(), walk_global.begin(), walk_global.end());
  splits.push_back(r);
  tet_count_after.push_back(static_cast<uint32_t>(mesh.tets.size()));
  ++level;
}

template std::string ProgressiveTetMesh::Impl::applyNewSplit(const Link&, uint32_t, bool);

void ProgressiveTetMesh::Impl::redo(uint32_t k) {
  const PtSplitRecord& r = splits[k];
  const uint32_t vt = header.base_vertex_count + k;
  redoSplit(&mesh, r.vs, vt, &cuts[r.cut_begin], r.cut_length, r.closed, &moved[r.moved_begin], r.moved_count);
}

void ProgressiveTetMesh::Impl::undo(uint32_t k) {
  const PtSplitRecord& r = splits[k];
  const uint32_t vt = header.base_vertex_count + k;
  undoSplit(&mesh, r.vs, vt, &cuts[r.cut_begin], r.cut_length, r.closed, &moved[r.moved_begin], r.moved_count);
}

void ProgressiveTetMesh::Impl::prefetchSplit(uint32_t k) const {
  const PtSplitRecord& r = splits[k];
  const uint32_t vt = header.base_vertex_count + k;
  mesh.incident.prefetch(r.vs);
  mesh.incident.prefetch(vt);
  for (uint32_t i = 0; i < r.cut_length; ++i) mesh.incident.prefetch(cuts[r.cut_begin + i]);
  for (uint32_t i = 0; i < r.moved_count; ++i) __builtin_prefetch(&mesh.tets[moved[r.moved_begin + i]], 1);
}

void ProgressiveTetMesh::Impl::prefetchSplitLists(uint32_t k) const {
  const PtSplitRecord& r = splits[k];
  mesh.incident.prefetchEntries(r.vs);
  for (uint32_t i = 0; i < r.cut_length; ++i) mesh.incident.prefetchEntries(cuts[r.cut_begin + i]);
}

ProgressiveTetMesh::ProgressiveTetMesh() : impl_(std::make_unique<Impl>()) {}
ProgressiveTetMesh::~ProgressiveTetMesh() = default;
ProgressiveTetMesh::ProgressiveTetMesh(ProgressiveTetMesh&&) noexcept = default;
ProgressiveTetMesh& ProgressiveTetMesh::operator=(ProgressiveTetMesh&&) noexcept = default;

const PtHeader& ProgressiveTetMesh::header() const { return impl_->header; }
uint32_t ProgressiveTetMesh::splitsDecoded() const { return static_cast<uint32_t>(impl_->splits.size()); }
uint32_t ProgressiveTetMesh::level() const { return impl_->level; }
uint32_t ProgressiveTetMesh::vertexCount() const {
  // No vertices before the base mesh is read (a prefix without TBAS).
  return impl_->mesh.tets.empty() ? 0 : impl_->header.base_vertex_count + impl_->level;
}
uint32_t ProgressiveTetMesh::tetCount() const { return static_cast<uint32_t>(impl_->mesh.tets.size()); }

uint32_t ProgressiveTetMesh::tetCountAt(uint32_t level) const {
  level = std::min(level, splitsDecoded());
  return level == 0 ? impl_->header.base_tet_count : impl_->tet_count_after[level - 1];
}

uint32_t ProgressiveTetMesh::finestLevelWithin(uint64_t max_tets) const {
  // Tet counts only grow with the level (every split adds at least one tet).
  const auto& after = impl_->tet_count_after;
  if (impl_->header.base_tet_count > max_tets) return 0;
  return static_cast<uint32_t>(std::upper_bound(after.begin(), after.end(), max_tets) - after.begin());
}

void ProgressiveTetMesh::setLevel(uint32_t level) {
  level = std::min(level, splitsDecoded());
  // Moving between levels is a few scattered writes per split: in a mesh
  // larger than the caches, the tets, lists and cut vertices of the split 4
  // further on are asked for while this one is redone or undone (CT crop,
  // 178,746 tets: reaching 10 % of them from the finest 2.97-3.50 ->
  // 2.32-2.80 ms). In a smaller one all is at hand and the prefetches only
  // cost (the hand, 29,998 tets: 15 to 25 % slower with them).
  const bool ahead = impl_->mesh.tets.size() >= (1u << 16);
  while (impl_->level < level) {
    if (ahead && impl_->level + 4 < level) impl_->prefetchSplit(impl_->level + 4);
    if (ahead && impl_->level + 2 < level) impl_->prefetchSplitLists(impl_->level + 2);
    impl_->redo(impl_->level++);
  }
  while (impl_->level > level) {
    if (ahead && impl_->level >= level + 5) impl_->prefetchSplit(impl_->level - 5);
    if (ahead && impl_->level >= level + 3) impl_->prefetchSplitLists(impl_->level - 3);
    impl_->undo(--impl_->level);
  }
}

std::vector<std::array<int32_t, 3>> ProgressiveTetMesh::quantizedPositions() const {
  const auto& p = impl_->mesh.positions;
  return {p.begin(), p.begin() + vertexCount()};
}

std::vector<int32_t> ProgressiveTetMesh::quantizedScalars() const {
  const auto& s = impl_->mesh.scalars;
  return {s.begin(), s.begin() + size_t{vertexCount()} * impl_->header.fields.size()};
}

std::vector<std::array<uint32_t, 4>> ProgressiveTetMesh::tets() const {
  return {impl_->mesh.tets.begin(), impl_->mesh.tets.end()};
}

TetMesh ProgressiveTetMesh::mesh() const {
  const PtHeader& h = impl_->header;
  const uint32_t n = vertexCount();
  const size_t fc = h.fields.size();
  TetMesh out;
  out.positions.resize(n);
  for (uint32_t v = 0; v < n; ++v)
    for (int a = 0; a < 3; ++a)
      out.positions[v][a] = h.origin[a] + impl_->mesh.positions[v][a] * h.position_step;
  out.tets.assign(impl_->mesh.tets.begin(), impl_->mesh.tets.end());
  for (size_t f = 0; f < fc; ++f) {
    ScalarField field;
    field.name = h.fields[f].name;
    field.values.resize(n);
    for (uint32_t v = 0; v < n; ++v)
      field.values[v] = h.fields[f].origin + impl_->mesh.scalars[v * fc + f] * h.fields[f].step;
    out.fields.push_back(std::move(field));
  }
  return out;
}

std::vector<uint8_t> canonicalTetMeshOutput(const ProgressiveTetMesh& mesh) {
  const PtHeader& h = mesh.header();
  const uint32_t n = mesh.vertexCount();
  const size_t fc = h.fields.size();
  const auto& state = mesh.state().mesh;
  std::string head = "mrsv-canonical-tets 1 " + std::to_string(n) + " " + std::to_string(mesh.tetCount()) + " " +
                     std::to_string(h.position_bits) + " " + std::to_string(fc) + "\n";
  std::vector<uint8_t> out(head.begin(), head.end());
  out.reserve(out.size() + size_t{n} * (12 + 4 * fc) + size_t{mesh.tetCount()} * 16);
  auto put32 = [&](uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
  };
  for (uint32_t v = 0; v < n; ++v) {
    for (int a = 0; a < 3; ++a) put32(static_cast<uint32_t>(state.positions[v][a]));
    for (size_t f = 0; f < fc; ++f) put32(static_cast<uint32_t>(state.scalars[v * fc + f]));
  }
  for (const Tet& t : state.tets)
    for (uint32_t v : t) put32(v);
  return out;
}

}  // namespace mrsv
