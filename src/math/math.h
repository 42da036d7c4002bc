// Small vector/matrix vocabulary over glm, and the floating-point helpers the
// geometry kernels use for their error bounds.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

namespace rayform {

using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using mat3 = glm::mat3;
using mat4 = glm::mat4;  // column-major, as glm: m[column][row]
using dvec3 = glm::dvec3;

// pi, the one spelling: `pi` in float, std::numbers::pi where double is meant.
inline constexpr float pi = std::numbers::pi_v<float>;
inline constexpr float infinity = std::numeric_limits<float>::infinity();
// Unit roundoff of float: half the distance from 1 to the next float.
inline constexpr float machine_epsilon = std::numeric_limits<float>::epsilon() * 0.5f;

// The largest of a colour's or vector's three components.
inline float max_component(vec3 c) { return std::max(std::max(c.x, c.y), c.z); }

inline float radians(float degrees) { return degrees * (pi / 180.0f); }

// Bound on the relative error of n chained float operations (Higham's gamma_n,
// as used by pbrt): |fl(x) - x| <= gamma(n) |x|.
constexpr float gamma_bound(int n) { return (n * machine_epsilon) / (1 - n * machine_epsilon); }

// The neighbouring representable floats (ties towards the ray offsets of pbrt-v4).
inline float next_float_up(float v) {
  if (std::isinf(v) && v > 0.f) return v;
  if (v == -0.f) v = 0.f;
  uint32_t ui = std::bit_cast<uint32_t>(v);
  ui = v >= 0 ? ui + 1 : ui - 1;
  return std::bit_cast<float>(ui);
}
inline float next_float_down(float v) {
  if (std::isinf(v) && v < 0.f) return v;
  if (v == 0.f) v = -0.f;
  uint32_t ui = std::bit_cast<uint32_t>(v);
  ui = v > 0 ? ui - 1 : ui + 1;
  return std::bit_cast<float>(ui);
}

inline int max_dimension(vec3 v) { return (v.x > v.y) ? (v.x > v.z ? 0 : 2) : (v.y > v.z ? 1 : 2); }

inline bool is_finite(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

inline bool is_identity(const mat4& m) { return m == mat4(1.f); }

// Point and vector transforms by an affine 4x4 matrix.
inline vec3 transform_point(const mat4& m, vec3 p) { return vec3(m * vec4(p, 1.0f)); }
inline vec3 transform_vector(const mat4& m, vec3 v) { return vec3(m * vec4(v, 0.0f)); }

}  // namespace rayform
