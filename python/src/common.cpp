// Sources, output paths, metadata and array conversions shared by the bindings.
#include <cmath>

#include "common.h"

namespace mrsv::python {

Source loadSource(const py::object& source) {
  Source s;
  if (py::isinstance<py::bytes>(source)) {
    s.holder = py::reinterpret_borrow<py::bytes>(source);
  } else if (py::isinstance<py::bytearray>(source) || py::isinstance<py::memoryview>(source)) {
    // A mutable buffer could change while the GIL is released: take a copy.
    s.holder = py::bytes(py::module_::import("builtins").attr("bytes")(source));
  } else {
    // pathlib gives the usual TypeError for a non-path and OSError subclasses
    // (FileNotFoundError, PermissionError) for files that cannot be read.
    s.holder = py::module_::import("pathlib").attr("Path")(source).attr("read_bytes")();
  }
  char* data = nullptr;
  py::ssize_t size = 0;
  if (PyBytes_AsStringAndSize(s.holder.ptr(), &data, &size) != 0) throw py::error_already_set();
  s.data = reinterpret_cast<const uint8_t*>(data);
  s.size = static_cast<size_t>(size);
  return s;
}

bool applyByteLimit(const py::object& limit, Source* source) {
  if (limit.is_none()) return false;
  if (!py::isinstance<py::int_>(limit) || py::isinstance<py::bool_>(limit))
    throw py::type_error("bytes= must be an int (a prefix length) or None");
  long long n = limit.cast<long long>();
  if (n < 0) throw py::value_error("bytes= must not be negative");
  if (static_cast<unsigned long long>(n) >= source->size) return false;
  source->size = static_cast<size_t>(n);
  return true;
}

std::string outputPath(const py::object& path) {
  py::object fs = py::module_::import("os").attr("fspath")(path);
  if (!py::isinstance<py::str>(fs)) throw py::type_error("the output path must be a str or os.PathLike of str");
  return fs.cast<std::string>();
}

py::dict metadataDict(const Metadata& metadata) {
  py::dict d;
  for (const auto& [key, value] : metadata.entries) d[py::str(key)] = py::str(value);
  return d;
}

void addMetadata(const py::object& entries, Metadata* metadata) {
  if (entries.is_none()) return;
  if (!py::isinstance<py::dict>(entries)) throw py::type_error("metadata= must be a dict of str to str");
  for (auto [k, v] : entries.cast<py::dict>()) {
    if (!py::isinstance<py::str>(k) || !py::isinstance<py::str>(v))
      throw py::type_error("metadata= must be a dict of str to str");
    std::string key = k.cast<std::string>(), value = v.cast<std::string>();
    if (std::string problem = metadataEntryProblem(key, value); !problem.empty())
      throw py::value_error("metadata '" + key + "': " + problem);
    metadata->set(key, value);
  }
}

namespace {

// A C-contiguous float64 or int64 view of an array-like with `columns`
// columns (0: one-dimensional).
py::array asArray(const py::object& array, const char* what, bool integers, size_t columns) {
  py::module_ np = py::module_::import("numpy");
  py::array a = np.attr("asarray")(array);
  std::string kind = py::str(a.dtype().attr("kind"));
  if (integers ? (kind != "i" && kind != "u") : (kind != "i" && kind != "u" && kind != "f"))
    throw py::type_error(std::string(what) + " must hold " + (integers ? "integers" : "numbers") + ", not " +
                         std::string(py::str(a.dtype())));
  bool shape_ok = columns == 0 ? a.ndim() == 1 : a.ndim() == 2 && static_cast<size_t>(a.shape(1)) == columns;
  if (!shape_ok)
    throw py::value_error(std::string(what) + " must have shape " +
                          (columns == 0 ? std::string("(N,)") : "(N, " + std::to_string(columns) + ")") +
                          ", not " + std::string(py::str(a.attr("shape"))));
  return np.attr("ascontiguousarray")(a, integers ? "int64" : "float64");
}

}  // namespace

std::vector<std::array<double, 3>> pointsFromArray(const py::object& array, const char* what) {
  py::array a = asArray(array, what, false, 3);
  const double* p = static_cast<const double*>(a.data());
  std::vector<std::array<double, 3>> rows(static_cast<size_t>(a.shape(0)));
  for (auto& row : rows)
    for (double& v : row) {
      v = *p++;
      if (!std::isfinite(v)) throw py::value_error(std::string(what) + " must be finite");
    }
  return rows;
}

template <size_t C>
std::vector<std::array<uint32_t, C>> indicesFromArray(const py::object& array, const char* what, size_t vertex_count) {
  py::array a = asArray(array, what, true, C);
  const int64_t* p = static_cast<const int64_t*>(a.data());
  std::vector<std::array<uint32_t, C>> rows(static_cast<size_t>(a.shape(0)));
  for (size_t r = 0; r < rows.size(); ++r)
    for (size_t c = 0; c < C; ++c) {
      int64_t v = *p++;
      if (v < 0 || static_cast<uint64_t>(v) >= vertex_count)
        throw py::value_error(std::string(what) + "[" + std::to_string(r) + "] has vertex index " +
                              std::to_string(v) + ", out of range (" + std::to_string(vertex_count) + " vertices)");
      rows[r][c] = static_cast<uint32_t>(v);
    }
  return rows;
}
template std::vector<std::array<uint32_t, 3>> indicesFromArray<3>(const py::object&, const char*, size_t);
template std::vector<std::array<uint32_t, 4>> indicesFromArray<4>(const py::object&, const char*, size_t);

std::vector<double> valuesFromArray(const py::object& array, const char* what, size_t count) {
  py::array a = asArray(array, what, false, 0);
  if (static_cast<size_t>(a.shape(0)) != count)
    throw py::value_error(std::string(what) + " must hold one value per vertex (" + std::to_string(count) +
                          "), not " + std::to_string(a.shape(0)));
  const double* p = static_cast<const double*>(a.data());
  return std::vector<double>(p, p + count);
}

}  // namespace mrsv::python
