// Format dispatch and the checks shared by all mesh formats.
#include "mrsv/mesh_formats.h"

#include <charconv>
#include <cmath>

#include "io/file_extension.h"
#include "io/mesh_format_codecs.h"
#include "mrsv/file_io.h"

namespace mrsv {
namespace {

const char* formatName(MeshFormat format) {
  switch (format) {
    case MeshFormat::kObj: return "OBJ";
    case MeshFormat::kPly: return "PLY";
    case MeshFormat::kOff: return "OFF";
    case MeshFormat::kUnknown: break;
  }
  return "unknown";
}

// What makes `mesh` unwritable, or "".
std::string meshProblem(const TriangleMesh& mesh, MeshFormat format) {
  if (mesh.positions.size() > mesh_io::kMaxMeshVertices) return "more than 2^32-1 vertices";
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    for (double c : mesh.positions[v])
      if (!std::isfinite(c)) return "vertex " + std::to_string(v) + " has a NaN or Inf coordinate";
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (uint32_t v : mesh.triangles[t])
      if (v >= mesh.positions.size())
        return "triangle " + std::to_string(t) + " has vertex index " + std::to_string(v) +
               " out of range (" + std::to_string(mesh.positions.size()) + " vertices)";
  if (!mesh.scalars.empty()) {
    if (format != MeshFormat::kPly)
      return std::string(formatName(format)) + " has no per-vertex scalars; write .ply";
    if (mesh.scalars.size() != mesh.positions.size())
      return std::to_string(mesh.scalars.size()) + " scalars for " +
             std::to_string(mesh.positions.size()) + " vertices";
  }
  return "";
}

}  // namespace

namespace mesh_io {

void appendShortestDouble(double value, std::string* out) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  (void)ec;  // 32 characters hold any double's shortest form (at most 24)
  out->append(buffer, end);
}

void appendUnsigned(uint64_t value, std::string* out) {
  char buffer[24];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  (void)ec;
  out->append(buffer, end);
}

}  // namespace mesh_io

MeshFormat meshFormatOf(const std::string& path) {
  if (hasExtension(path, ".obj")) return MeshFormat::kObj;
  if (hasExtension(path, ".ply")) return MeshFormat::kPly;
  if (hasExtension(path, ".off")) return MeshFormat::kOff;
  return MeshFormat::kUnknown;
}

bool readMeshBytes(const std::string& name, MeshFormat format, const uint8_t* data, size_t size,
                   const std::string& scalar_property, TriangleMesh* mesh, std::string* error) {
  *mesh = TriangleMesh{};
  if (format == MeshFormat::kUnknown) {
    *error = name + ": unknown mesh format (the name must end in .obj, .ply or .off)";
    return false;
  }
  if (!scalar_property.empty() && format != MeshFormat::kPly) {
    *error = name + ": " + formatName(format) + " has no vertex properties, so there is no '" +
             scalar_property + "' scalar to read";
    return false;
  }
  bool ok = format == MeshFormat::kObj ? mesh_io::readObj(name, data, size, mesh, error)
            : format == MeshFormat::kOff
                ? mesh_io::readOff(name, data, size, mesh, error)
                : mesh_io::readPly(name, data, size, scalar_property, mesh, error);
  if (!ok) *mesh = TriangleMesh{};
  return ok;
}

bool readMeshFile(const std::string& path, const std::string& scalar_property, TriangleMesh* mesh,
                  std::string* error) {
  *mesh = TriangleMesh{};
  MeshFormat format = meshFormatOf(path);
  if (format == MeshFormat::kUnknown) {
    *error = path + ": unknown mesh format (the name must end in .obj, .ply or .off)";
    return false;
  }
  std::vector<uint8_t> bytes;
  if (!readWholeFile(path, &bytes, error)) {
    *error = path + ": " + *error;
    return false;
  }
  return readMeshBytes(path, format, bytes.data(), bytes.size(), scalar_property, mesh, error);
}

bool encodeMeshFile(const std::string& path, const TriangleMesh& mesh, std::vector<uint8_t>* out,
                    std::string* error) {
  out->clear();
  MeshFormat format = meshFormatOf(path);
  if (format == MeshFormat::kUnknown) {
    *error = path + ": unknown mesh format (the name must end in .obj, .ply or .off)";
    return false;
  }
  if (std::string problem = meshProblem(mesh, format); !problem.empty()) {
    *error = path + ": cannot write the mesh: " + problem;
    return false;
  }
  switch (format) {
    case MeshFormat::kObj: mesh_io::encodeObj(mesh, out); break;
    case MeshFormat::kOff: mesh_io::encodeOff(mesh, out); break;
    default: mesh_io::encodePly(mesh, out); break;
  }
  return true;
}

}  // namespace mrsv
