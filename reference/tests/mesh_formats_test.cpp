// Mesh file formats: the shared real meshes, exact round trips, every PLY
// encoding and type, and one test per error the readers promise to name.
#include "mrsv/mesh_formats.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "mrsv/file_io.h"
#include "test_support.h"

namespace mrsv {
namespace {

std::string surfacePath(const std::string& name) {
  return std::string(MRSV_SHARED_DATA) + "/surface/" + name;
}

struct ReadResult {
  bool ok = false;
  TriangleMesh mesh;
  std::string error;
};

// Parses `bytes` from an exact-size heap copy, so that ASan sees any over-read.
ReadResult readBytes(MeshFormat format, const std::vector<uint8_t>& bytes,
                     const std::string& scalar = "") {
  ReadResult r;
  std::unique_ptr<uint8_t[]> copy(new uint8_t[bytes.size() + (bytes.empty() ? 1 : 0)]);
  if (!bytes.empty()) std::memcpy(copy.get(), bytes.data(), bytes.size());
  r.ok = readMeshBytes("test", format, copy.get(), bytes.size(), scalar, &r.mesh, &r.error);
  return r;
}

ReadResult readText(MeshFormat format, const std::string& text, const std::string& scalar = "") {
  return readBytes(format, std::vector<uint8_t>(text.begin(), text.end()), scalar);
}

using Triangles = std::vector<std::array<uint32_t, 3>>;

// --- the shared real meshes --------------------------------------------------

struct SharedMesh {
  const char* file;
  size_t vertices;
  size_t triangles;
};

constexpr SharedMesh kSharedMeshes[] = {
    {"cow_viewpoint_2903v_5804tri.obj", 2903, 5804},
    {"fandisk_6475v_12946tri.obj", 6475, 12946},
    {"armadillo_stanford_decimated_43243v_86482tri.obj", 43243, 86482},
    {"bunny_stanford_zipper_35947v_69451tri.ply", 35947, 69451},
    {"horse_cyberware_48485v_96966tri_binbe.ply", 48485, 96966},
    {"turbine_blade_99519v_199034tri_binle.ply", 99519, 199034},
};

TEST(SharedMeshes, LoadWithTheCountsOfTheDataReadme) {
  for (const SharedMesh& expected : kSharedMeshes) {
    SCOPED_TRACE(expected.file);
    TriangleMesh mesh;
    std::string error;
    auto start = std::chrono::steady_clock::now();
    ASSERT_TRUE(readMeshFile(surfacePath(expected.file), "", &mesh, &error)) << error;
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count();
    std::printf("[ read     ] %-52s %6zu v %7zu tri  %7.1f ms\n", expected.file,
                mesh.positions.size(), mesh.triangles.size(), ms);
    EXPECT_EQ(mesh.positions.size(), expected.vertices);
    EXPECT_EQ(mesh.triangles.size(), expected.triangles);
    EXPECT_TRUE(mesh.scalars.empty());
  }
}

// A float32 or int32 read by hand from the file, to check the reader against.
uint32_t wordAt(const std::vector<uint8_t>& bytes, size_t at, bool big_endian) {
  uint32_t w = 0;
  for (int i = 0; i < 4; ++i) w |= uint32_t{bytes[at + i]} << (big_endian ? 8 * (3 - i) : 8 * i);
  return w;
}

float floatAt(const std::vector<uint8_t>& bytes, size_t at, bool big_endian) {
  uint32_t w = wordAt(bytes, at, big_endian);
  float f;
  std::memcpy(&f, &w, 4);
  return f;
}

// The first vertex and the last triangle of the binary shared meshes, decoded
// by hand from the known layout of the file (see the data README).
TEST(SharedMeshes, BinaryPlyValuesMatchTheFileLayout) {
  struct Case {
    const char* file;
    bool big_endian;
  } cases[] = {{"horse_cyberware_48485v_96966tri_binbe.ply", true},
               {"turbine_blade_99519v_199034tri_binle.ply", false}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    std::vector<uint8_t> bytes = test::readFileOrFail(surfacePath(c.file));
    std::string text(bytes.begin(), bytes.end());
    size_t body = text.find("end_header\n");
    ASSERT_NE(body, std::string::npos);
    body += 11;
    TriangleMesh mesh;
    std::string error;
    ASSERT_TRUE(readMeshFile(surfacePath(c.file), "", &mesh, &error)) << error;
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(mesh.positions[0][k], static_cast<double>(floatAt(bytes, body + 4 * k, c.big_endian)));
    // Every face is "3 a b c": one count byte and three int32.
    const size_t last = bytes.size() - 12;
    ASSERT_EQ(bytes[last - 1], 3);
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(mesh.triangles.back()[k], wordAt(bytes, last + 4 * k, c.big_endian));
  }
}

TEST(SharedMeshes, BunnyConfidenceAsScalar) {
  TriangleMesh mesh;
  std::string error;
  ASSERT_TRUE(readMeshFile(surfacePath("bunny_stanford_zipper_35947v_69451tri.ply"), "confidence",
                           &mesh, &error))
      << error;
  ASSERT_EQ(mesh.scalars.size(), 35947u);
  // The first line of the body: -0.0378297 0.12794 0.00447467 0.850855 0.5
  EXPECT_EQ(mesh.positions[0][0], -0.0378297);
  EXPECT_EQ(mesh.positions[0][2], 0.00447467);
  EXPECT_EQ(mesh.scalars[0], 0.850855);
  EXPECT_EQ(mesh.scalars[1], 0.900159);
  EXPECT_FALSE(readMeshFile(surfacePath("bunny_stanford_zipper_35947v_69451tri.ply"), "red", &mesh,
                            &error));
  EXPECT_NE(error.find("'red'"), std::string::npos) << error;
  EXPECT_NE(error.find("confidence, intensity"), std::string::npos) << error;
}

// --- exact round trips --------------------------------------------------------

TriangleMesh awkwardMesh() {
  TriangleMesh mesh;
  const double d = std::numeric_limits<double>::denorm_min();
  mesh.positions = {{0.1, 0.2, 0.3},
                    {-0.0, 1e-300, 1.7976931348623157e308},
                    {d, -d, 3.141592653589793},
                    {1.0 / 3.0, 2.0 / 3.0, -123456789.123456789},
                    {5e-324, 4.9406564584124654e-324, 2.2250738585072014e-308}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 3, 2}, {1, 4, 0}};
  return mesh;
}

bool bitwiseEqual(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expectIdentical(const TriangleMesh& a, const TriangleMesh& b) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (size_t v = 0; v < a.positions.size(); ++v)
    for (int k = 0; k < 3; ++k)
      ASSERT_TRUE(bitwiseEqual(a.positions[v][k], b.positions[v][k]))
          << "vertex " << v << " coordinate " << k << ": " << a.positions[v][k] << " vs "
          << b.positions[v][k];
  EXPECT_EQ(a.triangles, b.triangles);
  ASSERT_EQ(a.scalars.size(), b.scalars.size());
  for (size_t v = 0; v < a.scalars.size(); ++v)
    ASSERT_TRUE(bitwiseEqual(a.scalars[v], b.scalars[v])) << "scalar " << v;
}

TEST(MeshRoundTrip, EveryFormatGivesBackTheSameBits) {
  TriangleMesh mesh = awkwardMesh();
  for (const char* name : {"a.obj", "a.off", "a.ply", "A.PLY"}) {
    SCOPED_TRACE(name);
    std::vector<uint8_t> bytes;
    std::string error;
    ASSERT_TRUE(encodeMeshFile(name, mesh, &bytes, &error)) << error;
    ReadResult back = readBytes(meshFormatOf(name), bytes);
    ASSERT_TRUE(back.ok) << back.error;
    expectIdentical(mesh, back.mesh);
  }
}

TEST(MeshRoundTrip, PlyKeepsScalars) {
  TriangleMesh mesh = awkwardMesh();
  mesh.scalars = {0.5, -1e-10, 7.0, 1e300, -0.0};
  std::vector<uint8_t> bytes;
  std::string error;
  ASSERT_TRUE(encodeMeshFile("a.ply", mesh, &bytes, &error)) << error;
  ReadResult back = readBytes(MeshFormat::kPly, bytes, "scalar");
  ASSERT_TRUE(back.ok) << back.error;
  expectIdentical(mesh, back.mesh);
}

TEST(MeshRoundTrip, RealMeshesThroughEveryFormatAndAFile) {
  TriangleMesh cow;
  std::string error;
  ASSERT_TRUE(readMeshFile(surfacePath("cow_viewpoint_2903v_5804tri.obj"), "", &cow, &error)) << error;
  TriangleMesh horse;
  ASSERT_TRUE(readMeshFile(surfacePath("horse_cyberware_48485v_96966tri_binbe.ply"), "", &horse,
                           &error))
      << error;
  std::string dir = ::testing::TempDir();
  for (const TriangleMesh* mesh : {&cow, &horse}) {
    for (const char* ext : {".obj", ".off", ".ply"}) {
      std::string path = dir + "/mrsv_mesh_roundtrip" + ext;
      std::vector<uint8_t> bytes;
      ASSERT_TRUE(encodeMeshFile(path, *mesh, &bytes, &error)) << error;
      ASSERT_TRUE(writeFileAtomically(path, bytes, &error)) << error;
      TriangleMesh back;
      ASSERT_TRUE(readMeshFile(path, "", &back, &error)) << error;
      expectIdentical(*mesh, back);
      std::remove(path.c_str());
    }
  }
}

TEST(MeshWrite, RefusesWhatTheFormatCannotHold) {
  std::vector<uint8_t> bytes;
  std::string error;
  TriangleMesh mesh = awkwardMesh();
  mesh.scalars.assign(mesh.positions.size(), 1.0);
  EXPECT_FALSE(encodeMeshFile("a.obj", mesh, &bytes, &error));
  EXPECT_NE(error.find("scalars"), std::string::npos) << error;
  EXPECT_FALSE(encodeMeshFile("a.off", mesh, &bytes, &error));
  mesh.scalars.pop_back();
  EXPECT_FALSE(encodeMeshFile("a.ply", mesh, &bytes, &error));
  EXPECT_NE(error.find("4 scalars for 5 vertices"), std::string::npos) << error;
  mesh = awkwardMesh();
  mesh.triangles.push_back({0, 1, 5});
  EXPECT_FALSE(encodeMeshFile("a.ply", mesh, &bytes, &error));
  EXPECT_NE(error.find("vertex index 5 out of range"), std::string::npos) << error;
  mesh = awkwardMesh();
  mesh.positions[3][1] = std::nan("");
  EXPECT_FALSE(encodeMeshFile("a.obj", mesh, &bytes, &error));
  EXPECT_NE(error.find("vertex 3 has a NaN"), std::string::npos) << error;
  EXPECT_FALSE(encodeMeshFile("a.stl", awkwardMesh(), &bytes, &error));
  EXPECT_NE(error.find("unknown mesh format"), std::string::npos) << error;
}

TEST(MeshFormat, ChosenByExtension) {
  EXPECT_EQ(meshFormatOf("x/y.obj"), MeshFormat::kObj);
  EXPECT_EQ(meshFormatOf("Y.OBJ"), MeshFormat::kObj);
  EXPECT_EQ(meshFormatOf("y.Ply"), MeshFormat::kPly);
  EXPECT_EQ(meshFormatOf("y.off"), MeshFormat::kOff);
  EXPECT_EQ(meshFormatOf("y.stl"), MeshFormat::kUnknown);
  EXPECT_EQ(meshFormatOf("obj"), MeshFormat::kUnknown);
  TriangleMesh mesh;
  std::string error;
  EXPECT_FALSE(readMeshFile("nonexistent.stl", "", &mesh, &error));
  EXPECT_FALSE(readMeshFile(::testing::TempDir() + "/mrsv_no_such_file.obj", "", &mesh, &error));
  EXPECT_NE(error.find("mrsv_no_such_file.obj: "), std::string::npos) << error;
}

// --- OBJ ------------------------------------------------------------------------

TEST(ObjRead, CornerFormsNegativeIndicesPolygonsCommentsAndCrLf) {
  ReadResult r = readText(MeshFormat::kObj,
                          "# a comment\r\n"
                          "mtllib x.mtl\r\n"
                          "o thing\n"
                          "v 0 0 0\r\n"
                          "v 1 0 0 1.0\n"
                          "v 1 1 0   # trailing comment\n"
                          "v 0 1 0 0.5 0.5 0.5\n"
                          "vt 0 0\nvn 0 0 1\n"
                          "g group\ns 1\nusemtl m\n"
                          "f 1 2 3\n"
                          "f 1/1 3/1 4/1\n"
                          "f 1//1 2//1 3//1\n"
                          "f 1/1/1 2/1/1 3/1/1\n"
                          "f -4 -3 -2 -1\n"
                          "\tf  +1 2 3  \r\n"
                          "l 1 2\n"
                          "f 1 2 3");  // no final newline
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.mesh.positions.size(), 4u);
  EXPECT_EQ(r.mesh.positions[2], (std::array<double, 3>{1, 1, 0}));
  Triangles expected = {{0, 1, 2}, {0, 2, 3}, {0, 1, 2}, {0, 1, 2},
                        {0, 1, 2}, {0, 2, 3}, {0, 1, 2}, {0, 1, 2}};
  EXPECT_EQ(r.mesh.triangles, expected);
}

TEST(ObjRead, NegativeIndicesAreRelativeToTheVerticesSoFar) {
  ReadResult r = readText(MeshFormat::kObj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"
                                            "v 5 5 5\nf -4 -3 -1\n");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.mesh.triangles, (Triangles{{0, 1, 2}, {0, 1, 3}}));
}

struct ErrorCase {
  const char* text;
  const char* expected;  // must appear in the message
};

void expectErrors(MeshFormat format, const std::vector<ErrorCase>& cases) {
  for (const ErrorCase& c : cases) {
    SCOPED_TRACE(c.text);
    ReadResult r = readText(format, c.text);
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.error.find(c.expected), std::string::npos) << r.error;
    EXPECT_EQ(r.error.find('\n'), std::string::npos) << r.error;
    EXPECT_EQ(r.error.rfind("test:", 0), 0u) << r.error;
    EXPECT_TRUE(r.mesh.positions.empty() && r.mesh.triangles.empty());
  }
}

TEST(ObjRead, ErrorsNameTheLineFieldAndRule) {
  expectErrors(MeshFormat::kObj,
               {
                   {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", ":4: f: vertex index 9 is out of range (3 vertices"},
                   {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", ":4: f: vertex index 0 is out of range"},
                   {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n", ":4: f: vertex index -4 is out of range"},
                   {"v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\n", ":2: f: vertex index 2 is out of range (1 vertices"},
                   {"v 0 0 0\nv 1 0 0\nf 1 2\n", ":3: f: 2 vertices (a face needs at least 3)"},
                   {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 x 2\n", ":4: f: vertex index 'x' is not a number"},
                   {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 //2 3\n", ":4: f: vertex index '//2' is not a number"},
                   {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n", "out of range"},
                   {"\n\nv nan 0 0\n", ":3: v: coordinate 'nan' is not finite"},
                   {"v 0 inf 0\n", ":1: v: coordinate 'inf' is not finite"},
                   {"v 0 0 1e999\n", ":1: v: coordinate '1e999' is out of range"},
                   {"v 0 0,5 0\n", ":1: v: coordinate '0,5' is not a number"},
                   {"v 0x10 0 0\n", "coordinate '0x10' is not a number"},
                   {"v 0 0\n", ":1: v: 2 numbers"},
                   {"v 0 0 0 0 0\n", ":1: v: 5 numbers"},
                   {"v 1 2 3 4 5 6 7 8\n", "more than 7 numbers"},
               });
}

// --- OFF ------------------------------------------------------------------------

TEST(OffRead, CommentsPolygonsAndColourColumns) {
  ReadResult r = readText(MeshFormat::kOff,
                          "# leading comment\n"
                          "COFF\r\n"
                          "\n"
                          "# counts follow\n"
                          "4 2 0\n"
                          "0 0 0 255 0 0 255\n"
                          "1 0 0 255 0 0 255  # a comment\n"
                          "1 1 0 255 0 0 255\n"
                          "\n"
                          "0 1 0 255 0 0 255\n"
                          "4 0 1 2 3 0.5 0.5 0.5\n"
                          "3 3 2 1\n\n# the end\n");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.mesh.positions.size(), 4u);
  EXPECT_EQ(r.mesh.triangles, (Triangles{{0, 1, 2}, {0, 2, 3}, {3, 2, 1}}));
  ReadResult same_line = readText(MeshFormat::kOff, "OFF 3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2");
  ASSERT_TRUE(same_line.ok) << same_line.error;
  EXPECT_EQ(same_line.mesh.triangles, (Triangles{{0, 1, 2}}));
  EXPECT_TRUE(readText(MeshFormat::kOff, "NOFF\n1 0 0\n0 0 0 0 0 1\n").ok);
}

TEST(OffRead, ErrorsNameTheLineFieldAndRule) {
  expectErrors(MeshFormat::kOff,
               {
                   {"PLY\n", ":1: header: not an OFF file"},
                   {"4OFF\n", "'4OFF' is not supported"},
                   {"OFF BINARY\n", "binary OFF is not supported"},
                   {"OFF\n3 x 0\n", ":2: header: face count 'x' is not a number"},
                   {"OFF\n3\n", "face count '' is missing"},
                   {"OFF\n-3 1 0\n", "vertex count is negative"},
                   {"OFF\n1000000000 1000000000 0\n0 0 0\n", "cannot fit in the 6 bytes that follow"},
                   {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", ":6: face 0: vertex index 3 is out of range (3 vertices)"},
                   {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "vertex index -1 is out of range"},
                   {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", ":6: face 0: 2 vertices"},
                   {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", "line ends after 3 of 4 vertex indices"},
                   {"OFF\n3 1 0\n0 0 0\n1 NaN 0\n0 1 0\n3 0 1 2\n", ":4: vertex 1: coordinate 'NaN' is not finite"},
                   {"OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", ":4: vertex 1: fewer than 3 coordinates"},
                   {"OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n#\n                    ", "face 1: file ends after 1 of 2 faces"},
                   {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n", ":7: unexpected text"},
               });
}

// --- PLY ------------------------------------------------------------------------

const char* kTypeNames[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double"};
const size_t kTypeBytes[] = {1, 1, 2, 2, 4, 4, 4, 8};

// Appends `value` as PLY type `type` (an index into kTypeNames).
void appendValue(int type, double value, bool ascii, bool big_endian, std::string* out) {
  if (ascii) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g ", value);
    *out += text;
    return;
  }
  uint64_t bits = 0;
  if (type == 6) {
    float f = static_cast<float>(value);
    uint32_t b;
    std::memcpy(&b, &f, 4);
    bits = b;
  } else if (type == 7) {
    std::memcpy(&bits, &value, 8);
  } else {
    bits = static_cast<uint64_t>(static_cast<int64_t>(value));
  }
  const size_t n = kTypeBytes[type];
  for (size_t i = 0; i < n; ++i)
    out->push_back(static_cast<char>(bits >> (8 * (big_endian ? n - 1 - i : i))));
}

// A square (4 vertices, one quad and one triangle) in the given encoding and
// types, with extra properties and elements the reader must read past.
std::string plySquare(const char* format, int coord_type, int count_type, int index_type) {
  const bool ascii = std::strcmp(format, "ascii") == 0;
  const bool big = std::strcmp(format, "binary_big_endian") == 0;
  std::string text = std::string("ply\nformat ") + format + " 1.0\ncomment made by the test\n";
  text += "element material 1\nproperty list uchar float rgb\nproperty int id\n";
  text += "element vertex 4\n";
  text += std::string("property ") + kTypeNames[coord_type] + " z\n";
  text += "property list uchar short neighbours\n";
  text += std::string("property ") + kTypeNames[coord_type] + " x\n";
  text += "property uchar red\nproperty double quality\n";
  text += std::string("property ") + kTypeNames[coord_type] + " y\n";
  text += "element edge 2\nproperty int vertex1\nproperty int vertex2\n";
  text += std::string("element face 2\nproperty uchar flags\nproperty list ") +
          kTypeNames[count_type] + " " + kTypeNames[index_type] + " vertex_indices\n";
  text += "property list int double texcoord\nend_header\n";
  auto put = [&](int type, double value) { appendValue(type, value, ascii, big, &text); };
  // material: rgb list of 3 floats, id
  put(1, 3), put(6, 0.25), put(6, 0.5), put(6, 0.75), put(4, 7);
  if (ascii) text += "\n";
  const double xs[4] = {0, 2, 2, 0}, ys[4] = {0, 0, 2, 2};
  const double zs[4] = {coord_type == 0 ? -3.0 : 3.0, 1, 2, 0};
  for (int v = 0; v < 4; ++v) {
    put(coord_type, zs[v]);
    put(1, 2), put(2, -1), put(2, 300);  // neighbours
    put(coord_type, xs[v]);
    put(1, 200), put(7, 0.125);
    put(coord_type, ys[v]);
    if (ascii) text += "\n";
  }
  put(4, 0), put(4, 1), put(4, 1), put(4, 2);
  if (ascii) text += "\n";
  put(1, 9), put(count_type, 4), put(index_type, 0), put(index_type, 1), put(index_type, 2),
      put(index_type, 3), put(4, 2), put(7, 0.5), put(7, 0.5);
  if (ascii) text += "\n";
  put(1, 9), put(count_type, 3), put(index_type, 3), put(index_type, 2), put(index_type, 1),
      put(4, 0);
  if (ascii) text += "\n";
  return text;
}

TEST(PlyRead, EveryEncodingAndTypeCombination) {
  int files = 0;
  for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    for (int coord = 0; coord < 8; ++coord) {
      for (int count = 0; count < 6; ++count) {
        for (int index = 0; index < 6; ++index) {
          SCOPED_TRACE(std::string(format) + " coordinates " + kTypeNames[coord] + ", list " +
                       kTypeNames[count] + " " + kTypeNames[index]);
          ReadResult r = readText(MeshFormat::kPly, plySquare(format, coord, count, index), "red");
          ASSERT_TRUE(r.ok) << r.error;
          ASSERT_EQ(r.mesh.positions.size(), 4u);
          EXPECT_EQ(r.mesh.positions[0], (std::array<double, 3>{0, 0, coord == 0 ? -3.0 : 3.0}));
          EXPECT_EQ(r.mesh.positions[2], (std::array<double, 3>{2, 2, 2}));
          EXPECT_EQ(r.mesh.triangles, (Triangles{{0, 1, 2}, {0, 2, 3}, {3, 2, 1}}));
          EXPECT_EQ(r.mesh.scalars, (std::vector<double>{200, 200, 200, 200}));
          ++files;
        }
      }
    }
  }
  EXPECT_EQ(files, 3 * 8 * 6 * 6);
}

TEST(PlyRead, HandWrittenAsciiWithCrLfAndVertexIndex) {
  ReadResult r = readText(MeshFormat::kPly,
                          "ply\r\nformat ascii 1.0\r\nobj_info from a scanner\r\n"
                          "element vertex 3\r\nproperty float32 x\r\nproperty float32 y\r\n"
                          "property float32 z\r\nelement face 1\r\n"
                          "property list uint8 int32 vertex_index\r\nend_header\r\n"
                          "0 0 0\r\n1 0 0\r\n0 1 +0.5e0\r\n3 0 1 2\r\n\r\n");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.mesh.positions[2][2], 0.5);
  EXPECT_EQ(r.mesh.triangles, (Triangles{{0, 1, 2}}));
}

// The bytes of a small valid binary little-endian PLY (a triangle).
std::string plyTriangleLe() { return plySquare("binary_little_endian", 6, 1, 4); }

TEST(PlyRead, ErrorsNameTheFieldAndRule) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  expectErrors(MeshFormat::kPly,
               {
                   {"ply", "the header has no end_header"},
                   {"plx\n", "not a PLY file"},
                   {"ply\nformat binary_middle_endian 1.0\nend_header\n",
                    "line 2: format 'binary_middle_endian' is unknown"},
                   {"ply\nformat ascii 2.0\nend_header\n", "format version '2.0'"},
                   {"ply\nelement vertex 1\nproperty float x\nend_header\n", "no format line"},
                   {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n",
                    "line 4: property: type 'float128' is unknown"},
                   {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", "property before any element"},
                   {"ply\nformat ascii 1.0\nelement vertex -1\nend_header\n", "count of 0 or more"},
                   {"ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\n",
                    "count type 'float' is not an integer type"},
                   {"ply\nformat ascii 1.0\nwhatever\nend_header\n", "unknown header keyword 'whatever'"},
                   {"ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                    "element face 0\nproperty list uchar int vertex_indices\nend_header\n",
                    "vertex element has no 'z' property (it has x, y)"},
                   {"ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                    "property float z\nend_header\n",
                    "no 'face' element"},
                   {"ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 0\nproperty list uchar float vertex_indices\nend_header\n",
                    "non-integer index type float"},
                   {"ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 0\nproperty list uchar int corners\nend_header\n",
                    "face element has no vertex_indices"},
                   {"ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n",
                    "header line 3: element 'vertex' count 4000000000 cannot fit in the 0 bytes"},
                   {(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n").c_str(),
                    "line 13: face 0 vertex_indices: vertex index 3 is out of range (3 vertices)"},
                   {(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n").c_str(), "vertex index -1 is out of range"},
                   {(head + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n").c_str(), "face 0 vertex_indices: 2 vertices"},
                   {(head + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n").c_str(),
                    "line 11: vertex 1 y: 'nan' is not finite"},
                   {(head + "0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n").c_str(), "'300' is out of range for uchar"},
                   {(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2.0\n").c_str(), "'2.0' is not a number"},
                   {(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 7\n").c_str(), "line 13: unexpected data after the last element"},
                   {(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n").c_str(), "face 0 vertex_indices: the file ends inside the body"},
               });
}

std::string binaryTriangle(bool big_endian, float y1, int32_t index2, size_t drop_tail, bool extra) {
  std::string text = std::string("ply\nformat ") +
                     (big_endian ? "binary_big_endian" : "binary_little_endian") +
                     " 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                     "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const float coords[9] = {0, 0, 0, 1, y1, 0, 0, 1, 0};
  for (float c : coords) appendValue(6, c, false, big_endian, &text);
  appendValue(1, 3, false, big_endian, &text);
  for (int32_t i : {0, 1, index2}) appendValue(4, i, false, big_endian, &text);
  if (extra) text += '\0';
  text.resize(text.size() - drop_tail);
  return text;
}

TEST(PlyRead, BinaryErrorsNameTheByteOffset) {
  const std::string header_only = binaryTriangle(false, 0, 2, 49, false);
  const size_t body = header_only.size();
  ASSERT_TRUE(readText(MeshFormat::kPly, binaryTriangle(false, 0, 2, 0, false)).ok);
  ASSERT_TRUE(readText(MeshFormat::kPly, binaryTriangle(true, 0, 2, 0, false)).ok);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  struct Case {
    std::string bytes;
    std::string expected;
  } cases[] = {
      {binaryTriangle(false, nan, 2, 0, false),
       "byte " + std::to_string(body + 16) + ": vertex 1 y: value is not finite"},
      {binaryTriangle(true, -inf, 2, 0, false), "vertex 1 y: value is not finite"},
      {binaryTriangle(false, 0, 3, 0, false),
       "byte " + std::to_string(body + 45) + ": face 0 vertex_indices: vertex index 3 is out of range"},
      {binaryTriangle(true, 0, -7, 0, false), "vertex index -7 is out of range"},
      {binaryTriangle(false, 0, 2, 2, false),
       "byte " + std::to_string(body + 45) + ": face 0 vertex_indices: the file ends inside the body"},
      {binaryTriangle(false, 0, 2, 20, false), "cannot fit in the 29 bytes after the header"},
      {binaryTriangle(true, 0, 2, 0, true), "1 bytes after the last element"},
  };
  for (const Case& c : cases) {
    ReadResult r = readText(MeshFormat::kPly, c.bytes);
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.error.find(c.expected), std::string::npos) << r.error;
  }
}

TEST(PlyRead, TinyFileCannotAskForGigabytes) {
  // 2^31 faces of at least 1 byte each (then 12 bytes each in memory); the file has 0 body bytes.
  std::string text =
      "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
      "property float z\nelement face 2147483648\nproperty list uchar int vertex_indices\nend_header\n";
  ReadResult r = readText(MeshFormat::kPly, text);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("element 'face' count 2147483648 cannot fit"), std::string::npos) << r.error;
  // A list whose declared item count runs past the end.
  std::string lists =
      "ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty list uint double junk\n"
      "property float x\nproperty float y\nproperty float z\nelement face 0\n"
      "property list uchar int vertex_indices\nend_header\n\xff\xff\xff\xff" + std::string(12, '\0');
  r = readText(MeshFormat::kPly, lists);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("vertex 0 junk: the file ends inside the body"), std::string::npos) << r.error;
  // An element without properties reads nothing, however large its count.
  std::string empty_element =
      "ply\nformat binary_little_endian 1.0\nelement nothing 9223372036854775807\n"
      "element vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement face 0\n"
      "property list uchar int vertex_indices\nend_header\n";
  r = readText(MeshFormat::kPly, empty_element);
  EXPECT_TRUE(r.ok) << r.error;
}

// --- any bytes: never a crash ---------------------------------------------------

TEST(MeshRead, EveryPrefixAndByteFlipIsSafe) {
  std::vector<std::pair<MeshFormat, std::string>> files = {
      {MeshFormat::kPly, plyTriangleLe()},
      {MeshFormat::kPly, plySquare("binary_big_endian", 7, 5, 5)},
      {MeshFormat::kPly, plySquare("ascii", 2, 0, 3)},
      {MeshFormat::kObj, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1/1 2/2/2 -2//3 -1\n"},
      {MeshFormat::kOff, "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n"},
  };
  uint32_t seed = 12345;
  auto random = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return seed >> 8;
  };
  for (const auto& [format, text] : files) {
    std::vector<uint8_t> bytes(text.begin(), text.end());
    ASSERT_TRUE(readBytes(format, bytes).ok) << readBytes(format, bytes).error;
    for (size_t n = 0; n < bytes.size(); ++n) {
      ReadResult r = readBytes(format, std::vector<uint8_t>(bytes.begin(), bytes.begin() + n));
      if (!r.ok) {
        EXPECT_FALSE(r.error.empty());
      }
      // A binary body must be complete; a text prefix may be a valid smaller mesh.
      if (format == MeshFormat::kPly && text.find("binary") != std::string::npos) {
        EXPECT_FALSE(r.ok) << "prefix of " << n << " bytes";
      }
    }
    for (int trial = 0; trial < 3000; ++trial) {
      std::vector<uint8_t> flipped = bytes;
      for (int k = 0; k < 1 + trial % 3; ++k)
        flipped[random() % flipped.size()] ^= static_cast<uint8_t>(1 + random() % 255);
      ReadResult r = readBytes(format, flipped);
      if (!r.ok) {
        EXPECT_FALSE(r.error.empty());
        continue;
      }
      for (const auto& t : r.mesh.triangles)
        for (uint32_t v : t) ASSERT_LT(v, r.mesh.positions.size());
    }
  }
}

TEST(MeshRead, ScalarOnlyFromPly) {
  ReadResult r = readText(MeshFormat::kObj, "v 0 0 0\n", "confidence");
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("OBJ has no vertex properties"), std::string::npos) << r.error;
}

}  // namespace
}  // namespace mrsv
