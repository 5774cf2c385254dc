// The _mrsv extension module: the MRSV reference library for Python. The
// pure-Python package mrsv (python/mrsv/__init__.py) re-exports it.
#include "common.h"

PYBIND11_MODULE(_mrsv, m) {
  m.doc() = "MRSV reference codec: grids, progressive meshes and progressive tet meshes";
  // Errors first: every other part raises mrsv.Error.
  mrsv::python::registerErrors(m);
  mrsv::python::registerGrid(m);
  mrsv::python::registerCheck(m);
  mrsv::python::registerMesh(m);
  mrsv::python::registerTets(m);
  mrsv::python::registerReconstruct(m);
  mrsv::python::registerStream(m);
}
