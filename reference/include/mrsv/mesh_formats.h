// Mesh file formats read and written by the tools (never by the decoder):
// Wavefront OBJ, PLY (ascii, binary_little_endian, binary_big_endian) and
// OFF. The format is chosen by the file name's extension (case ignored).
//
// Reading
//   OBJ  `v x y z [w]` (also the colour extension `v x y z r g b [a]`, colours
//        ignored); `f` corners `a`, `a/b`, `a//c`, `a/b/c`, 1-based, negative
//        indices count back from the last vertex defined so far; every other
//        statement is ignored.
//   PLY  element `vertex` with properties x, y, z of any scalar type in any
//        order among others; element `face` with a list `vertex_indices` (or
//        `vertex_index`) of any integer count and index type; every other
//        element and property is read past. Binary bodies must end exactly
//        where the header says; ascii bodies may only be followed by white space.
//   OFF  `OFF` (or the ST/C/N variants, whose extra columns are ignored),
//        `#` comments, counts, vertices, polygons.
//   Polygons with more than three corners are fan-split: (c0, ck, ck+1).
//   Rejected with an error: NaN/Inf or unparsable coordinates, an index out of
//   range, a face with fewer than 3 corners, counts the remaining bytes could
//   not hold (checked before allocating), truncated bodies, unknown PLY
//   formats or types, a missing x, y or z.
//
// Writing
//   OBJ and OFF as text with the shortest decimal form that reads back as the
//   same double; PLY as binary_little_endian with float64 x y z, a float64
//   `scalar` property when mesh.scalars is not empty, and uint8 count + uint32
//   indices. Writing then reading gives the identical mesh. OBJ and OFF have
//   no place for scalars, so writing a mesh with scalars to them is an error.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/mesh.h"

namespace mrsv {

enum class MeshFormat { kObj, kPly, kOff, kUnknown };

// By extension: .obj, .ply, .off (any case); anything else is kUnknown.
MeshFormat meshFormatOf(const std::string& path);

// Reads a mesh file. `scalar_property` names a PLY vertex property to read
// into mesh->scalars; empty reads none (OBJ and OFF have none to name). On
// failure returns false, leaves `mesh` empty and sets `error` to one line
// naming the file, the line (text) or byte offset (binary), the field and the
// rule broken, e.g. "a.ply: byte 1234: face 7 vertex_indices: vertex index 90
// is out of range (80 vertices)".
bool readMeshFile(const std::string& path, const std::string& scalar_property, TriangleMesh* mesh,
                  std::string* error);

// As readMeshFile, for a file already in memory; `name` is used in messages
// only. Safe on any bytes: never reads outside [data, data + size).
bool readMeshBytes(const std::string& name, MeshFormat format, const uint8_t* data, size_t size,
                   const std::string& scalar_property, TriangleMesh* mesh, std::string* error);

// The bytes of a mesh file for `path`'s format. Fails (with one line in
// `error`) on an unknown extension, an index out of range, a non-finite
// coordinate, a scalar count that is not the vertex count, or scalars for a
// format without them.
bool encodeMeshFile(const std::string& path, const TriangleMesh& mesh, std::vector<uint8_t>* out,
                    std::string* error);

}  // namespace mrsv
