// TetGen's .node and .ele files: line-based text, '#' comments, a header line
// of counts, one numbered point or tet per line. The first point's number (0
// or 1) sets the base of every index in both files.
#include <string_view>

#include "io/mesh_format_codecs.h"
#include "io/mesh_text_scanner.h"
#include "io/tet_format_codecs.h"

namespace mrsv::tet_io {
namespace {

using mesh_io::NumberProblem;
using mesh_io::numberProblemText;
using mesh_io::parseFiniteDouble;
using mesh_io::parseInteger;
using mesh_io::TextScanner;

void skipEmptyLines(TextScanner* scanner) {
  while (!scanner->atEnd() && scanner->atLineEnd('#')) scanner->nextLine();
}

// "# fields: a b c" as written by encodeTetgenNode, or empty.
std::vector<std::string> fieldNamesComment(const uint8_t* data, size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> names;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    size_t first = line.find_first_not_of(" \t\r");
    if (first != std::string_view::npos && line[first] != '#') break;  // the header line
    constexpr std::string_view kTag = "# fields:";
    if (first != std::string_view::npos && line.substr(first, kTag.size()) == kTag) {
      TextScanner words(reinterpret_cast<const uint8_t*>(line.data() + first + kTag.size()),
                        line.size() - first - kTag.size());
      for (std::string_view w = words.lineToken(); !w.empty(); w = words.lineToken())
        names.emplace_back(w);
      return names;
    }
    pos = end + 1;
  }
  return names;
}

// Reads `count` whole numbers of a header line into `out`; the rest of the line
// may hold fewer (missing ones are 0) when `optional_from` allows.
bool headerNumbers(TextScanner* scanner, const char* const* names, int count, int required,
                   int64_t* out, std::string* problem) {
  for (int k = 0; k < count; ++k) {
    std::string_view token = scanner->lineToken('#');
    out[k] = 0;
    if (token.empty() && k >= required) continue;
    if (NumberProblem p = parseInteger(token, &out[k]); p != NumberProblem::kNone) {
      *problem = std::string("header: ") + names[k] + " '" + std::string(token) + "' " +
                 (token.empty() ? "is missing" : numberProblemText(p));
      return false;
    }
    if (out[k] < 0) {
      *problem = std::string("header: ") + names[k] + " is negative";
      return false;
    }
  }
  scanner->nextLine();
  return true;
}

}  // namespace

bool readTetgen(const std::string& node_name, const uint8_t* node, size_t node_size,
                const std::string& ele_name, const uint8_t* ele, size_t ele_size, TetMesh* mesh,
                std::string* error) {
  // ---- .node
  TextScanner scanner(node, node_size);
  const std::string* name = &node_name;
  auto fail = [&](const std::string& problem) {
    *error = *name + ":" + std::to_string(scanner.line()) + ": " + problem;
    return false;
  };
  skipEmptyLines(&scanner);
  static const char* const kNodeHeader[] = {"point count", "dimension", "attribute count",
                                            "boundary marker flag"};
  int64_t header[4];
  std::string problem;
  if (!headerNumbers(&scanner, kNodeHeader, 4, 1, header, &problem)) return fail(problem);
  if (header[1] != 3)
    return fail("header: dimension " + std::to_string(header[1]) + " (tet meshes are 3-D)");
  const uint64_t points = static_cast<uint64_t>(header[0]);
  const uint64_t attributes = static_cast<uint64_t>(header[2]);
  const bool markers = header[3] != 0;
  const uint64_t columns = 4 + attributes + (markers ? 1 : 0);
  // Each point line is at least 2 bytes per column (the last may lack the newline).
  uint64_t remaining = node_size - scanner.position();
  if (attributes > remaining || points > kMaxTetVertices ||
      points > (remaining + 1) / (2 * columns))
    return fail("header: " + std::to_string(points) + " points of " + std::to_string(columns) +
                " columns cannot fit in the " + std::to_string(remaining) + " bytes that follow");
  std::vector<std::string> names = fieldNamesComment(node, node_size);
  if (names.size() != attributes) {
    names.clear();
    for (uint64_t a = 0; a < attributes; ++a) names.push_back("attribute" + std::to_string(a + 1));
  }
  mesh->positions.resize(points);
  mesh->fields.resize(attributes);
  for (uint64_t a = 0; a < attributes; ++a) {
    mesh->fields[a].name = names[a];
    mesh->fields[a].values.resize(points);
  }
  int64_t base = 0;
  for (uint64_t v = 0; v < points; ++v) {
    skipEmptyLines(&scanner);
    if (scanner.atEnd())
      return fail("the file ends after " + std::to_string(v) + " of " + std::to_string(points) +
                  " points");
    std::string_view token = scanner.lineToken('#');
    int64_t number = 0;
    if (NumberProblem p = parseInteger(token, &number); p != NumberProblem::kNone)
      return fail("point number '" + std::string(token) + "' " + numberProblemText(p));
    if (v == 0) {
      if (number != 0 && number != 1)
        return fail("the first point is numbered " + std::to_string(number) +
                    " (TetGen numbers points from 0 or 1)");
      base = number;
    } else if (number != base + static_cast<int64_t>(v)) {
      return fail("point number " + std::to_string(number) + " where " +
                  std::to_string(base + static_cast<int64_t>(v)) +
                  " was due (points are numbered consecutively)");
    }
    for (uint64_t k = 0; k < 3 + attributes; ++k) {
      token = scanner.lineToken('#');
      double value = 0;
      if (NumberProblem p = parseFiniteDouble(token, &value); p != NumberProblem::kNone)
        return fail("point " + std::to_string(number) + ": " +
                    (k < 3 ? "coordinate" : "attribute") + " '" + std::string(token) + "' " +
                    (token.empty() ? "is missing" : numberProblemText(p)));
      if (k < 3) {
        if (std::string why = coordinateProblem(value); !why.empty())
          return fail("point " + std::to_string(number) + ": coordinate " + std::string(token) +
                      " " + why);
        mesh->positions[v][k] = value;
      } else {
        mesh->fields[k - 3].values[v] = value;
      }
    }
    scanner.nextLine();  // the boundary marker, if any, is not used
  }

  // ---- .ele
  scanner = TextScanner(ele, ele_size);
  name = &ele_name;
  skipEmptyLines(&scanner);
  static const char* const kEleHeader[] = {"tet count", "nodes per tet", "region attribute count"};
  if (!headerNumbers(&scanner, kEleHeader, 3, 2, header, &problem)) return fail(problem);
  if (header[1] != 4)
    return fail("header: " + std::to_string(header[1]) +
                " nodes per tet (only linear, 4-node tets are read)");
  const uint64_t tets = static_cast<uint64_t>(header[0]);
  const uint64_t ele_columns = 5 + static_cast<uint64_t>(header[2]);
  remaining = ele_size - scanner.position();
  if (static_cast<uint64_t>(header[2]) > remaining || tets > (remaining + 1) / (2 * ele_columns))
    return fail("header: " + std::to_string(tets) + " tets of " + std::to_string(ele_columns) +
                " columns cannot fit in the " + std::to_string(remaining) + " bytes that follow");
  mesh->tets.resize(tets);
  for (uint64_t t = 0; t < tets; ++t) {
    skipEmptyLines(&scanner);
    if (scanner.atEnd())
      return fail("the file ends after " + std::to_string(t) + " of " + std::to_string(tets) +
                  " tets");
    std::string_view token = scanner.lineToken('#');
    int64_t number = 0;
    if (NumberProblem p = parseInteger(token, &number); p != NumberProblem::kNone)
      return fail("tet number '" + std::string(token) + "' " + numberProblemText(p));
    for (int k = 0; k < 4; ++k) {
      token = scanner.lineToken('#');
      int64_t index = 0;
      if (NumberProblem p = parseInteger(token, &index); p != NumberProblem::kNone)
        return fail("tet " + std::to_string(number) + ": vertex '" + std::string(token) + "' " +
                    (token.empty() ? "is missing" : numberProblemText(p)));
      if (index < base || static_cast<uint64_t>(index - base) >= points)
        return fail("tet " + std::to_string(number) + ": vertex index " + std::to_string(index) +
                    " is out of range (" + std::to_string(points) + " points numbered from " +
                    std::to_string(base) + " in the .node file)");
      mesh->tets[t][k] = static_cast<uint32_t>(index - base);
    }
    scanner.nextLine();  // region attributes are not used
  }
  return true;
}

void encodeTetgenNode(const TetMesh& mesh, std::vector<uint8_t>* out) {
  std::string text = "# written by mrsv\n";
  if (!mesh.fields.empty()) {
    text += "# fields:";
    for (const ScalarField& f : mesh.fields) text += " " + f.name;
    text += '\n';
  }
  text.reserve(mesh.positions.size() * (64 + 24 * mesh.fields.size()) + 64);
  mesh_io::appendUnsigned(mesh.positions.size(), &text);
  text += " 3 ";
  mesh_io::appendUnsigned(mesh.fields.size(), &text);
  text += " 0\n";
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    mesh_io::appendUnsigned(v, &text);
    for (double c : mesh.positions[v]) {
      text += ' ';
      mesh_io::appendShortestDouble(c, &text);
    }
    for (const ScalarField& f : mesh.fields) {
      text += ' ';
      mesh_io::appendShortestDouble(f.values[v], &text);
    }
    text += '\n';
  }
  out->assign(text.begin(), text.end());
}

void encodeTetgenEle(const TetMesh& mesh, std::vector<uint8_t>* out) {
  std::string text = "# written by mrsv\n";
  text.reserve(mesh.tets.size() * 48 + 64);
  mesh_io::appendUnsigned(mesh.tets.size(), &text);
  text += " 4 0\n";
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    mesh_io::appendUnsigned(t, &text);
    for (uint32_t v : mesh.tets[t]) {
      text += ' ';
      mesh_io::appendUnsigned(v, &text);
    }
    text += '\n';
  }
  out->assign(text.begin(), text.end());
}

}  // namespace mrsv::tet_io
