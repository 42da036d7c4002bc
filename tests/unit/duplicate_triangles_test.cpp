// Exactly repeated triangles merged before the BVH build
// (src/accel/duplicate_triangles.h): which count as duplicates, the lowest
// index kept, hits unchanged, and prepare_scene building a mesh of 100000
// copies of one triangle as one triangle.
#include "rayform/accel/duplicate_triangles.h"
#include "rayform/render/prepared_scene.h"
#include "test_scenes.h"

#include <gtest/gtest.h>

#include <cstring>

namespace rayform {
namespace {

// Vertices 0..2 and 3..5 at the same corners with the same uvs; vertex 6 at
// corner 0 with another uv.
Mesh corners_mesh() {
  Mesh m;
  const vec3 a(-1.f, -1.f, 0.f), b(1.f, -1.f, 0.f), c(0.f, 1.f, 0.f);
  m.positions = {a, b, c, a, b, c, a};
  m.uvs = {vec2(0.f), vec2(1.f, 0.f), vec2(0.5f, 1.f), vec2(0.f), vec2(1.f, 0.f), vec2(0.5f, 1.f), vec2(0.25f)};
  return m;
}

TEST(DuplicateTriangles, SameCornersInTheSameOrderWithTheSameAttributesAreMerged) {
  Mesh m = corners_mesh();
  m.indices = {
      0, 1, 2,  // 0: kept
      0, 1, 2,  // 1: the same indices: merged into 0
      1, 2, 0,  // 2: the corners turned (b, c, a): another float evaluation, kept
      3, 4, 5,  // 3: other vertices at the same corners with the same uvs: merged into 0
      6, 1, 2,  // 4: corner 0 with another uv: kept
      2, 1, 0,  // 5: reversed: kept
      1, 2, 0,  // 6: the same as 2: merged into 2
  };
  EXPECT_EQ(distinct_triangles(m), (std::vector<uint32_t>{0, 2, 4, 5}));
  // A face material apart keeps a copy too.
  m.face_materials = {0, 0, 0, 1, 0, 0, 0};
  EXPECT_EQ(distinct_triangles(m), (std::vector<uint32_t>{0, 2, 3, 4, 5}));
  // No duplicates: empty (every triangle kept).
  m.indices = {0, 1, 2, 1, 2, 0};
  m.face_materials.clear();
  EXPECT_TRUE(distinct_triangles(m).empty());
}

TEST(DuplicateTriangles, ManyCopiesOfTwoKindsKeepOneOfEach) {
  // 300 triangles at the same corners, alternately with the uvs of
  // vertices 0..2 and with vertex 6's uv at corner 0 (past the run length
  // beyond which the attributes are hashed too).
  Mesh m = corners_mesh();
  for (int k = 0; k < 300; ++k) m.indices.insert(m.indices.end(), {k % 2 ? 6u : 0u, 1u, 2u});
  EXPECT_EQ(distinct_triangles(m), (std::vector<uint32_t>{0, 1}));
}

TEST(DuplicateTriangles, CopiesFarApartInALargeMeshAreFoundInIndexOrder) {
  // 300000 distinct triangles of a grid (the candidates are collected in
  // blocks of 65536), then every 9973rd one made a copy of the triangle
  // 70001 before it, so most pairs lie in different blocks.
  Mesh m;
  constexpr uint32_t side = 400;
  for (uint32_t j = 0; j < side; ++j)
    for (uint32_t i = 0; i < side; ++i) m.positions.push_back(vec3(float(i), float(j), 0.f));
  for (uint32_t j = 0; j + 1 < side && m.triangle_count() < 300000; ++j)
    for (uint32_t i = 0; i + 1 < side; ++i) {
      const uint32_t v = j * side + i;
      m.indices.insert(m.indices.end(), {v, v + 1, v + side});
      m.indices.insert(m.indices.end(), {v + 1, v + side + 1, v + side});
    }
  const size_t n = m.triangle_count();
  ASSERT_GT(n, size_t(300000));
  std::vector<uint32_t> expected;
  for (size_t t = 0; t < n; ++t) {
    if (t >= 70001 && t % 9973 == 0) {
      for (size_t k = 0; k < 3; ++k) m.indices[3 * t + k] = m.indices[3 * (t - 70001) + k];
      continue;
    }
    expected.push_back(uint32_t(t));
  }
  ASSERT_LT(expected.size(), n - 20);
  EXPECT_EQ(distinct_triangles(m), expected);
}

TEST(DuplicateTriangles, HitsReportTheLowestIndexWithTheSameTAndBarycentrics) {
  Mesh one = corners_mesh(), copies = corners_mesh();
  one.indices = {0, 1, 2};
  // Five different triangles first (far away in z), then 1000 copies of (3, 4, 5).
  for (int k = 0; k < 5; ++k) {
    copies.positions.push_back(vec3(float(k), 0.f, -10.f));
    copies.positions.push_back(vec3(float(k) + 1.f, 0.f, -10.f));
    copies.positions.push_back(vec3(float(k), 1.f, -10.f));
    copies.uvs.resize(copies.positions.size(), vec2(0.f));
    const uint32_t v = uint32_t(copies.positions.size()) - 3;
    copies.indices.insert(copies.indices.end(), {v, v + 1, v + 2});
  }
  for (int k = 0; k < 1000; ++k) copies.indices.insert(copies.indices.end(), {3, 4, 5});
  const MeshAccel a = build_mesh_accel_without_duplicates(one);
  const MeshAccel b = build_mesh_accel_without_duplicates(copies);
  EXPECT_EQ(b.triangles.size(), 6u) << "five triangles and one of the copies";
  for (const vec3 origin : {vec3(0.f, 0.f, 5.f), vec3(0.3f, -0.2f, 5.f), vec3(-0.7f, -0.9f, 3.f)}) {
    Ray r;
    r.origin = origin;
    r.direction = vec3(0.01f, 0.02f, -1.f);
    float ta = infinity, tb = infinity;
    MeshHit ha{}, hb{};
    ASSERT_TRUE(intersect_mesh(a, r, ta, &ha));
    ASSERT_TRUE(intersect_mesh(b, r, tb, &hb));
    EXPECT_EQ(hb.triangle, 5u) << "the first copy, the mesh's own index";
    EXPECT_EQ(std::memcmp(&ta, &tb, sizeof ta), 0);
    EXPECT_EQ(ha.b0, hb.b0);
    EXPECT_EQ(ha.b1, hb.b1);
    EXPECT_EQ(ha.b2, hb.b2);
  }
}

TEST(DuplicateTriangles, PrepareBuildsAHundredThousandCopiesAsOneTriangle) {
  Scene s;
  s.cameras.push_back(Camera{});
  Mesh m = corners_mesh();
  for (int k = 0; k < 100000; ++k) m.indices.insert(m.indices.end(), {0, 1, 2});
  s.meshes.push_back(m);
  test::add_root_group(s, {test::shape_node(ShapeKind::mesh, 0)});
  const PreparedScene p = prepare_scene(s);
  ASSERT_EQ(p.meshes.size(), 1u);
  EXPECT_EQ(p.meshes[0].triangles, (std::vector<uint32_t>{0}));
  ASSERT_FALSE(p.meshes[0].packets.empty());
  for (uint32_t id : p.meshes[0].packets[0].id) EXPECT_EQ(id, 0u);
}

}  // namespace
}  // namespace rayform
