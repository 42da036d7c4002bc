// Colour transfer functions (IEC 61966-2-1 sRGB).
#pragma once

#include <cmath>

namespace rayform {

inline float srgb_to_linear(float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); }
// Exactly 1 at 1: the formula's float rounding gives 0.99999994 there, whose
// 8-bit value is 254, not 255.
inline float linear_to_srgb(float v) {
  if (v == 1.f) return 1.f;
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.f / 2.4f) - 0.055f;
}

}  // namespace rayform
