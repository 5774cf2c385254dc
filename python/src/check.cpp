// mrsv.check: every rule a decoder applies, for any kind of stream (as 'mrsv check').
#include <pybind11/stl.h>

#include "common.h"
#include "mrsv/grid.h"
#include "mrsv/progressive_mesh.h"
#include "mrsv/progressive_tet_mesh.h"

namespace mrsv::python {
namespace {

py::dict check(const py::object& source_object) {
  Source source = loadSource(source_object);
  py::dict r;
  Error e;
  // Decode with the GIL released, then build the report from what was read.
  if (isProgressiveTetStream(source.data, source.size)) {
    DecodedTetMesh d;
    {
      py::gil_scoped_release release;
      e = decodeProgressiveTetMesh(source.data, source.size, DecodeOptions{}, &d);
    }
    if (!e.ok()) raiseStreamError(e);
    r["kind"] = "tets";
    r["vertex_count"] = d.header.vertex_count;
    r["tet_count"] = d.header.tet_count;
    r["base_vertex_count"] = d.header.base_vertex_count;
    r["base_tet_count"] = d.header.base_tet_count;
    r["splits"] = d.header.splitCount();
    r["batches"] = d.header.batch_count;
    py::list fields;
    for (const PtField& f : d.header.fields) fields.append(f.name);
    r["fields"] = fields;
    r["complete"] = d.container.complete;
    r["metadata"] = metadataDict(d.metadata);
  } else if (isProgressiveMeshStream(source.data, source.size)) {
    DecodedMesh d;
    {
      py::gil_scoped_release release;
      e = decodeProgressiveMesh(source.data, source.size, DecodeOptions{}, &d);
    }
    if (!e.ok()) raiseStreamError(e);
    r["kind"] = "mesh";
    r["vertex_count"] = d.header.vertex_count;
    r["base_vertex_count"] = d.header.base_vertex_count;
    r["base_triangle_count"] = d.header.base_triangle_count;
    r["splits"] = d.header.splitCount();
    r["batches"] = d.header.batch_count;
    r["complete"] = d.container.complete;
    r["metadata"] = metadataDict(d.metadata);
  } else {
    DecodedGrid d;
    {
      py::gil_scoped_release release;
      e = decodeGrid(source.data, source.size, DecodeOptions{}, &d);
    }
    if (!e.ok()) raiseStreamError(e);
    r["kind"] = "grid";
    std::vector<py::ssize_t> shape;
    const uint32_t sizes[3] = {d.header.size_x, d.header.size_y, d.header.size_z};
    for (int axis = d.header.num_dims - 1; axis >= 0; --axis) shape.push_back(sizes[axis]);
    r["shape"] = py::tuple(py::cast(shape));
    r["sample_type"] = sampleTypeName(d.header.sample_type);
    r["coding"] = d.header.coding == GridCoding::kStored ? "stored" : "wavelet";
    r["complete"] = d.container.complete;
    r["metadata"] = metadataDict(d.metadata);
    // What the encoder recorded of its errors (spec 2.6), as 'mrsv check' prints.
    py::dict recorded;
    for (const char* key : {"error_bound", "error_max_abs", "error_psnr_db", "error_rmse"})
      if (const std::string* v = d.metadata.find(key)) recorded[key] = *v;
    r["recorded"] = recorded;
  }
  r["bytes"] = source.size;
  return r;
}

}  // namespace

void registerCheck(py::module_& m) {
  m.def("check", &check, py::arg("source"),
        R"doc(Validate an MRSV stream (a path or bytes) against every rule a decoder applies.

Returns a dict describing a valid stream: kind ('grid', 'mesh' or 'tets'),
complete (False for a prefix without MEND), bytes, metadata and the kind's
header fields. Raises mrsv.Error (code, name, offset, field, rule) otherwise.)doc");
}

}  // namespace mrsv::python
