// Fuzz target: the PT stream decoder (spec 7) as 'mrsv decode' and 'mrsv
// check' run it, then level switching down and up again, which must give
// back exactly the mesh decoded first, every level a manifold of positive tets.
#include <cstdint>
#include <cstdlib>

#include "fuzz_params.h"
#include "mrsv/progressive_tet_mesh.h"
#include "pt/pt_state.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mrsv::DecodeOptions options;
  options.container = mrsv::fuzz::containerOptionsFromTail(data, size);
  options.max_output_bytes = 64u << 20;
  mrsv::DecodedTetMesh decoded;
  mrsv::Error e = mrsv::decodeProgressiveTetMesh(data, size, options, &decoded);
  if (!e.ok() && (e.offset > size || e.message.empty())) std::abort();
  if (e.ok() && decoded.has_mesh) {
    mrsv::ProgressiveTetMesh& pt = decoded.mesh;
    const uint32_t finest = pt.splitsDecoded();
    std::vector<uint8_t> full = mrsv::canonicalTetMeshOutput(pt);
    pt.setLevel(finest / 2);
    if (pt.tetCount() != pt.tetCountAt(finest / 2)) std::abort();
    mrsv::TetComplex c = pt.state().mesh;
    c.positions.resize(pt.vertexCount());
    c.buildIncidence();
    if (!c.checkManifold().empty()) std::abort();
    pt.setLevel(0);
    pt.setLevel(finest);
    if (mrsv::canonicalTetMeshOutput(pt) != full) std::abort();
  }
  return 0;
}
