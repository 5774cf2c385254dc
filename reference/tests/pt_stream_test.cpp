// The PT stream (spec 7): written from collapses, decoded at every level,
// moved between levels, read by prefixes, and damaged streams refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <set>

#include "mrsv/progressive_tet_mesh.h"
#include "pt/pt_encode.h"
#include "pt/pt_state.h"
#include "pt_test_meshes.h"

namespace mrsv {
namespace {

// Greedy collapses found by trial: each one kept only when the stream with
// it still writes (the writer runs the decoder's rules). One collapse per
// batch, so the test needs no independence rule.
std::vector<std::vector<PtCollapse>> trialCollapses(const QuantizedTets& mesh, size_t wanted, uint32_t seed) {
  std::vector<std::array<uint32_t, 2>> edges;
  for (const Tet& t : mesh.tets)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (i != j) edges.push_back({t[i], t[j]});
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::mt19937 rng(seed);
  std::shuffle(edges.begin(), edges.end(), rng);
  std::vector<std::vector<PtCollapse>> batches;
  std::vector<uint8_t> gone(mesh.positions.size(), 0);
  std::vector<uint8_t> bytes;
  for (const auto& e : edges) {
    if (batches.size() == wanted) break;
    if (gone[e[0]] || gone[e[1]]) continue;
    batches.push_back({PtCollapse{e[0], e[1]}});
    if (writePtStream(mesh, batches, &bytes).ok()) {
      gone[e[1]] = 1;
    } else {
      batches.pop_back();
    }
  }
  return batches;
}

// The mesh as a set of tets of positions, independent of numbering and of
// the order of a tet's corners up to an even permutation.
template <class Points, class Tets>
std::multiset<std::vector<int64_t>> geometry(const Points& p, const Tets& tets) {
  std::multiset<std::vector<int64_t>> out;
  for (const Tet& t : tets) {
    // Rotate the smallest corner to the front by an even permutation.
    Tet k = t;
    int lo = 0;
    for (int i = 1; i < 4; ++i)
      if (p[k[i]] < p[k[lo]]) lo = i;
    static const int kEven[4][4] = {{0, 1, 2, 3}, {1, 0, 3, 2}, {2, 3, 0, 1}, {3, 2, 1, 0}};
    Tet r{k[kEven[lo][0]], k[kEven[lo][1]], k[kEven[lo][2]], k[kEven[lo][3]]};
    // Then the smallest of the remaining three in front by a cyclic rotation.
    while (p[r[1]] > p[r[2]] || p[r[1]] > p[r[3]]) r = {r[0], r[2], r[3], r[1]};
    std::vector<int64_t> key;
    for (uint32_t v : r)
      for (int a = 0; a < 3; ++a) key.push_back(p[v][a]);
    out.insert(key);
  }
  return out;
}

TEST(PtStream, DecodesTheFullMeshAndEveryLevelIsAManifold) {
  const QuantizedTets mesh = test::gridTets(5);
  const auto batches = trialCollapses(mesh, 60, 7);
  ASSERT_GE(batches.size(), 20u) << "too few collapses were accepted";
  std::vector<uint8_t> bytes;
  PtStreamStats stats;
  ASSERT_TRUE(writePtStream(mesh, batches, &bytes, &stats).ok());
  DecodedTetMesh d;
  Error e = decodeProgressiveTetMesh(bytes.data(), bytes.size(), DecodeOptions{}, &d);
  ASSERT_TRUE(e.ok()) << e.describe();
  ASSERT_TRUE(d.has_mesh);
  EXPECT_EQ(d.mesh.vertexCount(), mesh.positions.size());
  EXPECT_EQ(d.mesh.tetCount(), mesh.tets.size());
  const auto& s = d.mesh.state();
  EXPECT_EQ(geometry(s.mesh.positions, s.mesh.tets), geometry(mesh.positions, mesh.tets));
  // Field values travel with their vertices.
  std::multiset<std::array<int32_t, 4>> in, out;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    in.insert({mesh.positions[v][0], mesh.positions[v][1], mesh.positions[v][2], mesh.scalars[v]});
    out.insert({s.mesh.positions[v][0], s.mesh.positions[v][1], s.mesh.positions[v][2], s.mesh.scalars[v]});
  }
  EXPECT_EQ(in, out);

  const std::vector<uint8_t> finest = canonicalTetMeshOutput(d.mesh);
  std::vector<std::vector<uint8_t>> levels;
  for (uint32_t level = 0; level <= d.mesh.splitsDecoded(); ++level) {
    d.mesh.setLevel(level);
    ASSERT_EQ(d.mesh.tetCount(), d.mesh.tetCountAt(level));
    TetComplex c = d.mesh.state().mesh;
    c.positions.resize(d.mesh.vertexCount());
    c.buildIncidence();
    ASSERT_EQ(c.checkManifold(), "") << "level " << level;
    levels.push_back(canonicalTetMeshOutput(d.mesh));
  }
  EXPECT_EQ(levels.back(), finest);
  // Down and up again in jumps gives the same bytes at every level, and the
  // same tet lists as built afresh (in slot order, incidence_lists.h).
  for (uint32_t level : {7u, 0u, 13u, 2u, static_cast<uint32_t>(levels.size() - 1), 5u}) {
    d.mesh.setLevel(level);
    EXPECT_EQ(canonicalTetMeshOutput(d.mesh), levels[level]) << "level " << level;
    const TetComplex& held = d.mesh.state().mesh;
    TetComplex fresh = held;
    fresh.positions.resize(d.mesh.vertexCount());
    fresh.buildIncidence();
    for (uint32_t v = 0; v < d.mesh.vertexCount(); ++v) {
      const auto a = held.incident.of(v), b = fresh.incident.of(v);
      ASSERT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << "level " << level << ", vertex " << v;
    }
  }
}

TEST(PtStream, EveryPrefixOfCompleteChunksDecodesToALevel) {
  const QuantizedTets mesh = test::gridTets(4);
  const auto batches = trialCollapses(mesh, 15, 3);
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(writePtStream(mesh, batches, &bytes).ok());
  DecodedTetMesh whole;
  ASSERT_TRUE(decodeProgressiveTetMesh(bytes.data(), bytes.size(), DecodeOptions{}, &whole).ok());
  DecodeOptions partial;
  partial.container.allow_partial_tail = true;
  uint32_t last_batches = 0;
  for (size_t size = kFileHeaderSize; size <= bytes.size(); ++size) {
    DecodedTetMesh d;
    Error e = decodeProgressiveTetMesh(bytes.data(), size, partial, &d);
    ASSERT_TRUE(e.ok()) << "prefix " << size << ": " << e.describe();
    ASSERT_GE(d.batches_decoded, last_batches);
    last_batches = d.batches_decoded;
    if (d.has_mesh) {
      whole.mesh.setLevel(d.mesh.splitsDecoded());
      ASSERT_EQ(canonicalTetMeshOutput(d.mesh), canonicalTetMeshOutput(whole.mesh)) << "prefix " << size;
    }
  }
  EXPECT_EQ(last_batches, batches.size());
}

TEST(PtStream, DamagedStreamsAreRefusedOrDecodeToManifolds) {
  const QuantizedTets mesh = test::gridTets(4);
  const auto batches = trialCollapses(mesh, 15, 5);
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(writePtStream(mesh, batches, &bytes).ok());
  DecodeOptions options;
  options.container.verify_checksums = false;  // reach the chunk decoders
  std::mt19937 rng(11);
  int refused = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::vector<uint8_t> damaged = bytes;
    const size_t at = 12 + rng() % (damaged.size() - 12);
    damaged[at] ^= static_cast<uint8_t>(1 + rng() % 255);
    DecodedTetMesh d;
    Error e = decodeProgressiveTetMesh(damaged.data(), damaged.size(), options, &d);
    if (!e.ok()) {
      ++refused;
      continue;
    }
    // Whatever decodes is still a manifold of positive tets.
    TetComplex c = d.mesh.state().mesh;
    c.buildIncidence();
    ASSERT_EQ(c.checkManifold(), "") << "trial " << trial;
  }
  EXPECT_GT(refused, 1000);
}

TEST(PtStream, InvalidCollapsesAreRefusedByTheWriter) {
  const QuantizedTets mesh = test::gridTets(3);
  std::vector<uint8_t> bytes;
  // Vertices 0 and 26 (opposite corners of the block) share no tet.
  Error e = writePtStream(mesh, {{PtCollapse{0, 26}}}, &bytes);
  EXPECT_FALSE(e.ok());
  // The interior vertex 13 into a corner of the boundary: Table 1 case 2/3.
  e = writePtStream(mesh, {{PtCollapse{0, 13}}}, &bytes);
  EXPECT_FALSE(e.ok());
}

}  // namespace
}  // namespace mrsv

namespace mrsv {
namespace {

// Writes small PT streams as fuzz seeds when MRSV_WRITE_PT_SEEDS names a
// directory (fuzz/corpus_pt was made so); otherwise checks they still write.
TEST(PtStream, FuzzSeeds) {
  const char* dir = std::getenv("MRSV_WRITE_PT_SEEDS");
  int k = 0;
  for (int n : {3, 4}) {
    for (uint32_t seed : {1u, 2u}) {
      const QuantizedTets mesh = test::gridTets(n);
      const auto batches = trialCollapses(mesh, n == 3 ? 6 : 12, seed);
      std::vector<uint8_t> bytes;
      ASSERT_TRUE(writePtStream(mesh, batches, &bytes).ok());
      if (dir) {
        std::string path = std::string(dir) + "/grid" + std::to_string(n) + "_" + std::to_string(k++) + ".mrsv";
        FILE* f = std::fopen(path.c_str(), "wb");
        ASSERT_NE(f, nullptr);
        std::fwrite(bytes.data(), 1, bytes.size(), f);
        std::fclose(f);
      }
    }
  }
}

}  // namespace
}  // namespace mrsv
