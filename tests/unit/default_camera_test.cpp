// The default camera sees flat models (scene/scene_defaults.h: default_orbit):
// a quad lying in the xz plane is looked at from above at an angle and fills
// a good part of the picture, one in the yz plane is seen from +x, and bounds
// that are not flat keep the camera of the +z side, bit for bit.
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"
#include "rayform/scene/scene_defaults.h"
#include "rayform/scene/scene_stats.h"
#include "test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace rayform {
namespace {

// A scene of one quad with corners lo and hi (flat along the axis where they agree).
Scene quad_scene(vec3 lo, vec3 hi, int flat_axis) {
  Scene s;
  Mesh mesh;
  const int a = (flat_axis + 1) % 3, b = (flat_axis + 2) % 3;
  for (int i = 0; i < 4; ++i) {
    vec3 p = lo;
    p[a] = i & 1 ? hi[a] : lo[a];
    p[b] = i & 2 ? hi[b] : lo[b];
    mesh.positions.push_back(p);
  }
  mesh.indices = {0, 1, 3, 0, 3, 2};
  s.meshes.push_back(mesh);
  test::add_root_group(s, {test::shape_node(ShapeKind::mesh, 0)});
  return s;
}

// The fraction of a 64x64 picture from the scene's first camera in which the scene is hit.
float covered_fraction(Scene s) {
  add_headlight(s, 0);
  const PreparedScene p = prepare_scene(s);
  RenderOptions o;
  o.width = o.height = 64;
  o.depth = true;
  const RenderResult r = render(p, o);
  const auto hits = std::count_if(r.depth.begin(), r.depth.end(), [](float d) { return std::isfinite(d); });
  return float(hits) / float(r.depth.size());
}

// The cosine between the camera's view direction and the axis `axis`.
float view_cosine(const Camera& c, int axis) { return std::abs(glm::normalize(c.direction)[axis]); }

TEST(DefaultCamera, SeesAQuadInTheXzPlaneFromAbove) {
  Scene s = quad_scene(vec3(-1.f, 0.f, -1.f), vec3(1.f, 0.f, 1.f), 1);
  ASSERT_TRUE(add_default_camera(s));
  const Camera& c = s.cameras[0];
  // From above (y > the plane) on the +z side, at flat_view_elevation_deg.
  EXPECT_GT(c.center.y, 0.f);
  EXPECT_GT(c.center.z, 0.f);
  EXPECT_NEAR(view_cosine(c, 1), std::sin(radians(flat_view_elevation_deg)), 1e-6f);
  // Today's camera (Orbit{}) sees it edge-on: nothing.
  Scene edge_on = s;
  edge_on.cameras = {orbit_camera(scene_stats(s).bounds, Orbit{})};
  EXPECT_EQ(covered_fraction(edge_on), 0.f);
  // The quad covers a good part of the picture (a square framed with a 10%
  // margin, foreshortened by the elevation's sine: about a third).
  EXPECT_GT(covered_fraction(s), 0.25f);
}

TEST(DefaultCamera, SeesAQuadInTheYzPlaneFromPlusX) {
  Scene s = quad_scene(vec3(3.f, -1.f, -2.f), vec3(3.f, 1.f, 2.f), 0);
  ASSERT_TRUE(add_default_camera(s));
  const Camera& c = s.cameras[0];
  EXPECT_GT(c.center.x, 3.f);
  EXPECT_NEAR(view_cosine(c, 0), 1.f, 1e-6f);
  EXPECT_GT(covered_fraction(s), 0.25f);
}

TEST(DefaultCamera, BoundsThatAreNotFlatKeepThePlusZSide) {
  struct Case {
    vec3 lo, hi;
  };
  // A cube; a box thin along z (facing +z already); boxes just at the
  // flatness fraction along y and x (not flat); a line; a point.
  for (const Case& k : {Case{vec3(-1.f), vec3(1.f)}, Case{vec3(0.f), vec3(4.f, 4.f, 0.1f)},
                        Case{vec3(0.f), vec3(4.f, flat_bounds_fraction * 4.f, 8.f)},
                        Case{vec3(0.f), vec3(flat_bounds_fraction * 2.f, 2.f, 3.f)},
                        Case{vec3(0.f), vec3(0.f, 0.f, 5.f)}, Case{vec3(2.f), vec3(2.f)}}) {
    const Bounds3 b{k.lo, k.hi};
    const Orbit o = default_orbit(b);
    EXPECT_EQ(o.azimuth_deg, 0.f);
    EXPECT_EQ(o.elevation_deg, 0.f);
    EXPECT_FALSE(o.distance.has_value());
  }
  EXPECT_EQ(default_orbit(Bounds3{}).elevation_deg, 0.f);  // empty
  // Thinner than the fraction: flat.
  EXPECT_EQ(default_orbit(Bounds3{vec3(0.f), vec3(4.f, 0.99f * flat_bounds_fraction * 4.f, 8.f)}).elevation_deg,
            flat_view_elevation_deg);
}

TEST(DefaultCamera, CubeCameraUnchanged) {
  // The camera of a cube is orbit_camera at Orbit{}, as before flat models had their own view.
  Scene s = quad_scene(vec3(-1.f, -1.f, 1.f), vec3(1.f, 1.f, 1.f), 2);
  // A triangle to a corner behind: the bounds are a cube.
  s.meshes[0].positions.push_back(vec3(-1.f, -1.f, -1.f));
  s.meshes[0].indices.insert(s.meshes[0].indices.end(), {0, 1, 4});
  ASSERT_TRUE(add_default_camera(s));
  const Camera want = orbit_camera(Bounds3{vec3(-1.f), vec3(1.f)}, Orbit{});
  EXPECT_EQ(s.cameras[0].center, want.center);
  EXPECT_EQ(s.cameras[0].direction, want.direction);
  EXPECT_EQ(s.cameras[0].direction, vec3(0.f, 0.f, -1.f));
}

}  // namespace
}  // namespace rayform
