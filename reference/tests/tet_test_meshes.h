// Tet meshes for the simplifier's tests and bench, built from ../shared/data:
// the MEDIT meshes (a minimal reader, until the formats branch lands), the
// paper's 32^3 crop of the CT head as 6 tets per voxel cube, and the LOX post
// PLOT3D grid as 5 tets per hex; and a scalar-field sampler for the paper's
// PSNR measure (7.2). Free of GoogleTest, so the bench shares it.
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "tetsimplify/tet_simplify.h"

namespace mrsv::test {

// Reads a MEDIT .mesh (Vertices and Tetrahedra), quantises the positions to
// [0, 2^29) over the bounding box's largest side and orients every tet
// positively (swapping two corners where the file's order is negative).
bool readMeditTets(const std::string& path, QuantizedTetMesh* mesh, std::string* error);

// The n^3-sample crop of the CT head starting at sample (x0, y0, z0), as 6
// tets per cube around each cube's main diagonal (conforming faces), sample
// values as the scalar field. Positions are sample indices times 1024
// (times 1024 z_scale along z: the volume's slices are 2 pixels apart).
bool ctHeadCrop(int n, int x0, int y0, int z0, QuantizedTetMesh* mesh, std::string* error, int z_scale = 1);
// The paper's crop (7.2): 32^3 samples, 178,746 tets.
bool paperCtCrop(QuantizedTetMesh* mesh, std::string* error);

// The LOX post (PLOT3D, 38 x 76 x 38, cells with an IBLANK 0 corner left
// out: none in this file) as 5 tets per hex, alternating parity so faces
// conform; the x momentum as the scalar (the file's density is constant).
bool loxPost(QuantizedTetMesh* mesh, std::string* error);

// Point location in a tet mesh through a uniform grid of tet bounding boxes;
// the value is the linear interpolant of field 0.
class FieldSampler {
 public:
  explicit FieldSampler(const QuantizedTetMesh& mesh);
  // False when p is in no tet.
  bool sample(const std::array<double, 3>& p, double* value) const;

 private:
  const QuantizedTetMesh& mesh_;
  std::array<double, 3> lo_{}, cell_{};
  std::array<int, 3> dims_{};
  std::vector<uint32_t> start_, items_;
};

struct PsnrResult {
  double psnr = 0.0;
  uint64_t outside = 0;  // samples of the original domain outside the simplified mesh (counted as 0)
};
// The paper's measure: the scalar of both meshes at `samples` uniformly random
// points of the original mesh (rejection from its bounding box), PSNR over the
// original's range.
PsnrResult scalarPsnr(const QuantizedTetMesh& original, const QuantizedTetMesh& simplified, uint64_t samples,
                      uint32_t seed);

}  // namespace mrsv::test
