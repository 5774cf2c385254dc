// mrsv encode / decode for tetrahedral meshes: the PT stream (spec 7).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "cli.h"
#include "commands.h"
#include "mrsv/file_io.h"
#include "mrsv/progressive_tet_mesh.h"
#include "mrsv/tet_formats.h"
#include "pt/pt_encode.h"
#include "tetsimplify/tet_simplify.h"

namespace mrsv::cli {
namespace {

const char kEncodeHelp[] =
    "Usage: mrsv encode [options] IN.{mesh,node,ele,vtu,vtk} OUT.mrsv\n"
    "\n"
    "Encode a tetrahedral mesh as a progressive tetrahedralization (PT stream, spec 7):\n"
    "a base tet mesh and batches of vertex splits, coarse to fine, so that any prefix\n"
    "decodes to a coarser mesh. Per-vertex scalar fields travel with their vertices.\n"
    "Every level is a 3-manifold of positive tets with the input's topology; the\n"
    "collapses evaded by each consistency test are printed.\n"
    "\n"
    "Options:\n"
    "  --cost quadric|paper  collapse order: a quadric of the linear scalar field and the\n"
    "                        boundary planes (default) or the paper's terms (6.1)\n"
    "  --weights G,V,E,L,N   weights of the paper's terms: scalar gradient, volume,\n"
    "                        equilateral, edge length, boundary normal (default 1,1,0.1,0.1,1)\n"
    "  --bits B              positions: bits per coordinate over the bounding box's longest\n"
    "                        side, 1..30 (default 16, or the fewest above that keep every\n"
    "                        tet positive)\n"
    "  --field-bits B        fields: bits over each field's range, 1..30 (default 16; a\n"
    "                        field of integers spanning fewer values is kept exactly)\n"
    "  --base-tets N         stop simplifying at N tets (default: as far as the rules allow)\n"
    "  --time-budget S       stop simplifying after S seconds (the stream stays valid)\n"
    "  --min-dihedral D      refuse collapses that make a tet with a dihedral angle below\n"
    "                        D degrees (for levels used in simulations; default off)\n"
    "  --no-intersection-test  skip the boundary self-intersection test (faster; levels\n"
    "                        may then fold their boundary through itself)\n"
    "  --quiet               no progress or notes on stderr\n"
    "  --help                this text\n"
    "\n"
    "Exit status: 0 done, 1 invalid input, 2 usage error, 3 file error.\n";

bool parseWeights(const std::string& text, double* w, int n) {
  size_t at = 0;
  for (int i = 0; i < n; ++i) {
    size_t comma = text.find(',', at);
    if ((comma == std::string::npos) != (i == n - 1)) return false;
    if (!parseDouble(text.substr(at, comma == std::string::npos ? std::string::npos : comma - at), &w[i]) || w[i] < 0)
      return false;
    at = comma + 1;
  }
  return true;
}

}  // namespace

bool isTetEncode(int argc, char** argv) {
  for (int i = 0; i < argc; ++i)
    if (std::strncmp(argv[i], "--", 2) != 0 && tetFormatOf(argv[i]) != TetFormat::kUnknown) return true;
  return false;
}

int runTetEncode(int argc, char** argv) {
  const char* cmd = "encode";
  Args args;
  std::string error;
  if (!args.parse(argc, argv,
                  {{"cost", "weights", "bits", "field-bits", "base-tets", "time-budget", "min-dihedral"},
                   {"no-intersection-test", "quiet", "help"},
                   {}},
                  &error))
    return fail(cmd, error + " (see 'mrsv encode --help' with a tet mesh IN)", kExitUsage);
  if (args.flag("help")) {
    std::fputs(kEncodeHelp, stdout);
    return kExitOk;
  }
  if (args.positional().size() != 2) return fail(cmd, "expected IN.{mesh,node,ele,vtu,vtk} and OUT.mrsv", kExitUsage);
  const std::string& in = args.positional()[0];
  const std::string& out = args.positional()[1];
  if (isSameFile(in, out)) return fail(cmd, "OUT is the same file as IN; refusing to overwrite the input", kExitUsage);
  const bool quiet = args.flag("quiet");

  TetSimplifyOptions simplify;
  uint64_t number = 0;
  int position_bits = 16, field_bits = 16;
  if (args.has("cost")) {
    if (args.value("cost") == "quadric") simplify.cost = TetCost::kQuadric;
    else if (args.value("cost") == "paper") simplify.cost = TetCost::kPaper;
    else return fail(cmd, "--cost must be quadric or paper", kExitUsage);
  }
  if (args.has("weights")) {
    double w[5];
    if (!parseWeights(args.value("weights"), w, 5))
      return fail(cmd, "--weights must be five non-negative numbers G,V,E,L,N", kExitUsage);
    simplify.weight_gradient = w[0];
    simplify.weight_volume = w[1];
    simplify.weight_equilateral = w[2];
    simplify.weight_edge_length = w[3];
    simplify.weight_normal = w[4];
  }
  if (args.has("bits")) {
    if (!parseUint64(args.value("bits"), &number) || number < 1 || number > 30)
      return fail(cmd, "--bits must be a whole number from 1 to 30", kExitUsage);
    position_bits = static_cast<int>(number);
  }
  if (args.has("field-bits")) {
    if (!parseUint64(args.value("field-bits"), &number) || number < 1 || number > 30)
      return fail(cmd, "--field-bits must be a whole number from 1 to 30", kExitUsage);
    field_bits = static_cast<int>(number);
  }
  if (args.has("base-tets") && !parseUint64(args.value("base-tets"), &simplify.min_base_tets))
    return fail(cmd, "--base-tets must be a whole number", kExitUsage);
  if (args.has("time-budget") &&
      (!parseDouble(args.value("time-budget"), &simplify.time_budget_seconds) || simplify.time_budget_seconds <= 0))
    return fail(cmd, "--time-budget must be a positive number of seconds", kExitUsage);
  if (args.has("min-dihedral") &&
      (!parseDouble(args.value("min-dihedral"), &simplify.min_dihedral_degrees) ||
       simplify.min_dihedral_degrees < 0 || simplify.min_dihedral_degrees >= 70.5))
    return fail(cmd, "--min-dihedral must be a number of degrees from 0 to 70.5", kExitUsage);
  simplify.boundary_intersection_test = !args.flag("no-intersection-test");

  TetMesh mesh;
  TetReadReport read_report;
  if (!readTetFile(in, &mesh, &read_report, &error)) return fail(cmd, error, kExitInvalidData);
  if (!quiet && read_report.flipped)
    std::fprintf(stderr, "mrsv encode: %s: %llu negatively oriented tets turned positive\n", in.c_str(),
                 static_cast<unsigned long long>(read_report.flipped));
  // Without --bits: 16, or the fewest bits above that keep every tet positive
  // (meshes with slivers flatten or invert some on a coarse grid).
  QuantizedTets quantized;
  Error quantize_error = quantizeTetMesh(mesh, position_bits, field_bits, &quantized);
  for (int bits = position_bits + 2; !quantize_error.ok() && !args.has("bits") && bits <= 30; bits += 2) {
    if (quantize_error.status != Status::kInvalidArgument || quantize_error.field != "tets") break;
    if (!quiet) std::fprintf(stderr, "mrsv encode: %s: %s; trying %d bits\n", in.c_str(), quantize_error.message.c_str(), bits);
    quantize_error = quantizeTetMesh(mesh, bits, field_bits, &quantized);
  }
  if (!quantize_error.ok())
    return fail(cmd, in + ": " + quantize_error.field + ": " + quantize_error.message, kExitInvalidData);
  QuantizedTetMesh input;
  input.positions = quantized.positions;
  input.tets = quantized.tets;
  for (const ScalarField& f : mesh.fields) input.fields.push_back(f.values);

  Progress progress("simplify", quiet);
  simplify.progress = [&](double f) { progress.update(0.9 * f); };
  auto start = std::chrono::steady_clock::now();
  TetSimplifyResult result;
  if (Error e = simplifyTets(input, simplify, &result); !e.ok())
    return fail(cmd, in + ": " + e.message, kExitInvalidData);
  auto simplified = std::chrono::steady_clock::now();
  std::vector<std::vector<PtCollapse>> batches(result.batches.size());
  for (size_t b = 0; b < batches.size(); ++b)
    for (const TetCollapse& c : result.batches[b]) batches[b].push_back(PtCollapse{c.vs, c.vt});
  std::vector<uint8_t> stream;
  PtStreamStats stats;
  if (Error e = writePtStream(quantized, batches, &stream, &stats); !e.ok())
    return fail(cmd, in + ": " + e.message, kExitInvalidData);
  auto encoded = std::chrono::steady_clock::now();
  progress.update(1.0);
  if (!writeFileAtomically(out, stream, &error)) return fail(cmd, out + ": " + error, kExitIo);
  if (!quiet) {
    auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    const TetSimplifyStats& s = result.stats;
    std::fprintf(stderr,
                 "mrsv encode: %s: %zu bytes; %zu vertices, %zu tets, %zu fields; base %llu vertices, %llu tets "
                 "(%llu bytes); %u splits in %u batches (%llu bytes, %.2f bits/split); simplify %.0f ms, "
                 "encode %.0f ms\n"
                 "mrsv encode: per split: %.2f bits of connectivity (%.2f flags in %.1f decisions, %.2f cut), %.2f of geometry; "
                 "%.2f bits per tet\n"
                 "mrsv encode: collapses evaded: %llu boundary table, %llu link condition, %llu inversion, "
                 "%llu degenerate, %llu min dihedral, %llu boundary self-intersection\n",
                 out.c_str(), stream.size(), mesh.positions.size(), mesh.tets.size(), mesh.fields.size(),
                 static_cast<unsigned long long>(stats.base_vertices),
                 static_cast<unsigned long long>(stats.base_tets), static_cast<unsigned long long>(stats.base_bytes),
                 stats.splits, stats.batches, static_cast<unsigned long long>(stats.split_bytes),
                 stats.splits ? 8.0 * stats.split_bytes / stats.splits : 0.0, ms(start, simplified),
                 ms(simplified, encoded), (stats.flag_bits + stats.cut_bits) / std::max(1u, stats.splits),
                 stats.flag_bits / std::max(1u, stats.splits),
                 double(stats.flag_decisions) / std::max(1u, stats.splits), stats.cut_bits / std::max(1u, stats.splits),
                 stats.value_bits / std::max(1u, stats.splits), 8.0 * stream.size() / std::max<size_t>(1, mesh.tets.size()),
                 static_cast<unsigned long long>(s.evaded_boundary_table),
                 static_cast<unsigned long long>(s.evaded_link), static_cast<unsigned long long>(s.evaded_inversion),
                 static_cast<unsigned long long>(s.evaded_degenerate),
                 static_cast<unsigned long long>(s.evaded_min_dihedral),
                 static_cast<unsigned long long>(s.evaded_self_intersection));
  }
  return kExitOk;
}

// mrsv decode for a PT stream: the level comes from --tets, --vertices or --fraction.
int runTetDecode(const Args& args, const std::string& in, const std::string& out, const TetDecodeFn& decode,
                 const DecodeOptions& options) {
  const char* cmd = "decode";
  std::string error;
  if (args.has("levels") || args.has("endian") || args.has("faces"))
    return fail(cmd, in + ": a PT stream takes --tets, --vertices or --fraction", kExitUsage);
  if (args.has("tets") + args.has("vertices") + args.has("fraction") > 1)
    return fail(cmd, "give at most one of --tets, --vertices and --fraction", kExitUsage);
  uint64_t number = 0;
  if (args.has("vertices") && !parseUint64(args.value("vertices"), &number))
    return fail(cmd, "--vertices must be a whole number", kExitUsage);
  if (args.has("tets") && !parseUint64(args.value("tets"), &number))
    return fail(cmd, "--tets must be a whole number", kExitUsage);
  const DecodeOptions limited = levelLimits(args, "tets", number, options);
  DecodedTetMesh decoded;
  auto start = std::chrono::steady_clock::now();
  if (Error e = decode(limited, &decoded); !e.ok())
    return reportError(cmd, in, e);
  auto done = std::chrono::steady_clock::now();
  ProgressiveTetMesh& pt = decoded.mesh;
  const uint32_t finest = pt.splitsDecoded();
  uint32_t level = finest;
  if (args.has("vertices")) {
    const uint64_t base = pt.header().base_vertex_count;
    level = number <= base ? 0 : static_cast<uint32_t>(std::min<uint64_t>(number - base, finest));
  } else if (args.has("tets") || args.has("fraction")) {
    uint64_t target = number;
    if (!args.has("tets")) {
      double f = 0;
      if (!parseDouble(args.value("fraction"), &f) || f < 0 || f > 1)
        return fail(cmd, "--fraction must be a number from 0 to 1", kExitUsage);
      target = static_cast<uint64_t>(std::floor(f * pt.tetCountAt(finest) + 1e-9));
    }
    level = pt.finestLevelWithin(target);
  }
  if (!decoded.has_mesh && !args.flag("canonical"))
    return fail(cmd, in + ": the stream ends before its base mesh (TBAS)", kExitInvalidData);
  pt.setLevel(level);
  std::vector<TetFileBytes> files;
  if (args.flag("canonical")) {
    files.push_back({out, canonicalTetMeshOutput(pt)});
  } else {
    TetWriteReport report;
    if (!encodeTetFile(out, pt.mesh(), TetWriteOptions{}, &files, &report, &error)) return fail(cmd, error, kExitUsage);
  }
  for (const TetFileBytes& f : files)
    if (!writeFileAtomically(f.path, f.bytes, &error)) return fail(cmd, f.path + ": " + error, kExitIo);
  if (!args.flag("quiet")) {
    std::fprintf(stderr, "mrsv decode: %s: level %u of %u: %u vertices, %u tets (decoded %u splits in %.1f ms)\n",
                 out.c_str(), level, decoded.header.splitCount(), pt.vertexCount(), pt.tetCount(), finest,
                 std::chrono::duration<double, std::milli>(done - start).count());
    if (decoded.stopped_early)
      std::fprintf(stderr, "mrsv decode: %s: decoded %u of %u batches (the level needs no more)\n", in.c_str(),
                   decoded.batches_decoded, decoded.header.batch_count);
    else if (!decoded.container.complete)
      std::fprintf(stderr, "mrsv decode: %s: note: stream is a prefix (no MEND); decoded %u of %u batches\n",
                   in.c_str(), decoded.batches_decoded, decoded.header.batch_count);
  }
  return kExitOk;
}

}  // namespace mrsv::cli
