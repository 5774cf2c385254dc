// CGAL's Tetrahedral_remeshing as a coarsener to a tet count (see tet_cgal_peer.h).
#include "tet_cgal_peer.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_3/tet_soup_to_c3t3.h>
#include <CGAL/Tetrahedral_remeshing/Remeshing_triangulation_3.h>
#include <CGAL/property_map.h>
#include <CGAL/tetrahedral_remeshing.h>

#include <algorithm>
#include <boost/unordered_set.hpp>
#include <chrono>
#include <cmath>
#include <map>
#include <unordered_map>

#include "mrsv/tet_metrics.h"

namespace mrsv::bench {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangulation = CGAL::Tetrahedral_remeshing::Remeshing_triangulation_3<Kernel>;
using VertexHandle = Triangulation::Vertex_handle;
using VertexPair = std::pair<VertexHandle, VertexHandle>;
using ConstraintSet = boost::unordered_set<VertexPair, boost::hash<VertexPair>>;

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// The input's boundary edges sharper than `angle` degrees, as vertex index pairs.
std::vector<std::pair<uint32_t, uint32_t>> featureEdges(const TetMesh& in, double angle) {
  std::vector<uint32_t> original;
  const TriangleMesh boundary = tetBoundary(in, &original);
  std::vector<std::array<double, 3>> normal(boundary.triangles.size());
  // (low, high, face) per boundary edge use; the two uses of an edge adjacent after sorting.
  std::vector<std::array<uint32_t, 3>> uses;
  for (size_t f = 0; f < boundary.triangles.size(); ++f) {
    const auto& t = boundary.triangles[f];
    const auto &a = boundary.positions[t[0]], &b = boundary.positions[t[1]],
               &c = boundary.positions[t[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    normal[f] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    for (int e = 0; e < 3; ++e)
      uses.push_back({std::min(t[e], t[(e + 1) % 3]), std::max(t[e], t[(e + 1) % 3]),
                      static_cast<uint32_t>(f)});
  }
  std::sort(uses.begin(), uses.end());
  const double cos_limit = std::cos(angle * 3.14159265358979323846 / 180.0);
  std::vector<std::pair<uint32_t, uint32_t>> out;
  for (size_t i = 0; i + 1 < uses.size(); ++i) {
    if (uses[i][0] != uses[i + 1][0] || uses[i][1] != uses[i + 1][1]) continue;
    const auto& n = normal[uses[i][2]];
    const auto& m = normal[uses[i + 1][2]];
    const double dot = n[0] * m[0] + n[1] * m[1] + n[2] * m[2];
    const double len = std::sqrt((n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) *
                                 (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]));
    if (len > 0.0 && dot < cos_limit * len)
      out.push_back({original[uses[i][0]], original[uses[i][1]]});
  }
  return out;
}

struct Run {
  TetMesh mesh;  // positions and tets; fields filled for the run kept
  double edge_length = 0.0;
  double seconds = 0.0;
};

// One remeshing of the input at `edge_length`.
bool remesh(const TetMesh& in, const std::vector<std::pair<uint32_t, uint32_t>>& features,
            double edge_length, unsigned iterations, Run* run, std::string* error) {
  // Only the vertices the tets use: a vertex without a cell makes CGAL's
  // triangulation invalid (the blunt fin's merged grid points are such).
  std::vector<int> index_of(in.positions.size(), -1);
  std::vector<Kernel::Point_3> points;
  for (const auto& t : in.tets)
    for (uint32_t v : t)
      if (index_of[v] < 0) {
        index_of[v] = static_cast<int>(points.size());
        points.emplace_back(in.positions[v][0], in.positions[v][1], in.positions[v][2]);
      }
  // Every tet in subdomain 1: the faces between it and the outside (index
  // 0) are the boundary CGAL keeps the domain's shape by.
  std::vector<std::array<int, 5>> cells;
  cells.reserve(in.tets.size());
  for (const auto& t : in.tets)
    cells.push_back({index_of[t[0]], index_of[t[1]], index_of[t[2]], index_of[t[3]], 1});
  Triangulation tr;
  std::vector<VertexHandle> handles;
  const std::map<std::array<int, 3>, Triangulation::Cell::Surface_patch_index> no_patches;
  if (!CGAL::build_triangulation<Triangulation, false>(tr, points, cells, no_patches, handles)) {
    *error = "CGAL cannot build a triangulation from the tets (not a manifold complex?)";
    return false;
  }
  ConstraintSet constraints;
  for (const auto& [a, b] : features) {
    // handles[0] is the infinite vertex.
    const VertexHandle x = handles[index_of[a] + 1], y = handles[index_of[b] + 1];
    constraints.insert(x < y ? VertexPair(x, y) : VertexPair(y, x));
  }
  const auto start = std::chrono::steady_clock::now();
  CGAL::tetrahedral_isotropic_remeshing(
      tr, edge_length,
      CGAL::parameters::number_of_iterations(iterations)
          .edge_is_constrained_map(CGAL::Boolean_property_map<ConstraintSet>(constraints)));
  run->seconds = seconds(start);
  run->edge_length = edge_length;

  // The cells of the domain, vertices renumbered in the order met.
  run->mesh = TetMesh{};
  std::unordered_map<VertexHandle, uint32_t> index;
  for (auto c : tr.finite_cell_handles()) {
    if (c->subdomain_index() == 0) continue;
    std::array<uint32_t, 4> tet;
    for (int i = 0; i < 4; ++i) {
      const VertexHandle v = c->vertex(i);
      auto [it, added] = index.emplace(v, static_cast<uint32_t>(run->mesh.positions.size()));
      if (added) run->mesh.positions.push_back({v->point().x(), v->point().y(), v->point().z()});
      tet[i] = it->second;
    }
    // CGAL's finite cells are positively oriented in CGAL's sense, which is
    // TetMesh's (det[b - a, c - a, d - a] > 0).
    run->mesh.tets.push_back(tet);
  }
  return true;
}

}  // namespace

bool cgalCoarsen(const TetMesh& in, size_t target_tets, const CgalPeerOptions& options,
                 CgalPeerResult* result, std::string* error) {
  *result = CgalPeerResult{};
  result->target_tets = target_tets;
  const auto start = std::chrono::steady_clock::now();
  const auto features = featureEdges(in, options.feature_angle);
  result->constrained_edges = features.size();

  // First guess: regular tets of the mean volume (V = L^3 / (6 sqrt 2)).
  const double volume = tetMeshVolume(in);
  double length = std::cbrt(6.0 * std::sqrt(2.0) * volume / static_cast<double>(target_tets));
  // The count goes as L^-k; k starts at 3 and is re-estimated from the last
  // two runs (a secant step in log-log).
  double exponent = 3.0;
  Run best;
  double best_miss = HUGE_VAL;
  double last_length = 0.0, last_count = 0.0;
  for (int r = 0; r < options.max_runs; ++r) {
    Run run;
    if (!remesh(in, features, length, options.iterations, &run, error)) return false;
    ++result->runs;
    const auto count = static_cast<double>(run.mesh.tets.size());
    const double miss = std::fabs(count / static_cast<double>(target_tets) - 1.0);
    if (miss < best_miss) {
      best_miss = miss;
      best = std::move(run);
    }
    if (miss <= options.tolerance) break;
    if (last_count > 0.0 && count != last_count && length != last_length) {
      const double k = -std::log(count / last_count) / std::log(length / last_length);
      if (k > 0.5 && k < 10.0) exponent = k;
    }
    last_length = length;
    last_count = count;
    length *= std::pow(count / static_cast<double>(target_tets), 1.0 / exponent);
  }
  result->seconds_all = seconds(start);
  result->within_tolerance = best_miss <= options.tolerance;
  result->edge_length = best.edge_length;
  result->seconds = best.seconds;
  result->mesh = std::move(best.mesh);
  // Every field resampled at the new vertices from the original mesh.
  for (const ScalarField& f : in.fields) {
    const TetFieldProbe probe(in, f.values);
    ScalarField out{f.name, {}};
    out.values.reserve(result->mesh.positions.size());
    for (const auto& p : result->mesh.positions) {
      TetFieldProbe::Sample s;
      probe.sample(p, &s);
      out.values.push_back(s.value);
    }
    result->mesh.fields.push_back(std::move(out));
  }
  return true;
}

}  // namespace mrsv::bench
