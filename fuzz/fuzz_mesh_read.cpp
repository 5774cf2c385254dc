// Fuzz target: the mesh file readers (OBJ, PLY in its three encodings, OFF)
// that `mrsv encode` runs on user files, then the repair and the writers on
// whatever they accept. Readers must fail with a message, never crash, and a
// mesh they accept must have every index in range.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "mrsv/mesh_formats.h"
#include "mrsv/mesh_repair.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  // The first byte picks the format and whether a PLY scalar is asked for.
  static const mrsv::MeshFormat kFormats[] = {mrsv::MeshFormat::kObj, mrsv::MeshFormat::kPly,
                                              mrsv::MeshFormat::kOff};
  const mrsv::MeshFormat format = kFormats[data[0] % 3];
  const std::string scalar = (data[0] & 0x80) && format == mrsv::MeshFormat::kPly ? "quality" : "";
  mrsv::TriangleMesh mesh;
  std::string error;
  if (!mrsv::readMeshBytes("fuzz", format, data + 1, size - 1, scalar, &mesh, &error)) {
    if (error.empty()) std::abort();
    return 0;
  }
  for (const auto& t : mesh.triangles)
    for (uint32_t v : t)
      if (v >= mesh.positions.size()) std::abort();
  mrsv::MeshRepairReport report;
  std::vector<uint32_t> origin;
  if (!mrsv::repairMesh(&mesh, mrsv::MeshRepairOptions{}, &report, &origin, &error)) {
    if (error.empty()) std::abort();
    return 0;
  }
  std::vector<uint8_t> bytes;
  for (const char* name : {"out.obj", "out.ply", "out.off"})
    if (!mrsv::encodeMeshFile(name, mesh, &bytes, &error) && error.empty()) std::abort();
  return 0;
}
