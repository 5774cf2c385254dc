// The subcommands of mrsv. Each takes the arguments after its name.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mrsv/grid.h"
#include "mrsv/progressive_mesh.h"
#include "mrsv/progressive_tet_mesh.h"
#include "mrsv/raw_grid.h"
#include "mrsv/tiled_grid.h"

namespace mrsv::cli {

int runEncode(int argc, char** argv);
int runDecode(int argc, char** argv);
int runInfo(int argc, char** argv);
int runCheck(int argc, char** argv);
int runCompare(int argc, char** argv);
int runTetrahedralize(int argc, char** argv);
int runMesh(int argc, char** argv);  // cmd_reconstruct.cpp: the reconstructors of spec 8

// Meshes (cmd_mesh.cpp): encode dispatches when an argument names a mesh file;
// decode and check dispatch on the stream's first chunk.
bool isMeshEncode(int argc, char** argv);
int runMeshEncode(int argc, char** argv);
class Args;
// `decode` decodes the stream with the options the level needs (mrsv decode
// feeds it the input as it arrives).
using MeshDecodeFn = std::function<Error(const DecodeOptions&, DecodedMesh*)>;
int runMeshDecode(const Args& args, const std::string& in, const std::string& out,
                  const MeshDecodeFn& decode, const DecodeOptions& options);

// Tet meshes (cmd_tets.cpp): encode dispatches when an argument names a tet
// mesh file; decode, info and check dispatch on the stream's first chunk.
bool isTetEncode(int argc, char** argv);
int runTetEncode(int argc, char** argv);
using TetDecodeFn = std::function<Error(const DecodeOptions&, DecodedTetMesh*)>;
int runTetDecode(const Args& args, const std::string& in, const std::string& out,
                 const TetDecodeFn& decode, const DecodeOptions& options);

// mrsv decode --region (cmd_decode_region.cpp): a box of a grid, read through
// the tile index when the stream is tiled. `source` null: IN is read by offset.
int runRegionDecode(const Args& args, const std::string& in, const std::string& out,
                    const GridRegion& region, int threads, Endian endian, uint64_t levels,
                    ByteSource* source = nullptr);

// mrsv compare of two tet meshes (cmd_compare_tets.cpp).
bool isTetCompare(const Args& args);
int runTetCompare(const Args& args, uint64_t samples, uint64_t seed, unsigned threads);

}  // namespace mrsv::cli
