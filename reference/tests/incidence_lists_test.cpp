// IncidenceLists (tetmesh/incidence_lists.h), the PT decoder's tet lists: the
// same lists as one std::vector per vertex through every operation the
// decoder uses, across blocks moved to the pool's end and the pool packed.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "tetmesh/incidence_lists.h"

namespace mrsv {
namespace {

void expectSame(const IncidenceLists& lists, const std::vector<std::vector<uint32_t>>& model) {
  ASSERT_EQ(lists.vertexCount(), model.size());
  for (uint32_t v = 0; v < model.size(); ++v) {
    const IncidenceLists::View list = lists.of(v);
    ASSERT_EQ(list.size(), model[v].size()) << "vertex " << v;
    for (uint32_t i = 0; i < list.size(); ++i) ASSERT_EQ(list[i], model[v][i]) << "vertex " << v << ", entry " << i;
  }
}

TEST(IncidenceLists, MatchOneVectorPerVertexThroughMovesAndPacking) {
  std::mt19937 rng(21);
  IncidenceLists lists;
  std::vector<std::vector<uint32_t>> model(300);
  lists.assign(300);
  uint32_t slot = 0;
  for (int step = 0; step < 200000; ++step) {
    const uint32_t v = rng() % model.size();
    const uint32_t op = rng() % 16;
    if (op < 9) {  // a tet gained
      lists.push(v, slot);
      model[v].push_back(slot++);
    } else if (op < 11 && !model[v].empty()) {  // the last tet undone
      lists.pop(v);
      model[v].pop_back();
    } else if (op == 11) {  // a split's vs: keeps every other tet
      uint32_t* data = lists.data(v);
      uint32_t kept = 0;
      for (uint32_t i = 0; i < model[v].size(); i += 2) data[kept++] = model[v][i];
      lists.resize(v, kept);
      std::vector<uint32_t> rest;
      for (uint32_t i = 0; i < model[v].size(); i += 2) rest.push_back(model[v][i]);
      model[v] = rest;
    } else if (op == 12) {  // a split's vt: a new vertex, its first tets written through data()
      lists.addVertex();
      model.emplace_back();
      const uint32_t vt = static_cast<uint32_t>(model.size() - 1);
      const uint32_t first = rng() % 40;
      lists.reserve(vt, 2 * first);
      for (uint32_t i = 0; i < first; ++i) {
        lists.data(vt)[i] = slot;
        model[vt].push_back(slot++);
      }
      lists.resize(vt, first);
    } else if (op == 13 && model.size() > 300) {  // the last split undone
      lists.removeLastVertex();
      model.pop_back();
    } else if (op == 14) {
      lists.clear(v);
      model[v].clear();
    }
  }
  expectSame(lists, model);
  // Lists built afresh from tets, as the base mesh's are.
  IncidenceLists fresh;
  fresh.assign(static_cast<uint32_t>(model.size()));
  for (uint32_t v = 0; v < model.size(); ++v)
    for (uint32_t t : model[v]) fresh.push(v, t);
  expectSame(fresh, model);
}

}  // namespace
}  // namespace mrsv
