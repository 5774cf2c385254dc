// spec: 6.6 connectivity, vertex split and edge collapse.
#include "mesh/corner_table.h"

#include <algorithm>

namespace mrsv {

std::string CornerTable::build(uint32_t vertex_count,
                               const std::vector<std::array<uint32_t, 3>>& triangles) {
  const size_t corners = triangles.size() * 3;
  corners_.assign(corners, Corner{});
  vertex_corner_.assign(vertex_count, kNone);
  for (size_t f = 0; f < triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      uint32_t v = triangles[f][k];
      if (v >= vertex_count) return "triangle " + std::to_string(f) + " uses a vertex out of range";
      V(3 * f + k) = v;
    }
  for (size_t f = 0; f < triangles.size(); ++f) {
    const auto& t = triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      return "triangle " + std::to_string(f) + " repeats a vertex";
  }
  // Pair the two sides of every edge: sort the corners by the undirected edge they face.
  struct Side {
    uint64_t key;     // smaller vertex << 32 | larger vertex
    uint32_t corner;  // the corner facing this side
    bool forward;     // the face runs from the smaller to the larger vertex
  };
  std::vector<Side> sides(corners);
  for (uint32_t c = 0; c < corners; ++c) {
    uint32_t from = V(next(c)), to = V(prev(c));
    uint32_t lo = std::min(from, to), hi = std::max(from, to);
    sides[c] = {uint64_t{lo} << 32 | hi, c, from < to};
  }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return x.key != y.key ? x.key < y.key : x.corner < y.corner;
  });
  for (size_t i = 0; i < sides.size();) {
    size_t j = i;
    while (j < sides.size() && sides[j].key == sides[i].key) ++j;
    const std::string edge = "edge (" + std::to_string(sides[i].key >> 32) + ", " +
                             std::to_string(sides[i].key & 0xFFFFFFFFu) + ")";
    if (j - i > 2) return edge + " has more than two triangles (non-manifold edge)";
    if (j - i == 2) {
      if (sides[i].forward == sides[i + 1].forward)
        return edge + " is run in the same direction by two triangles (inconsistent orientation)";
      link(sides[i].corner, sides[i + 1].corner);
    }
    i = j;
  }
  // One fan per vertex: the faces reached by swinging around v are all of its faces.
  std::vector<uint32_t> uses(vertex_count, 0);
  for (uint32_t c = 0; c < corners; ++c) {
    ++uses[V(c)];
    vertex_corner_[V(c)] = c;
  }
  for (uint32_t v = 0; v < vertex_count; ++v) {
    if (uses[v] == 0) return "vertex " + std::to_string(v) + " is used by no triangle";
    resetVertexCorner(v, vertex_corner_[v]);
    uint32_t c = vertex_corner_[v], count = 0;
    do {
      ++count;
      uint32_t across = O(next(c));
      if (across == kNone) break;
      c = next(across);
    } while (c != vertex_corner_[v] && count <= uses[v]);
    if (count != uses[v])
      return "vertex " + std::to_string(v) + " joins more than one fan of triangles (non-manifold vertex)";
  }
  return "";
}

void CornerTable::resetVertexCorner(uint32_t v, uint32_t corner) {
  // Clockwise until the boundary or back at the start; the step cap only
  // guards against a corrupted table (build() and split() never make one).
  uint32_t c = corner;
  const size_t cap = corners_.size();
  for (size_t steps = 0; steps < cap; ++steps) {
    uint32_t across = O(prev(c));
    if (across == kNone) break;
    uint32_t before = prev(across);
    if (before == corner) break;
    c = before;
  }
  vertex_corner_[v] = c;
}

void CornerTable::ring(uint32_t v, Ring* out) const {
  out->neighbours.clear();
  out->corners.clear();
  const uint32_t start = vertex_corner_[v];
  out->boundary = O(prev(start)) == kNone;
  if (out->boundary) {
    // Counter-clockwise from the first face of the fan (VC) to the last: each
    // face's corner at v and the neighbour it starts at, then the last
    // neighbour, across v's incoming boundary edge.
    uint32_t c = start;
    while (true) {
      out->corners.push_back(c);
      out->neighbours.push_back(V(next(c)));
      uint32_t across = O(next(c));
      if (across == kNone) break;
      c = next(across);
    }
    out->neighbours.push_back(V(prev(c)));
    return;
  }
  // Interior. First find the face F_0, whose first neighbour is the smallest
  // (spec 6.6.1): walk both ways from VC until the two walks meet. Each step
  // depends on the face read by the step before (usually a cache miss on a
  // large mesh), and the two walks do not depend on each other, so the
  // processor runs them side by side: half the waiting of one walk around.
  uint32_t forward = start, backward = start;  // the last face each walk reached
  uint32_t first = start, smallest = V(next(start));
  auto consider = [&](uint32_t c) {
    const uint32_t w = V(next(c));
    if (w < smallest) smallest = w, first = c;
  };
  while (true) {
    forward = next(O(next(forward)));  // the next face counter-clockwise
    if (forward == backward) break;
    consider(forward);
    backward = prev(O(prev(backward)));  // the next face clockwise
    if (backward == forward) break;
    consider(backward);
  }
  // Then list the ring counter-clockwise from F_0; its faces are in cache now.
  uint32_t c = first;
  do {
    out->corners.push_back(c);
    out->neighbours.push_back(V(next(c)));
    c = next(O(next(c)));
  } while (c != first);
}

bool splitPositionsValid(bool boundary, uint32_t d, uint32_t a, uint32_t b,
                         CornerTable::SplitShape shape) {
  if (!boundary) return d >= 3 && a < d && b < d && a != b && shape.has_g1 && shape.has_g2;
  // A fan of d neighbours has d - 1 faces; vt takes faces a .. b-1.
  if (d < 2 || a > b || b > d - 1) return false;
  if (shape.has_g1 && shape.has_g2) return a < b;  // a = b: two faces on the same three vertices
  if (shape.has_g2) return a == 0;                 // vt takes the first faces
  if (shape.has_g1) return b == d - 1;             // vt takes the last faces
  return false;                                    // vs would keep no face
}

void CornerTable::split(uint32_t vs, const Ring& ring, uint32_t a, uint32_t b, SplitShape shape) {
  const uint32_t d = static_cast<uint32_t>(ring.neighbours.size());
  const uint32_t faces = static_cast<uint32_t>(ring.corners.size());  // d, or d - 1 on the boundary
  const uint32_t vt = vertexCount();
  const uint32_t t = triangleCount();
  // Faces that move to vt: F_a .. F_(b-1), modulo d for an interior vs (a and
  // b are below d, so no division is needed to wrap).
  const uint32_t k = b >= a ? b - a : b + d - a;
  auto faceCorner = [&](uint32_t i) { return ring.corners[i]; };
  auto faceBefore = [&](uint32_t i) { return ring.corners[i > 0 ? i - 1 : faces - 1]; };
  // F_{a-1} and F_b exist unless the fan ends there.
  const bool has_before = !ring.boundary || a > 0;
  const bool has_after = !ring.boundary || b < d - 1;

  for (uint32_t i = 0, f = a; i < k; ++i, f = f + 1 == faces ? 0 : f + 1) V(faceCorner(f)) = vt;
  const uint32_t g1 = 3 * t, g2 = shape.has_g1 ? 3 * t + 3 : 3 * t;
  const uint32_t added = (shape.has_g1 ? 3 : 0) + (shape.has_g2 ? 3 : 0);
  corners_.resize(corners_.size() + added);
  const uint32_t wa = ring.neighbours[a], wb = ring.neighbours[b];
  if (shape.has_g1) {  // G1 = (vs, w_a, vt)
    V(g1) = vs;
    V(g1 + 1) = wa;
    V(g1 + 2) = vt;
    link(g1, k > 0 ? prev(faceCorner(a)) : kNone);
    link(g1 + 2, has_before ? next(faceBefore(a)) : kNone);  // F_{a-1}
    O(g1 + 1) = kNone;
  }
  if (shape.has_g2) {  // G2 = (vs, vt, w_b)
    V(g2) = vs;
    V(g2 + 1) = vt;
    V(g2 + 2) = wb;
    link(g2, k > 0 ? next(faceBefore(b)) : kNone);  // F_{b-1}
    link(g2 + 1, has_after ? prev(faceCorner(b)) : kNone);
    O(g2 + 2) = kNone;
  }
  if (shape.has_g1 && shape.has_g2) link(g1 + 1, g2 + 2);

  // VC: the first corner of each changed boundary fan (spec 6.6.1).
  vertex_corner_.push_back(shape.has_g1 ? g1 + 2 : k > 0 ? faceCorner(a) : g2 + 1);
  if (!ring.boundary) vertex_corner_[vs] = g1;
  else if (a == 0) vertex_corner_[vs] = shape.has_g1 ? g1 : g2;
  // A new outgoing boundary edge w_a -> vt or w_b -> vs starts that neighbour's fan.
  if (shape.has_g1 && O(g1) == kNone) vertex_corner_[wa] = g1 + 1;
  if (shape.has_g2 && O(g2 + 1) == kNone) vertex_corner_[wb] = g2 + 2;
}

void CornerTable::collapseLast(uint32_t vs, SplitShape shape) {
  const uint32_t t = triangleCount();
  const uint32_t added = (shape.has_g1 ? 1 : 0) + (shape.has_g2 ? 1 : 0);
  const uint32_t g1 = 3 * (t - added), g2 = shape.has_g1 ? g1 + 3 : g1;
  // A split leaves vs on the boundary exactly when it was there before, so
  // this tells what vs will be once the split is undone.
  const bool vs_on_boundary = isBoundary(vs);
  // Surviving corners of w_a and w_b: in F_{a-1} or F_a, in F_b or F_{b-1}.
  uint32_t keep_wa = kNone, keep_wb = kNone, keep_vs = kNone;
  if (shape.has_g1)
    keep_wa = O(g1 + 2) != kNone ? next(O(g1 + 2)) : next(next(O(g1)));
  if (shape.has_g2)
    keep_wb = O(g2 + 1) != kNone ? prev(O(g2 + 1)) : next(O(g2));
  if (shape.has_g1 && O(g1 + 2) != kNone) keep_vs = prev(O(g1 + 2));
  if (shape.has_g2 && O(g2 + 1) != kNone) keep_vs = next(O(g2 + 1));
  // vt's other faces lie between G1 and G2: walk them and give them back to vs.
  if (shape.has_g1) {
    uint32_t c = g1 + 2;
    while (true) {
      uint32_t across = O(next(c));
      if (across == kNone) break;
      c = next(across);
      if (shape.has_g2 && c == g2 + 1) break;
      V(c) = vs;
      keep_vs = c;
    }
  } else {
    uint32_t c = g2 + 1;
    while (true) {
      uint32_t across = O(prev(c));
      if (across == kNone) break;
      c = prev(across);
      V(c) = vs;
      keep_vs = c;
    }
  }
  if (shape.has_g1) link(O(g1), O(g1 + 2));
  if (shape.has_g2) link(O(g2), O(g2 + 1));
  corners_.resize(g1);
  vertex_corner_.pop_back();
  // An interior vertex may keep any of its corners in VC; only a boundary
  // fan has to be walked back to its first face.
  if (vs_on_boundary) resetVertexCorner(vs, keep_vs);
  else vertex_corner_[vs] = keep_vs;
  if (shape.has_g1 && vertex_corner_[V(keep_wa)] >= g1)
    resetVertexCorner(V(keep_wa), keep_wa);
  if (shape.has_g2 && vertex_corner_[V(keep_wb)] >= g1)
    resetVertexCorner(V(keep_wb), keep_wb);
}

std::vector<std::array<uint32_t, 3>> CornerTable::triangles() const {
  std::vector<std::array<uint32_t, 3>> out(triangleCount());
  for (uint32_t f = 0; f < out.size(); ++f)
    out[f] = {V(3 * f), V(3 * f + 1), V(3 * f + 2)};
  return out;
}

std::string CornerTable::validate() const {
  CornerTable fresh;
  std::string problem = fresh.build(vertexCount(), triangles());
  if (!problem.empty()) return problem;
  for (uint32_t c = 0; c < corners_.size(); ++c)
    if (fresh.O(c) != O(c)) return "opposite corners differ from a fresh build";
  for (uint32_t v = 0; v < vertexCount(); ++v) {
    uint32_t c = vertex_corner_[v];
    if (c >= corners_.size() || V(c) != v)
      return "VC of vertex " + std::to_string(v) + " is not one of its corners";
    if (fresh.isBoundary(v) != isBoundary(v))
      return "VC of boundary vertex " + std::to_string(v) + " is not the start of its fan";
  }
  return "";
}

}  // namespace mrsv
