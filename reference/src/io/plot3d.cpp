// PLOT3D single-block 3-D grids and solutions (binary, float32, no Fortran
// record markers: the layout VTK's vtkMultiBlockPLOT3DReader reads by
// default), and their tetrahedralization with 5 tets per hexahedron.
#include <cmath>
#include <cstring>

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
// parity), and a tet at each other corner with its three neighbours.
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
  builder.reserveTets(5 * uint64_t{ni - 1} * (nj - 1) * (nk - 1));
  for (uint32_t k = 0; k + 1 < nk; ++k)
    for (uint32_t j = 0; j + 1 < nj; ++j)
      for (uint32_t i = 0; i + 1 < ni; ++i) {
        uint32_t corner[8];
        bool blank = false;
        for (int c = 0; c < 8; ++c) {
          corner[c] = static_cast<uint32_t>((i + (c & 1)) + uint64_t{ni} * ((j + ((c >> 1) & 1)) +
                                                                          uint64_t{nj} * (k + (c >> 2))));
          if (!data.iblank.empty() && data.iblank[corner[c]] == 0) blank = true;
        }
        ++report->cells;
        if (blank) {
          ++report->cells_left_out;
          continue;
        }
        for (const auto& t : kHex.tets[(i + j + k) & 1])
          if (!builder.addTet({corner[t[0]], corner[t[1]], corner[t[2]], corner[t[3]]})) {
            *error = "hexahedron (i, j, k) = (" + std::to_string(i) + ", " + std::to_string(j) + ", " +
                     std::to_string(k) + ") gives a degenerate tet (corners " + std::to_string(corner[t[0]]) +
                     " " + std::to_string(corner[t[1]]) + " " + std::to_string(corner[t[2]]) + " " +
                     std::to_string(corner[t[3]]) + " lie in one plane)";
            return false;
          }
      }
  report->flipped = builder.flipped;
  report->collapsed = builder.collapsed;
  builder.finish(mesh);
  return true;
}

}  // namespace mrsv
