// Legacy VTK files (.vtk), DATASET UNSTRUCTURED_GRID, ASCII or BINARY. The
// keywords are text in both; BINARY data are big-endian blocks that start on
// the line after their keyword line. Versions before 5 store CELLS as one
// list (count, then indices, per cell); 5.x as OFFSETS and CONNECTIVITY.
#include <cmath>
#include <cstring>
#include <string_view>

#include "io/mesh_format_codecs.h"
#include "io/mesh_text_scanner.h"
#include "io/tet_format_codecs.h"
#include "io/tet_value_types.h"

namespace mrsv::tet_io {
namespace {

using mesh_io::NumberProblem;
using mesh_io::parseFiniteDouble;
using mesh_io::parseInteger;

bool legacyType(std::string_view name, ValueType* out) {
  static const struct {
    const char* name;
    ValueType type;
  } kTypes[] = {{"char", ValueType::kInt8},           {"unsigned_char", ValueType::kUInt8},
                {"short", ValueType::kInt16},         {"unsigned_short", ValueType::kUInt16},
                {"int", ValueType::kInt32},           {"unsigned_int", ValueType::kUInt32},
                {"long", ValueType::kInt64},          {"unsigned_long", ValueType::kUInt64},
                {"vtktypeint64", ValueType::kInt64},  {"vtktypeuint64", ValueType::kUInt64},
                {"vtkIdType", ValueType::kInt32},     {"float", ValueType::kFloat32},
                {"double", ValueType::kFloat64}};
  for (const auto& t : kTypes)
    if (name == t.name) {
      *out = t.type;
      return true;
    }
  return false;
}

class LegacyReader {
 public:
  LegacyReader(const std::string& name, const uint8_t* data, size_t size)
      : name_(name), text_(reinterpret_cast<const char*>(data), size) {}
  bool read(TetMesh* mesh, uint64_t* skipped, std::string* error);

 private:
  bool fail(const std::string& problem) {
    if (binary_ && header_done_)
      error_ = name_ + ": byte " + std::to_string(pos_) + ": " + problem;
    else
      error_ = name_ + ":" + std::to_string(line_) + ": " + problem;
    return false;
  }
  static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\0'; }
  // The next white-space separated token, crossing lines; empty at the end.
  std::string_view token() {
    while (pos_ < text_.size() && isSpace(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
    size_t start = pos_;
    while (pos_ < text_.size() && !isSpace(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }
  // The next token if it is on the current line, else empty (nothing consumed).
  std::string_view lineToken() {
    size_t p = pos_;
    while (p < text_.size() && isSpace(text_[p]) && text_[p] != '\n') ++p;
    if (p >= text_.size() || text_[p] == '\n') return {};
    return token();
  }
  // The rest of the current line, and the cursor past its newline.
  std::string_view restOfLine() {
    size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    std::string_view line = text_.substr(start, pos_ - start);
    if (pos_ < text_.size()) {
      ++pos_;
      ++line_;
    }
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
  }
  bool count(const char* what, uint64_t* out) {
    std::string_view t = token();
    int64_t v = 0;
    if (parseInteger(t, &v) != NumberProblem::kNone || v < 0)
      return fail(std::string(what) + " '" + std::string(t) + "' is not a non-negative whole number");
    *out = static_cast<uint64_t>(v);
    return true;
  }
  bool type(ValueType* out) {
    std::string_view t = token();
    if (!legacyType(t, out))
      return fail("data type '" + std::string(t) + "' is not one of char, unsigned_char, short, "
                  "unsigned_short, int, unsigned_int, long, unsigned_long, vtktypeint64, "
                  "vtktypeuint64, vtkIdType, float, double");
    return true;
  }
  // `n` values of type `t` (ascii tokens or a big-endian block); exactly one
  // of doubles / integers is non-null and gets them.
  bool values(const std::string& what, ValueType t, uint64_t n, std::vector<double>* doubles,
              std::vector<int64_t>* integers);
  bool skipMetadata();
  bool attributeSection(std::string_view keyword, uint64_t n, bool keep, TetMesh* mesh);

  const std::string& name_;
  std::string_view text_;
  size_t pos_ = 0, line_ = 1;
  bool binary_ = false, header_done_ = false;
  std::string error_;
};

bool LegacyReader::values(const std::string& what, ValueType t, uint64_t n,
                          std::vector<double>* doubles, std::vector<int64_t>* integers) {
  if (doubles) doubles->clear();
  if (integers) integers->clear();
  const uint64_t remaining = text_.size() - pos_;
  if (binary_) {
    restOfLine();  // the block starts on the next line
    const size_t size = valueSize(t);
    if (n > (text_.size() - pos_) / size)
      return fail(what + ": " + std::to_string(n) + " values of " + std::to_string(size) +
                  " bytes cannot fit in the " + std::to_string(text_.size() - pos_) + " bytes left");
    if (doubles) doubles->resize(n);
    else integers->resize(n);
    const uint8_t* p = reinterpret_cast<const uint8_t*>(text_.data()) + pos_;
    for (uint64_t i = 0; i < n; ++i) {
      double d = 0;
      int64_t v = 0;
      loadValue(p + i * size, t, true, &d, &v);
      if (integers) {
        (*integers)[i] = v;
      } else {
        if (!std::isfinite(d)) {
          pos_ += i * size;
          return fail(what + ": value " + std::to_string(i) + " is not finite");
        }
        (*doubles)[i] = d;
      }
    }
    pos_ += n * size;
    return true;
  }
  if (n > (remaining + 1) / 2)
    return fail(what + ": " + std::to_string(n) + " values cannot fit in the " +
                std::to_string(remaining) + " bytes left");
  if (doubles) doubles->reserve(n);
  else integers->reserve(n);
  for (uint64_t i = 0; i < n; ++i) {
    std::string_view tok = token();
    if (tok.empty()) return fail(what + ": the file ends after " + std::to_string(i) + " of " +
                                 std::to_string(n) + " values");
    if (integers) {
      int64_t v = 0;
      if (parseInteger(tok, &v) != NumberProblem::kNone)
        return fail(what + ": '" + std::string(tok) + "' is not a whole number");
      integers->push_back(v);
    } else {
      double v = 0;
      if (NumberProblem p = parseFiniteDouble(tok, &v); p != NumberProblem::kNone)
        return fail(what + ": '" + std::string(tok) + "' " + mesh_io::numberProblemText(p));
      doubles->push_back(v);
    }
  }
  return true;
}

// METADATA blocks (VTK 8 and later) run to the first empty line.
bool LegacyReader::skipMetadata() {
  restOfLine();
  while (pos_ < text_.size()) {
    std::string_view line = restOfLine();
    if (line.find_first_not_of(" \t") == std::string_view::npos) return true;
  }
  return true;
}

// One POINT_DATA / CELL_DATA section of `n` tuples; kept as fields when `keep`.
bool LegacyReader::attributeSection(std::string_view keyword, uint64_t n, bool keep, TetMesh* mesh) {
  const std::string key(keyword);
  std::vector<double> data;
  auto addFields = [&](const std::string& field_name, uint64_t components) {
    if (!keep) return;
    for (uint64_t k = 0; k < components; ++k) {
      ScalarField field;
      field.name = components == 1 ? field_name : field_name + "_" + std::to_string(k);
      field.values.resize(n);
      for (uint64_t v = 0; v < n; ++v) field.values[v] = data[v * components + k];
      mesh->fields.push_back(std::move(field));
    }
  };
  auto numberOfValues = [&](uint64_t components, uint64_t* total) {
    if (components == 0 || components > 1024) return fail(key + ": " + std::to_string(components) + " components (1 to 1024)");
    if (n > text_.size()) return fail(key + ": " + std::to_string(n) + " tuples cannot fit in the file");
    *total = n * components;
    return true;
  };
  ValueType t;
  uint64_t total = 0;
  if (keyword == "SCALARS") {
    std::string field_name(token());
    if (field_name.empty()) return fail("SCALARS has no name");
    if (!type(&t)) return false;
    uint64_t components = 1;
    if (std::string_view c = lineToken(); !c.empty()) {
      int64_t v = 0;
      if (parseInteger(c, &v) != NumberProblem::kNone || v < 1 || v > 4)
        return fail("SCALARS " + field_name + ": component count '" + std::string(c) + "' is not 1 to 4");
      components = static_cast<uint64_t>(v);
    }
    // An optional LOOKUP_TABLE line names the table; the data follow it.
    size_t save_pos = pos_, save_line = line_;
    if (token() == "LOOKUP_TABLE") {
      token();
    } else {
      pos_ = save_pos;
      line_ = save_line;
    }
    if (!numberOfValues(components, &total) || !values("SCALARS " + field_name, t, total, &data, nullptr))
      return false;
    addFields(field_name, components);
    return true;
  }
  if (keyword == "FIELD") {
    token();  // the field data's name
    uint64_t arrays = 0;
    if (!count("FIELD array count", &arrays)) return false;
    if (arrays > text_.size()) return fail("FIELD: " + std::to_string(arrays) + " arrays cannot fit in the file");
    for (uint64_t a = 0; a < arrays; ++a) {
      std::string array_name(token());
      while (array_name == "METADATA") {  // VTK writes one after each array
        skipMetadata();
        array_name = token();
      }
      uint64_t components = 0, tuples = 0;
      if (array_name.empty()) return fail("FIELD: the file ends before array " + std::to_string(a + 1));
      if (!count("FIELD array component count", &components) || !count("FIELD array tuple count", &tuples) ||
          !type(&t))
        return false;
      if (components == 0 || components > 1024 || tuples > text_.size())
        return fail("FIELD " + array_name + ": " + std::to_string(components) + " components of " +
                    std::to_string(tuples) + " tuples cannot fit in the file");
      if (!values("FIELD " + array_name, t, components * tuples, &data, nullptr)) return false;
      if (tuples == n) addFields(array_name, components);
    }
    return true;
  }
  uint64_t components = 0;
  if (keyword == "VECTORS" || keyword == "NORMALS") {
    components = 3;
  } else if (keyword == "TENSORS") {
    components = 9;
  } else if (keyword == "TENSORS6") {
    components = 6;
  } else if (keyword == "GLOBAL_IDS" || keyword == "PEDIGREE_IDS") {
    components = 1;
  } else if (keyword == "TEXTURE_COORDINATES") {
    token();
    if (!count("TEXTURE_COORDINATES dimension", &components)) return false;
    if (!type(&t)) return false;
    if (!numberOfValues(components, &total)) return false;
    return values(key, t, total, &data, nullptr);
  } else if (keyword == "COLOR_SCALARS" || keyword == "LOOKUP_TABLE") {
    token();
    if (!count(keyword == "LOOKUP_TABLE" ? "LOOKUP_TABLE size" : "COLOR_SCALARS value count", &components))
      return false;
    // Colours and tables are floats in ASCII files and bytes in binary ones.
    uint64_t tuples = keyword == "LOOKUP_TABLE" ? components : n;
    if (keyword == "LOOKUP_TABLE") components = 4;
    if (components == 0 || components > 1024 || tuples > text_.size())
      return fail(key + ": too many values for the file");
    return values(key, binary_ ? ValueType::kUInt8 : ValueType::kFloat32, tuples * components, &data,
                  nullptr);
  } else {
    return fail("unknown keyword '" + key + "'");
  }
  token();  // the array's name
  if (!type(&t) || !numberOfValues(components, &total)) return false;
  return values(key, t, total, &data, nullptr);
}

bool LegacyReader::read(TetMesh* mesh, uint64_t* skipped, std::string* error) {
  auto done = [&](bool ok) {
    if (!ok) *error = error_;
    return ok;
  };
  std::string_view line = restOfLine();
  constexpr std::string_view kMagic = "# vtk DataFile Version ";
  if (line.substr(0, kMagic.size()) != kMagic)
    return done(fail("not a legacy VTK file (no '# vtk DataFile Version' line)"));
  const bool version5 = line.size() > kMagic.size() && line[kMagic.size()] >= '5';
  restOfLine();  // the title
  line = restOfLine();
  std::string_view encoding = line.substr(0, line.find_last_not_of(" \t") + 1);
  if (encoding == "BINARY") binary_ = true;
  else if (encoding != "ASCII") return done(fail("the third line must be ASCII or BINARY"));
  std::string_view t = token();
  std::string_view kind = token();
  if (t != "DATASET") return done(fail("DATASET is missing"));
  if (kind != "UNSTRUCTURED_GRID")
    return done(fail("DATASET " + std::string(kind) + " (only UNSTRUCTURED_GRID holds tetrahedra)"));
  header_done_ = true;

  uint64_t n_points = 0;
  bool have_points = false, have_cells = false, have_types = false;
  std::vector<int64_t> offsets, connectivity, cell_types;  // offsets: n_cells + 1 entries
  std::vector<double> data;
  enum class Mode { kNone, kPoint, kCell } mode = Mode::kNone;
  uint64_t mode_count = 0;
  for (std::string_view keyword = token(); !keyword.empty(); keyword = token()) {
    if (keyword == "METADATA") {
      skipMetadata();
    } else if (keyword == "POINTS") {
      if (have_points) return done(fail("a second POINTS section"));
      ValueType pt;
      if (!count("POINTS count", &n_points) || !type(&pt)) return done(false);
      if (n_points > kMaxTetVertices || n_points > text_.size())
        return done(fail("POINTS: " + std::to_string(n_points) + " points cannot fit in the file"));
      if (!values("POINTS", pt, 3 * n_points, &data, nullptr)) return done(false);
      mesh->positions.resize(n_points);
      for (uint64_t v = 0; v < n_points; ++v)
        for (int k = 0; k < 3; ++k) {
          if (std::string why = coordinateProblem(data[v * 3 + k]); !why.empty())
            return done(fail("POINTS: point " + std::to_string(v) + ": a coordinate " + why));
          mesh->positions[v][k] = data[v * 3 + k];
        }
      have_points = true;
    } else if (keyword == "CELLS") {
      if (have_cells) return done(fail("a second CELLS section"));
      uint64_t a = 0, b = 0;
      if (!count("CELLS count", &a) || !count("CELLS size", &b)) return done(false);
      if (version5) {
        // CELLS <offset count> <connectivity size>, then the two arrays.
        ValueType ot;
        if (token() != "OFFSETS") return done(fail("CELLS (version 5): OFFSETS is missing"));
        if (!type(&ot) || !values("OFFSETS", ot, a, nullptr, &offsets)) return done(false);
        if (token() != "CONNECTIVITY") return done(fail("CELLS (version 5): CONNECTIVITY is missing"));
        if (!type(&ot) || !values("CONNECTIVITY", ot, b, nullptr, &connectivity)) return done(false);
        if (offsets.empty() || offsets[0] != 0)
          return done(fail("OFFSETS must start with 0"));
      } else {
        // CELLS <cell count> <list size>: per cell its vertex count, then the indices.
        std::vector<int64_t> list;
        if (!values("CELLS", ValueType::kInt32, b, nullptr, &list)) return done(false);
        if (a > b) return done(fail("CELLS: " + std::to_string(a) + " cells cannot fit in a list of " + std::to_string(b)));
        offsets.reserve(a + 1);
        connectivity.reserve(b - a);
        offsets.push_back(0);
        size_t i = 0;
        for (uint64_t c = 0; c < a; ++c) {
          if (i >= list.size() || list[i] < 0 || static_cast<uint64_t>(list[i]) > list.size() - i - 1)
            return done(fail("CELLS: cell " + std::to_string(c) + " runs past the end of the list"));
          int64_t k = list[i++];
          connectivity.insert(connectivity.end(), list.begin() + static_cast<long>(i),
                              list.begin() + static_cast<long>(i + static_cast<size_t>(k)));
          i += static_cast<size_t>(k);
          offsets.push_back(static_cast<int64_t>(connectivity.size()));
        }
        if (i != list.size())
          return done(fail("CELLS: the list holds " + std::to_string(list.size() - i) +
                           " values after the last cell"));
      }
      have_cells = true;
    } else if (keyword == "CELL_TYPES") {
      uint64_t n = 0;
      if (!count("CELL_TYPES count", &n)) return done(false);
      if (!values("CELL_TYPES", ValueType::kInt32, n, nullptr, &cell_types)) return done(false);
      have_types = true;
    } else if (keyword == "POINT_DATA" || keyword == "CELL_DATA") {
      if (!count(keyword == "POINT_DATA" ? "POINT_DATA count" : "CELL_DATA count", &mode_count))
        return done(false);
      mode = keyword == "POINT_DATA" ? Mode::kPoint : Mode::kCell;
      if (mode == Mode::kPoint && mode_count != n_points)
        return done(fail("POINT_DATA " + std::to_string(mode_count) + " for " + std::to_string(n_points) + " points"));
    } else if (keyword == "FIELD" && mode == Mode::kNone) {
      // Field data of the whole data set (TIME, CYCLE, ...): read past.
      if (!attributeSection(keyword, UINT64_MAX, false, mesh)) return done(false);
    } else {
      if (mode == Mode::kNone)
        return done(fail("'" + std::string(keyword) + "' outside POINT_DATA or CELL_DATA, or unknown"));
      if (!attributeSection(keyword, mode_count, mode == Mode::kPoint, mesh)) return done(false);
    }
  }
  if (!have_points) return done(fail("no POINTS section"));
  if (have_cells != have_types) return done(fail("CELLS and CELL_TYPES go together"));
  const uint64_t n_cells = offsets.empty() ? 0 : offsets.size() - 1;
  if (have_cells && cell_types.size() != n_cells)
    return done(fail("CELL_TYPES gives " + std::to_string(cell_types.size()) + " types for " +
                     std::to_string(n_cells) + " cells"));
  uint64_t tets = 0;
  for (uint64_t c = 0; c < n_cells; ++c) {
    int64_t begin = offsets[c], end = offsets[c + 1];
    if (begin < 0 || end < begin || static_cast<uint64_t>(end) > connectivity.size())
      return done(fail("cell " + std::to_string(c) + ": offsets " + std::to_string(begin) + ".." +
                       std::to_string(end) + " outside the connectivity of " +
                       std::to_string(connectivity.size())));
    VtkCellKind cell_kind = vtkCellKind(cell_types[c]);
    if (cell_kind == VtkCellKind::kOther3d)
      return done(fail("cell " + std::to_string(c) + " is a " + vtkCellTypeName(cell_types[c]) +
                       " (only tetrahedra, VTK type 10, are read)"));
    if (cell_kind == VtkCellKind::kTetra) {
      if (end - begin != 4)
        return done(fail("cell " + std::to_string(c) + " is a tetrahedron with " +
                         std::to_string(end - begin) + " vertices"));
      ++tets;
    }
  }
  mesh->tets.reserve(tets);
  for (uint64_t c = 0; c < n_cells; ++c) {
    if (vtkCellKind(cell_types[c]) != VtkCellKind::kTetra) {
      ++*skipped;
      continue;
    }
    std::array<uint32_t, 4> tet;
    for (int k = 0; k < 4; ++k) {
      int64_t v = connectivity[static_cast<size_t>(offsets[c] + k)];
      if (v < 0 || static_cast<uint64_t>(v) >= n_points)
        return done(fail("cell " + std::to_string(c) + " has vertex index " + std::to_string(v) +
                         " out of range (" + std::to_string(n_points) + " points)"));
      tet[k] = static_cast<uint32_t>(v);
    }
    mesh->tets.push_back(tet);
  }
  return true;
}

void putBigEndian(uint64_t bits, size_t bytes, std::string* out) {
  for (size_t i = 0; i < bytes; ++i) out->push_back(static_cast<char>(bits >> (8 * (bytes - 1 - i))));
}

void appendDouble(double value, bool ascii, std::string* out) {
  if (ascii) {
    mesh_io::appendShortestDouble(value, out);
  } else {
    uint64_t bits;
    std::memcpy(&bits, &value, 8);
    putBigEndian(bits, 8, out);
  }
}

void appendInt32(uint32_t value, bool ascii, std::string* out) {
  if (ascii) mesh_io::appendUnsigned(value, out);
  else putBigEndian(value, 4, out);
}

}  // namespace

bool readVtkLegacy(const std::string& name, const uint8_t* data, size_t size, TetMesh* mesh,
                   uint64_t* skipped_cells, std::string* error) {
  *skipped_cells = 0;
  LegacyReader reader(name, data, size);
  return reader.read(mesh, skipped_cells, error);
}

void encodeVtkLegacy(const TetMesh& mesh, bool ascii, std::vector<uint8_t>* out) {
  const size_t n = mesh.positions.size(), m = mesh.tets.size();
  std::string text = "# vtk DataFile Version 3.0\nwritten by mrsv\n";
  text += ascii ? "ASCII\n" : "BINARY\n";
  text.reserve(n * (ascii ? 60 : 24) + m * (ascii ? 40 : 24) + n * mesh.fields.size() * 24 + 256);
  text += "DATASET UNSTRUCTURED_GRID\nPOINTS " + std::to_string(n) + " double\n";
  // ASCII: a separator after every value (a space, a newline per tuple).
  auto separator = [&](bool end_of_tuple) {
    if (ascii) text += end_of_tuple ? '\n' : ' ';
  };
  for (const auto& p : mesh.positions)
    for (int k = 0; k < 3; ++k) {
      appendDouble(p[k], ascii, &text);
      separator(k == 2);
    }
  if (!ascii) text += '\n';
  text += "CELLS " + std::to_string(m) + " " + std::to_string(5 * m) + "\n";
  for (const auto& t : mesh.tets) {
    appendInt32(4, ascii, &text);
    separator(false);
    for (int k = 0; k < 4; ++k) {
      appendInt32(t[k], ascii, &text);
      separator(k == 3);
    }
  }
  if (!ascii) text += '\n';
  text += "CELL_TYPES " + std::to_string(m) + "\n";
  for (size_t t = 0; t < m; ++t) {
    appendInt32(10, ascii, &text);
    separator(true);
  }
  if (!ascii) text += '\n';
  // The first field as SCALARS (a reader's active scalars), the others in a
  // FIELD block: VTK's reader takes only the first SCALARS unless told to
  // read them all, but every array of a FIELD.
  if (!mesh.fields.empty()) {
    text += "POINT_DATA " + std::to_string(n) + "\n";
    for (size_t f = 0; f < mesh.fields.size(); ++f) {
      const ScalarField& field = mesh.fields[f];
      if (f == 0) {
        text += "SCALARS " + field.name + " double 1\nLOOKUP_TABLE default\n";
      } else {
        if (f == 1) text += "FIELD FieldData " + std::to_string(mesh.fields.size() - 1) + "\n";
        text += field.name + " 1 " + std::to_string(n) + " double\n";
      }
      for (double v : field.values) {
        appendDouble(v, ascii, &text);
        separator(true);
      }
      if (!ascii) text += '\n';
    }
  }
  out->assign(text.begin(), text.end());
}

}  // namespace mrsv::tet_io
