// Independent checks of reconstructed meshes for the tests: real terrain
// crops as sample fields, triangulation validity, and the largest error over
// every sample by brute force (not the reconstructors' own code).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "mrsv/grid_mesh.h"

namespace mrsv::test {

// A crop of a terrain of ../shared/data/terrain (file name without directory).
SampleField terrainCrop(const std::string& file, uint32_t x0, uint32_t y0, uint32_t w, uint32_t h);

// Empty when `mesh` triangulates its grid's rectangle: every triangle
// counter-clockwise and not flat, areas summing to the rectangle's, every
// edge in one triangle each way or on the rectangle's border (so no
// T-junction and no crack); otherwise the first problem.
std::string triangulationProblem(const GridMesh& mesh);

// The largest |sample - mesh| over every sample of `field`, exact, compared
// with `bound`: true when every sample is within it. `worst` gets the largest
// error as a double.
bool withinBoundEverywhere(const SampleField& field, const GridMesh& mesh, const ErrorBound& bound,
                           double* worst);

// The mesh's points on its grid's border, sorted: what tiles must share.
std::vector<std::array<uint32_t, 3>> borderPoints(const GridMesh& mesh);

}  // namespace mrsv::test
