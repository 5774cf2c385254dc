// spec: 8.1 sample field, 8.2 canonical output of a reconstructed mesh.
#include "mrsv/grid_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <numeric>

namespace mrsv {
namespace {

template <typename T>
void widen(const std::vector<uint8_t>& bytes, std::vector<int32_t>* out) {
  const size_t n = bytes.size() / sizeof(T);
  out->resize(n);
  for (size_t i = 0; i < n; ++i) {
    T v;
    std::memcpy(&v, bytes.data() + i * sizeof(T), sizeof(T));  // little-endian hosts only (spec 1)
    (*out)[i] = static_cast<int32_t>(v);
  }
}

void putU32(std::vector<uint8_t>* out, uint32_t v) {
  for (int k = 0; k < 4; ++k) out->push_back(static_cast<uint8_t>(v >> (8 * k)));
}

// Parses a spec 2.6 number-list of up to three numbers into `values`,
// leaving the axes it does not name as they were.
bool parseNumberList(const std::string& text, double values[3]) {
  size_t start = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v)) return false;
    values[axis] = v;
    if (comma == std::string::npos) return true;
    start = comma + 1;
  }
  return false;  // more than three numbers
}

}  // namespace

bool sampleFieldFromGrid(const DecodedGrid& grid, SampleField* field, std::string* error) {
  const GridHeader& h = grid.header;
  if (!grid.has_samples) {
    *error = "the stream holds no samples (no band decoded)";
    return false;
  }
  if (h.num_dims < 2) {
    *error = "the grid is 1-D; the reconstructors mesh 2-D and 3-D grids";
    return false;
  }
  field->size[0] = grid.output_size[0];
  field->size[1] = grid.output_size[1];
  field->size[2] = h.num_dims == 3 ? grid.output_size[2] : 1;
  // spec 8.1 (2-D) and 10 (3-D): every side from 2 samples, at most 2^16 in
  // 2-D and 2^15 in 3-D, so that the exact products fit 128 bits.
  const uint32_t largest = h.num_dims == 3 ? 32768 : 65536;
  for (int a = 0; a < h.num_dims; ++a)
    if (field->size[a] < 2 || field->size[a] > largest) {
      *error = "the grid is " + std::to_string(field->size[0]) + " x " + std::to_string(field->size[1]) +
               (h.num_dims == 3 ? " x " + std::to_string(field->size[2]) : std::string()) +
               "; the reconstructors take sides of 2 to " + std::to_string(largest) + " samples (spec 8.1)";
      return false;
    }
  switch (h.sample_type) {
    case SampleType::kUint8: widen<uint8_t>(grid.samples, &field->values); break;
    case SampleType::kInt16: widen<int16_t>(grid.samples, &field->values); break;
    case SampleType::kUint16: widen<uint16_t>(grid.samples, &field->values); break;
    case SampleType::kInt32: widen<int32_t>(grid.samples, &field->values); break;
    default:
      *error = std::string("samples of type ") + sampleTypeName(h.sample_type) +
               " are not integers; the reconstructors read integer samples (spec 8.1)";
      return false;
  }
  if (field->values.size() != uint64_t{field->size[0]} * field->size[1] * field->size[2]) {
    *error = "the decoded sample count does not match the grid's sizes";
    return false;
  }
  return true;
}

bool parseErrorBound(const std::string& text, ErrorBound* bound) {
  int64_t num = 0, den = 1;
  size_t i = 0, digits = 0, decimals = 0;
  bool point = false;
  for (; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '.' && !point) {
      point = true;
      continue;
    }
    if (c < '0' || c > '9') return false;
    if (point && ++decimals > 9) return false;
    num = num * 10 + (c - '0');
    if (point) den *= 10;
    if (num > (int64_t{1} << 31) * den) return false;
    ++digits;
  }
  if (digits == 0) return false;
  while (den > 1 && num % 10 == 0) num /= 10, den /= 10;
  bound->num = num;
  bound->den = den;
  return true;
}

std::vector<uint8_t> canonicalGridMeshOutput(const GridMesh& mesh) {
  const size_t nv = mesh.points.size();
  const int corners = mesh.dims == 3 ? 4 : 3;
  // Vertices in ascending linear sample index.
  std::vector<uint32_t> order(nv);
  std::iota(order.begin(), order.end(), 0u);
  auto linear = [&](uint32_t v) {
    const auto& p = mesh.points[v];
    return (uint64_t{p[2]} * mesh.size[1] + p[1]) * mesh.size[0] + p[0];
  };
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return linear(a) < linear(b); });
  std::vector<uint32_t> rank(nv);
  for (uint32_t i = 0; i < nv; ++i) rank[order[i]] = i;

  // Cells renumbered, each in its canonical rotation, then sorted.
  std::vector<std::array<uint32_t, 4>> cells;
  cells.reserve(mesh.cells.size());
  for (const auto& c : mesh.cells) {
    std::array<uint32_t, 4> r = {rank[c[0]], rank[c[1]], rank[c[2]], corners == 4 ? rank[c[3]] : 0u};
    if (corners == 3) {
      // Rotate the smallest index first; the cyclic order (orientation) stays.
      const int m = r[0] < r[1] ? (r[0] < r[2] ? 0 : 2) : (r[1] < r[2] ? 1 : 2);
      r = {r[m], r[(m + 1) % 3], r[(m + 2) % 3], 0u};
    } else {
      // Ascending, then the last two swapped if that took an odd permutation,
      // so the orientation stays.
      int swaps = 0;
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j + 1 < 4 - i; ++j)
          if (r[j] > r[j + 1]) std::swap(r[j], r[j + 1]), ++swaps;
      if (swaps % 2) std::swap(r[2], r[3]);
    }
    cells.push_back(r);
  }
  std::sort(cells.begin(), cells.end());

  const std::string line = "mrsv-canonical-grid-mesh 1 " + std::to_string(mesh.dims) + " " +
                           std::to_string(nv) + " " + std::to_string(cells.size()) + "\n";
  std::vector<uint8_t> out(line.begin(), line.end());
  out.reserve(out.size() + nv * 16 + cells.size() * 4 * corners);
  for (uint32_t v : order) {
    for (int k = 0; k < 3; ++k) putU32(&out, mesh.points[v][k]);
    putU32(&out, static_cast<uint32_t>(mesh.values[v]));
  }
  for (const auto& c : cells)
    for (int k = 0; k < corners; ++k) putU32(&out, c[k]);
  return out;
}

bool gridMeshGeometryFromMetadata(const Metadata& metadata, int dims, GridMeshGeometry* geometry,
                                  std::string* error) {
  for (const char* key : {"spacing", "origin"}) {
    const std::string* text = metadata.find(key);
    if (!text) continue;
    double* values = std::strcmp(key, "spacing") == 0 ? geometry->spacing : geometry->origin;
    double parsed[3] = {values[0], values[1], values[2]};
    if (!parseNumberList(*text, parsed)) {
      *error = std::string("meta entry '") + key + "' is '" + *text + "', not 1 to 3 finite numbers";
      return false;
    }
    for (int k = 0; k < dims; ++k) values[k] = parsed[k];
  }
  return true;
}

TriangleMesh gridMeshToTriangles(const GridMesh& mesh, const GridMeshGeometry& g) {
  TriangleMesh out;
  out.positions.reserve(mesh.points.size());
  out.scalars.reserve(mesh.points.size());
  for (size_t v = 0; v < mesh.points.size(); ++v) {
    const auto& p = mesh.points[v];
    out.positions.push_back({g.origin[0] + p[0] * g.spacing[0], g.origin[1] + p[1] * g.spacing[1],
                             mesh.values[v] * g.z_scale});
    out.scalars.push_back(mesh.values[v]);
  }
  // A negative spacing mirrors the map; keep the triangles facing up.
  const bool flip = (g.spacing[0] < 0) != (g.spacing[1] < 0);
  out.triangles.reserve(mesh.cells.size());
  for (const auto& c : mesh.cells)
    out.triangles.push_back(flip ? std::array<uint32_t, 3>{c[0], c[2], c[1]}
                                 : std::array<uint32_t, 3>{c[0], c[1], c[2]});
  return out;
}

TetMesh gridMeshToTets(const GridMesh& mesh, const GridMeshGeometry& g) {
  TetMesh out;
  out.positions.reserve(mesh.points.size());
  ScalarField field{"value", {}};
  field.values.reserve(mesh.points.size());
  for (size_t v = 0; v < mesh.points.size(); ++v) {
    const auto& p = mesh.points[v];
    out.positions.push_back({g.origin[0] + p[0] * g.spacing[0], g.origin[1] + p[1] * g.spacing[1],
                             g.origin[2] + p[2] * g.spacing[2]});
    field.values.push_back(mesh.values[v]);
  }
  out.fields.push_back(std::move(field));
  // An odd number of negative spacings mirrors space; keep the tets positive.
  const bool flip = ((g.spacing[0] < 0) + (g.spacing[1] < 0) + (g.spacing[2] < 0)) % 2 == 1;
  out.tets.reserve(mesh.cells.size());
  for (const auto& c : mesh.cells)
    out.tets.push_back(flip ? std::array<uint32_t, 4>{c[0], c[1], c[3], c[2]} : c);
  return out;
}

}  // namespace mrsv
