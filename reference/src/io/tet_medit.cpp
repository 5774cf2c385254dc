// MEDIT ASCII meshes (.mesh, INRIA's format as written by TetGen, CGAL,
// libigl, gmsh, mmg): keyword sections, each a count and that many entries of
// numbers. Only Vertices and Tetrahedra are kept; every other section known to
// MEDIT is read past by its entry size. White space, newlines included, only
// separates tokens; '#' starts a comment to the end of the line.
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

// The next token, past white space and comments; empty at the end.
std::string_view nextToken(TextScanner* scanner) {
  for (;;) {
    std::string_view token = scanner->token();
    if (token.empty() || token[0] != '#') return token;
    scanner->nextLine();
  }
}

// Numbers per entry of the sections read past (3-D meshes). Cells of other
// kinds than tetrahedra with a non-zero count are refused elsewhere.
struct Section {
  const char* keyword;
  int numbers;
  bool other_3d_cell;
};
const Section kSections[] = {
    {"Edges", 3, false},          {"Triangles", 4, false},      {"Quadrilaterals", 5, false},
    {"Hexahedra", 9, true},       {"Prisms", 7, true},          {"Pyramids", 6, true},
    {"Corners", 1, false},        {"RequiredVertices", 1, false}, {"Ridges", 1, false},
    {"RequiredEdges", 1, false},  {"RequiredTriangles", 1, false},
    {"RequiredQuadrilaterals", 1, false}, {"RequiredTetrahedra", 1, false},
    {"Normals", 3, false},        {"Tangents", 3, false},       {"NormalAtVertices", 2, false},
    {"TangentAtVertices", 2, false}, {"TangentAtEdges", 3, false},
    {"NormalAtTriangleVertices", 3, false}, {"NormalAtQuadrilateralVertices", 3, false},
    {"EdgesP2", 4, false},        {"TrianglesP2", 7, false},    {"TetrahedraP2", 11, true},
    {"QuadrilateralsQ2", 10, false}, {"HexahedraQ2", 28, true},
};

}  // namespace

bool readMedit(const std::string& name, const uint8_t* data, size_t size, TetMesh* mesh,
               std::string* error) {
  TextScanner scanner(data, size);
  auto fail = [&](const std::string& problem) {
    *error = name + ":" + std::to_string(scanner.line()) + ": " + problem;
    return false;
  };
  // A count, checked against the bytes left: an entry of k numbers takes at
  // least 2k bytes (each number a digit and a separator; the last may lack it).
  auto readCount = [&](std::string_view keyword, int numbers, uint64_t* count) {
    std::string_view token = nextToken(&scanner);
    int64_t value = 0;
    if (NumberProblem p = parseInteger(token, &value); p != NumberProblem::kNone)
      return fail(std::string(keyword) + ": count '" + std::string(token) + "' " +
                  (token.empty() ? "is missing" : numberProblemText(p)));
    if (value < 0) return fail(std::string(keyword) + ": count is negative");
    const uint64_t remaining = size - scanner.position();
    if (static_cast<uint64_t>(value) > (remaining + 1) / (2 * static_cast<uint64_t>(numbers)))
      return fail(std::string(keyword) + ": " + std::to_string(value) +
                  " entries cannot fit in the " + std::to_string(remaining) + " bytes that follow");
    *count = static_cast<uint64_t>(value);
    return true;
  };

  std::string_view token = nextToken(&scanner);
  if (token != "MeshVersionFormatted")
    return fail("not a MEDIT mesh (it must start with MeshVersionFormatted)");
  token = nextToken(&scanner);
  int64_t version = 0;
  if (parseInteger(token, &version) != NumberProblem::kNone || version < 1 || version > 4)
    return fail("MeshVersionFormatted '" + std::string(token) + "' is not 1, 2, 3 or 4");

  bool have_dimension = false, have_vertices = false, have_tets = false;
  size_t tet_section_line = 0;
  for (;;) {
    token = nextToken(&scanner);
    if (token.empty() || token == "End") break;
    if (token == "Dimension") {
      token = nextToken(&scanner);
      int64_t dimension = 0;
      if (parseInteger(token, &dimension) != NumberProblem::kNone || dimension != 3)
        return fail("Dimension '" + std::string(token) + "': only 3-D meshes hold tetrahedra");
      have_dimension = true;
    } else if (token == "Vertices") {
      if (!have_dimension) return fail("Vertices before Dimension 3");
      if (have_vertices) return fail("a second Vertices section");
      have_vertices = true;
      uint64_t count = 0;
      if (!readCount("Vertices", 4, &count)) return false;
      if (count > kMaxTetVertices) return fail("Vertices: more than 2^32-1 vertices");
      mesh->positions.resize(count);
      for (uint64_t v = 0; v < count; ++v) {
        for (int k = 0; k < 4; ++k) {
          token = nextToken(&scanner);
          if (token.empty())
            return fail("Vertices: the file ends in vertex " + std::to_string(v + 1) + " of " +
                        std::to_string(count));
          if (k < 3) {
            double c = 0;
            if (NumberProblem p = parseFiniteDouble(token, &c); p != NumberProblem::kNone)
              return fail("vertex " + std::to_string(v + 1) + ": coordinate '" +
                          std::string(token) + "' " + numberProblemText(p));
            if (std::string problem = coordinateProblem(c); !problem.empty())
              return fail("vertex " + std::to_string(v + 1) + ": coordinate " +
                          std::string(token) + " " + problem);
            mesh->positions[v][k] = c;
          } else {
            int64_t reference = 0;
            if (parseInteger(token, &reference) != NumberProblem::kNone)
              return fail("vertex " + std::to_string(v + 1) + ": reference '" +
                          std::string(token) + "' is not an integer");
          }
        }
      }
    } else if (token == "Tetrahedra") {
      if (have_tets) return fail("a second Tetrahedra section");
      have_tets = true;
      tet_section_line = scanner.line();
      uint64_t count = 0;
      if (!readCount("Tetrahedra", 5, &count)) return false;
      mesh->tets.resize(count);
      for (uint64_t t = 0; t < count; ++t) {
        for (int k = 0; k < 5; ++k) {
          token = nextToken(&scanner);
          if (token.empty())
            return fail("Tetrahedra: the file ends in tet " + std::to_string(t + 1) + " of " +
                        std::to_string(count));
          int64_t index = 0;
          if (NumberProblem p = parseInteger(token, &index); p != NumberProblem::kNone)
            return fail("tet " + std::to_string(t + 1) + ": '" + std::string(token) + "' " +
                        numberProblemText(p));
          if (k == 4) break;  // the reference number
          // Checked now when the vertices came first (the usual order), else below.
          const uint64_t limit = have_vertices ? mesh->positions.size() : kMaxTetVertices;
          if (index < 1 || static_cast<uint64_t>(index) > limit)
            return fail("tet " + std::to_string(t + 1) + ": vertex index " + std::to_string(index) +
                        " is out of range (1-based, " +
                        (have_vertices ? std::to_string(limit) + " vertices)" : "2^32-1 at most)"));
          mesh->tets[t][k] = static_cast<uint32_t>(index - 1);
        }
      }
    } else {
      const Section* section = nullptr;
      for (const Section& s : kSections)
        if (token == s.keyword) section = &s;
      if (!section)
        return fail("unknown section '" + std::string(token) +
                    "' (its entry size is unknown, so it cannot be read past)");
      uint64_t count = 0;
      if (!readCount(section->keyword, section->numbers, &count)) return false;
      if (section->other_3d_cell && count > 0)
        return fail(std::string(section->keyword) + ": " + std::to_string(count) +
                    " cells that are not tetrahedra (only tetrahedral meshes are read)");
      for (uint64_t e = 0; e < count * static_cast<uint64_t>(section->numbers); ++e) {
        token = nextToken(&scanner);
        double value = 0;
        if (token.empty())
          return fail(std::string(section->keyword) + ": the file ends in entry " +
                      std::to_string(e / section->numbers + 1) + " of " + std::to_string(count));
        if (parseFiniteDouble(token, &value) != NumberProblem::kNone)
          return fail(std::string(section->keyword) + ": '" + std::string(token) +
                      "' is not a number");
      }
    }
  }
  if (!have_vertices) return fail("no Vertices section");
  for (size_t t = 0; t < mesh->tets.size(); ++t)
    for (uint32_t v : mesh->tets[t])
      if (v >= mesh->positions.size()) {
        *error = name + ":" + std::to_string(tet_section_line) + ": tet " + std::to_string(t + 1) +
                 ": vertex index " + std::to_string(uint64_t{v} + 1) + " is out of range (1-based, " +
                 std::to_string(mesh->positions.size()) + " vertices)";
        return false;
      }
  return true;
}

void encodeMedit(const TetMesh& mesh, std::vector<uint8_t>* out) {
  std::string text = "MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n";
  text.reserve(mesh.positions.size() * 64 + mesh.tets.size() * 40 + 64);
  mesh_io::appendUnsigned(mesh.positions.size(), &text);
  text += '\n';
  for (const auto& p : mesh.positions) {
    for (double c : p) {
      mesh_io::appendShortestDouble(c, &text);
      text += ' ';
    }
    text += "0\n";
  }
  text += "\nTetrahedra\n";
  mesh_io::appendUnsigned(mesh.tets.size(), &text);
  text += '\n';
  for (const auto& t : mesh.tets) {
    for (uint32_t v : t) {
      mesh_io::appendUnsigned(uint64_t{v} + 1, &text);
      text += ' ';
    }
    text += "1\n";
  }
  text += "\nEnd\n";
  out->assign(text.begin(), text.end());
}

}  // namespace mrsv::tet_io
