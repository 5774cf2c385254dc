// mrsv compare for tet meshes: every tet measurement of B against A in one
// report, and that report as JSON.
#include <cmath>
#include <cstdio>

#include "metrics/surface_distance.h"
#include "mrsv/tet_metrics.h"

namespace mrsv {

TetCompareReport compareTetMeshes(const TetMesh& a, const TetMesh& b,
                                  const TetCompareOptions& options) {
  TetCompareReport r;
  r.a_vertices = a.positions.size();
  r.a_tets = a.tets.size();
  r.b_vertices = b.positions.size();
  r.b_tets = b.tets.size();
  std::string why;
  if (!checkTetMesh(a, &why)) {
    r.error = "A: " + why;
    return r;
  }
  if (!checkTetMesh(b, &why)) {
    r.error = "B: " + why;
    return r;
  }
  r.volume_a = tetMeshVolume(a);
  r.volume_b = tetMeshVolume(b);
  r.volume_difference = std::fabs(r.volume_b - r.volume_a);
  r.volume_difference_relative =
      r.volume_a != 0.0 ? r.volume_difference / std::fabs(r.volume_a) : 0.0;

  if (options.quality) {
    TetQualityOptions q;
    q.self_intersections = options.self_intersections;
    r.quality_a = measureTetQuality(a, q);
    r.quality_b = measureTetQuality(b, q);
    r.has_quality = true;
  }

  // The boundary distance is sampled as mrsv compare samples surfaces, with
  // the same count and seed as the field.
  SurfaceDistanceOptions distance;
  distance.sampling.sample_count = options.field.sample_count;
  distance.sampling.seed = options.field.seed;
  distance.threads = options.threads;
  SurfaceDistanceReport surface;
  if (!measureSurfaceDistance(tetBoundary(a), tetBoundary(b), distance, &surface, &why)) {
    r.error = "boundary of " + why;
    return r;
  }
  r.boundary.a_to_b_max = surface.a_to_b.max;
  r.boundary.b_to_a_max = surface.b_to_a.max;
  r.boundary.hausdorff = surface.hausdorff;
  r.boundary.mean = surface.mean;
  r.boundary.rms = surface.rms;
  r.boundary.bbox_diagonal = surface.bbox_diagonal;

  if (!a.fields.empty()) {
    if (!measureTetFieldError(a, b, options.field, &r.field, &why)) {
      r.error = why;
      return r;
    }
    r.has_field = true;
  }
  return r;
}

namespace {

// JSON has no infinity or NaN: those are null.
std::string number(double x) {
  if (!std::isfinite(x)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string qualityJson(const TetQuality& q) {
  const TetManifoldReport& m = q.manifold;
  return "{\"tets\": " + std::to_string(q.tets) + ", \"vertices\": " + std::to_string(q.vertices) +
         ", \"inverted\": " + std::to_string(q.inverted) +
         ", \"degenerate\": " + std::to_string(q.degenerate) +
         ", \"min_dihedral_worst\": " + number(q.min_dihedral_worst) +
         ", \"min_dihedral_mean\": " + number(q.min_dihedral_mean) +
         ", \"max_dihedral_worst\": " + number(q.max_dihedral_worst) +
         ", \"boundary_faces\": " + std::to_string(q.boundary_faces) +
         ", \"boundary_self_intersections\": " +
         (q.boundary_self_intersections < 0 ? std::string("null")
                                            : std::to_string(q.boundary_self_intersections)) +
         ", \"manifold\": " + (m.manifold() ? "true" : "false") +
         ", \"overshared_faces\": " + std::to_string(m.overshared_faces) +
         ", \"misoriented_faces\": " + std::to_string(m.misoriented_faces) +
         ", \"nonmanifold_edges\": " + std::to_string(m.nonmanifold_edges) +
         ", \"nonmanifold_vertices\": " + std::to_string(m.nonmanifold_vertices) +
         ", \"unused_vertices\": " + std::to_string(m.unused_vertices) +
         ", \"valid\": " + (q.valid() ? "true" : "false") + "}";
}

}  // namespace

std::string tetCompareJson(const TetCompareReport& r) {
  std::string s = "{\n";
  if (!r.error.empty()) s += "  \"error\": " + quoted(r.error) + ",\n";
  s += "  \"a\": {\"vertices\": " + std::to_string(r.a_vertices) +
       ", \"tets\": " + std::to_string(r.a_tets) + "},\n";
  s += "  \"b\": {\"vertices\": " + std::to_string(r.b_vertices) +
       ", \"tets\": " + std::to_string(r.b_tets) + "},\n";
  if (r.has_field) {
    const TetFieldError& f = r.field;
    s += "  \"field\": {\"name\": " + quoted(f.field) +
         ", \"samples\": " + std::to_string(f.samples) + ", \"psnr_db\": " + number(f.psnr_db) +
         ", \"rms\": " + number(f.rms) + ", \"mean_abs\": " + number(f.mean_abs) +
         ", \"max_abs\": " + number(f.max_abs) + ", \"range\": " + number(f.range) +
         ", \"outside_b\": " + std::to_string(f.outside_b) +
         ", \"outside_b_max_distance\": " + number(f.outside_b_max_distance) + "},\n";
  } else {
    s += "  \"field\": null,\n";
  }
  s += "  \"volume\": {\"a\": " + number(r.volume_a) + ", \"b\": " + number(r.volume_b) +
       ", \"difference\": " + number(r.volume_difference) +
       ", \"difference_relative\": " + number(r.volume_difference_relative) + "},\n";
  const TetBoundaryDistance& d = r.boundary;
  const double diag = d.bbox_diagonal > 0.0 ? d.bbox_diagonal : NAN;
  s += "  \"boundary\": {\"hausdorff\": " + number(d.hausdorff) + ", \"mean\": " + number(d.mean) +
       ", \"rms\": " + number(d.rms) + ", \"a_to_b_max\": " + number(d.a_to_b_max) +
       ", \"b_to_a_max\": " + number(d.b_to_a_max) +
       ", \"bbox_diagonal\": " + number(d.bbox_diagonal) +
       ", \"hausdorff_relative\": " + number(d.hausdorff / diag) +
       ", \"rms_relative\": " + number(d.rms / diag) + "},\n";
  if (r.has_quality) {
    s += "  \"quality_a\": " + qualityJson(r.quality_a) + ",\n";
    s += "  \"quality_b\": " + qualityJson(r.quality_b) + "\n";
  } else {
    s += "  \"quality_a\": null,\n  \"quality_b\": null\n";
  }
  return s + "}";
}

}  // namespace mrsv
