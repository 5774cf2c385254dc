// PLY (Turk's polygon file format) in its three encodings: ascii,
// binary_little_endian and binary_big_endian.
//
// Read: the `vertex` element's x, y, z (any scalar type, any order, among
// any other properties) and optionally one more named scalar property; the
// `face` element's `vertex_indices` or `vertex_index` list (any integer count
// and index types). Every other element and property, lists included, is read
// past. Written: binary_little_endian, float64 x y z [scalar], uint8 count and
// uint32 indices, so that a write-read round trip is exact.
#include <cstring>
#include <string_view>

#include "io/mesh_format_codecs.h"
#include "io/mesh_text_scanner.h"

namespace mrsv::mesh_io {
namespace {

enum class PlyType : uint8_t { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

struct PlyTypeInfo {
  PlyType type;
  const char* name;      // the original PLY name
  const char* sized;     // the name with its size, also in common use
  size_t bytes;
  bool is_integer;
  int64_t min, max;      // the range of an integer type
};

constexpr PlyTypeInfo kPlyTypes[] = {
    {PlyType::kInt8, "char", "int8", 1, true, INT8_MIN, INT8_MAX},
    {PlyType::kUint8, "uchar", "uint8", 1, true, 0, UINT8_MAX},
    {PlyType::kInt16, "short", "int16", 2, true, INT16_MIN, INT16_MAX},
    {PlyType::kUint16, "ushort", "uint16", 2, true, 0, UINT16_MAX},
    {PlyType::kInt32, "int", "int32", 4, true, INT32_MIN, INT32_MAX},
    {PlyType::kUint32, "uint", "uint32", 4, true, 0, UINT32_MAX},
    {PlyType::kFloat32, "float", "float32", 4, false, 0, 0},
    {PlyType::kFloat64, "double", "float64", 8, false, 0, 0},
};

const PlyTypeInfo& info(PlyType type) { return kPlyTypes[static_cast<int>(type)]; }

bool plyTypeNamed(std::string_view name, PlyType* out) {
  for (const PlyTypeInfo& t : kPlyTypes)
    if (name == t.name || name == t.sized) {
      *out = t.type;
      return true;
    }
  return false;
}

// What the reader does with one property of one element.
enum class Use : uint8_t { kSkip, kX, kY, kZ, kScalar, kFaceIndices };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;  // the item type of a list
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;
  Use use = Use::kSkip;
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  size_t header_line = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyEncoding { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

// Values of a binary body. Reads never pass the end: a short read leaves
// `problem` set and returns false.
class BinaryValues {
 public:
  BinaryValues(const uint8_t* data, size_t size, size_t pos, bool big_endian)
      : data_(data), size_(size), pos_(pos), big_endian_(big_endian) {}

  std::string where() const { return "byte " + std::to_string(value_start_); }
  std::string problem;

  bool number(PlyType type, double* out) {
    uint64_t bits;
    if (!fetch(type, &bits)) return false;
    if (type == PlyType::kFloat32) {
      float f;
      uint32_t b32 = static_cast<uint32_t>(bits);
      std::memcpy(&f, &b32, sizeof f);
      *out = f;
    } else if (type == PlyType::kFloat64) {
      std::memcpy(out, &bits, sizeof *out);
    } else {
      *out = static_cast<double>(integerOf(type, bits));
    }
    return true;
  }

  // `type` is an integer type (the header check guarantees it).
  bool integer(PlyType type, int64_t* out) {
    uint64_t bits;
    if (!fetch(type, &bits)) return false;
    *out = integerOf(type, bits);
    return true;
  }

  bool skip(PlyType type) {
    uint64_t bits;
    return fetch(type, &bits);
  }

  bool skipItems(PlyType type, int64_t count) {
    value_start_ = pos_;
    uint64_t bytes = static_cast<uint64_t>(count) * info(type).bytes;
    if (size_ - pos_ < bytes) return truncated();
    pos_ += bytes;
    return true;
  }

  // Bytes after the last element, which the header does not account for.
  size_t trailing() const { return size_ - pos_; }
  size_t position() const { return pos_; }

 private:
  bool fetch(PlyType type, uint64_t* bits) {
    value_start_ = pos_;
    const size_t n = info(type).bytes;
    if (size_ - pos_ < n) return truncated();
    uint64_t v = 0;
    for (size_t i = 0; i < n; ++i) {
      size_t shift = big_endian_ ? 8 * (n - 1 - i) : 8 * i;
      v |= uint64_t{data_[pos_ + i]} << shift;
    }
    pos_ += n;
    *bits = v;
    return true;
  }

  static int64_t integerOf(PlyType type, uint64_t bits) {
    switch (type) {
      case PlyType::kInt8: return static_cast<int8_t>(bits);
      case PlyType::kInt16: return static_cast<int16_t>(bits);
      case PlyType::kInt32: return static_cast<int32_t>(bits);
      default: return static_cast<int64_t>(bits);
    }
  }

  bool truncated() {
    problem = "the file ends inside the body (truncated, or the header lists more data than there is)";
    pos_ = size_;
    return false;
  }

  const uint8_t* data_;
  size_t size_;
  size_t pos_;
  size_t value_start_ = 0;
  bool big_endian_;
};

// Values of an ascii body: white-space separated tokens, lines not significant.
class AsciiValues {
 public:
  AsciiValues(const uint8_t* data, size_t size, size_t pos, size_t line)
      : scanner_(data + pos, size - pos, line) {}

  std::string where() const { return "line " + std::to_string(value_line_); }
  std::string problem;

  bool number(PlyType, double* out) {
    std::string_view token;
    if (!next(&token)) return false;
    if (NumberProblem p = parseFiniteDouble(token, out); p != NumberProblem::kNone) {
      problem = "'" + std::string(token) + "' " + numberProblemText(p);
      return false;
    }
    return true;
  }

  bool integer(PlyType type, int64_t* out) {
    std::string_view token;
    if (!next(&token)) return false;
    NumberProblem p = parseInteger(token, out);
    if (p == NumberProblem::kNone && (*out < info(type).min || *out > info(type).max))
      p = NumberProblem::kRange;
    if (p != NumberProblem::kNone) {
      problem = "'" + std::string(token) + "' " + numberProblemText(p) + " for " + info(type).name;
      return false;
    }
    return true;
  }

  bool skip(PlyType) {
    std::string_view token;
    return next(&token);
  }

  bool skipItems(PlyType type, int64_t count) {
    for (int64_t k = 0; k < count; ++k)
      if (!skip(type)) return false;
    return true;
  }

  bool onlyWhiteSpaceLeft() {
    scanner_.skipWhiteSpace();
    value_line_ = scanner_.line();
    return scanner_.atEnd();
  }

 private:
  bool next(std::string_view* token) {
    *token = scanner_.token();
    value_line_ = scanner_.line();
    if (token->empty()) {
      problem = "the file ends inside the body (truncated, or the header lists more data than there is)";
      return false;
    }
    return true;
  }

  TextScanner scanner_;
  size_t value_line_ = 0;
};

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::kAscii;
  std::vector<PlyElement> elements;
  size_t body_offset = 0;
  size_t body_line = 0;
};

bool parseHeader(const uint8_t* data, size_t size, PlyHeader* header, std::string* problem) {
  TextScanner scanner(data, size);
  auto fail = [&](const std::string& text) {
    *problem = "line " + std::to_string(scanner.line()) + ": " + text;
    return false;
  };
  if (scanner.lineToken() != "ply" || !scanner.atLineEnd())
    return fail("not a PLY file (the first line must be 'ply')");
  scanner.nextLine();
  bool has_format = false;
  for (;;) {
    if (scanner.atEnd()) return fail("the header has no end_header line");
    std::string_view keyword = scanner.lineToken();
    if (keyword == "end_header") {
      if (!scanner.atLineEnd()) return fail("text after end_header");
      // The body starts right after this line's '\n'.
      scanner.nextLine();
      break;
    }
    if (keyword == "comment" || keyword == "obj_info" || keyword.empty()) {
      scanner.nextLine();
      continue;
    }
    if (keyword == "format") {
      std::string_view encoding = scanner.lineToken();
      std::string_view version = scanner.lineToken();
      if (encoding == "ascii") header->encoding = PlyEncoding::kAscii;
      else if (encoding == "binary_little_endian") header->encoding = PlyEncoding::kBinaryLittleEndian;
      else if (encoding == "binary_big_endian") header->encoding = PlyEncoding::kBinaryBigEndian;
      else
        return fail("format '" + std::string(encoding) +
                    "' is unknown (ascii, binary_little_endian or binary_big_endian)");
      if (version != "1.0") return fail("format version '" + std::string(version) + "' is not 1.0");
      has_format = true;
    } else if (keyword == "element") {
      PlyElement element;
      element.name = std::string(scanner.lineToken());
      std::string_view count = scanner.lineToken();
      int64_t value = 0;
      if (element.name.empty() || parseInteger(count, &value) != NumberProblem::kNone || value < 0)
        return fail("element: expects 'element NAME COUNT' with a count of 0 or more");
      for (const PlyElement& e : header->elements)
        if (e.name == element.name) return fail("element '" + element.name + "' appears twice");
      element.count = static_cast<uint64_t>(value);
      element.header_line = scanner.line();
      header->elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header->elements.empty()) return fail("property before any element");
      PlyProperty property;
      std::string_view type = scanner.lineToken();
      if (type == "list") {
        property.is_list = true;
        std::string_view count_type = scanner.lineToken();
        if (!plyTypeNamed(count_type, &property.count_type) || !info(property.count_type).is_integer)
          return fail("property list: count type '" + std::string(count_type) +
                      "' is not an integer type");
        type = scanner.lineToken();
      }
      if (!plyTypeNamed(type, &property.type))
        return fail("property: type '" + std::string(type) + "' is unknown");
      property.name = std::string(scanner.lineToken());
      if (property.name.empty() || !scanner.atLineEnd())
        return fail("property: expects 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
      for (const PlyProperty& p : header->elements.back().properties)
        if (p.name == property.name)
          return fail("property '" + property.name + "' appears twice in element '" +
                      header->elements.back().name + "'");
      header->elements.back().properties.push_back(std::move(property));
    } else {
      return fail("unknown header keyword '" + std::string(keyword) + "'");
    }
    if (!scanner.atLineEnd()) return fail("unexpected text at the end of the line");
    scanner.nextLine();
  }
  if (!has_format) return fail("the header has no format line");
  header->body_offset = scanner.position();
  header->body_line = scanner.line();
  return true;
}

// Decides what each vertex and face property is for; returns a problem or "".
std::string assignUses(PlyHeader* header, const std::string& scalar_property) {
  PlyElement* vertex = nullptr;
  PlyElement* face = nullptr;
  for (PlyElement& e : header->elements) {
    if (e.name == "vertex") vertex = &e;
    if (e.name == "face") face = &e;
  }
  if (!vertex) return "header: no 'vertex' element";
  if (!face) return "header: no 'face' element";
  if (vertex->count > kMaxMeshVertices)
    return "header line " + std::to_string(vertex->header_line) + ": " +
           std::to_string(vertex->count) + " vertices (at most 2^32-1)";
  bool found[4] = {false, false, false, false};
  const char* names[4] = {"x", "y", "z", scalar_property.c_str()};
  const Use uses[4] = {Use::kX, Use::kY, Use::kZ, Use::kScalar};
  std::string available;
  for (PlyProperty& p : vertex->properties) {
    available += (available.empty() ? "" : ", ") + p.name;
    for (int k = 0; k < 4; ++k) {
      if (k == 3 && scalar_property.empty()) continue;
      if (p.name != names[k]) continue;
      if (p.is_list) return "header: vertex property '" + p.name + "' is a list, not a number";
      p.use = uses[k];
      found[k] = true;
    }
  }
  for (int k = 0; k < 3; ++k)
    if (!found[k])
      return std::string("header: vertex element has no '") + names[k] + "' property (it has " +
             (available.empty() ? "none" : available) + ")";
  if (!scalar_property.empty() && !found[3])
    return "header: vertex element has no property '" + scalar_property + "' for the scalar (it has " +
           available + ")";
  bool has_indices = false;
  for (PlyProperty& p : face->properties) {
    if (p.name != "vertex_indices" && p.name != "vertex_index") continue;
    if (has_indices) return "header: face element has both vertex_indices and vertex_index";
    if (!p.is_list) return "header: face property '" + p.name + "' is not a list";
    if (!info(p.type).is_integer)
      return "header: face property '" + p.name + "' has non-integer index type " + info(p.type).name;
    p.use = Use::kFaceIndices;
    has_indices = true;
  }
  if (!has_indices) return "header: face element has no vertex_indices (or vertex_index) list";
  return "";
}

// The fewest body bytes one instance of `element` can take: a list may be
// empty, and in ascii every value takes at least a character and a separator.
uint64_t minimumInstanceBytes(const PlyElement& element, bool ascii) {
  uint64_t bytes = 0;
  for (const PlyProperty& p : element.properties)
    bytes += ascii ? 2 : info(p.is_list ? p.count_type : p.type).bytes;
  return bytes;
}

template <typename Values>
bool readBody(const PlyHeader& header, bool with_scalar, Values* values, TriangleMesh* mesh,
              std::string* problem) {
  const size_t vertex_count = [&] {
    for (const PlyElement& e : header.elements)
      if (e.name == "vertex") return static_cast<size_t>(e.count);
    return size_t{0};
  }();
  std::vector<uint32_t> corners;
  for (const PlyElement& element : header.elements) {
    if (element.properties.empty()) continue;  // nothing to read, however large the count
    if (element.name == "vertex") {
      mesh->positions.resize(element.count);
      if (with_scalar) mesh->scalars.resize(element.count);
    }
    if (element.name == "face") mesh->triangles.reserve(element.count);
    for (uint64_t i = 0; i < element.count; ++i) {
      for (const PlyProperty& p : element.properties) {
        auto fail = [&](const std::string& text) {
          *problem = values->where() + ": " + element.name + " " + std::to_string(i) + " " +
                     p.name + ": " + text;
          return false;
        };
        if (p.is_list) {
          int64_t count = 0;
          if (!values->integer(p.count_type, &count)) return fail(values->problem);
          if (count < 0) return fail("list count " + std::to_string(count) + " is negative");
          if (p.use != Use::kFaceIndices) {
            if (!values->skipItems(p.type, count)) return fail(values->problem);
            continue;
          }
          if (count < 3)
            return fail(std::to_string(count) + " vertices (a face needs at least 3)");
          corners.clear();
          for (int64_t k = 0; k < count; ++k) {
            int64_t index = 0;
            if (!values->integer(p.type, &index)) return fail(values->problem);
            if (index < 0 || static_cast<uint64_t>(index) >= vertex_count)
              return fail("vertex index " + std::to_string(index) + " is out of range (" +
                          std::to_string(vertex_count) + " vertices)");
            corners.push_back(static_cast<uint32_t>(index));
          }
          for (size_t k = 1; k + 1 < corners.size(); ++k)
            mesh->triangles.push_back({corners[0], corners[k], corners[k + 1]});
          continue;
        }
        if (p.use == Use::kSkip) {
          if (!values->skip(p.type)) return fail(values->problem);
          continue;
        }
        double value = 0;
        if (!values->number(p.type, &value)) return fail(values->problem);
        if (!std::isfinite(value)) return fail("value is not finite (NaN or Inf)");
        switch (p.use) {
          case Use::kX: mesh->positions[i][0] = value; break;
          case Use::kY: mesh->positions[i][1] = value; break;
          case Use::kZ: mesh->positions[i][2] = value; break;
          case Use::kScalar: mesh->scalars[i] = value; break;
          default: break;
        }
      }
    }
  }
  return true;
}

void appendBytesLe(uint64_t value, size_t n, std::vector<uint8_t>* out) {
  for (size_t i = 0; i < n; ++i) out->push_back(static_cast<uint8_t>(value >> (8 * i)));
}

void appendDoubleLe(double value, std::vector<uint8_t>* out) {
  uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  appendBytesLe(bits, 8, out);
}

}  // namespace

bool readPly(const std::string& name, const uint8_t* data, size_t size,
             const std::string& scalar_property, TriangleMesh* mesh, std::string* error) {
  PlyHeader header;
  std::string problem;
  if (!parseHeader(data, size, &header, &problem) ||
      !(problem = assignUses(&header, scalar_property)).empty()) {
    *error = name + ": " + problem;
    return false;
  }
  const bool ascii = header.encoding == PlyEncoding::kAscii;
  // Checked before anything is allocated: the counts must fit in the bytes
  // that follow the header.
  uint64_t remaining = size - header.body_offset + (ascii ? 1 : 0);
  for (const PlyElement& e : header.elements) {
    uint64_t each = minimumInstanceBytes(e, ascii);
    if (each == 0) continue;
    if (e.count > remaining / each) {
      *error = name + ": header line " + std::to_string(e.header_line) + ": element '" + e.name +
               "' count " + std::to_string(e.count) + " cannot fit in the " +
               std::to_string(size - header.body_offset) + " bytes after the header";
      return false;
    }
    remaining -= e.count * each;
  }
  const bool with_scalar = !scalar_property.empty();
  bool ok;
  if (ascii) {
    AsciiValues values(data, size, header.body_offset, header.body_line);
    ok = readBody(header, with_scalar, &values, mesh, &problem);
    if (ok && !values.onlyWhiteSpaceLeft()) {
      problem = values.where() + ": unexpected data after the last element";
      ok = false;
    }
  } else {
    BinaryValues values(data, size, header.body_offset,
                        header.encoding == PlyEncoding::kBinaryBigEndian);
    ok = readBody(header, with_scalar, &values, mesh, &problem);
    if (ok && values.trailing() != 0) {
      problem = "byte " + std::to_string(values.position()) + ": " +
                std::to_string(values.trailing()) +
                " bytes after the last element (the header does not describe them)";
      ok = false;
    }
  }
  if (!ok) *error = name + ": " + problem;
  return ok;
}

void encodePly(const TriangleMesh& mesh, std::vector<uint8_t>* out) {
  const bool with_scalar = !mesh.scalars.empty();
  std::string head = "ply\nformat binary_little_endian 1.0\ncomment written by mrsv\nelement vertex ";
  appendUnsigned(mesh.positions.size(), &head);
  head += "\nproperty double x\nproperty double y\nproperty double z\n";
  if (with_scalar) head += "property double scalar\n";
  head += "element face ";
  appendUnsigned(mesh.triangles.size(), &head);
  head += "\nproperty list uchar uint vertex_indices\nend_header\n";
  out->assign(head.begin(), head.end());
  out->reserve(out->size() + mesh.positions.size() * (with_scalar ? 32 : 24) +
               mesh.triangles.size() * 13);
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    for (double c : mesh.positions[v]) appendDoubleLe(c, out);
    if (with_scalar) appendDoubleLe(mesh.scalars[v], out);
  }
  for (const auto& t : mesh.triangles) {
    out->push_back(3);
    for (uint32_t v : t) appendBytesLe(v, 4, out);
  }
}

}  // namespace mrsv::mesh_io
