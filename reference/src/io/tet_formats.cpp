// Tet mesh format dispatch, the checks shared by all formats, and the
// orientation repair after reading (decision D38).
#include "mrsv/tet_formats.h"

#include <cmath>
#include <cstdio>

#include "io/file_extension.h"
#include "io/tet_format_codecs.h"
#include "mrsv/file_io.h"

namespace mrsv {
namespace {

std::string withoutExtension(const std::string& path) {
  size_t dot = path.find_last_of('.');
  size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return path;
  return path.substr(0, dot);
}

const char kUnknownFormat[] =
    ": unknown tet mesh format (the name must end in .mesh, .node, .ele, .vtu or .vtk)";

// What makes `mesh` unwritable, or "".
std::string meshProblem(const TetMesh& mesh) {
  if (mesh.positions.size() > tet_io::kMaxTetVertices) return "more than 2^32-1 vertices";
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    for (double c : mesh.positions[v])
      if (!std::isfinite(c)) return "vertex " + std::to_string(v) + " has a NaN or Inf coordinate";
  for (size_t t = 0; t < mesh.tets.size(); ++t)
    for (uint32_t v : mesh.tets[t])
      if (v >= mesh.positions.size())
        return "tet " + std::to_string(t) + " has vertex index " + std::to_string(v) +
               " out of range (" + std::to_string(mesh.positions.size()) + " vertices)";
  for (const ScalarField& field : mesh.fields) {
    if (field.values.size() != mesh.positions.size())
      return "field '" + field.name + "' has " + std::to_string(field.values.size()) +
             " values for " + std::to_string(mesh.positions.size()) + " vertices";
    if (field.name.empty()) return "a field has an empty name";
    for (char c : field.name)
      if (static_cast<unsigned char>(c) <= ' ' || c == '"' || c == '\'' || c == '<' || c == '>' ||
          c == '&' || c == 127)
        return "field name '" + field.name +
               "' holds white space or one of \" ' < > & (the formats cannot all carry them)";
    for (size_t v = 0; v < field.values.size(); ++v)
      if (!std::isfinite(field.values[v]))
        return "field '" + field.name + "' has a NaN or Inf value at vertex " + std::to_string(v);
  }
  return "";
}

// After a reader: fields sized right, orientation repaired.
bool finishRead(const std::string& name, TetMesh* mesh, TetReadReport* report,
                std::string* error) {
  for (const ScalarField& field : mesh->fields)
    if (field.values.size() != mesh->positions.size()) {
      *error = name + ": field '" + field.name + "' has " + std::to_string(field.values.size()) +
               " values for " + std::to_string(mesh->positions.size()) + " vertices";
      return false;
    }
  uint64_t flipped = 0;
  if (!orientTets(mesh, &flipped, error)) {
    *error = name + ": " + *error;
    return false;
  }
  if (report) report->flipped = flipped;
  return true;
}

}  // namespace

namespace tet_io {

std::string coordinateProblem(double c) {
  if (!std::isfinite(c)) return "is not finite (NaN or Inf)";
  double m = std::fabs(c);
  if (m > kMaxCoordinate || (m != 0.0 && m < kMinCoordinate))
    return "is outside the supported range (0, or 1e-50 to 1e50 in magnitude, where "
           "orientation tests are exact)";
  return "";
}

VtkCellKind vtkCellKind(int64_t type) {
  if (type == 10) return VtkCellKind::kTetra;
  if (type >= 1 && type <= 9) return VtkCellKind::kLowerDimension;
  return VtkCellKind::kOther3d;
}

std::string vtkCellTypeName(int64_t type) {
  switch (type) {
    case 1: return "vertex";
    case 2: return "poly-vertex";
    case 3: return "line";
    case 4: return "poly-line";
    case 5: return "triangle";
    case 6: return "triangle strip";
    case 7: return "polygon";
    case 8: return "pixel";
    case 9: return "quad";
    case 10: return "tetrahedron";
    case 11: return "voxel";
    case 12: return "hexahedron";
    case 13: return "wedge";
    case 14: return "pyramid";
    case 24: return "quadratic tetrahedron";
    case 25: return "quadratic hexahedron";
    case 42: return "polyhedron";
    default: return "type " + std::to_string(type);
  }
}

}  // namespace tet_io

TetFormat tetFormatOf(const std::string& path) {
  if (hasExtension(path, ".mesh")) return TetFormat::kMedit;
  if (hasExtension(path, ".node") || hasExtension(path, ".ele")) return TetFormat::kTetgen;
  if (hasExtension(path, ".vtu")) return TetFormat::kVtu;
  if (hasExtension(path, ".vtk")) return TetFormat::kVtkLegacy;
  return TetFormat::kUnknown;
}

std::string tetgenNodePath(const std::string& path) { return withoutExtension(path) + ".node"; }
std::string tetgenElePath(const std::string& path) { return withoutExtension(path) + ".ele"; }

bool readTetBytes(const std::string& name, TetFormat format, const uint8_t* data, size_t size,
                  TetMesh* mesh, TetReadReport* report, std::string* error) {
  *mesh = TetMesh{};
  if (report) *report = TetReadReport{};
  uint64_t skipped = 0;
  bool ok = false;
  switch (format) {
    case TetFormat::kMedit: ok = tet_io::readMedit(name, data, size, mesh, error); break;
    case TetFormat::kVtu: ok = tet_io::readVtu(name, data, size, mesh, &skipped, error); break;
    case TetFormat::kVtkLegacy:
      ok = tet_io::readVtkLegacy(name, data, size, mesh, &skipped, error);
      break;
    case TetFormat::kTetgen:
      *error = name + ": a TetGen mesh is two files (.node and .ele); read it by its path";
      break;
    case TetFormat::kUnknown: *error = name + kUnknownFormat; break;
  }
  if (ok) ok = finishRead(name, mesh, report, error);
  if (!ok) {
    *mesh = TetMesh{};
    return false;
  }
  if (report) report->skipped_cells = skipped;
  return true;
}

bool readTetgenBytes(const std::string& node_name, const uint8_t* node, size_t node_size,
                     const std::string& ele_name, const uint8_t* ele, size_t ele_size,
                     TetMesh* mesh, TetReadReport* report, std::string* error) {
  *mesh = TetMesh{};
  if (report) *report = TetReadReport{};
  bool ok = tet_io::readTetgen(node_name, node, node_size, ele_name, ele, ele_size, mesh, error) &&
            finishRead(ele_name, mesh, report, error);
  if (!ok) *mesh = TetMesh{};
  return ok;
}

bool readTetFile(const std::string& path, TetMesh* mesh, TetReadReport* report,
                 std::string* error) {
  *mesh = TetMesh{};
  TetFormat format = tetFormatOf(path);
  if (format == TetFormat::kUnknown) {
    *error = path + kUnknownFormat;
    return false;
  }
  if (format == TetFormat::kTetgen) {
    std::string node_path = tetgenNodePath(path), ele_path = tetgenElePath(path);
    std::vector<uint8_t> node, ele;
    if (!readWholeFile(node_path, &node, error)) {
      *error = node_path + ": " + *error;
      return false;
    }
    if (!readWholeFile(ele_path, &ele, error)) {
      *error = ele_path + ": " + *error;
      return false;
    }
    return readTetgenBytes(node_path, node.data(), node.size(), ele_path, ele.data(), ele.size(),
                           mesh, report, error);
  }
  std::vector<uint8_t> bytes;
  if (!readWholeFile(path, &bytes, error)) {
    *error = path + ": " + *error;
    return false;
  }
  return readTetBytes(path, format, bytes.data(), bytes.size(), mesh, report, error);
}

bool encodeTetFile(const std::string& path, const TetMesh& mesh, const TetWriteOptions& options,
                   std::vector<TetFileBytes>* files, TetWriteReport* report, std::string* error) {
  files->clear();
  if (report) *report = TetWriteReport{};
  TetFormat format = tetFormatOf(path);
  if (format == TetFormat::kUnknown) {
    *error = path + kUnknownFormat;
    return false;
  }
  if (std::string problem = meshProblem(mesh); !problem.empty()) {
    *error = path + ": cannot write the mesh: " + problem;
    return false;
  }
  switch (format) {
    case TetFormat::kMedit:
      files->push_back({path, {}});
      tet_io::encodeMedit(mesh, &files->back().bytes);
      if (report) report->fields_dropped = mesh.fields.size();
      break;
    case TetFormat::kTetgen:
      files->push_back({tetgenNodePath(path), {}});
      tet_io::encodeTetgenNode(mesh, &files->back().bytes);
      files->push_back({tetgenElePath(path), {}});
      tet_io::encodeTetgenEle(mesh, &files->back().bytes);
      break;
    case TetFormat::kVtu:
      files->push_back({path, {}});
      tet_io::encodeVtu(mesh, options.ascii, &files->back().bytes);
      break;
    default:
      files->push_back({path, {}});
      tet_io::encodeVtkLegacy(mesh, options.ascii, &files->back().bytes);
      break;
  }
  return true;
}

bool writeTetFile(const std::string& path, const TetMesh& mesh, const TetWriteOptions& options,
                  TetWriteReport* report, std::string* error) {
  std::vector<TetFileBytes> files;
  if (!encodeTetFile(path, mesh, options, &files, report, error)) return false;
  for (const TetFileBytes& file : files)
    if (!writeFileAtomically(file.path, file.bytes, error)) {
      *error = file.path + ": " + *error;
      return false;
    }
  return true;
}

}  // namespace mrsv
