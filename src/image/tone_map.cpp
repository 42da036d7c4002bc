#include "rayform/image/tone_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rayform {
namespace {

// Each channel in [0, sqrt(largest float)], negative and NaN values as 0:
// both tone maps are defined for non-negative input, and the bound keeps the
// squares in their formulas finite (both are flat long before it: infinity
// shows as white).
vec3 in_domain(vec3 c) {
  const float largest = std::sqrt(std::numeric_limits<float>::max());
  for (int k = 0; k < 3; ++k) c[k] = c[k] > 0.f ? std::min(c[k], largest) : 0.f;
  return c;
}

}  // namespace

vec3 tone_map_khr_neutral(vec3 linear) {
  constexpr float f90 = 0.04f;                     // Fresnel reflectance at normal incidence, IOR 1.5
  constexpr float start_compression = 0.8f - f90;  // Ks
  constexpr float desaturation = 0.15f;            // Kd
  vec3 c = in_domain(linear);
  const float x = std::min({c.r, c.g, c.b});
  const float offset = x < 2.f * f90 ? x - x * x / (4.f * f90) : f90;
  c -= offset;
  const float peak = std::max({c.r, c.g, c.b});
  if (peak < start_compression) return c;
  const float d = 1.f - start_compression;
  const float new_peak = 1.f - d * d / (peak + d - start_compression);
  c *= new_peak / peak;
  const float g = 1.f - 1.f / (desaturation * (peak - new_peak) + 1.f);
  return glm::mix(c, vec3(new_peak), g);
}

vec3 tone_map_aces(vec3 linear) {
  constexpr float exposure_boost = 1.f / 0.6f;
  const vec3 v = in_domain(linear * exposure_boost);
  // Rows of the matrices (out_i = sum_j m[i][j] v_j); each row sums to 1, so grey stays grey.
  // sRGB -> XYZ -> D65 to D60 -> AP1 -> RRT saturation.
  constexpr float input[3][3] = {
      {0.59719f, 0.35458f, 0.04823f}, {0.07600f, 0.90834f, 0.01566f}, {0.02840f, 0.13383f, 0.83777f}};
  // ODT saturation -> XYZ -> D60 to D65 -> sRGB.
  constexpr float output[3][3] = {
      {1.60475f, -0.53108f, -0.07367f}, {-0.10208f, 1.10813f, -0.00605f}, {-0.00327f, -0.07276f, 1.07602f}};
  vec3 fitted;
  for (int i = 0; i < 3; ++i) {
    const float a = input[i][0] * v.r + input[i][1] * v.g + input[i][2] * v.b;
    // The rational fit of the RRT followed by the ODT.
    fitted[i] = (a * (a + 0.0245786f) - 0.000090537f) / (a * (0.983729f * a + 0.4329510f) + 0.238081f);
  }
  vec3 out;
  for (int i = 0; i < 3; ++i)
    out[i] = std::clamp(output[i][0] * fitted.r + output[i][1] * fitted.g + output[i][2] * fitted.b, 0.f, 1.f);
  return out;
}

vec3 apply_tone_map(ToneMap map, vec3 linear) {
  switch (map) {
    case ToneMap::none: return linear;
    case ToneMap::khr_neutral: return tone_map_khr_neutral(linear);
    case ToneMap::aces: return tone_map_aces(linear);
  }
  return linear;
}

const char* tone_map_name(ToneMap map) {
  switch (map) {
    case ToneMap::none: return "none";
    case ToneMap::khr_neutral: return "khr-neutral";
    case ToneMap::aces: return "aces";
  }
  return "none";
}

std::optional<ToneMap> tone_map_from_name(const std::string& name) {
  for (ToneMap m : {ToneMap::none, ToneMap::khr_neutral, ToneMap::aces})
    if (name == tone_map_name(m)) return m;
  return std::nullopt;
}

}  // namespace rayform
