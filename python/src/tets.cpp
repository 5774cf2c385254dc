// Progressive tetrahedral meshes (spec 7): mrsv.ProgressiveTetMesh for any
// level of a PT stream as vertex, tet and field arrays, mrsv.encode_tets to
// write one, mrsv.read_tets for tet mesh files and mrsv.tetrahedralize for
// tet meshes of 3-D arrays.
#include <cstring>
#include <optional>

#include <pybind11/stl.h>

#include "common.h"
#include "mrsv/file_io.h"
#include "mrsv/progressive_tet_mesh.h"
#include "mrsv/tet_formats.h"
#include "pt/pt_encode.h"
#include "tetsimplify/tet_simplify.h"

namespace mrsv::python {
namespace {

class PyProgressiveTetMesh {
 public:
  PyProgressiveTetMesh(const py::object& source_object, const py::object& byte_limit) {
    Source source = loadSource(source_object);
    DecodeOptions options;
    options.container.allow_partial_tail = applyByteLimit(byte_limit, &source);
    if (!isProgressiveTetStream(source.data, source.size))
      throw py::value_error("not a progressive tet mesh stream (its first chunk is not THDR); grids open with "
                            "mrsv.decode, triangle meshes with mrsv.ProgressiveMesh");
    Error e;
    {
      py::gil_scoped_release release;
      e = decodeProgressiveTetMesh(source.data, source.size, options, &d_);
    }
    if (!e.ok()) raiseStreamError(e);
    if (!d_.has_mesh) throw py::value_error("the stream ends before its base mesh (TBAS)");
  }

  uint32_t finestLevel() const { return d_.mesh.splitsDecoded(); }
  uint32_t level() const { return d_.mesh.level(); }
  void setLevel(long long level) {
    checkLevel(level);
    py::gil_scoped_release release;
    d_.mesh.setLevel(static_cast<uint32_t>(level));
  }
  // Each split adds one vertex (spec 7.1).
  uint32_t vertexCountAt(long long level) const {
    checkLevel(level);
    return d_.header.base_vertex_count + static_cast<uint32_t>(level);
  }
  uint32_t tetCountAt(long long level) const {
    checkLevel(level);
    return d_.mesh.tetCountAt(static_cast<uint32_t>(level));
  }
  const DecodedTetMesh& decoded() const { return d_; }

 private:
  void checkLevel(long long level) const {
    if (level < 0 || level > finestLevel())
      throw py::index_error("level " + std::to_string(level) + " is not in 0.." + std::to_string(finestLevel()) +
                            " (the splits decoded)");
  }
  DecodedTetMesh d_;
};

py::dict fieldsDict(const std::vector<ScalarField>& fields) {
  py::dict d;
  for (const ScalarField& f : fields) d[py::str(f.name)] = vectorToArray<double>(f.values);
  return d;
}

py::tuple meshTuple(const TetMesh& mesh) {
  return py::make_tuple(rowsToArray<double>(mesh.positions), rowsToArray<int32_t>(mesh.tets), fieldsDict(mesh.fields));
}

TetMesh meshFromArrays(const py::object& vertices, const py::object& tets, const py::object& fields) {
  TetMesh mesh;
  mesh.positions = pointsFromArray(vertices, "vertices");
  mesh.tets = indicesFromArray<4>(tets, "tets", mesh.positions.size());
  if (!fields.is_none()) {
    if (!py::isinstance<py::dict>(fields)) throw py::type_error("fields= must be a dict of name to (N,) array");
    for (auto [name, values] : fields.cast<py::dict>()) {
      if (!py::isinstance<py::str>(name)) throw py::type_error("fields= names must be str");
      mesh.fields.push_back({name.cast<std::string>(), valuesFromArray(py::reinterpret_borrow<py::object>(values), "a field", mesh.positions.size())});
    }
  }
  return mesh;
}

py::dict encodeTets(const py::object& vertices, const py::object& tets, const py::object& path,
                    const py::object& fields, const std::optional<int>& bits, int field_bits, const std::string& cost,
                    const std::optional<std::vector<double>>& weights, const std::optional<uint64_t>& base_tets,
                    const std::optional<double>& time_budget, const std::optional<double>& min_dihedral,
                    bool intersection_test) {
  TetMesh mesh = meshFromArrays(vertices, tets, fields);
  std::string out = outputPath(path);
  if (mesh.fields.size() > static_cast<size_t>(kMaxTetFields))
    throw py::value_error("at most " + std::to_string(kMaxTetFields) + " fields");
  // The options as 'mrsv encode' with a tet mesh checks them (tools/mrsv/cmd_tets.cpp).
  TetSimplifyOptions simplify;
  if (cost == "paper") simplify.cost = TetCost::kPaper;
  else if (cost != "quadric") throw py::value_error("cost= must be 'quadric' or 'paper'");
  if (weights) {
    const std::vector<double>& w = *weights;
    if (w.size() != 5 || w[0] < 0 || w[1] < 0 || w[2] < 0 || w[3] < 0 || w[4] < 0)
      throw py::value_error("weights= must be five non-negative numbers (gradient, volume, equilateral, "
                            "edge length, normal)");
    simplify.weight_gradient = w[0];
    simplify.weight_volume = w[1];
    simplify.weight_equilateral = w[2];
    simplify.weight_edge_length = w[3];
    simplify.weight_normal = w[4];
  }
  if (bits && (*bits < 1 || *bits > 30)) throw py::value_error("bits= must be a whole number from 1 to 30");
  if (field_bits < 1 || field_bits > 30) throw py::value_error("field_bits= must be a whole number from 1 to 30");
  if (base_tets) simplify.min_base_tets = *base_tets;
  if (time_budget) {
    if (!(*time_budget > 0)) throw py::value_error("time_budget= must be a positive number of seconds");
    simplify.time_budget_seconds = *time_budget;
  }
  if (min_dihedral) {
    if (!(*min_dihedral >= 0 && *min_dihedral < 70.5))
      throw py::value_error("min_dihedral= must be a number of degrees from 0 to 70.5");
    simplify.min_dihedral_degrees = *min_dihedral;
  }
  simplify.boundary_intersection_test = intersection_test;

  std::string error, io_error;
  Error e;
  uint64_t flipped = 0;
  QuantizedTets quantized;
  TetSimplifyResult result;
  std::vector<uint8_t> stream;
  PtStreamStats stats;
  bool written = false;
  {
    py::gil_scoped_release release;
    // As a file reader would: every tet positive (vertices swapped when not).
    if (!orientTets(&mesh, &flipped, &error)) {
      e = Error{Status::kInvalidArgument, 0, "tets", error};
    } else {
      // Without bits=: 16, or the fewest bits above that keep every tet positive.
      int position_bits = bits ? *bits : 16;
      e = quantizeTetMesh(mesh, position_bits, field_bits, &quantized);
      for (int b = position_bits + 2; !e.ok() && !bits && b <= 30; b += 2) {
        if (e.status != Status::kInvalidArgument || e.field != "tets") break;
        e = quantizeTetMesh(mesh, b, field_bits, &quantized);
      }
    }
    if (e.ok()) {
      QuantizedTetMesh input;
      input.positions = quantized.positions;
      input.tets = quantized.tets;
      for (const ScalarField& f : mesh.fields) input.fields.push_back(f.values);
      e = simplifyTets(input, simplify, &result);
    }
    if (e.ok()) {
      std::vector<std::vector<PtCollapse>> batches(result.batches.size());
      for (size_t b = 0; b < batches.size(); ++b)
        for (const TetCollapse& c : result.batches[b]) batches[b].push_back(PtCollapse{c.vs, c.vt});
      e = writePtStream(quantized, batches, &stream, &stats);
    }
    if (e.ok()) written = writeFileAtomically(out, stream, &io_error);
  }
  if (!e.ok()) throw py::value_error(e.field.empty() ? e.message : e.field + ": " + e.message);
  if (!written) {
    PyErr_SetString(PyExc_OSError, (out + ": " + io_error).c_str());
    throw py::error_already_set();
  }
  py::dict r;
  r["bytes"] = stream.size();
  r["flipped"] = flipped;
  r["position_bits"] = quantized.header.position_bits;
  r["vertex_count"] = mesh.positions.size();
  r["tet_count"] = mesh.tets.size();
  r["base_vertex_count"] = stats.base_vertices;
  r["base_tet_count"] = stats.base_tets;
  r["splits"] = stats.splits;
  r["batches"] = stats.batches;
  return r;
}

py::tuple readTets(const py::object& path) {
  std::string file = outputPath(path);
  TetMesh mesh;
  std::string error;
  bool ok;
  {
    py::gil_scoped_release release;
    ok = readTetFile(file, &mesh, nullptr, &error);
  }
  if (!ok) throw py::value_error(error);
  return meshTuple(mesh);
}

// A 3-D array (numpy (z, y, x)) as 6 tets per cube, the samples as field 'value'.
py::tuple tetrahedralize(const py::object& array_like, const py::object& spacing_object, const py::object& nodata) {
  py::module_ np = py::module_::import("numpy");
  py::array a = np.attr("asarray")(array_like);
  if (a.ndim() != 3) throw py::value_error("tetrahedralize needs a 3-D array (z, y, x)");
  GridHeader h;
  std::string name = py::str(a.dtype().attr("name"));
  if (!parseSampleType(name, &h.sample_type))
    throw py::type_error("dtype " + name + " is not a sample type of the format");
  h.num_dims = 3;
  h.size_x = static_cast<uint32_t>(a.shape(2));
  h.size_y = static_cast<uint32_t>(a.shape(1));
  h.size_z = static_cast<uint32_t>(a.shape(0));
  if (std::string problem = gridHeaderProblem(h); !problem.empty()) throw py::value_error(problem);
  if (!nodata.is_none()) {
    // The same bits as the array's own dtype gives the value.
    py::array one = np.attr("array")(py::make_tuple(nodata), a.dtype().attr("newbyteorder")("<"));
    std::memcpy(&h.nodata_bits, one.data(), sampleSize(h.sample_type));
    h.grid_flags |= kGridFlagHasNodata;
  }
  std::vector<double> spacing = {1, 1, 1};
  if (!spacing_object.is_none()) spacing = spacing_object.cast<std::vector<double>>();
  if (spacing.size() != 3) throw py::value_error("spacing= must give 3 numbers (x, y, z order)");
  py::array samples = np.attr("ascontiguousarray")(a, a.dtype().attr("newbyteorder")("<"));
  const uint8_t* p = static_cast<const uint8_t*>(samples.data());
  std::vector<uint8_t> bytes(p, p + samples.nbytes());
  TetMesh mesh;
  TetBuildReport report;  // the library fills it unconditionally
  std::string error;
  bool ok;
  {
    py::gil_scoped_release release;
    ok = tetrahedralizeGrid(h, bytes, spacing.data(), GridCrop{}, &mesh, &report, &error);
  }
  if (!ok) throw py::value_error(error);
  return meshTuple(mesh);
}

}  // namespace

void registerTets(py::module_& m) {
  py::class_<PyProgressiveTetMesh>(m, "ProgressiveTetMesh", R"doc(A progressive tet mesh (PT stream, spec 7).

ProgressiveTetMesh(source, bytes=None): as ProgressiveMesh, with tets (M, 4)
positively oriented and the per-vertex fields as a dict of (N,) arrays.)doc")
      .def(py::init<const py::object&, const py::object&>(), py::arg("source"), py::kw_only(),
           py::arg("bytes") = py::none())
      .def_property_readonly("finest_level", &PyProgressiveTetMesh::finestLevel, "the finest level: splits decoded")
      .def_property_readonly("levels", [](const PyProgressiveTetMesh& p) { return p.finestLevel() + 1; },
                             "the number of levels, 0 to finest_level")
      .def_property("level", &PyProgressiveTetMesh::level, &PyProgressiveTetMesh::setLevel, "the current level")
      .def("set_level", &PyProgressiveTetMesh::setLevel, py::arg("level"), "move to a level (splits applied)")
      .def_property_readonly("vertices", [](const PyProgressiveTetMesh& p) {
            return rowsToArray<double>(p.decoded().mesh.mesh().positions);
          }, "(N, 3) float64 positions of the current level")
      .def_property_readonly("quantized_vertices", [](const PyProgressiveTetMesh& p) {
            return rowsToArray<int32_t>(p.decoded().mesh.quantizedPositions());
          }, "(N, 3) int32 quantised positions (spec 7.8)")
      .def_property_readonly("tets", [](const PyProgressiveTetMesh& p) {
            return rowsToArray<int32_t>(p.decoded().mesh.tets());
          }, "(M, 4) int32 vertex indices, positively oriented")
      .def_property_readonly("fields", [](const PyProgressiveTetMesh& p) {
            return fieldsDict(p.decoded().mesh.mesh().fields);
          }, "dict of field name to (N,) float64 values of the current level")
      .def_property_readonly("vertex_count", [](const PyProgressiveTetMesh& p) { return p.decoded().mesh.vertexCount(); })
      .def_property_readonly("tet_count", [](const PyProgressiveTetMesh& p) { return p.decoded().mesh.tetCount(); })
      .def("vertex_count_at", &PyProgressiveTetMesh::vertexCountAt, py::arg("level"))
      .def("tet_count_at", &PyProgressiveTetMesh::tetCountAt, py::arg("level"))
      .def("finest_level_within", [](const PyProgressiveTetMesh& p, uint64_t max_tets) {
            return p.decoded().mesh.finestLevelWithin(max_tets);
          }, py::arg("max_tets"), "the finest level with at most max_tets tets (0 if none)")
      .def_property_readonly("complete", [](const PyProgressiveTetMesh& p) { return p.decoded().container.complete; })
      .def_property_readonly("batches_decoded", [](const PyProgressiveTetMesh& p) { return p.decoded().batches_decoded; })
      .def_property_readonly("metadata", [](const PyProgressiveTetMesh& p) { return metadataDict(p.decoded().metadata); })
      .def_property_readonly("header", [](const PyProgressiveTetMesh& p) {
            const PtHeader& h = p.decoded().header;
            py::dict d;
            d["vertex_count"] = h.vertex_count;
            d["tet_count"] = h.tet_count;
            d["base_vertex_count"] = h.base_vertex_count;
            d["base_tet_count"] = h.base_tet_count;
            d["batch_count"] = h.batch_count;
            d["position_bits"] = h.position_bits;
            d["position_step"] = h.position_step;
            d["origin"] = py::make_tuple(h.origin[0], h.origin[1], h.origin[2]);
            py::list fields;
            for (const PtField& f : h.fields) {
              py::dict fd;
              fd["name"] = f.name;
              fd["bits"] = f.bits;
              fd["origin"] = f.origin;
              fd["step"] = f.step;
              fields.append(fd);
            }
            d["fields"] = fields;
            return d;
          }, "the THDR fields (spec 7.2)");

  m.def("encode_tets", &encodeTets, py::arg("vertices"), py::arg("tets"), py::arg("path"), py::kw_only(),
        py::arg("fields") = py::none(), py::arg("bits") = py::none(), py::arg("field_bits") = 16,
        py::arg("cost") = "quadric", py::arg("weights") = py::none(), py::arg("base_tets") = py::none(),
        py::arg("time_budget") = py::none(), py::arg("min_dihedral") = py::none(),
        py::arg("intersection_test") = true,
        R"doc(Encode a tet mesh as a progressive tet mesh (as 'mrsv encode IN.vtu OUT.mrsv').

vertices (N, 3), tets (M, 4) (negative tets are turned), fields a dict of
name to (N,) values. Options as the CLI's: bits (default 16, or the fewest
above that keep every tet positive), field_bits, cost ('quadric'|'paper'),
weights (5), base_tets, time_budget, min_dihedral, intersection_test.
Returns a dict of counts and bytes.)doc");
  m.def("read_tets", &readTets, py::arg("path"),
        "Read a tet mesh file (.mesh, .node/.ele, .vtu, .vtk): (vertices (N, 3) float64, tets (M, 4) int32, "
        "fields dict).");
  m.def("tetrahedralize", &tetrahedralize, py::arg("array"), py::kw_only(), py::arg("spacing") = py::none(),
        py::arg("nodata") = py::none(),
        "A 3-D array (z, y, x) as 6 tets per cube of samples (as 'mrsv tetrahedralize'): (vertices, tets, "
        "{'value': samples}); vertex (x, y, z) at (x*sx, y*sy, z*sz), spacing in x, y, z order; cubes with a "
        "nodata sample are left out.");
}

}  // namespace mrsv::python
