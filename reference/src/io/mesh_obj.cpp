// Wavefront OBJ: the `v` and `f` statements; every other statement (vt, vn,
// g, o, s, usemtl, mtllib, l, p, ...) is read past, since a TriangleMesh has
// nowhere to keep it.
#include <string_view>

#include "io/mesh_format_codecs.h"
#include "io/mesh_text_scanner.h"

namespace mrsv::mesh_io {

bool readObj(const std::string& name, const uint8_t* data, size_t size, TriangleMesh* mesh,
             std::string* error) {
  TextScanner scanner(data, size);
  auto fail = [&](const std::string& problem) {
    *error = name + ":" + std::to_string(scanner.line()) + ": " + problem;
    return false;
  };
  std::vector<uint32_t> corners;
  while (!scanner.atEnd()) {
    std::string_view keyword = scanner.lineToken('#');
    if (keyword == "v") {
      double values[7];
      int count = 0;
      for (std::string_view token = scanner.lineToken('#'); !token.empty();
           token = scanner.lineToken('#')) {
        if (count == 7) return fail("v: more than 7 numbers (expects x y z [w] or x y z r g b [a])");
        if (NumberProblem p = parseFiniteDouble(token, &values[count]); p != NumberProblem::kNone)
          return fail("v: coordinate '" + std::string(token) + "' " + numberProblemText(p));
        ++count;
      }
      // x y z, x y z w, and the common colour extension x y z r g b [a].
      if (count < 3 || count == 5)
        return fail("v: " + std::to_string(count) + " numbers (expects x y z [w] or x y z r g b [a])");
      if (mesh->positions.size() >= kMaxMeshVertices) return fail("v: more than 2^32-1 vertices");
      mesh->positions.push_back({values[0], values[1], values[2]});
    } else if (keyword == "f") {
      corners.clear();
      const int64_t defined = static_cast<int64_t>(mesh->positions.size());
      for (std::string_view token = scanner.lineToken('#'); !token.empty();
           token = scanner.lineToken('#')) {
        // a, a/b, a//c, a/b/c: only the vertex index a matters here.
        std::string_view vertex = token.substr(0, token.find('/'));
        int64_t index = 0;
        if (NumberProblem p = parseInteger(vertex, &index); p != NumberProblem::kNone)
          return fail("f: vertex index '" + std::string(token) + "' " + numberProblemText(p));
        // Positive indices count from 1; negative ones count back from the
        // last vertex defined so far (-1 is that vertex).
        int64_t resolved = index > 0 ? index - 1 : defined + index;
        if (index == 0 || resolved < 0 || resolved >= defined)
          return fail("f: vertex index " + std::to_string(index) + " is out of range (" +
                      std::to_string(defined) + " vertices defined so far)");
        corners.push_back(static_cast<uint32_t>(resolved));
      }
      if (corners.size() < 3)
        return fail("f: " + std::to_string(corners.size()) + " vertices (a face needs at least 3)");
      for (size_t k = 1; k + 1 < corners.size(); ++k)
        mesh->triangles.push_back({corners[0], corners[k], corners[k + 1]});
    }
    scanner.nextLine();
  }
  return true;
}

void encodeObj(const TriangleMesh& mesh, std::vector<uint8_t>* out) {
  std::string text = "# written by mrsv\n";
  text.reserve(mesh.positions.size() * 64 + mesh.triangles.size() * 24 + 64);
  for (const auto& p : mesh.positions) {
    text += "v";
    for (double c : p) {
      text += ' ';
      appendShortestDouble(c, &text);
    }
    text += '\n';
  }
  for (const auto& t : mesh.triangles) {
    text += "f";
    for (uint32_t v : t) {
      text += ' ';
      appendUnsigned(uint64_t{v} + 1, &text);
    }
    text += '\n';
  }
  out->assign(text.begin(), text.end());
}

}  // namespace mrsv::mesh_io
