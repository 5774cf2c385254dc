// Object File Format (OFF): a keyword line, the counts, one vertex per line,
// one polygon per line. The ST/C/N variants (texture coordinates, colours,
// normals) add columns after the ones read here, and are accepted by reading
// past them; the 4OFF/nOFF variants (other dimensions) and binary OFF are not.
#include <string_view>

#include "io/mesh_format_codecs.h"
#include "io/mesh_text_scanner.h"

namespace mrsv::mesh_io {
namespace {

// "OFF" with an optional "ST", "C", "N" prefix in that order (e.g. "STCNOFF").
bool isOffKeyword(std::string_view keyword) {
  if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF") return false;
  std::string_view prefix = keyword.substr(0, keyword.size() - 3);
  for (std::string_view part : {"ST", "C", "N"})
    if (prefix.substr(0, part.size()) == part) prefix.remove_prefix(part.size());
  return prefix.empty();
}

// Moves past blank and comment-only lines.
void skipEmptyLines(TextScanner* scanner) {
  while (!scanner->atEnd() && scanner->atLineEnd('#')) scanner->nextLine();
}

}  // namespace

bool readOff(const std::string& name, const uint8_t* data, size_t size, TriangleMesh* mesh,
             std::string* error) {
  TextScanner scanner(data, size);
  auto fail = [&](const std::string& problem) {
    *error = name + ":" + std::to_string(scanner.line()) + ": " + problem;
    return false;
  };
  skipEmptyLines(&scanner);
  std::string_view keyword = scanner.lineToken('#');
  if (!isOffKeyword(keyword)) {
    if (keyword.size() > 3 && keyword.substr(keyword.size() - 3) == "OFF")
      return fail("header: '" + std::string(keyword) +
                  "' is not supported (only 3-D OFF, COFF, NOFF, STOFF and their combinations)");
    return fail("header: not an OFF file (the first line must be OFF, COFF, NOFF, ...)");
  }
  if (scanner.atLineEnd('#')) {
    scanner.nextLine();
    skipEmptyLines(&scanner);
  }
  int64_t counts[3] = {0, 0, 0};
  const char* count_names[3] = {"vertex count", "face count", "edge count"};
  for (int k = 0; k < 3; ++k) {
    std::string_view token = scanner.lineToken('#');
    if (token.empty() && k == 2) break;  // the edge count is often left out
    if (token == "BINARY") return fail("header: binary OFF is not supported");
    if (NumberProblem p = parseInteger(token, &counts[k]); p != NumberProblem::kNone)
      return fail(std::string("header: ") + count_names[k] + " '" + std::string(token) + "' " +
                  (token.empty() ? "is missing" : numberProblemText(p)));
    if (counts[k] < 0) return fail(std::string("header: ") + count_names[k] + " is negative");
  }
  scanner.nextLine();
  const uint64_t vertex_count = static_cast<uint64_t>(counts[0]);
  const uint64_t face_count = static_cast<uint64_t>(counts[1]);
  // The shortest vertex line is "0 0 0\n" (6 bytes), the shortest face line
  // (even if wrong) "0\n"; the last line may lack its newline. Checked before
  // any allocation so that a tiny file cannot ask for gigabytes.
  const uint64_t remaining = size - scanner.position();
  if (vertex_count > kMaxMeshVertices || vertex_count > (remaining + 1) / 6 ||
      face_count > (remaining + 1) / 2 || vertex_count * 6 + face_count * 2 > remaining + 1)
    return fail("header: " + std::to_string(vertex_count) + " vertices and " +
                std::to_string(face_count) + " faces cannot fit in the " + std::to_string(remaining) +
                " bytes that follow");
  mesh->positions.reserve(vertex_count);
  mesh->triangles.reserve(face_count);

  for (uint64_t v = 0; v < vertex_count; ++v) {
    skipEmptyLines(&scanner);
    if (scanner.atEnd())
      return fail("vertex " + std::to_string(v) + ": file ends after " + std::to_string(v) +
                  " of " + std::to_string(vertex_count) + " vertices");
    std::array<double, 3> p;
    for (size_t c = 0; c < 3; ++c) {
      std::string_view token = scanner.lineToken('#');
      if (token.empty())
        return fail("vertex " + std::to_string(v) + ": fewer than 3 coordinates");
      if (NumberProblem problem = parseFiniteDouble(token, &p[c]); problem != NumberProblem::kNone)
        return fail("vertex " + std::to_string(v) + ": coordinate '" + std::string(token) + "' " +
                    numberProblemText(problem));
    }
    mesh->positions.push_back(p);
    scanner.nextLine();  // colour, normal and texture columns
  }

  std::vector<uint32_t> corners;
  for (uint64_t f = 0; f < face_count; ++f) {
    skipEmptyLines(&scanner);
    if (scanner.atEnd())
      return fail("face " + std::to_string(f) + ": file ends after " + std::to_string(f) + " of " +
                  std::to_string(face_count) + " faces");
    std::string_view token = scanner.lineToken('#');
    int64_t corner_count = 0;
    if (NumberProblem p = parseInteger(token, &corner_count); p != NumberProblem::kNone)
      return fail("face " + std::to_string(f) + ": vertex count '" + std::string(token) + "' " +
                  numberProblemText(p));
    if (corner_count < 3)
      return fail("face " + std::to_string(f) + ": " + std::to_string(corner_count) +
                  " vertices (a face needs at least 3)");
    corners.clear();
    for (int64_t k = 0; k < corner_count; ++k) {
      token = scanner.lineToken('#');
      int64_t index = 0;
      if (token.empty())
        return fail("face " + std::to_string(f) + ": line ends after " + std::to_string(k) +
                    " of " + std::to_string(corner_count) + " vertex indices");
      if (NumberProblem p = parseInteger(token, &index); p != NumberProblem::kNone)
        return fail("face " + std::to_string(f) + ": vertex index '" + std::string(token) + "' " +
                    numberProblemText(p));
      if (index < 0 || static_cast<uint64_t>(index) >= vertex_count)
        return fail("face " + std::to_string(f) + ": vertex index " + std::to_string(index) +
                    " is out of range (" + std::to_string(vertex_count) + " vertices)");
      corners.push_back(static_cast<uint32_t>(index));
    }
    for (size_t k = 1; k + 1 < corners.size(); ++k)
      mesh->triangles.push_back({corners[0], corners[k], corners[k + 1]});
    scanner.nextLine();  // an optional face colour
  }
  skipEmptyLines(&scanner);
  if (!scanner.atEnd())
    return fail("unexpected text after the last of the " + std::to_string(face_count) + " faces");
  return true;
}

void encodeOff(const TriangleMesh& mesh, std::vector<uint8_t>* out) {
  std::string text = "OFF\n";
  text.reserve(mesh.positions.size() * 64 + mesh.triangles.size() * 26 + 64);
  appendUnsigned(mesh.positions.size(), &text);
  text += ' ';
  appendUnsigned(mesh.triangles.size(), &text);
  text += " 0\n";
  for (const auto& p : mesh.positions) {
    for (size_t c = 0; c < 3; ++c) {
      if (c) text += ' ';
      appendShortestDouble(p[c], &text);
    }
    text += '\n';
  }
  for (const auto& t : mesh.triangles) {
    text += '3';
    for (uint32_t v : t) {
      text += ' ';
      appendUnsigned(v, &text);
    }
    text += '\n';
  }
  out->assign(text.begin(), text.end());
}

}  // namespace mrsv::mesh_io
