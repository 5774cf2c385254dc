// region= and region decodes shared by mrsv.decode and mrsv.mesh_grid.
#include "region.h"

#include <algorithm>
#include <memory>
#include <thread>

#include "mrsv/limits.h"
#include "mrsv/progressive_mesh.h"
#include "mrsv/progressive_tet_mesh.h"

namespace mrsv::python {
namespace {

const char kRegionForm[] = "region= must be ((x0, y0[, z0]), (x1, y1[, z1])): two corners of whole numbers, x, y, z order";

std::vector<uint32_t> corner(const py::handle& item) {
  if (!py::isinstance<py::sequence>(item) || py::isinstance<py::str>(item) || py::isinstance<py::bytes>(item))
    throw py::type_error(kRegionForm);
  std::vector<uint32_t> out;
  for (const py::handle& v : py::reinterpret_borrow<py::sequence>(item)) {
    if (py::isinstance<py::bool_>(v) || py::isinstance<py::float_>(v) || !py::hasattr(v, "__index__"))
      throw py::type_error(kRegionForm);
    const long long n = py::reinterpret_borrow<py::object>(v).attr("__index__")().cast<long long>();
    if (n < 0 || n > static_cast<long long>(kMaxGridAxis))
      throw py::value_error("region= coordinate " + std::to_string(n) + " is not a whole number from 0 to " +
                            std::to_string(kMaxGridAxis));
    out.push_back(static_cast<uint32_t>(n));
  }
  return out;
}

}  // namespace

RegionArgument parseGridRegion(const py::object& region) {
  if (!py::isinstance<py::sequence>(region) || py::isinstance<py::str>(region) || py::len(region) != 2)
    throw py::type_error(kRegionForm);
  py::sequence corners = py::reinterpret_borrow<py::sequence>(region);
  const std::vector<uint32_t> lo = corner(corners[0]), hi = corner(corners[1]);
  if (lo.size() != hi.size() || lo.empty() || lo.size() > 3)
    throw py::value_error("region= corners must both give 1 to 3 numbers, one per axis of the grid (x, y, z order)");
  RegionArgument r;
  r.dims = static_cast<int>(lo.size());
  for (int a = 0; a < r.dims; ++a) {
    r.box.lo[a] = lo[a];
    r.box.hi[a] = hi[a];
  }
  return r;
}

py::tuple regionTuple(const RegionArgument& region) {
  py::list lo, hi;
  for (int a = 0; a < region.dims; ++a) {
    lo.append(region.box.lo[a]);
    hi.append(region.box.hi[a]);
  }
  return py::make_tuple(py::tuple(lo), py::tuple(hi));
}

void refuseMeshStreams(const uint8_t* data, size_t size) {
  if (isProgressiveMeshStream(data, size))
    throw py::value_error("this is a progressive mesh stream (spec 6): open it with mrsv.ProgressiveMesh");
  if (isProgressiveTetStream(data, size))
    throw py::value_error("this is a progressive tet mesh stream (spec 7): open it with mrsv.ProgressiveTetMesh");
}

int threadCount(const py::object& threads) {
  if (threads.is_none()) return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (!py::isinstance<py::int_>(threads) || py::isinstance<py::bool_>(threads))
    throw py::type_error("threads= must be an int or None");
  const long long n = threads.cast<long long>();
  if (n < 1 || n > 1024) throw py::value_error("threads= must be a whole number from 1 to 1024");
  return static_cast<int>(n);
}

RegionDecode decodeRegion(const py::object& source_object, const py::object& byte_limit,
                          const RegionArgument& region, DecodeOptions options) {
  const bool in_memory = py::isinstance<py::bytes>(source_object) || py::isinstance<py::bytearray>(source_object) ||
                         py::isinstance<py::memoryview>(source_object);
  // A whole file is read through the file itself (only the tiles the box
  // touches of a tiled stream, spec 11.5); a prefix (bytes=) or bytes-like
  // source from memory, as 'mrsv decode --region' with --bytes.
  Source bytes;
  std::unique_ptr<ByteSource> source;
  if (!in_memory && byte_limit.is_none()) {
    const std::string path = py::module_::import("os").attr("fsdecode")(source_object).cast<std::string>();
    std::string error;
    source = openFileByteSource(path, &error);
    if (!source) {
      // Python's own open gives the usual OSError subclass (FileNotFoundError, ...).
      py::module_::import("builtins").attr("open")(path, "rb").attr("close")();
      PyErr_SetString(PyExc_OSError, (path + ": " + error).c_str());
      throw py::error_already_set();
    }
  } else {
    bytes = loadSource(source_object);
    options.container.allow_partial_tail = applyByteLimit(byte_limit, &bytes);
    source = std::make_unique<MemoryByteSource>(bytes.data, bytes.size);
  }
  RegionDecode r;
  Error e;
  {
    py::gil_scoped_release release;
    e = decodeGridRegion(*source, region.box, options, &r.grid);
  }
  r.bytes_read = source->bytesRead();
  r.bytes_total = source->size();
  // No chunk at all is a stream cut after its file header: no samples (the callers say so).
  const bool grid_stream = r.grid.container.chunks.empty() ||
                           r.grid.container.chunks[0].chunk_type == kChunkGridHeader;
  if (!e.ok() || !grid_stream) {
    uint8_t head[kFileHeaderSize + 4] = {};
    const size_t n = static_cast<size_t>(std::min<uint64_t>(sizeof head, source->size()));
    if (source->read(0, n, head)) refuseMeshStreams(head, n);
  }
  if (e.status == Status::kInvalidArgument)
    throw py::value_error((e.field == "reduce_levels" ? std::string("levels=") : e.field + "=") + ": " + e.message);
  if (!e.ok()) raiseStreamError(e);
  if (!grid_stream) throw py::value_error("region= is for grid streams");
  const int dims = r.grid.header.num_dims;
  if (!r.grid.container.chunks.empty() && region.dims != dims)
    throw py::value_error("region= gives corners of " + std::to_string(region.dims) + " numbers for a grid of " +
                          std::to_string(dims) + " dimensions: give one number per axis (x, y, z order)");
  return r;
}

}  // namespace mrsv::python
