// The per-format readers and writers behind tet_formats.h. Each reader gets
// the whole file in memory and the name for messages, fills positions, tets
// (0-based, orientation not yet repaired) and fields, and checks every index
// and count; the dispatcher (tet_formats.cpp) then repairs the orientation.
// Each writer gets a mesh already checked by the dispatcher.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/tet_formats.h"

namespace mrsv::tet_io {

bool readMedit(const std::string& name, const uint8_t* data, size_t size, TetMesh* mesh,
               std::string* error);
bool readTetgen(const std::string& node_name, const uint8_t* node, size_t node_size,
                const std::string& ele_name, const uint8_t* ele, size_t ele_size, TetMesh* mesh,
                std::string* error);
bool readVtu(const std::string& name, const uint8_t* data, size_t size, TetMesh* mesh,
             uint64_t* skipped_cells, std::string* error);
bool readVtkLegacy(const std::string& name, const uint8_t* data, size_t size, TetMesh* mesh,
                   uint64_t* skipped_cells, std::string* error);

void encodeMedit(const TetMesh& mesh, std::vector<uint8_t>* out);
void encodeTetgenNode(const TetMesh& mesh, std::vector<uint8_t>* out);
void encodeTetgenEle(const TetMesh& mesh, std::vector<uint8_t>* out);
void encodeVtu(const TetMesh& mesh, bool ascii, std::vector<uint8_t>* out);
void encodeVtkLegacy(const TetMesh& mesh, bool ascii, std::vector<uint8_t>* out);

// "" when `c` is a coordinate the readers accept, otherwise why not.
std::string coordinateProblem(double c);

// What a VTK cell type means to the readers (VTU and legacy VTK).
enum class VtkCellKind { kTetra, kLowerDimension, kOther3d };
VtkCellKind vtkCellKind(int64_t type);
std::string vtkCellTypeName(int64_t type);

// The largest vertex count a TetMesh can index.
constexpr uint64_t kMaxTetVertices = UINT32_MAX;

}  // namespace mrsv::tet_io
