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

// Floor division for a positive divisor (C++ rounds toward zero).
inline int64_t floorDivide(int64_t num, int64_t den) {
  int64_t q = num / den;
  return (num % den != 0 && num < 0) ? q - 1 : q;
}

// spec 6.7.3: a difference of coordinates reduced to 20 bits by floor
// division by a power of two (an arithmetic shift), for the arc normal.
static_assert((int64_t{-3} >> 1) == -2, "floor division by shifting needs an arithmetic right shift");
inline int normalDrop(int position_bits) { return position_bits > 20 ? position_bits - 20 : 0; }
inline void reducedEdge(const std::array<int32_t, 3>& w, const std::array<int32_t, 3>& p, int drop, int64_t* e) {
  for (int k = 0; k < 3; ++k) e[k] = (int64_t{w[k]} - p[k]) >> drop;
}
inline void addCross(const int64_t* e0, const int64_t* e1, std::array<int64_t, 3>* n) {
  (*n)[0] += e0[1] * e1[2] - e0[2] * e1[1];
  (*n)[1] += e0[2] * e1[0] - e0[0] * e1[2];
  (*n)[2] += e0[0] * e1[1] - e0[1] * e1[0];
}
// The sum halved (rounding down) until every component is below 2^30, so
// that no product of a prediction exceeds 62 bits.
inline void reduceNormal(std::array<int64_t, 3>* n) {
  while (std::max({std::abs((*n)[0]), std::abs((*n)[1]), std::abs((*n)[2])}) >= (int64_t{1} << 30))
    for (int64_t& c : *n) c >>= 1;
}

// spec 6.7.3: the arc normal, the sum over the faces F_a .. F_(a + count - 3)
// of the ring around `vs` of (w_i - vs) x (w_i+1 - vs), from reduced
// differences, then reduced. The arc has count - 2 faces (so for the faces vt
// takes, `count` is the number of vt's new neighbours). The encoder sums the
// same faces from its own face lists (pm_encode.cpp): the sum's order does
// not matter.
inline std::array<int64_t, 3> arcNormal(const std::vector<std::array<int32_t, 3>>& positions,
                                        const std::array<int32_t, 3>& vs, const CornerTable::Ring& ring,
                                        uint32_t a, uint32_t count, int position_bits) {
  const int drop = normalDrop(position_bits);
  const uint32_t d = static_cast<uint32_t>(ring.neighbours.size());
  std::array<int64_t, 3> n{0, 0, 0};
  if (count < 3) return n;
  int64_t e0[3], e1[3];
  uint32_t at = a;
  reducedEdge(positions[ring.neighbours[at]], vs, drop, e0);
  for (uint32_t i = 0; i + 2 < count; ++i) {
    at = at + 1 == d ? 0 : at + 1;
    reducedEdge(positions[ring.neighbours[at]], vs, drop, e1);
    addCross(e0, e1, &n);
    for (int k = 0; k < 3; ++k) e0[k] = e1[k];
  }
  reduceNormal(&n);
  return n;
}

// spec 6.7.3 step 1: the tangential part of a move of vs is coded in units of
// 2^shift, shift = max(0, floor(log2 L2) / 2 - move_detail) (integer halving),
// L2 the largest squared length of the edges w_i w_(i+1) of its faces; 0
// without detail or when the ring collapses to a point.
inline int moveShift(int64_t longest2, uint8_t move_detail) {
  if (move_detail == 0 || longest2 <= 0) return 0;
  const int log2_longest2 = 63 - __builtin_clzll(static_cast<uint64_t>(longest2));
  return std::max(0, log2_longest2 / 2 - int{move_detail});
}
inline int64_t squaredDistance(const std::array<int32_t, 3>& p, const std::array<int32_t, 3>& q) {
  int64_t sum = 0;
  for (int k = 0; k < 3; ++k) {
    const int64_t e = int64_t{p[k]} - q[k];
    sum += e * e;
  }
  return sum;
}
// L2 of a ring: its faces F_0 .. F_(d-1) (interior) or F_0 .. F_(d-2) (boundary).
inline int64_t longestFaceEdge2(const std::vector<std::array<int32_t, 3>>& positions, const CornerTable::Ring& ring) {
  const uint32_t d = static_cast<uint32_t>(ring.neighbours.size());
  const uint32_t faces = ring.boundary ? d - 1 : d;
  int64_t longest = 0;
  for (uint32_t i = 0; i < faces; ++i)
    longest = std::max(longest, squaredDistance(positions[ring.neighbours[i]],
                                                positions[ring.neighbours[i + 1 == d ? 0 : i + 1]]));
  return longest;
}

// The axis with the largest component of `normal` (the lowest on ties), or
// -1 when the normal is zero (no plane); spec 6.7.3.
inline int normalAxis(const std::array<int64_t, 3>& normal) {
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(normal[k]) > std::abs(normal[axis])) axis = k;
  return normal[axis] != 0 ? axis : -1;
}

// The other two axes of `axis`, in increasing order.
inline std::array<int, 2> otherAxes(int axis) { return {axis == 0 ? 1 : 0, axis == 2 ? 1 : 2}; }

// spec 6.7.3: the offset along `axis` that puts a point on the plane with
// `normal` through the origin, given its offsets along the other two axes,
// rounded: floor((2A + |n|) / (2|n|)), A = -(sum of n_i x offset_i), negated
// when n < 0. Offsets below 2^31 and components below 2^30, whose largest is
// n_axis, keep 2A below 2^63.
inline int64_t offsetOnPlane(const std::array<int64_t, 3>& normal, int axis, const int64_t offset[3]) {
  int64_t along = 0;
  for (int k : otherAxes(axis)) along -= normal[k] * offset[k];
  const int64_t n = normal[axis];
  if (n < 0) along = -along;
  return floorDivide(2 * along + std::abs(n), 2 * std::abs(n));
}

// One coordinate of vt: `predicted` plus a signed residual, in [0, 2^bits).
template <class Coder>
bool codePosition(Coder& coder, IntegerModels& m, int32_t predicted, int bits, int32_t* value) {
  int32_t residual = *value - predicted;
  if (!codeSigned(coder, m, &residual)) return false;
  const int64_t q = int64_t{predicted} + residual;
  if (q < 0 || q >= (int64_t{1} << bits)) return false;
  *value = static_cast<int32_t>(q);
  return true;
}

// spec 6.7.2: the face F_i of an interior ring with the largest
// |w_i - vs|^2 + |w_i+1 - vs|^2 (the first such i); at most 62 bits.
inline uint32_t widestFace(const std::vector<std::array<int32_t, 3>>& positions,
                           const std::array<int32_t, 3>& vs, const CornerTable::Ring& ring) {
  const uint32_t d = static_cast<uint32_t>(ring.neighbours.size());
  const auto squared = [&](uint32_t i) { return squaredDistance(positions[ring.neighbours[i]], vs); };
  uint32_t widest = 0;
  int64_t best = -1, previous = squared(0);
  for (uint32_t i = 0; i < d; ++i) {
    const int64_t next = squared(i + 1 == d ? 0 : i + 1);
    if (previous + next > best) best = previous + next, widest = i;
    previous = next;
  }
  return widest;
}

// spec 6.7: one vertex split of the batch at `batch`.
template <class Coder>
std::string codeSplit(Coder& coder, PmContexts& ctx, ProgressiveMesh::Impl& s, BatchCursor* batch,
                      SplitRecord* r) {
  const PmHeader& h = s.header;
  // spec 6.7.1: vs is the first vertex after prev_vs, not locked, whose split
  // flag is 1. Each flag costs coded data (at least about 1/360 of a byte),
  // so a hostile stream cannot make this walk much longer than its payload.
  uint32_t vs = static_cast<uint32_t>(batch->prev_vs + 1);
  for (;; ++vs) {
    if (vs >= batch->start)
      return "no split vertex among the " + std::to_string(batch->start) +
             " vertices of the mesh at the start of the batch";
    if (s.lock_stamp[vs] == batch->stamp) {
      if (Coder::kEncoding && vs == r->vs)
        return "split vertex " + std::to_string(vs) + " neighbours an earlier split of its batch";
      continue;
    }
    if (coder.bit(&ctx.split_flag[s.flag_context[vs]], Coder::kEncoding && vs == r->vs)) break;
    if (coder.overrun()) return "coded data ends inside a vertex split (truncated record)";
  }
  r->vs = vs;
  batch->prev_vs = vs;
  // The encoder has found vs's ring already: it names vl and vr by it.
  const CornerTable::Ring& ring = s.ring;
  if (!Coder::kEncoding) s.findRing(r->vs);
  const uint32_t d = static_cast<uint32_t>(ring.neighbours.size());
  if (d > kMaxRingSize)
    return "split vertex " + std::to_string(vs) + " has " + std::to_string(d) +
           " neighbours, more than 1024";
  // Its neighbours are locked at the end of the record; their marks are
  // asked into cache now.
  for (uint32_t w : ring.neighbours)
    if (w < batch->start) __builtin_prefetch(&s.lock_stamp[w]);
  // spec 6.7.2 ring positions.
  if (!ring.boundary) {
    // vt's old faces are the stretched ones after its collapse: a is coded
    // as its distance back from the face whose corners lie farthest from vs.
    const uint32_t widest = widestFace(s.positions, s.positions[r->vs], ring);
    uint32_t back = Coder::kEncoding ? (widest + d - r->a) % d : 0;
    if (!codeUnsigned(coder, ctx.arc_start[std::min<uint32_t>(d, kTurnContexts - 1)], &back))
      return "the ring start is too long";
    if (back >= d)
      return "ring start " + std::to_string(back) + " back from the widest face, beyond a ring of " +
             std::to_string(d);
    r->a = (widest + d - back) % d;
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
    // The move of vs is mostly along the faces it keeps (both its positions
    // lie on the surface), so the axis nearest their plane's normal is
    // predicted from the plane once the other two are known, as vt's is.
    const uint32_t kept_count = ring.boundary ? d + 1 : (r->a + d - r->b) % d + 2;
    const std::array<int64_t, 3> kept_normal =
        arcNormal(s.positions, s.positions[r->vs], ring, ring.boundary ? 0 : r->b, kept_count, h.position_bits);
    const int plane_axis = normalAxis(kept_normal);
    const int axis = plane_axis < 0 ? 2 : plane_axis;
    // Along the plane, the move is coded in units of 2^shift, which grow
    // with the ring: the surface hardly changes when a vertex slides a
    // fraction of an edge along it, and the encoder places vs on that grid.
    // A flag lets the encoder keep every step where sliding would take vs off
    // the planes of its triangles (a crease, a curved fan).
    const std::array<int, 2> along = otherAxes(axis);
    int shift = h.move_detail ? moveShift(longestFaceEdge2(s.positions, ring), h.move_detail) : 0;
    if (shift > 0) {
      const int32_t mask = (int32_t{1} << shift) - 1;
      if (coder.bit(&ctx.move_fine,
                    Coder::kEncoding && ((r->vs_move[along[0]] & mask) | (r->vs_move[along[1]] & mask)) != 0))
        shift = 0;
    }
    int64_t move[3] = {0, 0, 0};
    for (int t = 0; t < 2; ++t) {
      const int k = along[t];
      int32_t units = r->vs_move[k] >> shift;
      if (!codeSigned(coder, ctx.vs_move[t], &units)) return "a vs move is too long";
      move[k] = int64_t{units} * (int64_t{1} << shift);
      if (std::abs(move[k]) >= (int64_t{1} << 30)) return "a vs move is too long";
    }
    const int64_t predicted = plane_axis < 0 ? 0 : offsetOnPlane(kept_normal, axis, move);
    const int64_t wanted = Coder::kEncoding ? r->vs_move[axis] - predicted : 0;
    if (std::abs(wanted) >= (int64_t{1} << 30)) return "a vs move is too long";
    int32_t residual = static_cast<int32_t>(wanted);
    if (!codeSigned(coder, ctx.vs_move[2], &residual)) return "a vs move is too long";
    move[axis] = predicted + residual;
    for (int k = 0; k < 3; ++k) {
      const int64_t q = int64_t{s.positions[r->vs][k]} + move[k];
      if (q < 0 || q >= limit) return "vs moves outside [0, 2^position_bits)";
      r->vs_move[k] = static_cast<int32_t>(move[k]);
    }
  }
  // vt's neighbours after the split: w_a .. w_b and vs (moved), `count` of
  // them; the two axes along vt's plane are predicted by their centroid.
  const uint32_t count = (ring.boundary ? r->b - r->a : (r->b + d - r->a) % d) + 2;
  // Ring positions a, a + 1, ... (mod d) without a division per step.
  const auto next = [d](uint32_t at) { return at + 1 == d ? 0 : at + 1; };
  std::array<int32_t, 3> vs_position = s.positions[r->vs];
  if (h.placement == kPlacementFree)
    for (int k = 0; k < 3; ++k) vs_position[k] += r->vs_move[k];
  int64_t sum[3] = {vs_position[0], vs_position[1], vs_position[2]};
  for (uint32_t i = 0, at = r->a; i + 1 < count; ++i, at = next(at))
    for (int k = 0; k < 3; ++k) sum[k] += s.positions[ring.neighbours[at]][k];
  int32_t centroid[3];
  for (int k = 0; k < 3; ++k) centroid[k] = static_cast<int32_t>((sum[k] + count / 2) / count);
  // spec 6.7.3: vt lies close to the plane of the faces it takes from vs
  // (the cheapest collapses are the flattest), so the axis closest to that
  // plane's normal is predicted from the plane once the other two are known.
  const std::array<int64_t, 3> normal =
      arcNormal(s.positions, vs_position, ring, r->a, count, h.position_bits);
  const int plane_axis = normalAxis(normal);
  const int normal_axis = plane_axis < 0 ? 2 : plane_axis;
  for (int t = 0; t < 2; ++t) {
    const int k = otherAxes(normal_axis)[t];
    if (!codePosition(coder, ctx.tangent_position[t], centroid[k], h.position_bits, &r->vt_position[k]))
      return "vt lies outside [0, 2^position_bits) or its residual is too long";
  }
  int32_t predicted = centroid[normal_axis];
  if (plane_axis >= 0) {
    // (vt - vs) . normal = 0, solved for the normal axis, rounded, clamped.
    int64_t offset[3];
    for (int k = 0; k < 3; ++k) offset[k] = int64_t{r->vt_position[k]} - vs_position[k];
    const int64_t step = offsetOnPlane(normal, normal_axis, offset);
    const int64_t top = (int64_t{1} << h.position_bits) - 1;
    predicted = static_cast<int32_t>(std::clamp<int64_t>(vs_position[normal_axis] + step, 0, top));
  }
  if (!codePosition(coder, ctx.normal_position, predicted, h.position_bits, &r->vt_position[normal_axis]))
    return "vt lies outside [0, 2^position_bits) or its residual is too long";
  if (h.scalar_bits) {
    // The scalar: the rounded mean of the same neighbours' scalars.
    int64_t scalar_sum = s.scalars[r->vs];
    for (uint32_t i = 0, at = r->a; i + 1 < count; ++i, at = next(at))
      scalar_sum += s.scalars[ring.neighbours[at]];
    const int32_t predicted = static_cast<int32_t>((scalar_sum + count / 2) / count);
    int32_t residual = r->vt_scalar - predicted;
    if (!codeSigned(coder, ctx.scalar, &residual)) return "a scalar residual is too long";
    int64_t q = int64_t{predicted} + residual;
    if (q < 0 || q >= (int64_t{1} << h.scalar_bits)) return "vt's scalar lies outside [0, 2^scalar_bits)";
    r->vt_scalar = static_cast<int32_t>(q);
  }
  if (coder.overrun()) return "coded data ends inside a vertex split (truncated record)";
  for (uint32_t w : ring.neighbours)
    if (w > r->vs && w < batch->start) s.lock_stamp[w] = batch->stamp;
  // spec 6.7.1: the neighbour counts after the split. vs keeps w_b .. w_a
  // (less w_a without G1, less w_b without G2) and gains vt, so it loses the
  // k - 1 neighbours strictly between w_a and w_b (k = count - 2 = b - a,
  // modulo d); w_a and w_b gain vt if its face with vs is added; vt has
  // `count` neighbours.
  const uint32_t taken = count - 2;
  const uint32_t without = (r->shape.has_g1 ? 0 : 1) + (r->shape.has_g2 ? 0 : 1);
  std::vector<uint8_t>& context = s.flag_context;
  context[r->vs] = s.flagContext(d - taken + 2 - without);
  const auto gain = [&](uint32_t w) { context[w] = s.flagContext(context[w] + 1u); };
  if (r->shape.has_g1) gain(ring.neighbours[r->a]);
  if (r->shape.has_g2) gain(ring.neighbours[r->b]);
  context.push_back(s.flagContext(count));
  return "";
}

}  // namespace mrsv::pm
