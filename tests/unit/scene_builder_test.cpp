// SceneBuilder (src/scene/scene_builder.h): a scene built in code prepares and
// renders to the values the shading formula gives, and every bad argument is
// an error naming it that leaves the scene unchanged.
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"
#include "rayform/base/error.h"
#include "rayform/scene/scene_builder.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace rayform {
namespace {

constexpr float nan = std::numeric_limits<float>::quiet_NaN();

// Expects `fn` to throw rayform::Error whose message contains `part`.
template <class Fn>
void expect_error(Fn&& fn, const std::string& part) {
  try {
    fn();
    ADD_FAILURE() << "no error; expected one containing '" << part << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

// Defaults with one field changed (designated initializers would warn under -Wextra).
template <class T, class Fn>
T with(Fn&& change) {
  T t;
  change(t);
  return t;
}

vec3 pixel(const RenderResult& r, int x, int y) {
  const float* p = r.color.at(x, y);
  return vec3(p[0], p[1], p[2]);
}

// A camera at (0, 0, 10) looking down -z (30 degrees: the view spans
// +-tan(15) * 10 = +-2.68 at z = 0, outermost pixel centres on the edges), a
// red sphere of radius 1.5 at the origin, and a green unit quad scaled by 0.4
// and moved to x = 2.2 by a transform node; one white-ish light along the view.
TEST(SceneBuilder, BuiltSceneRendersTheShadingFormula) {
  SceneBuilder b;
  const int red = b.add_material(with<Material>([](Material& m) { m.diffuse = vec3(0.8f, 0.3f, 0.2f); }));
  const int green = b.add_material(with<Material>([](Material& m) { m.diffuse = vec3(0.2f, 0.6f, 0.4f); }));
  const SceneBuilder::Shape ball = b.add_sphere(vec3(0.f), 1.5f);
  const SceneBuilder::Shape quad =
      b.add_mesh({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}, {0, 1, 2, 0, 2, 3},
                 {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}}, {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  EXPECT_EQ(ball.kind, ShapeKind::sphere);
  EXPECT_EQ(quad.kind, ShapeKind::mesh);
  const int aside = b.add_transform(glm::scale(glm::translate(mat4(1.f), vec3(2.2f, 0.f, 0.f)), vec3(0.4f)));
  b.add_instance(ball, red);
  b.add_instance(quad, green, aside);
  Camera c;
  c.center = vec3(0.f, 0.f, 10.f);
  c.direction = vec3(0.f, 0.f, -1.f);
  c.fov_deg = 30.f;
  EXPECT_EQ(b.add_camera(c), 0);
  Light l;
  l.kind = Light::Kind::directional;
  l.direction = vec3(0.f, 0.f, -1.f);
  l.color = vec3(0.9f);
  EXPECT_EQ(b.add_light(l), 0);
  Scene scene = b.take();
  scene.background.color = vec3(0.1f, 0.2f, 0.3f);

  const PreparedScene prepared = prepare_scene(scene);
  RenderOptions o;
  o.width = o.height = 21;  // odd: pixel 10 looks straight down the axis
  const RenderResult r = render(prepared, o);
  // The sphere's front point faces the light: K x light colour.
  const vec3 centre = pixel(r, 10, 10);
  EXPECT_NEAR(centre.x, 0.8f * 0.9f, 1e-5f);
  EXPECT_NEAR(centre.y, 0.3f * 0.9f, 1e-5f);
  EXPECT_NEAR(centre.z, 0.2f * 0.9f, 1e-5f);
  // Column 18 sees x = 0.8 * 2.68 = 2.14, on the moved quad (x in 1.8 .. 2.6); column 16, x = 1.61, nothing.
  const vec3 on_quad = pixel(r, 18, 10);
  EXPECT_NEAR(on_quad.x, 0.2f * 0.9f, 1e-5f);
  EXPECT_NEAR(on_quad.y, 0.6f * 0.9f, 1e-5f);
  EXPECT_NEAR(on_quad.z, 0.4f * 0.9f, 1e-5f);
  EXPECT_EQ(pixel(r, 16, 10), vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(pixel(r, 0, 0), vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(pixel(r, 20, 20), vec3(0.1f, 0.2f, 0.3f));
}

TEST(SceneBuilder, BadArgumentsAreErrorsNamingThemAndChangeNothing) {
  SceneBuilder b;
  const SceneBuilder::Shape ball = b.add_sphere(vec3(0.f), 1.f);
  const int m = b.add_material(Material{});
  const int leaf = b.add_instance(ball, m);
  const Scene before = b.scene();

  expect_error([&] { b.add_mesh({}, {}); }, "add_mesh: no positions");
  expect_error([&] { b.add_mesh({{0, 0, 0}, {1, 0, 0}, {0, nan, 0}}, {0, 1, 2}); }, "position 2 is not finite");
  expect_error([&] { b.add_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1}); }, "three per triangle, got 2");
  expect_error(
      [&] {
        b.add_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {0, 1, 2, 2, 1, 7});
      },
      "index 5 (triangle 1) is 7, beyond the 4 vertices");
  expect_error(
      [&] {
        b.add_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, {{0, 0, 1}});
      },
      "1 normals for 3 positions");
  expect_error(
      [&] {
        b.add_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, {{0, 0, 1}, {0, 0, 0}, {0, 0, 1}});
      },
      "normal 1 must be finite and not zero");
  expect_error(
      [&] {
        b.add_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, {}, {{0, 0}, {1, 0}});
      },
      "2 uvs for 3 positions");
  expect_error([&] { b.add_sphere(vec3(0.f), nan); }, "add_sphere: radius must be a finite number > 0");
  expect_error([&] { b.add_sphere(vec3(0.f), -1.f); }, "radius must be a finite number > 0");
  expect_error([&] { b.add_sphere(vec3(INFINITY, 0.f, 0.f), 1.f); }, "center must be finite");
  expect_error([&] { b.add_material(with<Material>([](Material& m) { m.diffuse = vec3(-0.1f, 0.f, 0.f); })); },
               "add_material: diffuse must not be negative");
  expect_error([&] { b.add_material(with<Material>([](Material& m) { m.shininess = nan; })); },
               "shininess must be a finite number >= 0");
  expect_error([&] { b.add_material(with<Material>([](Material& m) { m.diffuse_texture = 0; })); },
               "diffuse_texture 0 is not a texture handle");
  expect_error(
      [&] {
        b.add_instance(SceneBuilder::Shape{ShapeKind::sphere, 1});
      },
      "add_instance: shape 1 is not a sphere handle (the scene has 1)");
  expect_error([&] { b.add_instance(SceneBuilder::Shape{ShapeKind::mesh, 0}); }, "shape 0 is not a mesh handle");
  expect_error([&] { b.add_instance(ball, 3); }, "material 3 is not a material handle (the scene has 1)");
  expect_error([&] { b.add_instance(ball, m, 9); }, "parent 9 is not a node handle");
  expect_error([&] { b.add_instance(ball, m, leaf); }, "parent 1 is an instance");
  expect_error([&] { b.add_transform(mat4(0.f) + mat4(1.f) * nan); }, "add_transform: the matrix must be finite");
  expect_error([&] { b.add_transform(glm::scale(mat4(1.f), vec3(1.f, 0.f, 1.f))); }, "the matrix must be invertible");
  mat4 projective(1.f);
  projective[2][3] = 1.f;
  expect_error([&] { b.add_transform(projective); }, "the matrix must be affine");
  expect_error([&] { b.add_camera(with<Camera>([](Camera& c) { c.direction = vec3(0.f); })); },
               "add_camera: direction must not be zero");
  expect_error([&] { b.add_camera(with<Camera>([](Camera& c) { c.direction = vec3(0.f, 2.f, 0.f); })); },
               "up must not be zero or parallel");
  expect_error([&] { b.add_camera(with<Camera>([](Camera& c) { c.fov_deg = 180.f; })); },
               "fov_deg must lie strictly between 0 and 180");
  expect_error([&] { b.add_light(with<Light>([](Light& l) { l.color = vec3(nan); })); },
               "add_light: color must be finite");
  expect_error(
      [&] {
        b.add_light(with<Light>([](Light& l) {
          l.kind = Light::Kind::spot;
          l.spot_inner_deg = 50.f;
          l.spot_outer_deg = 40.f;
        }));
      },
      "spot angles");

  const Scene& after = b.scene();
  EXPECT_EQ(after.nodes.size(), before.nodes.size());
  EXPECT_EQ(after.nodes[0].children, before.nodes[0].children);
  EXPECT_EQ(after.meshes.size(), 0u);
  EXPECT_EQ(after.spheres.size(), 1u);
  EXPECT_EQ(after.materials.size(), 1u);
  EXPECT_EQ(after.cameras.size(), 0u);
  EXPECT_EQ(after.lights.size(), 0u);
}

TEST(SceneBuilder, TreesStopAtTheDeepestLevel) {
  SceneBuilder b;
  int parent = SceneBuilder::root_node;
  for (int depth = 2; depth <= max_node_depth; ++depth) parent = b.add_transform(mat4(1.f), parent);
  expect_error([&] { b.add_transform(mat4(1.f), parent); }, "at the deepest level a tree may have (256)");
}

}  // namespace
}  // namespace rayform
