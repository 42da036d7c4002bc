// Default camera and headlight for scenes whose files have none.
#include "obj/obj_reader.h"
#include "scene/scene_defaults.h"
#include "scene/scene_stats.h"
#include "test_paths.h"
#include "test_scenes.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace rayform {
namespace {

// A scene of one box mesh spanning [lo, hi] under a transform node.
Scene box_scene(vec3 lo, vec3 hi, const mat4& m = mat4(1.f)) {
  Scene s;
  Mesh mesh;
  for (int i = 0; i < 8; ++i)
    mesh.positions.push_back(vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z));
  mesh.indices = {0, 1, 2, 1, 3, 2, 4, 5, 6, 5, 7, 6};
  s.meshes.push_back(mesh);
  Node shape = test::shape_node(ShapeKind::mesh, 0);
  Node t;
  t.kind = Node::Kind::transform;
  t.local = m;
  t.children = {0};
  s.nodes = {shape, t};
  s.root = 1;
  return s;
}

// Largest |x| and |y| over the box corners in the camera's normalised image
// plane (1 = the edge of the vertical field of view); also checks that every
// corner is in front of the camera.
float max_image_coordinate(const Camera& c, const Bounds3& b) {
  const vec3 w = glm::normalize(c.direction), u = glm::normalize(glm::cross(w, c.up)), v = glm::cross(u, w);
  const float t = std::tan(radians(c.fov_deg) * 0.5f);
  float worst = 0.f;
  for (int i = 0; i < 8; ++i) {
    vec3 p((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z);
    vec3 d = p - c.center;
    float depth = glm::dot(d, w);
    EXPECT_GT(depth, 0.f) << "corner " << i << " behind the camera";
    worst = std::max({worst, std::abs(glm::dot(d, u)) / (depth * t), std::abs(glm::dot(d, v)) / (depth * t)});
  }
  return worst;
}

TEST(SceneDefaults, CameraFramesTheBoundsLookingDownMinusZ) {
  for (const auto& [lo, hi] : std::vector<std::pair<vec3, vec3>>{{{-1, -1, -1}, {1, 1, 1}},
                                                                 {{10, 0, -3}, {14, 1, 5}},
                                                                 {{0, -5, 0}, {0.1f, 5, 0.1f}},
                                                                 {{-3, 2, 7}, {3, 2.5f, 9}}}) {
    Scene s = box_scene(lo, hi);
    ASSERT_TRUE(add_default_camera(s));
    ASSERT_EQ(s.cameras.size(), 1u);
    const Camera& c = s.cameras[0];
    EXPECT_EQ(c.projection, Camera::Projection::perspective);
    EXPECT_EQ(c.aspect, Camera::Aspect::fit);
    EXPECT_EQ(c.direction, vec3(0, 0, -1));
    EXPECT_EQ(c.up, vec3(0, 1, 0));
    EXPECT_FLOAT_EQ(c.fov_deg, default_camera_fov_deg);
    EXPECT_FLOAT_EQ(c.center.x, 0.5f * (lo.x + hi.x));
    EXPECT_FLOAT_EQ(c.center.y, 0.5f * (lo.y + hi.y));
    EXPECT_GT(c.center.z, hi.z);
    // In view with the 10% margin, and not absurdly far: the widest corner
    // reaches 1 / 1.1 of the field of view.
    float m = max_image_coordinate(c, Bounds3{lo, hi});
    EXPECT_LE(m, 1.f / 1.1f + 1e-4f);
    EXPECT_GE(m, 1.f / 1.1f - 1e-3f) << "lo " << lo.x << " " << lo.y << " " << lo.z;
  }
}

TEST(SceneDefaults, CameraUsesWorldBoundsThroughTransforms) {
  Scene s = box_scene({-1, -1, -1}, {1, 1, 1}, glm::translate(mat4(1.f), vec3(100, 0, 0)));
  ASSERT_TRUE(add_default_camera(s));
  EXPECT_FLOAT_EQ(s.cameras[0].center.x, 100.f);
}

TEST(SceneDefaults, NothingAddedWhenPresent) {
  Scene s = box_scene({-1, -1, -1}, {1, 1, 1});
  Camera mine;
  mine.center = vec3(7, 7, 7);
  s.cameras.push_back(mine);
  Light l;
  l.color = vec3(0.25f);
  s.lights.push_back(l);
  EXPECT_FALSE(add_default_camera(s));
  EXPECT_FALSE(add_headlight(s));
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras[0].center, vec3(7, 7, 7));
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].color, vec3(0.25f));
}

TEST(SceneDefaults, HeadlightShinesAlongTheCamera) {
  Scene s = box_scene({-1, -1, -1}, {1, 1, 1});
  Camera c;
  c.direction = vec3(0, -2, 0);
  c.up = vec3(0, 0, 1);
  s.cameras.push_back(c);
  ASSERT_TRUE(add_headlight(s));
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].kind, Light::Kind::directional);
  EXPECT_EQ(s.lights[0].direction, vec3(0, -1, 0));
  EXPECT_EQ(s.lights[0].color, vec3(1.f));
  EXPECT_EQ(s.lights[0].name, "headlight");
  // Added once.
  EXPECT_FALSE(add_headlight(s));
  // Without a camera it shines down -z, like the default camera looks.
  Scene bare = box_scene({-1, -1, -1}, {1, 1, 1});
  ASSERT_TRUE(add_headlight(bare));
  EXPECT_EQ(bare.lights[0].direction, vec3(0, 0, -1));
  // It follows the camera asked for (the one rendered), the first when out of range.
  Scene two = box_scene({-1, -1, -1}, {1, 1, 1});
  two.cameras.push_back(c);
  Camera side;
  side.direction = vec3(3, 0, 0);
  two.cameras.push_back(side);
  Scene two_again = two;
  ASSERT_TRUE(add_headlight(two, 1));
  EXPECT_EQ(two.lights[0].direction, vec3(1, 0, 0));
  ASSERT_TRUE(add_headlight(two_again, 5));
  EXPECT_EQ(two_again.lights[0].direction, vec3(0, -1, 0));
}

TEST(SceneDefaults, EmptySceneGetsACameraAtZ5) {
  Scene s;
  ASSERT_TRUE(add_default_camera(s));
  EXPECT_EQ(s.cameras[0].center, vec3(0, 0, 5));
  EXPECT_EQ(s.cameras[0].direction, vec3(0, 0, -1));
}

TEST(SceneDefaults, FramesTheStanfordBunny) {
  RAYFORM_REQUIRE_SHARED();
  Scene s = read_obj_scene((test::shared_dir() / "assets/obj/stanford-bunny.obj").string());
  ASSERT_TRUE(add_default_camera(s));
  ASSERT_TRUE(add_headlight(s));
  Bounds3 b = scene_stats(s).bounds;
  float m = max_image_coordinate(s.cameras[0], b);
  EXPECT_LE(m, 1.f / 1.1f + 1e-4f);
  EXPECT_GE(m, 0.85f);
  EXPECT_EQ(s.lights[0].direction, s.cameras[0].direction);
}

}  // namespace
}  // namespace rayform
