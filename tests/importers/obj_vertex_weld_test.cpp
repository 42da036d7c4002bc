// weld_vertices (the OBJ reader's parallel vertex welding) against the loop
// it replaces: one pass over the corners with a map from key to vertex,
// vertices numbered as their keys are first met.
#include "rayform/importers/obj/obj_vertex_weld.h"

#include <gtest/gtest.h>

#include <random>
#include <unordered_map>
#include <vector>

namespace rayform::obj {
namespace {

struct Reference {
  std::vector<uint32_t> first_corner, corner_vertex;
};

Reference weld_one_by_one(const std::vector<CornerKey>& keys) {
  Reference r;
  std::unordered_map<CornerKey, uint32_t, CornerKeyHash> vertex_of;
  for (size_t c = 0; c < keys.size(); ++c) {
    auto [it, added] = vertex_of.try_emplace(keys[c], uint32_t(r.first_corner.size()));
    if (added) r.first_corner.push_back(uint32_t(c));
    r.corner_vertex.push_back(it->second);
  }
  return r;
}

// Corners over `positions` positions, each position with a few possible uv
// and normal keys (seams, creases, faceted corners), in a random order
// spanning many of the weld's blocks.
std::vector<CornerKey> random_keys(size_t corners, int positions, int keys_per_position, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> position(0, positions - 1), variant(0, keys_per_position - 1);
  std::vector<CornerKey> keys(corners);
  for (size_t c = 0; c < corners; ++c) {
    CornerKey& k = keys[c];
    k.position = position(rng);
    const int v = variant(rng);
    k.uv = v % 2 == 0 ? -1 : k.position + v;
    k.normal = v == 3 ? -2 - int(c / 3) : (v > 3 ? v : -1);  // v == 3: a faceted corner, its face's own
  }
  return keys;
}

TEST(ObjVertexWeld, GivesTheVerticesOfOneLoopWithAMap) {
  for (int keys_per_position : {1, 2, 6}) {
    for (int positions : {1, 7, 5000, 200000}) {
      const std::vector<CornerKey> keys = random_keys(3 * 40000, positions, keys_per_position, uint32_t(positions));
      const Reference want = weld_one_by_one(keys);
      const WeldedVertices got = weld_vertices(size_t(positions), keys.size(), [&](size_t c) { return keys[c]; });
      ASSERT_EQ(got.first_corner, want.first_corner) << positions << " positions, " << keys_per_position << " keys";
      ASSERT_EQ(got.corner_vertex, want.corner_vertex) << positions << " positions, " << keys_per_position << " keys";
      if (keys_per_position == 1 && positions <= 5000) {
        EXPECT_EQ(got.first_corner.size(), size_t(positions));
      }
    }
  }
}

TEST(ObjVertexWeld, NoCornersNoVertices) {
  const WeldedVertices w = weld_vertices(10, 0, [](size_t) { return CornerKey{}; });
  EXPECT_TRUE(w.first_corner.empty());
  EXPECT_TRUE(w.corner_vertex.empty());
}

}  // namespace
}  // namespace rayform::obj
