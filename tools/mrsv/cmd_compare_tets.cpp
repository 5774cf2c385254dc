// mrsv compare for two tet meshes: the field's PSNR at random positions (the
// paper's 7.2 measure), volumes, boundary distances, quality and validity.
#include <cmath>
#include <cstdio>
#include <string>

#include "cli.h"
#include "commands.h"
#include "mrsv/tet_formats.h"
#include "mrsv/tet_metrics.h"

namespace mrsv::cli {

bool isTetCompare(const Args& args) {
  return args.positional().size() == 2 && tetFormatOf(args.positional()[0]) != TetFormat::kUnknown &&
         tetFormatOf(args.positional()[1]) != TetFormat::kUnknown;
}

int runTetCompare(const Args& args, uint64_t samples, uint64_t seed, unsigned threads) {
  const char* cmd = "compare";
  std::string error;
  TetMesh a, b;
  if (!readTetFile(args.positional()[0], &a, nullptr, &error)) return fail(cmd, error, kExitInvalidData);
  if (!readTetFile(args.positional()[1], &b, nullptr, &error)) return fail(cmd, error, kExitInvalidData);
  TetCompareOptions options;
  if (samples) options.field.sample_count = samples;
  options.field.seed = seed;
  options.threads = threads;
  const TetCompareReport r = compareTetMeshes(a, b, options);
  if (!r.error.empty()) return fail(cmd, r.error, kExitInvalidData);
  // Meshes of one field in different frames (a crop kept at its place in the
  // volume against one moved to the origin) give a low PSNR that reads like a
  // poor approximation: say so when many samples fall outside B.
  if (r.has_field && r.field.samples > 0 && r.field.outside_b * 100 > r.field.samples)
    std::fprintf(stderr, "mrsv compare: warning: %llu of %llu samples (%.1f %%) lie outside B: do A and B share "
                 "their origin and spacing?\n", (unsigned long long)r.field.outside_b,
                 (unsigned long long)r.field.samples, 100.0 * double(r.field.outside_b) / double(r.field.samples));
  if (args.flag("json")) {
    std::printf("%s\n", tetCompareJson(r).c_str());
    return kExitOk;
  }
  std::printf("A: %s: %llu vertices, %llu tets\nB: %s: %llu vertices, %llu tets\n", args.positional()[0].c_str(),
              (unsigned long long)r.a_vertices, (unsigned long long)r.a_tets, args.positional()[1].c_str(),
              (unsigned long long)r.b_vertices, (unsigned long long)r.b_tets);
  if (r.has_field)
    std::printf("field '%s' at %llu random positions in A: PSNR %.2f dB, max %.6g, mean %.6g, RMS %.6g "
                "(%llu outside B)\n",
                r.field.field.c_str(), (unsigned long long)r.field.samples, r.field.psnr_db, r.field.max_abs,
                r.field.mean_abs, r.field.rms, (unsigned long long)r.field.outside_b);
  std::printf("volume: A %.9g, B %.9g, difference %.3g (%.4f %%)\n", r.volume_a, r.volume_b, r.volume_difference,
              100 * r.volume_difference_relative);
  std::printf("boundary: Hausdorff %.6g (%.5f of the diagonal), mean %.6g, RMS %.6g\n", r.boundary.hausdorff,
              r.boundary.hausdorff / r.boundary.bbox_diagonal, r.boundary.mean, r.boundary.rms);
  if (r.has_quality)
    for (const auto& [name, q] : {std::pair<const char*, const TetQuality&>{"A", r.quality_a}, {"B", r.quality_b}})
      std::printf("%s: min dihedral worst %.2f, mean %.2f deg; %llu inverted, %llu degenerate, %s manifold, "
                  "%lld boundary self-intersections: %s\n",
                  name, q.min_dihedral_worst, q.min_dihedral_mean, (unsigned long long)q.inverted,
                  (unsigned long long)q.degenerate, q.manifold.manifold() ? "a" : "NOT a",
                  (long long)q.boundary_self_intersections, q.valid() ? "valid" : "INVALID");
  return kExitOk;
}

}  // namespace mrsv::cli
