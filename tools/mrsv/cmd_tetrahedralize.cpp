// mrsv tetrahedralize: tet meshes from grids and PLOT3D data, and conversion
// between the tet mesh formats.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "cli.h"
#include "commands.h"
#include "mrsv/file_io.h"
#include "mrsv/grid.h"
#include "mrsv/grid_formats.h"
#include "mrsv/raw_grid.h"
#include "mrsv/tet_formats.h"

namespace mrsv::cli {
namespace {

const char kHelp[] =
    "Usage: mrsv tetrahedralize [options] IN OUT.{mesh,node,ele,vtu,vtk}\n"
    "\n"
    "Make a tetrahedral mesh, or convert one between formats. IN is one of:\n"
    "  a tet mesh (.mesh MEDIT, .node/.ele TetGen, .vtu VTK XML, .vtk legacy VTK):\n"
    "      converted to OUT's format;\n"
    "  a grid (.nrrd, .mrsv, or headerless raw with --dims and --type, like 'mrsv encode'):\n"
    "      6 tets per cube of 8 neighbouring samples, cut alike so neighbours meet face to\n"
    "      face; the samples become the field 'value'; spacing from the NRRD header or the\n"
    "      .mrsv meta entry 'spacing', else 1 (an X x Y x Z grid gives 6(X-1)(Y-1)(Z-1) tets);\n"
    "  a PLOT3D grid (.xyz: single block, binary, float32, no record markers, IBLANK\n"
    "      optional) with its solution --q FILE.q: 5 tets per hexahedron, alternating with\n"
    "      the parity of i+j+k so neighbours meet face to face; points at one position\n"
    "      welded; a hexahedron the 5 tets do not fit (distorted, or at a seam of odd\n"
    "      period) cut into 6 tets from a corner or 12 around an added centroid vertex;\n"
    "      hexahedra with an IBLANK 0 corner left out; the q variables become the fields\n"
    "      density, momentum_x, momentum_y, momentum_z, energy.\n"
    "Every tet is made positively oriented (exact test; two vertices swapped where needed);\n"
    "a degenerate tet is an error naming it. OUT.node or OUT.ele writes both TetGen files.\n"
    "MEDIT .mesh has no per-vertex fields: they are not written (a note says so).\n"
    "\n"
    "Options:\n"
    "  --dims X,Y,Z          grid size in samples (raw input)\n"
    "  --type T              sample type: uint8, int16, uint16, int32, float32, float64 (raw)\n"
    "  --endian little|big   byte order of a raw IN (default little)\n"
    "  --crop X0,Y0,Z0,NX,NY,NZ  only the NX x NY x NZ samples from (X0, Y0, Z0) (grids)\n"
    "  --spacing SX,SY,SZ    sample spacing, overriding the file's (grids)\n"
    "  --q FILE.q            the PLOT3D solution of a .xyz grid\n"
    "  --ascii               write .vtu and .vtk as text (default: binary)\n"
    "  --quiet               no notes on stderr\n"
    "  --help                this text\n"
    "\n"
    "Prints the vertex, tet and field counts. OUT is written under a temporary name and\n"
    "renamed when complete. Exit status: 0 done, 1 invalid input, 2 usage error, 3 file error.\n";

bool endsWith(const std::string& s, const char* suffix) {
  std::string lower = s;
  for (char& c : lower) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  const std::string t(suffix);
  return lower.size() >= t.size() && lower.compare(lower.size() - t.size(), t.size(), t) == 0;
}

// "a,b,c" into `count` numbers.
bool parseNumbers(const std::string& text, size_t count, double* out) {
  size_t start = 0;
  for (size_t i = 0; i < count; ++i) {
    size_t comma = text.find(',', start);
    if ((comma == std::string::npos) != (i + 1 == count)) return false;
    std::string part = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    out[i] = std::strtod(part.c_str(), &end);
    if (part.empty() || *end != '\0' || !std::isfinite(out[i])) return false;
    start = comma + 1;
  }
  return true;
}

// Files that cannot be opened are file errors (exit 3), not data errors.
bool readable(const std::string& path) { return ::access(path.c_str(), R_OK) == 0; }

std::string fieldList(const TetMesh& mesh) {
  std::string s;
  for (const ScalarField& f : mesh.fields) s += (s.empty() ? "" : ", ") + f.name;
  return s.empty() ? "none" : s;
}

}  // namespace

int runTetrahedralize(int argc, char** argv) {
  const char* cmd = "tetrahedralize";
  Args args;
  std::string error;
  if (!args.parse(argc, argv, {{"dims", "type", "endian", "crop", "spacing", "q"}, {"ascii", "quiet", "help"}, {}},
                  &error))
    return fail(cmd, error + " (see 'mrsv tetrahedralize --help')", kExitUsage);
  if (args.flag("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  if (args.positional().size() != 2)
    return fail(cmd, "expected IN and OUT (see 'mrsv tetrahedralize --help')", kExitUsage);
  const std::string& in = args.positional()[0];
  const std::string& out = args.positional()[1];
  const bool quiet = args.flag("quiet");
  const TetFormat out_format = tetFormatOf(out);
  if (out_format == TetFormat::kUnknown)
    return fail(cmd, out + ": OUT must end in .mesh, .node, .ele, .vtu or .vtk", kExitUsage);
  std::vector<std::string> out_paths = {out};
  if (out_format == TetFormat::kTetgen) out_paths = {tetgenNodePath(out), tetgenElePath(out)};
  std::vector<std::string> in_paths = {in};
  if (tetFormatOf(in) == TetFormat::kTetgen) in_paths = {tetgenNodePath(in), tetgenElePath(in)};
  if (args.has("q")) in_paths.push_back(args.value("q"));
  for (const std::string& o : out_paths)
    for (const std::string& i : in_paths)
      if (isSameFile(i, o))
        return fail(cmd, o + " is an input file; refusing to overwrite it", kExitUsage);
  for (const std::string& i : in_paths)
    if (!readable(i)) return fail(cmd, i + ": cannot be read", kExitIo);

  const bool is_grid = tetFormatOf(in) == TetFormat::kUnknown && !endsWith(in, ".xyz");
  if (!is_grid && (args.has("dims") || args.has("type") || args.has("crop") || args.has("spacing") ||
                   args.has("endian")))
    return fail(cmd, "--dims, --type, --endian, --crop and --spacing are for grid input", kExitUsage);
  if (args.has("q") && !endsWith(in, ".xyz"))
    return fail(cmd, "--q FILE.q goes with a PLOT3D grid IN.xyz", kExitUsage);

  TetMesh mesh;
  std::vector<std::string> notes;
  if (tetFormatOf(in) != TetFormat::kUnknown) {
    TetReadReport report;
    if (!readTetFile(in, &mesh, &report, &error)) return fail(cmd, error, kExitInvalidData);
    if (report.flipped)
      notes.push_back(std::to_string(report.flipped) + " negatively oriented tets repaired (two vertices swapped)");
    if (report.skipped_cells)
      notes.push_back(std::to_string(report.skipped_cells) + " cells of dimension 0 to 2 skipped");
  } else if (endsWith(in, ".xyz")) {
    Plot3dData data;
    if (!readPlot3d(in, args.has("q") ? args.value("q") : "", &data, &error))
      return fail(cmd, error, kExitInvalidData);
    TetBuildReport report;
    if (!tetrahedralizePlot3d(data, &mesh, &report, &error)) return fail(cmd, in + ": " + error, kExitInvalidData);
    notes.push_back(std::to_string(data.dims[0]) + "x" + std::to_string(data.dims[1]) + "x" +
                    std::to_string(data.dims[2]) + " points" + (data.iblank.empty() ? "" : " with IBLANK") + ", " +
                    std::to_string(report.cells) + " hexahedra, " + std::to_string(report.cells_left_out) +
                    " left out (IBLANK 0), " + std::to_string(report.welded) + " coincident points welded, " +
                    std::to_string(report.collapsed) + " collapsed tets dropped, " + std::to_string(report.flipped) +
                    " tets flipped to positive, " + std::to_string(report.cut_from_corner) +
                    " hexahedra cut into 6 tets from a corner, " + std::to_string(report.cut_around_centroid) +
                    " into 12 around an added centroid");
  } else {
    GridHeader header;
    std::vector<uint8_t> samples;
    const Metadata* metadata = nullptr;
    GridInput input;
    DecodedGrid decoded;
    if (endsWith(in, ".mrsv")) {
      if (args.has("dims") || args.has("type") || args.has("endian"))
        return fail(cmd, "--dims, --type and --endian are for headerless raw input", kExitUsage);
      std::vector<uint8_t> bytes;
      if (!readWholeFile(in, &bytes, &error)) return fail(cmd, in + ": " + error, kExitIo);
      if (Error e = decodeGrid(bytes.data(), bytes.size(), DecodeOptions{}, &decoded); !e.ok())
        return reportError(cmd, in, e);
      if (!decoded.has_samples)
        return fail(cmd, in + ": the stream ends before its sample data", kExitInvalidData);
      header = decoded.header;
      samples = std::move(decoded.samples);
      metadata = &decoded.metadata;
    } else {
      RawLayout raw;
      if (args.has("dims") != args.has("type"))
        return fail(cmd, "--dims and --type go together", kExitUsage);
      if (args.has("dims")) {
        if (gridFormatOf(in) != GridFormat::kRaw)
          return fail(cmd, "--dims and --type are for headerless raw input; " + in + " has a header", kExitUsage);
        raw.has_layout = true;
        if (std::string problem = parseDims(args.value("dims"), &raw.header); !problem.empty())
          return fail(cmd, "--dims: " + problem, kExitUsage);
        if (!parseSampleType(args.value("type"), &raw.header.sample_type))
          return fail(cmd, "--type '" + args.value("type") + "' is not one of uint8, int16, uint16, int32, float32, float64",
                      kExitUsage);
      } else if (gridFormatOf(in) == GridFormat::kRaw) {
        return fail(cmd, in + ": not a tet mesh, .xyz, .nrrd or .mrsv; headerless raw input needs --dims and --type",
                    kExitUsage);
      }
      if (args.has("endian")) {
        if (args.value("endian") == "big") raw.big_endian = true;
        else if (args.value("endian") != "little") return fail(cmd, "--endian must be little or big", kExitUsage);
      }
      if (!readGridInput(in, raw, &input, &error)) return fail(cmd, error, kExitInvalidData);
      header = input.header;
      samples = std::move(input.samples);
      metadata = &input.metadata;
    }
    double spacing[3] = {1, 1, 1};
    if (const std::string* s = metadata->find("spacing"); s && !args.has("spacing")) {
      if (!parseNumbers(*s, 3, spacing))
        return fail(cmd, in + ": spacing '" + *s + "' is not three numbers (use --spacing)", kExitInvalidData);
    }
    if (args.has("spacing") && !parseNumbers(args.value("spacing"), 3, spacing))
      return fail(cmd, "--spacing must be three numbers SX,SY,SZ", kExitUsage);
    GridCrop crop;
    if (args.has("crop")) {
      double c[6];
      if (!parseNumbers(args.value("crop"), 6, c))
        return fail(cmd, "--crop must be six whole numbers X0,Y0,Z0,NX,NY,NZ", kExitUsage);
      for (int k = 0; k < 6; ++k) {
        if (c[k] < 0 || c[k] != std::floor(c[k]) || c[k] > UINT32_MAX)
          return fail(cmd, "--crop must be six whole numbers X0,Y0,Z0,NX,NY,NZ", kExitUsage);
        (k < 3 ? crop.origin[k] : crop.size[k - 3]) = static_cast<uint32_t>(c[k]);
      }
      for (int k = 0; k < 3; ++k)
        if (crop.size[k] == 0) return fail(cmd, "--crop sizes must be at least 2", kExitUsage);
    }
    TetBuildReport report;
    if (!tetrahedralizeGrid(header, samples, spacing, crop, &mesh, &report, &error))
      return fail(cmd, in + ": " + error, kExitInvalidData);
    notes.push_back(std::to_string(report.cells) + " cubes" +
                    (report.cells_left_out ? ", " + std::to_string(report.cells_left_out) + " left out (no-data samples)"
                                           : std::string()) +
                    ", spacing " + std::to_string(spacing[0]) + "," + std::to_string(spacing[1]) + "," +
                    std::to_string(spacing[2]));
  }

  TetWriteOptions options;
  options.ascii = args.flag("ascii");
  TetWriteReport written;
  if (!writeTetFile(out, mesh, options, &written, &error)) {
    // Unwritable meshes (bad field names, ...) are data errors; the rest file errors.
    bool data_problem = error.find("cannot write the mesh") != std::string::npos;
    return fail(cmd, error, data_problem ? kExitInvalidData : kExitIo);
  }
  if (written.fields_dropped)
    notes.push_back(std::to_string(written.fields_dropped) +
                    " fields not written: MEDIT .mesh has no place for them (write .vtu, .vtk or .node)");
  if (!quiet)
    for (const std::string& note : notes) std::fprintf(stderr, "mrsv tetrahedralize: %s: %s\n", in.c_str(), note.c_str());
  std::printf("%s: %zu vertices, %zu tets, %zu fields (%s)\n", out.c_str(), mesh.positions.size(),
              mesh.tets.size(), mesh.fields.size(), fieldList(mesh).c_str());
  return kExitOk;
}

}  // namespace mrsv::cli
