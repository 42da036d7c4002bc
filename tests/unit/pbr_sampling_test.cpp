// Importance sampling of the metallic-roughness BRDF (render/pbr_sampling.h)
// against numerical quadrature: the GGX visible-normal pdf's normalisation
// and the reflected and refracted directions' pdfs (their Jacobians) against
// the fraction of samples they account for, a chi-square test of the
// sampled normals against the pdf, the unbiasedness of sample_pbr's weights
// (their mean is the directional albedo of pbr_reflection integrated
// directly), pbr_pdf against the sampler, the shading frame and the MIS
// weights. Random numbers: sample_random (render/sampling.h) with fixed
// streams. Statistical tolerances are stated in standard errors (SE).
#include "rayform/render/pbr_sampling.h"
#include "rayform/render/sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace rayform {
namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;
const vec3 up(0.f, 0.f, 1.f);

vec3 view_at(float n_dot_v) { return vec3(std::sqrt(std::max(0.f, 1.f - n_dot_v * n_dot_v)), 0.f, n_dot_v); }

vec2 random2(uint32_t stream, uint32_t i) { return vec2(sample_random(stream, i, 0), sample_random(stream, i, 1)); }
vec3 random3(uint32_t stream, uint32_t i) {
  return vec3(sample_random(stream, i, 0), sample_random(stream, i, 1), sample_random(stream, i, 2));
}

// A point of the hemisphere about +z at polar parameter t in [0, 1) under
// the mapping tan(theta) = grid_alpha tan(pi t / 2), which puts a midpoint
// grid's points where a GGX lobe of that alpha lies; d_theta_dt its Jacobian.
struct PolarPoint {
  double theta, d_theta_dt;
};
PolarPoint polar_point(double t, double grid_alpha) {
  const double tan_t = std::tan(0.5 * std::numbers::pi * t);
  const double tan_h = grid_alpha * tan_t;
  return {std::atan(tan_h), grid_alpha * 0.5 * std::numbers::pi * (1.0 + tan_t * tan_t) / (1.0 + tan_h * tan_h)};
}

vec3 spherical(double theta, double phi) {
  return vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
}

// The integral of a function of direction over the hemisphere about +z
// (z_sign 1) or -z (z_sign -1), on a polar_steps x azimuth_steps midpoint grid
// in (t, phi) with the mapping of polar_point.
template <typename F>
double integrate_hemisphere(F&& f, double grid_alpha, int polar_steps, int azimuth_steps, float z_sign = 1.f) {
  const double dt = 1.0 / polar_steps, d_phi = two_pi / azimuth_steps;
  double sum = 0;
  for (int p = 0; p < polar_steps; ++p) {
    const PolarPoint q = polar_point((p + 0.5) * dt, grid_alpha);
    double row = 0;
    for (int a = 0; a < azimuth_steps; ++a) {
      vec3 w = spherical(q.theta, (a + 0.5) * d_phi);
      w.z *= z_sign;
      row += double(f(w));
    }
    sum += row * std::sin(q.theta) * q.d_theta_dt;
  }
  return sum * dt * d_phi;
}

// The integral over l of pbr_reflection (f cos), as an integral over the
// half vector h (l = 2 (v.h) h - v, d omega_l = 4 (v.h) d omega_h), as in
// pbr_brdf_test.cpp: no table and no code of the sampler under test.
vec3 directional_albedo(const PbrSurface& s, vec3 v, double grid_alpha, int polar_steps, int azimuth_steps) {
  const double dt = 1.0 / polar_steps, d_phi = two_pi / azimuth_steps;
  dvec3 sum(0.0);
  for (int p = 0; p < polar_steps; ++p) {
    const PolarPoint q = polar_point((p + 0.5) * dt, grid_alpha);
    const double area = std::sin(q.theta) * q.d_theta_dt * dt * d_phi;
    for (int a = 0; a < azimuth_steps; ++a) {
      const vec3 h = spherical(q.theta, (a + 0.5) * d_phi);
      const float v_dot_h = glm::dot(v, h);
      if (v_dot_h <= 0.f) continue;
      const vec3 l = glm::normalize(2.f * v_dot_h * h - v);
      sum += dvec3(pbr_reflection(s, up, v, l)) * (4.0 * v_dot_h * area);
    }
  }
  return vec3(sum);
}

// Mean and standard error of a stream of RGB values.
struct MeanEstimate {
  dvec3 sum{0.0}, sum2{0.0};
  long count = 0;
  void add(vec3 x) {
    sum += dvec3(x);
    sum2 += dvec3(x) * dvec3(x);
    ++count;
  }
  dvec3 mean() const { return sum / double(count); }
  dvec3 standard_error() const {
    const dvec3 m = mean();
    return glm::sqrt(glm::max(sum2 / double(count) - m * m, dvec3(0.0)) / double(count));
  }
};

TEST(PbrSampling, ShadingFrameIsOrthonormalRightHandedAndInvertible) {
  const std::array<vec3, 7> normals = {vec3(0, 0, 1), vec3(0, 0, -1),     vec3(1, 0, 0),           vec3(0, -1, 0),
                                       vec3(1, 2, 3), vec3(1e-4f, 0, -1), vec3(-0.3f, 0.5f, -0.8f)};
  const float tolerance = 8.f * machine_epsilon;
  for (vec3 n : normals) {
    n = glm::normalize(n);
    const ShadingFrame f = make_shading_frame(n);
    EXPECT_NEAR(glm::length(f.t), 1.f, tolerance);
    EXPECT_NEAR(glm::length(f.b), 1.f, tolerance);
    EXPECT_NEAR(glm::dot(f.t, f.b), 0.f, tolerance);
    EXPECT_NEAR(glm::dot(f.t, f.n), 0.f, tolerance);
    EXPECT_NEAR(glm::dot(f.b, f.n), 0.f, tolerance);
    EXPECT_NEAR(glm::length(glm::cross(f.t, f.b) - f.n), 0.f, tolerance);
    const vec3 w = glm::normalize(vec3(0.3f, -0.7f, 0.2f));
    EXPECT_NEAR(glm::length(to_world(f, to_local(f, w)) - w), 0.f, tolerance);
    EXPECT_NEAR(to_local(f, n).z, 1.f, tolerance);
  }
}

TEST(PbrSampling, SmithG1MatchesTheHeightCorrelatedVisibility) {
  // G2 = 4 V (n.l) (n.v) = 1 / (1 + Lambda(v) + Lambda(l)) and 1 / G1 = 1 +
  // Lambda, so 1 / G2 = 1 / G1(v) + 1 / G1(l) - 1.
  for (float alpha : {min_ggx_alpha, 0.1f, 0.5f, 1.f})
    for (float nv : {0.05f, 0.4f, 1.f})
      for (float nl : {0.1f, 0.7f}) {
        const float g2 = 4.f * smith_visibility(nl, nv, alpha) * nl * nv;
        EXPECT_NEAR(1.f / g2, 1.f / smith_g1(nv, alpha) + 1.f / smith_g1(nl, alpha) - 1.f, 1e-5f / g2)
            << alpha << " " << nv << " " << nl;
      }
  EXPECT_FLOAT_EQ(smith_g1(1.f, 0.7f), 1.f);
  EXPECT_FLOAT_EQ(smith_g1(0.5f, 1.f), 0.5f * 2.f / 1.5f);  // alpha 1: 2 nv / (nv + 1)
}

TEST(PbrSampling, VisibleNormalPdfIntegratesToOne) {
  for (float alpha : {0.01f, 0.1f, 0.3f, 0.6f, 1.f})
    for (float nv : {0.05f, 0.3f, 0.7f, 1.f}) {
      const vec3 v = view_at(nv);
      const double integral = integrate_hemisphere([&](vec3 h) { return ggx_vndf_pdf(v, h, alpha); }, alpha, 800, 256);
      EXPECT_NEAR(integral, 1.0, 2e-3) << "alpha " << alpha << " n.v " << nv;
    }
}

TEST(PbrSampling, SampledVisibleNormalsAreVisibleAndInTheHemisphere) {
  for (float alpha : {min_ggx_alpha, 0.2f, 1.f})
    for (float nv : {1e-3f, 0.5f, 1.f}) {
      const vec3 v = view_at(nv);
      for (uint32_t i = 0; i < 2000; ++i) {
        const vec3 h = sample_ggx_vndf(v, alpha, random2(7, i));
        ASSERT_NEAR(glm::length(h), 1.f, 1e-5f);
        ASSERT_GE(h.z, 0.f);
        ASSERT_GE(glm::dot(v, h), -1e-5f) << alpha << " " << nv;
      }
    }
}

// The reflected direction's pdf over the upper hemisphere of l (quadrature
// on a fine uniform grid in (theta_l, phi_l), no mapping shared with the
// sampler) against the fraction of sampled normals whose reflection lands
// above the horizon; and over the whole sphere it integrates to 1.
TEST(PbrSampling, ReflectedDirectionPdfAccountsForTheSamplesAboveTheHorizon) {
  constexpr uint32_t samples = 100000;
  for (float alpha : {0.1f, 0.3f, 0.8f})
    for (float nv : {0.2f, 0.6f, 1.f}) {
      const vec3 v = view_at(nv);
      auto pdf = [&](vec3 l) { return ggx_reflection_pdf(v, l, alpha); };
      const double above = integrate_hemisphere(pdf, 1.0, 1024, 512);
      const double below = integrate_hemisphere(pdf, 1.0, 1024, 512, -1.f);
      uint32_t count = 0;
      for (uint32_t i = 0; i < samples; ++i) {
        const vec3 h = sample_ggx_vndf(v, alpha, random2(11, i));
        if ((2.f * glm::dot(v, h) * h - v).z > 0.f) ++count;
      }
      const double fraction = double(count) / samples;
      const double se = std::sqrt(fraction * (1.0 - fraction) / samples);
      const double quadrature_error = 2e-3;
      EXPECT_NEAR(above, fraction, 3.0 * se + quadrature_error) << "alpha " << alpha << " n.v " << nv;
      EXPECT_NEAR(above + below, 1.0, quadrature_error) << "alpha " << alpha << " n.v " << nv;
      // Seen along n, l = 2 (n.h) h - n is above the horizon where theta_h <
      // 45 degrees, of probability tan^2 / (alpha^2 + tan^2) = 1 / (alpha^2 + 1)
      // (the GGX's cumulative distribution; the VNDF at v = n is D (n.h)).
      if (nv == 1.f) {
        EXPECT_NEAR(above, 1.0 / (double(alpha) * alpha + 1.0), quadrature_error) << "alpha " << alpha;
      }
    }
}

// The same for refraction (the Jacobian of the generalised half vector):
// entering glass (eta 1.5: every visible facet refracts) and leaving it
// (eta 1 / 1.5: total internal reflection for part of the facets).
TEST(PbrSampling, RefractedDirectionPdfAccountsForTheRefractedSamples) {
  constexpr uint32_t samples = 100000;
  for (float eta : {1.5f, 1.f / 1.5f})
    for (float alpha : {0.1f, 0.3f, 0.7f})
      for (float nv : {0.3f, 0.8f}) {
        const vec3 v = view_at(nv);
        const double integral =
            integrate_hemisphere([&](vec3 l) { return ggx_refraction_pdf(v, l, alpha, eta); }, 1.0, 1024, 512, -1.f);
        uint32_t count = 0;
        for (uint32_t i = 0; i < samples; ++i) {
          const vec3 l = refract_through(v, sample_ggx_vndf(v, alpha, random2(13, i)), eta);
          if (l.z < 0.f) ++count;
        }
        const double fraction = double(count) / samples;
        const double se = std::sqrt(fraction * (1.0 - fraction) / samples);
        EXPECT_NEAR(integral, fraction, 3.0 * se + 2e-3) << "eta " << eta << " alpha " << alpha << " n.v " << nv;
        if (eta > 1.f) {
          EXPECT_GT(fraction, 0.9);
        } else if (nv < 0.5f) {
          EXPECT_LT(fraction, 0.5);  // beyond the critical angle: mostly total internal reflection
        }
      }
  // Snell's law at a flat facet: sin(theta_t) = sin(theta_i) / eta.
  const vec3 v = view_at(0.6f);
  const vec3 l = refract_through(v, up, 1.5f);
  EXPECT_NEAR(std::sqrt(1.f - l.z * l.z), 0.8f / 1.5f, 1e-6f);
  EXPECT_LT(l.x, 0.f);
  EXPECT_EQ(refract_through(view_at(0.3f), up, 1.f / 1.5f), vec3(0.f));
}

// A chi-square test of sampled visible normals against ggx_vndf_pdf on 16 x
// 16 bins in (t, phi), t the polar parameter of polar_point with grid_alpha =
// alpha (so every bin holds a share of the lobe), each bin's expected count
// by 8 x 8 midpoint quadrature inside it. With ~255 degrees of freedom the
// statistic is dof +- sqrt(2 dof); the bound is dof + 5 sqrt(2 dof).
TEST(PbrSampling, SampledVisibleNormalsFollowThePdf) {
  constexpr int bins = 16, sub = 8;
  constexpr uint32_t samples = 200000;
  for (float alpha : {0.05f, 0.25f, 0.7f})
    for (float nv : {0.15f, 0.6f, 0.95f}) {
      const vec3 v = view_at(nv);
      std::vector<double> observed(bins * bins, 0.0), expected(bins * bins, 0.0);
      for (uint32_t i = 0; i < samples; ++i) {
        const vec3 h = sample_ggx_vndf(v, alpha, random2(17, i));
        const double theta = std::acos(std::clamp(double(h.z), -1.0, 1.0));
        const double t = std::atan(std::tan(theta) / alpha) * 2.0 / std::numbers::pi;
        double phi = std::atan2(double(h.y), double(h.x));
        if (phi < 0) phi += two_pi;
        const int bt = std::min(int(t * bins), bins - 1), bp = std::min(int(phi / two_pi * bins), bins - 1);
        observed[size_t(bt * bins + bp)] += 1.0;
      }
      const double dt = 1.0 / (bins * sub), d_phi = two_pi / (bins * sub);
      for (int p = 0; p < bins * sub; ++p) {
        const PolarPoint q = polar_point((p + 0.5) * dt, alpha);
        for (int a = 0; a < bins * sub; ++a) {
          const double pdf = ggx_vndf_pdf(v, spherical(q.theta, (a + 0.5) * d_phi), alpha);
          expected[size_t((p / sub) * bins + a / sub)] += pdf * std::sin(q.theta) * q.d_theta_dt * dt * d_phi * samples;
        }
      }
      // Bins expecting fewer than 5 samples are pooled into one.
      double chi2 = 0, pooled_observed = 0, pooled_expected = 0;
      int cells = 0;
      for (size_t k = 0; k < observed.size(); ++k) {
        if (expected[k] < 5.0) {
          pooled_observed += observed[k];
          pooled_expected += expected[k];
          continue;
        }
        chi2 += (observed[k] - expected[k]) * (observed[k] - expected[k]) / expected[k];
        ++cells;
      }
      if (pooled_expected >= 5.0) {
        chi2 += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
        ++cells;
      }
      const double dof = cells - 1;
      EXPECT_GT(cells, 100) << "alpha " << alpha << " n.v " << nv;
      EXPECT_LT(chi2, dof + 5.0 * std::sqrt(2.0 * dof)) << "alpha " << alpha << " n.v " << nv << " dof " << dof;
    }
}

TEST(PbrSampling, CosineHemisphereSamplesHaveTheirPdfsMoments) {
  // E[z] = 2/3 and E[z^2] = 1/2 under pdf cos / pi; x and y average to 0.
  constexpr uint32_t samples = 100000;
  MeanEstimate z, xy;
  for (uint32_t i = 0; i < samples; ++i) {
    const vec3 w = sample_cosine_hemisphere(random2(19, i));
    ASSERT_NEAR(glm::length(w), 1.f, 1e-5f);
    z.add(vec3(w.z, w.z * w.z, 0.f));
    xy.add(vec3(w.x, w.y, 0.f));
  }
  EXPECT_NEAR(z.mean().x, 2.0 / 3.0, 3.0 * z.standard_error().x);
  EXPECT_NEAR(z.mean().y, 0.5, 3.0 * z.standard_error().y);
  EXPECT_NEAR(xy.mean().x, 0.0, 3.0 * xy.standard_error().x);
  EXPECT_NEAR(xy.mean().y, 0.0, 3.0 * xy.standard_error().y);
  EXPECT_FLOAT_EQ(cosine_hemisphere_pdf(1.f), 1.f / pi);
  EXPECT_EQ(cosine_hemisphere_pdf(-0.1f), 0.f);
}

struct NamedSurface {
  const char* name;
  PbrSurface s;
  double grid_alpha;  // the narrowest lobe's alpha, for the quadrature's grid
};

std::vector<NamedSurface> test_surfaces() {
  std::vector<NamedSurface> out;
  PbrSurface d;  // a red plastic
  d.base = vec3(0.8f, 0.2f, 0.1f);
  d.metallic = 0.f;
  d.roughness = 0.5f;
  out.push_back({"dielectric", d, 0.25});
  PbrSurface m;  // gold
  m.base = vec3(1.f, 0.78f, 0.34f);
  m.metallic = 1.f;
  m.roughness = 0.4f;
  out.push_back({"metal", m, 0.16});
  PbrSurface r = d;
  r.base = vec3(0.3f, 0.6f, 0.9f);
  r.roughness = 1.f;
  out.push_back({"rough dielectric", r, 1.0});
  PbrSurface sm = m;
  sm.base = vec3(0.95f, 0.64f, 0.54f);
  sm.roughness = 0.1f;
  out.push_back({"smooth metal", sm, 0.01});
  PbrSurface sd = d;
  sd.roughness = 0.15f;
  out.push_back({"smooth dielectric", sd, 0.0225});
  PbrSurface mixed = d;  // half metal
  mixed.metallic = 0.5f;
  mixed.roughness = 0.3f;
  out.push_back({"half metal", mixed, 0.09});
  PbrSurface c = d;  // a clearcoat over a rough base, the coat normal tilted
  c.roughness = 0.7f;
  c.clearcoat = 1.f;
  c.clearcoat_roughness = 0.3f;
  c.clearcoat_normal = glm::normalize(vec3(0.1f, 0.05f, 1.f));
  out.push_back({"clearcoat", c, 0.09});
  PbrSurface sh = d;  // velvet
  sh.base = vec3(0.2f, 0.05f, 0.3f);
  sh.roughness = 0.8f;
  sh.sheen_color = vec3(0.9f, 0.6f, 1.f);
  sh.sheen_roughness = 0.4f;
  out.push_back({"sheen", sh, 0.64});
  PbrSurface t = d;  // thin glass with a rough reflection
  t.base = vec3(0.9f, 1.f, 0.95f);
  t.roughness = 0.35f;
  t.transmission = 1.f;
  out.push_back({"transmission", t, 0.1225});
  return out;
}

// The normalisation defect |integral of D(h) (n.h) d omega_h - 1| of
// pbr_brdf.cpp's float ggx_distribution on directional_albedo's grid: near
// the peak of a narrow lobe, n.h^2 (alpha^2 - 1) + 1 loses digits in float
// (about 2e-4 of the lobe at alpha 0.01), an error of the BRDF the reference
// integrates that the sampler's weights (D cancels in f / pdf) do not share.
double distribution_defect(float alpha, double grid_alpha, int polar_steps, int azimuth_steps) {
  const double integral = integrate_hemisphere([&](vec3 h) { return ggx_distribution(h.z, alpha) * h.z; }, grid_alpha,
                                               polar_steps, azimuth_steps);
  return std::abs(integral - 1.0);
}

// The mean weight of sample_pbr is the directional albedo (reflection) plus
// pbr_transmission_weight (the transmission lobe), per channel within 3 SE of
// the samples plus the quadrature's error: twice the difference of the
// quadratures at two resolutions, plus the albedo times the float D's
// normalisation defect (distribution_defect) of the GGX lobes.
TEST(PbrSampling, SampledWeightsAverageToTheDirectionalAlbedo) {
  constexpr uint32_t samples = 200000;
  for (const NamedSurface& c : test_surfaces())
    for (float nv : {0.25f, 0.8f}) {
      const vec3 v = view_at(nv);
      MeanEstimate estimate;
      for (uint32_t i = 0; i < samples; ++i) estimate.add(sample_pbr(c.s, up, v, random3(41, i)).weight);
      const vec3 coarse = directional_albedo(c.s, v, c.grid_alpha, 400, 128);
      const vec3 fine = directional_albedo(c.s, v, c.grid_alpha, 800, 256);
      const vec3 expected = fine + pbr_transmission_weight(c.s, nv);
      const dvec3 mean = estimate.mean(), se = estimate.standard_error();
      double defect = distribution_defect(ggx_alpha(c.s.roughness), c.grid_alpha, 800, 256);
      if (c.s.clearcoat > 0.f)
        defect = std::max(defect, distribution_defect(ggx_alpha(c.s.clearcoat_roughness), c.grid_alpha, 800, 256));
      for (int k = 0; k < 3; ++k) {
        const double quadrature_error = 2.0 * std::abs(double(fine[k]) - double(coarse[k])) + defect * fine[k];
        EXPECT_NEAR(mean[k], expected[k], 3.0 * se[k] + quadrature_error)
            << c.name << " n.v " << nv << " channel " << k << " se " << se[k] << " quadrature " << quadrature_error;
      }
    }
}

// pbr_pdf gives the pdf sample_pbr reports for its directions, and matches
// the lobe pdfs where the material has a single lobe.
TEST(PbrSampling, PdfOfASampledDirectionIsTheSamplesPdf) {
  for (const NamedSurface& c : test_surfaces())
    for (float nv : {0.25f, 0.8f}) {
      const vec3 v = view_at(nv);
      for (uint32_t i = 0; i < 2000; ++i) {
        const BrdfSample b = sample_pbr(c.s, up, v, random3(29, i));
        if (b.specular_transmission) {
          EXPECT_EQ(b.direction, -v);
          EXPECT_FLOAT_EQ(b.pdf, pbr_lobe_probabilities(c.s, up, v).transmission);
          continue;
        }
        if (b.pdf == 0.f) {
          EXPECT_LE(b.direction.z, 0.f);
          EXPECT_EQ(b.weight, vec3(0.f));
          continue;
        }
        EXPECT_NEAR(pbr_pdf(c.s, up, v, b.direction), b.pdf, 1e-6f * b.pdf) << c.name;
      }
    }
  // A metal has only the GGX lobe; a dielectric without specular reflection
  // (specular = 0: F0 = F90 = 0) only the diffuse.
  PbrSurface metal = test_surfaces()[1].s, matte = test_surfaces()[0].s;
  matte.specular = 0.f;
  const vec3 v = view_at(0.5f);
  for (uint32_t i = 0; i < 200; ++i) {
    const vec3 l = sample_cosine_hemisphere(random2(31, i));
    EXPECT_FLOAT_EQ(pbr_pdf(metal, up, v, l), ggx_reflection_pdf(v, l, ggx_alpha(metal.roughness)));
    EXPECT_FLOAT_EQ(pbr_pdf(matte, up, v, l), l.z / pi);
  }
  EXPECT_EQ(pbr_pdf(metal, up, v, vec3(0.f, 0.6f, -0.8f)), 0.f);
  EXPECT_EQ(pbr_pdf(metal, up, vec3(0.f, 0.6f, -0.8f), v), 0.f);
  EXPECT_EQ(sample_pbr(metal, up, vec3(0.f, 0.6f, -0.8f), vec3(0.5f)).pdf, 0.f);
}

// pbr_pdf over the hemisphere is 1 - P(transmission) - P(below the surface);
// the latter measured from sample_pbr's samples (3 SE).
TEST(PbrSampling, PdfIntegratesToTheShareOfReflectedSamples) {
  constexpr uint32_t samples = 100000;
  for (const NamedSurface& c : test_surfaces()) {
    if (c.grid_alpha < 0.05) continue;  // the uniform grid in l does not resolve the smooth lobes
    for (float nv : {0.25f, 0.8f}) {
      const vec3 v = view_at(nv);
      const double integral = integrate_hemisphere([&](vec3 l) { return pbr_pdf(c.s, up, v, l); }, 1.0, 1024, 512);
      uint32_t reflected = 0;
      for (uint32_t i = 0; i < samples; ++i) {
        const BrdfSample b = sample_pbr(c.s, up, v, random3(37, i));
        if (!b.specular_transmission && b.pdf > 0.f) ++reflected;
      }
      const double fraction = double(reflected) / samples;
      const double se = std::sqrt(fraction * (1.0 - fraction) / samples);
      EXPECT_NEAR(integral, fraction, 3.0 * se + 2e-3) << c.name << " n.v " << nv;
      EXPECT_LE(integral, 1.0 + 2e-3) << c.name;
    }
  }
}

TEST(PbrSampling, LobeProbabilitiesFollowTheMaterial) {
  const vec3 v = view_at(0.7f);
  const PbrLobeProbabilities metal = pbr_lobe_probabilities(test_surfaces()[1].s, up, v);
  EXPECT_FLOAT_EQ(metal.specular, 1.f);
  EXPECT_EQ(metal.diffuse + metal.coat + metal.transmission, 0.f);
  const PbrLobeProbabilities plastic = pbr_lobe_probabilities(test_surfaces()[0].s, up, v);
  EXPECT_GT(plastic.diffuse, 0.8f);  // base mean 0.37 against a specular albedo near 0.04
  EXPECT_GT(plastic.specular, 0.05f);
  EXPECT_FLOAT_EQ(plastic.diffuse + plastic.specular, 1.f);
  const PbrLobeProbabilities coat = pbr_lobe_probabilities(test_surfaces()[6].s, up, v);
  EXPECT_GT(coat.coat, 0.f);
  EXPECT_FLOAT_EQ(coat.diffuse + coat.specular + coat.coat, 1.f);
  const PbrLobeProbabilities glass = pbr_lobe_probabilities(test_surfaces()[8].s, up, v);
  EXPECT_GT(glass.transmission, 0.8f);
  EXPECT_EQ(glass.diffuse, 0.f);  // transmission 1: no diffuse left
  PbrSurface black;
  black.base = vec3(0.f);
  black.metallic = 0.f;
  black.specular = 0.f;
  const PbrLobeProbabilities none = pbr_lobe_probabilities(black, up, v);
  EXPECT_EQ(none.diffuse + none.specular + none.coat + none.transmission, 0.f);
  const BrdfSample b = sample_pbr(black, up, v, vec3(0.5f));
  EXPECT_EQ(b.pdf, 0.f);
  EXPECT_EQ(b.weight, vec3(0.f));
}

TEST(PbrSampling, MisWeightsSumToOne) {
  const float inf = std::numeric_limits<float>::infinity();
  const std::array<float, 9> pdfs = {0.f, 1e-30f, 1e-3f, 0.25f, 1.f, 3.f, 1e4f, 1e30f, 3e38f};
  for (float a : pdfs)
    for (float b : pdfs) {
      if (a == 0.f && b == 0.f) continue;
      EXPECT_NEAR(power_heuristic(a, b) + power_heuristic(b, a), 1.f, 4.f * machine_epsilon) << a << " " << b;
      EXPECT_NEAR(balance_heuristic(a, b) + balance_heuristic(b, a), 1.f, 4.f * machine_epsilon) << a << " " << b;
    }
  EXPECT_FLOAT_EQ(power_heuristic(1.f, 2.f), 0.2f);
  EXPECT_FLOAT_EQ(power_heuristic(3.f, 1.f), 0.9f);
  EXPECT_FLOAT_EQ(balance_heuristic(1.f, 3.f), 0.25f);
  EXPECT_EQ(power_heuristic(0.f, 0.f), 0.f);
  EXPECT_EQ(power_heuristic(inf, 2.f), 1.f);
  EXPECT_EQ(power_heuristic(2.f, inf), 0.f);
  EXPECT_EQ(balance_heuristic(inf, 2.f), 1.f);
  EXPECT_EQ(balance_heuristic(2.f, inf), 0.f);
}

}  // namespace
}  // namespace rayform
