#include "simplify/edge_topology.h"

#include <algorithm>

namespace mrsv::simplify {

bool EdgeTopology::build(const TriangleMesh& mesh, std::string* error) {
  const size_t num_vertices = mesh.positions.size();
  const size_t num_triangles = mesh.triangles.size();
  if (num_vertices >= kNone || num_triangles >= kNone / 3) {
    *error = "mesh too large for 32-bit half-edge indices";
    return false;
  }
  he_.assign(3 * num_triangles, HalfEdge{kNone, kNone});
  outgoing_.assign(num_vertices, kNone);
  live_triangles_ = num_triangles;
  for (size_t t = 0; t < num_triangles; ++t) {
    const auto& tri = mesh.triangles[t];
    for (int i = 0; i < 3; ++i) {
      if (tri[i] >= num_vertices) {
        *error = "triangle " + std::to_string(t) + " has a vertex index out of range";
        return false;
      }
      he_[3 * t + i].corner = tri[i];
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
      *error = "triangle " + std::to_string(t) + " repeats a vertex";
      return false;
    }
  }

  // Half-edges grouped by origin (counting sort), so that pairing a half-edge
  // with its opposite only scans the target's few outgoing half-edges.
  std::vector<uint32_t> first(num_vertices + 1, 0);
  for (const HalfEdge& e : he_) ++first[e.corner + 1];
  for (size_t v = 0; v < num_vertices; ++v) first[v + 1] += first[v];
  // (target, half-edge) pairs by origin, so the scans below stay within two
  // short contiguous lists instead of chasing he_.
  std::vector<std::pair<uint32_t, uint32_t>> by_origin(he_.size());
  {
    std::vector<uint32_t> fill(first.begin(), first.end() - 1);
    for (uint32_t h = 0; h < he_.size(); ++h) by_origin[fill[he_[h].corner]++] = {target(h), h};
  }
  for (uint32_t u = 0; u < num_vertices; ++u) {
    for (uint32_t k = first[u]; k < first[u + 1]; ++k) {
      const auto [w, h] = by_origin[k];
      for (uint32_t j = first[u]; j < k; ++j) {
        if (by_origin[j].first == w) {
          *error = "edge " + std::to_string(u) + "-" + std::to_string(w) +
                   " is used twice in the same direction (inconsistent orientation or non-manifold edge)";
          return false;
        }
      }
      for (uint32_t j = first[w]; j < first[w + 1]; ++j) {
        if (by_origin[j].first == u) {
          he_[h].opposite = by_origin[j].second;
          break;
        }
      }
    }
  }
  boundary_.assign(num_vertices, 0);
  for (uint32_t v = 0; v < num_vertices; ++v) {
    if (first[v] == first[v + 1]) continue;  // unused vertex: stays dead
    settleOutgoing(v, by_origin[first[v]].second);
    boundary_[v] = he_[outgoing_[v]].opposite == kNone;
    uint32_t fan = 0;
    forEachOutgoing(v, [&](uint32_t) { ++fan; });
    if (fan != first[v + 1] - first[v]) {
      *error = "vertex " + std::to_string(v) + " is non-manifold (more than one fan of triangles)";
      return false;
    }
  }
  return true;
}

void EdgeTopology::settleOutgoing(uint32_t v, uint32_t any_outgoing) {
  // Clockwise (h -> next(opposite(h))) until the boundary or back to the start.
  uint32_t h = any_outgoing;
  for (;;) {
    const uint32_t o = he_[h].opposite;
    if (o == kNone) break;
    h = next(o);
    if (h == any_outgoing) break;
  }
  outgoing_[v] = h;
}

uint32_t EdgeTopology::findHalfEdge(uint32_t a, uint32_t b) const {
  uint32_t found = kNone;
  const uint32_t start = outgoing_[a];
  uint32_t h = start;
  do {
    if (target(h) == b) {
      found = h;
      break;
    }
    h = he_[prev(h)].opposite;
  } while (h != kNone && h != start);
  return found;
}

void EdgeTopology::collapse(uint32_t removed, uint32_t kept, uint32_t h) {
  const uint32_t twin = he_[h].opposite;
  const uint32_t h_rk = he_[h].corner == removed ? h : twin;  // removed -> kept, or kNone
  const uint32_t h_kr = he_[h].corner == removed ? twin : h;  // kept -> removed, or kNone

  // Every corner of `removed` becomes a corner of `kept` (the dying triangles'
  // too, which is harmless since they are cleared below).
  forEachOutgoing(removed, [&](uint32_t g) { he_[g].corner = kept; });

  auto glue = [&](uint32_t x, uint32_t y) {
    if (x != kNone) he_[x].opposite = y;
    if (y != kNone) he_[y].opposite = x;
  };
  auto kill = [&](uint32_t t) {
    for (int i = 0; i < 3; ++i) {
      he_[3 * t + i].corner = kNone;
      he_[3 * t + i].opposite = kNone;
    }
    --live_triangles_;
  };

  // A dying triangle with apex x leaves its edges kept-x and x-removed as one
  // edge kept-x: their outer half-edges become each other's opposite. Keep,
  // per dying triangle, one live outgoing half-edge of the apex and of `kept`
  // for afterwards (the link condition guarantees one exists).
  uint32_t apex[2] = {kNone, kNone};
  uint32_t apex_out[2] = {kNone, kNone};
  uint32_t kept_out = kNone;
  int side = 0;
  for (uint32_t g : {h_rk, h_kr}) {
    if (g == kNone) continue;
    const uint32_t n = next(g);
    const uint32_t p = prev(g);
    const uint32_t on = he_[n].opposite;
    const uint32_t op = he_[p].opposite;
    // For (removed, kept, x): on is x -> kept, op becomes kept -> x. For
    // (kept, removed, y): on becomes y -> kept, op is kept -> y. Either way on
    // leaves the apex and op leaves `kept`, and next() of one leaves the other.
    apex[side] = he_[p].corner;
    apex_out[side] = on != kNone ? on : next(op);
    if (kept_out == kNone) kept_out = op != kNone ? op : next(on);
    glue(on, op);
    ++side;
  }
  for (uint32_t g : {h_rk, h_kr}) {
    if (g != kNone) kill(triangleOf(g));
  }
  outgoing_[removed] = kNone;
  for (int s = 0; s < side; ++s) settleOutgoing(apex[s], apex_out[s]);
  settleOutgoing(kept, kept_out);
}

bool EdgeTopology::validate(std::string* error) const {
  const uint32_t nv = numVertices();
  std::vector<uint32_t> corners_of(nv, 0);
  for (uint32_t h = 0; h < he_.size(); ++h) {
    const uint32_t v = he_[h].corner;
    if (v == kNone) {
      if (he_[3 * triangleOf(h)].corner != kNone || he_[h].opposite != kNone) {
        *error = "half-edge " + std::to_string(h) + " of a dead triangle is partly alive";
        return false;
      }
      continue;
    }
    if (v >= nv || outgoing_[v] == kNone) {
      *error = "half-edge " + std::to_string(h) + " starts at a dead vertex";
      return false;
    }
    ++corners_of[v];
    if (v == target(h)) {
      *error = "triangle " + std::to_string(triangleOf(h)) + " is degenerate";
      return false;
    }
    const uint32_t o = he_[h].opposite;
    if (o != kNone) {
      if (o >= he_.size() || he_[o].opposite != h || he_[o].corner != target(h) ||
          target(o) != v || triangleOf(o) == triangleOf(h)) {
        *error = "half-edge " + std::to_string(h) + " is badly paired";
        return false;
      }
    }
  }
  uint64_t live = 0;
  for (uint32_t t = 0; t < numTriangles(); ++t) live += triangleAlive(t);
  if (live != live_triangles_) {
    *error = "live triangle count is stale";
    return false;
  }
  std::vector<uint32_t> neighbours;
  for (uint32_t v = 0; v < nv; ++v) {
    if (outgoing_[v] == kNone) {
      if (corners_of[v] != 0) {
        *error = "dead vertex " + std::to_string(v) + " is still used";
        return false;
      }
      continue;
    }
    if (he_[outgoing_[v]].corner != v) {
      *error = "vertex " + std::to_string(v) + " has a foreign outgoing half-edge";
      return false;
    }
    uint32_t fan = 0;
    bool boundary_seen = false;
    forEachOutgoing(v, [&](uint32_t h) {
      ++fan;
      boundary_seen |= he_[h].opposite == kNone;
    });
    if (fan != corners_of[v]) {
      *error = "vertex " + std::to_string(v) + " has more than one fan";
      return false;
    }
    if (boundary_seen != (he_[outgoing_[v]].opposite == kNone) || boundary_seen != (boundary_[v] != 0)) {
      *error = "vertex " + std::to_string(v) + " has a stale boundary flag or does not start its fan at the boundary";
      return false;
    }
    neighbours.clear();
    forEachNeighbour(v, [&](uint32_t w) { neighbours.push_back(w); });
    std::sort(neighbours.begin(), neighbours.end());
    if (std::adjacent_find(neighbours.begin(), neighbours.end()) != neighbours.end()) {
      *error = "vertex " + std::to_string(v) + " has a repeated neighbour (duplicate edge)";
      return false;
    }
  }
  return true;
}

void EdgeTopology::liveTriangleList(std::vector<std::array<uint32_t, 3>>* out) const {
  out->clear();
  for (uint32_t t = 0; t < numTriangles(); ++t) {
    if (triangleAlive(t)) out->push_back({he_[3 * t].corner, he_[3 * t + 1].corner, he_[3 * t + 2].corner});
  }
}

}  // namespace mrsv::simplify
