// Default camera, head-light and light rig for scenes whose files have none.
#include "rayform/importers/obj/obj_reader.h"
#include "rayform/base/error.h"
#include "rayform/scene/scene_defaults.h"
#include "rayform/scene/scene_stats.h"
#include "test_paths.h"
#include "test_scenes.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <limits>

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

// The diffuse light a white surface with unit normal n gets from the lights.
float diffuse_sum(const Scene& s, vec3 n) {
  float sum = 0.f;
  for (const Light& l : s.lights) sum += std::max(0.f, glm::dot(-l.direction, n)) * l.color.x;
  return sum;
}

TEST(SceneDefaults, LightRigIsFixedToTheCamera) {
  // Looking down +x with up +y: right is +z, top +y, back -x.
  Scene s = box_scene({-1, -1, -1}, {1, 1, 1});
  Camera c;
  c.direction = vec3(2, 0, 0);
  c.up = vec3(0, 3, 0);
  s.cameras.push_back(c);
  ASSERT_TRUE(add_light_rig(s));
  ASSERT_EQ(s.lights.size(), 3u);
  const float k = 1.f / std::sqrt(3.f), f = 1.f / std::sqrt(2.0625f);
  const struct {
    const char* name;
    vec3 direction;  // where the light travels: minus (right, top, back) in the camera's frame
    float intensity;
  } want[3] = {{"headlight", vec3(1, 0, 0), 0.3f},
               {"key", -(k * vec3(0, 0, 1) + k * vec3(0, 1, 0) + k * vec3(-1, 0, 0)), 0.7f},
               {"fill", -(-f * vec3(0, 0, 1) - 0.25f * f * vec3(0, 1, 0) + f * vec3(-1, 0, 0)), 0.2f}};
  for (int i = 0; i < 3; ++i) {
    const Light& l = s.lights[size_t(i)];
    EXPECT_EQ(l.name, want[i].name);
    EXPECT_EQ(l.kind, Light::Kind::directional);
    EXPECT_EQ(l.color, vec3(want[i].intensity));
    EXPECT_NEAR(glm::length(l.direction - want[i].direction), 0.f, 1e-6f) << want[i].name;
  }
  // Added once; nothing added to a scene with lights.
  EXPECT_FALSE(add_light_rig(s));
  EXPECT_EQ(s.lights.size(), 3u);
  // It follows the camera asked for (the first when out of range); without a camera, the default camera's frame.
  Scene two = box_scene({-1, -1, -1}, {1, 1, 1});
  two.cameras = {Camera{}, c};
  Scene two_again = two;
  ASSERT_TRUE(add_light_rig(two, 1));
  EXPECT_NEAR(glm::length(two.lights[0].direction - vec3(1, 0, 0)), 0.f, 1e-6f);
  ASSERT_TRUE(add_light_rig(two_again, 7));
  EXPECT_NEAR(glm::length(two_again.lights[0].direction - vec3(0, 0, -1)), 0.f, 1e-6f);
  Scene bare = box_scene({-1, -1, -1}, {1, 1, 1});
  ASSERT_TRUE(add_light_rig(bare));
  EXPECT_NEAR(glm::length(bare.lights[1].direction + k * vec3(1, 1, 1)), 0.f, 1e-6f);
}

TEST(SceneDefaults, LightRigKeepsWhiteSurfacesInRange) {
  // A camera looking at an angle, up not orthogonal to it.
  Scene s = box_scene({-1, -1, -1}, {1, 1, 1});
  Camera c;
  c.direction = vec3(-1, -0.5f, -2);
  c.up = vec3(0.2f, 1, 0);
  s.cameras.push_back(c);
  ASSERT_TRUE(add_light_rig(s));
  // Facing the camera: 0.30 + 0.70 / sqrt(3) + 0.20 / 1.436 = 0.843 (documented in scene_defaults.h).
  EXPECT_NEAR(diffuse_sum(s, -glm::normalize(c.direction)), 0.8434f, 1e-4f);
  // No orientation over 0.96 (the length of the weighted sum of directions): 20 000 normals on the sphere.
  float most = 0.f;
  for (int i = 0; i < 20000; ++i) {
    const float z = 1.f - 2.f * (float(i) + 0.5f) / 20000.f, r = std::sqrt(1.f - z * z), phi = 2.39996323f * float(i);
    most = std::max(most, diffuse_sum(s, vec3(r * std::cos(phi), r * std::sin(phi), z)));
  }
  EXPECT_LE(most, 0.9581f);
  EXPECT_GE(most, 0.955f);
  // The sides are lit, differently: the key's side brighter than the fill's, nothing black but the underside.
  const vec3 fwd = glm::normalize(c.direction), right = glm::normalize(glm::cross(fwd, c.up)),
             top = glm::cross(right, fwd);
  EXPECT_NEAR(diffuse_sum(s, right), 0.7f / std::sqrt(3.f), 1e-5f);
  EXPECT_NEAR(diffuse_sum(s, -right), 0.2f / std::sqrt(2.0625f), 1e-5f);
  EXPECT_NEAR(diffuse_sum(s, top), 0.7f / std::sqrt(3.f), 1e-5f);
}

TEST(SceneDefaults, EmptySceneGetsACameraAtZ5) {
  Scene s;
  ASSERT_TRUE(add_default_camera(s));
  EXPECT_EQ(s.cameras[0].center, vec3(0, 0, 5));
  EXPECT_EQ(s.cameras[0].direction, vec3(0, 0, -1));
}

// The camera's position relative to `centre` as azimuth (degrees about +y
// from +z towards +x), elevation (degrees above the xz plane) and distance.
vec3 orbit_of(const Camera& c, vec3 centre) {
  const vec3 p = c.center - centre;
  const float dist = glm::length(p);
  return vec3(std::atan2(p.x, p.z) * 180.f / pi, std::asin(p.y / dist) * 180.f / pi, dist);
}

TEST(SceneDefaults, OrbitZeroZeroIsTheDefaultCamera) {
  for (const auto& [lo, hi] : std::vector<std::pair<vec3, vec3>>{{{-1, -1, -1}, {1, 1, 1}},
                                                                 {{10, 0, -3}, {14, 1, 5}},
                                                                 {{0, -5, 0}, {0.1f, 5, 0.1f}},
                                                                 {{2, 2, 2}, {2, 2, 2}}}) {
    Scene s = box_scene(lo, hi);
    ASSERT_TRUE(add_default_camera(s));
    const Camera d = s.cameras[0], o = orbit_camera(Bounds3{lo, hi}, Orbit{});
    // Bit for bit (EXPECT_EQ on floats), -0 and +0 told apart.
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(o.center[k], d.center[k]);
      EXPECT_EQ(o.direction[k], d.direction[k]);
      EXPECT_EQ(std::signbit(o.direction[k]), std::signbit(d.direction[k]));
    }
    EXPECT_EQ(o.up, d.up);
    EXPECT_EQ(o.fov_deg, d.fov_deg);
    EXPECT_EQ(o.aspect, d.aspect);
    EXPECT_EQ(o.projection, d.projection);
    EXPECT_EQ(o.up_vector, d.up_vector);
  }
  // Empty bounds: at (0, 0, 5), like the default camera of an empty scene.
  EXPECT_EQ(orbit_camera(Bounds3{}, Orbit{}).center, vec3(0, 0, 5));
}

TEST(SceneDefaults, OrbitPlacesTheCameraOnTheSphere) {
  const Bounds3 b{{1, 2, 3}, {3, 4, 7}};  // centre (2, 3, 5)
  const vec3 centre(2, 3, 5);
  // Exact places: +90 is the +x side (counter-clockwise seen from above), 180 the -z side.
  const struct {
    Orbit orbit;
    vec3 offset;
  } places[] = {{{0, 0, 4.f}, {0, 0, 4}},
                {{90, 0, 4.f}, {4, 0, 0}},
                {{180, 0, 4.f}, {0, 0, -4}},
                {{-90, 0, 4.f}, {-4, 0, 0}},
                {{270, 0, 4.f}, {-4, 0, 0}},
                {{0, 45, 2.f}, {0, std::sqrt(2.f), std::sqrt(2.f)}},
                {{90, -30, 2.f}, {std::sqrt(3.f), -1, 0}}};
  for (const auto& [orbit, offset] : places) {
    const Camera c = orbit_camera(b, orbit);
    SCOPED_TRACE(testing::Message() << "orbit " << orbit.azimuth_deg << "," << orbit.elevation_deg);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c.center[k], centre[k] + offset[k], 1e-5f);
    // Looks at the centre, up +y, the default camera's projection.
    const vec3 to_centre = glm::normalize(centre - c.center);
    EXPECT_NEAR(glm::length(glm::normalize(c.direction) - to_centre), 0.f, 1e-6f);
    EXPECT_EQ(c.up, vec3(0, 1, 0));
    EXPECT_EQ(c.fov_deg, default_camera_fov_deg);
    EXPECT_EQ(c.aspect, Camera::Aspect::fit);
  }
  // Angles and distance read back from the position.
  for (float az : {-170.f, -45.f, 0.f, 30.f, 135.f})
    for (float el : {-89.f, -20.f, 0.f, 60.f, 89.9f}) {
      const vec3 got = orbit_of(orbit_camera(b, Orbit{az, el, 7.5f}), centre);
      SCOPED_TRACE(testing::Message() << "orbit " << az << "," << el);
      if (std::abs(el) < 89.f) {  // straight above, the azimuth is lost to rounding
        EXPECT_NEAR(got.x, az, 1e-3f);
      }
      EXPECT_NEAR(got.y, el, 2e-3f);
      EXPECT_NEAR(got.z, 7.5f, 1e-4f);
    }
}

TEST(SceneDefaults, OrbitFramesTheBoundsFromAnySide) {
  for (const auto& [lo, hi] : std::vector<std::pair<vec3, vec3>>{{{-1, -1, -1}, {1, 1, 1}},
                                                                 {{10, 0, -3}, {14, 1, 5}},
                                                                 {{0, -5, 0}, {0.1f, 5, 0.1f}},
                                                                 {{-3, 2, 7}, {3, 2.5f, 9}}})
    for (float az : {0.f, 30.f, 90.f, 200.f, -45.f})
      for (float el : {-80.f, -30.f, 0.f, 45.f, 89.f}) {
        SCOPED_TRACE(testing::Message() << "orbit " << az << "," << el << " box " << lo.x << " " << lo.y << " "
                                        << lo.z);
        const Camera c = orbit_camera(Bounds3{lo, hi}, Orbit{az, el, std::nullopt});
        // Every corner in view with the margin; the framing is conservative
        // off the axes (the box's extents in the camera's frame), but the
        // box still fills at least half of the view.
        float m = max_image_coordinate(c, Bounds3{lo, hi});
        EXPECT_LE(m, 1.f / 1.1f + 1e-4f);
        EXPECT_GE(m, 0.5f);
        // On the sphere asked for, around the centre.
        const vec3 got = orbit_of(c, 0.5f * (lo + hi));
        EXPECT_NEAR(got.y, el, 0.01f);
        if (std::abs(el) < 89.f) {
          EXPECT_NEAR(std::remainder(got.x - az, 360.f), 0.f, 0.01f);
        }
      }
}

TEST(SceneDefaults, OrbitFramesForTheFieldOfView) {
  const Bounds3 b{{-1, -2, -1}, {1, 2, 1}};
  const float d40 = orbit_of(orbit_camera(b, Orbit{30, 10, std::nullopt}), vec3(0)).z;
  for (float fov : {10.f, 20.f, 90.f, 150.f}) {
    const Camera c = orbit_camera(b, Orbit{30, 10, std::nullopt}, fov);
    EXPECT_EQ(c.fov_deg, fov);
    EXPECT_LE(max_image_coordinate(c, b), 1.f / 1.1f + 1e-4f) << fov;
    EXPECT_GE(max_image_coordinate(c, b), 0.5f) << fov;
    const float d = orbit_of(c, vec3(0)).z;
    if (fov < 40.f) {
      EXPECT_GT(d, d40) << fov;
    } else {
      EXPECT_LT(d, d40) << fov;
    }
  }
  // An explicit distance is kept whatever the field of view.
  EXPECT_NEAR(orbit_of(orbit_camera(b, Orbit{0, 0, 3.f}, 10.f), vec3(0)).z, 3.f, 1e-6f);
}

TEST(SceneDefaults, OrbitProblems) {
  EXPECT_EQ(orbit_problem(Orbit{}), "");
  EXPECT_EQ(orbit_problem(Orbit{-720, 89.9f, 1e-3f}), "");
  const float nan = std::nanf(""), inf = std::numeric_limits<float>::infinity();
  for (const Orbit& bad :
       {Orbit{0, 90, std::nullopt}, Orbit{0, -90, std::nullopt}, Orbit{0, 120, 1.f}, Orbit{0, nan, std::nullopt}}) {
    EXPECT_EQ(orbit_problem(bad), "elevation EL must lie strictly between -90 and 90 degrees");
    EXPECT_THROW(orbit_camera(Bounds3{}, bad), Error);
  }
  for (const Orbit& bad : {Orbit{nan, 0, std::nullopt}, Orbit{inf, 0, std::nullopt}}) {
    EXPECT_EQ(orbit_problem(bad), "azimuth AZ must be a finite number of degrees");
    EXPECT_THROW(orbit_camera(Bounds3{}, bad), Error);
  }
  for (float dist : {0.f, -1.f, inf, nan}) {
    const Orbit bad{0, 10, dist};
    EXPECT_EQ(orbit_problem(bad), "distance DIST must be a finite number greater than 0");
    EXPECT_THROW(orbit_camera(Bounds3{}, bad), Error);
  }
  for (float fov : {0.f, 180.f, -5.f, nan}) EXPECT_THROW(orbit_camera(Bounds3{}, Orbit{}, fov), Error);
}

TEST(SceneDefaults, FramingTargetIsTheBoundsCentre) {
  EXPECT_EQ(framing_target(Bounds3{{1, 2, 3}, {3, 4, 7}}), vec3(2, 3, 5));
  EXPECT_EQ(framing_target(Bounds3{}), vec3(0));
  EXPECT_EQ(framing_target(Bounds3{{0, 0, -infinity}, {1, 1, 1}}), vec3(0));
}

TEST(SceneDefaults, UpIsReplacedOnlyWhenParallel) {
  const vec3 y(0, 1, 0);
  EXPECT_EQ(up_not_parallel(y, vec3(1, -1, 0)), y);
  EXPECT_EQ(up_not_parallel(vec3(0, 0, 2), vec3(1, 0, 0)), vec3(0, 0, 2));
  // Parallel (either way): +y, unless the view is vertical: -z looking down, +z looking up.
  EXPECT_EQ(up_not_parallel(vec3(0, 0, 1), vec3(0, 0, -3)), y);
  EXPECT_EQ(up_not_parallel(vec3(1, 1, 1), vec3(-2, -2, -2)), y);
  EXPECT_EQ(up_not_parallel(y, vec3(0, -4.5f, 0)), vec3(0, 0, -1));
  EXPECT_EQ(up_not_parallel(y, vec3(0, 2, 0)), vec3(0, 0, 1));
  EXPECT_EQ(up_not_parallel(vec3(0, -1, 0), vec3(0, -1, 0)), vec3(0, 0, -1));
  // Zero up: treated as parallel.
  EXPECT_EQ(up_not_parallel(vec3(0), vec3(1, 0, 0)), y);
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
