// Fuzz target: the PM stream decoder (spec 6) as 'mrsv decode' and 'mrsv
// check' run it, then level switching down and up again, which must give
// back exactly the mesh decoded first.
#include <cstdint>
#include <cstdlib>

#include "fuzz_params.h"
#include "mrsv/progressive_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mrsv::DecodeOptions options;
  options.container = mrsv::fuzz::containerOptionsFromTail(data, size);
  options.max_output_bytes = 64u << 20;
  mrsv::DecodedMesh decoded;
  mrsv::Error e = mrsv::decodeProgressiveMesh(data, size, options, &decoded);
  if (!e.ok() && (e.offset > size || e.message.empty())) std::abort();
  if (e.ok() && decoded.has_mesh) {
    mrsv::ProgressiveMesh& pm = decoded.mesh;
    const uint32_t finest = pm.splitsDecoded();
    std::vector<uint8_t> full = mrsv::canonicalMeshOutput(pm);
    pm.setLevel(finest / 2);
    if (pm.triangleCount() != pm.triangleCountAt(finest / 2)) std::abort();
    pm.setLevel(0);
    pm.setLevel(finest);
    if (mrsv::canonicalMeshOutput(pm) != full) std::abort();
  }
  return 0;
}
