// Fuzz target: the tet mesh readers (MEDIT, TetGen, VTU, legacy VTK) that
// `mrsv tetrahedralize` runs on user files, and the PLOT3D reader, then the
// writers on whatever they accept. Readers must fail with a message, never
// crash, and a mesh they accept must have every index in range and every tet
// positively oriented.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "mrsv/tet_formats.h"

namespace {

void checkMesh(const mrsv::TetMesh& mesh) {
  for (const auto& t : mesh.tets) {
    for (uint32_t v : t)
      if (v >= mesh.positions.size()) std::abort();
    if (mrsv::orient3dSign(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]],
                           mesh.positions[t[3]]) <= 0)
      std::abort();
  }
  for (const auto& f : mesh.fields)
    if (f.values.size() != mesh.positions.size()) std::abort();
  std::vector<mrsv::TetFileBytes> files;
  std::string error;
  for (const char* name : {"out.mesh", "out.node", "out.vtu", "out.vtk"})
    for (bool ascii : {false, true}) {
      mrsv::TetWriteOptions options;
      options.ascii = ascii;
      // Field names from a file may hold characters the formats cannot carry: a message, not a crash.
      if (!mrsv::encodeTetFile(name, mesh, options, &files, nullptr, &error) && error.empty()) std::abort();
    }
}

}  // namespace

// The first byte picks the reader. TetGen and PLOT3D take two files: the
// input is cut in two at the first "\n====\n" (or the second part is empty).
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const uint8_t selector = data[0] % 5;
  ++data;
  --size;
  mrsv::TetMesh mesh;
  std::string error;
  if (selector < 3) {
    static const mrsv::TetFormat kFormats[] = {mrsv::TetFormat::kMedit, mrsv::TetFormat::kVtu,
                                               mrsv::TetFormat::kVtkLegacy};
    if (!mrsv::readTetBytes("fuzz", kFormats[selector], data, size, &mesh, nullptr, &error)) {
      if (error.empty()) std::abort();
      return 0;
    }
    checkMesh(mesh);
    return 0;
  }
  const std::string text(reinterpret_cast<const char*>(data), size);
  const size_t cut = text.find("\n====\n");
  const size_t first = cut == std::string::npos ? size : cut + 1;
  const size_t second = cut == std::string::npos ? size : cut + 6;
  if (selector == 3) {
    if (!mrsv::readTetgenBytes("fuzz.node", data, first, "fuzz.ele", data + second, size - second, &mesh,
                               nullptr, &error)) {
      if (error.empty()) std::abort();
      return 0;
    }
    checkMesh(mesh);
    return 0;
  }
  mrsv::Plot3dData plot3d;
  if (!mrsv::readPlot3dBytes("fuzz.xyz", data, first, cut == std::string::npos ? "" : "fuzz.q",
                             data + second, size - second, &plot3d, &error)) {
    if (error.empty()) std::abort();
    return 0;
  }
  // Grids from the fuzzer are small (the file holds every point).
  mrsv::TetBuildReport report;
  if (mrsv::tetrahedralizePlot3d(plot3d, &mesh, &report, &error)) checkMesh(mesh);
  else if (error.empty()) std::abort();
  return 0;
}
