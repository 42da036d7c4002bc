#include "rayform/render/environment_filter.h"

#include "rayform/render/pbr_brdf.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace rayform {

namespace {

// The basis of the header, at a unit direction d.
std::array<float, 9> sh_basis(dvec3 d) {
  return {0.282095f,
          float(0.488603 * d.y),
          float(0.488603 * d.z),
          float(0.488603 * d.x),
          float(1.092548 * d.x * d.y),
          float(1.092548 * d.y * d.z),
          float(0.315392 * (3.0 * d.z * d.z - 1.0)),
          float(1.092548 * d.x * d.z),
          float(0.546274 * (d.x * d.x - d.y * d.y))};
}

// Solid angle (sr) of the band of rows [j0, j1) of a map of `height` rows,
// per unit of u (multiply by 2 pi times the width in u).
double band_cos_difference(int j0, int j1, int height) {
  return std::cos(std::numbers::pi * j0 / height) - std::cos(std::numbers::pi * j1 / height);
}

// The map averaged down to at most width x height texels (solid-angle
// weighted), as structure-of-arrays: the world direction of each texel's
// centre (rotation applied), its solid angle (sr) and its radiance times
// intensity.
struct Source {
  std::vector<float> x, y, z, solid_angle;
  std::vector<vec3> radiance;
};

Source downsample(const EnvironmentMap& env, int max_width, int max_height) {
  const int w = std::min(env.width, max_width), h = std::min(env.height, max_height);
  Source s;
  const size_t n = size_t(w) * size_t(h);
  s.x.resize(n), s.y.resize(n), s.z.resize(n), s.solid_angle.resize(n), s.radiance.resize(n);
  for (int jj = 0; jj < h; ++jj) {
    const int j0 = int(int64_t(jj) * env.height / h), j1 = int(int64_t(jj + 1) * env.height / h);
    for (int ii = 0; ii < w; ++ii) {
      const int i0 = int(int64_t(ii) * env.width / w), i1 = int(int64_t(ii + 1) * env.width / w);
      dvec3 sum(0.0);
      double total = 0.0;
      for (int j = j0; j < j1; ++j) {
        const double row_weight = band_cos_difference(j, j + 1, env.height);
        for (int i = i0; i < i1; ++i) {
          const float* p = env.rgb.data() + (size_t(j) * size_t(env.width) + size_t(i)) * 3;
          sum += row_weight * dvec3(p[0], p[1], p[2]);
        }
        total += row_weight * (i1 - i0);
      }
      const size_t k = size_t(jj) * size_t(w) + size_t(ii);
      const vec2 uv(float(0.5 * (i0 + i1) / env.width), float(0.5 * (j0 + j1) / env.height));
      const vec3 d = uv_to_direction(uv, env.rotation);
      s.x[k] = d.x, s.y[k] = d.y, s.z[k] = d.z;
      s.solid_angle[k] =
          float(2.0 * std::numbers::pi * (i1 - i0) / env.width * band_cos_difference(j0, j1, env.height));
      s.radiance[k] = total > 0.0 ? vec3(sum / total) * env.intensity : vec3(0.f);
    }
  }
  return s;
}

// One level: width x height texels (rotation 0, intensity 1), texel R the
// mean of the source weighted by D(n.h) (n.l) Omega with n = v = R. With
// c = R.l, (n.h)^2 = (1 + c) / 2, so D needs no square root; its constant
// factor alpha^2 / pi cancels in the mean.
EnvironmentMap filter_level(const Source& s, int width, int height, float alpha) {
  std::vector<float> rgb(size_t(width) * size_t(height) * 3);
  const float a2_minus_1 = alpha * alpha - 1.f;
  const size_t n = s.x.size();
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j < rows.end(); ++j)
      for (int i = 0; i < width; ++i) {
        const vec3 r = uv_to_direction(vec2((i + 0.5f) / float(width), (j + 0.5f) / float(height)));
        float sum_w = 0.f, sum_r = 0.f, sum_g = 0.f, sum_b = 0.f;
        for (size_t k = 0; k < n; ++k) {
          const float c = r.x * s.x[k] + r.y * s.y[k] + r.z * s.z[k];
          const float t = (0.5f + 0.5f * c) * a2_minus_1 + 1.f;
          const float w = c > 0.f ? c * s.solid_angle[k] / (t * t) : 0.f;
          sum_w += w;
          sum_r += w * s.radiance[k].r, sum_g += w * s.radiance[k].g, sum_b += w * s.radiance[k].b;
        }
        // sum_w > 0: the texels around R (c > 0) always have positive solid angle.
        float* out = rgb.data() + (size_t(j) * size_t(width) + size_t(i)) * 3;
        out[0] = sum_r / sum_w, out[1] = sum_g / sum_w, out[2] = sum_b / sum_w;
      }
  });
  return make_environment_map(width, height, std::move(rgb));
}

}  // namespace

EnvironmentIrradiance environment_irradiance(const EnvironmentMap& env) {
  EnvironmentIrradiance e;
  if (env.width <= 0 || env.height <= 0) return e;
  std::array<dvec3, 9> sum{};
  // Texel centres as uv_to_direction places them (rotation applied), from
  // per-column azimuths and per-row polar angles.
  std::vector<glm::dvec2> column(static_cast<size_t>(env.width));  // (cos phi, sin phi)
  for (int i = 0; i < env.width; ++i) {
    const double phi = 2.0 * std::numbers::pi * ((i + 0.5) / env.width - 0.5) - double(env.rotation);
    column[size_t(i)] = glm::dvec2(std::cos(phi), std::sin(phi));
  }
  for (int j = 0; j < env.height; ++j) {
    const double solid_angle = 2.0 * std::numbers::pi / env.width * band_cos_difference(j, j + 1, env.height);
    const double theta = std::numbers::pi * (j + 0.5) / env.height;
    const double sin_t = std::sin(theta), cos_t = std::cos(theta);
    for (int i = 0; i < env.width; ++i) {
      const dvec3 d(sin_t * column[size_t(i)].x, cos_t, sin_t * column[size_t(i)].y);
      const float* p = env.rgb.data() + (size_t(j) * size_t(env.width) + size_t(i)) * 3;
      const dvec3 l = solid_angle * dvec3(p[0], p[1], p[2]);
      const std::array<float, 9> y = sh_basis(d);
      for (size_t k = 0; k < 9; ++k) sum[k] += double(y[k]) * l;
    }
  }
  for (size_t k = 0; k < 9; ++k) e.sh[k] = vec3(sum[k]) * env.intensity;
  return e;
}

vec3 irradiance(const EnvironmentIrradiance& e, vec3 n) {
  // The cosine lobe's SH coefficients A_l (Ramamoorthi and Hanrahan 2001).
  constexpr float a0 = pi, a1 = 2.f * pi / 3.f, a2 = pi / 4.f;
  const std::array<float, 9> y = sh_basis(dvec3(n));
  vec3 result = a0 * y[0] * e.sh[0];
  for (size_t k = 1; k < 4; ++k) result += a1 * y[k] * e.sh[k];
  for (size_t k = 4; k < 9; ++k) result += a2 * y[k] * e.sh[k];
  return result;
}

PrefilteredEnvironment prefilter_environment(const EnvironmentMap& env, int levels) {
  PrefilteredEnvironment p;
  if (env.width <= 0 || env.height <= 0 || levels < 2) {
    p.level_count = std::max(levels, 1);
    return p;
  }
  p.level_count = levels;
  // Level 1 (the sharpest lobe) from the finer source, the rest from the coarser.
  const Source fine = downsample(env, 128, 64), coarse = downsample(env, 64, 32);
  p.levels.reserve(size_t(levels - 1));
  for (int k = 1; k < levels; ++k) {
    const float alpha = ggx_alpha(float(k) / float(levels - 1));
    const bool first = k == 1;
    p.levels.push_back(filter_level(first ? fine : coarse, std::min(env.width, first ? 64 : 32),
                                    std::min(env.height, first ? 32 : 16), alpha));
  }
  return p;
}

vec3 prefiltered_radiance(const PrefilteredEnvironment& p, const EnvironmentMap& env, vec3 direction, float roughness) {
  const int stored = int(p.levels.size());
  if (p.level_count < 2 || stored != p.level_count - 1 || !(roughness > 0.f))
    return environment_radiance_bilinear(env, direction);
  const float x = std::min(roughness, 1.f) * float(p.level_count - 1);
  const int k0 = std::min(int(x), p.level_count - 1), k1 = std::min(k0 + 1, p.level_count - 1);
  const float t = x - float(k0);
  const auto level = [&](int k) {
    return k == 0 ? environment_radiance_bilinear(env, direction)
                  : environment_radiance_bilinear(p.levels[size_t(k - 1)], direction);
  };
  const vec3 a = level(k0);
  return t > 0.f && k1 != k0 ? glm::mix(a, level(k1), t) : a;
}

}  // namespace rayform
