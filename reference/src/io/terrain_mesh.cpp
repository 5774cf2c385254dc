// Terrain to mesh; the rules are in terrain_mesh.h.
#include "mrsv/terrain_mesh.h"

#include <cmath>
#include <cstring>

namespace mrsv {
namespace {

// The raw little-endian bits of sample `index`, zero-extended (as nodata_bits is).
uint64_t sampleBits(const uint8_t* samples, size_t bytes, uint64_t index) {
  uint64_t bits = 0;
  for (size_t k = 0; k < bytes; ++k) bits |= uint64_t{samples[index * bytes + k]} << (8 * k);
  return bits;
}

double sampleValue(SampleType type, uint64_t bits) {
  switch (type) {
    case SampleType::kUint8: return static_cast<double>(static_cast<uint8_t>(bits));
    case SampleType::kInt16: return static_cast<double>(static_cast<int16_t>(bits));
    case SampleType::kUint16: return static_cast<double>(static_cast<uint16_t>(bits));
    case SampleType::kInt32: return static_cast<double>(static_cast<int32_t>(bits));
    case SampleType::kFloat32: {
      uint32_t b = static_cast<uint32_t>(bits);
      float f;
      std::memcpy(&f, &b, sizeof f);
      return f;
    }
    case SampleType::kFloat64: {
      double d;
      std::memcpy(&d, &bits, sizeof d);
      return d;
    }
  }
  return 0.0;
}

}  // namespace

bool terrainToMesh(const GridHeader& header, const std::vector<uint8_t>& samples,
                   const TerrainMeshOptions& options, TriangleMesh* mesh, std::string* error) {
  *mesh = TriangleMesh{};
  if (std::string problem = gridHeaderProblem(header); !problem.empty()) {
    *error = "terrain grid: " + problem;
    return false;
  }
  if (header.num_dims != 2 || header.size_z != 1) {
    *error = "terrain grid: needs a 2-D grid, not " + std::to_string(header.num_dims) + "-D";
    return false;
  }
  const size_t bytes = sampleSize(header.sample_type);
  const uint64_t count = header.sampleCount();
  if (samples.size() != count * bytes) {
    *error = "terrain grid: " + std::to_string(samples.size()) + " bytes of samples, but " +
             std::to_string(header.size_x) + "x" + std::to_string(header.size_y) + " " +
             sampleTypeName(header.sample_type) + " needs " + std::to_string(count * bytes);
    return false;
  }
  if (count > UINT32_MAX) {
    *error = "terrain grid: more than 2^32-1 samples cannot all be mesh vertices";
    return false;
  }
  if (!std::isfinite(options.spacing_x) || !std::isfinite(options.spacing_y) ||
      options.spacing_x == 0 || options.spacing_y == 0 || !std::isfinite(options.z_scale)) {
    *error = "terrain mesh: spacings must be finite and not zero, and the z scale finite";
    return false;
  }

  const uint32_t w = header.size_x, h = header.size_y;
  std::vector<double> value(count);
  std::vector<uint8_t> valid(count);
  for (uint64_t s = 0; s < count; ++s) {
    uint64_t bits = sampleBits(samples.data(), bytes, s);
    value[s] = sampleValue(header.sample_type, bits);
    valid[s] = !(header.hasNodata() && bits == header.nodata_bits) && std::isfinite(value[s]);
  }
  auto cellValid = [&](uint64_t s) { return valid[s] && valid[s + 1] && valid[s + w] && valid[s + w + 1]; };

  // First pass: which samples some cell uses; they are numbered in sample order.
  constexpr uint32_t kUnused = UINT32_MAX;
  std::vector<uint32_t> vertex(count, kUnused);
  uint64_t cells = 0;
  for (uint32_t j = 0; j + 1 < h; ++j)
    for (uint32_t i = 0; i + 1 < w; ++i) {
      uint64_t s = uint64_t{j} * w + i;
      if (!cellValid(s)) continue;
      ++cells;
      vertex[s] = vertex[s + 1] = vertex[s + w] = vertex[s + w + 1] = 0;
    }
  for (uint64_t s = 0; s < count; ++s) {
    if (vertex[s] == kUnused) continue;
    vertex[s] = static_cast<uint32_t>(mesh->positions.size());
    mesh->positions.push_back({static_cast<double>(s % w) * options.spacing_x,
                               static_cast<double>(s / w) * options.spacing_y,
                               value[s] * options.z_scale});
  }

  // Around a cell, corners 00 -> 10 -> 11 -> 01 run counter-clockwise seen
  // from +z when the spacings have the same sign; otherwise the x-y map is
  // mirrored and every triangle is listed the other way round.
  const bool mirrored = (options.spacing_x < 0) != (options.spacing_y < 0);
  mesh->triangles.reserve(2 * cells);
  auto emit = [&](uint32_t a, uint32_t b, uint32_t c) {
    mesh->triangles.push_back(mirrored ? std::array<uint32_t, 3>{a, c, b}
                                       : std::array<uint32_t, 3>{a, b, c});
  };
  for (uint32_t j = 0; j + 1 < h; ++j)
    for (uint32_t i = 0; i + 1 < w; ++i) {
      uint64_t s = uint64_t{j} * w + i;
      if (!cellValid(s)) continue;
      const uint32_t v00 = vertex[s], v10 = vertex[s + 1], v01 = vertex[s + w], v11 = vertex[s + w + 1];
      if (std::fabs(value[s] - value[s + w + 1]) <= std::fabs(value[s + 1] - value[s + w])) {
        emit(v00, v10, v11);
        emit(v00, v11, v01);
      } else {
        emit(v00, v10, v01);
        emit(v10, v11, v01);
      }
    }
  return true;
}

}  // namespace mrsv
