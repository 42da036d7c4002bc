// Limits (base/limits.h): what --limit accepts, and the instance count of a
// node graph measured without walking its paths (scene/node_walk.h).
#include "rayform/base/limits.h"
#include "rayform/scene/node_walk.h"

#include <gtest/gtest.h>

namespace rayform {
namespace {

TEST(Limits, SetByNameWithSuffixes) {
  Limits l;
  EXPECT_EQ(set_limit(l, "triangles", "5"), "");
  EXPECT_EQ(l.triangles, 5u);
  EXPECT_EQ(set_limit(l, "vertices", "3k"), "");
  EXPECT_EQ(l.vertices, 3000u);
  EXPECT_EQ(set_limit(l, "instances", "2M"), "");
  EXPECT_EQ(l.instances, 2000000u);
  EXPECT_EQ(set_limit(l, "texture-texels", "1G"), "");
  EXPECT_EQ(l.texture_texels, 1000000000u);
  EXPECT_EQ(set_limit(l, "json-depth", "64"), "");
  EXPECT_EQ(l.json_depth, 64u);
}

TEST(Limits, BadNamesAndValuesAreExplained) {
  Limits l;
  EXPECT_EQ(set_limit(l, "polygons", "5"),
            "unknown limit 'polygons' (expected one of: triangles, vertices, unbacked-elements, instances, "
            "texture-texels, json-depth, memory)");
  EXPECT_NE(set_limit(l, "triangles", "0").find("expected a positive whole number"), std::string::npos);
  EXPECT_NE(set_limit(l, "triangles", "-1").find("expected a positive whole number"), std::string::npos);
  EXPECT_NE(set_limit(l, "triangles", "1.5").find("expected a positive whole number"), std::string::npos);
  EXPECT_NE(set_limit(l, "triangles", "5T").find("expected a positive whole number"), std::string::npos);
  EXPECT_NE(set_limit(l, "triangles", "").find("expected a positive whole number"), std::string::npos);
  EXPECT_NE(set_limit(l, "triangles", "99999999999999999999").find("too large"), std::string::npos);
  EXPECT_NE(set_limit(l, "triangles", "99999999999G").find("too large"), std::string::npos);
  EXPECT_EQ(set_limit(l, "json-depth", "1025"), "limit json-depth: 1025 is too large (at most 1024)");
  EXPECT_EQ(l.triangles, Limits{}.triangles);  // unchanged by the failures
  EXPECT_EQ(l.json_depth, Limits{}.json_depth);
}

// Levels of two group nodes, each naming both nodes of the next level; the
// last level's nodes are shapes: 2^levels paths to shapes.
Scene doubling_graph(int levels) {
  Scene s;
  for (int level = 0; level < levels; ++level)
    for (int k = 0; k < 2; ++k) {
      Node n;
      if (level + 1 < levels) n.children = {2 * level + 2, 2 * level + 3};
      else n.kind = Node::Kind::shape;
      s.nodes.push_back(n);
    }
  Node root;
  root.children = {0, 1};
  s.nodes.push_back(root);
  s.root = int(s.nodes.size()) - 1;
  return s;
}

TEST(Limits, ShapeVisitsAreCountedWithoutWalkingThePaths) {
  EXPECT_EQ(count_shape_visits(doubling_graph(10), 1u << 20), 1024u);
  // 2^60 paths: counting stops just above the cap, at once.
  EXPECT_EQ(count_shape_visits(doubling_graph(60), 1000), 1001u);
  const Scene big = doubling_graph(40);
  try {
    for_each_shape_node(
        big, [](const Node&, const mat4&) { FAIL() << "walked a path"; }, 1u << 20);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("more than 1048576 shape instances"), std::string::npos) << e.what();
  }
  int visits = 0;
  for_each_shape_node(
      doubling_graph(10), [&](const Node&, const mat4&) { ++visits; }, 1024);
  EXPECT_EQ(visits, 1024);
}

}  // namespace
}  // namespace rayform
