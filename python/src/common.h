// Helpers shared by the binding files: stream errors as mrsv.Error, sources
// (a path or bytes), numpy conversions. Each binding file registers its part
// of the module through one register* function.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "mrsv/metadata.h"
#include "mrsv/status.h"

namespace mrsv::python {

namespace py = pybind11;

// Creates mrsv.Error on `m` (called once, first, by the module).
void registerErrors(py::module_& m);
void registerGrid(py::module_& m);
void registerCheck(py::module_& m);
void registerMesh(py::module_& m);
void registerTets(py::module_& m);
void registerReconstruct(py::module_& m);
void registerStream(py::module_& m);

// Raises mrsv.Error for a broken stream rule. The GIL must be held.
[[noreturn]] void raiseStreamError(const Error& error);

// The bytes of a stream: `source` is bytes-like or a path (str or
// os.PathLike, read with Python's own I/O so that a missing file is a
// FileNotFoundError). The returned object keeps the buffer alive; the data
// is immutable, so it may be read with the GIL released.
struct Source {
  py::bytes holder;
  const uint8_t* data = nullptr;
  size_t size = 0;
};
Source loadSource(const py::object& source);

// Applies bytes=N (a prefix, as 'mrsv decode --bytes'): None keeps all.
// Returns true when the stream was cut, so that the decoder should accept
// an incomplete last chunk.
bool applyByteLimit(const py::object& limit, Source* source);

// A path for the encoders' output: str or os.PathLike.
std::string outputPath(const py::object& path);

py::dict metadataDict(const Metadata& metadata);
// Adds a {str: str} dict to `metadata`; raises TypeError or ValueError (the
// rule of spec 2.6) on a bad key or value.
void addMetadata(const py::object& entries, Metadata* metadata);

// Copies of library arrays as numpy arrays (rows of N columns).
template <typename Out, typename In, size_t N>
py::array_t<Out> rowsToArray(const std::vector<std::array<In, N>>& rows) {
  py::array_t<Out> out({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(N)});
  Out* p = out.mutable_data();
  for (const auto& row : rows)
    for (size_t c = 0; c < N; ++c) *p++ = static_cast<Out>(row[c]);
  return out;
}
template <typename Out, typename In>
py::array_t<Out> vectorToArray(const std::vector<In>& values) {
  py::array_t<Out> out(static_cast<py::ssize_t>(values.size()));
  Out* p = out.mutable_data();
  for (const In& v : values) *p++ = static_cast<Out>(v);
  return out;
}

// An (N, C) array of numbers as rows; raises ValueError naming `what` when the
// shape is wrong or (for index arrays, `max_index` > 0) a value is out of range.
std::vector<std::array<double, 3>> pointsFromArray(const py::object& array, const char* what);
template <size_t C>
std::vector<std::array<uint32_t, C>> indicesFromArray(const py::object& array, const char* what, size_t vertex_count);
// A 1-D array of `count` numbers.
std::vector<double> valuesFromArray(const py::object& array, const char* what, size_t count);

}  // namespace mrsv::python
