// Tetrahedral mesh file formats read and written by the tools (never by the
// decoder), and tet meshes made from grids and PLOT3D curvilinear grids.
// Everything here needs the C++ standard library only (the decoder-only build
// compiles it and fuzzes the readers).
//
// Formats, chosen by the file name's extension (case ignored):
//   .mesh        MEDIT ASCII (MeshVersionFormatted 1 or 2, Dimension 3)
//   .node/.ele   TetGen: a pair of files with the same base name; either may be named
//   .vtu         VTK XML UnstructuredGrid
//   .vtk         VTK legacy, DATASET UNSTRUCTURED_GRID (versions 2.0 to 5.1)
//
// Reading
//   MEDIT  `Vertices` (x y z ref) and `Tetrahedra` (a b c d ref, 1-based); every
//          other section (Triangles, Edges, Corners, Normals, ...) is read past
//          by its count; reference numbers are ignored. MEDIT has no fields.
//   TetGen .node `n 3 attributes markers`, then `i x y z attr... [marker]`; the
//          first node's number says whether indices are 0- or 1-based, and the
//          .ele (`m 4 region`, `i a b c d [region]`) must use the same base.
//          Attributes become fields named by a `# fields: NAME...` comment
//          (written by us) or else attribute1, attribute2, ...; markers and
//          regions are ignored. 10-node (quadratic) .ele files are refused.
//   VTU    one Piece; Points and the Cells arrays connectivity, offsets, types;
//          every PointData array (Float32/64, Int8..64, UInt8..64) becomes a
//          field, an array of k > 1 components k fields NAME_0 .. NAME_k-1.
//          DataArray format ascii, binary (base64, header_type UInt32 or UInt64,
//          header and data in one base64 run or each in its own) and appended
//          (AppendedData encoding raw or base64); either byte_order. Compressed
//          files (a `compressor` attribute) are refused: zlib is not a
//          dependency of the library.
//   VTK    ASCII or BINARY (big-endian), POINTS, CELLS (the classic `n size`
//          list or the 5.1 OFFSETS/CONNECTIVITY pair), CELL_TYPES, POINT_DATA
//          with SCALARS (LOOKUP_TABLE read past) and FIELD arrays as fields;
//          VECTORS/NORMALS/TENSORS/..., CELL_DATA and METADATA are read past.
//   Cells (VTU, VTK): tetrahedra (VTK type 10) are read; vertices, lines,
//   polygons and other cells of dimension 0 to 2 (types 1 to 9) are skipped,
//   as MEDIT's boundary Triangles are; any other 3-D cell (hexahedron, wedge,
//   quadratic tet, ...) is refused with an error naming the cell.
//   Every reader checks each index against the vertex count and each count
//   against the bytes left (before allocating), and refuses NaN/Inf and
//   coordinates outside kMaxCoordinate (see orient3dSign). Errors are one line
//   naming the file, the line (text) or byte offset (binary) and the rule.
//   Orientation (decision D38): a tet with det[b-a, c-a, d-a] < 0 is repaired
//   by swapping its last two vertices (MEDIT and TetGen files of either
//   convention exist) and counted in TetReadReport::flipped; a tet with
//   det == 0 (exact test) is an error naming it.
//
// Writing
//   MEDIT  MeshVersionFormatted 2, Vertices and Tetrahedra (reference 0/1),
//          shortest round-trip decimals. MEDIT has no place for fields: they
//          are not written (TetWriteReport::fields_dropped counts them).
//   TetGen .node (0-based, fields as attributes, a `# fields:` comment naming
//          them) and .ele, shortest round-trip decimals.
//   VTU    Float64 points, Int64 connectivity and offsets, UInt8 types, Float64
//          point data; binary (base64, UInt64 header, one run per array) or
//          ascii with 17 significant digits.
//   VTK    version 3.0, BINARY (big-endian) or ASCII, double points, one
//          SCALARS array per field.
//   Writing then reading gives the identical mesh (positions bit-exact).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/grid.h"
#include "mrsv/tet_mesh.h"

namespace mrsv {

enum class TetFormat { kMedit, kTetgen, kVtu, kVtkLegacy, kUnknown };

// By extension: .mesh, .node or .ele, .vtu, .vtk (any case); else kUnknown.
TetFormat tetFormatOf(const std::string& path);

// "name.node" and "name.ele" for a path ending in either.
std::string tetgenNodePath(const std::string& path);
std::string tetgenElePath(const std::string& path);

// Coordinates of magnitude above this, or non-zero below kMinCoordinate, are
// refused by the readers: inside the range the orientation test is exact.
constexpr double kMaxCoordinate = 1e50;
constexpr double kMinCoordinate = 1e-50;

// The sign of det[b - a, c - a, d - a]: +1, -1 or 0, exact for coordinates
// that are 0 or of magnitude in [kMinCoordinate, kMaxCoordinate] (a
// floating-point filter with a proven error bound, and exact expansion
// arithmetic when the filter cannot decide).
int orient3dSign(const std::array<double, 3>& a, const std::array<double, 3>& b,
                 const std::array<double, 3>& c, const std::array<double, 3>& d);

// Makes every tet of `mesh` positively oriented by swapping its last two
// vertices where det < 0; `flipped` counts them. Fails (one line in `error`,
// naming the tet by its 0-based number) on a degenerate tet (det == 0) or an
// index out of range.
bool orientTets(TetMesh* mesh, uint64_t* flipped, std::string* error);

struct TetReadReport {
  uint64_t flipped = 0;         // negatively oriented tets repaired (vertices swapped)
  uint64_t skipped_cells = 0;   // VTU/VTK cells of dimension 0 to 2 left out
};

// Reads a tet mesh file (for TetGen, `path` names the .node or the .ele and the
// other is found beside it). On failure returns false, leaves `mesh` empty and
// sets `error` to one line, e.g. "a.vtk:12: CELLS: cell 7 has vertex index 90
// out of range (80 points)". `report` may be null.
bool readTetFile(const std::string& path, TetMesh* mesh, TetReadReport* report,
                 std::string* error);

// As readTetFile for a file in memory (not TetGen: see readTetgenBytes);
// `name` is used in messages only. Safe on any bytes.
bool readTetBytes(const std::string& name, TetFormat format, const uint8_t* data, size_t size,
                  TetMesh* mesh, TetReadReport* report, std::string* error);
bool readTetgenBytes(const std::string& node_name, const uint8_t* node, size_t node_size,
                     const std::string& ele_name, const uint8_t* ele, size_t ele_size,
                     TetMesh* mesh, TetReadReport* report, std::string* error);

struct TetWriteOptions {
  bool ascii = false;  // VTU and VTK: text instead of binary
};

struct TetWriteReport {
  size_t fields_dropped = 0;  // fields a format had no place for (MEDIT)
};

// One output file: TetGen makes two (.node and .ele), the others one.
struct TetFileBytes {
  std::string path;
  std::vector<uint8_t> bytes;
};

// The bytes of the file(s) for `path`'s format. Fails (one line in `error`) on
// an unknown extension, an index out of range, a non-finite coordinate, a
// field whose value count is not the vertex count or whose name is empty or
// holds white space or any of " ' < > &.
bool encodeTetFile(const std::string& path, const TetMesh& mesh, const TetWriteOptions& options,
                   std::vector<TetFileBytes>* files, TetWriteReport* report, std::string* error);

// encodeTetFile, then each file written through a temporary name and renamed.
bool writeTetFile(const std::string& path, const TetMesh& mesh, const TetWriteOptions& options,
                  TetWriteReport* report, std::string* error);

// ---- Tet meshes from data -------------------------------------------------

// What a tetrahedralization did.
struct TetBuildReport {
  uint64_t cells = 0;             // cubes or hexahedra tetrahedralized
  uint64_t cells_left_out = 0;    // cells with a no-data sample or an IBLANK 0 corner
  uint64_t flipped = 0;           // tets made positive by swapping two vertices
  uint64_t welded = 0;            // PLOT3D: points merged into an earlier one at the same position
  uint64_t collapsed = 0;         // PLOT3D: tets dropped, two of their corners welded together
  uint64_t cut_from_corner = 0;   // PLOT3D: hexahedra cut into 6 tets from a corner, not 5
  uint64_t cut_around_centroid = 0;  // PLOT3D: hexahedra cut into 12 tets around an added vertex
};

// A box of samples: origin and size per axis (size 0: to the end of the axis).
struct GridCrop {
  uint32_t origin[3] = {0, 0, 0};
  uint32_t size[3] = {0, 0, 0};
};

// A 3-D grid of samples (little-endian bytes as GridInput and DecodedGrid hold
// them, x fastest) as 6 tets per cube of 8 neighbouring samples: the cube is
// cut along its diagonal from the lowest to the highest corner into the six
// tets of the coordinate permutations, so every cube face is cut along the
// same diagonal from both sides and the mesh is conforming. Vertex (x, y, z)
// of the crop lies at ((x0 + x) * sx, (y0 + y) * sy, (z0 + z) * sz) and holds
// the sample as the field "value". An X x Y x Z crop gives 6 (X-1)(Y-1)(Z-1)
// tets. Cubes with a no-data sample (header.hasNodata()) are left out, and the
// samples they alone used with them. Spacings must be non-zero and finite.
bool tetrahedralizeGrid(const GridHeader& header, const std::vector<uint8_t>& samples,
                        const double spacing[3], const GridCrop& crop, TetMesh* mesh,
                        TetBuildReport* report, std::string* error);

// A single-block 3-D PLOT3D grid (binary, no record markers, float32, either
// byte order; big-endian as VTK reads by default) and its optional solution.
struct Plot3dData {
  uint32_t dims[3] = {0, 0, 0};           // ni, nj, nk
  std::vector<std::array<double, 3>> xyz; // i fastest
  std::vector<int32_t> iblank;            // empty when the grid has none
  std::vector<ScalarField> q;             // density, momentum_x/y/z, energy; empty without .q
  float q_header[4] = {0, 0, 0, 0};       // fsmach, alpha, re, time
};

// Reads `xyz_path` and, when not empty, `q_path` (whose dims must match). The
// .xyz holds 12 + 12 N bytes, or 12 + 16 N with IBLANK; the .q at least
// 12 + 16 + 20 N (trailing bytes, as the blunt fin's 484, are ignored).
bool readPlot3d(const std::string& xyz_path, const std::string& q_path, Plot3dData* data,
                std::string* error);
bool readPlot3dBytes(const std::string& xyz_name, const uint8_t* xyz, size_t xyz_size,
                     const std::string& q_name, const uint8_t* q, size_t q_size,
                     Plot3dData* data, std::string* error);

// 5 tets per hexahedron: the tet of the four corners whose (i + j + k) is even
// and the four corner tets around it, so neighbouring hexahedra cut their
// common face along the same diagonal. Hexahedra with a corner whose IBLANK is
// 0 are left out, and vertices no tet uses dropped. The q variables become
// the fields. Grid points at exactly the same position are welded into the
// first of them (its q values kept): curvilinear grids have collapsed edges
// (the blunt fin: 39 at k = 0) and seams (the LOX post's O-grid: 1,444), and
// without the weld those would be zero-volume tets and slits. A tet with two
// corners welded together has no volume and is dropped (counted). Where the
// 5-tet cut does not fit (decision D45) a hexahedron is cut differently, each
// face still along the diagonal its neighbour uses: a face that a weld makes
// common to two hexahedra that are not grid neighbours (a seam whose ring of
// hexahedra has an odd count, where the parity does not alternate) takes the
// first hexahedron's diagonal, and a hexahedron whose faces then differ from
// its parity's, or whose 5 tets are not all alike oriented (a distorted cell,
// two in the combustion chamber), is cut into 6 tets from a corner that the
// diagonals of its three faces meet, or else into 12 tets around an added
// vertex at the mean of its corners (its field values the mean of theirs).
// The tets of a left-handed hexahedron are flipped (counted). A hexahedron
// that none of the cuts gives tets of one orientation is an error naming it.
// The meshes of the real grids of ../shared/data/tet are 3-manifolds of
// positive tets (tested); a grid that folds onto itself gives no such mesh.
bool tetrahedralizePlot3d(const Plot3dData& data, TetMesh* mesh, TetBuildReport* report,
                          std::string* error);

}  // namespace mrsv
