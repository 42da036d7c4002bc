// Noise-free environment lighting (render/environment_filter.h): the SH
// irradiance against the closed forms and against direct quadrature of
// L max(0, n.w) over the map's texels, and the GGX-prefiltered levels
// (constant maps stay constant, a small bright patch spreads with roughness
// while its total stays, roughness 0 is the bilinear map), with rotation and
// intensity honoured by both.
#include "rayform/render/environment_filter.h"

#include "rayform/render/sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

namespace rayform {
namespace {

constexpr double dpi = std::numbers::pi;

// A width x height map whose texel holds f at its centre's direction (rotation 0).
EnvironmentMap map_of(int width, int height, const std::function<vec3(vec3)>& f, float intensity = 1.f,
                      float rotation = 0.f) {
  std::vector<float> rgb(size_t(width) * size_t(height) * 3);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const vec3 l = f(uv_to_direction(vec2((i + 0.5f) / float(width), (j + 0.5f) / float(height))));
      float* p = rgb.data() + (size_t(j) * size_t(width) + size_t(i)) * 3;
      p[0] = l.x, p[1] = l.y, p[2] = l.z;
    }
  return make_environment_map(width, height, std::move(rgb), intensity, rotation);
}

// Uniform on the unit sphere, from the counter hash (fixed seed).
vec3 random_direction(uint32_t index) {
  const float a = sample_random(31u, index, 0), b = sample_random(31u, index, 1);
  const float z = 1.f - 2.f * a, r = std::sqrt(std::max(0.f, 1.f - z * z)), phi = 2.f * pi * b;
  return vec3(r * std::cos(phi), z, r * std::sin(phi));
}

// E(n) = integral of L max(0, n.w) dw by quadrature over the map's texels
// (nearest-texel radiance, rotation and intensity applied), each texel split
// into sub x sub cells of exact solid angle evaluated at their centres.
dvec3 quadrature_irradiance(const EnvironmentMap& env, vec3 n, int sub = 2) {
  dvec3 e(0.0);
  const int w = env.width * sub, h = env.height * sub;
  for (int j = 0; j < h; ++j) {
    const double solid_angle = 2.0 * dpi / w * (std::cos(dpi * j / h) - std::cos(dpi * (j + 1) / h));
    for (int i = 0; i < w; ++i) {
      const vec3 d = uv_to_direction(vec2((i + 0.5f) / float(w), (j + 0.5f) / float(h)), env.rotation);
      const double c = std::max(0.0, double(glm::dot(n, d)));
      if (c > 0.0) e += solid_angle * c * dvec3(environment_radiance(env, d));
    }
  }
  return e;
}

// Integral of a map's radiance over the sphere (texel value times exact solid angle).
dvec3 map_integral(const EnvironmentMap& env) {
  dvec3 sum(0.0);
  for (int j = 0; j < env.height; ++j) {
    const double solid_angle =
        2.0 * dpi / env.width * (std::cos(dpi * j / env.height) - std::cos(dpi * (j + 1) / env.height));
    for (int i = 0; i < env.width; ++i) {
      const float* p = env.rgb.data() + (size_t(j) * size_t(env.width) + size_t(i)) * 3;
      sum += solid_angle * dvec3(p[0], p[1], p[2]);
    }
  }
  return sum * double(env.intensity);
}

void expect_near_rel(vec3 got, dvec3 want, double rel, double abs_floor = 0.0) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(double(got[c]), want[c], std::max(rel * std::abs(want[c]), abs_floor)) << "channel " << c;
}

TEST(EnvironmentShIrradiance, ConstantMapGivesPiTimesRadiance) {
  const vec3 l(0.3f, 0.5f, 2.f);
  const EnvironmentMap env = map_of(256, 128, [&](vec3) { return l; });
  const EnvironmentIrradiance e = environment_irradiance(env);
  for (uint32_t k = 0; k < 32; ++k) expect_near_rel(irradiance(e, random_direction(k)), dpi * dvec3(l), 1e-4);
  for (vec3 n : {vec3(0, 1, 0), vec3(0, -1, 0), vec3(1, 0, 0), vec3(0, 0, -1)})
    expect_near_rel(irradiance(e, n), dpi * dvec3(l), 1e-4);
}

TEST(EnvironmentShIrradiance, EmptyMapIsBlack) {
  const EnvironmentIrradiance e = environment_irradiance(EnvironmentMap{});
  EXPECT_EQ(irradiance(e, vec3(0, 1, 0)), vec3(0.f));
}

// L = 1 on the upper hemisphere (y > 0), 0 below. The step's SH projection
// has only bands 0 and 1 (plus odd bands >= 3, which the cosine kernel
// annihilates), so SH2 irradiance is exact: E(n) = pi (1 + n_y) / 2, the
// sky-dome formula (E(+Y) = pi, E(-Y) = 0). The SH coefficients themselves ring
// (the radiance rebuilt from them is 1/2 + 3/4 y, not a step), the irradiance
// does not: checked against the closed form and against quadrature of the map.
TEST(EnvironmentShIrradiance, UpperHemisphereStepIsTheSkyDomeFormula) {
  const EnvironmentMap env = map_of(256, 128, [](vec3 d) { return vec3(d.y > 0.f ? 1.f : 0.f); });
  const EnvironmentIrradiance e = environment_irradiance(env);
  EXPECT_NEAR(e.sh[0].x, 0.282095 * 2.0 * dpi, 1e-4);  // integral of Y00 over the upper half
  EXPECT_NEAR(e.sh[1].x, 0.488603 * dpi, 1e-3);        // integral of 0.488603 y over the upper half
  for (size_t k = 4; k < 9; ++k) EXPECT_NEAR(e.sh[k].x, 0.0, 1e-3) << "band 2, k = " << k;

  EXPECT_NEAR(irradiance(e, vec3(0, 1, 0)).x, dpi, 1e-3 * dpi);
  EXPECT_NEAR(irradiance(e, vec3(0, -1, 0)).x, 0.0, 1e-3 * dpi);
  for (uint32_t k = 0; k < 12; ++k) {
    const vec3 n = random_direction(k);
    const double closed_form = dpi * (1.0 + n.y) / 2.0;
    EXPECT_NEAR(irradiance(e, n).x, closed_form, 1e-3 * dpi) << "n.y = " << n.y;
    EXPECT_NEAR(quadrature_irradiance(env, n).x, closed_form, 1e-3 * dpi) << "n.y = " << n.y;
  }
}

// L = 1 + 0.5 y + 0.25 x (per channel scaled) lies in SH band 0 and 1: E is
// pi + (2 pi / 3) (0.5 n_y + 0.25 n_x) exactly, and quadrature of the map agrees.
TEST(EnvironmentShIrradiance, LinearMapMatchesQuadratureAndClosedForm) {
  const vec3 scale(1.f, 0.5f, 2.f);
  const EnvironmentMap env = map_of(256, 128, [&](vec3 d) { return scale * (1.f + 0.5f * d.y + 0.25f * d.x); });
  const EnvironmentIrradiance e = environment_irradiance(env);
  for (uint32_t k = 0; k < 12; ++k) {
    const vec3 n = random_direction(100 + k);
    const dvec3 closed_form = dvec3(scale) * (dpi + 2.0 * dpi / 3.0 * (0.5 * n.y + 0.25 * n.x));
    expect_near_rel(irradiance(e, n), quadrature_irradiance(env, n), 1e-3);
    expect_near_rel(irradiance(e, n), closed_form, 1e-3);
  }
}

// A quadratic map lies in bands 0 to 2, where SH2 irradiance is exact too
// (this one checks the band-2 factor A2 = pi / 4).
TEST(EnvironmentShIrradiance, QuadraticMapMatchesQuadrature) {
  const EnvironmentMap env =
      map_of(256, 128, [](vec3 d) { return vec3(3.f * d.y * d.y, 1.f + d.x * d.z, 0.5f + d.x * d.x - d.z * d.y); });
  const EnvironmentIrradiance e = environment_irradiance(env);
  for (uint32_t k = 0; k < 8; ++k) {
    const vec3 n = random_direction(150 + k);
    expect_near_rel(irradiance(e, n), quadrature_irradiance(env, n), 2e-3, 2e-3);
  }
}

// Rotation turns the lighting with the map (a normal turned by R_y(rotation)
// sees what the unrotated map shows the unturned normal), intensity scales it.
TEST(EnvironmentShIrradiance, RotationAndIntensityAreHonoured) {
  const auto f = [](vec3 d) {
    return vec3(1.f + 0.8f * d.x + 0.3f * d.z * d.x, 0.5f + 0.4f * d.z, 0.2f + std::max(0.f, d.x - 0.7f) * 20.f);
  };
  const float rotation = 0.7f, intensity = 2.5f;
  const EnvironmentIrradiance plain = environment_irradiance(map_of(128, 64, f));
  const EnvironmentMap turned_map = map_of(128, 64, f, intensity, rotation);
  const EnvironmentIrradiance turned = environment_irradiance(turned_map);
  const float c = std::cos(rotation), s = std::sin(rotation);
  for (uint32_t k = 0; k < 16; ++k) {
    const vec3 n = random_direction(200 + k);
    const vec3 rn(n.x * c + n.z * s, n.y, -n.x * s + n.z * c);
    expect_near_rel(irradiance(turned, rn), dvec3(intensity * irradiance(plain, n)), 1e-4, 1e-5);
  }
  // The map's +X appears towards (cos r, 0, -sin r); and a direct quadrature agrees.
  const vec3 towards(c, 0.f, -s);
  expect_near_rel(irradiance(turned, towards), dvec3(intensity * irradiance(plain, vec3(1, 0, 0))), 1e-4);
  const dvec3 quad = quadrature_irradiance(turned_map, towards, 2);
  EXPECT_NEAR(irradiance(turned, towards).x, quad.x, 0.02 * quad.x);  // SH2 of a non-polynomial map
  EXPECT_GT(irradiance(turned, towards).x, 1.5f * irradiance(turned, -towards).x);
}

// The default studio (environment_map.h) is scaled so that the exact E(+Y)
// of its nearest-texel map is pi studio_up_radiance. Its softboxes are not
// low-order: SH2 misses a little of it (ringing), within 3 %.
TEST(EnvironmentShIrradiance, StudioUpIrradianceWithinTheSh2Error) {
  const EnvironmentMap env = studio_environment();
  const double sh = irradiance(environment_irradiance(env), vec3(0, 1, 0)).x;
  EXPECT_NEAR(quadrature_irradiance(env, vec3(0, 1, 0)).x, dpi * studio_up_radiance, 1e-3 * dpi);
  EXPECT_NEAR(sh, dpi * studio_up_radiance, 0.03 * dpi * studio_up_radiance);
  EXPECT_LT(sh, dpi * studio_up_radiance);  // the ringing's sign for this map
}

TEST(PrefilteredEnvironment, LevelsAndTheirSizes) {
  const EnvironmentMap env = map_of(256, 128, [](vec3) { return vec3(1.f); });
  const PrefilteredEnvironment p = prefilter_environment(env);
  ASSERT_EQ(p.level_count, 6);
  ASSERT_EQ(p.levels.size(), 5u);
  EXPECT_EQ(p.levels[0].width, 64);
  EXPECT_EQ(p.levels[0].height, 32);
  for (size_t k = 1; k < 5; ++k) {
    EXPECT_EQ(p.levels[k].width, 32);
    EXPECT_EQ(p.levels[k].height, 16);
  }
  // A map smaller than the levels keeps its own size.
  const PrefilteredEnvironment small = prefilter_environment(map_of(16, 8, [](vec3) { return vec3(1.f); }), 3);
  ASSERT_EQ(small.levels.size(), 2u);
  EXPECT_EQ(small.levels[0].width, 16);
  EXPECT_EQ(small.levels[1].height, 8);
  // No levels: the map itself for every roughness.
  const PrefilteredEnvironment none = prefilter_environment(env, 1);
  EXPECT_TRUE(none.levels.empty());
  EXPECT_EQ(prefiltered_radiance(none, env, vec3(1, 0, 0), 0.7f), environment_radiance_bilinear(env, vec3(1, 0, 0)));
}

TEST(PrefilteredEnvironment, ConstantMapStaysConstant) {
  const vec3 l(0.25f, 1.f, 4.f);
  const EnvironmentMap env = map_of(
      200, 100, [&](vec3) { return l; }, 1.5f, 0.4f);
  const PrefilteredEnvironment p = prefilter_environment(env);
  for (const EnvironmentMap& level : p.levels) {
    EXPECT_EQ(level.intensity, 1.f);
    EXPECT_EQ(level.rotation, 0.f);
    for (size_t k = 0; k < level.rgb.size(); ++k) EXPECT_NEAR(level.rgb[k], 1.5f * l[int(k % 3)], 1e-5f * 6.f);
  }
  for (uint32_t k = 0; k < 32; ++k)
    expect_near_rel(prefiltered_radiance(p, env, random_direction(300 + k), float(k) / 31.f), dvec3(1.5f * l), 1e-5);
}

TEST(PrefilteredEnvironment, RoughnessZeroIsTheBilinearMapAndLevelsBlendLinearly) {
  const EnvironmentMap env = map_of(
      96, 48, [](vec3 d) { return vec3(1.f + d.x, 2.f + std::sin(5.f * d.z), 0.5f + d.y * d.y); }, 1.3f, 1.1f);
  const PrefilteredEnvironment p = prefilter_environment(env, 6);
  for (uint32_t k = 0; k < 32; ++k) {
    const vec3 d = random_direction(400 + k);
    EXPECT_EQ(prefiltered_radiance(p, env, d, 0.f), environment_radiance_bilinear(env, d));
    EXPECT_EQ(prefiltered_radiance(p, env, d, -1.f), environment_radiance_bilinear(env, d));
    EXPECT_EQ(prefiltered_radiance(p, env, d, 1.f), environment_radiance_bilinear(p.levels[4], d));
    EXPECT_EQ(prefiltered_radiance(p, env, d, 2.f), environment_radiance_bilinear(p.levels[4], d));
    EXPECT_EQ(prefiltered_radiance(p, env, d, 0.4f), environment_radiance_bilinear(p.levels[1], d));
    const vec3 half = 0.5f * (environment_radiance_bilinear(env, d) + environment_radiance_bilinear(p.levels[0], d));
    expect_near_rel(prefiltered_radiance(p, env, d, 0.1f), dvec3(half), 1e-5);
    const vec3 mid =
        0.75f * environment_radiance_bilinear(p.levels[2], d) + 0.25f * environment_radiance_bilinear(p.levels[3], d);
    expect_near_rel(prefiltered_radiance(p, env, d, 0.65f), dvec3(mid), 1e-5);
  }
}

// One small bright patch (4 x 4 texels of a 256 x 128 map around +X) on
// black: with roughness the peak in the patch's direction falls and the light
// spreads (its radiance-weighted mean angle from +X grows), while the
// integral over the sphere stays that of the map.
TEST(PrefilteredEnvironment, BrightPatchSpreadsWithRoughnessAndKeepsItsTotal) {
  constexpr int w = 256, h = 128;
  std::vector<float> rgb(size_t(w) * h * 3, 0.f);
  for (int j = h / 2 - 2; j < h / 2 + 2; ++j)
    for (int i = w / 2 - 2; i < w / 2 + 2; ++i)
      for (int c = 0; c < 3; ++c) rgb[(size_t(j) * w + size_t(i)) * 3 + size_t(c)] = 100.f;
  const EnvironmentMap env = make_environment_map(w, h, std::move(rgb));
  const PrefilteredEnvironment p = prefilter_environment(env, 6);
  const dvec3 total = map_integral(env);

  float previous_peak = prefiltered_radiance(p, env, vec3(1, 0, 0), 0.f).x;
  EXPECT_NEAR(previous_peak, 100.f, 1e-3f);
  double previous_spread = 0.0;
  for (int k = 1; k < 6; ++k) {
    const EnvironmentMap& level = p.levels[size_t(k - 1)];
    const float peak = prefiltered_radiance(p, env, vec3(1, 0, 0), float(k) / 5.f).x;
    EXPECT_LT(peak, 0.8f * previous_peak) << "level " << k;
    EXPECT_GT(peak, 0.f);
    previous_peak = peak;
    // Radiance-weighted mean angle (radians) between +X and the level's texels.
    double weighted_angle = 0.0, weight = 0.0;
    for (int j = 0; j < level.height; ++j)
      for (int i = 0; i < level.width; ++i) {
        const vec3 d = uv_to_direction(vec2((i + 0.5f) / float(level.width), (j + 0.5f) / float(level.height)));
        const double l = level.rgb[(size_t(j) * level.width + size_t(i)) * 3] *
                         (std::cos(dpi * j / level.height) - std::cos(dpi * (j + 1) / level.height));
        weighted_angle += l * std::acos(std::clamp(double(d.x), -1.0, 1.0));
        weight += l;
      }
    const double spread = weighted_angle / weight;
    EXPECT_GT(spread, previous_spread + 0.05) << "level " << k;
    previous_spread = spread;
    const dvec3 level_total = map_integral(level);
    EXPECT_NEAR(level_total.x, total.x, 0.01 * total.x) << "level " << k;
  }
  // Roughness 1 (alpha 1, D constant) is the cosine lobe: the patch's
  // direction sees total / pi, and the mean angle of max(0, cos) is pi / 4.
  EXPECT_NEAR(previous_peak, total.x / dpi, 0.02 * total.x / dpi);
  EXPECT_NEAR(previous_spread, dpi / 4.0, 0.01);
}

// The prefiltered levels are in the world frame: a rotated, brighter map's
// level at R_y(rotation) d is the plain map's at d times the intensity (up to
// resampling: the levels' grid does not turn with the map).
TEST(PrefilteredEnvironment, RotationAndIntensityAreHonoured) {
  const auto f = [](vec3 d) { return vec3(1.f + d.x + 0.5f * d.z, 1.f, 1.f + std::max(0.f, d.x) * 3.f); };
  const float rotation = 0.9f, intensity = 3.f;
  const EnvironmentMap plain = map_of(128, 64, f), turned = map_of(128, 64, f, intensity, rotation);
  const PrefilteredEnvironment pp = prefilter_environment(plain), pt = prefilter_environment(turned);
  const float c = std::cos(rotation), s = std::sin(rotation);
  for (float roughness : {0.f, 0.3f, 0.6f, 1.f})
    for (uint32_t k = 0; k < 16; ++k) {
      const vec3 d = random_direction(500 + k);
      const vec3 rd(d.x * c + d.z * s, d.y, -d.x * s + d.z * c);
      expect_near_rel(prefiltered_radiance(pt, turned, rd, roughness),
                      dvec3(intensity * prefiltered_radiance(pp, plain, d, roughness)), 0.02);
    }
}

}  // namespace
}  // namespace rayform
