// Tet meshes for the tet-metric tests and tools/bench/tet_peer_bench, until
// the tet file formats and grid generators of issue 21 land in the library:
// a grid cut into 6 tets per cube, and a minimal MEDIT .mesh reader.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>

#include "mrsv/tet_mesh.h"

namespace mrsv::test {

// The grid of nx x ny x nz samples (sample (i, j, k) at origin + (i, j, k) *
// spacing, i fastest), each cube cut into the 6 tets of Kuhn's subdivision
// (the paths from corner 000 to 111), all positively oriented; every cube is
// cut the same way, so neighbouring cubes' faces match. (nx-1)(ny-1)(nz-1) * 6
// tets: 32^3 samples give 178,746. `value(i, j, k)`, when given, fills one
// field named `field`.
TetMesh gridTetMesh(int nx, int ny, int nz, const std::array<double, 3>& origin,
                    const std::array<double, 3>& spacing,
                    const std::function<double(int, int, int)>& value = nullptr,
                    const std::string& field = "value");

// Vertices and Tetrahedra of a MEDIT ASCII .mesh file (1-based indices,
// references dropped; other sections skipped). Tets are taken as they are.
bool readMeditTetMesh(const std::string& path, TetMesh* mesh, std::string* error);

// A single-grid binary PLOT3D pair (big-endian, no record markers, no
// IBLANK: the blunt fin and the combustion chamber of ../shared/data/tet),
// each hexahedron cut into 5 tets, the cut alternating with the parity of
// i + j + k so that neighbouring faces match; tets turned positive where the
// grid is left-handed. Grid points at the same place are merged and the
// tets that collapse are left out (the points merged stay, unused). The q
// file's density is the field "density".
bool readPlot3dTetMesh(const std::string& xyz_path, const std::string& q_path, TetMesh* mesh,
                       std::string* error);

}  // namespace mrsv::test
