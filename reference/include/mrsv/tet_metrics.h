// Measurements of tetrahedral meshes: point location and interpolation of a
// per-vertex scalar field, the field's error between two meshes (the PSNR of
// section 7.2 of the Staadt & Gross paper: the field sampled at 10^6 random
// positions), volumes, the boundary surface and its distance to another
// boundary, and the quality and validity checks the PT levels must pass
// (inverted and degenerate tets, dihedral angles, a manifold complex, a
// boundary without self-intersections). Library mrsv_metrics: tools and tests
// only, never the decoder.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mrsv/mesh.h"
#include "mrsv/tet_mesh.h"

namespace mrsv {

using Point3 = std::array<double, 3>;

// Checks what every measurement needs: tet corners in range and four distinct
// ones per tet, finite coordinates, every field one value per vertex. On
// failure returns false with one line in `error` naming the element.
bool checkTetMesh(const TetMesh& mesh, std::string* error);

// --- point location --------------------------------------------------------

// Finds the tet that contains a point: a uniform grid over the bounding box
// (about one cell per tet) lists the tets whose bounding boxes meet each cell;
// the candidates of the point's cell are tested with barycentric coordinates.
// A point clearly inside a tet (every coordinate above a rounding margin) is
// answered at once; otherwise exact orientation predicates decide, so a point
// on a face shared by two tets, or in the rounding gap between them, is never
// lost, and it belongs to the lowest-indexed tet whose closed set holds it.
// The mesh must pass checkTetMesh and outlive the locator. Flat tets (exact
// orientation zero) are never answered (they have no barycentric frame);
// inverted ones are, by their unsigned shape.
class TetLocator {
 public:
  explicit TetLocator(const TetMesh& mesh);
  ~TetLocator();
  TetLocator(TetLocator&&) noexcept;
  TetLocator& operator=(TetLocator&&) noexcept;

  // The tet holding `p`, or -1; `bary` (optional) receives the barycentric
  // coordinates of `p` for the tet's corners 0..3 (each in [0, 1], sum 1).
  // `hint`, a tet likely to hold `p`, is tried first; the answer is the one
  // without the hint (a point inside a tet beyond rounding is in no other
  // tet of a valid mesh; any other point is searched as without it).
  int64_t locate(const Point3& p, std::array<double, 4>* bary = nullptr, int64_t hint = -1) const;
  // Linear interpolation of `values` (one per vertex) at `p`; false when `p`
  // is in no tet. Two locators of equal meshes give equal values.
  bool interpolate(const std::vector<double>& values, const Point3& p, double* value,
                   int64_t hint = -1) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A field's value anywhere: interpolated in the tet holding the point, and
// for a point in no tet, at the nearest point of the mesh's boundary
// (interpolated on that boundary face). The field error measures B with it;
// a remesher resamples a field at its new vertices with it.
class TetFieldProbe {
 public:
  // `mesh` (which must pass checkTetMesh) and `values` (one per vertex) must
  // outlive the probe.
  TetFieldProbe(const TetMesh& mesh, const std::vector<double>& values);
  ~TetFieldProbe();
  TetFieldProbe(TetFieldProbe&&) noexcept;
  TetFieldProbe& operator=(TetFieldProbe&&) noexcept;

  struct Sample {
    double value = 0.0;
    bool inside = false;    // in a tet (else at the nearest boundary point)
    double distance = 0.0;  // to that boundary point when outside
  };
  // False only for a point outside a mesh without a usable boundary (no
  // face of nonzero area).
  bool sample(const Point3& p, Sample* out, int64_t hint = -1) const;
  const TetLocator& locator() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// --- volume and boundary ---------------------------------------------------

// Sum of the signed tet volumes (an inverted tet counts negative).
double tetMeshVolume(const TetMesh& mesh);

// The faces that belong to exactly one tet, each oriented outward (its
// right-hand normal points away from its tet). Vertices are renumbered to the
// ones the boundary uses, in their original order; `tet_vertex` (optional)
// receives the original index of each. Faces in three or more tets are not
// boundary faces (measureTetQuality reports them).
TriangleMesh tetBoundary(const TetMesh& mesh, std::vector<uint32_t>* tet_vertex = nullptr);

// --- quality and validity --------------------------------------------------

// What the PT levels must satisfy (issue 21: every level of every benchmark
// mesh has 0 inverted tets, 0 boundary self-intersections and a manifold
// boundary).
struct TetManifoldReport {
  // Faces in three or more tets.
  uint64_t overshared_faces = 0;
  // Faces in two tets that orient it the same way (the tets lie on the same
  // side of it: they overlap).
  uint64_t misoriented_faces = 0;
  // Edges whose link (the opposite edges of its tets) is not one path or one
  // cycle: the tets around the edge form several fans.
  uint64_t nonmanifold_edges = 0;
  // Vertices whose link (the faces opposite it in its tets) is not a sphere
  // (an interior vertex) or a disk (a boundary vertex): several components,
  // a link edge in more than two link faces, or the wrong Euler characteristic.
  uint64_t nonmanifold_vertices = 0;
  // Vertices no tet uses (allowed; reported so a caller can reject them).
  uint64_t unused_vertices = 0;
  // An offender of each kind, for a one-line message (-1: none): the lowest
  // tet on a bad face, the lowest vertex of the first bad edge found, the
  // lowest bad vertex.
  int64_t first_bad_face_tet = -1;
  int64_t first_bad_edge = -1;  // as a vertex of the edge (the lower index)
  int64_t first_bad_vertex = -1;
  // Every face in one or two tets, oppositely oriented, every edge and
  // vertex link a path/cycle and a disk/sphere: a 3-manifold with boundary,
  // whose boundary is then a closed 2-manifold.
  bool manifold() const {
    return overshared_faces == 0 && misoriented_faces == 0 && nonmanifold_edges == 0 &&
           nonmanifold_vertices == 0;
  }
};
TetManifoldReport checkTetManifold(const TetMesh& mesh);

// Pairs of boundary triangles that intersect other than in the vertex or edge
// they share (exact predicates, CGAL's box intersection: never all pairs).
// Where the boundary is not a 2-manifold, its non-manifold vertices are
// duplicated first, so triangles that only touch there count as intersecting.
uint64_t countBoundarySelfIntersections(const TriangleMesh& boundary);

struct TetQualityOptions {
  // The boundary self-intersection test is the slowest part (CGAL's box
  // intersection with exact predicates); false skips it (reported as -1).
  bool self_intersections = true;
};

struct TetQuality {
  uint64_t tets = 0;
  uint64_t vertices = 0;
  // Exact orientation: det[b - a, c - a, d - a] < 0.
  uint64_t inverted = 0;
  // Not inverted, and flat: the exact orientation is zero, or the volume is
  // at most 1e-12 of the longest edge cubed (a tet made of rounding noise).
  uint64_t degenerate = 0;
  // Per tet, the smallest of its six dihedral angles (degrees); the worst
  // (smallest) over the mesh and the mean over the tets. Inverted tets take
  // part with the angles of their unsigned shape.
  double min_dihedral_worst = 0.0;
  double min_dihedral_mean = 0.0;
  // The largest of all dihedral angles (degrees): near 180 means a flat tet.
  double max_dihedral_worst = 0.0;
  double volume = 0.0;
  uint64_t boundary_faces = 0;
  TetManifoldReport manifold;
  int64_t boundary_self_intersections = -1;  // -1: not measured
  // The PT levels' condition: no inverted or degenerate tet, a manifold
  // complex, and no boundary self-intersection (when measured).
  bool valid() const {
    return inverted == 0 && degenerate == 0 && manifold.manifold() &&
           boundary_self_intersections <= 0;
  }
};
// The mesh must pass checkTetMesh.
TetQuality measureTetQuality(const TetMesh& mesh, const TetQualityOptions& options = {});

// --- the field's error -----------------------------------------------------

constexpr uint64_t kDefaultTetSampleCount = 1000000;

struct TetFieldErrorOptions {
  // The field compared: the first one of A when empty; B must have a field
  // of the same name.
  std::string field;
  uint64_t sample_count = kDefaultTetSampleCount;
  uint64_t seed = 1;
};

// The scalar field of B against A's at random positions uniformly spread over
// A's volume: a tet of A chosen with probability proportional to its volume,
// then a uniform point inside it (barycentric coordinates from the spacings
// of three sorted uniforms). A's value there is interpolated with A's
// locator, hinted with that tet (so equal meshes give equal values and an
// error of exactly 0); B's in the tet of B that holds the point. A point in
// no tet of B (where B's domain does not cover A's) takes B's value at the
// nearest point of B's boundary, interpolated on that boundary face, and is
// counted.
// The samples are drawn in the order of A's tets (sorted volume fractions),
// which keeps the point location in cache; the same seed, meshes and count
// give the same figures.
struct TetFieldError {
  std::string field;
  uint64_t samples = 0;
  uint64_t outside_b = 0;               // samples in no tet of B
  double outside_b_max_distance = 0.0;  // the farthest of them from B's boundary
  double range = 0.0;                   // max - min of A's field over A's vertices
  double max_abs = 0.0;
  double mean_abs = 0.0;
  double rms = 0.0;
  // 20 log10(range / rms): +infinity when rms is 0, NaN when range is 0.
  double psnr_db = 0.0;
};
// Both meshes must pass checkTetMesh; false with one line in `error` when
// the field is missing or A has no volume.
bool measureTetFieldError(const TetMesh& a, const TetMesh& b, const TetFieldErrorOptions& options,
                          TetFieldError* result, std::string* error);

// --- mrsv compare for tet meshes --------------------------------------------

struct TetCompareOptions {
  TetFieldErrorOptions field;  // sample_count and seed also drive the boundary distance
  bool quality = true;         // measureTetQuality on both meshes
  bool self_intersections = true;
  unsigned threads = 0;  // for the boundary distance; 0: every core
};

struct TetBoundaryDistance {
  // As mrsv compare reports for surfaces: one-sided maxima, and the
  // symmetric Hausdorff (the larger max), mean and RMS (the larger of the
  // two directions), all absolute; relative ones divide by bbox_diagonal,
  // the diagonal of A's boundary's bounding box.
  double a_to_b_max = 0.0, b_to_a_max = 0.0;
  double hausdorff = 0.0, mean = 0.0, rms = 0.0;
  double bbox_diagonal = 0.0;
};

struct TetCompareReport {
  std::string error;  // empty when every measurement was made
  uint64_t a_vertices = 0, a_tets = 0, b_vertices = 0, b_tets = 0;
  bool has_field = false;  // false when A has no field: no field error
  TetFieldError field;
  double volume_a = 0.0, volume_b = 0.0;
  double volume_difference = 0.0;           // |volume_b - volume_a|
  double volume_difference_relative = 0.0;  // divided by |volume_a|
  TetBoundaryDistance boundary;
  bool has_quality = false;
  TetQuality quality_a, quality_b;
};

// Everything above for A (the reference) and B. On invalid input the report
// carries `error` (naming A or B) and the figures measured so far.
TetCompareReport compareTetMeshes(const TetMesh& a, const TetMesh& b,
                                  const TetCompareOptions& options = {});
// One JSON object (no trailing newline); infinite or undefined figures
// (a PSNR of identical fields) are null.
std::string tetCompareJson(const TetCompareReport& report);

}  // namespace mrsv
