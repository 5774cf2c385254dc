// spec: 7.9 (informative) the reference PT stream writer.
#include "pt/pt_encode.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "bitstream/range_encoder.h"
#include "pt/pt_coding.h"
#include "pt/pt_state.h"

namespace mrsv {

namespace {

// The encoder's coder with a running estimate of the bits spent (the
// information content of each decision under its model before it adapts),
// so that the stats can split the stream into connectivity and geometry.
struct CountingCoder {
  static constexpr bool kEncoding = true;
  RangeEncoder* rc;
  double bits = 0;
  int bit(BitModel* m, int b) {
    const double p0 = m->p0 / double{kProbabilityOne};
    bits -= std::log2(b ? 1 - p0 : p0);
    rc->bit(m, b);
    return b;
  }
  int bitUnpredictable(BitModel* m, int b) { return bit(m, b); }
  int symbol(SymbolModel* m, int s) {
    bits -= std::log2(m->width(s) / double{1u << kSymbolBits});
    rc->symbol(m, s);
    return s;
  }
  uint32_t direct(uint32_t value, int n) {
    bits += n;
    rc->direct(value, n);
    return value;
  }
  bool overrun() const { return false; }
};

Error fail(Status status, const std::string& field, std::string message) {
  return Error{status, 0, field, std::move(message)};
}

// A field's grid: exact when its values are integers that fit in `bits`.
PtField fieldGrid(const ScalarField& field, int bits) {
  PtField grid;
  grid.bits = static_cast<uint8_t>(bits);
  grid.name = field.name.substr(0, kTetFieldNameSize);
  for (char& c : grid.name)
    if (c < 0x20 || c > 0x7E) c = '_';
  double lo = INFINITY, hi = -INFINITY;
  bool integers = true;
  for (double v : field.values) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    integers = integers && v == std::floor(v);
  }
  if (field.values.empty()) lo = hi = 0;
  grid.origin = lo;
  const double levels = std::ldexp(1.0, bits) - 1;
  grid.step = integers && hi - lo <= levels ? 1.0 : (hi > lo ? (hi - lo) / levels : 1.0);
  return grid;
}

}  // namespace

Error quantizeTetMesh(const TetMesh& mesh, int position_bits, int field_bits, QuantizedTets* out) {
  if (position_bits < 1 || position_bits > kMaxPositionBits)
    return fail(Status::kInvalidArgument, "position_bits", "must be 1 to 30");
  if (field_bits < 1 || field_bits > kMaxPositionBits)
    return fail(Status::kInvalidArgument, "field_bits", "must be 1 to 30");
  if (mesh.fields.size() > static_cast<size_t>(kMaxTetFields))
    return fail(Status::kInvalidArgument, "fields", "a PT stream holds at most 8 fields");
  *out = QuantizedTets{};
  PtHeader& h = out->header;
  h.position_bits = static_cast<uint8_t>(position_bits);
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (const auto& p : mesh.positions)
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(p[a])) return fail(Status::kInvalidArgument, "positions", "a coordinate is not finite");
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  double extent = 0;
  for (int a = 0; a < 3; ++a) {
    h.origin[a] = lo[a];
    extent = std::max(extent, hi[a] - lo[a]);
  }
  h.position_step = extent > 0 ? extent / (std::ldexp(1.0, position_bits) - 1) : 1.0;
  const double top = std::ldexp(1.0, position_bits) - 1;
  out->positions.resize(mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    for (int a = 0; a < 3; ++a)
      out->positions[v][a] =
          static_cast<int32_t>(std::clamp(std::round((mesh.positions[v][a] - lo[a]) / h.position_step), 0.0, top));
  const size_t fc = mesh.fields.size();
  for (const ScalarField& f : mesh.fields) {
    if (f.values.size() != mesh.positions.size())
      return fail(Status::kInvalidArgument, "fields", "field '" + f.name + "' does not have one value per vertex");
    h.fields.push_back(fieldGrid(f, field_bits));
  }
  out->scalars.resize(mesh.positions.size() * fc);
  for (size_t f = 0; f < fc; ++f) {
    const PtField& g = h.fields[f];
    const double field_top = std::ldexp(1.0, g.bits) - 1;
    for (size_t v = 0; v < mesh.positions.size(); ++v)
      out->scalars[v * fc + f] = static_cast<int32_t>(
          std::clamp(std::round((mesh.fields[f].values[v] - g.origin) / g.step), 0.0, field_top));
  }
  out->tets = mesh.tets;
  for (size_t t = 0; t < out->tets.size(); ++t) {
    const Tet& k = out->tets[t];
    for (uint32_t v : k)
      if (v >= mesh.positions.size())
        return fail(Status::kInvalidArgument, "tets", "tet " + std::to_string(t) + " names a vertex out of range");
    const int o = orient3d(out->positions[k[0]], out->positions[k[1]], out->positions[k[2]], out->positions[k[3]]);
    if (o <= 0)
      return fail(Status::kInvalidArgument, "tets",
                  "tet " + std::to_string(t) + (o == 0 ? " is flat" : " is inverted") + " at " +
                      std::to_string(position_bits) + " position bits" +
                      (o == 0 ? " (more bits may keep it apart)" : ""));
  }
  return {};
}

namespace {

// One collapse as the splits need it: the cut's directed edges x -> y (the
// tets (vt, x, y, vs) that the collapse removes), in the input's numbering.
struct CollapseRecord {
  uint32_t vs, vt;
  std::vector<std::array<uint32_t, 2>> cut_edges;
};

// Replays the collapses on the input, fine to coarse, recording each one's cut.
Error replayCollapses(const QuantizedTets& mesh, const std::vector<std::vector<PtCollapse>>& batches,
                      std::vector<std::vector<CollapseRecord>>* records, std::vector<Tet>* tets,
                      std::vector<uint8_t>* tet_alive) {
  const uint32_t n = static_cast<uint32_t>(mesh.positions.size());
  *tets = mesh.tets;
  tet_alive->assign(tets->size(), 1);
  std::vector<std::vector<uint32_t>> incident(n);
  for (uint32_t t = 0; t < tets->size(); ++t)
    for (uint32_t v : (*tets)[t]) incident[v].push_back(t);
  std::vector<uint8_t> vertex_alive(n, 1);
  records->assign(batches.size(), {});
  for (size_t b = 0; b < batches.size(); ++b) {
    for (size_t k = 0; k < batches[b].size(); ++k) {
      const PtCollapse c = batches[b][k];
      const std::string where = "batch " + std::to_string(b) + ", collapse " + std::to_string(k);
      if (c.vs >= n || c.vt >= n || c.vs == c.vt || !vertex_alive[c.vs] || !vertex_alive[c.vt])
        return fail(Status::kInvalidArgument, "collapses", where + ": names a vertex that is not there");
      CollapseRecord r{c.vs, c.vt, {}};
      for (uint32_t slot : incident[c.vt]) {
        if (!(*tet_alive)[slot]) continue;
        Tet& t = (*tets)[slot];
        int at_vt = 0, at_vs = -1;
        for (int i = 0; i < 4; ++i) {
          if (t[i] == c.vt) at_vt = i;
          if (t[i] == c.vs) at_vs = i;
        }
        if (at_vs < 0) {
          t[at_vt] = c.vs;
          incident[c.vs].push_back(slot);
          continue;
        }
        // (vt, p, q, r) is even; rotate (p, q, r) so that vs comes last.
        const uint32_t p = t[kLinkOrder[at_vt][0]], q = t[kLinkOrder[at_vt][1]], rr = t[kLinkOrder[at_vt][2]];
        if (rr == c.vs) r.cut_edges.push_back({p, q});
        else if (p == c.vs) r.cut_edges.push_back({q, rr});
        else r.cut_edges.push_back({rr, p});
        (*tet_alive)[slot] = 0;
      }
      if (r.cut_edges.empty()) return fail(Status::kInvalidArgument, "collapses", where + ": vs and vt share no tet");
      incident[c.vt].clear();
      vertex_alive[c.vt] = 0;
      (*records)[b].push_back(std::move(r));
    }
  }
  return {};
}

// Orders a cut's directed edges into the walk of spec 7.7.2: a cycle from its
// smallest vertex, or the path from the vertex no edge enters.
bool orderCut(const std::vector<std::array<uint32_t, 2>>& edges, std::vector<uint32_t>* walk, bool* closed) {
  std::vector<std::array<uint32_t, 2>> sorted = edges;
  std::sort(sorted.begin(), sorted.end());
  auto successor = [&](uint32_t x) -> int64_t {
    auto it = std::lower_bound(sorted.begin(), sorted.end(), std::array<uint32_t, 2>{x, 0});
    return it != sorted.end() && (*it)[0] == x ? static_cast<int64_t>((*it)[1]) : -1;
  };
  std::vector<uint32_t> targets;
  for (const auto& e : sorted) targets.push_back(e[1]);
  std::sort(targets.begin(), targets.end());
  uint32_t start = UINT32_MAX;
  for (const auto& e : sorted)
    if (!std::binary_search(targets.begin(), targets.end(), e[0])) start = std::min(start, e[0]);
  *closed = start == UINT32_MAX;
  if (*closed) start = sorted[0][0];
  walk->assign(1, start);
  for (size_t steps = 0; steps <= edges.size(); ++steps) {
    const int64_t next = successor(walk->back());
    if (next < 0) return !*closed && walk->size() == edges.size() + 1;
    if (*closed && next == start) return walk->size() == edges.size();
    walk->push_back(static_cast<uint32_t>(next));
  }
  return false;
}

}  // namespace

Error writePtStream(const QuantizedTets& mesh, const std::vector<std::vector<PtCollapse>>& batches,
                    std::vector<uint8_t>* out, PtStreamStats* stats) {
  std::vector<std::vector<CollapseRecord>> records;
  std::vector<Tet> tets;
  std::vector<uint8_t> tet_alive;
  if (Error e = replayCollapses(mesh, batches, &records, &tets, &tet_alive); !e.ok()) return e;

  // spec 7.3 numbering: base vertices in order of first use by the base
  // tets, then each split's vt, coarse to fine, vs ascending within a batch.
  const uint32_t n = static_cast<uint32_t>(mesh.positions.size());
  std::vector<uint32_t> number(n, UINT32_MAX), original;
  std::vector<Tet> base_tets;
  for (uint32_t t = 0; t < tets.size(); ++t) {
    if (!tet_alive[t]) continue;
    Tet k = tets[t];
    for (uint32_t& v : k) {
      if (number[v] == UINT32_MAX) {
        number[v] = static_cast<uint32_t>(original.size());
        original.push_back(v);
      }
      v = number[v];
    }
    base_tets.push_back(k);
  }
  const uint32_t base_vertices = static_cast<uint32_t>(original.size());
  for (size_t b = batches.size(); b-- > 0;) {
    std::vector<CollapseRecord>& batch = records[b];
    std::sort(batch.begin(), batch.end(),
              [&](const CollapseRecord& x, const CollapseRecord& y) { return number[x.vs] < number[y.vs]; });
    for (CollapseRecord& r : batch) {
      if (number[r.vs] == UINT32_MAX) return fail(Status::kInvalidArgument, "collapses", "a vs is gone before its batch");
      number[r.vt] = static_cast<uint32_t>(original.size());
      original.push_back(r.vt);
    }
  }
  if (original.size() != n)
    return fail(Status::kInvalidArgument, "mesh", std::to_string(n - original.size()) + " vertices are in no tet");

  PtHeader h = mesh.header;
  h.vertex_count = n;
  h.base_vertex_count = base_vertices;
  h.base_tet_count = static_cast<uint32_t>(base_tets.size());
  h.tet_count = static_cast<uint32_t>(mesh.tets.size());
  h.batch_count = 0;
  for (const auto& b : batches) h.batch_count += b.empty() ? 0 : 1;
  const size_t fc = h.fields.size();

  ProgressiveTetMesh decoded;
  ProgressiveTetMesh::Impl& s = decoded.state();
  s.header = h;
  s.mesh.field_count = static_cast<int>(fc);
  for (uint32_t v = 0; v < base_vertices; ++v) {
    s.mesh.positions.push_back(mesh.positions[original[v]]);
    for (size_t f = 0; f < fc; ++f) s.mesh.scalars.push_back(mesh.scalars[original[v] * fc + f]);
  }
  s.mesh.tets.assign(base_tets.begin(), base_tets.end());

  ContainerWriter writer;
  const std::vector<uint8_t> header_bytes = serializePtHeader(h);
  writer.addChunk(kChunkTetHeader, header_bytes);
  pt::PtContexts ctx;
  {
    std::vector<uint8_t> payload;
    RangeEncoder rc(&payload);
    EncodingCoder coder{&rc};
    std::string problem = pt::codeBaseMesh(coder, ctx, h, &s.mesh);
    if (!problem.empty()) return fail(Status::kInvalidArgument, "base mesh", problem);
    rc.finish();
    problem = s.startFromBase();
    if (!problem.empty()) return fail(Status::kInvalidArgument, "base mesh", "the base mesh: " + problem);
    writer.addChunk(kChunkTetBase, payload);
    if (stats) {
      stats->header_bytes = header_bytes.size();
      stats->base_bytes = payload.size();
      stats->base_vertices = base_vertices;
      stats->base_tets = base_tets.size();
    }
  }

  std::vector<uint32_t> walk_global;
  for (size_t b = batches.size(); b-- > 0;) {
    const std::vector<CollapseRecord>& batch = records[b];
    if (batch.empty()) continue;
    std::vector<uint8_t> payload(4);
    const uint32_t count = static_cast<uint32_t>(batch.size());
    for (int i = 0; i < 4; ++i) payload[i] = static_cast<uint8_t>(count >> (8 * i));
    RangeEncoder rc(&payload);
    CountingCoder coder{&rc};
    size_t next = 0;
    // 7.7.1: a group flag at each group's first vertex; in a group whose flag
    // is 1, a flag per vertex, the last implied while none was 1 before it.
    const uint32_t vertices_at_start = s.mesh.vertexCount();
    uint32_t group_end = 0;
    int previous_group = 0;
    bool split_in_group = false;
    for (uint32_t v = 0; next < batch.size(); ++v) {
      const CollapseRecord& r = batch[next];
      double before = coder.bits;
      if (v == group_end) {
        group_end = std::min(v + pt::kSplitGroup, vertices_at_start);
        const int has_split = number[r.vs] < group_end ? 1 : 0;
        coder.bit(&ctx.group_flag[previous_group], has_split);
        if (stats) ++stats->flag_decisions;
        previous_group = has_split;
        split_in_group = false;
      }
      if (stats) stats->flag_bits += coder.bits - before;
      if (previous_group == 0) {
        v = group_end - 1;
        continue;
      }
      const int flag = number[r.vs] == v ? 1 : 0;
      before = coder.bits;
      if (v + 1 < group_end || split_in_group) {
        coder.bit(&ctx.split_flag[pt::flagContext(s.mesh, v)], flag);
        if (stats) ++stats->flag_decisions;
      }
      if (stats) stats->flag_bits += coder.bits - before;
      if (!flag) continue;
      split_in_group = true;
      const std::string where = "batch " + std::to_string(b) + ", the collapse of " + std::to_string(r.vt) +
                                " into " + std::to_string(r.vs);
      std::vector<std::array<uint32_t, 2>> edges = r.cut_edges;
      for (auto& e : edges) e = {number[e[0]], number[e[1]]};
      bool closed = false;
      if (!orderCut(edges, &walk_global, &closed))
        return fail(Status::kInvalidArgument, "collapses", where + ": the link of the edge is not a cycle or a path");
      s.mesh.buildLink(v, &s.link);
      if (s.link.vertices.size() > kMaxSplitLinkVertices)
        return fail(Status::kInvalidArgument, "collapses",
                    where + ": the link of vs would have more than " + std::to_string(kMaxSplitLinkVertices) +
                        " vertices (spec B.6)");
      if (closed == s.link.has_boundary)
        return fail(Status::kInvalidArgument, "collapses",
                    where + (closed ? ": an interior edge at a boundary vertex" : ": a boundary edge at an interior vertex"));
      s.walk_local.clear();
      for (uint32_t g : walk_global) s.walk_local.push_back(s.link.localIndex(g));
      bool coded_closed = closed;
      const std::vector<uint32_t> wanted = s.walk_local;
      before = coder.bits;
      std::string problem = pt::codeCut(coder, ctx, s.link, &s.scratch, &s.walk_local, &coded_closed);
      if (stats) stats->cut_bits += coder.bits - before;
      before = coder.bits;
      if (problem.empty() && (coded_closed != closed || s.walk_local != wanted))
        problem = "the cut is not a simple walk in the link of vs";
      Point3i position = mesh.positions[r.vt];
      int32_t values[kMaxTetFields] = {};
      for (size_t f = 0; f < fc; ++f) values[f] = mesh.scalars[r.vt * fc + f];
      if (problem.empty())
        problem = pt::codeSplitValues(coder, ctx, h, s.mesh, v, walk_global.data(),
                                      static_cast<uint32_t>(walk_global.size()), &position, values);
      if (stats) stats->value_bits += coder.bits - before;
      if (problem.empty()) {
        s.mesh.positions.push_back(position);
        s.mesh.scalars.insert(s.mesh.scalars.end(), values, values + fc);
        problem = s.applyNewSplit(s.link, v, closed);
      }
      if (!problem.empty()) return fail(Status::kInvalidArgument, "collapses", where + ": " + problem);
      ++next;
    }
    rc.finish();
    if (stats) {
      stats->split_bytes += payload.size();
      ++stats->batches;
      stats->splits += count;
    }
    writer.addChunk(kChunkTetSplits, payload);
  }
  if (s.mesh.tets.size() != h.tet_count)
    return fail(Status::kInvalidArgument, "collapses", "the splits rebuild " + std::to_string(s.mesh.tets.size()) +
                                                           " tets of " + std::to_string(h.tet_count));
  *out = writer.finish();
  return {};
}

}  // namespace mrsv
