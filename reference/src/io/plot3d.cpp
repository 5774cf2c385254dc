// PLOT3D single-block 3-D grids and solutions (binary, float32, no Fortran
// record markers: the layout VTK's vtkMultiBlockPLOT3DReader reads by
// default), and their tetrahedralization with 5 tets per hexahedron (6 or 12
// where 5 do not fit: decision D45).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "io/tet_build.h"
#include "io/tet_format_codecs.h"
#include "mrsv/file_io.h"
#include "mrsv/tet_formats.h"

namespace mrsv {
namespace {

uint32_t load32(const uint8_t* p, bool big_endian) {
  return big_endian ? (uint32_t(p[0]) << 24) | (uint32_t(p[1]) << 16) | (uint32_t(p[2]) << 8) | p[3]
                    : (uint32_t(p[3]) << 24) | (uint32_t(p[2]) << 16) | (uint32_t(p[1]) << 8) | p[0];
}

float loadFloat(const uint8_t* p, bool big_endian) {
  uint32_t bits = load32(p, big_endian);
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

// ni, nj, nk and their product, or false when any is not from 1 to 2^31-1
// or the product exceeds 2^32-1.
bool dims(const uint8_t* p, bool big_endian, uint32_t out[3], uint64_t* n) {
  *n = 1;
  for (int a = 0; a < 3; ++a) {
    out[a] = load32(p + 4 * a, big_endian);
    if (out[a] < 1 || out[a] > INT32_MAX) return false;
    *n *= out[a];
    if (*n > UINT32_MAX) return false;  // more points than a TetMesh indexes (and no overflow)
  }
  return true;
}

std::string dimsText(const uint32_t d[3]) {
  return std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]);
}

}  // namespace

bool readPlot3dBytes(const std::string& xyz_name, const uint8_t* xyz, size_t xyz_size,
                     const std::string& q_name, const uint8_t* q, size_t q_size, Plot3dData* data,
                     std::string* error) {
  *data = Plot3dData{};
  if (xyz_size < 12) {
    *error = xyz_name + ": " + std::to_string(xyz_size) + " bytes cannot hold the ni nj nk header";
    return false;
  }
  // The byte order whose dims match the file size; big-endian first.
  bool big_endian = true, iblank = false;
  uint64_t n = 0;
  bool found = false;
  for (bool be : {true, false}) {
    uint32_t d[3];
    uint64_t count;
    if (!dims(xyz, be, d, &count) || count > (xyz_size - 12) / 12) continue;
    if (xyz_size - 12 == 12 * count || xyz_size - 12 == 16 * count) {
      big_endian = be;
      iblank = xyz_size - 12 == 16 * count;
      n = count;
      std::memcpy(data->dims, d, sizeof d);
      found = true;
      break;
    }
  }
  if (!found) {
    uint32_t d[3] = {load32(xyz, true), load32(xyz + 4, true), load32(xyz + 8, true)};
    *error = xyz_name + ": byte 0: header ni nj nk = " + dimsText(d) + " (big-endian) but the file has " +
             std::to_string(xyz_size) + " bytes, not 12 + 12 N or 12 + 16 N (N points, with IBLANK): "
             "only single-block binary grids without record markers are read";
    return false;
  }
  data->xyz.resize(n);
  for (int a = 0; a < 3; ++a)
    for (uint64_t v = 0; v < n; ++v) {
      const size_t offset = 12 + 4 * (a * n + v);
      double c = loadFloat(xyz + offset, big_endian);
      if (std::string why = tet_io::coordinateProblem(c); !why.empty()) {
        *error = xyz_name + ": byte " + std::to_string(offset) + ": point " + std::to_string(v) + " " +
                 "xyz"[a] + " coordinate " + why;
        return false;
      }
      data->xyz[v][a] = c;
    }
  if (iblank) {
    data->iblank.resize(n);
    for (uint64_t v = 0; v < n; ++v)
      data->iblank[v] = static_cast<int32_t>(load32(xyz + 12 + 12 * n + 4 * v, big_endian));
  }
  if (q_name.empty()) return true;

  const uint64_t need = 12 + 16 + 20 * n;
  if (q_size < 12) {
    *error = q_name + ": " + std::to_string(q_size) + " bytes cannot hold the ni nj nk header";
    return false;
  }
  uint32_t qd[3] = {load32(q, big_endian), load32(q + 4, big_endian), load32(q + 8, big_endian)};
  if (std::memcmp(qd, data->dims, sizeof qd) != 0) {
    *error = q_name + ": byte 0: solution dims " + dimsText(qd) + " differ from the grid's " + dimsText(data->dims);
    return false;
  }
  if (q_size < need) {
    *error = q_name + ": " + std::to_string(q_size) + " bytes, but the header, fsmach, alpha, re, time and "
             "5 arrays of " + std::to_string(n) + " float32 need " + std::to_string(need);
    return false;
  }
  for (int k = 0; k < 4; ++k) data->q_header[k] = loadFloat(q + 12 + 4 * k, big_endian);
  static const char* const kNames[5] = {"density", "momentum_x", "momentum_y", "momentum_z", "energy"};
  data->q.resize(5);
  for (int f = 0; f < 5; ++f) {
    data->q[f].name = kNames[f];
    data->q[f].values.resize(n);
    for (uint64_t v = 0; v < n; ++v) {
      const size_t offset = 28 + 4 * (f * n + v);
      double value = loadFloat(q + offset, big_endian);
      if (!std::isfinite(value)) {
        *error = q_name + ": byte " + std::to_string(offset) + ": " + kNames[f] + " at point " +
                 std::to_string(v) + " is not finite";
        return false;
      }
      data->q[f].values[v] = value;
    }
  }
  return true;
}

bool readPlot3d(const std::string& xyz_path, const std::string& q_path, Plot3dData* data,
                std::string* error) {
  std::vector<uint8_t> xyz, q;
  if (!readWholeFile(xyz_path, &xyz, error)) {
    *error = xyz_path + ": " + *error;
    return false;
  }
  if (!q_path.empty() && !readWholeFile(q_path, &q, error)) {
    *error = q_path + ": " + *error;
    return false;
  }
  return readPlot3dBytes(xyz_path, xyz.data(), xyz.size(), q_path, q.data(), q.size(), data, error);
}

namespace {

// The 5-tet split of a hexahedron whose corner (0,0,0) has parity p: the
// central tet of the four corners of local parity p (those of even global
// parity), and a tet at each other corner with its three neighbours. Each
// face is cut along the diagonal joining its two corners of local parity p.
struct HexTemplates {
  std::array<std::array<int, 4>, 5> tets[2];
  HexTemplates() {
    for (int p = 0; p < 2; ++p) {
      int central[4], n = 0, t = 1;
      for (int c = 0; c < 8; ++c) {
        if ((__builtin_popcount(static_cast<unsigned>(c)) & 1) == p) {
          central[n++] = c;
        } else {
          tets[p][t++] = {c, c ^ 1, c ^ 2, c ^ 4};
        }
      }
      tets[p][0] = {central[0], central[1], central[2], central[3]};
      tet_build::orientTemplate(tets[p].data(), 5);
    }
  }
};

int parity(int corner) { return __builtin_popcount(static_cast<unsigned>(corner)) & 1; }

// Face f = 2 * axis + side of a hexahedron: its corners in cyclic order.
std::array<int, 4> faceCorners(int f) {
  const int axis = f >> 1, u = 1 << ((axis + 1) % 3), w = 1 << ((axis + 2) % 3);
  const int base = (f & 1) << axis;
  return {base, base | u, base | u | w, base | w};
}

// The tets from `apex` (a corner 0-7, or 8: the centroid) to the triangles of
// the faces not holding it, face f cut along the diagonal joining its two
// corners of local parity q[f]; oriented positively on the unit cube. Returns
// the count (12 from the centroid, 6 from a corner).
size_t coneTets(int apex, const int q[6], std::array<int, 4>* out) {
  auto point = [](int c) {
    return c == 8
               ? std::array<double, 3>{0.5, 0.5, 0.5}
               : std::array<double, 3>{double(c & 1), double((c >> 1) & 1), double((c >> 2) & 1)};
  };
  size_t n = 0;
  for (int f = 0; f < 6; ++f) {
    if (apex < 8 && ((apex >> (f >> 1)) & 1) == (f & 1)) continue;  // the apex's own face
    std::array<int, 4> c = faceCorners(f);
    if (parity(c[0]) != q[f]) c = {c[1], c[2], c[3], c[0]};  // the diagonal from c[0] to c[2]
    for (const std::array<int, 3>& tri :
         {std::array<int, 3>{c[0], c[1], c[2]}, std::array<int, 3>{c[0], c[2], c[3]}}) {
      std::array<int, 4> tet = {tri[0], tri[1], tri[2], apex};
      if (orient3dSign(point(tet[0]), point(tet[1]), point(tet[2]), point(tet[3])) < 0)
        std::swap(tet[0], tet[1]);
      out[n++] = tet;
    }
  }
  return n;
}

std::string hexName(uint32_t i, uint32_t j, uint32_t k) {
  return "hexahedron (i, j, k) = (" + std::to_string(i) + ", " + std::to_string(j) + ", " +
         std::to_string(k) + ")";
}

}  // namespace

bool tetrahedralizePlot3d(const Plot3dData& data, TetMesh* mesh, TetBuildReport* report,
                          std::string* error) {
  *mesh = TetMesh{};
  *report = TetBuildReport{};
  const uint32_t ni = data.dims[0], nj = data.dims[1], nk = data.dims[2];
  const uint64_t n = uint64_t{ni} * nj * nk;
  if (ni < 2 || nj < 2 || nk < 2) {
    *error = "the grid is " + dimsText(data.dims) + ": hexahedra need 2 points along each axis";
    return false;
  }
  if (data.xyz.size() != n || (!data.iblank.empty() && data.iblank.size() != n)) {
    *error = "the grid's arrays do not hold " + std::to_string(n) + " points";
    return false;
  }
  if (n > UINT32_MAX) {
    *error = "more than 2^32-1 points";
    return false;
  }
  for (const ScalarField& f : data.q)
    if (f.values.size() != n) {
      *error = "solution '" + f.name + "' does not hold " + std::to_string(n) + " values";
      return false;
    }
  static const HexTemplates kHex;
  tet_build::Builder builder(n, data.q.size());
  builder.positions = data.xyz;
  for (size_t f = 0; f < data.q.size(); ++f) builder.fields[f] = data.q[f];
  report->welded = builder.weld();

  auto cornersOf = [&](uint32_t i, uint32_t j, uint32_t k, uint32_t corner[8]) {
    bool blank = false;
    for (int c = 0; c < 8; ++c) {
      corner[c] = static_cast<uint32_t>(
          (i + (c & 1)) + uint64_t{ni} * ((j + ((c >> 1) & 1)) + uint64_t{nj} * (k + (c >> 2))));
      if (!data.iblank.empty() && data.iblank[corner[c]] == 0) blank = true;
    }
    return blank;
  };
  const uint64_t cells = uint64_t{ni - 1} * (nj - 1) * (nk - 1);

  // Faces that welding makes common to two hexahedra that are not neighbours
  // in the grid (the LOX post's seam) may be cut along different diagonals
  // from the two sides: the parity of i + j + k is not periodic when a ring
  // of hexahedra has an odd count (75 there). Such a face takes the diagonal
  // its first hexahedron (in grid order) gives it, and the other hexahedron
  // takes note (a bit per face) and is cut to match below. Only faces with a
  // welded corner can be common to two hexahedra other than grid neighbours.
  std::vector<uint8_t> other_diagonal;
  if (report->welded > 0) {
    std::vector<bool> in_weld(n, false);
    for (uint32_t v = 0; v < n; ++v)
      if (builder.canonical[v] != v) in_weld[v] = in_weld[builder.canonical[v]] = true;
    struct FaceUse {
      std::array<uint32_t, 4> key;  // the corners' welded numbers, sorted
      uint64_t cell;
      int face;
      std::array<uint32_t, 2> diagonal[2];  // along the corners of local parity 0, 1; sorted
    };
    std::vector<FaceUse> uses;
    uint64_t cell = 0;
    for (uint32_t k = 0; k + 1 < nk; ++k)
      for (uint32_t j = 0; j + 1 < nj; ++j)
        for (uint32_t i = 0; i + 1 < ni; ++i, ++cell) {
          uint32_t corner[8];
          if (cornersOf(i, j, k, corner)) continue;
          for (int f = 0; f < 6; ++f) {
            const std::array<int, 4> c = faceCorners(f);
            bool welded = false;
            FaceUse use{{}, cell, f, {}};
            for (int m = 0; m < 4; ++m) {
              welded |= in_weld[corner[c[m]]];
              use.key[m] = builder.canonical[corner[c[m]]];
            }
            if (!welded) continue;
            for (int d = 0; d < 2; ++d) {
              uint32_t a = use.key[d], b = use.key[d + 2];
              use.diagonal[parity(c[d])] = {std::min(a, b), std::max(a, b)};
            }
            std::sort(use.key.begin(), use.key.end());
            if (std::adjacent_find(use.key.begin(), use.key.end()) != use.key.end())
              continue;  // collapsed: one cut
            uses.push_back(use);
          }
        }
    std::sort(uses.begin(), uses.end(), [](const FaceUse& a, const FaceUse& b) {
      return a.key != b.key ? a.key < b.key : a.cell < b.cell;
    });
    for (size_t u = 1; u < uses.size(); ++u) {
      size_t first = u - 1;
      while (first > 0 && uses[first - 1].key == uses[u].key) --first;
      if (uses[first].key != uses[u].key) continue;
      auto own = [&](const FaceUse& use) {  // the diagonal the cell's parity gives the face
        const uint64_t i = use.cell % (ni - 1), j = use.cell / (ni - 1) % (nj - 1),
                       k = use.cell / (ni - 1) / (nj - 1);
        return use.diagonal[(i + j + k) & 1];
      };
      const std::array<uint32_t, 2> wanted = own(uses[first]);
      if (own(uses[u]) == wanted) continue;
      const FaceUse& use = uses[u];
      const uint64_t i = use.cell % (ni - 1), j = use.cell / (ni - 1) % (nj - 1),
                     k = use.cell / (ni - 1) / (nj - 1);
      if (use.diagonal[0] != wanted && use.diagonal[1] != wanted) {
        const FaceUse& f = uses[first];
        *error = hexName(uint32_t(i), uint32_t(j), uint32_t(k)) + " and " +
                 hexName(uint32_t(f.cell % (ni - 1)), uint32_t(f.cell / (ni - 1) % (nj - 1)),
                         uint32_t(f.cell / (ni - 1) / (nj - 1))) +
                 " have a face with the same corners but not the same edges";
        return false;
      }
      if (other_diagonal.empty()) other_diagonal.assign(cells, 0);
      other_diagonal[use.cell] |= uint8_t(1u << use.face);
    }
  }

  // Each hexahedron: the 5-tet cut of its parity when its faces take that
  // cut's diagonals and its tets are alike oriented; else 6 tets from a
  // corner that the diagonals of its three faces all meet; else 12 tets
  // around an added vertex at its centroid (the mean of its corners, as are
  // its field values). All three cut every face along the same diagonal.
  builder.reserveTets(5 * cells);
  uint64_t cell = 0;
  for (uint32_t k = 0; k + 1 < nk; ++k)
    for (uint32_t j = 0; j + 1 < nj; ++j)
      for (uint32_t i = 0; i + 1 < ni; ++i, ++cell) {
        uint32_t corner[8];
        const bool blank = cornersOf(i, j, k, corner);
        ++report->cells;
        if (blank) {
          ++report->cells_left_out;
          continue;
        }
        const int p = (i + j + k) & 1;
        const uint8_t other = other_diagonal.empty() ? 0 : other_diagonal[cell];
        std::array<uint32_t, 4> tets[12];
        if (other == 0) {
          for (int t = 0; t < 5; ++t)
            for (int m = 0; m < 4; ++m) tets[t][m] = corner[kHex.tets[p][t][m]];
          if (builder.addCell(tets, 5)) continue;
        }
        int q[6];
        for (int f = 0; f < 6; ++f) q[f] = p ^ ((other >> f) & 1);
        std::array<int, 4> cone[12];
        bool done = false;
        for (int apex = 0; apex < 8 && !done; ++apex) {
          bool meets = true;  // the diagonals of the apex's three faces all end at it
          for (int axis = 0; axis < 3; ++axis)
            meets &= q[2 * axis + ((apex >> axis) & 1)] == parity(apex);
          if (!meets) continue;
          const size_t count = coneTets(apex, q, cone);
          for (size_t t = 0; t < count; ++t)
            for (int m = 0; m < 4; ++m) tets[t][m] = corner[cone[t][m]];
          done = builder.addCell(tets, count);
        }
        if (done) {
          ++report->cut_from_corner;
          continue;
        }
        std::array<double, 3> centre = {0, 0, 0};
        std::vector<double> values(builder.fields.size(), 0.0);
        for (int c = 0; c < 8; ++c) {
          const uint32_t v = builder.canonical.empty() ? corner[c] : builder.canonical[corner[c]];
          for (int a = 0; a < 3; ++a) centre[a] += builder.positions[v][a] / 8;
          for (size_t f = 0; f < values.size(); ++f) values[f] += builder.fields[f].values[v] / 8;
        }
        if (builder.positions.size() >= UINT32_MAX) {
          *error = hexName(i, j, k) + " needs a centroid vertex past 2^32-1 vertices";
          return false;
        }
        const uint32_t added = builder.addVertex(centre, values);
        const size_t count = coneTets(8, q, cone);
        for (size_t t = 0; t < count; ++t)
          for (int m = 0; m < 4; ++m) tets[t][m] = cone[t][m] == 8 ? added : corner[cone[t][m]];
        if (!builder.addCell(tets, count)) {
          *error = hexName(i, j, k) +
                   " cannot be cut into tets of one orientation: its 5-tet cut, the 6 tets "
                   "from a corner and the 12 around its centroid each give a flat tet or tets of "
                   "both orientations";
          return false;
        }
        ++report->cut_around_centroid;
      }
  report->flipped = builder.flipped;
  report->collapsed = builder.collapsed;
  builder.finish(mesh);
  return true;
}

}  // namespace mrsv
