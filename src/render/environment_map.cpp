#include "rayform/render/environment_map.h"

#include "rayform/base/error.h"
#include "rayform/image/image.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

namespace rayform {

namespace {

constexpr float inv_two_pi = 0.5f / pi;
// The largest float below 1: keeps a remainder in [0, 1).
constexpr float one_minus_ulp = 1.f - machine_epsilon;

bool is_zero(vec3 d) { return d.x == 0.f && d.y == 0.f && d.z == 0.f; }

// sin(theta) of a non-zero direction (theta the polar angle from +Y). The
// sampler and the pdf compute it the same way, so that a sample's pdf equals
// environment_pdf of its direction bit for bit.
float sin_theta(vec3 d) { return std::sqrt(d.x * d.x + d.z * d.z) / glm::length(d); }

// The texel holding (u, v) (u in [0, 1), v in [0, 1]).
int texel_index(const EnvironmentMap& map, vec2 uv) {
  const int i = std::min(int(uv.x * float(map.width)), map.width - 1);
  const int j = std::min(int(uv.y * float(map.height)), map.height - 1);
  return j * map.width + i;
}

vec3 texel(const EnvironmentMap& map, int index) {
  const float* p = map.rgb.data() + size_t(index) * 3;
  return vec3(p[0], p[1], p[2]);
}

// Fills cdf[0..n] from weights w[0..n-1] (cdf[0] = 0, cdf[n] = 1 exactly);
// returns the weights' sum. All-zero weights give the uniform CDF.
double build_cdf(const float* w, int n, float* cdf) {
  double sum = 0.0;
  for (int k = 0; k < n; ++k) sum += double(w[k]);
  double partial = 0.0;
  cdf[0] = 0.f;
  for (int k = 1; k < n; ++k) {
    partial += double(w[k - 1]);
    cdf[k] = sum > 0.0 ? float(partial / sum) : float(k) / float(n);
  }
  cdf[n] = 1.f;
  return sum;
}

// The index k with cdf[k] <= x < cdf[k + 1] (x in [0, 1)), and the remainder
// (x - cdf[k]) / (cdf[k + 1] - cdf[k]) in [0, 1). A bin of zero width is never
// chosen for x in [0, 1).
std::pair<int, float> invert_cdf(const float* cdf, int n, float x) {
  const int k = std::clamp(int(std::upper_bound(cdf, cdf + n + 1, x) - cdf) - 1, 0, n - 1);
  const float width = cdf[k + 1] - cdf[k];
  const float rest = width > 0.f ? (x - cdf[k]) / width : 0.f;
  return {k, std::clamp(rest, 0.f, one_minus_ulp)};
}

float smoothstep(float edge0, float edge1, float x) {
  const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.f, 1.f);
  return t * t * (3.f - 2.f * t);
}

}  // namespace

EnvironmentMap make_environment_map(int width, int height, std::vector<float> rgb, float intensity,
                                    float rotation_rad) {
  if (width <= 0 || height <= 0)
    throw Error("environment map: size " + std::to_string(width) + "x" + std::to_string(height) + " is not positive");
  const size_t texels = size_t(width) * size_t(height);
  if (rgb.size() != texels * 3)
    throw Error("environment map: " + std::to_string(rgb.size()) + " values for " + std::to_string(width) + "x" +
                std::to_string(height) + " RGB texels (" + std::to_string(texels * 3) + " expected)");
  if (!std::isfinite(intensity) || intensity < 0.f)
    throw Error("environment map: intensity " + std::to_string(intensity) + " is not a finite value >= 0");
  if (!std::isfinite(rotation_rad)) throw Error("environment map: the rotation is not finite");
  for (size_t k = 0; k < rgb.size(); ++k)
    if (!std::isfinite(rgb[k]))
      throw Error("environment map: texel (" + std::to_string(k / 3 % size_t(width)) + ", " +
                  std::to_string(k / 3 / size_t(width)) + ") is not finite");

  EnvironmentMap map;
  map.width = width;
  map.height = height;
  map.rgb = std::move(rgb);
  map.intensity = intensity;
  map.rotation = rotation_rad;

  map.texel_weight.resize(texels);
  map.column_cdf.resize(size_t(height) * size_t(width + 1));
  map.row_cdf.resize(size_t(height) + 1);
  std::vector<float> row_weight(static_cast<size_t>(height));
  for (int j = 0; j < height; ++j) {
    const float sin_row = float(std::sin(std::numbers::pi * (j + 0.5) / height));
    float* w = map.texel_weight.data() + size_t(j) * width;
    for (int i = 0; i < width; ++i) w[i] = std::max(0.f, environment_luminance(texel(map, j * width + i))) * sin_row;
    row_weight[size_t(j)] = float(build_cdf(w, width, map.column_cdf.data() + size_t(j) * (width + 1)));
  }
  // The total from the texel weights themselves (not the rounded row sums),
  // in double: p_uv = w_ij W H / total integrates to 1 over [0, 1]^2.
  double total = 0.0;
  for (float w : map.texel_weight) total += double(w);
  build_cdf(row_weight.data(), height, map.row_cdf.data());
  map.samplable = total > 0.0;
  map.pdf_uv_scale = map.samplable ? float(double(texels) / total) : 0.f;
  return map;
}

EnvironmentMap environment_from_image(const Image& image, float intensity, float rotation_rad) {
  if (image.channels != 3 && image.channels != 4)
    throw Error("environment map: the image has " + std::to_string(image.channels) +
                " channels (3 or 4 expected: RGB or RGBA)");
  const size_t texels = size_t(image.width) * size_t(image.height);
  if (image.width <= 0 || image.height <= 0 || image.pixels.size() != texels * size_t(image.channels))
    throw Error("environment map: the image is empty or its pixel count does not match its size");
  std::vector<float> rgb(texels * 3);
  for (size_t k = 0; k < texels; ++k)
    for (size_t c = 0; c < 3; ++c) rgb[k * 3 + c] = image.pixels[k * size_t(image.channels) + c];
  return make_environment_map(image.width, image.height, std::move(rgb), intensity, rotation_rad);
}

vec2 direction_to_uv(vec3 d, float rotation_rad) {
  if (!is_finite(d) || is_zero(d)) return vec2(std::numeric_limits<float>::quiet_NaN());
  float u = 0.5f + (std::atan2(d.z, d.x) + rotation_rad) * inv_two_pi;
  u -= std::floor(u);
  if (u >= 1.f) u = 0.f;  // a tiny negative u rounds to 1 after the wrap
  // atan2 of (sin theta, cos theta) up to a common factor: acos(dy / |d|),
  // without acos's loss of precision near the poles.
  const float v = std::atan2(std::sqrt(d.x * d.x + d.z * d.z), d.y) * (1.f / pi);
  return vec2(u, v);
}

vec3 uv_to_direction(vec2 uv, float rotation_rad) {
  const float phi = 2.f * pi * (uv.x - 0.5f) - rotation_rad, theta = pi * uv.y;
  const float s = std::sin(theta);
  return vec3(s * std::cos(phi), std::cos(theta), s * std::sin(phi));
}

vec3 environment_radiance(const EnvironmentMap& map, vec3 direction) {
  const vec2 uv = direction_to_uv(direction, map.rotation);
  if (!std::isfinite(uv.x) || map.rgb.empty()) return vec3(0.f);
  return map.intensity * texel(map, texel_index(map, uv));
}

vec3 environment_radiance_bilinear(const EnvironmentMap& map, vec3 direction) {
  const vec2 uv = direction_to_uv(direction, map.rotation);
  if (!std::isfinite(uv.x) || map.rgb.empty()) return vec3(0.f);
  // Continuous texel coordinates with texel centres on whole numbers.
  const float x = uv.x * float(map.width) - 0.5f, y = uv.y * float(map.height) - 0.5f;
  const float x0 = std::floor(x), y0 = std::floor(y);
  const float fx = x - x0, fy = y - y0;
  const int i0 = (int(x0) % map.width + map.width) % map.width, i1 = (i0 + 1) % map.width;
  const int j0 = std::clamp(int(y0), 0, map.height - 1), j1 = std::clamp(int(y0) + 1, 0, map.height - 1);
  const vec3 top = glm::mix(texel(map, j0 * map.width + i0), texel(map, j0 * map.width + i1), fx);
  const vec3 bottom = glm::mix(texel(map, j1 * map.width + i0), texel(map, j1 * map.width + i1), fx);
  return map.intensity * glm::mix(top, bottom, fy);
}

EnvironmentSample sample_environment(const EnvironmentMap& map, vec2 u) {
  EnvironmentSample s;
  if (!map.samplable) return s;
  u = glm::clamp(u, vec2(0.f), vec2(one_minus_ulp));
  const auto [j, dv] = invert_cdf(map.row_cdf.data(), map.height, u.y);
  const auto [i, du] = invert_cdf(map.column_cdf.data() + size_t(j) * (map.width + 1), map.width, u.x);
  const vec2 uv((float(i) + du) / float(map.width), (float(j) + dv) / float(map.height));
  s.direction = uv_to_direction(uv, map.rotation);
  const int index = j * map.width + i;
  s.radiance = map.intensity * texel(map, index);
  const float sin_t = sin_theta(s.direction);
  s.pdf = sin_t > 0.f ? map.texel_weight[size_t(index)] * map.pdf_uv_scale / (2.f * pi * pi * sin_t) : 0.f;
  return s;
}

float environment_pdf(const EnvironmentMap& map, vec3 direction) {
  if (!map.samplable) return 0.f;
  const vec2 uv = direction_to_uv(direction, map.rotation);
  if (!std::isfinite(uv.x)) return 0.f;
  const float sin_t = sin_theta(direction);
  if (!(sin_t > 0.f)) return 0.f;
  return map.texel_weight[size_t(texel_index(map, uv))] * map.pdf_uv_scale / (2.f * pi * pi * sin_t);
}

namespace {

// A soft-edged rectangle in (azimuth, elevation) on the sphere: the centre
// direction at yaw `yaw_deg` from +Z towards +X and elevation `elevation_deg`
// above the horizon, half extents in degrees of arc, edges fading over
// +-soft_deg, and its radiance added to the backdrop inside.
struct Softbox {
  float yaw_deg, elevation_deg, half_width_deg, half_height_deg, soft_deg, radiance;
};

// Key (front right, above), fill (front left, lower, dimmer), rim (behind, above).
constexpr Softbox studio_softboxes[] = {
    {45.f, 35.f, 20.f, 14.f, 6.f, 6.f},
    {-60.f, 10.f, 22.f, 16.f, 8.f, 2.f},
    {160.f, 40.f, 16.f, 10.f, 6.f, 4.f},
};

float softbox_factor(const Softbox& b, float azimuth, float elevation) {
  // Azimuth as atan2(z, x) (the mapping's), of the centre direction
  // (sin yaw cos e, sin e, cos yaw cos e).
  const float yaw = radians(b.yaw_deg);
  const float centre_azimuth = std::atan2(std::cos(yaw), std::sin(yaw));
  float d_azimuth = azimuth - centre_azimuth;
  d_azimuth -= 2.f * pi * std::round(d_azimuth * inv_two_pi);  // into [-pi, pi]
  // Arc lengths (radians) across and up the box from its centre.
  const float across = std::abs(d_azimuth) * std::cos(elevation);
  const float up = std::abs(elevation - radians(b.elevation_deg));
  const float soft = radians(b.soft_deg);
  const float wx = radians(b.half_width_deg), wy = radians(b.half_height_deg);
  return (1.f - smoothstep(wx - soft, wx + soft, across)) * (1.f - smoothstep(wy - soft, wy + soft, up));
}

// The backdrop's radiance at elevation e (radians above the horizon).
float studio_backdrop(float elevation) {
  constexpr float floor_radiance = 0.10f, wall_radiance = 0.42f, zenith_radiance = 0.55f;
  constexpr float band_low = -0.25f, band_high = 0.10f;  // the horizon band, radians of elevation
  const float wall = wall_radiance + (zenith_radiance - wall_radiance) * std::max(std::sin(elevation), 0.f);
  return glm::mix(floor_radiance, wall, smoothstep(band_low, band_high, elevation));
}

}  // namespace

EnvironmentMap studio_environment(int width, int height) {
  if (width <= 0 || height <= 0)
    throw Error("studio environment: size " + std::to_string(width) + "x" + std::to_string(height) +
                " is not positive");
  std::vector<float> radiance(size_t(width) * size_t(height));
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const vec3 d = uv_to_direction(vec2((i + 0.5f) / float(width), (j + 0.5f) / float(height)));
      const float elevation = std::asin(std::clamp(d.y, -1.f, 1.f)), azimuth = std::atan2(d.z, d.x);
      float l = studio_backdrop(elevation);
      for (const Softbox& b : studio_softboxes) l += b.radiance * softbox_factor(b, azimuth, elevation);
      radiance[size_t(j) * width + i] = l;
    }
  // E_up = sum over texels of L (2 pi / W) integral over the row of
  // max(cos theta, 0) sin theta d theta = (c0^2 - c1^2) / 2, c = max(cos, 0)
  // at the row's edges.
  double e_up = 0.0;
  for (int j = 0; j < height; ++j) {
    const double c0 = std::max(std::cos(std::numbers::pi * j / height), 0.0);
    const double c1 = std::max(std::cos(std::numbers::pi * (j + 1) / height), 0.0);
    double row = 0.0;
    for (int i = 0; i < width; ++i) row += double(radiance[size_t(j) * width + i]);
    e_up += row * (2.0 * std::numbers::pi / width) * 0.5 * (c0 * c0 - c1 * c1);
  }
  const float scale = float(std::numbers::pi * studio_up_radiance / e_up);
  std::vector<float> rgb(radiance.size() * 3);
  for (size_t k = 0; k < radiance.size(); ++k) rgb[k * 3] = rgb[k * 3 + 1] = rgb[k * 3 + 2] = radiance[k] * scale;
  return make_environment_map(width, height, std::move(rgb));
}

}  // namespace rayform
