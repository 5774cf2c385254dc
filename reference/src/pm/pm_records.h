// spec: 6.4 base_mesh() and 6.7 vertex_split(): the records of the PM stream,
// written once over the coder (decoding is normative; the encoder runs the
// same code with the values it chose). Each function returns "" or the rule
// broken; in decoding mode it also applies what it decoded to the state.
#pragma once

#include <algorithm>
#include <string>

#include "mrsv/limits.h"
#include "pm/pm_coding.h"
#include "pm/pm_state.h"

namespace mrsv::pm {

inline uint32_t zigzag(int32_t v) { return v < 0 ? 2u * static_cast<uint32_t>(-(v + 1)) + 1 : 2u * v; }
inline int32_t unzigzag(uint32_t u) {
  return (u & 1) ? -static_cast<int32_t>(u >> 1) - 1 : static_cast<int32_t>(u >> 1);
}

// spec 6.4: base vertices (positions as differences to the previous vertex,
// scalars likewise) then triangles (each corner a new vertex, or a back
// reference to one already used). `triangles` is filled in decoding mode.
template <class Coder>
std::string codeBaseMesh(Coder& coder, PmContexts& ctx, ProgressiveMesh::Impl& s,
                         std::vector<std::array<uint32_t, 3>>* triangles) {
  const PmHeader& h = s.header;
  const int32_t limit = int32_t{1} << h.position_bits;
  const int32_t scalar_limit = int32_t{1} << h.scalar_bits;
  if (!Coder::kEncoding) {
    s.positions.assign(h.base_vertex_count, {0, 0, 0});
    if (h.scalar_bits) s.scalars.assign(h.base_vertex_count, 0);
  }
  std::array<int32_t, 3> last{0, 0, 0};
  int32_t last_scalar = 0;
  for (uint32_t v = 0; v < h.base_vertex_count; ++v) {
    for (int k = 0; k < 3; ++k) {
      int32_t delta = s.positions[v][k] - last[k];
      if (!codeSigned(coder, ctx.base_position[k], &delta)) return "a base position difference is too long";
      int64_t q = int64_t{last[k]} + delta;
      if (q < 0 || q >= limit)
        return "base vertex " + std::to_string(v) + " lies outside [0, 2^position_bits)";
      s.positions[v][k] = last[k] = static_cast<int32_t>(q);
    }
    if (h.scalar_bits) {
      int32_t delta = s.scalars[v] - last_scalar;
      if (!codeSigned(coder, ctx.base_scalar, &delta)) return "a base scalar difference is too long";
      int64_t q = int64_t{last_scalar} + delta;
      if (q < 0 || q >= scalar_limit)
        return "base scalar " + std::to_string(v) + " lies outside [0, 2^scalar_bits)";
      s.scalars[v] = last_scalar = static_cast<int32_t>(q);
    }
    if (coder.overrun()) return "coded data ends inside the base vertices";
  }
  if (!Coder::kEncoding) triangles->assign(h.base_triangle_count, {0, 0, 0});
  uint32_t used = 0;  // vertices 0 .. used-1 have appeared
  for (uint32_t t = 0; t < h.base_triangle_count; ++t) {
    for (int k = 0; k < 3; ++k) {
      uint32_t v = (*triangles)[t][k];
      int is_new = coder.bit(&ctx.base_new_vertex[k], Coder::kEncoding && v == used);
      if (is_new) {
        if (used == h.base_vertex_count)
          return "triangle " + std::to_string(t) + " introduces more than base_vertex_count vertices";
        v = used++;
      } else {
        uint32_t back = Coder::kEncoding ? used - 1 - v : 0;
        if (!codeUnsigned(coder, ctx.base_back_reference, &back) || back >= used)
          return "triangle " + std::to_string(t) + " refers to a vertex not yet introduced";
        v = used - 1 - back;
      }
      (*triangles)[t][k] = v;
    }
    if (coder.overrun()) return "coded data ends inside the base triangles";
  }
  if (used != h.base_vertex_count)
    return "the base triangles use " + std::to_string(used) + " of " +
           std::to_string(h.base_vertex_count) + " base vertices";
  return "";
}

// spec 6.7: one vertex split. `prev_vs` is the previous split vertex of this
// batch (or -1), `batch_start` the vertex count when the batch began.
template <class Coder>
std::string codeSplit(Coder& coder, PmContexts& ctx, ProgressiveMesh::Impl& s, uint32_t batch_start,
                      int64_t* prev_vs, SplitRecord* r) {
  const PmHeader& h = s.header;
  uint32_t gap = Coder::kEncoding ? static_cast<uint32_t>(r->vs - (*prev_vs + 1)) : 0;
  if (!codeUnsigned(coder, ctx.gap, &gap)) return "the vertex gap is too long";
  const int64_t vs = *prev_vs + 1 + int64_t{gap};
  if (vs >= batch_start)
    return "split vertex " + std::to_string(vs) + " is not a vertex of the mesh at the start of the batch (" +
           std::to_string(batch_start) + " vertices)";
  r->vs = static_cast<uint32_t>(vs);
  *prev_vs = vs;
  CornerTable::Ring& ring = s.ring;
  s.findRing(r->vs);
  const uint32_t d = static_cast<uint32_t>(ring.neighbours.size());
  if (d > kMaxRingSize)
    return "split vertex " + std::to_string(vs) + " has " + std::to_string(d) +
           " neighbours, more than 1024";
  // spec 6.7.2 ring positions.
  if (!ring.boundary) {
    r->a = codeTruncated(coder, d, r->a);
    const uint32_t half = d / 2;
    uint32_t k = (r->b + d - r->a) % d;
    uint32_t turn = Coder::kEncoding ? zigzag(static_cast<int32_t>(k) - static_cast<int32_t>(half)) : 0;
    if (!codeUnsigned(coder, ctx.turn[std::min<uint32_t>(d, kTurnContexts - 1)], &turn))
      return "the ring turn is too long";
    int64_t k_decoded = int64_t{half} + unzigzag(turn);
    if (k_decoded < 1 || k_decoded > int64_t{d} - 1)
      return "ring turn " + std::to_string(k_decoded) + " outside 1 to " + std::to_string(d - 1);
    r->b = static_cast<uint32_t>((r->a + k_decoded) % d);
    r->shape = {true, true};
  } else {
    // Both new faces (vt inside the fan), or only G2 (vt takes the first
    // faces) or only G1 (vt takes the last faces): spec 6.7.2.
    int on_edge = coder.bit(&ctx.boundary_kind[0], !(r->shape.has_g1 && r->shape.has_g2));
    if (!on_edge) {
      r->shape = {true, true};
      r->a = codeTruncated(coder, d - 1, r->a);
      uint32_t extra = Coder::kEncoding ? r->b - r->a - 1 : 0;
      if (!codeUnsigned(coder, ctx.fan_interior, &extra)) return "the fan position is too long";
      if (extra > d - 2 - r->a) return "split position b beyond the fan";
      r->b = r->a + 1 + extra;
    } else {
      int last = coder.bit(&ctx.boundary_kind[1], !r->shape.has_g2);
      uint32_t faces = Coder::kEncoding ? (last ? d - 1 - r->a : r->b) : 0;
      if (!codeUnsigned(coder, ctx.fan_faces, &faces)) return "the fan position is too long";
      if (faces > d - 1) return "the new vertex would take more faces than the fan has";
      if (!last) {
        r->shape = {false, true};
        r->a = 0;
        r->b = faces;
      } else {
        r->shape = {true, false};
        r->a = d - 1 - faces;
        r->b = d - 1;
      }
    }
  }
  if (!splitPositionsValid(ring.boundary, d, r->a, r->b, r->shape))
    return "ring positions " + std::to_string(r->a) + ", " + std::to_string(r->b) +
           " are not a valid split";
  // spec 6.7.3 geometry.
  const int32_t limit = int32_t{1} << h.position_bits;
  if (h.placement == kPlacementFree) {
    for (int k = 0; k < 3; ++k) {
      if (!codeSigned(coder, ctx.vs_move[k], &r->vs_move[k])) return "a vs move is too long";
      int64_t q = int64_t{s.positions[r->vs][k]} + r->vs_move[k];
      if (q < 0 || q >= limit) return "vs moves outside [0, 2^position_bits)";
    }
  }
  // vt's neighbours after the split: w_a .. w_b and vs (moved).
  const uint32_t count = (ring.boundary ? r->b - r->a : (r->b + d - r->a) % d) + 2;
  int64_t sum[3] = {0, 0, 0}, scalar_sum = 0;
  for (uint32_t i = 0, at = r->a; i + 1 < count; ++i, at = at + 1 == d ? 0 : at + 1) {  // at = (a + i) mod d
    uint32_t w = ring.neighbours[at];
    for (int k = 0; k < 3; ++k) sum[k] += s.positions[w][k];
    if (h.scalar_bits) scalar_sum += s.scalars[w];
  }
  for (int k = 0; k < 3; ++k)
    sum[k] += s.positions[r->vs][k] + (h.placement == kPlacementFree ? r->vs_move[k] : 0);
  if (h.scalar_bits) scalar_sum += s.scalars[r->vs];
  for (int k = 0; k < 3; ++k) {
    const int32_t predicted = static_cast<int32_t>((sum[k] + count / 2) / count);
    int32_t residual = r->vt_position[k] - predicted;
    if (!codeSigned(coder, ctx.position[k], &residual)) return "a position residual is too long";
    int64_t q = int64_t{predicted} + residual;
    if (q < 0 || q >= limit) return "vt lies outside [0, 2^position_bits)";
    r->vt_position[k] = static_cast<int32_t>(q);
  }
  if (h.scalar_bits) {
    const int32_t predicted = static_cast<int32_t>((scalar_sum + count / 2) / count);
    int32_t residual = r->vt_scalar - predicted;
    if (!codeSigned(coder, ctx.scalar, &residual)) return "a scalar residual is too long";
    int64_t q = int64_t{predicted} + residual;
    if (q < 0 || q >= (int64_t{1} << h.scalar_bits)) return "vt's scalar lies outside [0, 2^scalar_bits)";
    r->vt_scalar = static_cast<int32_t>(q);
  }
  if (coder.overrun()) return "coded data ends inside a vertex split (truncated record)";
  return "";
}

}  // namespace mrsv::pm
