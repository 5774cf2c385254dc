// Edge-collapse simplification: the first stage of the PM encoder (spec 6.9).
//
// The simplifier only decides WHICH half-edge collapses to make and in what
// order; the PM encoder (pm/pm_encode.cpp) replays them to write the stream.
// A half-edge collapse merges vertex `removed` into vertex `kept`; with
// Placement::kEndpoint `kept` keeps its position, with kFree it moves to
// `kept_position`. Collapses are grouped in batches: the collapses of one
// batch are independent (see SimplifyResult), so the decoder may undo them
// in any order, which is what makes the stream's vertex addressing cheap.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mrsv/mesh.h"

namespace mrsv {

enum class CollapseCost {
  kQuadric,  // Garland-Heckbert quadric error
  kPaper,    // Staadt-Gross section 6.1 / 7.1: normal, edge-length and equilateral energies
};

enum class Placement {
  kEndpoint,  // the kept vertex stays where it is (half-edge collapse)
  kFree,      // the kept vertex moves (volume-preserving quadric optimum near the edge)
};

struct SimplifyOptions {
  CollapseCost cost = CollapseCost::kQuadric;
  Placement placement = Placement::kEndpoint;
  // Weights of the paper's energies (section 7.1 preset: 50, 1, 5).
  double weight_normal = 50.0;
  double weight_edge_length = 1.0;
  double weight_equilateral = 5.0;
  // Stop when no more than this many triangles remain (0: as far as the
  // consistency rules allow).
  uint64_t target_triangles = 0;
  // Stop after this many seconds of collapsing (0: no limit); the result is
  // still complete and valid, only less simplified.
  double time_budget_seconds = 0.0;
  // Weight of the deviation guard (simplify/deviation_guard.h; quadric costs
  // only, 0 turns it off): a collapse costs at least this times its new fan's
  // area times the squared distances between the input and the new fan that
  // the quadric misses (spec decision D32).
  double deviation_weight = 0.3;
  // Called now and then with the fraction done, in [0, 1].
  std::function<void(double)> progress;
  // The batch rule: a batch takes, cheapest first, the consistent collapses
  // whose endpoints no earlier collapse of the batch has locked (locking both
  // endpoints and all their neighbours), as long as their cost is at most
  // batch_cost_ratio times the cheapest candidate's cost or within the
  // cheapest batch_min_fraction of the candidates, whichever reaches higher,
  // and at most batch_max_fraction of the live vertices. Larger batches make
  // the stream smaller; greedier ones make the result worse. Each batch scans
  // all live edges, so batches of one or two collapses make the run
  // quadratic. The quantile is there because memoryless costs have a long
  // tail near zero (flat spots): with the ratio alone, most batches took a
  // handful of near-free collapses. Measured on bunny, armadillo, horse and
  // turbine at 10 % and 1 % (spec decision D22): 0.05 needs 40 to 50 % fewer
  // batches than the ratio alone, with the same RMS error (geometric mean
  // within 1 %); 0.1 to 0.3 leave it within 3 %.
  double batch_cost_ratio = 8.0;
  double batch_min_fraction = 0.05;
  double batch_max_fraction = 1.0;
  // Once fewer than coarse_vertex_fraction of the input's vertices are left,
  // batches follow coarse_batch_cost_ratio and coarse_batch_min_fraction
  // instead: nearer the greedy order (spec decision D35). A level between
  // two batches decodes the later batch only in part, and in vertex order,
  // not cost order, so it may hold that batch's dearest collapses; at coarse
  // levels, where a collapse is a large part of the error, narrower batches
  // lowered the RMS error around 1 % of the faces by 3 to 4 % and the
  // Hausdorff distance by 12 to 25 % on three of the four test meshes (on
  // the fourth they rose 1 and 12 %), for endpoint streams about 1 % larger.
  double coarse_vertex_fraction = 0.05;
  double coarse_batch_cost_ratio = 2.0;
  double coarse_batch_min_fraction = 0.02;
  // While more than fine_vertex_fraction of the input's vertices are left,
  // batches follow fine_batch_cost_ratio and fine_batch_min_fraction
  // instead: wider (spec decision D37; 1, the default: never). Near full
  // resolution the collapses are many and each a small part of the error, so
  // their order matters little there, while every batch fewer saves split
  // flags, which cost about 4 bits per split with the default rule. From 0.3
  // (`mrsv encode --wide-batches 0.3`) the streams at 14 bits were 3 to 8 %
  // smaller (bunny flags 4.1 -> 3.0 bits per split) with the RMS error at
  // 10 % and 1 % of the faces within -2 to +2 % (geometric mean +0.2 %), but
  // 21 to 30 % larger at 80 % of the faces, and the bunny's 10 % cell, the
  // nearest to Lindstrom-Turk's error, moved to the wrong side of it (+0.9 %
  // with 10^6 samples), so it is not the default. With no limit at all the
  // error at 10 % rose by up to 31 %.
  double fine_vertex_fraction = 1.0;
  double fine_batch_cost_ratio = 32.0;
  double fine_batch_min_fraction = 0.2;
  // Free placement moves kept vertices only in batches that start with at
  // most this fraction of the input's vertices (1: from the first collapse);
  // before, they stay, as with endpoint placement (spec decision D36). A move
  // costs about 16 of the 46 bits of a split (bunny, 14 bits), and what the
  // first collapses gain by it does not last: a kept vertex moves again
  // whenever a later collapse keeps it. From 0.7 the streams were 6 to 12 %
  // smaller at 16 bits with the RMS error at 10 % and 1 % of the faces within
  // -2.4 to +0.6 % (geometric mean over five levels each); from 0.5, 14 to
  // 18 % smaller, but the bunny's 1 % levels 11 % worse.
  double free_placement_below = 0.7;
};

struct HalfEdgeCollapse {
  uint32_t removed = 0;  // vertex index in the input mesh
  uint32_t kept = 0;     // vertex index in the input mesh
  std::array<double, 3> kept_position{};  // where `kept` is after the collapse
};

// batches[0] is applied first to the input mesh, then batches[1], and so on.
// Independence within a batch: for two collapses c1, c2 of one batch, neither
// endpoint of c2 is an endpoint of c1 or a neighbour of an endpoint of c1 in
// the mesh at the start of the batch (and vice versa). Every collapse is
// valid when made: link condition, boundary rules of the paper's Table 1
// (spec 6.9), no flipped or degenerate triangle, no non-manifold result.
struct SimplifyResult {
  std::vector<std::vector<HalfEdgeCollapse>> batches;
  uint64_t final_triangles = 0;
  uint64_t final_vertices = 0;  // vertices still used by a triangle
};

// The input must be an oriented 2-manifold, possibly with boundary (see
// mesh_repair.h); returns false with one line in `error` otherwise.
bool simplifyMesh(const TriangleMesh& mesh, const SimplifyOptions& options,
                  SimplifyResult* result, std::string* error);

}  // namespace mrsv
