// The integrator's metallic-roughness path on hand-built scenes: light
// passes the holes of a MASK texture and a blended surface lets 1 - alpha
// through (shadow rays), a camera ray through a blended surface is covered
// by alpha (AlphaMode coverage), and under a uniform white environment a
// sphere shows its material's directional albedo (a white furnace).
#include "rayform/render/pbr_brdf.h"
#include "rayform/render/prepared_scene.h"
#include "rayform/render/render.h"
#include "rayform/render/whitted_integrator.h"
#include "test_scenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace rayform {
namespace {

// A white rough dielectric.
Material white_matte() {
  Material m;
  m.model = Material::Model::metallic_roughness;
  m.pbr.metallic = 0.f;
  m.pbr.roughness = 1.f;
  return m;
}

// A square at height 1 over x, z in [-1, 1] (uv u = (x + 1) / 2), and
// optionally the floor y = 0 below it, lit from straight above.
Scene square_over_floor(const Material& square_material, bool floor) {
  Scene s;
  Mesh quad;
  quad.positions = {{-1.f, 1.f, -1.f}, {1.f, 1.f, -1.f}, {1.f, 1.f, 1.f}, {-1.f, 1.f, 1.f}};
  quad.uvs = {{0.f, 0.f}, {1.f, 0.f}, {1.f, 1.f}, {0.f, 1.f}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  s.meshes.push_back(quad);
  s.planes.push_back(Plane{{0.f, 1.f, 0.f}, 0.f});
  s.materials = {white_matte(), square_material};
  // Two texels: the left (u < 1/2) transparent, the right opaque.
  Texture t;
  t.width = 2;
  t.height = 1;
  t.channels = 4;
  t.pixels = {255, 255, 255, 0, 255, 255, 255, 255};
  t.filter = Texture::Filter::nearest;
  t.wrap_u = t.wrap_v = Texture::Wrap::clamp;
  s.textures.push_back(t);
  Light sun;
  sun.direction = {0.f, -1.f, 0.f};
  s.lights.push_back(sun);
  std::vector<Node> children = {test::shape_node(ShapeKind::mesh, 0, 1)};
  if (floor) children.push_back(test::shape_node(ShapeKind::plane, 0, 0));
  test::add_root_group(s, children);
  return s;
}

// The colour of floor point (x, 0, 0) seen from below the square.
vec3 floor_colour(const Scene& scene, float x) {
  const PreparedScene p = prepare_scene(scene);
  RenderOptions o;
  o.shadows = true;
  const WhittedIntegrator<true, true, true> integrator{p, o, scene};
  const vec3 from(x, 0.5f, 3.f), to(x, 0.f, 0.f);
  float coverage;
  return integrator.radiance(Ray{from, to - from}, 0, &coverage);
}

TEST(PbrShading, LightPassesTheHolesOfAMask) {
  Material mask = white_matte();
  mask.pbr.alpha_mode = PbrMaterial::AlphaMode::mask;
  mask.pbr.base_color_texture.texture = 0;
  const Scene scene = square_over_floor(mask, true);
  const vec3 under_hole = floor_colour(scene, -0.5f), under_opaque = floor_colour(scene, 0.5f);
  EXPECT_GT(under_hole.g, 0.3f);
  EXPECT_EQ(under_opaque, vec3(0.f));
}

TEST(PbrShading, BlendedSurfacesLetOneMinusAlphaThrough) {
  Material blend = white_matte();
  blend.pbr.alpha_mode = PbrMaterial::AlphaMode::blend;
  blend.pbr.base_color.a = 0.25f;
  const vec3 behind = floor_colour(square_over_floor(blend, true), 0.5f);
  Material clear = blend;
  clear.pbr.base_color.a = 0.f;  // a blended alpha of 0: nothing there
  const vec3 open = floor_colour(square_over_floor(clear, true), 0.5f);
  ASSERT_GT(open.g, 0.3f);
  EXPECT_NEAR(behind.g / open.g, 0.75f, 1e-6f);
}

TEST(PbrShading, CameraRaysThroughABlendedSurfaceAreCoveredByAlpha) {
  Material square = white_matte();
  square.two_sided_lighting = true;  // lit from above, seen from above
  auto seen_from_above = [&](PbrMaterial::AlphaMode mode, float* coverage) {
    Material m = square;
    m.pbr.alpha_mode = mode;
    m.pbr.base_color.a = 0.25f;
    Scene scene = square_over_floor(m, false);
    scene.background.color = vec3(0.2f, 0.4f, 0.6f);
    const PreparedScene p = prepare_scene(scene);
    const RenderOptions o;
    const WhittedIntegrator<true, true, true> integrator{p, o, scene};
    return integrator.radiance(Ray{{0.f, 5.f, 0.f}, {0.f, -1.f, 0.f}}, 0, coverage);
  };
  float coverage_opaque, coverage_blend;
  const vec3 opaque = seen_from_above(PbrMaterial::AlphaMode::opaque, &coverage_opaque);
  const vec3 blend = seen_from_above(PbrMaterial::AlphaMode::blend, &coverage_blend);
  EXPECT_EQ(coverage_opaque, 1.f);
  EXPECT_FLOAT_EQ(coverage_blend, 0.25f);
  ASSERT_GT(opaque.g, 0.3f);
  const vec3 expected = 0.25f * opaque + 0.75f * vec3(0.2f, 0.4f, 0.6f);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(blend[k], expected[k], 1e-6f) << k;
}

// A sphere of radius 1 at the origin, of material `m`, under an environment
// of radiance 1 in every direction and no light: the mean over many camera
// rays at the centre of the sphere's picture (each its own random numbers)
// and its standard error.
struct Estimate {
  float mean = 0.f, standard_error = 0.f;
};
Estimate furnace(const Material& m, bool sampled) {
  Scene s;
  s.spheres.push_back(Sphere{vec3(0.f), 1.f});
  s.materials = {m};
  test::add_root_group(s, {test::shape_node(ShapeKind::sphere, 0, 0)});
  s.background.environment.source = Environment::Source::studio;  // replaced below by the uniform map
  PreparedScene p = prepare_scene(s);
  p.environment = make_environment_map(8, 4, std::vector<float>(8 * 4 * 3, 1.f));
  p.environment_irradiance = environment_irradiance(p.environment);
  p.prefiltered_environment = prefilter_environment(p.environment);
  RenderOptions o;
  o.bounces = 4;
  o.spp = sampled ? 2 : 1;  // the integrator samples the environment, or approximates it without noise
  const WhittedIntegrator<true, true, true> integrator{p, o, s};
  constexpr int n = 20000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    // Rays towards the sphere's centre from points spread over a small
    // patch: each ray its own seed (ray_seed), the view nearly head-on.
    const float dx = 0.05f * (float(i % 100) / 100.f - 0.5f), dy = 0.05f * (float(i / 100) / 200.f - 0.5f);
    float coverage;
    const float g = integrator.radiance(Ray{{dx, dy, 5.f}, {0.f, 0.f, -1.f}}, 0, &coverage).g;
    sum += g;
    sum2 += double(g) * g;
  }
  const double mean = sum / n, variance = std::max(0.0, sum2 / n - mean * mean);
  return {float(mean), float(std::sqrt(variance / n))};
}

TEST(PbrShading, WhiteFurnaceUnderAUniformEnvironment) {
  // A white metal of roughness 0.2 reflects 0.9983 at normal incidence, a
  // rough white dielectric 0.9722 (tests/unit/pbr_brdf_test.cpp's furnace,
  // to 1e-3 over the rays' n.v > 0.9996).
  Material metal = white_matte();
  metal.pbr.metallic = 1.f;
  metal.pbr.roughness = 0.2f;
  Material dielectric = white_matte();
  struct Case {
    Material m;
    float albedo;
  };
  for (const Case& c : {Case{metal, 0.9983f}, Case{dielectric, 0.9722f}}) {
    const Estimate e = furnace(c.m, true);
    std::printf("furnace, metallic %.0f: %.5f +- %.5f (albedo %.4f)\n", c.m.pbr.metallic, e.mean, e.standard_error,
                c.albedo);
    EXPECT_NEAR(e.mean, c.albedo, 3.f * e.standard_error + 1e-3f)
        << "metallic " << c.m.pbr.metallic << ": " << e.mean << " +- " << e.standard_error;
  }
}

// The deterministic first picture's approximation (1 sample a pixel: the
// unshadowed irradiance on the diffuse base, the blurred environment in the
// mirror ray) in the same furnace: the metal as sampled, the dielectric
// within the approximation's error, measured (its diffuse weight 1 - F(n.v)
// leaves out the specular lobe's loss).
TEST(PbrShading, WhiteFurnaceOfTheFirstPicture) {
  Material metal = white_matte();
  metal.pbr.metallic = 1.f;
  metal.pbr.roughness = 0.2f;
  const Estimate m = furnace(metal, false), d = furnace(white_matte(), false);
  std::printf("first picture's furnace: metal %.5f, dielectric %.5f\n", m.mean, d.mean);
  EXPECT_EQ(m.standard_error, 0.f);  // no noise
  EXPECT_NEAR(m.mean, 0.9983f, 2e-3f);
  EXPECT_NEAR(d.mean, 0.9722f, 0.04f);
}

// Under an environment each sample's random numbers come from its camera
// ray (ray_seed): the picture is the same whatever the threads and tiles.
TEST(PbrShading, EnvironmentPicturesDoNotDependOnThreadsOrTiles) {
  Scene s;
  s.spheres.push_back(Sphere{vec3(0.f), 1.f});
  Material m = white_matte();
  m.pbr.metallic = 0.5f;
  m.pbr.roughness = 0.4f;
  s.materials = {m};
  test::add_root_group(s, {test::shape_node(ShapeKind::sphere, 0, 0)});
  Camera c;
  c.center = {0.f, 0.f, 5.f};
  s.cameras = {c};
  s.background.environment.source = Environment::Source::studio;
  const PreparedScene p = prepare_scene(s);
  RenderOptions o;
  o.width = o.height = 48;
  o.spp = 4;
  o.bounces = 4;
  o.threads = 1;
  o.tile_size = 16;
  const RenderResult one = render(p, o);
  o.threads = 2;
  o.tile_size = 7;
  const RenderResult two = render(p, o);
  ASSERT_EQ(one.color.pixels.size(), two.color.pixels.size());
  EXPECT_EQ(one.color.pixels, two.color.pixels);
  float sum = 0.f;
  for (float v : one.color.pixels) sum += v;
  EXPECT_GT(sum, 0.f);
}

}  // namespace
}  // namespace rayform
