// Progressive triangle meshes (spec 6): mrsv.ProgressiveMesh for any level of
// a PM stream as vertex and face arrays, mrsv.encode_mesh to write one, and
// mrsv.read_mesh for OBJ, PLY and OFF files.
#include <optional>

#include <pybind11/stl.h>

#include "common.h"
#include "mrsv/file_io.h"
#include "mrsv/mesh_formats.h"
#include "mrsv/mesh_repair.h"
#include "mrsv/progressive_mesh.h"
#include "pm/pm_encode.h"
#include "simplify/simplify.h"

namespace mrsv::python {
namespace {

// A decoded PM stream kept in memory so that levels change in both directions
// without decoding again.
class PyProgressiveMesh {
 public:
  PyProgressiveMesh(const py::object& source_object, const py::object& byte_limit) {
    Source source = loadSource(source_object);
    DecodeOptions options;
    options.container.allow_partial_tail = applyByteLimit(byte_limit, &source);
    if (!isProgressiveMeshStream(source.data, source.size))
      throw py::value_error("not a progressive mesh stream (its first chunk is not PHDR); grids open with "
                            "mrsv.decode, tet meshes with mrsv.ProgressiveTetMesh");
    Error e;
    {
      py::gil_scoped_release release;
      e = decodeProgressiveMesh(source.data, source.size, options, &d_);
    }
    if (!e.ok()) raiseStreamError(e);
    if (!d_.has_mesh) throw py::value_error("the stream ends before its base mesh (PBAS)");
  }

  uint32_t finestLevel() const { return d_.mesh.splitsDecoded(); }
  uint32_t level() const { return d_.mesh.level(); }
  void setLevel(long long level) {
    checkLevel(level);
    py::gil_scoped_release release;
    d_.mesh.setLevel(static_cast<uint32_t>(level));
  }
  uint32_t vertexCountAt(long long level) const {
    checkLevel(level);
    return d_.mesh.vertexCountAt(static_cast<uint32_t>(level));
  }
  uint32_t faceCountAt(long long level) const {
    checkLevel(level);
    return d_.mesh.triangleCountAt(static_cast<uint32_t>(level));
  }
  const DecodedMesh& decoded() const { return d_; }

 private:
  void checkLevel(long long level) const {
    if (level < 0 || level > finestLevel())
      throw py::index_error("level " + std::to_string(level) + " is not in 0.." + std::to_string(finestLevel()) +
                            " (the splits decoded)");
  }
  DecodedMesh d_;
};

py::dict encodeMesh(const py::object& vertices, const py::object& faces, const py::object& path,
                    const py::object& scalars, int bits, int scalar_bits, const std::string& cost,
                    const std::optional<std::vector<double>>& weights, const std::string& placement,
                    const std::optional<int>& move_detail, const std::optional<double>& free_from,
                    const std::optional<double>& wide_batches, const std::optional<uint64_t>& base_faces,
                    const std::optional<double>& time_budget, const py::object& metadata_entries) {
  TriangleMesh mesh;
  mesh.positions = pointsFromArray(vertices, "vertices");
  mesh.triangles = indicesFromArray<3>(faces, "faces", mesh.positions.size());
  if (!scalars.is_none()) mesh.scalars = valuesFromArray(scalars, "scalars", mesh.positions.size());
  std::string out = outputPath(path);
  // The options as 'mrsv encode' with a mesh checks them (tools/mrsv/cmd_mesh.cpp).
  SimplifyOptions simplify;
  simplify.placement = Placement::kFree;  // the CLI's default (decision D22)
  PmEncodeOptions encode;
  if (cost == "paper") simplify.cost = CollapseCost::kPaper;
  else if (cost != "quadric") throw py::value_error("cost= must be 'quadric' or 'paper'");
  if (weights) {
    if (weights->size() != 3 || (*weights)[0] < 0 || (*weights)[1] < 0 || (*weights)[2] < 0)
      throw py::value_error("weights= must be three non-negative numbers (normal, edge length, equilateral)");
    simplify.weight_normal = (*weights)[0];
    simplify.weight_edge_length = (*weights)[1];
    simplify.weight_equilateral = (*weights)[2];
  }
  if (placement == "endpoint") simplify.placement = Placement::kEndpoint;
  else if (placement != "free") throw py::value_error("placement= must be 'free' or 'endpoint'");
  encode.placement = simplify.placement;
  if ((move_detail || free_from) && encode.placement != Placement::kFree)
    throw py::value_error("move_detail= and free_from= need placement='free'");
  if (move_detail) {
    if (*move_detail < 0 || *move_detail > 30) throw py::value_error("move_detail= must be 0 to 30");
    encode.move_detail = static_cast<uint8_t>(*move_detail);
  }
  if (free_from) {
    if (!(*free_from >= 0 && *free_from <= 1)) throw py::value_error("free_from= must be a number from 0 to 1");
    simplify.free_placement_below = *free_from;
  }
  if (wide_batches) {
    if (!(*wide_batches >= 0 && *wide_batches <= 1)) throw py::value_error("wide_batches= must be a number from 0 to 1");
    simplify.fine_vertex_fraction = *wide_batches;
  }
  if (bits < 1 || bits > 30) throw py::value_error("bits= must be a whole number from 1 to 30");
  if (scalar_bits < 1 || scalar_bits > 30) throw py::value_error("scalar_bits= must be a whole number from 1 to 30");
  encode.position_bits = static_cast<uint8_t>(bits);
  encode.scalar_bits = static_cast<uint8_t>(scalar_bits);
  if (base_faces) simplify.target_triangles = *base_faces;
  if (time_budget) {
    if (!(*time_budget > 0)) throw py::value_error("time_budget= must be a positive number of seconds");
    simplify.time_budget_seconds = *time_budget;
  }
  Metadata metadata;
  addMetadata(metadata_entries, &metadata);

  MeshRepairReport repair;
  std::vector<uint32_t> origin;
  SimplifyResult collapses;
  std::vector<uint8_t> stream;
  PmEncodeReport report;
  std::string error, io_error;
  bool ok = false, written = false;
  {
    py::gil_scoped_release release;
    ok = repairMesh(&mesh, MeshRepairOptions{}, &repair, &origin, &error) &&
         simplifyMesh(mesh, simplify, &collapses, &error) &&
         encodeProgressiveMesh(mesh, collapses, encode, metadata, &stream, &report, &error);
    if (ok) written = writeFileAtomically(out, stream, &io_error);
  }
  if (!ok) throw py::value_error(error);
  if (!written) {
    PyErr_SetString(PyExc_OSError, (out + ": " + io_error).c_str());
    throw py::error_already_set();
  }
  py::dict r;
  r["bytes"] = stream.size();
  r["repair"] = describe(repair);
  r["vertex_count"] = mesh.positions.size();  // after repair: the finest level's count
  r["face_count"] = mesh.triangles.size();
  r["base_vertex_count"] = report.base_vertices;
  r["base_face_count"] = report.base_triangles;
  r["splits"] = report.splits;
  r["batches"] = report.batches;
  return r;
}

py::tuple readMesh(const py::object& path, const std::optional<std::string>& scalar) {
  std::string file = outputPath(path);
  TriangleMesh mesh;
  std::string error;
  bool ok;
  {
    py::gil_scoped_release release;
    ok = readMeshFile(file, scalar ? *scalar : "", &mesh, &error);
  }
  if (!ok) throw py::value_error(error);
  py::object scalars = mesh.scalars.empty() ? py::object(py::none()) : py::object(vectorToArray<double>(mesh.scalars));
  return py::make_tuple(rowsToArray<double>(mesh.positions), rowsToArray<int32_t>(mesh.triangles), scalars);
}

}  // namespace

void registerMesh(py::module_& m) {
  py::class_<PyProgressiveMesh>(m, "ProgressiveMesh", R"doc(A progressive triangle mesh (PM stream, spec 6).

ProgressiveMesh(source, bytes=None): source is a path or the stream's bytes;
bytes=N decodes only the first N bytes (a prefix: fewer levels). The mesh
moves between levels 0 (the base mesh) and finest_level (every split
decoded) in both directions without decoding again; it starts at the finest.)doc")
      .def(py::init<const py::object&, const py::object&>(), py::arg("source"), py::kw_only(),
           py::arg("bytes") = py::none())
      .def_property_readonly("finest_level", &PyProgressiveMesh::finestLevel, "the finest level: splits decoded")
      .def_property_readonly("levels", [](const PyProgressiveMesh& p) { return p.finestLevel() + 1; },
                             "the number of levels, 0 to finest_level")
      .def_property("level", &PyProgressiveMesh::level, &PyProgressiveMesh::setLevel, "the current level")
      .def("set_level", &PyProgressiveMesh::setLevel, py::arg("level"), "move to a level (splits applied)")
      .def_property_readonly("vertices", [](const PyProgressiveMesh& p) {
            return rowsToArray<double>(p.decoded().mesh.mesh().positions);
          }, "(N, 3) float64 positions of the current level")
      .def_property_readonly("quantized_vertices", [](const PyProgressiveMesh& p) {
            return rowsToArray<int32_t>(p.decoded().mesh.quantizedPositions());
          }, "(N, 3) int32 quantised positions (spec 6.8)")
      .def_property_readonly("faces", [](const PyProgressiveMesh& p) {
            return rowsToArray<int32_t>(p.decoded().mesh.triangles());
          }, "(M, 3) int32 vertex indices, counter-clockwise seen from outside")
      .def_property_readonly("scalars", [](const PyProgressiveMesh& p) -> py::object {
            if (p.decoded().header.scalar_bits == 0) return py::none();
            return vectorToArray<double>(p.decoded().mesh.mesh().scalars);
          }, "(N,) float64 per-vertex scalar, or None")
      .def_property_readonly("vertex_count", [](const PyProgressiveMesh& p) { return p.decoded().mesh.vertexCount(); })
      .def_property_readonly("face_count", [](const PyProgressiveMesh& p) { return p.decoded().mesh.triangleCount(); })
      .def("vertex_count_at", &PyProgressiveMesh::vertexCountAt, py::arg("level"))
      .def("face_count_at", &PyProgressiveMesh::faceCountAt, py::arg("level"))
      .def("finest_level_within", [](const PyProgressiveMesh& p, uint64_t max_faces) {
            return p.decoded().mesh.finestLevelWithin(max_faces);
          }, py::arg("max_faces"), "the finest level with at most max_faces triangles (0 if none)")
      .def_property_readonly("complete", [](const PyProgressiveMesh& p) { return p.decoded().container.complete; })
      .def_property_readonly("batches_decoded", [](const PyProgressiveMesh& p) { return p.decoded().batches_decoded; })
      .def_property_readonly("metadata", [](const PyProgressiveMesh& p) { return metadataDict(p.decoded().metadata); })
      .def_property_readonly("header", [](const PyProgressiveMesh& p) {
            const PmHeader& h = p.decoded().header;
            py::dict d;
            d["vertex_count"] = h.vertex_count;
            d["base_vertex_count"] = h.base_vertex_count;
            d["base_triangle_count"] = h.base_triangle_count;
            d["batch_count"] = h.batch_count;
            d["position_bits"] = h.position_bits;
            d["position_step"] = h.position_step;
            d["origin"] = py::make_tuple(h.origin[0], h.origin[1], h.origin[2]);
            d["placement"] = h.placement == kPlacementFree ? "free" : "endpoint";
            d["scalar_bits"] = h.scalar_bits;
            return d;
          }, "the PHDR fields (spec 6.2)");

  m.def("encode_mesh", &encodeMesh, py::arg("vertices"), py::arg("faces"), py::arg("path"), py::kw_only(),
        py::arg("scalars") = py::none(), py::arg("bits") = 16, py::arg("scalar_bits") = 16,
        py::arg("cost") = "quadric", py::arg("weights") = py::none(), py::arg("placement") = "free",
        py::arg("move_detail") = py::none(), py::arg("free_from") = py::none(), py::arg("wide_batches") = py::none(),
        py::arg("base_faces") = py::none(), py::arg("time_budget") = py::none(), py::arg("metadata") = py::none(),
        R"doc(Encode a triangle mesh as a progressive mesh (as 'mrsv encode IN.obj OUT.mrsv').

vertices (N, 3) numbers, faces (M, 3) indices; the mesh is repaired first as
the CLI does (report['repair'] says what was done). Options as the CLI's:
scalars (N,), bits, scalar_bits, cost ('quadric'|'paper'), weights (3),
placement ('free'|'endpoint'), move_detail, free_from, wide_batches,
base_faces, time_budget, metadata. Returns a dict of counts and bytes.)doc");
  m.def("read_mesh", &readMesh, py::arg("path"), py::kw_only(), py::arg("scalar") = py::none(),
        "Read an OBJ, PLY or OFF file: (vertices (N, 3) float64, faces (M, 3) int32, scalars or None); "
        "scalar names a PLY vertex property to read.");
}

}  // namespace mrsv::python
