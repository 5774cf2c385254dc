// The coding of the PT stream's values (spec 7.5, 7.7), written once as
// templates over the coder so that the encoder and the normative decoder
// cannot drift apart (the pattern of pm/pm_coding.h). Decisions are 16-ary
// symbols wherever a value has more than two outcomes: a split codes a
// handful of symbols, not dozens of binary decisions (issue 3's lesson).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "bitstream/range_coder_adapter.h"
#include "mrsv/progressive_tet_mesh.h"
#include "pm/pm_coding.h"
#include "tetmesh/star_link.h"
#include "tetmesh/tet_complex.h"
#include "tetmesh/vertex_split.h"

namespace mrsv::pt {

constexpr int kDegreeContexts = 16;
constexpr int kFlagContexts = 16;
// spec 7.7.1: the vertices of a batch go in groups of this many, each with a
// group flag before its vertices' flags (D87).
constexpr uint32_t kSplitGroup = 32;

// spec 7.5.1 a signed value below 2^30 in magnitude: its bit length n (0 to
// 30) as one symbol, or 15 and a second symbol n - 15; then n - 1 bits below
// the leading one and a sign bit, all equiprobable.
struct SignedModels {
  SymbolModel length;
  SymbolModel length_high;
};

// spec 7.5.3 the models of a PT stream; the split models live across all TSPL chunks.
struct PtContexts {
  SignedModels base_position[3];
  SignedModels base_field[kMaxTetFields];
  BitModel base_new_vertex[4];
  pm::IntegerModels base_back_reference;

  BitModel group_flag[2];              // by the batch's previous group flag
  BitModel split_flag[kFlagContexts];  // by min(tets of the vertex / 2, 15)
  SymbolModel cut_start;               // c_0 of an interior vertex's cut
  SymbolModel cut_first[kDegreeContexts];
  SymbolModel turn[kDegreeContexts];
  SymbolModel path_start;  // p_0 of a boundary vertex's cut
  SymbolModel path_first[kDegreeContexts];
  pm::IntegerModels escape;  // values of 15 and more
  SignedModels position[3];
  SignedModels field[kMaxTetFields];
};

template <class Coder>
void codeSigned(Coder& coder, SignedModels& m, int32_t* value) {
  uint32_t magnitude = 0;
  int n = 0;
  if (Coder::kEncoding) {
    magnitude = *value < 0 ? 0u - static_cast<uint32_t>(*value) : static_cast<uint32_t>(*value);
    while ((magnitude >> n) != 0) ++n;
  }
  const int low_length = coder.symbol(&m.length, std::min(n, 15));
  n = low_length < 15 ? low_length : 15 + coder.symbol(&m.length_high, Coder::kEncoding ? n - 15 : 0);
  if (n == 0) {
    *value = 0;
    return;
  }
  const uint32_t low = n > 1 ? coder.direct(magnitude & ((1u << (n - 1)) - 1), n - 1) : 0;
  magnitude = (1u << (n - 1)) | low;
  const int negative = static_cast<int>(coder.direct(Coder::kEncoding && *value < 0 ? 1 : 0, 1));
  *value = negative ? -static_cast<int32_t>(magnitude) : static_cast<int32_t>(magnitude);
}

// spec 7.5.2 a small unsigned value: one symbol, or 15 and unsigned() (6.5.1)
// of the rest. False when the escape's length prefix reaches 31 bits.
template <class Coder>
bool codeSmall(Coder& coder, SymbolModel& model, pm::IntegerModels& escape, uint32_t* value) {
  const int s = coder.symbol(&model, Coder::kEncoding ? static_cast<int>(std::min<uint32_t>(*value, 15)) : 0);
  if (s < 15) {
    *value = static_cast<uint32_t>(s);
    return true;
  }
  uint32_t rest = Coder::kEncoding ? *value - 15 : 0;
  if (!pm::codeUnsigned(coder, escape, &rest)) return false;
  if (rest > UINT32_MAX - 15) return false;
  *value = 15 + rest;
  return true;
}

inline int degreeContext(size_t degree) { return static_cast<int>(std::min<size_t>(degree, kDegreeContexts - 1)); }

inline uint32_t indexIn(const std::vector<uint32_t>& list, uint32_t value) {
  return static_cast<uint32_t>(std::find(list.begin(), list.end(), value) - list.begin());
}
// The same among the first n entries (n when absent).
inline uint32_t indexIn(const std::vector<uint32_t>& list, uint32_t n, uint32_t value) {
  return static_cast<uint32_t>(std::find(list.begin(), list.begin() + n, value) - list.begin());
}

// spec 7.7.2 cut(): the walk through the link of vs, as local link vertices.
// Encoding: `walk` and `closed` hold the cut to code, with its first vertex
// chosen by the caller. LinkT: Link (the encoder) or StarLink (the decoder),
// which answer alike. Returns "" or the rule broken.
template <class Coder, class LinkT>
std::string codeCut(Coder& coder, PtContexts& ctx, const LinkT& link, SplitScratch* s, std::vector<uint32_t>* walk,
                    bool* closed) {
  const uint32_t m = static_cast<uint32_t>(link.vertices.size());
  std::vector<uint32_t>& w = *walk;
  std::vector<uint32_t> given;
  if (Coder::kEncoding) given = w;
  w.clear();
  zeroedPrefix(&s->walk_position, m);
  auto visit = [&](uint32_t v) {
    s->walk_position[v] = 1;
    w.push_back(v);
  };
  // The vertex after `at` on the cut being encoded (the first again when closed).
  auto givenNext = [&](size_t at) { return at + 1 < given.size() ? given[at + 1] : given[0]; };
  uint32_t first, prev, cur;
  if (!link.has_boundary) {
    uint32_t c0 = Coder::kEncoding ? given[0] : 0;
    if (Coder::kEncoding && c0 >= m) return "the cut is not a walk in the link";
    if (!codeSmall(coder, ctx.cut_start, ctx.escape, &c0)) return "cut_start: length prefix of 31 bits";
    if (c0 >= m) return "cut_start " + std::to_string(c0) + " is not below the link's " + std::to_string(m) + " vertices";
    c0 = link.localOfRank(c0);  // the c0-th smallest vertex number
    const uint32_t d0 = link.rotationFromLowestInto(c0, &s->rotation);
    if (d0 == 0) return "the link is not a manifold at c_0";
    uint32_t j = Coder::kEncoding ? indexIn(s->rotation, d0, given[1]) : 0;
    if (Coder::kEncoding && (given.size() < 3 || j == d0)) return "the cut is not a walk in the link";
    if (!codeSmall(coder, ctx.cut_first[degreeContext(d0)], ctx.escape, &j))
      return "cut_first: length prefix of 31 bits";
    if (j >= d0) return "cut_first " + std::to_string(j) + " is not below the degree of c_0";
    visit(c0);
    first = c0;
    prev = c0;
    cur = s->rotation[j];
  } else {
    link.boundaryVertices(&s->queue);  // ascending vertex numbers
    uint32_t b = Coder::kEncoding ? indexIn(s->queue, given[0]) : 0;
    if (Coder::kEncoding && b == s->queue.size()) return "the cut is not a walk in the link";
    if (!codeSmall(coder, ctx.path_start, ctx.escape, &b)) return "path_start: length prefix of 31 bits";
    if (b >= s->queue.size())
      return "path_start " + std::to_string(b) + " is not below the link's " + std::to_string(s->queue.size()) +
             " boundary vertices";
    const uint32_t p0 = s->queue[b];
    if (!link.rotation(p0, 0, &s->rotation)) return "the link is not a manifold at p_0";
    const uint32_t d = static_cast<uint32_t>(s->rotation.size());
    if (d < 3) return "p_0 has no interior edge in the link";
    uint32_t t1 = Coder::kEncoding ? indexIn(s->rotation, given[1]) - 1 : 0;
    if (Coder::kEncoding && (given.size() < 2 || t1 + 1 == 0 || t1 + 1 >= d)) return "the cut is not a walk in the link";
    if (!codeSmall(coder, ctx.path_first[degreeContext(d)], ctx.escape, &t1)) return "path_first: length prefix of 31 bits";
    if (t1 > d - 3) return "path_first " + std::to_string(t1) + " is above " + std::to_string(d - 3);
    visit(p0);
    first = p0;
    prev = p0;
    cur = s->rotation[t1 + 1];
  }
  // spec 7.7.2 turns: from each vertex reached, the next one is t steps
  // around it from the one before, 1 <= t <= degree - 1.
  while (true) {
    if (cur == first) {
      if (link.has_boundary) return "the path returns to p_0";
      *closed = true;
      return w.size() >= 3 ? "" : "the cycle has fewer than 3 vertices";
    }
    if (s->walk_position[cur]) return "the cut visits link vertex " + std::to_string(link.vertices[cur]) + " twice";
    visit(cur);
    if (link.has_boundary && link.on_boundary[cur]) {
      *closed = false;
      return "";
    }
    if (w.size() > m) return "the cut is longer than the link";
    const uint32_t deg = link.rotationInto(cur, prev, &s->rotation);
    if (deg == 0) return "the link is not a manifold along the cut";
    if (Coder::kEncoding && w.size() >= given.size() + (link.has_boundary ? 0 : 1)) return "the cut is not a walk in the link";
    uint32_t t = Coder::kEncoding ? indexIn(s->rotation, deg, givenNext(w.size() - 1)) - 1 : 0;
    if (Coder::kEncoding && (t + 1 == 0 || t + 1 >= deg)) return "the cut is not a walk in the link";
    if (!codeSmall(coder, ctx.turn[degreeContext(deg)], ctx.escape, &t)) return "turn: length prefix of 31 bits";
    if (t + 1 >= deg) return "turn " + std::to_string(t) + " is not below degree - 1 = " + std::to_string(deg - 1);
    prev = cur;
    cur = s->rotation[t + 1];
  }
}

// spec 7.7.3: the prediction of vt's value from the cut: twice the mean of
// the cut's values minus vs's, in [0, 2^bits). Exact integers.
inline int32_t predictFromCut(int64_t cut_sum, uint32_t cut_length, int32_t at_vs, int bits) {
  const int64_t p = (2 * cut_sum) / cut_length - at_vs;
  return static_cast<int32_t>(std::clamp<int64_t>(p, 0, (int64_t{1} << bits) - 1));
}

// spec 7.7 the geometry of a split: vt's position and field values, coded as
// differences from their predictions. Returns "" or the rule broken.
template <class Coder>
std::string codeSplitValues(Coder& coder, PtContexts& ctx, const PtHeader& h, const TetComplex& mesh, uint32_t vs,
                            const uint32_t* cut, uint32_t cut_length, Point3i* position, int32_t* fields) {
  for (int a = 0; a < 3; ++a) {
    int64_t sum = 0;
    for (uint32_t i = 0; i < cut_length; ++i) sum += mesh.positions[cut[i]][a];
    const int32_t predicted = predictFromCut(sum, cut_length, mesh.positions[vs][a], h.position_bits);
    int32_t d = Coder::kEncoding ? (*position)[a] - predicted : 0;
    codeSigned(coder, ctx.position[a], &d);
    const int64_t q = int64_t{predicted} + d;
    if (q < 0 || q >= (int64_t{1} << h.position_bits))
      return std::string("vt's ") + "xyz"[a] + " coordinate " + std::to_string(q) + " is outside [0, 2^position_bits)";
    (*position)[a] = static_cast<int32_t>(q);
  }
  const int fc = static_cast<int>(h.fields.size());
  for (int f = 0; f < fc; ++f) {
    int64_t sum = 0;
    for (uint32_t i = 0; i < cut_length; ++i) sum += mesh.scalars[size_t{cut[i]} * fc + f];
    const int32_t predicted = predictFromCut(sum, cut_length, mesh.scalars[size_t{vs} * fc + f], h.fields[f].bits);
    int32_t d = Coder::kEncoding ? fields[f] - predicted : 0;
    codeSigned(coder, ctx.field[f], &d);
    const int64_t q = int64_t{predicted} + d;
    if (q < 0 || q >= (int64_t{1} << h.fields[f].bits))
      return "vt's value of field " + std::to_string(f) + " is outside [0, 2^bits)";
    fields[f] = static_cast<int32_t>(q);
  }
  return "";
}

// spec 7.4 base_mesh(): positions and field values as differences from the
// previous vertex, then the tets' corners as new vertices or back references.
// `mesh` holds positions, scalars and tets on return (encoding: on entry).
template <class Coder>
std::string codeBaseMesh(Coder& coder, PtContexts& ctx, const PtHeader& h, TetComplex* mesh) {
  const int fc = static_cast<int>(h.fields.size());
  if (!Coder::kEncoding) {
    mesh->field_count = fc;
    mesh->position_bits = h.position_bits;  // every coordinate below is checked against it
    mesh->positions.assign(h.base_vertex_count, Point3i{0, 0, 0});
    mesh->scalars.assign(size_t{h.base_vertex_count} * fc, 0);
    mesh->tets.assign(h.base_tet_count, Tet{0, 0, 0, 0});
  }
  Point3i prev{0, 0, 0};
  std::vector<int32_t> prev_field(fc, 0);
  for (uint32_t v = 0; v < h.base_vertex_count; ++v) {
    // A decoder stops at the first byte wanted past the end (206).
    if (coder.overrun()) return "the coded data ends before the base mesh does";
    for (int a = 0; a < 3; ++a) {
      int32_t d = Coder::kEncoding ? mesh->positions[v][a] - prev[a] : 0;
      codeSigned(coder, ctx.base_position[a], &d);
      const int64_t q = int64_t{prev[a]} + d;
      if (q < 0 || q >= (int64_t{1} << h.position_bits))
        return "vertex " + std::to_string(v) + ": coordinate outside [0, 2^position_bits)";
      prev[a] = mesh->positions[v][a] = static_cast<int32_t>(q);
    }
    for (int f = 0; f < fc; ++f) {
      int32_t& value = mesh->scalars[size_t{v} * fc + f];
      int32_t d = Coder::kEncoding ? value - prev_field[f] : 0;
      codeSigned(coder, ctx.base_field[f], &d);
      const int64_t q = int64_t{prev_field[f]} + d;
      if (q < 0 || q >= (int64_t{1} << h.fields[f].bits))
        return "vertex " + std::to_string(v) + ": value of field " + std::to_string(f) + " outside [0, 2^bits)";
      prev_field[f] = value = static_cast<int32_t>(q);
    }
  }
  uint32_t used = 0;
  for (uint32_t t = 0; t < h.base_tet_count; ++t) {
    if (coder.overrun()) return "the coded data ends before the base mesh does";
    for (int j = 0; j < 4; ++j) {
      uint32_t& corner = mesh->tets[t][j];
      const int fresh = coder.bit(&ctx.base_new_vertex[j], Coder::kEncoding && corner == used);
      if (fresh) {
        if (used >= h.base_vertex_count) return "tet " + std::to_string(t) + " names more vertices than base_vertex_count";
        corner = used++;
      } else {
        uint32_t back = Coder::kEncoding ? used - 1 - corner : 0;
        if (!pm::codeUnsigned(coder, ctx.base_back_reference, &back))
          return "tet " + std::to_string(t) + ": back reference with a length prefix of 31 bits";
        if (back >= used) return "tet " + std::to_string(t) + ": back reference to a vertex not yet named";
        corner = used - 1 - back;
      }
    }
  }
  if (used != h.base_vertex_count)
    return "the tets name " + std::to_string(used) + " of the " + std::to_string(h.base_vertex_count) + " vertices";
  return "";
}

inline int flagContext(const TetComplex& mesh, uint32_t v) {
  return static_cast<int>(std::min<size_t>(mesh.incident.size(v) / 2, kFlagContexts - 1));
}

}  // namespace mrsv::pt
