// mrsv.Error: a broken rule of a stream, with the fields of mrsv::Error as
// attributes so that callers branch on the code rather than parse text.
#include <cstdint>

#include "common.h"

namespace mrsv::python {
namespace {

// Owned by the module for the life of the interpreter (never destroyed: the
// module is never unloaded).
PyObject* error_type = nullptr;

const char kErrorDoc[] =
    "A stream broke a rule of the MRSV specification.\n"
    "\n"
    "Attributes:\n"
    "  code    the status number of spec Annex A (int), e.g. 113\n"
    "  name    its stable name, e.g. 'checksum_mismatch'\n"
    "  offset  the byte offset in the file where the rule was found broken\n"
    "  field   the syntax element or chunk concerned, e.g. 'GRAW.chunk_crc'\n"
    "  rule    the rule that was broken, one line\n"
    "str() gives the line 'mrsv check' prints: 'offset 568: E113 checksum_mismatch: ...'.";

}  // namespace

void registerErrors(py::module_& m) {
  error_type = PyErr_NewExceptionWithDoc("mrsv.Error", kErrorDoc, PyExc_Exception, nullptr);
  if (error_type == nullptr) throw py::error_already_set();
  m.add_object("Error", py::handle(error_type));
}

void raiseStreamError(const Error& error) {
  py::object type = py::reinterpret_borrow<py::object>(error_type);
  py::object exc = type(error.describe());
  exc.attr("code") = static_cast<int>(error.status);
  exc.attr("name") = statusName(error.status);
  exc.attr("offset") = error.offset;
  exc.attr("field") = error.field;
  exc.attr("rule") = error.message;
  PyErr_SetObject(error_type, exc.ptr());
  throw py::error_already_set();
}

}  // namespace mrsv::python
