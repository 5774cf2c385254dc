// mrsv compare: Metro-like distances between two triangle meshes.
#include <cstdio>
#include <string>
#include <vector>

#include "cli.h"
#include "commands.h"
#include "metrics/surface_distance.h"
#include "mrsv/file_io.h"
#include "mrsv/mesh_formats.h"

namespace mrsv::cli {
namespace {

const char kHelp[] =
    "Usage: mrsv compare [options] A B\n"
    "\n"
    "Two tet meshes (.mesh, .node/.ele, .vtu, .vtk): the first field of A against B's\n"
    "field of the same name at --samples random positions spread over A's volume (PSNR\n"
    "over A's range, max, mean, RMS; the paper's 7.2 measure), the volumes, the distance\n"
    "between the boundary surfaces, and each mesh's dihedral angles and validity\n"
    "(inverted or flat tets, manifold, boundary self-intersections); --json for one object.\n"
    "\n"
    "Two triangle meshes:\n"
    "Measure how far apart two triangle meshes are, as Metro does: sample each\n"
    "surface densely (every vertex, points along every edge, stratified points\n"
    "inside the triangles in proportion to their area) and find for each sample\n"
    "the closest point of the other surface. A and B are .obj, .ply or .off files.\n"
    "Triangles of (numerically) zero area are not part of a surface.\n"
    "\n"
    "Reported for A -> B (samples of A, distances to B) and B -> A:\n"
    "  max     the one-sided Hausdorff distance (largest over all samples)\n"
    "  mean    the mean distance over the surface (area-proportional samples)\n"
    "  rms     the root mean square distance (area-proportional samples)\n"
    "and symmetric figures: Hausdorff = the larger max; mean and rms = the larger\n"
    "of the two directions (Metro's convention). Every figure is also given\n"
    "relative to the bounding-box diagonal of A.\n"
    "\n"
    "Options:\n"
    "  --samples N   samples per surface (default 1000000). All vertices are always\n"
    "                samples; when they are more than N/2, the total is V + N/2\n"
    "  --seed S      seed of the sample jitter (default 1); same seed, same result\n"
    "  --threads T   worker threads (default: all cores); results do not depend on it\n"
    "  --json        one JSON object on stdout instead of the table\n"
    "  --quiet       no progress output\n"
    "  --help        this text\n"
    "\n"
    "JSON fields:\n"
    "  a, b                  {file, vertices, triangles}\n"
    "  samples_requested, seed\n"
    "  bbox_diagonal         of A (vertices of its non-degenerate triangles)\n"
    "  a_to_b, b_to_a        {max, mean, rms, samples, area_samples, max_at: [x, y, z],\n"
    "                         max_relative, mean_relative, rms_relative}\n"
    "  hausdorff, mean, rms  symmetric figures\n"
    "  hausdorff_relative, mean_relative, rms_relative\n"
    "Relative figures are the absolute ones divided by bbox_diagonal.\n"
    "\n"
    "Exit status: 0 done, 1 a mesh has no usable surface or cannot be parsed,\n"
    "2 usage error, 3 file error.\n";

// More samples than this would take tens of gigabytes.
constexpr uint64_t kMaxSamples = 1000000000;

struct Input {
  std::string file;
  TriangleMesh mesh;
};

// Reads and checks one mesh; returns an exit status (kExitOk when usable).
int load(const std::string& file, Input* in) {
  in->file = file;
  const MeshFormat format = meshFormatOf(file);
  if (format == MeshFormat::kUnknown)
    return fail("compare", file + ": unknown mesh format (the name must end in .obj, .ply or .off)",
                kExitUsage);
  std::vector<uint8_t> bytes;
  std::string error;
  if (!readWholeFile(file, &bytes, &error)) return fail("compare", file + ": " + error, kExitIo);
  // readMeshBytes names the file in its message.
  if (!readMeshBytes(file, format, bytes.data(), bytes.size(), "", &in->mesh, &error))
    return fail("compare", error, kExitInvalidData);
  if (!checkSurfaceMesh(in->mesh, &error))
    return fail("compare", file + ": " + error, kExitInvalidData);
  return kExitOk;
}

void printDirectionJson(const char* name, const OneSidedDistance& d, const SurfaceDistanceReport& r,
                        bool last) {
  std::printf("  \"%s\": {\"max\": %.17g, \"mean\": %.17g, \"rms\": %.17g, \"samples\": %llu, "
              "\"area_samples\": %llu, \"max_at\": [%.17g, %.17g, %.17g], \"max_relative\": %.17g, "
              "\"mean_relative\": %.17g, \"rms_relative\": %.17g}%s\n",
              name, d.max, d.mean, d.rms, static_cast<unsigned long long>(d.samples),
              static_cast<unsigned long long>(d.area_samples), d.max_at[0], d.max_at[1],
              d.max_at[2], r.relative(d.max), r.relative(d.mean), r.relative(d.rms),
              last ? "" : ",");
}

void printJson(const Input& a, const Input& b, const SurfaceDistanceOptions& o,
               const SurfaceDistanceReport& r) {
  std::printf("{\n");
  for (const Input* in : {&a, &b})
    std::printf("  \"%s\": {\"file\": %s, \"vertices\": %zu, \"triangles\": %zu},\n",
                in == &a ? "a" : "b", jsonString(in->file).c_str(), in->mesh.positions.size(),
                in->mesh.triangles.size());
  std::printf("  \"samples_requested\": %llu,\n  \"seed\": %llu,\n  \"bbox_diagonal\": %.17g,\n",
              static_cast<unsigned long long>(o.sampling.sample_count),
              static_cast<unsigned long long>(o.sampling.seed), r.bbox_diagonal);
  printDirectionJson("a_to_b", r.a_to_b, r, false);
  printDirectionJson("b_to_a", r.b_to_a, r, false);
  std::printf("  \"hausdorff\": %.17g,\n  \"mean\": %.17g,\n  \"rms\": %.17g,\n", r.hausdorff,
              r.mean, r.rms);
  std::printf("  \"hausdorff_relative\": %.17g,\n  \"mean_relative\": %.17g,\n"
              "  \"rms_relative\": %.17g\n}\n",
              r.relative(r.hausdorff), r.relative(r.mean), r.relative(r.rms));
}

void printTable(const Input& a, const Input& b, const SurfaceDistanceReport& r) {
  for (const Input* in : {&a, &b})
    std::printf("%s: %s (%zu vertices, %zu triangles)\n", in == &a ? "A" : "B", in->file.c_str(),
                in->mesh.positions.size(), in->mesh.triangles.size());
  std::printf("bounding-box diagonal of A: %.6g\n\n", r.bbox_diagonal);
  std::printf("%-10s %9s  %-12s %-12s %-12s  %-10s %-10s %-10s\n", "", "samples", "max", "mean",
              "rms", "max/diag", "mean/diag", "rms/diag");
  auto row = [&](const char* name, const std::string& samples, double max, double mean,
                 double rms) {
    std::printf("%-10s %9s  %-12.6g %-12.6g %-12.6g  %-10.4g %-10.4g %-10.4g\n", name,
                samples.c_str(), max, mean, rms, r.relative(max), r.relative(mean),
                r.relative(rms));
  };
  row("A -> B", std::to_string(r.a_to_b.samples), r.a_to_b.max, r.a_to_b.mean, r.a_to_b.rms);
  row("B -> A", std::to_string(r.b_to_a.samples), r.b_to_a.max, r.b_to_a.mean, r.b_to_a.rms);
  row("symmetric", "", r.hausdorff, r.mean, r.rms);
}

}  // namespace

int runCompare(int argc, char** argv) {
  const char* cmd = "compare";
  Args args;
  std::string error;
  if (!args.parse(argc, argv, {{"samples", "seed", "threads"}, {"json", "quiet", "help"}, {}},
                  &error))
    return fail(cmd, error + " (see 'mrsv compare --help')", kExitUsage);
  if (args.flag("help")) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  if (args.positional().size() != 2)
    return fail(cmd, "expected two mesh files A and B (see 'mrsv compare --help')", kExitUsage);

  SurfaceDistanceOptions options;
  uint64_t value = 0;
  if (args.has("samples")) {
    if (!parseUint64(args.value("samples"), &value) || value == 0 || value > kMaxSamples)
      return fail(cmd, "--samples must be a whole number from 1 to 1000000000", kExitUsage);
    options.sampling.sample_count = value;
  }
  if (args.has("seed")) {
    if (!parseUint64(args.value("seed"), &value))
      return fail(cmd, "--seed must be a whole non-negative number", kExitUsage);
    options.sampling.seed = value;
  }
  if (args.has("threads")) {
    if (!parseUint64(args.value("threads"), &value) || value == 0 || value > 256)
      return fail(cmd, "--threads must be a whole number from 1 to 256", kExitUsage);
    options.threads = static_cast<unsigned>(value);
  }
  if (isTetCompare(args))
    return runTetCompare(args, args.has("samples") ? options.sampling.sample_count : 0, options.sampling.seed,
                         options.threads);

  Input a, b;
  if (int status = load(args.positional()[0], &a); status != kExitOk) return status;
  if (int status = load(args.positional()[1], &b); status != kExitOk) return status;

  SurfaceDistanceReport report;
  {
    // Scoped so that the progress line ends before the results are printed.
    Progress progress("compare", args.flag("quiet"));
    options.progress = [&progress](double fraction) { progress.update(fraction); };
    bool measured = measureSurfaceDistance(a.mesh, b.mesh, options, &report, &error);
    options.progress = nullptr;
    if (!measured) return fail(cmd, error, kExitInvalidData);  // both meshes were checked above
  }

  if (args.flag("json"))
    printJson(a, b, options, report);
  else
    printTable(a, b, report);
  return kExitOk;
}

}  // namespace mrsv::cli
