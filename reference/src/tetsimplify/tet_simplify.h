// Tet-mesh simplification: the first stage of the PT encoder (issue 21; paper
// sections 6.1 and 6.2).
//
// The simplifier only decides WHICH half-edge collapses to make and in what
// order; the PT encoder replays them to write the stream. A collapse (vs, vt)
// merges vt into vs: the tets holding both vanish, and in the tets holding vt
// only, vt is replaced by vs in place (same corner), while vs keeps its
// position and scalars. Everything is decided on quantised integer positions
// with exact predicates, so the decoder, which checks orientation exactly on
// the same integers, agrees with every decision.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "mrsv/status.h"

namespace mrsv {

struct QuantizedTetMesh {
  std::vector<std::array<int32_t, 3>> positions;  // in [0, 2^30)
  // Every tet positively oriented: orient3d(a, b, c, d) = det[b-a, c-a, d-a] > 0 exactly.
  std::vector<std::array<uint32_t, 4>> tets;
  std::vector<std::vector<double>> fields;  // per-vertex scalar fields (may be empty), for costs
};

// Half-edge collapse: vt merges into vs; vs keeps its position and scalars.
struct TetCollapse {
  uint32_t vs = 0;
  uint32_t vt = 0;
};

enum class TetCost {
  kQuadric,  // volume-weighted quadric of the linear scalar field plus boundary planes (D44)
  kPaper,    // Staadt-Gross 6.1: scalar difference, volume, equilateral, edge length, boundary normals
};

struct TetSimplifyOptions {
  TetCost cost = TetCost::kQuadric;
  // The paper's terms (6.1), each in normalised units: scalars divided by the
  // first field's range, lengths by the mean edge length, volumes by the mean
  // tet volume. kPaper only.
  double weight_gradient = 1.0;
  double weight_volume = 1.0;
  double weight_equilateral = 0.1;
  double weight_edge_length = 0.1;
  double weight_normal = 1.0;
  // kQuadric: weight of the boundary faces' planes (area times squared
  // distance, in mean edge lengths) against the scalar term (volume times the
  // squared scalar error, in field ranges).
  double quadric_boundary_weight = 1.0;
  // Halting: the base mesh keeps at least this many tets and vertices.
  uint64_t min_base_tets = 0;
  uint64_t min_base_vertices = 4;
  // Stop after this many seconds of collapsing (0: no limit); the result is
  // still complete and valid, only less simplified.
  double time_budget_seconds = 0.0;
  // Refuse collapses that make a tet with a dihedral angle below this many
  // degrees (0: off).
  double min_dihedral_degrees = 0.0;
  // Refuse collapses that make a boundary triangle intersect another.
  bool boundary_intersection_test = true;
  // Table 1 cases 2 and 3 (an interior edge with one end on the boundary).
  // Off by default: the PT decoder's split rule for a boundary vs expects a
  // path, not the cycle such a collapse leaves, so with this on only the link
  // condition is checked, not the split rule, and the PT decoder may refuse
  // the result.
  bool allow_boundary_cases_2_3 = false;
  // The batch rule (as simplify/simplify.h, spec decisions D22 and D35): a
  // batch takes, cheapest first, the consistent collapses none of whose tets
  // an earlier collapse of the batch touched, up to batch_cost_ratio times
  // the cheapest candidate's cost or the batch_min_fraction quantile of the
  // candidates' costs, whichever is higher.
  double batch_cost_ratio = 8.0;
  double batch_min_fraction = 0.05;
  // Called now and then with the fraction done, in [0, 1].
  std::function<void(double)> progress;
};

struct TetSimplifyStats {
  uint64_t collapses = 0;
  uint64_t batches = 0;
  // Collapses evaded, by the first test they failed (tests in the order
  // below). A Table 1 evasion is a target the table refuses that was cheaper
  // than the one the vertex got and within the batch's limit.
  uint64_t evaded_boundary_table = 0;   // Table 1 cases 2 to 4
  uint64_t evaded_inversion = 0;        // a tet would turn: orient3d < 0
  uint64_t evaded_degenerate = 0;       // a tet would go flat: orient3d == 0
  uint64_t evaded_min_dihedral = 0;     // a tet would have a smaller dihedral angle than allowed
  uint64_t evaded_link = 0;             // link condition (and the PT decoder's split rule)
  uint64_t evaded_self_intersection = 0;  // a boundary triangle would cross another
  uint64_t final_tets = 0;
  uint64_t final_vertices = 0;
  double seconds = 0.0;
  double averageBatchSize() const { return batches ? double(collapses) / double(batches) : 0.0; }
};

struct TetSimplifyResult {
  // In collapse order: batches[0] is applied first to the full mesh. Within a
  // batch the sets star(vs) u star(vt) (taken on the mesh before the batch)
  // of any two collapses are disjoint, so they may be undone in any order.
  std::vector<std::vector<TetCollapse>> batches;
  TetSimplifyStats stats;
};

// The input must be a 3-manifold with boundary (every face in one or two
// tets, every vertex link a sphere or a disk) with every tet positively
// oriented and an embedded boundary; otherwise one line names the element and
// the rule (kInvalidArgument).
Error simplifyTets(const QuantizedTetMesh& mesh, const TetSimplifyOptions& options, TetSimplifyResult* out);

// Dihedral angles of a mesh's tets, in degrees.
struct DihedralStats {
  double worst = 0.0;        // the smallest dihedral angle of any tet
  double mean_minimum = 0.0;  // the mean over tets of each tet's smallest one
};
DihedralStats dihedralStats(const QuantizedTetMesh& mesh);
// The smallest of one tet's six dihedral angles, in degrees.
double minDihedralDegrees(const std::array<int32_t, 3>& a, const std::array<int32_t, 3>& b,
                          const std::array<int32_t, 3>& c, const std::array<int32_t, 3>& d);

// Applies the first `collapses` collapses of `result` (all when larger) to
// `mesh`, removing vanished tets and unused vertices (renumbered in their
// order; `vertex_map`, if given, maps the input's vertices to the output's,
// or to ~0u). For tests, benches and the encoder's level statistics.
void applyTetCollapses(const QuantizedTetMesh& mesh, const TetSimplifyResult& result, uint64_t collapses,
                       QuantizedTetMesh* out, std::vector<uint32_t>* vertex_map = nullptr);

}  // namespace mrsv
