// mrsv mesh: an adaptive mesh of a grid stream by one of the reconstructors
// of spec 8 (Delaunay vertex insertion, 2-D and 3-D; quadtree vertex removal,
// 2-D).
#include <chrono>
#include <cstdio>
#include <memory>

#include "cli.h"
#include "commands.h"
#include "mrsv/file_io.h"
#include "mrsv/grid_mesh.h"
#include "mrsv/mesh_formats.h"
#include "mrsv/quadtree_mesh.h"
#include "mrsv/tiled_grid.h"
#include "mrsv/terrain_insertion.h"
#include "mrsv/volume_insertion.h"
#include "mrsv/tet_formats.h"

namespace mrsv::cli {
namespace {

const char kMeshHelp[] =
    "Usage: mrsv mesh [options] IN.mrsv OUT\n"
    "\n"
    "An adaptive mesh of a grid stream (spec 8): a TIN of a 2-D grid (OUT .obj, .ply\n"
    "with the sample as a vertex property, .off) or a tet mesh of a 3-D grid (OUT\n"
    ".vtu, .vtk, .mesh, .node; the sample as the field 'value'). x, y (and z) come\n"
    "from the stream's 'spacing' and 'origin' meta entries, heights from the samples.\n"
    "Every decision is exact integer arithmetic on the decoded samples, so the mesh\n"
    "is the same in every conforming implementation (--canonical writes the bytes\n"
    "the conformance suite hashes). No-data samples take the value the wavelet\n"
    "synthesis gives them.\n"
    "\n"
    "Options:\n"
    "  --method insertion|quadtree  Delaunay vertex insertion (default; 2-D and 3-D) or\n"
    "                        quadtree vertex removal (2-D)\n"
    "  --max-error E         every sample within E (sample units, a decimal such as\n"
    "                        20 or 0.5) of the mesh\n"
    "  --triangles N         2-D: stop at N triangles (insertion) or the finest mesh\n"
    "                        with at most N (quadtree)\n"
    "  --tets N              3-D: stop at N tets\n"
    "  --epsilon X           quadtree: the paper's wavelet criterion threshold\n"
    "  --remove-vertices     2-D: after the mesh, remove every inner vertex whose star\n"
    "                        can be re-triangulated within E (spec 9.7: one pass after\n"
    "                        the quadtree over links of at most 6 points, sharply bent\n"
    "                        points staying, 0.90 to 1.21 x insertion's triangles for\n"
    "                        1.9 to 2.8 x the tree's time; 8.8: passes until none\n"
    "                        leaves after insertion, which then needs --max-error and\n"
    "                        no --progressive, 0.5 to 0.85 x its triangles)\n"
    "  --distance mesh|trilinear  3-D insertion: a sample's distance to the current\n"
    "                        mesh (default; fewer tets at the same error, D62) or the\n"
    "                        paper's, to the trilinear interpolant of its cell\n"
    "                        (needs --max-error)\n"
    "  --progressive         insertion: refine level by level as the stream's bands\n"
    "                        come (spec 8.7) instead of once from the whole prefix\n"
    "  --no-border-rule      insertion, 2-D: let the greedy choice place the vertices\n"
    "                        of the sides too (by default each side is refined from its\n"
    "                        own samples, so that adjacent tiles meet without cracks)\n"
    "  --no-border-cleanup   insertion, 2-D: keep the Delaunay mesh as inserted (by\n"
    "                        default, with the border rule and --max-error and without\n"
    "                        --progressive, the inner vertices next to the sides are\n"
    "                        then tried once for removal, spec 8.8, winning back the\n"
    "                        triangles the border rule costs)\n"
    "  --bytes N             read only the first N bytes of IN, as if the rest had not\n"
    "                        arrived\n"
    "  --levels K            use the stream without its K finest levels\n"
    "  --region X0,Y0[,Z0],X1,Y1[,Z1]\n"
    "                        mesh only the samples of this half-open box (a tiled\n"
    "                        stream reads only the tiles it touches; spec 8.1): two\n"
    "                        boxes sharing a side meet without cracks (border rule)\n"
    "  --z-scale S           2-D: heights are sample x S (default 1)\n"
    "  --canonical           write the canonical output of spec 8.2 instead of a mesh\n"
    "  --quiet               no progress or summary on stderr\n"
    "  --help                this text\n"
    "\n"
    "Exit status: 0 success, 1 invalid input data, 2 usage error, 3 file error.\n";

struct MeshRequest {
  std::string method = "insertion";
  InsertionLimits limits;
  bool progressive = false;
  bool quiet = false;
};

bool isTriangleFormat(const std::string& path) {
  for (const char* ext : {".obj", ".ply", ".off"})
    if (path.size() > 4 && path.compare(path.size() - 4, 4, ext) == 0) return true;
  return false;
}

}  // namespace

int runMesh(int argc, char** argv) {
  const char* cmd = "mesh";
  Args args;
  std::string error;
  if (!args.parse(argc, argv,
                  {{"method", "max-error", "triangles", "tets", "epsilon", "bytes", "levels", "z-scale", "distance", "region"},
                   {"progressive", "no-border-rule", "no-border-cleanup", "remove-vertices", "canonical", "quiet", "help"},
                   {}},
                  &error))
    return fail(cmd, error + " (see 'mrsv mesh --help')", kExitUsage);
  if (args.flag("help")) {
    std::fputs(kMeshHelp, stdout);
    return kExitOk;
  }
  if (args.positional().size() != 2) return fail(cmd, "expected IN.mrsv and OUT", kExitUsage);
  const std::string in = args.positional()[0], out = args.positional()[1];
  if (isSameFile(in, out)) return fail(cmd, "OUT is the same file as IN; refusing to overwrite the input", kExitUsage);

  MeshRequest req;
  req.quiet = args.flag("quiet");
  if (args.has("method")) req.method = args.value("method");
  if (req.method != "insertion" && req.method != "quadtree")
    return fail(cmd, "--method must be insertion or quadtree", kExitUsage);
  if (args.has("max-error") && !parseErrorBound(args.value("max-error"), &req.limits.max_error))
    return fail(cmd, "--max-error must be a decimal from 0 to 2147483648 with at most 9 decimals", kExitUsage);
  if (args.has("triangles") && args.has("tets")) return fail(cmd, "give --triangles or --tets, not both", kExitUsage);
  for (const char* name : {"triangles", "tets"})
    if (args.has(name) && (!parseUint64(args.value(name), &req.limits.max_cells) || req.limits.max_cells == 0))
      return fail(cmd, std::string("--") + name + " must be a positive whole number", kExitUsage);
  if (!req.limits.max_error.set() && req.limits.max_cells == 0 && !args.has("epsilon"))
    return fail(cmd, "give --max-error, --triangles, --tets or --epsilon", kExitUsage);
  req.limits.border_rule = !args.flag("no-border-rule");
  req.progressive = args.flag("progressive");
  if (req.method == "quadtree" && req.progressive)
    return fail(cmd, "--progressive is for --method insertion (the quadtree is built bottom-up from the finest level)",
                kExitUsage);
  if (req.method == "insertion" && args.has("epsilon"))
    return fail(cmd, "--epsilon is for --method quadtree", kExitUsage);
  const bool remove_vertices = args.flag("remove-vertices");
  if (remove_vertices && req.method == "quadtree" && args.has("epsilon"))
    return fail(cmd, "--remove-vertices needs --max-error or --triangles, not --epsilon", kExitUsage);
  GridRegion region;
  const bool by_region = args.has("region");
  if (by_region && !parseRegionBox(args.value("region"), &region, &error)) return fail(cmd, error, kExitUsage);
  if (by_region && (req.progressive || args.has("levels") || args.has("epsilon")))
    return fail(cmd, "--region meshes the region's samples once: not with --progressive, --levels or --epsilon",
                kExitUsage);
  uint64_t byte_limit = UINT64_MAX, levels = 0;
  if (args.has("bytes") && !parseUint64(args.value("bytes"), &byte_limit))
    return fail(cmd, "--bytes must be a whole number", kExitUsage);
  if (args.has("levels") && (!parseUint64(args.value("levels"), &levels) || levels > 16))
    return fail(cmd, "--levels must be a whole number from 0 to 16", kExitUsage);
  double z_scale = 1;
  if (args.has("z-scale") && !parseDouble(args.value("z-scale"), &z_scale))
    return fail(cmd, "--z-scale must be a number", kExitUsage);
  const bool canonical = args.flag("canonical");
  const std::string distance = args.has("distance") ? args.value("distance") : "mesh";
  if (distance != "mesh" && distance != "trilinear") return fail(cmd, "--distance must be mesh or trilinear", kExitUsage);

  // A region of a whole file reads through the file (a tiled stream: the tiles
  // the box touches); anything else reads the bytes first.
  std::vector<uint8_t> bytes;
  std::unique_ptr<ByteSource> file_source;
  if (by_region && !args.has("bytes")) {
    file_source = openFileByteSource(in, &error);
    if (!file_source) return fail(cmd, in + ": " + error, kExitIo);
  } else if (!readWholeFile(in, &bytes, &error)) {
    return fail(cmd, in + ": " + error, kExitIo);
  }
  DecodeOptions options;
  options.void_values = true;
  if (byte_limit < bytes.size()) {
    // As if the rest had not arrived: an incomplete last chunk is ignored (2.5.1).
    bytes.resize(byte_limit);
    options.container.allow_partial_tail = true;
  }
  DecodedGrid grid;
  if (by_region) {
    // spec 8.1: the field is the region decode's (11.5), a grid of the box's sizes.
    MemoryByteSource memory(bytes.data(), bytes.size());
    ByteSource& source = file_source ? *file_source : memory;
    if (Error e = decodeGridRegion(source, region, options, &grid); !e.ok()) {
      if (e.status == Status::kInvalidArgument)
        return fail(cmd, in + ": --region " + args.value("region") + ": " + e.message, kExitUsage);
      return reportError(cmd, in, e);
    }
    grid.header.size_x = grid.output_size[0];
    grid.header.size_y = grid.output_size[1];
    grid.header.size_z = grid.output_size[2];
  } else if (Error e = decodeGrid(bytes.data(), bytes.size(), options, &grid); !e.ok()) {
    return reportError(cmd, in, e);
  }
  if (!grid.has_samples) return fail(cmd, in + ": the stream holds no samples yet (no band in the bytes read)", kExitInvalidData);
  const int dims = grid.header.num_dims;
  if (dims == 3 && req.method == "quadtree")
    return fail(cmd, in + ": the quadtree reconstructor meshes 2-D grids; use --method insertion", kExitUsage);
  if (dims == 2 && args.has("tets")) return fail(cmd, in + ": a 2-D grid gives triangles: use --triangles", kExitUsage);
  if (dims == 3 && args.has("triangles")) return fail(cmd, in + ": a 3-D grid gives tets: use --tets", kExitUsage);
  if (dims == 2 && args.has("distance")) return fail(cmd, in + ": --distance is for 3-D grids", kExitUsage);
  if (dims == 3 && remove_vertices) return fail(cmd, in + ": --remove-vertices is for 2-D grids", kExitUsage);
  if (remove_vertices && req.method == "insertion" && (!req.limits.max_error.set() || req.progressive))
    return fail(cmd, "--remove-vertices with --method insertion needs --max-error and no --progressive (spec 8.8)",
                kExitUsage);
  // spec 10.6: the paper's pass inserts what exceeds E; without E it has nothing to
  // compare with, and the mesh would silently be the `mesh` distance's.
  if (distance == "trilinear" && !args.has("max-error"))
    return fail(cmd, "--distance trilinear needs --max-error (the paper's pass compares with E)", kExitUsage);
  if (!canonical && dims == 2 && !isTriangleFormat(out))
    return fail(cmd, out + ": a 2-D grid gives a triangle mesh: write .obj, .ply or .off", kExitUsage);
  if (!canonical && dims == 3 && isTriangleFormat(out))
    return fail(cmd, out + ": a 3-D grid gives a tet mesh: write .vtu, .vtk, .mesh or .node", kExitUsage);

  // spec 8.7: the stages, less the K finest levels.
  // A region: one stage on the bytes already decoded (its `bytes` equal to
  // bytes.size(), so that no prefix is decoded again).
  std::vector<ReconstructionStage> stages =
      by_region ? std::vector<ReconstructionStage>{{bytes.size(), 0}}
                : reconstructionStages(grid, bytes.size(), unsigned(levels));
  if (stages.empty() && grid.header.coding == GridCoding::kTiled)
    return fail(cmd, in + ": --levels is not defined for tiled grids in this version (spec 8.7 stages are the "
                          "levels of one wavelet pyramid); mesh the whole grid or decode --levels first",
                kExitUsage);
  if (stages.empty())
    return fail(cmd, in + ": --levels " + std::to_string(levels) + " leaves no complete level in the bytes read",
                kExitInvalidData);
  if (!req.progressive) stages.erase(stages.begin(), stages.end() - 1);

  const auto start = std::chrono::steady_clock::now();
  GridMesh mesh;
  if (req.method == "insertion") {
    // The same stages for both dimensions (spec 8.7, 10.7).
    std::unique_ptr<TerrainInserter> terrain;
    std::unique_ptr<VolumeInserter> volume;
    if (dims == 2) {
      terrain = std::make_unique<TerrainInserter>(grid.header.size_x, grid.header.size_y);
    } else {
      volume = std::make_unique<VolumeInserter>(grid.header.size_x, grid.header.size_y, grid.header.size_z);
      volume->setDistance(distance == "trilinear" ? VolumeDistance::kTrilinear : VolumeDistance::kMesh);
    }
    SampleField field;  // the last stage's, for the removal pass
    for (size_t k = 0; k < stages.size(); ++k) {
      DecodedGrid prefix;
      const DecodedGrid* source = &grid;
      if (stages[k].bytes != bytes.size()) {
        if (Error e = decodeGrid(bytes.data(), stages[k].bytes, options, &prefix); !e.ok())
          return reportError(cmd, in, e);
        source = &prefix;
      }
      if (!sampleFieldFromGrid(*source, &field, &error)) return fail(cmd, in + ": " + error, kExitInvalidData);
      Progress progress("mesh", req.quiet);
      const uint64_t goal = req.limits.max_cells;
      const auto report = [&](uint64_t cells) {
        if (goal) progress.update(double(cells) / double(goal));
        else progress.count(cells, dims == 2 ? "triangles" : "tets");
        return true;
      };
      const bool refined = terrain ? terrain->refine(field, stages[k].shift, req.limits, &error, report)
                                   : volume->refine(field, stages[k].shift, req.limits, &error, report);
      if (!refined) return fail(cmd, in + ": " + error, kExitInvalidData);
      if (!req.quiet && stages.size() > 1) {
        double max_error = 0;
        if (terrain) {
          max_error = terrain->maxError();
        } else {
          int64_t num = 0, den = 1;
          volume->maxError(&num, &den);
          max_error = double(num) / double(den);
        }
        std::fprintf(stderr, "mrsv mesh: stage %zu of %zu (%llu bytes, lattice step %u): %llu %s, max error %.4g\n",
                     k + 1, stages.size(), (unsigned long long)stages[k].bytes, 1u << stages[k].shift,
                     (unsigned long long)(terrain ? terrain->cellCount() : volume->cellCount()),
                     dims == 2 ? "triangles" : "tets", max_error);
      }
    }
    if (terrain) terrain->mesh(&mesh);
    else volume->mesh(&mesh);
    if (remove_vertices) {
      uint64_t removed = 0;
      if (!removeInnerVertices(field, req.limits.max_error, &mesh, &removed, &error))
        return fail(cmd, in + ": " + error, kExitInvalidData);
      if (!req.quiet) std::fprintf(stderr, "mrsv mesh: %llu vertices removed after insertion\n", (unsigned long long)removed);
    } else if (dims == 2 && borderCleanupApplies(req.limits, req.progressive) && !args.flag("no-border-cleanup")) {
      uint64_t removed = 0;
      if (!cleanBorderZone(field, req.limits.max_error, &mesh, &removed, &error))
        return fail(cmd, in + ": " + error, kExitInvalidData);
      if (!req.quiet)
        std::fprintf(stderr, "mrsv mesh: %llu vertices removed next to the sides (border cleanup)\n",
                     (unsigned long long)removed);
    }
  } else if (req.method == "quadtree") {
    // The quadtree is bottom-up (paper 4): one stage, the last.
    const uint64_t stage_bytes = stages.back().bytes;
    SampleField field;
    QuadtreeDetails details;
    QuadtreeOptions qt;
    if (args.has("epsilon")) {
      qt.criterion = QuadtreeCriterion::kWavelet;
      if (!parseErrorBound(args.value("epsilon"), &qt.threshold))
        return fail(cmd, "--epsilon must be a decimal from 0 to 2147483648 with at most 9 decimals", kExitUsage);
      if (req.limits.max_error.set()) return fail(cmd, "give --epsilon or --max-error, not both", kExitUsage);
      if (!quadtreeDetailsFromStream(bytes.data(), stage_bytes, options, &field, &details, &error))
        return fail(cmd, in + ": " + error, kExitInvalidData);
    } else {
      DecodedGrid prefix;
      const DecodedGrid* source = &grid;
      if (stage_bytes != bytes.size()) {
        if (Error e = decodeGrid(bytes.data(), stage_bytes, options, &prefix); !e.ok()) return reportError(cmd, in, e);
        source = &prefix;
      }
      if (!sampleFieldFromGrid(*source, &field, &error)) return fail(cmd, in + ": " + error, kExitInvalidData);
      qt.threshold = req.limits.max_error;
      qt.tile_borders = req.limits.max_error.set() && req.limits.border_rule && field.size[0] >= 4 && field.size[1] >= 4;
    }
    qt.max_triangles = req.limits.max_cells;
    qt.remove_vertices = remove_vertices;
    QuadtreeReport report;
    if (!quadtreeMesh(field, args.has("epsilon") ? &details : nullptr, qt, &mesh, &error, &report))
      return fail(cmd, in + ": " + error, kExitInvalidData);
    if (!req.quiet && qt.max_triangles)
      std::fprintf(stderr, "mrsv mesh: quadtree threshold %lld/%lld for at most %llu triangles\n",
                   (long long)report.threshold.num, (long long)report.threshold.den, (unsigned long long)qt.max_triangles);
    if (!req.quiet && qt.remove_vertices)
      std::fprintf(stderr, "mrsv mesh: %llu vertices removed after the quadtree in %u passes\n",
                   (unsigned long long)report.vertices_removed, report.removal_passes);
  } else {
    return fail(cmd, in + ": --method " + req.method + " on a " + std::to_string(dims) + "-D grid is not available in this build",
                kExitUsage);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (canonical) {
    if (!writeFileAtomically(out, canonicalGridMeshOutput(mesh), &error)) return fail(cmd, out + ": " + error, kExitIo);
  } else {
    GridMeshGeometry geometry;
    geometry.z_scale = z_scale;
    if (!gridMeshGeometryFromMetadata(grid.metadata, dims, &geometry, &error))
      return fail(cmd, in + ": " + error, kExitInvalidData);
    if (by_region)  // positions in the whole grid's frame, so that adjacent regions meet
      for (int a = 0; a < 3; ++a) geometry.origin[a] += double(region.lo[a]) * geometry.spacing[a];
    if (dims == 2) {
      TriangleMesh tin = gridMeshToTriangles(mesh, geometry);
      if (out.size() < 4 || out.compare(out.size() - 4, 4, ".ply") != 0) tin.scalars.clear();
      std::vector<uint8_t> file;
      if (!encodeMeshFile(out, tin, &file, &error)) return fail(cmd, out + ": " + error, kExitUsage);
      if (!writeFileAtomically(out, file, &error)) return fail(cmd, out + ": " + error, kExitIo);
    } else {
      TetWriteReport report;
      if (!writeTetFile(out, gridMeshToTets(mesh, geometry), TetWriteOptions{}, &report, &error))
        return fail(cmd, out + ": " + error, kExitIo);
    }
  }
  if (!req.quiet)
    std::fprintf(stderr, "mrsv mesh: %s, %s: %zu vertices, %zu %s in %.3f s\n", in.c_str(), req.method.c_str(),
                 mesh.points.size(), mesh.cells.size(), dims == 2 ? "triangles" : "tets", seconds);
  return kExitOk;
}

}  // namespace mrsv::cli
