// VTK XML UnstructuredGrid (.vtu). The XML is scanned tag by tag (no DOM, no
// XML library): the elements that matter are VTKFile, Piece, the DataArrays of
// Points, Cells and PointData, and AppendedData, whose raw bytes are never
// scanned as XML. Arrays are located first and decoded after the scan, since
// appended ones point into the data at the end of the file.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string_view>
#include <type_traits>

#include "io/mesh_format_codecs.h"
#include "io/mesh_text_scanner.h"
#include "io/tet_format_codecs.h"
#include "io/tet_value_types.h"

namespace mrsv::tet_io {
namespace {

using mesh_io::NumberProblem;
using mesh_io::parseFiniteDouble;
using mesh_io::parseInteger;

struct Attribute {
  std::string_view name;
  std::string value;  // entities decoded
};

struct Tag {
  std::string_view name;
  std::vector<Attribute> attributes;
  bool closing = false;       // </name>
  bool self_closing = false;  // <name ... />
  size_t start = 0;           // offset of '<'
  size_t end = 0;             // offset past '>'

  const std::string* attribute(std::string_view key) const {
    for (const Attribute& a : attributes)
      if (a.name == key) return &a.value;
    return nullptr;
  }
};

// Where a DataArray's values are and how they are stored.
struct ArrayRef {
  std::string name;
  ValueType type = ValueType::kFloat64;
  uint64_t components = 1;
  enum class Format { kAscii, kBinary, kAppended } format = Format::kAscii;
  size_t content_begin = 0, content_end = 0;  // inline content
  uint64_t offset = 0;                         // appended
  size_t tag_offset = 0;                       // for messages
};

bool valueType(std::string_view name, ValueType* out) {
  static const struct {
    const char* name;
    ValueType type;
  } kTypes[] = {{"Int8", ValueType::kInt8},       {"UInt8", ValueType::kUInt8},
                {"Int16", ValueType::kInt16},     {"UInt16", ValueType::kUInt16},
                {"Int32", ValueType::kInt32},     {"UInt32", ValueType::kUInt32},
                {"Int64", ValueType::kInt64},     {"UInt64", ValueType::kUInt64},
                {"Float32", ValueType::kFloat32}, {"Float64", ValueType::kFloat64},
                {"Char", ValueType::kInt8},       {"UChar", ValueType::kUInt8}};
  for (const auto& t : kTypes)
    if (name == t.name) {
      *out = t.type;
      return true;
    }
  return false;
}

std::string decodeEntities(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '&') {
      static const struct {
        const char* entity;
        char c;
      } kEntities[] = {{"&lt;", '<'}, {"&gt;", '>'}, {"&amp;", '&'}, {"&quot;", '"'}, {"&apos;", '\''}};
      bool done = false;
      for (const auto& e : kEntities) {
        std::string_view entity(e.entity);
        if (text.substr(i, entity.size()) == entity) {
          out += e.c;
          i += entity.size() - 1;
          done = true;
          break;
        }
      }
      if (done) continue;
    }
    out += text[i];
  }
  return out;
}

bool isNameChar(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == ':' || c == '-' || c == '.';
}
bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Base64 with padding allowed between groups: VTK writes a header and its data
// as one base64 run, meshio and others as two runs, each padded.
int base64Value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

// Decodes text[begin, end) until `limit` bytes are out or the text ends;
// white space is skipped. Returns "" or the problem.
std::string decodeBase64(std::string_view text, size_t limit, std::vector<uint8_t>* out) {
  out->clear();
  int group[4];
  int filled = 0, padding = 0;
  for (size_t i = 0; i < text.size() && out->size() < limit; ++i) {
    char c = text[i];
    if (isSpace(c)) continue;
    if (c == '=') {
      if (filled < 2) return "base64 padding '=' too early in a group of four";
      group[filled++] = 0;
      ++padding;
    } else {
      int v = base64Value(c);
      if (v < 0) return std::string("character '") + c + "' is not base64";
      if (padding) return "base64 data after padding inside a group of four";
      group[filled++] = v;
    }
    if (filled == 4) {
      uint32_t bits = (uint32_t(group[0]) << 18) | (uint32_t(group[1]) << 12) |
                      (uint32_t(group[2]) << 6) | uint32_t(group[3]);
      out->push_back(static_cast<uint8_t>(bits >> 16));
      if (padding < 2) out->push_back(static_cast<uint8_t>(bits >> 8));
      if (padding < 1) out->push_back(static_cast<uint8_t>(bits));
      filled = padding = 0;
    }
  }
  if (filled != 0 && out->size() < limit) return "base64 data ends inside a group of four";
  if (out->size() > limit) out->resize(limit);
  return "";
}

class VtuReader {
 public:
  VtuReader(const std::string& name, const uint8_t* data, size_t size)
      : name_(name), text_(reinterpret_cast<const char*>(data), size) {}

  bool read(TetMesh* mesh, uint64_t* skipped, std::string* error);

 private:
  bool fail(size_t offset, const std::string& problem) {
    size_t line = 1 + static_cast<size_t>(std::count(text_.begin(), text_.begin() + std::min(offset, text_.size()), '\n'));
    error_ = name_ + ":" + std::to_string(line) + ": " + problem;
    return false;
  }
  bool nextTag(size_t* pos, Tag* tag);
  bool arrayRef(const Tag& tag, ArrayRef* ref);
  // The values of `ref`: `count` of them, or all when count is kAll (then
  // `count` is set). Exactly one of doubles/integers is non-null.
  static constexpr uint64_t kAll = UINT64_MAX;
  bool values(const ArrayRef& ref, uint64_t* count, std::vector<double>* doubles,
              std::vector<int64_t>* integers);
  bool binaryBlock(const ArrayRef& ref, std::vector<uint8_t>* block);

  const std::string& name_;
  std::string_view text_;
  std::string error_;
  bool big_endian_ = false;
  bool header64_ = false;
  bool appended_raw_ = true;
  size_t appended_begin_ = std::string_view::npos;  // first byte after '_'
  size_t appended_end_ = 0;
};

bool VtuReader::nextTag(size_t* pos, Tag* tag) {
  for (;;) {
    size_t open = text_.find('<', *pos);
    if (open == std::string_view::npos) return false;
    if (text_.substr(open, 4) == "<!--") {
      size_t close = text_.find("-->", open + 4);
      if (close == std::string_view::npos) return fail(open, "comment is not closed");
      *pos = close + 3;
      continue;
    }
    if (text_.substr(open, 2) == "<?" || text_.substr(open, 2) == "<!") {
      size_t close = text_.find('>', open);
      if (close == std::string_view::npos) return fail(open, "declaration is not closed");
      *pos = close + 1;
      continue;
    }
    *tag = Tag{};
    tag->start = open;
    size_t i = open + 1;
    if (i < text_.size() && text_[i] == '/') {
      tag->closing = true;
      ++i;
    }
    size_t name_begin = i;
    while (i < text_.size() && isNameChar(text_[i])) ++i;
    tag->name = text_.substr(name_begin, i - name_begin);
    if (tag->name.empty()) return fail(open, "'<' is not followed by an element name");
    for (;;) {
      while (i < text_.size() && isSpace(text_[i])) ++i;
      if (i >= text_.size()) return fail(open, "tag <" + std::string(tag->name) + "> is not closed");
      if (text_[i] == '>') {
        tag->end = i + 1;
        break;
      }
      if (text_[i] == '/' && i + 1 < text_.size() && text_[i + 1] == '>') {
        tag->self_closing = true;
        tag->end = i + 2;
        break;
      }
      size_t key_begin = i;
      while (i < text_.size() && isNameChar(text_[i])) ++i;
      std::string_view key = text_.substr(key_begin, i - key_begin);
      while (i < text_.size() && isSpace(text_[i])) ++i;
      if (key.empty() || i >= text_.size() || text_[i] != '=')
        return fail(open, "malformed attribute in <" + std::string(tag->name) + ">");
      ++i;
      while (i < text_.size() && isSpace(text_[i])) ++i;
      if (i >= text_.size() || (text_[i] != '"' && text_[i] != '\''))
        return fail(open, "attribute " + std::string(key) + " of <" + std::string(tag->name) +
                              "> has no quoted value");
      char quote = text_[i++];
      size_t close = text_.find(quote, i);
      if (close == std::string_view::npos)
        return fail(open, "attribute " + std::string(key) + " is not closed");
      tag->attributes.push_back({key, decodeEntities(text_.substr(i, close - i))});
      i = close + 1;
    }
    *pos = tag->end;
    return true;
  }
}

bool VtuReader::arrayRef(const Tag& tag, ArrayRef* ref) {
  *ref = ArrayRef{};
  ref->tag_offset = tag.start;
  if (const std::string* n = tag.attribute("Name")) ref->name = *n;
  const std::string* type = tag.attribute("type");
  if (!type) return fail(tag.start, "DataArray '" + ref->name + "' has no type");
  if (!valueType(*type, &ref->type))
    return fail(tag.start, "DataArray '" + ref->name + "' has type " + *type +
                               " (numbers only: Int8..Int64, UInt8..UInt64, Float32, Float64)");
  if (const std::string* c = tag.attribute("NumberOfComponents")) {
    int64_t components = 0;
    if (parseInteger(*c, &components) != NumberProblem::kNone || components < 1 ||
        components > 1024)
      return fail(tag.start, "DataArray '" + ref->name + "': NumberOfComponents '" + *c +
                                 "' is not a whole number from 1 to 1024");
    ref->components = static_cast<uint64_t>(components);
  }
  const std::string* format = tag.attribute("format");
  if (!format || *format == "ascii") {
    ref->format = ArrayRef::Format::kAscii;
  } else if (*format == "binary") {
    ref->format = ArrayRef::Format::kBinary;
  } else if (*format == "appended") {
    ref->format = ArrayRef::Format::kAppended;
    const std::string* offset = tag.attribute("offset");
    int64_t value = 0;
    if (!offset || parseInteger(*offset, &value) != NumberProblem::kNone || value < 0)
      return fail(tag.start, "appended DataArray '" + ref->name + "' has no valid offset");
    ref->offset = static_cast<uint64_t>(value);
  } else {
    return fail(tag.start, "DataArray '" + ref->name + "' has format '" + *format +
                               "' (ascii, binary or appended)");
  }
  if (!tag.self_closing) {
    ref->content_begin = tag.end;
    size_t close = text_.find('<', tag.end);
    ref->content_end = close == std::string_view::npos ? text_.size() : close;
  } else {
    ref->content_begin = ref->content_end = tag.end;
  }
  return true;
}

// The bytes of a binary or appended array after its byte-count header.
bool VtuReader::binaryBlock(const ArrayRef& ref, std::vector<uint8_t>* block) {
  const size_t header = header64_ ? 8 : 4;
  auto headerValue = [&](const uint8_t* p, uint64_t* n) {
    double ignored;
    int64_t value;
    loadValue(p, header64_ ? ValueType::kUInt64 : ValueType::kUInt32, big_endian_, &ignored, &value);
    *n = static_cast<uint64_t>(value);
    return value >= 0;
  };
  uint64_t n = 0;
  if (ref.format == ArrayRef::Format::kAppended && appended_raw_) {
    if (appended_begin_ == std::string_view::npos)
      return fail(ref.tag_offset, "DataArray '" + ref.name + "' is appended but there is no AppendedData");
    const uint64_t available = appended_end_ - appended_begin_;
    if (ref.offset > available || available - ref.offset < header)
      return fail(ref.tag_offset, "DataArray '" + ref.name + "': offset " + std::to_string(ref.offset) +
                                      " is past the end of the appended data");
    const uint8_t* p = reinterpret_cast<const uint8_t*>(text_.data()) + appended_begin_ + ref.offset;
    if (!headerValue(p, &n) || n > available - ref.offset - header)
      return fail(ref.tag_offset, "DataArray '" + ref.name + "': its byte count is larger than the " +
                                      std::to_string(available - ref.offset - header) +
                                      " appended bytes after it");
    block->assign(p + header, p + header + n);
    return true;
  }
  std::string_view encoded;
  if (ref.format == ArrayRef::Format::kAppended) {
    if (appended_begin_ == std::string_view::npos)
      return fail(ref.tag_offset, "DataArray '" + ref.name + "' is appended but there is no AppendedData");
    if (ref.offset > appended_end_ - appended_begin_)
      return fail(ref.tag_offset, "DataArray '" + ref.name + "': offset is past the appended data");
    encoded = text_.substr(appended_begin_ + ref.offset, appended_end_ - appended_begin_ - ref.offset);
  } else {
    encoded = text_.substr(ref.content_begin, ref.content_end - ref.content_begin);
  }
  // Inline text is decoded whole (every character checked); appended text
  // runs on to the other arrays, so only the header is decoded first.
  std::vector<uint8_t> head;
  const bool inline_text = ref.format != ArrayRef::Format::kAppended;
  if (std::string problem = decodeBase64(encoded, inline_text ? SIZE_MAX : header, &head); !problem.empty())
    return fail(ref.tag_offset, "DataArray '" + ref.name + "': " + problem);
  if (head.size() < header)
    return fail(ref.tag_offset, "DataArray '" + ref.name + "': no byte-count header");
  headerValue(head.data(), &n);
  if (inline_text) {
    if (n > head.size() - header)
      return fail(ref.tag_offset, "DataArray '" + ref.name + "': " + std::to_string(head.size() - header) +
                                      " bytes of data where the header says " + std::to_string(n));
    block->assign(head.begin() + static_cast<long>(header), head.begin() + static_cast<long>(header + n));
    return true;
  }
  // Base64 gives 3 bytes per 4 characters: check before decoding.
  if (n > encoded.size() / 4 * 3)
    return fail(ref.tag_offset, "DataArray '" + ref.name + "': byte count " + std::to_string(n) +
                                    " is larger than its base64 text can hold");
  if (std::string problem = decodeBase64(encoded, header + n, block); !problem.empty())
    return fail(ref.tag_offset, "DataArray '" + ref.name + "': " + problem);
  if (block->size() < header + n)
    return fail(ref.tag_offset, "DataArray '" + ref.name + "': " + std::to_string(block->size() - header) +
                                    " bytes of data where the header says " + std::to_string(n));
  block->erase(block->begin(), block->begin() + static_cast<long>(header));
  return true;
}

bool VtuReader::values(const ArrayRef& ref, uint64_t* count, std::vector<double>* doubles,
                       std::vector<int64_t>* integers) {
  const std::string what = "DataArray '" + ref.name + "'";
  if (integers && isFloatType(ref.type))
    return fail(ref.tag_offset, what + " holds indices, so its type must be an integer type");
  if (ref.format == ArrayRef::Format::kAscii) {
    // At least 2 characters per value: checked before allocating.
    const size_t length = ref.content_end - ref.content_begin;
    if (*count != kAll && *count > (length + 1) / 2)
      return fail(ref.tag_offset, what + ": " + std::to_string(*count) +
                                      " values cannot fit in its " + std::to_string(length) + " characters");
    mesh_io::TextScanner scanner(reinterpret_cast<const uint8_t*>(text_.data()) + ref.content_begin, length);
    uint64_t n = 0;
    for (std::string_view token = scanner.token(); !token.empty(); token = scanner.token(), ++n) {
      if (*count != kAll && n >= *count)
        return fail(ref.tag_offset, what + ": more than the " + std::to_string(*count) + " values due");
      if (integers) {
        int64_t v = 0;
        if (parseInteger(token, &v) != NumberProblem::kNone)
          return fail(ref.tag_offset, what + ": value " + std::to_string(n) + " '" +
                                          std::string(token) + "' is not an integer");
        integers->push_back(v);
      } else {
        double v = 0;
        if (parseFiniteDouble(token, &v) != NumberProblem::kNone)
          return fail(ref.tag_offset, what + ": value " + std::to_string(n) + " '" +
                                          std::string(token) + "' is not a finite number");
        doubles->push_back(v);
      }
    }
    if (*count != kAll && n != *count)
      return fail(ref.tag_offset, what + ": " + std::to_string(n) + " values where " +
                                      std::to_string(*count) + " are due");
    *count = n;
    return true;
  }
  std::vector<uint8_t> block;
  if (!binaryBlock(ref, &block)) return false;
  const size_t size = valueSize(ref.type);
  if (block.size() % size != 0)
    return fail(ref.tag_offset, what + ": " + std::to_string(block.size()) +
                                    " bytes is not a whole number of values");
  const uint64_t n = block.size() / size;
  if (*count != kAll && n != *count)
    return fail(ref.tag_offset, what + ": " + std::to_string(n) + " values where " +
                                    std::to_string(*count) + " are due");
  *count = n;
  if (integers) integers->resize(n);
  else doubles->resize(n);
  for (uint64_t i = 0; i < n; ++i) {
    double d = 0;
    int64_t v = 0;
    loadValue(block.data() + i * size, ref.type, big_endian_, &d, &v);
    if (integers) {
      (*integers)[i] = v;
    } else {
      if (!std::isfinite(d))
        return fail(ref.tag_offset, what + ": value " + std::to_string(i) + " is not finite");
      (*doubles)[i] = d;
    }
  }
  return true;
}

bool VtuReader::read(TetMesh* mesh, uint64_t* skipped, std::string* error) {
  size_t pos = 0;
  Tag tag;
  bool have_file = false, have_piece = false;
  std::vector<std::string_view> stack;
  ArrayRef points, connectivity, offsets, types;
  bool have_points = false, have_connectivity = false, have_offsets = false, have_types = false;
  std::vector<ArrayRef> point_data;
  uint64_t n_points = 0, n_cells = 0;
  auto done = [&](bool ok) {
    if (!ok) *error = error_;
    return ok;
  };
  while (nextTag(&pos, &tag)) {
    if (tag.closing) {
      if (stack.empty() || stack.back() != tag.name)
        return done(fail(tag.start, "</" + std::string(tag.name) + "> closes no open element"));
      stack.pop_back();
      continue;
    }
    const std::string_view parent = stack.empty() ? std::string_view() : stack.back();
    if (tag.name == "VTKFile") {
      const std::string* type = tag.attribute("type");
      if (!type || *type != "UnstructuredGrid")
        return done(fail(tag.start, "VTKFile type is '" + (type ? *type : std::string()) +
                                        "' (only UnstructuredGrid is read)"));
      if (const std::string* c = tag.attribute("compressor"); c && !c->empty())
        return done(fail(tag.start, "compressed data (" + *c +
                                        ") is not supported; write the file uncompressed "
                                        "(e.g. vtkXMLUnstructuredGridWriter SetCompressorTypeToNone)"));
      if (const std::string* order = tag.attribute("byte_order")) {
        if (*order == "BigEndian") big_endian_ = true;
        else if (*order != "LittleEndian")
          return done(fail(tag.start, "byte_order '" + *order + "' is not LittleEndian or BigEndian"));
      }
      if (const std::string* h = tag.attribute("header_type")) {
        if (*h == "UInt64") header64_ = true;
        else if (*h != "UInt32")
          return done(fail(tag.start, "header_type '" + *h + "' is not UInt32 or UInt64"));
      }
      have_file = true;
    } else if (!have_file) {
      return done(fail(tag.start, "not a VTK XML file (no <VTKFile> first)"));
    } else if (tag.name == "Piece") {
      if (have_piece) return done(fail(tag.start, "more than one Piece (only single-piece files are read)"));
      have_piece = true;
      int64_t value = 0;
      const std::string* p = tag.attribute("NumberOfPoints");
      if (!p || parseInteger(*p, &value) != NumberProblem::kNone || value < 0 ||
          static_cast<uint64_t>(value) > kMaxTetVertices)
        return done(fail(tag.start, "Piece NumberOfPoints is missing or not from 0 to 2^32-1"));
      n_points = static_cast<uint64_t>(value);
      const std::string* c = tag.attribute("NumberOfCells");
      if (!c || parseInteger(*c, &value) != NumberProblem::kNone || value < 0)
        return done(fail(tag.start, "Piece NumberOfCells is missing or negative"));
      n_cells = static_cast<uint64_t>(value);
      // Every point and cell takes at least one byte of the file.
      if (n_points > text_.size() || n_cells > text_.size())
        return done(fail(tag.start, "Piece: " + std::to_string(n_points) + " points and " +
                                        std::to_string(n_cells) + " cells cannot fit in a file of " +
                                        std::to_string(text_.size()) + " bytes"));
    } else if (tag.name == "DataArray") {
      ArrayRef ref;
      if (!arrayRef(tag, &ref)) return done(false);
      if (parent == "Points") {
        if (have_points) return done(fail(tag.start, "Points has more than one DataArray"));
        if (ref.components != 3)
          return done(fail(tag.start, "Points: NumberOfComponents is " + std::to_string(ref.components) +
                                          " (3 are due)"));
        points = ref;
        have_points = true;
      } else if (parent == "Cells") {
        if (ref.name == "connectivity") {
          connectivity = ref;
          have_connectivity = true;
        } else if (ref.name == "offsets") {
          offsets = ref;
          have_offsets = true;
        } else if (ref.name == "types") {
          types = ref;
          have_types = true;
        }
        // faces / faceoffsets belong to polyhedra, which are refused by type
      } else if (parent == "PointData") {
        point_data.push_back(ref);
      }
    } else if (tag.name == "AppendedData") {
      const std::string* encoding = tag.attribute("encoding");
      appended_raw_ = !encoding || *encoding == "raw";
      if (!appended_raw_ && *encoding != "base64")
        return done(fail(tag.start, "AppendedData encoding '" + *encoding + "' is not raw or base64"));
      size_t underscore = text_.find('_', tag.end);
      if (underscore == std::string_view::npos)
        return done(fail(tag.start, "AppendedData has no '_' before its data"));
      appended_begin_ = underscore + 1;
      // The data runs to the closing tag; raw bytes may contain anything, so
      // it is looked for from the end and nothing after it is scanned.
      size_t close = text_.rfind("</AppendedData>");
      appended_end_ = close == std::string_view::npos || close < appended_begin_ ? text_.size() : close;
      break;
    }
    if (!tag.self_closing) stack.push_back(tag.name);
    if (stack.size() > 64) return done(fail(tag.start, "elements nested more than 64 deep"));
  }
  if (!error_.empty()) return done(false);
  if (!have_file) return done(fail(0, "not a VTK XML file (no <VTKFile>)"));
  if (!have_piece) return done(fail(0, "no Piece"));
  if (n_points > 0 && !have_points) return done(fail(0, "Piece has points but no Points array"));
  if (n_cells > 0 && !(have_connectivity && have_offsets && have_types))
    return done(fail(0, "Cells needs the DataArrays connectivity, offsets and types"));

  std::vector<double> coordinates;
  uint64_t count = n_points * 3;
  if (n_points > 0 && !values(points, &count, &coordinates, nullptr)) return done(false);
  mesh->positions.resize(n_points);
  for (uint64_t v = 0; v < n_points; ++v)
    for (int k = 0; k < 3; ++k) {
      double c = coordinates[v * 3 + k];
      if (std::string why = coordinateProblem(c); !why.empty())
        return done(fail(points.tag_offset, "Points: point " + std::to_string(v) + " coordinate " +
                                                std::to_string(c) + " " + why));
      mesh->positions[v][k] = c;
    }
  coordinates = {};

  if (n_cells > 0) {
    std::vector<int64_t> cell_types, cell_offsets, cell_vertices;
    count = n_cells;
    if (!values(types, &count, nullptr, &cell_types)) return done(false);
    count = n_cells;
    if (!values(offsets, &count, nullptr, &cell_offsets)) return done(false);
    count = kAll;
    if (!values(connectivity, &count, nullptr, &cell_vertices)) return done(false);
    int64_t begin = 0;
    uint64_t tets = 0;
    for (uint64_t c = 0; c < n_cells; ++c) {
      const int64_t end = cell_offsets[c];
      if (end < begin || static_cast<uint64_t>(end) > cell_vertices.size())
        return done(fail(offsets.tag_offset, "offsets: cell " + std::to_string(c) + " ends at " +
                                                 std::to_string(end) + ", outside " + std::to_string(begin) +
                                                 ".." + std::to_string(cell_vertices.size())));
      VtkCellKind kind = vtkCellKind(cell_types[c]);
      if (kind == VtkCellKind::kOther3d)
        return done(fail(types.tag_offset, "cell " + std::to_string(c) + " is a " +
                                               vtkCellTypeName(cell_types[c]) +
                                               " (only tetrahedra, VTK type 10, are read)"));
      if (kind == VtkCellKind::kTetra) {
        if (end - begin != 4)
          return done(fail(offsets.tag_offset, "cell " + std::to_string(c) + " is a tetrahedron with " +
                                                   std::to_string(end - begin) + " vertices"));
        ++tets;
      }
      begin = end;
    }
    mesh->tets.reserve(tets);
    begin = 0;
    for (uint64_t c = 0; c < n_cells; ++c) {
      if (vtkCellKind(cell_types[c]) == VtkCellKind::kTetra) {
        std::array<uint32_t, 4> tet;
        for (int k = 0; k < 4; ++k) {
          int64_t v = cell_vertices[static_cast<size_t>(begin + k)];
          if (v < 0 || static_cast<uint64_t>(v) >= n_points)
            return done(fail(connectivity.tag_offset, "cell " + std::to_string(c) + " has vertex index " +
                                                          std::to_string(v) + " out of range (" +
                                                          std::to_string(n_points) + " points)"));
          tet[k] = static_cast<uint32_t>(v);
        }
        mesh->tets.push_back(tet);
      } else {
        ++*skipped;
      }
      begin = cell_offsets[c];
    }
  }

  for (const ArrayRef& ref : point_data) {
    std::vector<double> data;
    count = n_points * ref.components;
    if (ref.components > 1 && n_points > text_.size() / ref.components)
      return done(fail(ref.tag_offset, "DataArray '" + ref.name + "' is too large for the file"));
    if (!values(ref, &count, &data, nullptr)) return done(false);
    std::string base = ref.name.empty() ? "field" + std::to_string(mesh->fields.size()) : ref.name;
    for (uint64_t k = 0; k < ref.components; ++k) {
      ScalarField field;
      field.name = ref.components == 1 ? base : base + "_" + std::to_string(k);
      field.values.resize(n_points);
      for (uint64_t v = 0; v < n_points; ++v) field.values[v] = data[v * ref.components + k];
      mesh->fields.push_back(std::move(field));
    }
  }
  return true;
}

// ---- writing

void appendBase64(const uint8_t* data, size_t size, std::string* out) {
  static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  size_t i = 0;
  for (; i + 3 <= size; i += 3) {
    uint32_t bits = (uint32_t(data[i]) << 16) | (uint32_t(data[i + 1]) << 8) | data[i + 2];
    for (int s = 18; s >= 0; s -= 6) *out += kAlphabet[(bits >> s) & 63];
  }
  if (i < size) {
    uint32_t bits = uint32_t(data[i]) << 16;
    if (i + 1 < size) bits |= uint32_t(data[i + 1]) << 8;
    *out += kAlphabet[(bits >> 18) & 63];
    *out += kAlphabet[(bits >> 12) & 63];
    *out += i + 1 < size ? kAlphabet[(bits >> 6) & 63] : '=';
    *out += '=';
  }
}

void putLittleEndian(uint64_t bits, size_t bytes, std::vector<uint8_t>* out) {
  for (size_t i = 0; i < bytes; ++i) out->push_back(static_cast<uint8_t>(bits >> (8 * i)));
}

// One DataArray: the opening tag with `attributes`, the values get(0) ..
// get(count - 1) (doubles as Float64, integers in `bytes_per_value` bytes),
// the closing tag.
template <typename Get>
void appendArray(const char* type, const std::string& attributes, size_t count, bool ascii,
                 size_t bytes_per_value, Get get, std::string* text) {
  constexpr bool kFloat = std::is_same_v<decltype(get(size_t{0})), double>;
  *text += std::string("        <DataArray type=\"") + type + "\" " + attributes + " format=\"" +
           (ascii ? "ascii" : "binary") + "\">\n          ";
  if (ascii) {
    for (size_t i = 0; i < count; ++i) {
      if (i) *text += (i % 12 == 0) ? "\n          " : " ";
      if constexpr (kFloat) mesh_io::appendShortestDouble(get(i), text);
      else mesh_io::appendUnsigned(get(i), text);
    }
  } else {
    std::vector<uint8_t> block;
    block.reserve(8 + count * bytes_per_value);
    putLittleEndian(count * bytes_per_value, 8, &block);  // header_type UInt64
    for (size_t i = 0; i < count; ++i) {
      if constexpr (kFloat) {
        double value = get(i);
        uint64_t bits;
        std::memcpy(&bits, &value, 8);
        putLittleEndian(bits, 8, &block);
      } else {
        putLittleEndian(get(i), bytes_per_value, &block);
      }
    }
    appendBase64(block.data(), block.size(), text);
  }
  *text += "\n        </DataArray>\n";
}

}  // namespace

bool readVtu(const std::string& name, const uint8_t* data, size_t size, TetMesh* mesh,
             uint64_t* skipped_cells, std::string* error) {
  *skipped_cells = 0;
  VtuReader reader(name, data, size);
  return reader.read(mesh, skipped_cells, error);
}

void encodeVtu(const TetMesh& mesh, bool ascii, std::vector<uint8_t>* out) {
  const size_t n = mesh.positions.size(), m = mesh.tets.size();
  std::string text =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n"
      "  <UnstructuredGrid>\n"
      "    <Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfCells=\"" + std::to_string(m) +
      "\">\n";
  text.reserve(n * (ascii ? 60 : 32) + m * (ascii ? 50 : 60) + n * mesh.fields.size() * 24 + 1024);
  if (mesh.fields.empty()) {
    text += "      <PointData>\n";
  } else {
    text += "      <PointData Scalars=\"" + mesh.fields[0].name + "\">\n";
    for (const ScalarField& field : mesh.fields)
      appendArray("Float64", "Name=\"" + field.name + "\"", n, ascii, 8,
                  [&](size_t i) { return field.values[i]; }, &text);
  }
  text += "      </PointData>\n      <CellData>\n      </CellData>\n      <Points>\n";
  appendArray("Float64", "Name=\"Points\" NumberOfComponents=\"3\"", 3 * n, ascii, 8,
              [&](size_t i) { return mesh.positions[i / 3][i % 3]; }, &text);
  text += "      </Points>\n      <Cells>\n";
  appendArray("Int64", "Name=\"connectivity\"", 4 * m, ascii, 8,
              [&](size_t i) { return uint64_t{mesh.tets[i / 4][i % 4]}; }, &text);
  appendArray("Int64", "Name=\"offsets\"", m, ascii, 8,
              [&](size_t i) { return uint64_t{4 * (i + 1)}; }, &text);
  appendArray("UInt8", "Name=\"types\"", m, ascii, 1,
              [&](size_t) { return uint64_t{10}; }, &text);
  text += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  out->assign(text.begin(), text.end());
}

}  // namespace mrsv::tet_io
