// The per-format readers and writers behind mesh_formats.h. Each reader gets
// the whole file in memory and the name to put in error messages; each
// writer gets a mesh already checked by checkMeshForWriting().
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/mesh.h"

namespace mrsv::mesh_io {

bool readObj(const std::string& name, const uint8_t* data, size_t size, TriangleMesh* mesh,
             std::string* error);
bool readOff(const std::string& name, const uint8_t* data, size_t size, TriangleMesh* mesh,
             std::string* error);
bool readPly(const std::string& name, const uint8_t* data, size_t size,
             const std::string& scalar_property, TriangleMesh* mesh, std::string* error);

void encodeObj(const TriangleMesh& mesh, std::vector<uint8_t>* out);
void encodeOff(const TriangleMesh& mesh, std::vector<uint8_t>* out);
void encodePly(const TriangleMesh& mesh, std::vector<uint8_t>* out);

// Appends the shortest decimal text that reads back as exactly `value`.
void appendShortestDouble(double value, std::string* out);

// Appends `value` in decimal.
void appendUnsigned(uint64_t value, std::string* out);

// The largest number of vertices a TriangleMesh can index.
constexpr uint64_t kMaxMeshVertices = UINT32_MAX;

}  // namespace mrsv::mesh_io
