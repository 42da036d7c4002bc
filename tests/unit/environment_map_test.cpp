// Equirectangular environment maps (render/environment_map.h): the direction
// <-> (u, v) mapping of ../shared/reference-pbr/NOTES.md and its rotation, the
// lookups, and the importance-sampling distribution against numerical
// integration: the pdf integrates to 1 and follows the map, samples land where
// the weights say, Monte Carlo irradiance agrees with quadrature within 3
// standard errors, white furnaces, and the studio environment's brightness.
// Random numbers come from the counter hash of render/sampling.h with fixed
// seeds, so every statistical test is deterministic.
#include "rayform/render/environment_map.h"

#include "rayform/base/error.h"
#include "rayform/image/image.h"
#include "rayform/math/hash.h"
#include "rayform/render/sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

namespace rayform {
namespace {

constexpr double dpi = std::numbers::pi;

float random(uint32_t seed, uint32_t index, uint32_t dim) { return sample_random(seed, index, dim); }

vec2 random2(uint32_t seed, uint32_t index) { return vec2(random(seed, index, 0), random(seed, index, 1)); }

// Uniform on the unit sphere.
vec3 random_direction(uint32_t seed, uint32_t index) {
  const vec2 u = random2(seed, index);
  const float z = 1.f - 2.f * u.x, r = std::sqrt(std::max(0.f, 1.f - z * z)), phi = 2.f * pi * u.y;
  return vec3(r * std::cos(phi), z, r * std::sin(phi));
}

// A map whose texel (i, j) is f(i, j).
EnvironmentMap map_of(int w, int h, const std::function<vec3(int, int)>& f, float intensity = 1.f,
                      float rotation = 0.f) {
  std::vector<float> rgb;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const vec3 c = f(i, j);
      rgb.insert(rgb.end(), {c.r, c.g, c.b});
    }
  return make_environment_map(w, h, std::move(rgb), intensity, rotation);
}

// A non-uniform test map: a smooth variation, a few bright texels, black
// texels (weight 0) and one negative texel, coloured so that luminance and
// the channels differ.
vec3 busy_texel(int i, int j) {
  if (i == 5 && j == 3) return vec3(40.f, 30.f, 20.f);
  if (i == 17 && j == 9) return vec3(5.f, 80.f, 2.f);
  if (i == 0 && j == 0) return vec3(20.f);  // next to the pole: tiny sin(theta)
  if ((i + 3 * j) % 11 == 0) return vec3(0.f);
  if (i == 8 && j == 8) return vec3(-0.01f, 0.02f, -0.03f);
  const float a = 0.5f + 0.4f * std::sin(0.7f * float(i)) * std::cos(0.45f * float(j));
  return vec3(a, 0.8f * a + 0.1f, 0.3f + 0.05f * float(i % 4));
}

// The texel's own luminance weight, in double, for expected values.
double expected_weight(vec3 c, int j, int h) {
  const double y = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
  return std::max(0.0, y) * std::sin(dpi * (j + 0.5) / h);
}

// The mapping's inverse, written out from NOTES.md in double: (u, v) -> unit
// direction for a map turned by `rotation` about +Y.
dvec3 direction_of(double u, double v, double rotation) {
  const double phi = 2.0 * dpi * (u - 0.5) - rotation, theta = dpi * v;
  return dvec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
}

// integral over the sphere of L(d) max(n.d, 0) d omega for the map read with
// nearest texels: per texel, a sub x sub midpoint grid in (u, v) with
// d omega = 2 pi^2 sin(theta) du dv. Independent of the code under test.
dvec3 quadrature_irradiance(int w, int h, const std::function<vec3(int, int)>& f, dvec3 n, double rotation = 0.0,
                            int sub = 16) {
  dvec3 e(0.0);
  const double du = 1.0 / (double(w) * sub), dv = 1.0 / (double(h) * sub);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      double sum = 0.0;
      for (int b = 0; b < sub; ++b) {
        const double v = (j * sub + b + 0.5) * dv;
        for (int a = 0; a < sub; ++a) {
          const double u = (i * sub + a + 0.5) * du;
          const dvec3 d = direction_of(u, v, rotation);
          sum += std::max(glm::dot(n, d), 0.0) * 2.0 * dpi * dpi * std::sin(dpi * v) * du * dv;
        }
      }
      const vec3 c = f(i, j);
      e += dvec3(c) * sum;
    }
  return e;
}

// Mean and standard error of the importance-sampled estimate of irradiance
// at normal n (per channel): L(d) max(n.d, 0) / pdf(d), d ~ environment pdf.
struct Estimate {
  dvec3 mean, standard_error;
};
Estimate mc_irradiance(const EnvironmentMap& map, vec3 n, int count, uint32_t seed) {
  dvec3 sum(0.0), sum2(0.0);
  for (int k = 0; k < count; ++k) {
    const EnvironmentSample s = sample_environment(map, random2(seed, uint32_t(k)));
    dvec3 f(0.0);
    if (s.pdf > 0.f) f = dvec3(s.radiance) * double(std::max(glm::dot(n, s.direction), 0.f)) / double(s.pdf);
    sum += f;
    sum2 += f * f;
  }
  const dvec3 mean = sum / double(count);
  const dvec3 variance = (sum2 / double(count) - mean * mean) * (double(count) / (count - 1));
  return {mean, glm::sqrt(glm::max(variance, dvec3(0.0)) / double(count))};
}

// float rounding of the mapping's trigonometry: a few ulps of pi.
constexpr float mapping_tolerance = 2e-6f;

// --- the mapping ---------------------------------------------------------

TEST(EnvironmentMapping, AxisDirectionsLandWhereNotesSay) {
  const struct {
    vec3 d;
    vec2 uv;
  } cases[] = {
      {{1, 0, 0}, {0.5f, 0.5f}},        // +X: the image centre
      {{0, 0, -1}, {0.25f, 0.5f}},      // -Z
      {{0, 0, 1}, {0.75f, 0.5f}},       // +Z
      {{-1, 0, 0}, {0.f, 0.5f}},        // -X: the left/right seam (u wraps to 0)
      {{3, 4, 0}, {0.5f, 0.2048328f}},  // any length: acos(0.8) / pi
  };
  for (const auto& c : cases) {
    const vec2 uv = direction_to_uv(c.d);
    EXPECT_NEAR(uv.x, c.uv.x, mapping_tolerance) << c.d.x << " " << c.d.y << " " << c.d.z;
    EXPECT_NEAR(uv.y, c.uv.y, mapping_tolerance) << c.d.x << " " << c.d.y << " " << c.d.z;
  }
  EXPECT_EQ(direction_to_uv(vec3(0, 1, 0)).y, 0.f);        // +Y: the top edge
  EXPECT_EQ(direction_to_uv(vec3(0, -2, 0)).y, 1.f);       // -Y: the bottom edge
  EXPECT_GE(direction_to_uv(vec3(-1, 0, -1e-7f)).x, 0.f);  // just below the seam: u in [0, 1)
  EXPECT_LT(direction_to_uv(vec3(-1, 0, -1e-7f)).x, 1.f);
  EXPECT_TRUE(std::isnan(direction_to_uv(vec3(0.f)).x));
  // Looking along +X, +Z is to the right: u grows from -Z through +X to +Z.
  EXPECT_LT(direction_to_uv(vec3(1, 0, -0.1f)).x, 0.5f);
  EXPECT_GT(direction_to_uv(vec3(1, 0, 0.1f)).x, 0.5f);

  // The same through the lookup: a 9 x 5 map (axis directions at texel
  // centres) whose texel (i, j) holds (i, j, 1).
  const EnvironmentMap map = map_of(9, 5, [](int i, int j) { return vec3(float(i), float(j), 1.f); });
  EXPECT_EQ(environment_radiance(map, vec3(1, 0, 0)), vec3(4, 2, 1));   // centre column 4.5 / 9
  EXPECT_EQ(environment_radiance(map, vec3(0, 0, -1)), vec3(2, 2, 1));  // u = 0.25: column 2.25
  EXPECT_EQ(environment_radiance(map, vec3(0, 0, 1)), vec3(6, 2, 1));   // u = 0.75: column 6.75
  EXPECT_EQ(environment_radiance(map, vec3(-1, 0, 0)), vec3(0, 2, 1));
  EXPECT_EQ(environment_radiance(map, vec3(0, 1, 0)), vec3(4, 0, 1));   // top row
  EXPECT_EQ(environment_radiance(map, vec3(0, -1, 0)), vec3(4, 4, 1));  // bottom row
  EXPECT_EQ(environment_radiance(map, vec3(0.f)), vec3(0.f));
}

TEST(EnvironmentMapping, AgreesWithTheNotesFormulaInDouble) {
  for (uint32_t k = 0; k < 4096; ++k) {
    const vec3 d = random_direction(1, k) * (0.25f + 4.f * random(1, k, 5));
    const dvec3 dd(d);
    double u = 0.5 + std::atan2(dd.z, dd.x) / (2.0 * dpi);
    u -= std::floor(u);
    const double v = std::acos(dd.y / glm::length(dd)) / dpi;
    const vec2 uv = direction_to_uv(d);
    const double du = std::abs(uv.x - u);
    EXPECT_LT(std::min(du, 1.0 - du), mapping_tolerance) << k;  // across the seam u = 0 = 1
    EXPECT_NEAR(uv.y, v, mapping_tolerance) << k;
  }
}

TEST(EnvironmentMapping, RoundTripsWithRotation) {
  for (float rotation : {0.f, 0.7f, -2.5f, 2.f * pi, 10.f}) {
    float worst = 0.f, worst_uv = 0.f;
    for (uint32_t k = 0; k < 10000; ++k) {
      const vec3 d = random_direction(2, k);
      const vec2 uv = direction_to_uv(d, rotation);
      ASSERT_GE(uv.x, 0.f);
      ASSERT_LT(uv.x, 1.f);
      worst = std::max(worst, glm::length(uv_to_direction(uv, rotation) - d));
      // And (u, v) -> d -> (u, v) away from the poles (where u is undefined).
      const vec2 uv0(random(3, k, 0), 0.01f + 0.98f * random(3, k, 1));
      const vec2 back = direction_to_uv(uv_to_direction(uv0, rotation), rotation);
      const float du = std::abs(back.x - uv0.x);
      worst_uv = std::max({worst_uv, std::min(du, 1.f - du), std::abs(back.y - uv0.y)});
    }
    // The rotation's own rounding (up to 10 rad here) adds its ulp to phi.
    EXPECT_LT(worst, 4.f * mapping_tolerance) << rotation;
    EXPECT_LT(worst_uv, 4.f * mapping_tolerance) << rotation;
  }
}

TEST(EnvironmentMapping, RotationTurnsTheEnvironmentAboutY) {
  const float r = 0.6f;
  // The map's centre column (+X unrotated) appears towards (cos r, 0, -sin r).
  EXPECT_NEAR(direction_to_uv(vec3(std::cos(r), 0.f, -std::sin(r)), r).x, 0.5f, mapping_tolerance);
  const vec3 c = uv_to_direction(vec2(0.5f), r);
  EXPECT_NEAR(c.x, std::cos(r), mapping_tolerance);
  EXPECT_NEAR(c.z, -std::sin(r), mapping_tolerance);
  // What the unrotated map shows towards d, the rotated one shows towards
  // R_y(r) d (right-handed: x' = x cos r + z sin r, z' = -x sin r + z cos r).
  const EnvironmentMap plain = map_of(24, 12, busy_texel), turned = map_of(24, 12, busy_texel, 1.f, r);
  for (uint32_t k = 0; k < 2000; ++k) {
    const vec3 d = random_direction(4, k);
    const vec3 rd(d.x * std::cos(r) + d.z * std::sin(r), d.y, -d.x * std::sin(r) + d.z * std::cos(r));
    const vec2 a = direction_to_uv(d), b = direction_to_uv(rd, r);
    const float du = std::abs(a.x - b.x);
    EXPECT_LT(std::min(du, 1.f - du), 2.f * mapping_tolerance) << k;
    EXPECT_NEAR(a.y, b.y, 2.f * mapping_tolerance) << k;
    const vec3 la = environment_radiance_bilinear(plain, d), lb = environment_radiance_bilinear(turned, rd);
    EXPECT_LT(glm::length(la - lb), 1e-3f * (1.f + glm::length(la))) << k;  // bilinear: continuous in d
  }
}

// --- lookups --------------------------------------------------------------

TEST(EnvironmentLookup, NearestAndBilinearWithIntensityAndSeam) {
  const EnvironmentMap map = map_of(
      8, 4, [](int i, int j) { return vec3(float(i), float(10 * j), 1.f); }, 2.f);
  auto at = [](float u, float v) { return uv_to_direction(vec2(u, v)); };
  // At a texel centre both lookups give the texel, times intensity 2.
  EXPECT_EQ(environment_radiance(map, at(2.5f / 8, 1.5f / 4)), vec3(4.f, 20.f, 2.f));
  const vec3 centre = environment_radiance_bilinear(map, at(2.5f / 8, 1.5f / 4));
  EXPECT_NEAR(centre.x, 4.f, 1e-4f);
  EXPECT_NEAR(centre.y, 20.f, 1e-3f);
  // Halfway between the centres of columns 2 and 3 (u = 3/8, v at row 1's centre).
  const vec3 mid = environment_radiance_bilinear(map, at(3.f / 8, 1.5f / 4));
  EXPECT_NEAR(mid.x, 5.f, 1e-4f);  // (2 + 3) / 2 * 2
  EXPECT_NEAR(mid.y, 20.f, 1e-3f);
  // At the seam (u = 0, -X): halfway between columns 7 and 0.
  const vec3 seam = environment_radiance_bilinear(map, vec3(-1.f, 0.f, 0.f));
  EXPECT_NEAR(seam.x, 7.f, 1e-4f);   // (7 + 0) / 2 * 2
  EXPECT_NEAR(seam.y, 30.f, 1e-3f);  // v = 0.5: halfway between rows 1 and 2, (10 + 20) / 2 * 2
  // Above the top row's centre, clamped to the top row.
  EXPECT_NEAR(environment_radiance_bilinear(map, vec3(0.f, 1.f, 0.f)).y, 0.f, 1e-6f);
  EXPECT_EQ(environment_radiance_bilinear(map, vec3(0.f)), vec3(0.f));
}

TEST(EnvironmentLookup, BuildsFromImagesAndRejectsBadInput) {
  Image rgba(4, 2, 4);
  for (size_t k = 0; k < rgba.pixels.size(); ++k) rgba.pixels[k] = float(k);
  const EnvironmentMap map = environment_from_image(rgba, 0.5f, 0.25f);
  ASSERT_EQ(map.width, 4);
  ASSERT_EQ(map.height, 2);
  ASSERT_EQ(map.rgb.size(), 24u);
  EXPECT_EQ(map.rgb[3], 4.f);  // texel 1's red: alpha 3 dropped
  EXPECT_EQ(map.rgb[23], 30.f);
  EXPECT_EQ(map.intensity, 0.5f);
  EXPECT_EQ(map.rotation, 0.25f);
  EXPECT_THROW(environment_from_image(Image(4, 2, 1), 1.f, 0.f), Error);
  EXPECT_THROW(make_environment_map(0, 2, {}), Error);
  EXPECT_THROW(make_environment_map(2, 1, std::vector<float>(5)), Error);
  EXPECT_THROW(make_environment_map(1, 1, {0.f, NAN, 0.f}), Error);
  EXPECT_THROW(make_environment_map(1, 1, {1.f, 1.f, 1.f}, -1.f), Error);
  EXPECT_THROW(make_environment_map(1, 1, {1.f, 1.f, 1.f}, 1.f, INFINITY), Error);
}

// --- the sampling distribution -------------------------------------------

TEST(EnvironmentSampling, BlackMapIsNotSampled) {
  const EnvironmentMap map = map_of(8, 4, [](int, int) { return vec3(0.f); });
  EXPECT_FALSE(map.samplable);
  const EnvironmentSample s = sample_environment(map, vec2(0.3f, 0.6f));
  EXPECT_EQ(s.pdf, 0.f);
  EXPECT_EQ(s.radiance, vec3(0.f));
  EXPECT_EQ(environment_pdf(map, vec3(1.f, 0.f, 0.f)), 0.f);
  EXPECT_TRUE(map_of(8, 4, busy_texel).samplable);
}

TEST(EnvironmentSampling, PdfIntegratesToOneOverTheSphere) {
  for (float rotation : {0.f, 0.9f}) {
    const EnvironmentMap map = map_of(24, 12, busy_texel, 3.f, rotation);
    // Midpoint rule in (theta, phi) on a grid not aligned with the texels:
    // integral of pdf sin(theta) d theta d phi.
    const int n_theta = 1201, n_phi = 2399;
    double sum = 0.0;
    for (int a = 0; a < n_theta; ++a) {
      const double theta = (a + 0.5) * dpi / n_theta;
      double ring = 0.0;
      for (int b = 0; b < n_phi; ++b) {
        const double phi = (b + 0.5) * 2.0 * dpi / n_phi;
        const vec3 d(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
        ring += environment_pdf(map, d);
      }
      sum += ring * std::sin(theta) * (dpi / n_theta) * (2.0 * dpi / n_phi);
    }
    // Quadrature error: the grid cuts texel edges (the pdf jumps there).
    EXPECT_NEAR(sum, 1.0, 1e-4) << rotation;

    // The discrete probabilities the CDFs give sum to 1 and equal the weights' shares.
    double total_w = 0.0;
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 24; ++i) total_w += expected_weight(busy_texel(i, j), j, 12);
    double p_sum = 0.0;
    for (int j = 0; j < 12; ++j) {
      const double p_row = double(map.row_cdf[j + 1]) - map.row_cdf[j];
      for (int i = 0; i < 24; ++i) {
        const float* c = map.column_cdf.data() + j * 25;
        const double p = p_row * (double(c[i + 1]) - c[i]);
        p_sum += p;
        EXPECT_NEAR(p, expected_weight(busy_texel(i, j), j, 12) / total_w, 1e-6) << i << " " << j;
      }
    }
    EXPECT_NEAR(p_sum, 1.0, 1e-6);
  }
}

TEST(EnvironmentSampling, PdfFollowsTheMap) {
  const int w = 24, h = 12;
  const EnvironmentMap map = map_of(w, h, busy_texel, 1.f, 0.4f);
  double total_w = 0.0;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) total_w += expected_weight(busy_texel(i, j), j, h);
  // p_uv = w_ij W H / sum(w) and p = p_uv / (2 pi^2 sin theta): at any point
  // of texel (i, j), p sin(theta) / (Y_ij sin(theta_j)) = W H / (2 pi^2 sum(w)),
  // the same for every texel, the polar rows included.
  const double expected_ratio = w * h / (2.0 * dpi * dpi * total_w);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const vec3 c = busy_texel(i, j);
      const double y = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
      for (vec2 in_texel : {vec2(0.5f), vec2(0.1f, 0.2f), vec2(0.9f, 0.85f)}) {
        const vec2 uv((float(i) + in_texel.x) / w, (float(j) + in_texel.y) / h);
        const vec3 d = uv_to_direction(uv, map.rotation);
        const double pdf = environment_pdf(map, d);
        if (y <= 0.0) {
          EXPECT_EQ(pdf, 0.0) << i << " " << j;  // black and negative texels are never sampled
          continue;
        }
        const double sin_t = std::sin(dpi * uv.y), sin_j = std::sin(dpi * (j + 0.5) / h);
        EXPECT_NEAR(pdf * sin_t / (y * sin_j) / expected_ratio, 1.0, 2e-5) << i << " " << j;
      }
    }
}

TEST(EnvironmentSampling, BrightTexelsAreHitWithTheirProbability) {
  // Grey 0.1 everywhere, one bright texel mid-sphere and one in the top row
  // (whose weight sin(theta_0) is small): each is hit with probability
  // w / sum(w); the count is binomial.
  const int w = 32, h = 16;
  auto f = [](int i, int j) {
    if (i == 20 && j == 5) return vec3(100.f);
    if (i == 3 && j == 0) return vec3(0.f, 200.f, 0.f);
    return vec3(0.1f);
  };
  const EnvironmentMap map = map_of(w, h, f, 1.f, 1.3f);
  double total_w = 0.0;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) total_w += expected_weight(f(i, j), j, h);
  const double p_a = expected_weight(f(20, 5), 5, h) / total_w, p_b = expected_weight(f(3, 0), 0, h) / total_w;
  const int n = 65536;
  int hits_a = 0, hits_b = 0;
  for (int k = 0; k < n; ++k) {
    const EnvironmentSample s = sample_environment(map, random2(5, uint32_t(k)));
    if (s.radiance == vec3(100.f)) {
      ++hits_a;
      EXPECT_EQ(environment_radiance(map, s.direction), vec3(100.f)) << k;  // the direction lies in the texel
    }
    if (s.radiance.g == 200.f) ++hits_b;
  }
  const double se_a = std::sqrt(p_a * (1 - p_a) / n), se_b = std::sqrt(p_b * (1 - p_b) / n);
  EXPECT_NEAR(double(hits_a) / n, p_a, 3.0 * se_a);
  EXPECT_NEAR(double(hits_b) / n, p_b, 3.0 * se_b);
  // The expected values themselves: 100 sin(5.5 pi / 16) and 0.7152 * 200 sin(0.5 pi / 16) of 134.8.
  EXPECT_NEAR(p_a, 0.65443, 1e-5);
  EXPECT_NEAR(p_b, 0.10404, 1e-5);
}

TEST(EnvironmentSampling, SamplePdfEqualsEnvironmentPdf) {
  const EnvironmentMap map = map_of(24, 12, busy_texel, 2.f, -1.1f);
  const int n = 65536;
  int on_texel_edge = 0;
  for (int k = 0; k < n; ++k) {
    const EnvironmentSample s = sample_environment(map, random2(6, uint32_t(k)));
    ASSERT_GT(s.pdf, 0.f) << k;
    ASSERT_NEAR(glm::length(s.direction), 1.f, 4.f * machine_epsilon) << k;
    const float pdf = environment_pdf(map, s.direction);
    const vec3 l = environment_radiance(map, s.direction);
    if (pdf == s.pdf && l == s.radiance) continue;
    // Otherwise the rounding of the direction moved it across a texel edge:
    // it must lie within float precision of one.
    const vec2 uv = direction_to_uv(s.direction, map.rotation);
    const float fx = uv.x * 24.f - std::round(uv.x * 24.f), fy = uv.y * 12.f - std::round(uv.y * 12.f);
    EXPECT_LT(std::min(std::abs(fx), std::abs(fy)), 1e-4f) << k;
    ++on_texel_edge;
  }
  EXPECT_LE(on_texel_edge, n / 1000);
}

// --- irradiance: Monte Carlo against quadrature ----------------------------

TEST(EnvironmentIrradiance, ImportanceSampledMatchesQuadrature) {
  const int w = 24, h = 12;
  const float rotation = 0.3f;
  const EnvironmentMap map = map_of(w, h, busy_texel, 1.f, rotation);
  for (vec3 n : {vec3(0, 1, 0), vec3(0, -1, 0), vec3(1, 0, 0), glm::normalize(vec3(-0.3f, 0.5f, 0.8f))}) {
    const dvec3 q = quadrature_irradiance(w, h, busy_texel, dvec3(n), rotation);
    const Estimate e = mc_irradiance(map, n, 65536, 7);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(e.mean[c], q[c], 3.0 * e.standard_error[c]) << n.x << " " << n.y << " " << n.z << " ch " << c;
      EXPECT_LT(e.standard_error[c], 0.02 * q[c]);  // importance sampling keeps it small
    }
  }
}

TEST(EnvironmentIrradiance, ConstantMapGivesPiL) {
  const vec3 l(0.7f, 0.2f, 1.5f);
  auto f = [&](int, int) { return l; };
  const EnvironmentMap map = map_of(32, 16, f, 1.f, 2.f);
  for (vec3 n : {vec3(0, 1, 0), vec3(0, 0, -1), glm::normalize(vec3(0.6f, -0.3f, 0.2f))}) {
    const dvec3 q = quadrature_irradiance(32, 16, f, dvec3(n), 2.0);
    const Estimate e = mc_irradiance(map, n, 65536, 8);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(q[c], dpi * l[c], 1e-4 * dpi * l[c]);
      EXPECT_NEAR(e.mean[c], dpi * l[c], 3.0 * e.standard_error[c]);
    }
  }
}

TEST(EnvironmentIrradiance, WhiteFurnace) {
  // Radiance 1 everywhere: E = pi at every normal, and every sample carries 1.
  const EnvironmentMap map = map_of(64, 32, [](int, int) { return vec3(1.f); });
  for (uint32_t k = 0; k < 8; ++k) {
    const vec3 n = k < 2 ? vec3(0.f, k == 0 ? 1.f : -1.f, 0.f) : random_direction(9, k);
    const Estimate e = mc_irradiance(map, n, 65536, 10 + k);
    EXPECT_NEAR(e.mean.x, dpi, 3.0 * e.standard_error.x) << k;
    EXPECT_LT(e.standard_error.x, 0.01 * dpi) << k;
  }
  for (uint32_t k = 0; k < 1000; ++k) EXPECT_EQ(sample_environment(map, random2(11, k)).radiance, vec3(1.f));
}

// --- the studio environment ----------------------------------------------

TEST(StudioEnvironment, WhiteDiffuseFacingUpHasTheDocumentedRadiance) {
  const EnvironmentMap map = studio_environment();
  ASSERT_EQ(map.width, 256);
  ASSERT_EQ(map.height, 128);
  EXPECT_EQ(map.intensity, 1.f);
  auto f = [&](int i, int j) {
    const float* p = map.rgb.data() + (size_t(j) * 256 + i) * 3;
    return vec3(p[0], p[1], p[2]);
  };
  // Radiance of a white Lambertian surface = E / pi.
  const dvec3 q = quadrature_irradiance(256, 128, f, dvec3(0, 1, 0), 0.0, 4) / dpi;
  EXPECT_NEAR(q.x, studio_up_radiance, 1e-4);
  const Estimate e = mc_irradiance(map, vec3(0, 1, 0), 65536, 12);
  EXPECT_NEAR(e.mean.x / dpi, studio_up_radiance, 3.0 * e.standard_error.x / dpi);
  // Neutral: grey everywhere.
  for (size_t k = 0; k < map.rgb.size(); k += 3) {
    ASSERT_EQ(map.rgb[k], map.rgb[k + 1]);
    ASSERT_EQ(map.rgb[k], map.rgb[k + 2]);
  }
  // The design: floor 0.10 against the ceiling's 0.55, the key light
  // (6 above the backdrop) ahead of the rest, in front right above.
  const float up = environment_radiance(map, vec3(0, 1, 0)).x, down = environment_radiance(map, vec3(0, -1, 0)).x;
  EXPECT_NEAR(down / up, 0.10f / 0.55f, 1e-3f);
  const float key_e = radians(35.f), key_yaw = radians(45.f);
  const vec3 key_dir(std::sin(key_yaw) * std::cos(key_e), std::sin(key_e), std::cos(key_yaw) * std::cos(key_e));
  const float key = environment_radiance(map, key_dir).x;
  EXPECT_NEAR(key / up, (6.f + 0.42f + 0.13f * std::sin(key_e)) / 0.55f, 0.02f);
  float brightest = 0.f;
  for (size_t k = 0; k < map.rgb.size(); k += 3) brightest = std::max(brightest, map.rgb[k]);
  EXPECT_NEAR(brightest, key, 0.02f * key);
  const float rim_e = radians(40.f), rim_yaw = radians(160.f);  // the rim light behind
  const vec3 rim_dir(std::sin(rim_yaw) * std::cos(rim_e), std::sin(rim_e), std::cos(rim_yaw) * std::cos(rim_e));
  const float rim = environment_radiance(map, rim_dir).x;
  EXPECT_NEAR(rim / up, (4.f + 0.42f + 0.13f * std::sin(rim_e)) / 0.55f, 0.02f);
}

}  // namespace
}  // namespace rayform
