// Mesh file formats read and written by the tools (never by the decoder):
// Wavefront OBJ, PLY (ascii, binary_little_endian, binary_big_endian) and
// OFF. The format is chosen by the file name's extension.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/mesh.h"

namespace mrsv {

enum class MeshFormat { kObj, kPly, kOff, kUnknown };

MeshFormat meshFormatOf(const std::string& path);

// Reads a mesh file; polygons with more than three corners are fan-split.
// `scalar_property` names a PLY vertex property (or the OBJ/OFF "nothing")
// to read into mesh->scalars; empty reads none. On failure returns false with
// one line in `error` naming the file, the line or byte offset and the problem.
bool readMeshFile(const std::string& path, const std::string& scalar_property, TriangleMesh* mesh,
                  std::string* error);

// The bytes of a mesh file for `path`'s format (PLY is written binary little-endian,
// with a `scalar` vertex property when mesh.scalars is not empty).
bool encodeMeshFile(const std::string& path, const TriangleMesh& mesh, std::vector<uint8_t>* out,
                    std::string* error);

}  // namespace mrsv
