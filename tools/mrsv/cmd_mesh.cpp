// mrsv encode / decode for triangle meshes: the PM stream (spec 6).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "cli.h"
#include "commands.h"
#include "mrsv/file_io.h"
#include "mrsv/mesh_formats.h"
#include "mrsv/mesh_repair.h"
#include "mrsv/progressive_mesh.h"
#include "pm/pm_encode.h"
#include "simplify/simplify.h"

namespace mrsv::cli {
namespace {

const char kEncodeHelp[] =
    "Usage: mrsv encode [options] IN.{obj,ply,off} OUT.mrsv\n"
    "\n"
    "Encode a triangle mesh as a progressive mesh (PM stream, spec 6): a base mesh and\n"
    "vertex splits, coarse to fine, so that any prefix decodes to a coarser mesh.\n"
    "The input is repaired first where a documented rule allows (degenerate and\n"
    "duplicate triangles dropped, orientation made consistent, non-manifold vertices\n"
    "split, unused vertices dropped); what was repaired is printed.\n"
    "\n"
    "Options:\n"
    "  --cost quadric|paper  collapse order: quadric error (Garland-Heckbert; default) or\n"
    "                        the paper's energies (normal, edge length, equilateral)\n"
    "  --weights N,E,Q       weights of the paper's energies (default 50,1,5: section 7.1)\n"
    "  --placement free|endpoint  where the kept vertex goes: moves to the volume-\n"
    "                        preserving quadric optimum (default; each split also codes\n"
    "                        the move) or stays (22 to 29 % smaller stream at 14 bits,\n"
    "                        about 1.8 times the RMS error at 1 % of the faces)\n"
    "  --move-detail M       free placement: a move of the kept vertex along its surface\n"
    "                        keeps M bits per longest edge around it, 1..30 (default 4),\n"
    "                        or 0: every quantisation step (a larger stream)\n"
    "  --free-from F         free placement: kept vertices move only once at most F\n"
    "                        of the input's vertices are left, 0..1 (default 0.7; 1:\n"
    "                        from the first collapse, a stream 3 to 14 % larger with\n"
    "                        the same error at 10 % and 1 % of the faces and up to\n"
    "                        1.6 times less RMS error above half of them)\n"
    "  --wide-batches F      while more than F of the input's vertices are left, batches\n"
    "                        take collapses up to 32 times the cheapest one's cost or the\n"
    "                        cheapest 20 %, so fewer split flags are coded; 0..1 (default\n"
    "                        1: never; 0.3: a stream 3 to 8 % smaller at 14 bits with the\n"
    "                        RMS error at 10 % and 1 % of the faces within 2 % and at\n"
    "                        80 % 1.2 to 1.3 times the default's)\n"
    "  --bits B              quantisation: bits per coordinate over the bounding box's\n"
    "                        longest side, 1..30 (default 16)\n"
    "  --scalar NAME         carry the PLY vertex property NAME as the per-vertex scalar\n"
    "  --scalar-bits B       quantisation of the scalar (default 16)\n"
    "  --base-faces N        stop simplifying at N triangles (default: as far as the\n"
    "                        consistency rules allow)\n"
    "  --time-budget S       stop simplifying after S seconds (the stream stays valid)\n"
    "  --meta KEY=VALUE      add a meta entry; repeatable\n"
    "  --quiet               no progress or notes on stderr\n"
    "  --help                this text\n"
    "\n"
    "Exit status: 0 done, 1 invalid input, 2 usage error, 3 file error.\n";

}  // namespace

bool isMeshEncode(int argc, char** argv) {
  for (int i = 0; i < argc; ++i)
    if (std::strncmp(argv[i], "--", 2) != 0 && meshFormatOf(argv[i]) != MeshFormat::kUnknown) return true;
  return false;
}

int runMeshEncode(int argc, char** argv) {
  const char* cmd = "encode";
  Args args;
  std::string error;
  if (!args.parse(argc, argv,
                  {{"cost", "weights", "placement", "move-detail", "free-from", "wide-batches", "bits", "scalar",
                    "scalar-bits", "base-faces", "time-budget"},
                   {"quiet", "help"},
                   {"meta"}},
                  &error))
    return fail(cmd, error + " (see 'mrsv encode --help' with a mesh IN)", kExitUsage);
  if (args.flag("help")) {
    std::fputs(kEncodeHelp, stdout);
    return kExitOk;
  }
  if (args.positional().size() != 2) return fail(cmd, "expected IN.{obj,ply,off} and OUT.mrsv", kExitUsage);
  const std::string& in = args.positional()[0];
  const std::string& out = args.positional()[1];
  if (isSameFile(in, out)) return fail(cmd, "OUT is the same file as IN; refusing to overwrite the input", kExitUsage);
  const bool quiet = args.flag("quiet");

  SimplifyOptions simplify;
  // Free placement by default: at 10 % and 1 % of the faces it halves the RMS
  // error of endpoint placement, which is worth the moves' bits (decision D22).
  simplify.placement = Placement::kFree;
  PmEncodeOptions encode;
  if (args.has("cost")) {
    if (args.value("cost") == "quadric") simplify.cost = CollapseCost::kQuadric;
    else if (args.value("cost") == "paper") simplify.cost = CollapseCost::kPaper;
    else return fail(cmd, "--cost must be quadric or paper", kExitUsage);
  }
  if (args.has("weights")) {
    double w[3];
    std::string v = args.value("weights");
    size_t p1 = v.find(','), p2 = p1 == std::string::npos ? p1 : v.find(',', p1 + 1);
    if (p2 == std::string::npos || !parseDouble(v.substr(0, p1), &w[0]) ||
        !parseDouble(v.substr(p1 + 1, p2 - p1 - 1), &w[1]) || !parseDouble(v.substr(p2 + 1), &w[2]) ||
        w[0] < 0 || w[1] < 0 || w[2] < 0)
      return fail(cmd, "--weights must be three non-negative numbers N,E,Q", kExitUsage);
    simplify.weight_normal = w[0];
    simplify.weight_edge_length = w[1];
    simplify.weight_equilateral = w[2];
  }
  if (args.has("placement")) {
    if (args.value("placement") == "endpoint") simplify.placement = Placement::kEndpoint;
    else if (args.value("placement") == "free") simplify.placement = Placement::kFree;
    else return fail(cmd, "--placement must be endpoint or free", kExitUsage);
  }
  encode.placement = simplify.placement;
  uint64_t number = 0;
  if (args.has("move-detail")) {
    if (!parseUint64(args.value("move-detail"), &number) || number > 30)
      return fail(cmd, "--move-detail must be a whole number from 0 to 30", kExitUsage);
    if (encode.placement != Placement::kFree)
      return fail(cmd, "--move-detail needs free placement (the default), not --placement endpoint", kExitUsage);
    encode.move_detail = static_cast<uint8_t>(number);
  }
  if (args.has("free-from")) {
    double fraction = 0.0;
    if (!parseDouble(args.value("free-from"), &fraction) || fraction < 0.0 || fraction > 1.0)
      return fail(cmd, "--free-from must be a number from 0 to 1", kExitUsage);
    if (encode.placement != Placement::kFree)
      return fail(cmd, "--free-from needs free placement (the default), not --placement endpoint", kExitUsage);
    simplify.free_placement_below = fraction;
  }
  if (args.has("wide-batches")) {
    double fraction = 0.0;
    if (!parseDouble(args.value("wide-batches"), &fraction) || fraction < 0.0 || fraction > 1.0)
      return fail(cmd, "--wide-batches must be a number from 0 to 1", kExitUsage);
    simplify.fine_vertex_fraction = fraction;
  }
  if (args.has("bits")) {
    if (!parseUint64(args.value("bits"), &number) || number < 1 || number > 30)
      return fail(cmd, "--bits must be a whole number from 1 to 30", kExitUsage);
    encode.position_bits = static_cast<uint8_t>(number);
  }
  if (args.has("scalar-bits")) {
    if (!parseUint64(args.value("scalar-bits"), &number) || number < 1 || number > 30)
      return fail(cmd, "--scalar-bits must be a whole number from 1 to 30", kExitUsage);
    encode.scalar_bits = static_cast<uint8_t>(number);
  }
  if (args.has("base-faces") && !parseUint64(args.value("base-faces"), &simplify.target_triangles))
    return fail(cmd, "--base-faces must be a whole number", kExitUsage);
  if (args.has("time-budget") &&
      (!parseDouble(args.value("time-budget"), &simplify.time_budget_seconds) ||
       simplify.time_budget_seconds <= 0))
    return fail(cmd, "--time-budget must be a positive number of seconds", kExitUsage);
  Metadata metadata;
  if (!parseMetaOptions(args, &metadata, &error)) return fail(cmd, error, kExitUsage);

  TriangleMesh mesh;
  if (!readMeshFile(in, args.has("scalar") ? args.value("scalar") : "", &mesh, &error))
    return fail(cmd, error, kExitInvalidData);
  MeshRepairReport repair;
  std::vector<uint32_t> origin;
  if (!repairMesh(&mesh, MeshRepairOptions{}, &repair, &origin, &error))
    return fail(cmd, in + ": " + error, kExitInvalidData);
  if (!quiet) std::fprintf(stderr, "mrsv encode: %s: %s\n", in.c_str(), describe(repair).c_str());

  Progress progress("simplify", quiet);
  simplify.progress = [&](double f) { progress.update(0.9 * f); };
  auto start = std::chrono::steady_clock::now();
  SimplifyResult collapses;
  if (!simplifyMesh(mesh, simplify, &collapses, &error)) return fail(cmd, in + ": " + error, kExitInvalidData);
  auto simplified = std::chrono::steady_clock::now();
  std::vector<uint8_t> stream;
  PmEncodeReport report;
  if (!encodeProgressiveMesh(mesh, collapses, encode, metadata, &stream, &report, &error))
    return fail(cmd, in + ": " + error, kExitInvalidData);
  auto encoded = std::chrono::steady_clock::now();
  progress.update(1.0);
  if (!writeFileAtomically(out, stream, &error)) return fail(cmd, out + ": " + error, kExitIo);
  if (!quiet) {
    auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    std::fprintf(stderr,
                 "mrsv encode: %s: %zu bytes; base %u vertices, %u triangles (%llu bytes); %u splits in "
                 "%u batches (%llu bytes, %.2f bits/split); simplify %.0f ms, encode %.0f ms\n",
                 out.c_str(), stream.size(), report.base_vertices, report.base_triangles,
                 static_cast<unsigned long long>(report.base_bytes), report.splits, report.batches,
                 static_cast<unsigned long long>(report.split_bytes),
                 report.splits ? 8.0 * report.split_bytes / report.splits : 0.0, ms(start, simplified),
                 ms(simplified, encoded));
  }
  return kExitOk;
}

// mrsv decode for a PM stream: the level comes from --faces, --vertices or --fraction.
int runMeshDecode(const Args& args, const std::string& in, const std::string& out,
                  const MeshDecodeFn& decode, const DecodeOptions& options) {
  const char* cmd = "decode";
  std::string error;
  if (args.has("levels") || args.has("endian") || args.has("tets"))
    return fail(cmd, in + ": --levels, --endian and --tets are not for PM streams; a PM stream takes --faces, "
                     "--vertices or --fraction",
                kExitUsage);
  int chosen = args.has("faces") + args.has("vertices") + args.has("fraction");
  if (chosen > 1) return fail(cmd, "give at most one of --faces, --vertices and --fraction", kExitUsage);
  uint64_t number = 0;
  if (args.has("vertices") && !parseUint64(args.value("vertices"), &number))
    return fail(cmd, "--vertices must be a whole number", kExitUsage);
  if (args.has("faces") && !parseUint64(args.value("faces"), &number))
    return fail(cmd, "--faces must be a whole number", kExitUsage);
  const DecodeOptions limited = levelLimits(args, "faces", number, options);
  DecodedMesh decoded;
  auto start = std::chrono::steady_clock::now();
  if (Error e = decode(limited, &decoded); !e.ok())
    return reportError(cmd, in, e);
  auto done = std::chrono::steady_clock::now();
  if (!decoded.has_mesh) {
    // spec 6.8: a prefix without PBAS has the canonical output of an empty level.
    if (!args.flag("canonical"))
      return fail(cmd, in + ": the stream ends before its base mesh (PBAS)", kExitInvalidData);
    if (!writeFileAtomically(out, canonicalMeshOutput(decoded.mesh), &error))
      return fail(cmd, out + ": " + error, kExitIo);
    return kExitOk;
  }
  ProgressiveMesh& pm = decoded.mesh;
  const uint32_t finest = pm.splitsDecoded();
  uint32_t level = finest;
  if (args.has("vertices")) {
    uint64_t base = pm.header().base_vertex_count;
    level = number <= base ? 0 : static_cast<uint32_t>(std::min<uint64_t>(number - base, finest));
  } else if (args.has("faces") || args.has("fraction")) {
    uint64_t target = number;
    if (!args.has("faces")) {
      double f = 0;
      if (!parseDouble(args.value("fraction"), &f) || f < 0 || f > 1)
        return fail(cmd, "--fraction must be a number from 0 to 1", kExitUsage);
      // A fraction of the full mesh's triangles (of the stream's finest level here).
      target = static_cast<uint64_t>(std::floor(f * pm.triangleCountAt(finest) + 1e-9));
    }
    level = pm.finestLevelWithin(target);
  }
  pm.setLevel(level);
  std::vector<uint8_t> output;
  if (args.flag("canonical")) {
    output = canonicalMeshOutput(pm);
  } else if (!encodeMeshFile(out, pm.mesh(), &output, &error)) {
    return fail(cmd, error, kExitUsage);
  }
  if (!writeFileAtomically(out, output, &error)) return fail(cmd, out + ": " + error, kExitIo);
  if (!args.flag("quiet")) {
    std::fprintf(stderr, "mrsv decode: %s: level %u of %u: %u vertices, %u triangles (decoded %u splits in %.1f ms)\n",
                 out.c_str(), level, decoded.header.splitCount(), pm.vertexCount(), pm.triangleCount(), finest,
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
