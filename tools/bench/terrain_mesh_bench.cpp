// tools/bench/terrain_mesh_bench: issue 22's terrain goals, with the peers
// measured in the same run. For each real terrain of ../shared/data (the
// SRTM tiles with their voids filled as the decoder synthesises them, Big
// Tujunga, St Helens), coded as a lossless progressive MRSV stream:
//   - Delaunay insertion (spec 8.5) against Delatin 0.2.0 (node): triangles,
//     time, and the largest error over every sample, measured exactly here;
//   - progressive insertion (spec 8.7, stages per wavelet level) against one
//     stage: triangles, and the vertex sets nested;
//   - on the largest 2^k + 1 square crop, MARTINI (node) and, when built,
//     the quadtree (spec 9), in N rounds (3) that alternate the two, each
//     side's best time kept, so that a slow spell of the machine (timings on
//     a shared virtual machine vary by up to 1.8 x) falls on both alike.
//
//   terrain_mesh_bench [--peers DIR] [--errors 1,5,20,50] [--quick] [--only insertion|quadtree]
//                      [--rounds N]
//
// DIR holds node_modules with delatin and @mapbox/martini (tools/bench/
// setup_peers.sh installs them into build/node_peers).
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "grid_mesh_checks.h"
#include "mrsv/encode.h"
#include "mrsv/grid.h"
#include "mrsv/grid_mesh.h"
#include "mrsv/quadtree_mesh.h"
#include "mrsv/terrain_insertion.h"
#include "shared_data.h"

namespace {

using namespace mrsv;

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

struct PeerResult {
  double ms = 0;
  GridMesh mesh;
  bool ok = false;
};

// Runs terrain_peers.mjs on `field` and reads back one mesh per error.
std::vector<PeerResult> runPeer(const std::string& peers, const std::string& tool, const SampleField& field,
                                const std::vector<std::string>& errors, const std::string& scratch) {
  std::vector<PeerResult> out(errors.size());
  const std::string heights = scratch + "/heights.f32";
  {
    std::vector<float> h(field.values.begin(), field.values.end());
    std::ofstream f(heights, std::ios::binary);
    f.write(reinterpret_cast<const char*>(h.data()), std::streamsize(h.size() * sizeof(float)));
  }
  std::string list;
  for (const auto& e : errors) list += (list.empty() ? "" : ",") + e;
  const std::string cmd = "node " + std::string(MRSV_SOURCE_DIR) + "/tools/bench/terrain_peers.mjs " + peers + " " +
                          tool + " " + heights + " " + std::to_string(field.size[0]) + " " +
                          std::to_string(field.size[1]) + " " + list + " " + scratch + "/" + tool + "_";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return out;
  char line[512];
  size_t k = 0;
  while (fgets(line, sizeof line, p) && k < errors.size()) {
    const char* ms = std::strstr(line, "\"ms\":");
    if (!ms) continue;
    out[k].ms = std::atof(ms + 5);
    std::ifstream f(scratch + "/" + tool + "_" + errors[k] + ".bin", std::ios::binary);
    uint32_t nv = 0, nt = 0;
    f.read(reinterpret_cast<char*>(&nv), 4);
    f.read(reinterpret_cast<char*>(&nt), 4);
    std::vector<uint32_t> data(size_t(nv) * 2 + size_t(nt) * 3);
    f.read(reinterpret_cast<char*>(data.data()), std::streamsize(data.size() * 4));
    GridMesh& m = out[k].mesh;
    m.dims = 2;
    m.size[0] = field.size[0], m.size[1] = field.size[1], m.size[2] = 1;
    for (uint32_t v = 0; v < nv; ++v) {
      m.points.push_back({data[2 * v], data[2 * v + 1], 0});
      m.values.push_back(field.at(data[2 * v], data[2 * v + 1]));
    }
    // Peers' triangles may turn either way (y down): orient them counter-clockwise.
    for (uint32_t t = 0; t < nt; ++t) {
      std::array<uint32_t, 4> c = {data[2 * nv + 3 * t], data[2 * nv + 3 * t + 1], data[2 * nv + 3 * t + 2], 0};
      const auto &a = m.points[c[0]], &b = m.points[c[1]], &d = m.points[c[2]];
      const int64_t cross = (int64_t(b[0]) - a[0]) * (int64_t(d[1]) - a[1]) - (int64_t(b[1]) - a[1]) * (int64_t(d[0]) - a[0]);
      if (cross < 0) std::swap(c[1], c[2]);
      if (cross != 0) m.cells.push_back(c);
    }
    out[k].ok = true;
    ++k;
  }
  pclose(p);
  return out;
}

double worstError(const SampleField& f, const GridMesh& m, const ErrorBound& bound, bool* within) {
  double worst = 0;
  *within = test::withinBoundEverywhere(f, m, bound, &worst);
  return worst;
}

struct Terrain {
  std::string file;
  std::string label;
};

}  // namespace

int main(int argc, char** argv) {
  std::string peers = std::string(MRSV_SOURCE_DIR) + "/build/node_peers";
  std::vector<std::string> errors = {"1", "5", "20", "50"};
  bool quick = false;
  int rounds = 3;  // of MARTINI and the quadtree in turn
  std::string only;  // "insertion" or "quadtree": that part alone
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--peers" && i + 1 < argc) peers = argv[++i];
    else if (a == "--errors" && i + 1 < argc) {
      errors.clear();
      std::stringstream ss(argv[++i]);
      for (std::string e; std::getline(ss, e, ',');) errors.push_back(e);
    } else if (a == "--quick") quick = true;
    else if (a == "--rounds" && i + 1 < argc && std::atoi(argv[i + 1]) > 0) rounds = std::atoi(argv[++i]);
    else if (a == "--only" && i + 1 < argc && (std::string(argv[i + 1]) == "insertion" ||
                                               std::string(argv[i + 1]) == "quadtree")) only = argv[++i];
    else {
      std::fprintf(stderr,
                   "usage: terrain_mesh_bench [--peers DIR] [--errors 1,5,20,50] [--quick] [--only insertion|quadtree] "
                   "[--rounds N]\n");
      return a == "--help" ? 0 : 2;
    }
  }
  struct stat st;
  const bool have_peers = stat((peers + "/node_modules/delatin").c_str(), &st) == 0;
  // terrain_peers.mjs loads the peers through createRequire, which takes only an absolute path.
  if (have_peers) peers = std::filesystem::absolute(peers).string();
  if (!have_peers)
    std::fprintf(stderr, "terrain_mesh_bench: no %s/node_modules/delatin: run tools/bench/setup_peers.sh (peers skipped)\n",
                 peers.c_str());
  char scratch_template[] = "/tmp/mrsv-terrain-bench-XXXXXX";
  const std::string scratch = mkdtemp(scratch_template);

  std::vector<Terrain> terrains = {{"mt_st_helens_317x460_int16le.raw.zst", "St Helens 317x460"},
                                   {"big_tujunga_1197x643_int16le.raw.zst", "Big Tujunga 1197x643"},
                                   {"srtm3_N35E138_mt_fuji_1201x1201_int16le.raw.zst", "SRTM Fuji 1201^2"},
                                   {"srtm3_N46W122_mt_rainier_1201x1201_int16le.raw.zst", "SRTM Rainier 1201^2"},
                                   {"srtm3_N27E086_mt_everest_1201x1201_int16le.raw.zst", "SRTM Everest 1201^2"}};
  if (quick) terrains.resize(2);

  struct Crop {
    std::string label;
    SampleField field;
  };
  std::vector<Crop> crops;
  std::vector<std::string> removal_rows;  // printed after the insertion table
  std::printf("## Delaunay insertion against Delatin (every sample checked)\n\n");
  std::printf("| terrain | max error | Delatin triangles | MRSV triangles | ratio | Delatin ms | MRSV ms | speed-up | Delatin worst | MRSV worst | progressive triangles | progressive / single | without the cleanup / Delatin | no border rule / Delatin | of MRSV ms, the cleanup |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Terrain& t : terrains) {
    test::SharedGrid g;
    if (!test::loadSharedGrid(std::string(MRSV_SHARED_DATA) + "/terrain/" + t.file, &g)) return 1;
    if (t.file.find("srtm3") != std::string::npos) {
      g.header.grid_flags |= kGridFlagHasNodata;
      g.header.nodata_bits = uint64_t(uint16_t(int16_t(-32768)));
    }
    WaveletEncodeOptions options;
    options.max_error = 0;
    options.progressive = true;
    std::vector<uint8_t> stream;
    if (Error e = encodeWaveletGrid(g.header, g.samples, Metadata{}, options, &stream, nullptr); !e.ok()) {
      std::fprintf(stderr, "%s: encode failed: %s\n", t.file.c_str(), e.describe().c_str());
      return 1;
    }
    DecodeOptions decode;
    decode.void_values = true;
    DecodedGrid grid;
    if (Error e = decodeGrid(stream.data(), stream.size(), decode, &grid); !e.ok()) return 1;
    SampleField field;
    std::string error;
    if (!sampleFieldFromGrid(grid, &field, &error)) return 1;
    // The largest 2^k + 1 square at the grid's centre, for MARTINI.
    {
      uint32_t side = 2;
      while (2 * (side - 1) + 1 <= std::min(field.size[0], field.size[1])) side = 2 * (side - 1) + 1;
      Crop c;
      c.label = t.label.substr(0, t.label.rfind(' ')) + " " + std::to_string(side) + "^2";
      c.field.size[0] = c.field.size[1] = side;
      c.field.size[2] = 1;
      const uint32_t x0 = (field.size[0] - side) / 2, y0 = (field.size[1] - side) / 2;
      for (uint32_t y = 0; y < side; ++y)
        for (uint32_t x = 0; x < side; ++x) c.field.values.push_back(field.at(x0 + x, y0 + y));
      crops.push_back(std::move(c));
    }
    if (only == "quadtree") continue;
    // The prefixes' fields for the progressive stages.
    const std::vector<ReconstructionStage> stages = reconstructionStages(grid, stream.size());
    std::vector<SampleField> stage_fields(stages.size());
    for (size_t k = 0; k < stages.size(); ++k) {
      DecodedGrid prefix;
      decodeGrid(stream.data(), stages[k].bytes, decode, &prefix);
      sampleFieldFromGrid(prefix, &stage_fields[k], &error);
    }
    std::vector<PeerResult> delatin;
    if (have_peers) delatin = runPeer(peers, "delatin", field, errors, scratch);
    for (size_t k = 0; k < errors.size(); ++k) {
      ErrorBound bound;
      parseErrorBound(errors[k], &bound);
      InsertionLimits limits;
      limits.max_error = bound;
      // Best of up to three runs under 1 s, as terrain_peers.mjs times the
      // peers: the insertion and its border cleanup (spec 8.8, the default),
      // not the copy of the mesh out of the triangulation between them.
      GridMesh ours, inserted;
      double ms = 1e30, insert_ms = 1e30, cleanup_ms = 1e30;
      for (int run = 0; run < 3 && (run == 0 || ms < 1000); ++run) {
        TerrainInserter single(field.size[0], field.size[1]);
        const double t0 = now();
        single.refine(field, 0, limits, &error);
        const double refine_ms = (now() - t0) * 1000;
        single.mesh(&inserted);
        GridMesh cleaned = inserted;
        const double t1 = now();
        cleanBorderZone(field, bound, &cleaned, nullptr, &error);
        const double cleaned_ms = (now() - t1) * 1000;
        ms = std::min(ms, refine_ms + cleaned_ms);
        insert_ms = std::min(insert_ms, refine_ms);
        cleanup_ms = std::min(cleanup_ms, cleaned_ms);
        if (run == 0) ours = std::move(cleaned);
      }
      bool ours_ok = false;
      const double ours_worst = worstError(field, ours, bound, &ours_ok);
      TerrainInserter progressive(field.size[0], field.size[1]);
      for (size_t s = 0; s < stages.size(); ++s) progressive.refine(stage_fields[s], stages[s].shift, limits, &error);
      GridMesh prog;
      progressive.mesh(&prog);
      bool prog_ok = false;
      worstError(field, prog, bound, &prog_ok);
      // Delatin has no border rule (spec 8.6): without it the greedy choice is
      // Delatin's own, and so is the triangle count (untimed).
      char free_ratio[32] = "n/a | n/a";
      if (k < delatin.size() && delatin[k].ok) {
        InsertionLimits free_sides = limits;
        free_sides.border_rule = false;
        TerrainInserter unbordered(field.size[0], field.size[1]);
        unbordered.refine(field, 0, free_sides, &error);
        GridMesh free_mesh;
        unbordered.mesh(&free_mesh);
        std::snprintf(free_ratio, sizeof free_ratio, "%.3f | %.3f",
                      double(inserted.cells.size()) / delatin[k].mesh.cells.size(),
                      double(free_mesh.cells.size()) / delatin[k].mesh.cells.size());
      }
      char peer[256] = "| n/a | | | n/a | | | n/a ";
      if (k < delatin.size() && delatin[k].ok) {
        bool within = false;
        const double worst = worstError(field, delatin[k].mesh, bound, &within);
        std::snprintf(peer, sizeof peer, "| %zu | %zu | %.3f | %.0f | %.0f | %.1fx | %.2f%s ", delatin[k].mesh.cells.size(),
                      ours.cells.size(), double(ours.cells.size()) / delatin[k].mesh.cells.size(), delatin[k].ms, ms,
                      delatin[k].ms / ms, worst, within ? "" : " (over)");
      } else {
        std::snprintf(peer, sizeof peer, "| n/a | %zu | | n/a | %.0f | | n/a ", ours.cells.size(), ms);
      }
      std::printf("| %s | %s m %s| %.2f%s | %zu%s | %.3f | %s | %.1f |\n", t.label.c_str(), errors[k].c_str(), peer,
                  ours_worst, ours_ok ? "" : " (over)", prog.cells.size(), prog_ok ? "" : " (over)",
                  double(prog.cells.size()) / ours.cells.size(), free_ratio, cleanup_ms);
      std::fflush(stdout);
      // The vertex-removal pass after insertion (spec 8.8), timed with the insertion.
      GridMesh removed = inserted;
      const double t_pass = now();
      removeInnerVertices(field, bound, &removed, nullptr, &error);
      const double pass_ms = (now() - t_pass) * 1000;
      bool removed_ok = false;
      const double removed_worst = worstError(field, removed, bound, &removed_ok);
      char versus[64] = "| n/a | n/a ";  // against Delatin: triangles, speed-up
      if (k < delatin.size() && delatin[k].ok)
        std::snprintf(versus, sizeof versus, "| %.3f | %.2fx ",
                      double(removed.cells.size()) / delatin[k].mesh.cells.size(), delatin[k].ms / (insert_ms + pass_ms));
      char line[320];
      std::snprintf(line, sizeof line, "| %s | %s m | %zu | %.3f %s| %.0f | %.2f%s |\n", t.label.c_str(),
                    errors[k].c_str(), removed.cells.size(), double(removed.cells.size()) / inserted.cells.size(), versus,
                    insert_ms + pass_ms, removed_worst, removed_ok ? "" : " (over)");
      removal_rows.push_back(line);
    }
  }
  if (only == "insertion") return 0;
  std::printf("\n## Insertion with the vertex-removal pass (spec 8.8) against Delatin (every sample checked)\n\n");
  std::printf("| terrain | max error | triangles | / insertion | / Delatin | speed-up over Delatin | ms (insertion + pass) | worst |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const std::string& row : removal_rows) std::printf("%s", row.c_str());
  std::printf("\n## Quadtree against MARTINI and insertion on 2^k + 1 crops (every sample checked)\n\n");
  std::printf("| crop | max error | MARTINI triangles | quadtree triangles | insertion triangles | quadtree / insertion | MARTINI ms | quadtree ms | speed-up | MARTINI worst | quadtree worst | with removal (9.7) triangles | / insertion | ms | speed-up | worst |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Crop& c : crops) {
    // Rounds of MARTINI (all bounds) and the quadtree (all bounds, with and
    // without the pass) in turn, the best time of each kept: a slow spell of
    // the machine then falls on both sides alike.
    const size_t n = errors.size();
    std::vector<PeerResult> martini;
    std::vector<double> martini_ms(n, 1e30), tree_ms(n, 1e30), removal_ms(n, 1e30);
    std::vector<GridMesh> quads(n), removals(n);
    std::vector<QuadtreeOptions> options(n);
    for (size_t k = 0; k < n; ++k) {
      parseErrorBound(errors[k], &options[k].threshold);
      options[k].tile_borders = true;  // as `mrsv mesh --method quadtree --max-error E` meshes (spec 9.1)
    }
    for (int round = 0; round < rounds; ++round) {
      if (have_peers) {
        std::vector<PeerResult> run = runPeer(peers, "martini", c.field, errors, scratch);
        for (size_t k = 0; k < run.size() && k < n; ++k)
          if (run[k].ok) martini_ms[k] = std::min(martini_ms[k], run[k].ms);
        if (round == 0) martini = std::move(run);
      }
      for (size_t k = 0; k < n; ++k) {
        // The quadtree's mesh (spec 9, or with 9.7's pass) and its best time of 3.
        const auto timedQuadtree = [&](bool remove, GridMesh* mesh) {
          QuadtreeOptions qt = options[k];
          qt.remove_vertices = remove;
          std::string error;
          double best = 1e30;
          for (int rep = 0; rep < 3; ++rep) {
            const double t0 = now();
            quadtreeMesh(c.field, nullptr, qt, mesh, &error);
            best = std::min(best, (now() - t0) * 1000);
          }
          return best;
        };
        tree_ms[k] = std::min(tree_ms[k], timedQuadtree(false, &quads[k]));
        removal_ms[k] = std::min(removal_ms[k], timedQuadtree(true, &removals[k]));
      }
    }
    for (size_t k = 0; k < n; ++k) {
      const ErrorBound bound = options[k].threshold;
      std::string error;
      const GridMesh &quad = quads[k], &removal = removals[k];
      const double best_ms = tree_ms[k];
      bool quad_ok = false;
      const double quad_worst = worstError(c.field, quad, bound, &quad_ok);
      bool removal_ok = false;
      const double removal_worst = worstError(c.field, removal, bound, &removal_ok);
      InsertionLimits limits;
      limits.max_error = bound;
      TerrainInserter ins(c.field.size[0], c.field.size[1]);
      ins.refine(c.field, 0, limits, &error);
      GridMesh inserted;  // as mrsv mesh --max-error E makes it: with the border cleanup (8.8)
      ins.mesh(&inserted);
      cleanBorderZone(c.field, bound, &inserted, nullptr, &error);
      const unsigned long long insertion_cells = inserted.cells.size();
      char peer[160] = "| n/a ";
      char peer_time[200] = "| n/a | %.0f | | n/a ";
      std::snprintf(peer_time, sizeof peer_time, "| n/a | %.0f | | n/a ", best_ms);
      if (k < martini.size() && martini[k].ok) {
        bool within = false;
        const double worst = worstError(c.field, martini[k].mesh, bound, &within);
        std::snprintf(peer, sizeof peer, "| %zu ", martini[k].mesh.cells.size());
        std::snprintf(peer_time, sizeof peer_time, "| %.1f | %.1f | %.1fx | %.2f%s ", martini_ms[k], best_ms,
                      martini_ms[k] / best_ms, worst, within ? "" : " (over)");
      }
      char removal_speed[32] = "n/a";  // over MARTINI
      if (k < martini.size() && martini[k].ok)
        std::snprintf(removal_speed, sizeof removal_speed, "%.2fx", martini_ms[k] / removal_ms[k]);
      std::printf("| %s | %s m %s| %zu | %llu | %.2f %s| %.2f%s | %zu | %.2f | %.1f | %s | %.2f%s |\n", c.label.c_str(),
                  errors[k].c_str(), peer, quad.cells.size(), insertion_cells,
                  double(quad.cells.size()) / insertion_cells, peer_time, quad_worst, quad_ok ? "" : " (over)",
                  removal.cells.size(), double(removal.cells.size()) / insertion_cells, removal_ms[k], removal_speed,
                  removal_worst,
                  removal_ok ? "" : " (over)");
      std::fflush(stdout);
    }
  }
  std::string rm = "rm -rf " + scratch;
  if (std::system(rm.c_str()) != 0) return 1;
  return 0;
}
