// Refraction with the medium each ray carries (whitted_integrator.h, WhittedIntegrator::secondary):
// rays through nested and touching glass spheres and a closed glass mesh, at
// every incidence including grazing ones that end in total internal
// reflection. Glass here absorbs nothing (diffuse 0, specularColor 1), so each
// surface splits a ray's weight into R + (1 - R) = 1 (or all to the reflection
// under total internal reflection): the radiance of a ray is a convex
// combination of what its paths end on. Two consequences are checked on every
// pixel of many random views:
//   - inside a closed black shell (an analytic sphere; no light, ambient 0)
//     every path ends on black or at the bounce limit (0): the radiance is
//     exactly 0, and any other value is light leaking in from the white
//     background through the shell or a glass surface touching it;
//   - under a white background with no shell, the radiance lies in [0, 1]
//     (1 for a path that escapes, 0 for one cut at the bounce limit), and is
//     never NaN.
// Nothing here uses a fixed epsilon; there is no fixed-epsilon comparison.
#include "stress_common.h"

#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"
#include "rayform/scene/procedural_mesh.h"
#include "rayform/scene/scene_builder.h"

#include <glm/gtc/matrix_transform.hpp>

namespace rayform::stress {
namespace {

Material glass(float index) {
  Material m;
  m.diffuse = vec3(0.f);
  m.specular = vec3(1.f);
  m.specular_highlight = false;
  m.refraction_index = index;
  return m;
}

// Glass: a closed icosphere mesh of radius 2 (n = 1.5) holding a nested
// sphere (n = 1.33) and two spheres touching each other (n = 2.4 and 1.5) and
// that nested sphere; a sphere (n = 1.8) outside the mesh touching the shell
// of radius 3 (with `shell`, black), and a tilted glass cube (n = 1.5) across
// the mesh's surface, nearly touching the shell.
Scene glass_scene(bool shell) {
  SceneBuilder b;
  Mesh ico = make_icosphere(3);
  for (vec3& p : ico.positions) p *= 2.f;
  b.add_instance(b.add_mesh(ico.positions, ico.indices), b.add_material(glass(1.5f)));
  b.add_instance(b.add_sphere(vec3(0.f), 1.f), b.add_material(glass(1.33f)));
  b.add_instance(b.add_sphere(vec3(0.f, 1.4f, 0.f), 0.4f), b.add_material(glass(2.4f)));
  b.add_instance(b.add_sphere(vec3(0.f, 1.4f, 0.8f), 0.4f), b.add_material(glass(1.5f)));
  b.add_instance(b.add_sphere(vec3(0.f, 0.f, 2.5f), 0.5f), b.add_material(glass(1.8f)));
  Mesh cube = make_cube();
  const int cube_node =
      b.add_transform(glm::translate(mat4(1.f), vec3(0.f, -2.4f, 0.f)) *
                      glm::rotate(mat4(1.f), 0.3f, vec3(1.f, 1.f, 0.f)) * glm::scale(mat4(1.f), vec3(0.3f)));
  b.add_instance(b.add_mesh(cube.positions, cube.indices), b.add_material(glass(1.5f)), cube_node);
  if (shell) {
    Material black;
    black.diffuse = vec3(0.f);
    b.add_instance(b.add_sphere(vec3(0.f), 3.f), b.add_material(black));
  }
  Scene s = b.take();
  s.background.color = vec3(1.f);
  s.background.ambient = vec3(0.f);
  return s;
}

struct Counts {
  int64_t pixels = 0, nan = 0, out_of_range = 0, positive = 0, below_one = 0;
  float max = 0.f;
};

// Renders `views` random views of `base` (camera at a distance near..far from
// the origin, looking near it) and counts the channels that are NaN, outside
// [0, 1], above 0 and below 1.
Counts render_views(const Scene& base, int views, float near, float far, uint64_t seed, int bounces) {
  Counts c;
  Rng rng(seed);
  for (int v = 0; v < views; ++v) {
    Scene s = base;
    Camera cam;
    cam.center = vec3(rng.unit_vector() * rng.uniform(near, far));
    cam.direction = vec3(-dvec3(cam.center) + rng.unit_vector() * 0.8);
    cam.up = vec3(rng.unit_vector());
    cam.fov_deg = 70.f;
    s.cameras = {cam};
    const PreparedScene p = prepare_scene(s);
    RenderOptions o;
    o.width = o.height = 40;
    o.bounces = bounces;
    RenderResult r = render(p, o);
    for (float x : r.color.pixels) {
      ++c.pixels;
      if (std::isnan(x)) ++c.nan;
      else if (x < 0.f || x > 1.f) ++c.out_of_range;
      if (x > 0.f) ++c.positive;
      if (x < 1.f) ++c.below_one;
      c.max = std::max(c.max, x);
    }
  }
  c.pixels /= 3;
  return c;
}

TEST(StressRefraction, NoLightLeaksIntoAClosedShell) {
  const Scene s = glass_scene(true);
  const Counts c = render_views(s, int(scaled(24)), 0.f, 2.9f, 1, 8);
  std::cout << "[stress] refraction, closed shell: " << c.pixels << " pixels, " << c.positive
            << " channels above 0 (max " << c.max << "), " << c.nan << " NaN\n";
  ::testing::Test::RecordProperty("shell.pixels", std::to_string(c.pixels));
  ::testing::Test::RecordProperty("shell.leaks", std::to_string(c.positive));
  EXPECT_EQ(c.nan, 0);
  EXPECT_EQ(c.positive, 0) << "light from the background got through the shell";
}

TEST(StressRefraction, RadianceBoundedThroughNestedAndTouchingGlass) {
  const Scene s = glass_scene(false);
  const Counts c = render_views(s, int(scaled(24)), 3.2f, 8.f, 2, 8);
  std::cout << "[stress] refraction, open: " << c.pixels << " pixels, " << c.out_of_range
            << " channels outside [0, 1], " << c.nan << " NaN (max " << c.max << ")\n";
  ::testing::Test::RecordProperty("open.pixels", std::to_string(c.pixels));
  EXPECT_EQ(c.nan, 0);
  EXPECT_EQ(c.out_of_range, 0);
  EXPECT_GT(c.below_one, 0) << "no ray went deep into the glass: the views miss it";
}

// A ray entering the top of a glass slab at grazing incidence refracts at
// nearly the critical angle and meets the slab's sides beyond it: total
// internal reflection (and near-critical incidence on the bottom). Each view
// aims its centre ray at a point of the top face at a grazing angle from
// 1e-6 to 0.1 radians, from 40 units away. The glass is lossless and the
// background white, so a pixel is 1 unless its paths are cut at the bounce
// limit (some are: rays trapped by total internal reflection), never above 1
// and never NaN.
TEST(StressRefraction, GrazingIncidenceAndTotalInternalReflection) {
  SceneBuilder b;
  Mesh cube = make_cube();
  const int slab = b.add_transform(glm::scale(mat4(1.f), vec3(1.f, 0.2f, 1.f)));
  b.add_instance(b.add_mesh(cube.positions, cube.indices), b.add_material(glass(1.5f)), slab);
  Scene s = b.take();
  s.background.color = vec3(1.f);
  Counts total;
  int64_t below_one = 0;
  Rng rng(3);
  for (int v = 0; v < int(scaled(32)); ++v) {
    Scene sv = s;
    Camera cam;
    const double angle = rng.log_uniform(1e-6, 1e-1), turn = rng.uniform(0.0, 6.283185307179586);
    const dvec3 target(rng.uniform(-0.5, 0.5), 0.2, rng.uniform(-0.5, 0.5));
    const dvec3 d(std::cos(angle) * std::cos(turn), -std::sin(angle), std::cos(angle) * std::sin(turn));
    cam.center = vec3(target - 40.0 * d);
    cam.direction = vec3(d);
    cam.fov_deg = float(rng.log_uniform(0.001, 0.5));
    sv.cameras = {cam};
    const PreparedScene p = prepare_scene(sv);
    RenderOptions o;
    o.width = o.height = 24;
    o.bounces = 6;
    RenderResult r = render(p, o);
    for (float x : r.color.pixels) {
      ++total.pixels;
      if (std::isnan(x)) ++total.nan;
      else if (x < 0.f || x > 1.f) ++total.out_of_range;
      if (x < 1.f) ++below_one;
    }
  }
  std::cout << "[stress] refraction, grazing: " << total.pixels / 3 << " pixels, " << total.out_of_range
            << " channels outside [0, 1], " << total.nan << " NaN, " << below_one
            << " channels cut at the bounce limit\n";
  EXPECT_EQ(total.nan, 0);
  EXPECT_EQ(total.out_of_range, 0);
  EXPECT_GT(below_one, 0) << "no ray was trapped in the slab: the views miss it";
}

}  // namespace
}  // namespace rayform::stress
